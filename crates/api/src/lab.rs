//! The virtual lab's orchestration (`testbench`, `compare`, `sweep`, `experiment laser`, Python's
//! `iridis.lab`): the workbench of a SURFACE with the model's options, evaluators with progress, the test
//! bench with its warnings, method comparisons, and the laser experiment's coating and beam.

use std::path::Path;

use anyhow::{bail, Context, Result};
use iridis_color::{Illuminant, Observer, Spectrum, Xyz};
use iridis_diffraction::geometry::{FresnelConvention, Shading};
use iridis_diffraction::{Evaluator, SpectralSetup};
use iridis_lab::bench::{self, BenchResult, BenchSetup, ReflectanceMatrix};
use iridis_lab::compare::ComparisonRow;
use iridis_lab::image::{render, Pixels};
use iridis_lab::laser::MetalFresnel;
use iridis_lab::methods::{Method, MethodConfig, Workbench};
use serde_json::json;

use crate::model::coherence_for;
use crate::report::{with_progress, Report};
use crate::surface::{Source, SurfaceOptions};

/// How to read SURFACE and the model's parameters, shared by the lab commands (with the feature `cli`, their
/// flags).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
// The field docs are `--help` text too, where `schlick[:N]` is syntax, not a link.
#[allow(rustdoc::broken_intra_doc_links)]
pub struct LabOptions {
    #[cfg_attr(feature = "cli", command(flatten))]
    pub surface: SurfaceOptions,
    /// Coherence length 4σ_s of the window, a property of the light (default 65um, the paper's; a smaller
    /// patch is taken as one unit cell of a periodic surface; said in the output). At least 4 pixels.
    #[cfg_attr(feature = "cli", arg(long = "coherence", value_name = "COHERENCE"))]
    #[cfg_attr(feature = "cli", arg(value_parser = crate::args::positive_length_nm))]
    pub coherence_nm: Option<f64>,
    /// Taylor terms: auto (remainder bound 1e-6) or N.
    #[cfg_attr(feature = "cli", arg(long, default_value = "auto"))]
    pub terms: String,
    /// Fresnel factor: schlick[:N] (default schlick:1.5), index:N[+Ki], gold (measured) or a thin-film stack,
    /// e.g. "stack:air | keratin 300nm | n=1.56" (as brdf-map's --fresnel).
    #[cfg_attr(feature = "cli", arg(long, default_value = crate::fresnel::DEFAULT_FRESNEL))]
    pub fresnel: String,
    /// How the Fresnel reflectance enters: physical (R once, the default) or paper (R², the paper's formula as
    /// printed, to reproduce its figures; docs/PHYSICS.md).
    #[cfg_attr(feature = "cli", arg(long = "fresnel-convention", value_name = "physical|paper"))]
    #[cfg_attr(feature = "cli", arg(default_value = "physical", value_parser = crate::args::fresnel_convention))]
    pub convention: FresnelConvention,
    /// The Cook–Torrance shadowing term.
    #[cfg_attr(feature = "cli", arg(long = "no-shadowing", action = clap::ArgAction::SetFalse))]
    #[cfg_attr(feature = "cli", arg(help = "Leave out the Cook–Torrance shadowing term"))]
    pub shadowing: bool,
    /// ε of the wavelength selection of Stam's periodic models (stam-periodic, stam-periodic-triangular)
    /// [default: 0.01, the paper's]; refused with other methods.
    #[cfg_attr(feature = "cli", arg(long = "epsilon", value_name = "EPSILON"))]
    pub stam_epsilon: Option<f64>,
}

impl Default for LabOptions {
    fn default() -> Self {
        Self {
            surface: SurfaceOptions::default(),
            coherence_nm: None,
            terms: "auto".into(),
            fresnel: crate::fresnel::DEFAULT_FRESNEL.into(),
            convention: FresnelConvention::Physical,
            shadowing: true,
            stam_epsilon: None,
        }
    }
}

