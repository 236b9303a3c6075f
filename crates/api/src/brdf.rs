//! Evaluators of the diffraction BRDF for a method on a SURFACE or TABLE (`brdf-map`, `brdf eval`, Python's
//! `iridis.diffraction`), BRDF maps and point queries.

use std::path::Path;
use std::sync::Arc;

use anyhow::{bail, Context, Result};
use iridis_color::Xyz;
use iridis_diffraction::evaluator::{Evaluator, GroundTruth, Reference};
use iridis_diffraction::geometry::Shading;
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::{Patch, PointQuery, SpectralSetup};
use iridis_lab::methods::{Method, MethodConfig, Workbench};

use crate::model::{
    build_table, check_against_table, coherence_for, is_table, spectral_setup, taylor_terms, taylor_terms_for_light,
    ModelOptions, DEFAULT_EPSILON,
};
use crate::report::{with_progress, Report};
use crate::surface::{Source, SurfaceOptions};

// (The rigorous method's name lives in `model`, below both this module and `lab`, which names it too.)
pub use crate::model::RIGOROUS;

/// `--unit-cell auto` with another method than the rigorous one.
pub const UNIT_CELL_AUTO_RIGOROUS: &str =
    "--unit-cell auto chooses the unit cell of the rigorous method: use it with --method rigorous";

/// `--unit-cell`: `whole` (the patch is one period) or `auto` (a scan's dominant period, averaged along its
/// ridges); whether it is `auto`.
pub fn unit_cell_auto(s: &str) -> Result<bool> {
    match s.trim() {
        "auto" => Ok(true),
        "whole" => Ok(false),
        other => bail!("--unit-cell '{other}': expected whole (the patch) or auto (the dominant period)"),
    }
}

/// What makes an evaluator besides its input: the method and the model, shading, table and reading options
/// (`brdf-map`'s and `brdf eval`'s flags, Python's evaluator options).
#[derive(Debug, Clone)]
pub struct EvaluatorSetup<'a> {
    /// `--method`: reference, ground-truth, lookup, rigorous or one of the lab's models.
    pub method: &'a str,
    /// Coherence, Taylor terms, wavelengths and light (`--coherence`, `--terms`, …).
    pub model: &'a ModelOptions,
    /// Fresnel factor, its convention and shadowing around |A|².
    pub shading: Shading,
    /// The lookup table's u-v grid, where the method builds one.
    pub params: TableParams,
    /// The lookup table's arithmetic (f64 on the CPU).
    pub precision: Precision,
    /// How SURFACE is read (channel, pixel size, levelling, …).
    pub surface: &'a SurfaceOptions,
}

/// An evaluator for `--method` on a SURFACE argument or TABLE file (told apart by content, [`is_table`]).
pub fn make_evaluator(input: &str, setup: EvaluatorSetup<'_>, report: &dyn Report) -> Result<Box<dyn Evaluator>> {
    if is_table(input) {
        require_lookup(setup.method)?;
        let table = LookupTable::load(Path::new(input))?;
        return table_evaluator(Arc::new(table), setup.method, setup.model, setup.shading, setup.precision, report);
    }
    evaluator_for(&Source::Spec(input.to_string()), setup, report)
}

/// [`make_evaluator`] made ready for light from `wi` (a BRDF map's): with the rigorous method, Maxwell's
/// equations solved at every wavelength first, in parallel with progress, and the method's assumptions and
/// convergence returned.
pub fn map_evaluator(
    input: &str,
    setup: EvaluatorSetup<'_>,
    wi: [f64; 3],
    report: &dyn Report,
) -> Result<(Box<dyn Evaluator>, Option<crate::rigorous_brdf::RigorousSummary>)> {
    if setup.method == RIGOROUS && !is_table(input) {
        if setup.model.conserve_energy {
            bail!(CONSERVE_RIGOROUS);
        }
        let source = Source::Spec(input.to_string());
        let e = crate::rigorous_brdf::evaluator(&source, setup.model, setup.surface, report)?;
        e.prepare(wi, report)?;
        let s = e.summary();
        return Ok((Box::new(e), Some(s)));
    }
    Ok((make_evaluator(input, setup, report)?, None))
}

/// What `--conserve-energy` does, said where it is applied (`brdf eval`, `brdf-map`, `brdf vision`).
pub(crate) const ENERGY_CONSERVING_LOBES: &str = "energy-conserving lobes: each scaled by its order's factor in the \
     energy-normalised channel matrix of the patch taken as a unit cell (docs/PHYSICS.md, \"Order efficiencies\")";

