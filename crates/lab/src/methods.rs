//! One place that turns a method name into an evaluator for a patch, so every lab command offers the same
//! methods with the same parameters: `ground-truth` (finite aperture) and `ground-truth-periodic` (the patch's
//! periodic extension), `reference`, `lookup` (iridis-diffraction), `nmm`, `pq` ([`crate::variants`]),
//! `stam-periodic` / `stam-periodic-triangular`, `stam-gaussian` ([`crate::stam`]).

use std::sync::{Arc, Mutex};

use iridis_color::{Observer, Spectrum, Xyz};
use iridis_diffraction::table::{Lookup, LookupTable, Precision, Provenance, TableParams};
use iridis_diffraction::taylor::{terms_for_bound, Band};
use iridis_diffraction::{
    Accelerator, Aperture, Evaluator, GroundTruth, Patch, Reference, Shading, SpectralSetup, TaylorTerms,
};

use crate::analysis::{dominant_period, Axis};
use crate::stam::{Bump, StamGaussian, StamPeriodic};
use crate::variants::{Nmm, Pq};
use crate::{LabError, Progress};

/// An evaluation method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// The direct windowed sum over the patch alone (the window cut at its edge).
    GroundTruth,
    /// The direct windowed sum over the patch's periodic extension: the model the DFT-based methods approximate.
    GroundTruthPeriodic,
    Reference,
    Lookup,
    Nmm,
    Pq,
    StamPeriodic(Bump),
    StamGaussian,
}

impl Method {
    /// Every method, with the name the command line uses.
    pub const ALL: [Method; 9] = [
        Method::GroundTruth,
        Method::GroundTruthPeriodic,
        Method::Reference,
        Method::Lookup,
        Method::Nmm,
        Method::Pq,
        Method::StamPeriodic(Bump::Rectangular),
        Method::StamPeriodic(Bump::Triangular),
        Method::StamGaussian,
    ];

    /// The ground truth with the given aperture.
    pub fn ground_truth(aperture: Aperture) -> Method {
        match aperture {
            Aperture::Finite => Method::GroundTruth,
            Aperture::Periodic => Method::GroundTruthPeriodic,
        }
    }

    /// Whether this is one of the two ground truths.
    pub fn is_ground_truth(self) -> bool {
        matches!(self, Method::GroundTruth | Method::GroundTruthPeriodic)
    }

    /// The ground truth of the model this method approximates, the one its error is measured against by default:
    ///
    /// * reference, lookup, NMM, PQ: the windowed Fourier-series coefficients of the patch (DFT / samples,
    ///   eq. 8) are the transform of its periodic extension, so their exact answer is the periodic ground truth;
    /// * Stam's models: infinite surfaces (a lattice, a stationary random field) with no edge, whose parameters
    ///   are taken from the patch through its DFT — the periodogram's dominant periods, the circular
    ///   autocorrelation — that is, from the statistics of the periodic extension. The finite aperture would
    ///   add an edge these models cannot have, so they too are compared with the periodic ground truth;
    /// * the finite-aperture ground truth, compared this way, gives the periodic-extension error itself.
    pub fn model_truth(self) -> Method {
        Method::GroundTruthPeriodic
    }

    /// Whether the method answers spectral reflectance (needed by the test bench).
    pub fn is_spectral(self) -> bool {
        self != Method::Lookup
    }

    /// Whether the method is built from the Taylor terms of the height field (paper eq. 5–7), so that
    /// `MethodConfig::terms` changes it: not the ground truths (the exact phase) nor Stam's fitted models.
    pub fn uses_taylor_terms(self) -> bool {
        matches!(self, Method::Reference | Method::Lookup | Method::Nmm | Method::Pq)
    }

    /// Whether `MethodConfig::stam_epsilon` (ε of the wavelength selection) changes the method: Stam's periodic
    /// lattices only.
    pub fn uses_stam_epsilon(self) -> bool {
        matches!(self, Method::StamPeriodic(_))
    }
}