impl LabOptions {
    /// The methods' configuration (the coherence is replaced by the patch's in [`workbench`] when none is
    /// given).
    pub fn config(&self) -> Result<MethodConfig> {
        let terms = match self.terms.trim() {
            "auto" => None,
            t => match t.parse::<usize>() {
                Ok(n) if (1..=200).contains(&n) => Some(n),
                _ => bail!("--terms '{t}' must be 'auto' or a number of terms from 1 to 200"),
            },
        };
        let mut config = MethodConfig {
            // Replaced by the patch's coherence in `workbench` when none is given.
            coherence_nm: self.coherence_nm.unwrap_or(iridis_diffraction::DEFAULT_COHERENCE_NM),
            terms,
            shading: Shading {
                fresnel: crate::fresnel::parse_fresnel_source(&self.fresnel)?,
                shadowing: self.shadowing,
                convention: self.convention,
            },
            ..MethodConfig::default()
        };
        if let Some(e) = self.stam_epsilon {
            config.stam_epsilon = e;
        }
        Ok(config)
    }

    /// Refuses `--terms N` and `--epsilon` when none of the command's `methods` reads them: each would change
    /// nothing, without a word. `rigorous`: the rigorous method is among them (it reads the terms, for the scalar
    /// lobes it scales).
    pub fn refuse_unused(&self, methods: &[Method], rigorous: bool) -> Result<()> {
        refuse_unused_terms(&self.terms, methods, rigorous)?;
        if let Some(e) = self.stam_epsilon {
            if !methods.iter().any(|m| m.uses_stam_epsilon()) {
                let users: Vec<&str> = Method::ALL.iter().filter(|m| m.uses_stam_epsilon()).map(|m| m.name()).collect();
                bail!(
                    "--epsilon {e} would be ignored: it is ε of the wavelength selection of Stam's periodic models \
                     ({}), and {} none",
                    users.join(", "),
                    who(methods, rigorous, ("has", "have"))
                );
            }
        }
        Ok(())
    }
}

/// Refuses `--terms N` (anything but `auto`) when none of `methods` (and not the rigorous one) is built from
/// Taylor terms: the ground truths and Stam's models would ignore it.
pub fn refuse_unused_terms(terms: &str, methods: &[Method], rigorous: bool) -> Result<()> {
    let terms = terms.trim();
    if terms != "auto" && !rigorous && !methods.iter().any(|m| m.uses_taylor_terms()) {
        let users: Vec<&str> = Method::ALL.iter().filter(|m| m.uses_taylor_terms()).map(|m| m.name()).collect();
        bail!(
            "--terms {terms} would be ignored: {} no Taylor terms ({} and {} do)",
            who(methods, rigorous, ("uses", "use")),
            users.join(", "),
            crate::model::RIGOROUS
        );
    }
    Ok(())
}

/// "the NAME method VERB" or "the methods A, B VERBS", with `verb` (singular, plural).
fn who(methods: &[Method], rigorous: bool, verb: (&str, &str)) -> String {
    let mut names: Vec<&str> = methods.iter().map(|m| m.name()).collect();
    if rigorous {
        names.push(crate::model::RIGOROUS);
    }
    match names.as_slice() {
        [one] => format!("the {one} method {}", verb.0),
        many => format!("the methods {} {}", many.join(", "), verb.1),
    }
}

/// Loads SURFACE and makes the workbench for `config`, with the coherence given in `m` or fitted to the patch.
pub fn workbench(spec: &str, m: &LabOptions, config: MethodConfig, report: &dyn Report) -> Result<Workbench> {
    workbench_from(&Source::Spec(spec.to_string()), m, config, report)
}

/// [`workbench`] for a height field from anywhere (a SURFACE argument or a patch in memory).
pub fn workbench_from(source: &Source, m: &LabOptions, config: MethodConfig, report: &dyn Report) -> Result<Workbench> {
    workbench_with(source, m, config, CoherenceFrom::Options, report)
}