/// Why `--conserve-energy` is refused with the rigorous method.
const CONSERVE_RIGOROUS: &str = "--conserve-energy scales the scalar model's lobes; the rigorous method's lobes \
                                 carry Maxwell's efficiencies, which conserve energy: leave it out";

/// Why `--conserve-energy` is refused with the lookup method (a table, or one built here).
const CONSERVE_LOOKUP: &str = "--conserve-energy would be ignored: it scales each wavelength's lobes, and the \
     lookup method has none (its table integrates over λ in advance); brdf-map and brdf eval take it with --method \
     reference or ground-truth on the SURFACE";

/// What a lookup table cannot carry, refused where it would be ignored: energy-conserving lobes (the table
/// integrates over λ in advance), the rigorous method's material and unit cell. For a finished table's evaluator
/// and for `precompute` (the CLI's and Python's).
pub fn refuse_for_lookup_table(model: &ModelOptions) -> Result<()> {
    if model.conserve_energy {
        bail!(CONSERVE_LOOKUP);
    }
    if model.unit_cell_auto {
        bail!(UNIT_CELL_AUTO_RIGOROUS);
    }
    if let Some(m) = &model.material {
        bail!(
            "--material {m} would be ignored: it is the rigorous method's medium (and that of the scalar model's \
             error estimate on a scan), and a lookup table has neither; give the SURFACE with another method"
        );
    }
    Ok(())
}

/// One of the lab's methods by name; an unknown name's message lists the rigorous method too, which the
/// commands take besides (handled apart: it is not one of the lab's).
pub(crate) fn lab_method(name: &str) -> Result<Method> {
    name.parse().map_err(|e| anyhow::anyhow!("{e}, {RIGOROUS}"))
}

/// A finished table answers the lookup method only.
fn require_lookup(method: &str) -> Result<()> {
    if method != RIGOROUS {
        // An unknown name is said as such, not as a method that needs the height field.
        lab_method(method)?;
    }
    if method != "lookup" {
        bail!("--method {method} needs the height field, not a table: pass the SURFACE the table was made from");
    }
    Ok(())
}

/// The lookup evaluator of a table, checked against the model options the person gave.
pub fn table_evaluator(
    table: Arc<LookupTable>,
    method: &str,
    model: &ModelOptions,
    shading: Shading,
    precision: Precision,
    report: &dyn Report,
) -> Result<Box<dyn Evaluator>> {
    require_lookup(method)?;
    refuse_for_lookup_table(model)?;
    check_against_table(&table, model, report)?;
    Ok(Box::new(Lookup::new(table, shading, precision)?))
}

/// An evaluator for `method` on a height field: ground truth, reference, lookup (its table built here) or the
/// lab's models.
pub fn evaluator_for(source: &Source, setup: EvaluatorSetup<'_>, report: &dyn Report) -> Result<Box<dyn Evaluator>> {
    let EvaluatorSetup { method, model, shading, params, precision, surface: surface_opts } = setup;
    if method == RIGOROUS {
        if model.conserve_energy {
            bail!(CONSERVE_RIGOROUS);
        }
        return Ok(Box::new(crate::rigorous_brdf::evaluator(source, model, surface_opts, report)?));
    }
    if model.unit_cell_auto {
        bail!(UNIT_CELL_AUTO_RIGOROUS);
    }
    let parsed = lab_method(method)?;
    crate::lab::refuse_unused_terms(&model.terms, &[parsed], false)?;
    if method == "lookup" && shading.fresnel.depends_on_wavelength() {
        // Refused before the (long) table build rather than after it.
        bail!(
            "the lookup method integrates over wavelength in advance, so its Fresnel factor must not depend on λ \
             ({}); use --method reference or ground-truth",
            shading.fresnel.describe()
        );
    }
    let patch = source.patch(surface_opts, report)?;
    let spectral = spectral_setup(model, report)?;
    let input = source.name();
    let conserve = |e: Box<dyn Evaluator>, spectral: SpectralSetup| -> Result<Box<dyn Evaluator>> {
        if !model.conserve_energy {
            return Ok(e);
        }
        report.note(ENERGY_CONSERVING_LOBES);
        Ok(Box::new(iridis_diffraction::grating::LobeScaled::energy_normalised(e, &patch, spectral)?))
    };
    match parsed {
        Method::GroundTruth => {
            let coherence = crate::model::coherence_for_finite_aperture(&patch, model.coherence_nm, report)?;
            let samples = 2 * spectral.wavelengths().len() - 1;
            let e = Box::new(GroundTruth::new(&patch, coherence, shading, &spectral, samples)?);
            conserve(e, spectral)
        }
        Method::Reference => {
            let lambda_min = spectral.wavelengths().first().copied().unwrap_or(380.0);
            let terms = Arc::new(taylor_terms_for_light(&patch, model, lambda_min, report)?);
            conserve(Box::new(Reference { terms, shading, spectral: spectral.clone() }), spectral)
        }
        Method::Lookup if model.conserve_energy => bail!(CONSERVE_LOOKUP),
        _ if model.conserve_energy => bail!(
            "--conserve-energy scales each wavelength's lobes: the {method} method has none (lookup integrates over λ \
             in advance; the lab's models have no lobes of the patch's orders); use reference or ground-truth"
        ),
        Method::Lookup => {
            let terms = taylor_terms(&patch, model, report)?;
            let table = build_table(None, &terms, &spectral, params, input, report)?;
            Ok(Box::new(Lookup::new(Arc::new(table), shading, precision)?))
        }
        // The lab's variants (NMM, PQ) and Stam's analytic models, built as `iridis compare` builds them.
        lab => lab_evaluator(lab, input, patch, model, shading, spectral, report),
    }
}