iridis_color::names! {
    Method {
        GroundTruth => "ground-truth" | "truth" | "ground_truth" | "groundtruth" | "ground-truth-finite",
        GroundTruthPeriodic => "ground-truth-periodic" | "ground-truth-periodic-extension" | "ground_truth_periodic",
        Reference => "reference" | "flss",
        Lookup => "lookup",
        Nmm => "nmm",
        Pq => "pq",
        StamPeriodic(Bump::Rectangular) => "stam-periodic" | "stam-periodic-rectangular" | "stam-periodic-rect",
        StamPeriodic(Bump::Triangular) => "stam-periodic-triangular" | "stam-periodic-triangle" | "stam-periodic-tri",
        StamGaussian => "stam-gaussian",
    }
    else |s| -> LabError { LabError::unknown_name("method", s, Method::ALL.map(Method::name)) }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Parameters shared by all methods (each uses the ones it has).
#[derive(Debug, Clone)]
pub struct MethodConfig {
    /// Coherence length `4σ_s` (nm).
    pub coherence_nm: f64,
    /// Taylor terms `N`; from the remainder bound with `term_epsilon` when `None`.
    pub terms: Option<usize>,
    pub term_epsilon: f64,
    /// Wavelength grid and colour weights (illuminant or a custom light).
    pub spectral: SpectralSetup,
    /// A light spectrum replacing the illuminant (the laser); the ground truth rebuilds its weights from it.
    pub light: Option<Spectrum>,
    pub shading: Shading,
    /// Lookup-table grid and precision.
    pub table: TableParams,
    pub precision: Precision,
    /// A precomputed lookup table to use instead of building one.
    pub table_path: Option<std::path::PathBuf>,
    /// Wavenumber samples of the ground truth's spectral integral (0: twice the grid's count).
    pub ground_truth_samples: usize,
    /// Grating periods for NMM and Stam's lattice (estimated from the surface when `None`).
    pub period_x_nm: Option<f64>,
    pub period_y_nm: Option<f64>,
    /// ε of Stam's wavelength selection (paper: 0.01).
    pub stam_epsilon: f64,
    /// A device (the GPU) that builds lookup tables and renders the ground truths; the CPU when `None`.
    pub accelerator: Option<Arc<dyn Accelerator>>,
    /// The DFT bins the Taylor terms keep (every bin by default). Narrow it only for a method that reads
    /// within it — the reference method for one light ([`Band::light`]); the lookup table reads `|u|, |v| ≤ 2`.
    pub band: Band,
}

impl Default for MethodConfig {
    fn default() -> Self {
        Self {
            coherence_nm: iridis_diffraction::DEFAULT_COHERENCE_NM,
            terms: None,
            term_epsilon: 1e-6,
            spectral: SpectralSetup::default(),
            light: None,
            shading: Shading::default(),
            table: TableParams::default(),
            precision: Precision::F64,
            table_path: None,
            ground_truth_samples: 0,
            period_x_nm: None,
            period_y_nm: None,
            stam_epsilon: 0.01,
            accelerator: None,
            band: Band::ALL,
        }
    }
}

impl MethodConfig {
    /// The Taylor-term count for a patch; a relief too deep for the expansion ([`terms_for_bound`]) is refused
    /// whatever the count, as the model commands refuse it.
    pub fn term_count(&self, patch: &Patch) -> Result<usize, LabError> {
        let auto = terms_for_bound(patch.max_abs_height, self.spectral.wavelengths()[0], self.term_epsilon)?;
        Ok(self.terms.unwrap_or(auto.max(1)))
    }
}

/// A patch with a configuration: builds evaluators, sharing the Taylor terms between the methods that use
/// them.
#[derive(Debug)]
pub struct Workbench {
    pub patch: Patch,
    pub config: MethodConfig,
    /// Name of the surface (for table metadata).
    pub surface: String,
    terms: Mutex<Option<Arc<TaylorTerms>>>,
}

impl Workbench {
    pub fn new(patch: Patch, config: MethodConfig, surface: impl Into<String>) -> Result<Self, LabError> {
        let c = &config;
        patch.check_coherence(c.coherence_nm)?;
        if c.terms == Some(0) {
            return Err(LabError::invalid("the Taylor sum needs at least one term beyond the mirror (terms ≥ 1)"));
        }
        Ok(Self { patch, config, surface: surface.into(), terms: Mutex::new(None) })
    }

    /// The Taylor terms (computed once). `progress(terms_done)`.
    pub fn terms(&self, progress: Progress) -> Result<Arc<TaylorTerms>, LabError> {
        let mut guard = self.terms.lock().map_err(|_| LabError::invalid("internal: poisoned lock"))?;
        if let Some(t) = guard.as_ref() {
            return Ok(t.clone());
        }
        let n = self.config.term_count(&self.patch)?;
        let t = Arc::new(TaylorTerms::compute_in_band(
            &self.patch,
            n,
            self.config.coherence_nm,
            self.config.band,
            progress,
        )?);
        *guard = Some(t.clone());
        Ok(t)
    }

    /// The reference evaluator (thesis FLSS).
    pub fn reference(&self, progress: Progress) -> Result<Reference, LabError> {
        Ok(Reference {
            terms: self.terms(progress)?,
            shading: self.config.shading.clone(),
            spectral: self.config.spectral.clone(),
        })
    }

    /// Grating periods for NMM and Stam: given, else the surface's dominant periods.
    pub fn periods(&self) -> (Option<f64>, Option<f64>) {
        let px = self.config.period_x_nm.or_else(|| dominant_period(&self.patch, Axis::X).map(|p| p.period_nm));
        let py = self.config.period_y_nm.or_else(|| dominant_period(&self.patch, Axis::Y).map(|p| p.period_nm));
        (px, py)
    }

    /// The lookup method for `pixels` alone: a table whose nodes are computed where those pixels read them
    /// ([`LookupTable::build_nodes`]), so the colours are exactly the whole table's at a fraction of its cost
    /// (a 64² map of a 501² table: ~4 %). Where a table file or an accelerator would serve the whole table,
    /// [`Workbench::evaluator`]'s lookup. `progress` reports table rows.
    pub fn lookup_for(
        &self,
        pixels: &crate::image::Pixels,
        progress: Progress,
    ) -> Result<Box<dyn Evaluator>, LabError> {
        let c = &self.config;
        if c.table_path.is_some() || c.accelerator.is_some() {
            return self.evaluator(Method::Lookup, progress);
        }
        let terms = self.terms(&crate::no_progress)?;
        let dirs = pixels.samples.iter().flatten().map(|&(wi, wr, _)| (wi, wr));
        let nodes = iridis_diffraction::table::nodes_for(c.table, dirs);
        let table = LookupTable::build_nodes(&terms, &c.spectral, c.table, &self.surface, Some(&nodes), progress)?;
        Ok(Box::new(Lookup::new(Arc::new(table), c.shading.clone(), c.precision)?))
    }

    /// Builds the evaluator of `method`. `progress` reports the expensive step (terms or table rows).
    pub fn evaluator(&self, method: Method, progress: Progress) -> Result<Box<dyn Evaluator>, LabError> {
        let c = &self.config;
        Ok(match method {
            Method::GroundTruth | Method::GroundTruthPeriodic => {
                let aperture = if method == Method::GroundTruth { Aperture::Finite } else { Aperture::Periodic };
                let samples = if c.ground_truth_samples > 0 {
                    c.ground_truth_samples
                } else {
                    2 * c.spectral.wavelengths().len()
                };
                let mut gt = GroundTruth::with_aperture(
                    &self.patch,
                    c.coherence_nm,
                    c.shading.clone(),
                    &c.spectral,
                    samples,
                    aperture,
                )?;
                if let Some(light) = &c.light {
                    gt = gt.with_light(|l| light.value_at(l), c.spectral.observer);
                }
                Box::new(gt)
            }
            Method::Reference => Box::new(self.reference(progress)?),
            Method::Lookup => {
                let table = match &c.table_path {
                    Some(p) => {
                        let t = LookupTable::load(p)?;
                        check_table(&t, &p.display().to_string(), &self.patch, c)?;
                        t
                    }
                    None => {
                        let terms = self.terms(&crate::no_progress)?;
                        match &c.accelerator {
                            Some(a) => a.build_table(&terms, &c.spectral, c.table, &self.surface, progress)?,
                            None => LookupTable::build(&terms, &c.spectral, c.table, &self.surface, progress)?,
                        }
                    }
                };
                Box::new(Lookup::new(Arc::new(table), c.shading.clone(), c.precision)?)
            }
            Method::Nmm => {
                let (px, py) = self.periods();
                Box::new(Nmm::new(self.reference(progress)?, px, py)?)
            }
            Method::Pq => Box::new(Pq::new(self.terms(progress)?, c.shading.clone(), c.spectral.clone())),
            Method::StamPeriodic(bump) => {
                let mut s = StamPeriodic::fit(
                    &self.patch,
                    bump,
                    c.stam_epsilon,
                    c.coherence_nm,
                    c.shading.clone(),
                    c.spectral.clone(),
                )?;
                if let Some(px) = c.period_x_nm {
                    let scale = px / s.lattice.period_x;
                    s.lattice.period_x = px;
                    s.lattice.width *= scale;
                }
                if let Some(py) = c.period_y_nm {
                    s.lattice.period_y = Some(py);
                    s.lattice.length = py / 2.0;
                    s.lattice.height = 1.0;
                    let rms = (self.patch.heights.iter().map(|h| h * h).sum::<f64>() / self.patch.heights.len() as f64)
                        .sqrt();
                    s.lattice.height = rms / s.lattice.unit_variance().sqrt();
                }
                Box::new(s)
            }
            Method::StamGaussian => {
                Box::new(StamGaussian::new(&self.patch, c.coherence_nm, c.shading.clone(), c.spectral.clone())?)
            }
        })
    }
}

impl Workbench {
    /// [`crate::image::render`] of `evaluator`, on the configured accelerator where it evaluates this kind of
    /// evaluator (the ground truths on the GPU), else on the CPU. `progress(pixels_done)`.
    pub fn render(
        &self,
        evaluator: &dyn Evaluator,
        pixels: &crate::image::Pixels,
        progress: Progress,
    ) -> Result<Vec<Option<Xyz>>, LabError> {
        if let Some(a) = &self.config.accelerator {
            if let Some(img) = crate::image::render_on(a.as_ref(), evaluator, pixels, progress) {
                return img;
            }
        }
        Ok(crate::image::render(evaluator, pixels, progress))
    }
}

/// A loaded table must describe this patch and these settings: its whole provenance (surface fingerprint,
/// size, pixel size, coherence, illuminant or light spectrum, observer, Δλ and range, N, u-v grid), every
/// mismatch named ([`LookupTable::check`], the check `brdf-map` makes on the options a user gives).
pub fn check_table(t: &LookupTable, path: &str, patch: &Patch, c: &MethodConfig) -> Result<(), LabError> {
    let expected = Provenance::of(patch, c.coherence_nm, c.term_count(patch)?, &c.spectral, c.table);
    Ok(t.check(&expected, path)?)
}

/// A spectral setup lit by an arbitrary light spectrum on a uniform grid: the weights are the light's, and
/// the light's power on the grid is kept ([`SpectralSetup::light`]) so that a table built with it records it.
pub fn spectral_with_light(
    light: &Spectrum,
    observer: Observer,
    from_nm: f64,
    to_nm: f64,
    step_nm: f64,
) -> Result<SpectralSetup, LabError> {
    let mut s = SpectralSetup::with_range(iridis_color::Illuminant::E, observer, from_nm, to_nm, step_nm)?;
    let grid = s.wavelengths().to_vec();
    s.weights = iridis_color::SpectralWeights::with_light(&grid, |l| light.value_at(l), observer);
    s.light = Some(grid.iter().map(|&l| light.value_at(l)).collect());
    Ok(s)
}