/// Where a workbench's coherence length comes from, for the note that states it.
#[derive(Debug, Clone, Copy)]
pub enum CoherenceFrom<'a> {
    /// `--coherence`, or the paper's 65 µm.
    Options,
    /// The laser experiment's diaphragm (`--aperture`, nm).
    Aperture(f64),
    /// A sweep over these coherence lengths (nm); the workbench starts at the first.
    Swept(&'a [f64]),
    /// `--coherence` or the default, on a unit cell meant to repeat (the rigorous test bench): the cell being
    /// smaller than the window is the point, not a caveat about periods read off it.
    UnitCell,
}

/// [`workbench_from`] with the coherence from `from`.
pub fn workbench_with(
    source: &Source,
    m: &LabOptions,
    mut config: MethodConfig,
    from: CoherenceFrom<'_>,
    report: &dyn Report,
) -> Result<Workbench> {
    let patch = source.patch(&m.surface, report)?;
    let spec = source.name();
    config.coherence_nm = match from {
        CoherenceFrom::Options => coherence_for(&patch, m.coherence_nm, report)?,
        CoherenceFrom::UnitCell => {
            let c = patch.coherence(m.coherence_nm);
            patch.check_coherence(c.nm)?;
            report.note(&c.unit_cell_note());
            c.nm
        }
        CoherenceFrom::Aperture(nm) => {
            let c = patch.coherence(Some(nm));
            patch.check_coherence(nm)?;
            report.note(&c.note_as("the diaphragm's aperture, --aperture"));
            nm
        }
        CoherenceFrom::Swept(values) => {
            let shown: Vec<String> = values.iter().map(|&v| iridis_lab::sweep::Param::Coherence.display(v)).collect();
            let largest = patch.coherence(Some(values.iter().fold(0.0, |a: f64, &b| a.max(b))));
            let mut note = format!("coherence swept over {} (--values)", shown.join(", "));
            if let Some(p) = largest.periodic_note() {
                note += &format!("; where it exceeds the patch, {p}");
            }
            report.note(&note);
            values.first().copied().unwrap_or(largest.nm)
        }
    };
    // coherence_for says the model's warnings with its note; the other accounts of the coherence, here.
    if !matches!(from, CoherenceFrom::Options) {
        for w in patch.warnings() {
            report.warn(&w);
        }
    }
    report.info(&format!(
        "{spec}: {}×{} samples at {:.1} × {:.1} nm ({:.1} × {:.1} µm), |h|max {:.1} nm, coherence {:.1} µm",
        patch.cols,
        patch.rows,
        patch.dx,
        patch.dy,
        patch.cols as f64 * patch.dx / 1000.0,
        patch.rows as f64 * patch.dy / 1000.0,
        patch.max_abs_height,
        config.coherence_nm / 1000.0
    ));
    Ok(Workbench::new(patch, config, spec)?)
}

/// Builds an evaluator with progress on its expensive step.
pub fn evaluator(b: &Workbench, method: Method, report: &dyn Report) -> Result<Box<dyn Evaluator>> {
    let (len, what) = match method {
        Method::Lookup => (b.config.table.uv_resolution as u64, "lookup tables"),
        Method::GroundTruth | Method::GroundTruthPeriodic | Method::StamGaussian | Method::StamPeriodic(_) => {
            (1, "preparing")
        }
        _ => (b.config.term_count(&b.patch)? as u64 + 1, "Taylor terms"),
    };
    Ok(with_progress(report, len, what, |p| b.evaluator(method, p))?)
}

/// Colours of `pixels` (view directions; `None` below the horizon) by an evaluator, with progress.
pub fn render_pixels(e: &dyn Evaluator, pixels: &Pixels, what: &str, report: &dyn Report) -> Vec<Option<Xyz>> {
    with_progress(report, pixels.len() as u64, what, |p| render(e, pixels, p))
}