/// NMM, PQ and Stam's models from `iridis-lab`, with the same Taylor terms and window as `reference`.
fn lab_evaluator(
    method: Method,
    input: &str,
    patch: Patch,
    model: &ModelOptions,
    shading: Shading,
    spectral: SpectralSetup,
    report: &dyn Report,
) -> Result<Box<dyn Evaluator>> {
    let coherence = coherence_for(&patch, model.coherence_nm, report)?;
    let terms = match model.terms.trim() {
        "auto" => None,
        t => match t.parse::<usize>() {
            Ok(n) if (1..=200).contains(&n) => Some(n),
            _ => bail!("--terms '{t}' must be 'auto' or a number of terms from 1 to 200 for --method {method}"),
        },
    };
    let config = MethodConfig {
        coherence_nm: coherence,
        terms,
        term_epsilon: DEFAULT_EPSILON,
        spectral,
        shading,
        ..Default::default()
    };
    let bench = Workbench::new(patch, config, input)?;
    let uses_terms = matches!(method, Method::Nmm | Method::Pq);
    let len = if uses_terms { bench.config.term_count(&bench.patch)? as u64 + 1 } else { 1 };
    let e = with_progress(report, len, "preparing", |p| bench.evaluator(method, p));
    e.with_context(|| format!("--method {method} cannot make a map of {input}"))
}

/// A BRDF map (the paper's layout: pixel (x, y) views (x, y, √(1 − x² − y²)), row 0 at the top) for the
/// light direction `wi`, with progress: linear XYZ per pixel, each the mean of its `subsamples²` view samples
/// (1: its centre; [`iridis_diffraction::map::brdf_map`]).
pub fn render_map(e: &dyn Evaluator, wi: [f64; 3], size: usize, subsamples: usize, report: &dyn Report) -> Vec<Xyz> {
    with_progress(report, size as u64, &format!("{} map", e.name()), |p| {
        iridis_diffraction::map::brdf_map(e, wi, size, subsamples, p)
    })
}

/// The BRDF `f_r` in sr⁻¹ per pixel of a map, as XYZ under the model's light and observer (`Y` the luminous
/// BRDF; [`iridis_diffraction::map::brdf_map_per_sr`]), with progress.
pub fn render_map_per_sr(
    e: &dyn Evaluator,
    model: &ModelOptions,
    wi: [f64; 3],
    size: usize,
    subsamples: usize,
    report: &dyn Report,
) -> Result<Vec<Xyz>> {
    let spectral = crate::model::spectral_setup(model, report)?;
    with_progress(report, size as u64, &format!("{} BRDF in sr⁻¹", e.name()), |p| {
        Ok(iridis_diffraction::map::brdf_map_per_sr(e, &spectral.weights, wi, size, subsamples, p)?)
    })
}