/// [`render_pixels`] through the workbench: on its accelerator (the GPU of `--gpu`) where that evaluates the
/// method.
pub fn render_on_bench(
    b: &Workbench,
    e: &dyn Evaluator,
    pixels: &Pixels,
    what: &str,
    report: &dyn Report,
) -> Result<Vec<Option<Xyz>>> {
    Ok(with_progress(report, pixels.len() as u64, what, |p| b.render(e, pixels, p))?)
}

/// The lab's `--gpu`: the GPU builds the lookup tables and renders the ground truths; `None` when `on` is false.
pub fn gpu_accelerator(
    on: bool,
    report: &dyn Report,
) -> Result<Option<std::sync::Arc<dyn iridis_diffraction::Accelerator>>> {
    if !on {
        return Ok(None);
    }
    let a = iridis_gpu::GpuAccelerator::new()?;
    report.info(&format!(
        "on the GPU ({}): lookup tables and ground truths; other methods on the CPU",
        a.gpu().adapter_name()
    ));
    Ok(Some(std::sync::Arc::new(a)))
}

/// The spectral setup of the lab commands (CIE 1931), warning about steps over 5 nm.
pub fn spectral(ill: &str, step: f64, report: &dyn Report) -> Result<SpectralSetup> {
    let ill: Illuminant = ill.parse()?;
    crate::model::warn_coarse_step(step, report);
    Ok(SpectralSetup::new(ill, Observer::Cie1931, step)?)
}

// ---------------------------------------------------------------------------------------------------------
// test bench

/// Refuses a method without a spectral reflectance (the test bench reads peaks per wavelength).
pub fn check_spectral(method: Method) -> Result<()> {
    if !method.is_spectral() {
        bail!(
            "the {method} method integrates over wavelength in advance and has no spectral reflectance; the test \
             bench needs one of: reference, ground-truth, nmm, pq, stam-periodic, stam-gaussian"
        );
    }
    Ok(())
}

/// A test-bench run: the workbench it ran on, the reflectance over (λ, θ_r), and what was read off it.
#[derive(Debug)]
pub struct Testbench {
    pub workbench: Workbench,
    pub setup: BenchSetup,
    pub matrix: ReflectanceMatrix,
    pub result: BenchResult,
    /// The SURFACE's extent along the measured direction (nm): what the period is known to.
    pub extent_nm: f64,
    /// The rigorous method's assumptions and convergence (`--method rigorous`).
    pub rigorous: Option<crate::rigorous_brdf::RigorousSummary>,
}

/// The test bench (paper sec. 6.1) of `method` on SURFACE: `setup.period_hint_nm`, when set, centres the
/// order's window and gives NMM and Stam's lattice the period along the measured direction; `max_period_nm`
/// defaults to the smallest of 10 µm, 0.785 × coherence (the mirror lobe's 2σ_f) and half the patch's extent
/// along the measured direction (a longer period is no period of the scan). With `along_dominant`, the bench
/// measures along the orientation of the surface's strongest period (what `iridis surface info` finds). Says why a period is not definite (competing
/// ridges, spread over λ) as warnings, and how precisely it is known (half a DFT step along the direction, or
/// the window's resolution: [`bench::PatchGrid`]).
pub fn testbench(
    source: &Source,
    m: &LabOptions,
    method: Method,
    mut setup: BenchSetup,
    along_dominant: bool,
    max_period_nm: Option<f64>,
    report: &dyn Report,
) -> Result<Testbench> {
    check_spectral(method)?;
    let mut config = m.config()?;
    let patch = source.patch(&m.surface, report)?;
    if along_dominant {
        measure_along_dominant(&patch, &mut setup, report);
    }
    if let Some(p) = setup.period_hint_nm {
        // NMM and Stam's lattice take the period along the measured direction.
        if setup.azimuth.sin().abs() > setup.azimuth.cos().abs() {
            config.period_y_nm = Some(p);
        } else {
            config.period_x_nm = Some(p);
        }
    }
    let source = Source::Patch { patch, name: source.name().to_string() };
    let mut b = workbench_from(&source, m, config, report)?;
    let lambda_min =
        setup.wavelengths_nm.iter().chain(b.config.spectral.wavelengths()).copied().fold(f64::INFINITY, f64::min);
    // The Taylor terms serve the bench's shortest wavelength, not the colour grid's 380 nm (a bench from 0.5 nm,
    // µm read as nm, gave reflectances of 1e77 from terms counted for 380 nm); too deep there is refused.
    let auto = iridis_diffraction::taylor::terms_for_bound(b.patch.max_abs_height, lambda_min, b.config.term_epsilon)?;
    b.config.terms = Some(b.config.terms.unwrap_or(auto.max(1)));
    if method == Method::Reference {
        // The bench reads one light's lobes: its Taylor terms keep the bins that light reaches (memory).
        let margin = 1.001 * iridis_diffraction::taylor::window_radius(b.config.coherence_nm);
        b.config.band = iridis_diffraction::taylor::Band::light(setup.light(), lambda_min, margin);
    }
    let extent = b.patch.extent_along(setup.azimuth);
    let max_period =
        max_period_nm.unwrap_or((b.config.coherence_nm * std::f64::consts::FRAC_PI_4).min(10_000.0).min(0.5 * extent));
    let e = evaluator(&b, method, report)?;
    bench_on(b, e.as_ref(), setup, extent, max_period, report)
}

/// Measures along the orientation of the surface's strongest period (what `iridis surface info` finds).
fn measure_along_dominant(patch: &iridis_diffraction::Patch, setup: &mut BenchSetup, report: &dyn Report) {
    match crate::surface::strongest_period(patch) {
        Some(p) => {
            // The orientation only: the analysis' period may be a harmonic where the fundamental has too few
            // cycles in the patch, and the bench finds its own first order.
            setup.azimuth = p.orientation_deg.to_radians();
            report.note(&format!(
                "measuring along azimuth {:.1}°, the orientation of the surface's strongest period ({:.1} nm); \
                 --azimuth chooses another",
                p.orientation_deg, p.period_nm,
            ));
        }
        None => report.note("the surface has no dominant period: measuring along azimuth 0° (x)"),
    }
}