/// An exposure (RU) chosen from a map's own values: the 99th percentile of the brightest linear sRGB channel
/// over the lit pixels becomes white, so a bright mirror lobe does not black out the rest and a faint map is
/// not a white disk; with the share of the disk's pixels it clips. `None` for a map with no light in it.
pub fn auto_exposure(xyz: &[Xyz], size: usize) -> Option<AutoExposure> {
    use crate::lit::{is_lit, peak_channel};
    let in_disk = |k: usize| {
        let (x, y) =
            (-1.0 + (2 * (k % size) + 1) as f64 / size as f64, 1.0 - (2 * (k / size) + 1) as f64 / size as f64);
        x * x + y * y <= 1.0
    };
    let disk: Vec<f64> = xyz.iter().enumerate().filter(|(k, _)| in_disk(*k)).map(|(_, p)| peak_channel(p)).collect();
    let mut lit: Vec<f64> = disk.iter().copied().filter(|&v| is_lit(v)).collect();
    if lit.is_empty() {
        return None;
    }
    lit.sort_by(|a, b| a.total_cmp(b));
    let p99 = lit[((lit.len() - 1) as f64 * 0.99).round() as usize];
    let exposure_ru = 1.0 / p99;
    let clipped = disk.iter().filter(|&&v| v * exposure_ru > 1.0 + 1e-12).count();
    Some(AutoExposure {
        exposure_ru,
        clipped_share: clipped as f64 / disk.len() as f64,
        lit_share: lit.len() as f64 / disk.len() as f64,
    })
}

/// What [`auto_exposure`] chose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutoExposure {
    pub exposure_ru: f64,
    /// Share of the disk's pixels brighter than white at that exposure.
    pub clipped_share: f64,
    /// Share of the disk's pixels with any light.
    pub lit_share: f64,
}

/// The method `brdf eval` uses when none is given: reference for a SURFACE, lookup for a TABLE.
pub fn default_method(input: &str) -> &'static str {
    if is_table(input) {
        "lookup"
    } else {
        "reference"
    }
}

/// A direction's reflectance factor `π f_r(λ)` on `wavelengths_nm` as the visual system of `spec` sees it.
pub fn vision_of_factor(
    spec: &iridis_vision::Spec,
    wavelengths_nm: &[f64],
    factor: Vec<f64>,
) -> Result<iridis_vision::Analysis> {
    let system = spec.system().context("--visual")?;
    let options = spec.options(&system)?;
    Ok(iridis_vision::analyse(&[("view".to_string(), factor)], wavelengths_nm, &system, &options)?)
}

/// One method's answer for one pair of directions (`iridis brdf eval`, Python's `diffraction.eval`).
#[derive(Debug, Clone)]
pub struct PointEval {
    /// The evaluator's name.
    pub method: String,
    /// The coherence length the evaluator ran with (nm), where it has one.
    pub coherence_nm: Option<f64>,
    /// The coherence window's effective area `A_eff` (nm²) behind the BRDF's gain `A_eff/λ²`.
    pub effective_area_nm2: Option<f64>,
    /// The wavelength grid, ρ(λ) (`None` for lookup, which integrates over λ in advance) and XYZ.
    pub query: PointQuery,
    /// The rigorous method's assumptions and convergence.
    pub rigorous: Option<crate::rigorous_brdf::RigorousSummary>,
    /// A scalar method on a scan with a dominant period: how far the scalar model is from Maxwell's equations
    /// on the scan's averaged period for this light.
    pub scalar_error: Option<crate::rigorous_brdf::ScanScalarError>,
    /// The lookup method's table: what its numbers were built with (N, the u-v grid, the spectral step).
    pub table: Option<iridis_diffraction::table::TableMeta>,
}

impl PointEval {
    /// The table's settings in a line, for the lookup method.
    pub fn table_line(&self) -> Option<String> {
        let t = self.table.as_ref()?;
        Some(format!(
            "table of {}: N = {} Taylor terms, {}² u-v grid (power {}), {}–{} nm in {} nm steps, {}, CIE {} observer",
            t.surface,
            t.taylor_terms,
            t.uv_resolution,
            t.uv_power,
            t.wavelength_min_nm,
            t.wavelength_max_nm,
            t.wavelength_step_nm,
            t.illuminant,
            t.observer
        ))
    }
}

impl PointEval {
    /// The reflectance factor `π f_r(λ)` (unpolarised; a white diffuser's is 1), where the method gives `f_r`.
    pub fn reflectance_factor(&self) -> Option<Vec<f64>> {
        let b = self.query.brdf.as_ref()?;
        Some(b.unpolarized.iter().map(|f| std::f64::consts::PI * f).collect())
    }