/// The test bench of `--method rigorous` (docs/PHYSICS.md, "The rigorous BRDF"): the lobes of the unit cell's
/// periodic extension carrying Maxwell's efficiencies; the cell is SURFACE itself or, with `--unit-cell auto`,
/// its dominant period averaged along the ridges (`rigorous`: `material`, `unit_cell_auto`; the wavelengths
/// must lie in 380–780 nm). The period is then the cell's, known to half a DFT step of the SURFACE it came
/// from; `max_period_nm` defaults to 1.05 × the cell's period along the measured direction.
pub fn testbench_rigorous(
    source: &Source,
    m: &LabOptions,
    rigorous: &crate::ModelOptions,
    mut setup: BenchSetup,
    along_dominant: bool,
    max_period_nm: Option<f64>,
    report: &dyn Report,
) -> Result<Testbench> {
    let (lo, hi) = setup.wavelengths_nm.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &l| (a.min(l), b.max(l)));
    if lo < 380.0 - 1e-9 || hi > 780.0 + 1e-9 {
        bail!("the rigorous test bench runs on 380–780 nm (its window's spectral grid); --from/--to give {lo:.0}–{hi:.0} nm");
    }
    let patch = source.patch(&m.surface, report)?;
    if along_dominant {
        measure_along_dominant(&patch, &mut setup, report);
    }
    let name = source.name().to_string();
    let scan = Source::Patch { patch, name: name.clone() };
    let cell = crate::rigorous_brdf::unit_cell(&scan, &m.surface, rigorous.unit_cell_auto, lo, report)?;
    let config = m.config()?;
    let cell_source = Source::Patch { patch: cell.patch.clone(), name: format!("{name} (unit cell)") };
    let b = workbench_with(&cell_source, m, config, CoherenceFrom::UnitCell, report)?;
    // The bench's wavelengths on the window's spectral grid: one solve each.
    let step = setup.wavelengths_nm.windows(2).map(|w| w[1] - w[0]).next().unwrap_or(5.0);
    let model = crate::ModelOptions {
        terms: m.terms.clone(),
        coherence_nm: Some(b.config.coherence_nm),
        step_nm: Some(step),
        ..rigorous.clone()
    };
    // Quiet: the workbench said the window and the cell already; the solves report below.
    let e = crate::rigorous_brdf::RigorousBrdf::new(cell, rigorous.material.as_deref(), &model, &crate::report::Quiet)?;
    e.prepare(setup.light(), report)?;
    let (lx, ly) = e.cell().patch.extent();
    let along = (setup.azimuth - e.cell().rotation_rad()).rem_euclid(std::f64::consts::PI);
    // The cell's period along the measured direction (an averaged cell's grating vector runs along x).
    let period = if along.cos().abs() >= along.sin().abs() { lx / along.cos().abs() } else { ly / along.sin().abs() };
    let max_period = max_period_nm.unwrap_or(1.05 * period);
    if rigorous.unit_cell_auto {
        // The bench reads 1091.3 nm on a cell built at 1091.3 nm: its own input, not a measurement.
        report.note(&format!(
            "the cell is the scan's strongest period, {period:.1} nm along the bench's direction, read off its \
             spectrum: the bench reads that period back through Maxwell's orders (a check of the solver and the \
             grating equation), it does not measure the scan's period (the reference method's bench does)"
        ));
    }
    let extent = e.cell().scan_extent_nm;
    let mut t = bench_on(b, &e, setup, extent, max_period, report)?;
    t.rigorous = Some(e.summary());
    if let Some(err) = e.failures().first() {
        bail!("the rigorous solver failed: {err}");
    }
    Ok(t)
}

/// The bench's reflectance matrix by `e` and what is read off it, with the warnings.
/// Below this span of viewing angles the bench cannot tell its order from the next (said).
const MIN_BENCH_SPAN_DEG: f64 = 10.0;

fn bench_on(
    b: Workbench,
    e: &dyn Evaluator,
    mut setup: BenchSetup,
    extent: f64,
    max_period_nm: f64,
    report: &dyn Report,
) -> Result<Testbench> {
    setup.max_period_nm = max_period_nm;
    let (lo, hi) = (setup.angles_deg[0], setup.angles_deg[setup.angles_deg.len() - 1]);
    if hi - lo < MIN_BENCH_SPAN_DEG {
        // Radians given as degrees (−1…1.2) read order 4 as order 1 and called 625 nm "definite" for 2500 nm.
        report.warn(&format!(
            "the viewing angles span {}°…{}° only: a peak there may be another order than {} (the period is then \
             off by their ratio); the bench's default is −89°…89° (angles are in degrees)",
            iridis_color::spectrum::short_number(lo),
            iridis_color::spectrum::short_number(hi),
            setup.order
        ));
    }
    let matrix = with_progress(report, setup.wavelengths_nm.len() as u64, "test bench", |p| {
        bench::reflectance_matrix(e, &setup, p)
    })?;
    let result = bench::analyse(&matrix, &setup)?.on_patch(extent, b.config.coherence_nm);
    let azimuth_deg = setup.azimuth.to_degrees();
    if result.periodicity.is_definite() && !result.is_definite() {
        report.warn(&format!(
            "the peaks follow d = {:.1} nm, but {} ridges are nearly as strong (the strongest carries {:.2}× \
             the next, less than {}×): the surface has no definite period along azimuth {azimuth_deg:.0}°",
            result.periodicity.mean,
            result.ridges.len(),
            result.ridge_dominance().unwrap_or(1.0),
            bench::DOMINANT_RIDGE,
        ));
    } else if !result.periodicity.is_definite() {
        report.warn(&format!(
            "the peaks do not follow one period in this direction (d_λ spreads by {:.1} % of its mean, \
             more than {:.0} %): the surface has no definite period along azimuth {azimuth_deg:.0}°; the mean is \
             not a period",
            100.0 * result.periodicity.relative_spread(),
            100.0 * bench::DEFINITE_SPREAD,
        ));
    }
    Ok(Testbench { workbench: b, setup, matrix, result, extent_nm: extent, rigorous: None })
}

// ---------------------------------------------------------------------------------------------------------
// compare

/// The results of a comparison (`iridis compare`, the demo, Python's `lab.compare`).
#[derive(Debug)]
pub struct Comparison {
    /// One row per method and exposure, each against its own truth (`row.against`).
    pub rows: Vec<ComparisonRow>,
    pub images: Vec<(String, Vec<Option<Xyz>>)>,
    /// The images compared against, by method: both ground truths, and `against` if given.
    pub truths: Vec<(Method, Vec<Option<Xyz>>)>,
    /// The periodic ground truth against the finite-aperture one, per exposure.
    pub extension: Vec<ComparisonRow>,
}

impl Comparison {
    pub fn truth(&self, m: Method) -> &[Option<Xyz>] {
        self.truths.iter().find(|t| t.0 == m).map(|t| t.1.as_slice()).unwrap_or(&[])
    }

    /// A row's mean over the first method's at its exposure (Table 2's E2/E1); `None` where the first method's
    /// mean is 0 (its images match the truth at that exposure, e.g. both clipped to white), which no ratio
    /// divides by.
    pub fn ratio(&self, row: &ComparisonRow) -> Option<f64> {
        let first = self.rows.iter().find(|r| r.exposure_ru == row.exposure_ru)?.mean;
        (first > 0.0).then(|| row.mean / first)
    }

    /// The comparison as `iridis compare --json` prints it (keys in docs/json.md).
    pub fn to_json(
        &self,
        surface: &str,
        against: Option<Method>,
        size: usize,
        incidence_deg: f64,
        coherence_nm: f64,
    ) -> serde_json::Value {
        let rows: Vec<_> = self
            .rows
            .iter()
            .map(|r| {
                json!({"method": r.method, "against": r.against, "exposure_ru": r.exposure_ru, "mean": r.mean,
                       "p95": r.p95, "max": r.max, "ratio": self.ratio(r)})
            })
            .collect();
        let ext: Vec<_> = self
            .extension
            .iter()
            .map(|r| json!({"exposure_ru": r.exposure_ru, "mean": r.mean, "p95": r.p95, "max": r.max}))
            .collect();
        let against_name = against.map(|m| m.name()).unwrap_or("model");
        json!({"surface": surface, "against": against_name, "size": size,
            "incidence_deg": incidence_deg, "coherence_nm": coherence_nm, "results": rows,
            "periodic_extension_error": ext})
    }
}