    /// How an animal sees this direction's light: the reflectance factor analysed by the receptor-noise-limited
    /// model (`iridis-vision`) on the query's wavelengths.
    pub fn vision(&self, spec: &iridis_vision::Spec) -> Result<iridis_vision::Analysis> {
        let Some(factor) = self.reflectance_factor() else {
            bail!("--visual needs the BRDF f_r(λ), which the {} method does not give", self.method);
        };
        vision_of_factor(spec, &self.query.wavelengths_nm, factor)
    }

    /// The spectra as a CSV pavo reads (a wavelength column, one column per quantity): the reflectance factor
    /// `π f_r` for s, p and unpolarised light, and the relative `ρ`.
    pub fn spectra_csv(&self) -> Result<String> {
        let (Some(b), Some(rho)) = (&self.query.brdf, &self.query.reflectance) else {
            bail!("--spectra needs the spectral BRDF, which the {} method does not give", self.method);
        };
        let pi = std::f64::consts::PI;
        let mut out = String::from("wavelength_nm,pi_fr_s,pi_fr_p,pi_fr_unpolarized,rho_relative\n");
        for (k, l) in self.query.wavelengths_nm.iter().enumerate() {
            out += &format!("{l},{},{},{},{}\n", pi * b.s[k], pi * b.p[k], pi * b.unpolarized[k], rho[k]);
        }
        Ok(out)
    }
}

/// ρ(λ) and XYZ of `method` (default [`default_method`]) on INPUT for light `wi` and view `wr`.
pub fn eval_point(
    input: &str,
    method: Option<&str>,
    model: &ModelOptions,
    shading: Shading,
    params: TableParams,
    surface_opts: &SurfaceOptions,
    wi: [f64; 3],
    wr: [f64; 3],
    report: &dyn Report,
) -> Result<PointEval> {
    let method = method.unwrap_or_else(|| default_method(input));
    let precision = Precision::F64;
    let setup = EvaluatorSetup { method, model, shading, params, precision, surface: surface_opts };
    let (e, rigorous) = map_evaluator(input, setup, wi, report)?;
    let mut p = point(e.as_ref(), model, wi, wr, report)?;
    p.rigorous = rigorous;
    if !is_table(input) && p.rigorous.is_none() {
        let source = Source::Spec(input.to_string());
        p.scalar_error = scalar_error_said(&source, surface_opts, wi, model.material.as_deref(), report);
    }
    Ok(p)
}

/// The scalar model's error on SOURCE's own period for light `wi` (issue 28), warned on `report` where it is
/// above the threshold at which the scalar numbers are not to be trusted; `None`, with a note, where the scan
/// has no dominant period or the estimate failed. What `brdf eval` and Python's `evaluate` state beside a
/// scalar method's numbers.
pub fn scalar_error_said(
    source: &Source,
    surface_opts: &SurfaceOptions,
    wi: [f64; 3],
    material: Option<&str>,
    report: &dyn Report,
) -> Option<crate::rigorous_brdf::ScanScalarError> {
    match crate::rigorous_brdf::scalar_error_of_scan(source, surface_opts, wi, material, report) {
        Ok(Some(e)) => {
            if e.error.above_threshold() {
                report.warn(&format!(
                    "{}: above the {:.0} % (or ΔE00 {:.0}) at which the scalar numbers are not to be trusted; \
                     `--method rigorous --unit-cell auto` gives Maxwell's",
                    e.sentence(),
                    100.0 * crate::grating::SCALAR_WARN_RELATIVE,
                    crate::grating::SCALAR_WARN_DELTA_E
                ));
            }
            Some(e)
        }
        Ok(None) => {
            if let Some(m) = material {
                report.note(&format!(
                    "--material {m} is the medium of the scalar model's error estimate, which needs a dominant \
                     period (one carrying at least {:.0} % of the height variance, as `surface info` finds it); this surface has none, so none was \
                     made and --material was not used",
                    100.0 * crate::rigorous_brdf::MIN_PERIOD_SHARE
                ));
            }
            None
        }
        Err(err) => {
            report.note(&format!("the scalar model's error on this scan could not be estimated: {err:#}"));
            None
        }
    }
}

/// A BRDF feature between two samples this many standard deviations of its width apart is below ~1 % of its
/// peak at both (`exp(−3²/2)`): it can vanish from an image (a map's pixels, the laser screen's samples).
pub const SAMPLES_PER_LOBE_SIGMA: f64 = 6.0;

/// Samples at most this many standard deviations of a lobe's width apart sum to its integral within 0.1 %
/// (Poisson summation: a Gaussian sampled `h` apart along one axis sums with an error of up to
/// `±2 exp(−2π²σ²/h²)`, where in that range set by where the samples fall, twice that over the (u, v) disk: 6e-4
/// at `h = 1.5σ`, 2.9 % at `2σ`, 45 % at `3σ`, for the narrowest lobe, 380 nm's): what measuring a lobe's light
/// takes, beyond showing it ([`SAMPLES_PER_LOBE_SIGMA`]). Measured on an 1100 nm gold sine's rigorous map at 30°
/// (32², 65 µm): the sum of f_r 74 % short at 6σ, 3.2 % at 3σ, converged at 1.5σ.
pub const MEASURE_SAMPLES_PER_LOBE_SIGMA: f64 = 1.5;

/// View samples too far apart for the light's lobes ([`lobe_shortfall`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LobeShortfall {
    /// The narrowest lobe's width: σ of the window's `|G|²` at 380 nm, in direction cosines (≈ radians).
    pub sigma: f64,
    /// How many times closer the samples must be to sample every lobe.
    pub finer_by: f64,
}

/// Whether view samples `spacing` apart (direction cosines, or radians near the mirror direction) sample every
/// lobe of a light of this coherence length: `None` where they are at most [`SAMPLES_PER_LOBE_SIGMA`] widths of
/// the narrowest lobe (380 nm, [`iridis_diffraction::spectral::lobe_sigma_uv`]) apart; else that width and how
/// many times closer they must be. Shared by the maps' and the laser screen's warnings.
pub fn lobe_shortfall(spacing: f64, coherence_nm: f64) -> Option<LobeShortfall> {
    let sigma = iridis_diffraction::spectral::lobe_sigma_uv(380.0, coherence_nm);
    let widest = SAMPLES_PER_LOBE_SIGMA * sigma;
    (spacing > widest).then_some(LobeShortfall { sigma, finer_by: spacing / widest })
}

/// The coherence length whose Gaussian window has the effective area of `e`'s (`A_eff = 4πσ_s²`, from
/// [`Evaluator::radiometric_gain`]): the light's where the window lies inside the patch or on its periodic
/// lattice, less where the patch edge cuts it (the finite aperture), whose lobes are then wider.
pub fn lobe_coherence_nm(e: &dyn Evaluator) -> Option<f64> {
    // Any wavelength: the gain is A_eff/λ².
    let lambda = 550.0;
    e.radiometric_gain(lambda).map(|g| 4.0 * lambda * (g / (4.0 * std::f64::consts::PI)).sqrt()).or(e.coherence_nm())
}

/// How a lobe warning names the coherence behind the lobes' width: the light's, or, where the patch's edge cuts
/// the window (the finite aperture, [`lobe_coherence_nm`] shorter by more than 0.5 %), both — a map said
/// "coherence 59.5 µm" after the note's "coherence 65 µm".
pub fn lobe_coherence_label(effective_nm: f64, light_nm: Option<f64>) -> String {
    match light_nm {
        Some(light) if (effective_nm - light).abs() > 0.005 * light => format!(
            "effective coherence {:.1} µm: the light's {:.1} µm window cut by the patch's edge",
            effective_nm / 1000.0,
            light / 1000.0
        ),
        _ => format!("coherence {:.1} µm", effective_nm / 1000.0),
    }
}

/// ρ(λ) (on the model's wavelength grid) and XYZ of an evaluator for light `wi` and view `wr`.
pub fn point(
    e: &dyn Evaluator,
    model: &ModelOptions,
    wi: [f64; 3],
    wr: [f64; 3],
    report: &dyn Report,
) -> Result<PointEval> {
    let spectral = spectral_setup(model, report)?;
    let query = iridis_diffraction::point_query(e, spectral.wavelengths(), wi, wr)?;
    let effective_area_nm2 = e.radiometric_gain(1.0);
    Ok(PointEval {
        method: e.name().to_string(),
        coherence_nm: e.coherence_nm(),
        effective_area_nm2,
        query,
        rigorous: None,
        scalar_error: None,
        table: e.as_lookup().map(|l| l.table.meta.clone()),
    })
}