/// Each method against `against`, or against the ground truth of its own model ([`Method::model_truth`]) when
/// `None`; both ground truths are rendered for the periodic-extension error.
pub fn comparison(
    b: &Workbench,
    methods: &[Method],
    against: Option<Method>,
    pixels: &Pixels,
    exps: &[f64],
    report: &dyn Report,
) -> Result<Comparison> {
    let mut truths = Vec::new();
    let mut needed = vec![Method::GroundTruthPeriodic, Method::GroundTruth];
    if let Some(a) = against.filter(|a| !a.is_ground_truth()) {
        needed.push(a);
    }
    for m in needed {
        let e = evaluator(b, m, report)?;
        truths.push((m, render_on_bench(b, e.as_ref(), pixels, m.name(), report)?));
    }
    let mut c = Comparison { rows: Vec::new(), images: Vec::new(), truths, extension: Vec::new() };
    let mut compared_with: Vec<Method> = Vec::new();
    for &m in methods {
        // A lookup table only where the map reads it: the same colours, at the map's cost, not the table's.
        let e = match m {
            Method::Lookup => with_progress(report, b.config.table.uv_resolution as u64, "lookup tables", |p| {
                b.lookup_for(pixels, p)
            })?,
            _ => evaluator(b, m, report)?,
        };
        let img = render_on_bench(b, e.as_ref(), pixels, m.name(), report)?;
        let t = against.unwrap_or(m.model_truth());
        if !compared_with.contains(&t) {
            compared_with.push(t);
        }
        // Two black maps agree to ΔE00 0 and say nothing (the docs' own example compared them as perfect).
        // Pixels outside the disk are None.
        let black = |xyz: &[Option<iridis_color::Xyz>]| {
            crate::lit::dark_at_every_exposure(&xyz.iter().flatten().copied().collect::<Vec<_>>(), exps)
        };
        if black(&img) && black(c.truth(t)) {
            report.warn(&format!(
                "{m} and {t} are both black at every exposure on this {0}² map (their ΔE00 of 0 compares nothing): at \
                 this coherence each lobe is narrower than a pixel; give a larger --size or a shorter --coherence",
                pixels.width
            ));
        }
        let one = [(m.name().to_string(), img)];
        c.rows.extend(iridis_lab::compare::table(&one, c.truth(t), t.name(), exps));
        let [(name, img)] = one;
        c.images.push((name, img));
    }
    c.extension =
        iridis_lab::compare::extension_error(c.truth(Method::GroundTruthPeriodic), c.truth(Method::GroundTruth), exps);
    // Where a truth is mostly clipped white at an exposure, its rows there measure the display, not the method.
    for t in compared_with {
        for &e in exps {
            let share = iridis_lab::compare::clipped_white(c.truth(t), e);
            if let Some(w) = iridis_lab::compare::clipping_warning(share, &format!("the {t} image"), e) {
                report.warn(&w);
            }
        }
    }
    Ok(c)
}

/// `--against`: `model` (or `own`: each method against the ground truth of its own model) or a method.
pub fn parse_against(s: &str) -> Result<Option<Method>> {
    Ok(match s.trim().to_ascii_lowercase().as_str() {
        "model" | "own" => None,
        other => Some(other.parse().map_err(|e| anyhow::anyhow!("--against: {e}, or model"))?),
    })
}

// ---------------------------------------------------------------------------------------------------------
// laser experiment

/// The coating of the laser experiment: `gold` (Johnson & Christy), `none`, or an n,k file.
pub fn coating(s: &str) -> Result<Option<MetalFresnel>> {
    Ok(match s.trim().to_ascii_lowercase().as_str() {
        "none" => None,
        "gold" | "au" => Some(MetalFresnel::new(
            iridis_thinfilm::Material::builtin("gold").context("the built-in gold data are missing")?,
            380.0,
            780.0,
        )?),
        _ => {
            let m = iridis_thinfilm::Material::from_file(Path::new(s))
                .with_context(|| format!("--coating '{s}': not gold, none or a readable n,k file"))?;
            Some(MetalFresnel::new(m, 380.0, 780.0)?)
        }
    })
}

/// The beam's spectrum from a CSV (wavelength_nm, power), or an equal-energy beam (with a note) without one.
pub fn beam_spectrum(path: Option<&Path>, report: &dyn Report) -> Result<Spectrum> {
    Ok(match path {
        Some(p) => Spectrum::from_csv_path(p)?,
        None => {
            report.note("no --spectrum given; using an equal-energy beam (give the laser's CSV for its colours)");
            Spectrum::new(vec![300.0, 900.0], vec![1.0, 1.0])?
        }
    })
}
