//! The virtual lab's runs as the front ends ask for them (`iridis testbench|compare|sweep|experiment laser`,
//! Python's `iridis.lab`): each takes the parsed request, runs [`crate::lab`]'s orchestration, writes its figures
//! through the run's output set and returns a result with the text the command prints and its `--json`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use iridis_color::units::parse_length_nm;
use iridis_color::{Illuminant, Observer, Xyz};
use iridis_diffraction::table::TableParams;
use iridis_diffraction::SpectralSetup;
use iridis_lab::bench::{self, BenchSetup};
use iridis_lab::image::Pixels;
use iridis_lab::laser::LaserSetup;
use iridis_lab::methods::Method;
use iridis_lab::sweep::{Param, Point};
use serde_json::{json, Value};

use crate::lab::{
    comparison, evaluator, render_pixels, spectral, workbench, workbench_from, workbench_with, CoherenceFrom,
    Comparison, LabOptions, Testbench,
};
use crate::model::TableGrid;
use crate::output::write_png_rgb8;
use crate::report::{with_progress, Report};
use crate::surface::Source;

/// A surface name short enough for a plot title.
pub fn short_name(spec: &str) -> String {
    let s = spec.strip_prefix("builtin:").unwrap_or(spec);
    let s = Path::new(s).file_name().and_then(|f| f.to_str()).unwrap_or(s);
    if s.chars().count() > 28 {
        format!("{}…", s.chars().take(27).collect::<String>())
    } else {
        s.to_string()
    }
}

/// A comma-separated list (`--methods`, `--values`, `--exposures`), at least one value.
pub fn parse_list<T>(s: &str, what: &str, f: impl Fn(&str) -> Result<T>) -> Result<Vec<T>> {
    let v: Vec<T> = s.split(',').filter(|p| !p.trim().is_empty()).map(|p| f(p.trim())).collect::<Result<_>>()?;
    if v.is_empty() {
        bail!("{what}: give at least one value");
    }
    Ok(v)
}

/// Refuses a list that names a value twice (`--methods`, `--exposures`, `--values`): the second would repeat the
/// first's work and its row, to no end.
pub fn refuse_repeats<T: PartialEq + std::fmt::Display>(what: &str, values: &[T]) -> Result<()> {
    for (k, v) in values.iter().enumerate() {
        if values[..k].contains(v) {
            bail!("{what} lists {v} twice; give each value once");
        }
    }
    Ok(())
}

/// `--exposures`: positive exposures in RU (`1,1000,7500`; an `RU` suffix is allowed).
pub fn parse_exposures(s: &str) -> Result<Vec<f64>> {
    parse_list(s, "--exposures", |p| match p.trim_end_matches("RU").trim_end_matches("ru").parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => bail!("--exposures: '{p}' is not a positive exposure in RU (e.g. 1,1000,7500)"),
    })
}

// ---------------------------------------------------------------------------------------------------------
// testbench

/// What `iridis testbench` asks of [`testbench_run`].
#[derive(Debug, Clone)]
pub struct TestbenchRequest {
    /// reference, ground-truth, nmm, pq, stam-*, or rigorous.
    pub method: String,
    /// The rigorous method's material and unit cell (`material`, `unit_cell_auto`).
    pub rigorous: crate::ModelOptions,
    pub setup: BenchSetup,
    /// Measure along the surface's strongest period (no `--azimuth`).
    pub along_dominant: bool,
    pub max_period_nm: Option<f64>,
    /// The Figure-7 plot (PNG).
    pub plot: Option<PathBuf>,
}

/// A test bench with what the command prints.
#[derive(Debug)]
pub struct TestbenchRun {
    pub surface: String,
    pub method: String,
    pub bench: Testbench,
}

/// The test bench of a request: checks the method, runs [`crate::lab::testbench`] (or its rigorous form),
/// writes the plot.
pub fn testbench_run(
    source: &Source,
    lab: &LabOptions,
    req: &TestbenchRequest,
    report: &dyn Report,
) -> Result<TestbenchRun> {
    let rigorous = req.method == crate::brdf::RIGOROUS;
    // The lab's method (none for the rigorous one, which is not among them).
    let method: Option<Method> = (!rigorous).then(|| crate::brdf::lab_method(&req.method)).transpose()?;
    if let Some(m) = method {
        if req.rigorous.material.is_some() || req.rigorous.unit_cell_auto {
            bail!("--material and --unit-cell auto are the rigorous method's: add --method rigorous");
        }
        crate::lab::check_spectral(m)?;
    }
    lab.refuse_unused(method.as_slice(), rigorous)?;
    if rigorous {
        crate::fresnel::refuse_scalar_shading_for_rigorous(&lab.fresnel, lab.convention, lab.shadowing)?;
    }
    crate::output::declare_opt("--plot", req.plot.as_deref(), &["png"])?;
    let setup = req.setup.clone();
    let t = match method {
        Some(m) => crate::lab::testbench(source, lab, m, setup, req.along_dominant, req.max_period_nm, report)?,
        None => crate::lab::testbench_rigorous(
            source,
            lab,
            &req.rigorous,
            setup,
            req.along_dominant,
            req.max_period_nm,
            report,
        )?,
    };
    if let Some(r) = &t.rigorous {
        report.note(&r.sentence());
    }
    let run = TestbenchRun { surface: source.name().to_string(), method: req.method.clone(), bench: t };
    if let Some(path) = &req.plot {
        let (setup, result) = (&run.bench.setup, &run.bench.result);
        let curve = req.setup.period_hint_nm.unwrap_or(result.periodicity.mean);
        let title = format!(
            "{} ({}), θi {:.0}°, φ {:.0}°: d = {:.2} nm, var {:.3}",
            short_name(&run.surface),
            run.method,
            setup.incidence.to_degrees(),
            setup.azimuth.to_degrees(),
            result.periodicity.mean,
            result.periodicity.variance
        );
        let img = bench::plot(&run.bench.matrix, setup, result, curve, &title)?;
        write_png_rgb8(path, img.width, img.height, &img.data)?;
        report.info(&format!("wrote {}", path.display()));
    }
    Ok(run)
}

impl TestbenchRun {
    /// As `iridis testbench --json` prints it (keys in docs/json.md).
    pub fn to_json(&self) -> Value {
        let mut j = self.bench.result.to_json();
        j["method"] = json!(self.method);
        j["surface"] = json!(self.surface);
        j["rigorous"] = self.bench.rigorous.as_ref().map(|r| r.to_json()).unwrap_or(Value::Null);
        j
    }

    /// The text `iridis testbench` prints.
    pub fn text(&self) -> String {
        let (b, setup, result) = (&self.bench.workbench, &self.bench.setup, &self.bench.result);
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{} with {}: order {}, θi = {:.2}°, azimuth {:.2}°, {} of {} wavelengths with a peak",
            self.surface,
            self.method,
            setup.order,
            setup.incidence.to_degrees(),
            setup.azimuth.to_degrees(),
            result.peaks.len(),
            setup.wavelengths_nm.len()
        );
        let extent_um = self.bench.extent_nm / 1000.0;
        let _ = writeln!(
            s,
            "periodicity  mean {:.2} nm ± {:.1} nm ({}), variance {:.3} nm² (window centred on {:.1} nm){}",
            result.periodicity.mean,
            result.uncertainty_nm().unwrap_or(f64::NAN),
            if result.is_quantised() {
                format!("half a DFT step, d²/(2L), L = {extent_um:.3} µm along the direction")
            } else {
                format!("the {:.1} µm window's resolution, d²σ_f", b.config.coherence_nm / 1000.0)
            },
            result.periodicity.variance,
            result.window_period_nm,
            if result.is_definite() { ", definite" } else { ", not definite" }
        );
        if result.ridges.len() > 1 {
            for (k, r) in result.ridges.iter().enumerate() {
                let _ = writeln!(
                    s,
                    "ridge {}      {:.2} nm, variance {:.3} nm², {} wavelengths, mean peak ρ {:.3e}",
                    k + 1,
                    r.period_nm,
                    r.variance,
                    r.wavelengths,
                    r.strength
                );
            }
        }
        s += "  λ (nm)   θr (deg)   d_λ (nm)\n";
        let stride = (result.peaks.len() / 12).max(1);
        for p in result.peaks.iter().step_by(stride) {
            let _ = writeln!(s, "  {:6.1}   {:8.3}   {:8.2}", p.wavelength_nm, p.angle_deg, p.period_nm);
        }
        s
    }
}

// ---------------------------------------------------------------------------------------------------------
// compare

/// What `iridis compare` asks of [`compare_run`].
#[derive(Debug, Clone)]
pub struct CompareRequest {
    pub methods: Vec<Method>,
    /// `None`: each method against the ground truth of its own model.
    pub against: Option<Method>,
    pub exposures: Vec<f64>,
    /// Light direction θ, φ (radians).
    pub incidence: (f64, f64),
    /// Map size in pixels.
    pub size: usize,
    pub illuminant: String,
    pub dlambda_nm: f64,
    /// The u-v grid of the lookup table built from the surface (refused without the lookup method).
    pub table: TableGrid,
    /// A precomputed lookup table for the lookup method.
    pub table_path: Option<PathBuf>,
    /// Lookup tables and ground truths on the GPU.
    pub gpu: bool,
    /// Write the maps and ΔE heat maps into this folder.
    pub maps: Option<PathBuf>,
}

/// A comparison with what the command prints.
#[derive(Debug)]
pub struct CompareRun {
    pub surface: String,
    pub against: Option<Method>,
    pub size: usize,
    pub incidence_rad: f64,
    pub coherence_nm: f64,
    /// The colours' light and observer: `D65, CIE 1931, Δλ 5 nm`.
    pub colour_setup: String,
    pub comparison: Comparison,
}

/// An image over the view directions of a BRDF map ([`iridis_plot::ImagePlot::view_directions`]), titled, with an
/// optional colour bar, as a figure of `size` pixels.
pub fn view_plot(
    pixels: &iridis_plot::RgbImage,
    title: &str,
    colorbar: Option<iridis_plot::ColorBar>,
    size: (u32, u32),
) -> Result<iridis_plot::RgbImage> {
    Ok(iridis_plot::ImagePlot { colorbar, ..iridis_plot::ImagePlot::view_directions(title, pixels, size) }.render()?)
}

fn heat_plot(map: &[Option<f64>], size: usize, title: &str, max: f64) -> Result<iridis_plot::RgbImage> {
    let px = iridis_lab::image::heat(map, size, size, max);
    let bar = iridis_plot::ColorBar { label: "ΔE00".into(), min: 0.0, max, map: iridis_plot::magma };
    view_plot(&px, title, Some(bar), (620, 520))
}

fn map_plot(img: &[Option<Xyz>], size: usize, exposure: f64, title: &str) -> Result<iridis_plot::RgbImage> {
    view_plot(&iridis_lab::image::to_rgb(img, size, size, exposure), title, None, (520, 520))
}

/// The comparison of a request (paper sec. 6.3, Table 2), with its maps written when asked.
pub fn compare_run(source: &Source, lab: &LabOptions, req: &CompareRequest, report: &dyn Report) -> Result<CompareRun> {
    if !(8..=2048).contains(&req.size) {
        bail!("--size {} must be 8–2048 pixels", req.size);
    }
    if !req.methods.contains(&Method::Lookup) {
        // Only the lookup method reads a table: what shapes one would be ignored.
        let mut given = req.table.flags();
        given.extend(req.table_path.as_ref().map(|p| format!("--table {}", p.display())));
        if !given.is_empty() {
            bail!(
                "{} would be ignored: only the lookup method uses a table; add lookup to --methods",
                given.join(", ")
            );
        }
    }
    lab.refuse_unused(&req.methods.iter().copied().chain(req.against).collect::<Vec<_>>(), false)?;
    refuse_repeats("--methods", &req.methods)?;
    refuse_repeats("--exposures", &req.exposures)?;
    if let Some(m) = req.methods.iter().find(|m| req.against.unwrap_or(m.model_truth()) == **m) {
        let why = match req.against {
            Some(_) => "it is --against".to_string(),
            None => format!("with --against model each method is compared with {}", m.model_truth()),
        };
        bail!(
            "{m} would be compared with itself ({why}): its ΔE00 is 0 by construction and the ratios to it \
             meaningless; leave it out of --methods or give --against another"
        );
    }
    if let Some(d) = &req.maps {
        crate::output::create_dir(d)?;
    }
    let mut config = lab.config()?;
    config.spectral = spectral(&req.illuminant, req.dlambda_nm, report)?;
    config.table = req.table.params()?;
    config.table_path = req.table_path.clone();
    config.accelerator = crate::lab::gpu_accelerator(req.gpu, report)?;
    let b = workbench_from(source, lab, config, report)?;
    let (theta, phi) = req.incidence;
    let pixels = Pixels::brdf_map(theta, phi, req.size);
    let c = comparison(&b, &req.methods, req.against, &pixels, &req.exposures, report)?;
    if let Some(dir) = &req.maps {
        let size = req.size;
        for &e in &req.exposures {
            for (m, img) in &c.truths {
                let t = map_plot(img, size, e, &format!("{} at {e} RU", m.name()))?;
                write_png_rgb8(&dir.join(format!("{}_{e}RU.png", m.name())), t.width, t.height, &t.data)?;
            }
            for (name, img) in &c.images {
                let m = map_plot(img, size, e, &format!("{name} at {e} RU"))?;
                write_png_rgb8(&dir.join(format!("{name}_{e}RU.png",)), m.width, m.height, &m.data)?;
                let truth = name.parse::<Method>().map(|m| req.against.unwrap_or(m.model_truth()))?;
                let de = iridis_lab::compare::delta_e_map(img, c.truth(truth), e);
                let s = iridis_lab::compare::stats(&de);
                let h = heat_plot(
                    &de,
                    size,
                    &format!("ΔE00 {name} vs {} at {e} RU (mean {:.2})", truth.name(), s.mean),
                    s.max.max(1.0),
                )?;
                write_png_rgb8(&dir.join(format!("{name}_{e}RU_deltaE.png")), h.width, h.height, &h.data)?;
            }
        }
        report.info(&format!("wrote maps to {}", dir.display()));
    }
    Ok(CompareRun {
        surface: source.name().to_string(),
        against: req.against,
        size: req.size,
        incidence_rad: theta,
        coherence_nm: b.config.coherence_nm,
        colour_setup: format!(
            "{}, CIE {} observer, Δλ {} nm",
            b.config.spectral.illuminant.name(),
            b.config.spectral.observer.name(),
            b.config.spectral.step_nm
        ),
        comparison: c,
    })
}

impl CompareRun {
    /// As `iridis compare --json` prints it (keys in docs/json.md).
    pub fn to_json(&self) -> Value {
        let deg = iridis_color::units::degrees(self.incidence_rad);
        self.comparison.to_json(&self.surface, self.against, self.size, deg, self.coherence_nm)
    }

    /// The table `iridis compare` prints.
    pub fn text(&self) -> String {
        let c = &self.comparison;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "CIEDE2000 against {} ({}×{} BRDF map, θi = {:.1}°, coherence {:.1} µm, {}):",
            match self.against {
                None => "the ground truth of each method's model".to_string(),
                Some(m) => m.name().to_string(),
            },
            self.size,
            self.size,
            self.incidence_rad.to_degrees(),
            self.coherence_nm / 1000.0,
            self.colour_setup
        );
        let _ = writeln!(
            s,
            "  {:<26} {:<22} {:>10} {:>10} {:>10} {:>10}",
            "method", "against", "exposure", "mean", "p95", "ratio"
        );
        for r in &c.rows {
            let ratio = c.ratio(r).map_or("—".to_string(), |q| format!("{q:.3}"));
            let _ = writeln!(
                s,
                "  {:<26} {:<22} {:>7} RU {:>10.4} {:>10.4} {:>10}",
                r.method, r.against, r.exposure_ru, r.mean, r.p95, ratio
            );
        }
        let ext: Vec<String> = c
            .extension
            .iter()
            .map(|r| format!("{} RU: ΔE00 mean {:.4}, p95 {:.4}", r.exposure_ru, r.mean, r.p95))
            .collect();
        let _ = writeln!(
            s,
            "periodic-extension error (ground-truth-periodic vs ground-truth, finite aperture): {}",
            ext.join("; ")
        );
        if let Some(first) = c.rows.first() {
            let _ = writeln!(
                s,
                "ratio: a row's mean over the first method's ({}) at the same exposure (the paper's Table 2, E2/E1)",
                first.method
            );
        }
        s
    }
}

// ---------------------------------------------------------------------------------------------------------
// sweep

/// The u-v grid of a sweep's lookup tables where the grid is neither swept nor given: 201², not a table's
/// default 501², as a sweep builds a table for every value.
pub const SWEEP_UV_GRID: TableParams = TableParams { uv_resolution: 201, uv_power: 5.0 };

/// What `iridis sweep` asks of [`sweep_run`].
#[derive(Debug, Clone)]
pub struct SweepRequest {
    pub method: Method,
    pub param: Param,
    /// The values swept (lengths in nm).
    pub values: Vec<f64>,
    /// model, ground-truth or ground-truth-periodic.
    pub against: String,
    pub exposures: Vec<f64>,
    pub incidence: (f64, f64),
    pub size: usize,
    /// The wavelength step where it is not swept; `None`: the default spectral setup's (5 nm).
    pub dlambda_nm: Option<f64>,
    /// The u-v grid of the lookup method's tables where it is not swept ([`SWEEP_UV_GRID`] where not given).
    pub table: TableGrid,
    pub gpu: bool,
    /// The contact sheet (PNG).
    pub output: PathBuf,
    /// The error-against-parameter plot; default the sheet's name with `_error`.
    pub plot: Option<PathBuf>,
}

/// `--values` of a sweep of `param`: lengths with units for Δλ and coherence, numbers otherwise.
pub fn parse_sweep_values(param: Param, s: &str) -> Result<Vec<f64>> {
    parse_list(s, "--values", |s| match param {
        Param::DLambda | Param::Coherence => parse_length_nm(s).map_err(|e| anyhow::anyhow!("--values: {e}")),
        _ => s.parse::<f64>().map_err(|_| anyhow::anyhow!("--values: '{s}' is not a number")),
    })
}

/// A sweep with what the command prints.
#[derive(Debug)]
pub struct SweepRun {
    pub surface: String,
    pub method: Method,
    pub against: Method,
    pub param: Param,
    pub points: Vec<Point>,
    /// The contact sheet and the error plot written.
    pub files: (PathBuf, PathBuf),
    /// The model's settings the sweep held while it varied `param` (the swept one's entry is its first value).
    pub held: Held,
}

/// What a sweep held fixed, resolved (`auto` terms counted, defaults filled in).
#[derive(Debug, Clone, PartialEq)]
pub struct Held {
    pub coherence_nm: f64,
    pub taylor_terms: usize,
    pub uv_resolution: usize,
    pub uv_power: f64,
    pub dlambda_nm: f64,
    pub illuminant: String,
    pub observer: String,
}

impl Held {
    fn of(b: &iridis_lab::Workbench) -> Result<Self> {
        let c = &b.config;
        Ok(Held {
            coherence_nm: c.coherence_nm,
            taylor_terms: c.term_count(&b.patch)?,
            uv_resolution: c.table.uv_resolution,
            uv_power: c.table.uv_power,
            dlambda_nm: c.spectral.step_nm,
            illuminant: c.spectral.illuminant.name().to_string(),
            observer: c.spectral.observer.name().to_string(),
        })
    }

    /// The line the text prints, without the swept parameter's entry.
    fn text(&self, param: Param) -> String {
        let mut parts = Vec::new();
        if param != Param::Coherence {
            parts.push(format!("coherence {:.1} µm", self.coherence_nm / 1000.0));
        }
        if param != Param::Terms {
            parts.push(format!("N = {} Taylor terms", self.taylor_terms));
        }
        if param != Param::UvResolution {
            parts.push(format!("u-v grid {}²", self.uv_resolution));
        }
        if param != Param::UvPower {
            parts.push(format!("u-v power {}", self.uv_power));
        }
        if param != Param::DLambda {
            parts.push(format!("Δλ {} nm", self.dlambda_nm));
        }
        parts.push(format!("{}, CIE {} observer", self.illuminant, self.observer));
        format!("held: {}", parts.join(", "))
    }

    fn to_json(&self) -> Value {
        json!({"coherence_nm": self.coherence_nm, "taylor_terms": self.taylor_terms,
               "uv_resolution": self.uv_resolution, "uv_power": self.uv_power, "dlambda_nm": self.dlambda_nm,
               "illuminant": self.illuminant, "observer": self.observer})
    }
}

/// A convergence sweep (paper sec. 7, Figures 14–17): the maps and errors per value, the contact sheet and the
/// error plot written.
pub fn sweep_run(source: &Source, lab: &LabOptions, req: &SweepRequest, report: &dyn Report) -> Result<SweepRun> {
    let (method, param) = (req.method, req.param);
    if !param.applies_to(method) {
        let who: Vec<&str> = Method::ALL.iter().filter(|m| param.applies_to(**m)).map(|m| m.name()).collect();
        bail!("the {method} method has no parameter '{}'; it applies to: {}", param.name(), who.join(", "));
    }
    iridis_lab::sweep::check_values(param, &req.values)?;
    refuse_repeats("--values", &req.values)?;
    refuse_repeats("--exposures", &req.exposures)?;
    req.table.refuse_unless_lookup(method.name())?;
    lab.refuse_unused(&[method], false)?;
    // The parameter swept given as an option too: each value of --values would replace it.
    let swept_and_given = match param {
        Param::UvResolution => req.table.uv_resolution.map(|v| format!("--uv-resolution {v}")),
        Param::UvPower => req.table.uv_power.map(|p| format!("--uv-power {p}")),
        Param::DLambda => req.dlambda_nm.map(|d| format!("--dlambda {d}nm")),
        Param::Coherence => lab.coherence_nm.map(|c| format!("--coherence {c}nm")),
        Param::Terms => (lab.terms.trim() != "auto").then(|| format!("--terms {}", lab.terms.trim())),
    };
    if let Some(flag) = swept_and_given {
        bail!("{flag} would be ignored: {} is the parameter swept, its values come from --values", param.name());
    }
    let against = match req.against.trim().to_ascii_lowercase().as_str() {
        "model" | "own" => method.model_truth(),
        other => match other.parse::<Method>() {
            Ok(m) if m.is_ground_truth() => m,
            _ => bail!("--against '{}': expected model, ground-truth or ground-truth-periodic", req.against),
        },
    };
    if req.exposures.is_empty() {
        bail!("--exposures: give at least one value");
    }
    if !(8..=1024).contains(&req.size) {
        bail!("--size {} must be 8–1024 pixels", req.size);
    }
    crate::output::declare("-o", &req.output, &["png"])?;
    let plot_path = req.plot.clone().unwrap_or_else(|| {
        let stem = req.output.file_stem().and_then(|s| s.to_str()).unwrap_or("sweep");
        req.output.with_file_name(format!("{stem}_error.png"))
    });
    crate::output::declare("--plot", &plot_path, &["png"])?;
    let mut config = lab.config()?;
    let dlambda_nm = req.dlambda_nm.unwrap_or(SpectralSetup::default().step_nm);
    config.spectral = spectral("d65", dlambda_nm, report)?;
    config.table = req.table.params_or(SWEEP_UV_GRID)?;
    config.accelerator = crate::lab::gpu_accelerator(req.gpu, report)?;
    let from = if param == Param::Coherence { CoherenceFrom::Swept(&req.values) } else { CoherenceFrom::Options };
    let b = workbench_with(source, lab, config, from, report)?;
    let held = Held::of(&b)?;
    let pixels = Pixels::brdf_map(req.incidence.0, req.incidence.1, req.size);
    let (_, points) = with_progress(report, req.values.len() as u64, &format!("sweep {}", param.name()), |p| {
        iridis_lab::sweep::run(&b, method, param, &req.values, &pixels, &req.exposures, against, p)
    })?;
    for (k, &e) in req.exposures.iter().enumerate() {
        // The truth changes with the value only where coherence is swept: its most clipped value speaks.
        let (share, value) =
            points.iter().map(|p| (p.truth_clipped[k], p.value)).fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        let what = match param {
            Param::Coherence => format!("the {against} image at coherence {}", param.display(value)),
            _ => format!("the {against} image"),
        };
        if let Some(w) = iridis_lab::compare::clipping_warning(share, &what, e) {
            report.warn(&w);
        }
    }
    let sheet = iridis_lab::sweep::contact_sheet(param, method, &points, &pixels, req.exposures[0])?;
    let plot = iridis_lab::sweep::error_plot(param, method, &points)?;
    write_png_rgb8(&req.output, sheet.width, sheet.height, &sheet.data)?;
    write_png_rgb8(&plot_path, plot.width, plot.height, &plot.data)?;
    report.info(&format!("wrote {} and {}", req.output.display(), plot_path.display()));
    Ok(SweepRun {
        surface: source.name().to_string(),
        method,
        against,
        param,
        points,
        files: (req.output.clone(), plot_path),
        held,
    })
}

impl SweepRun {
    /// As `iridis sweep --json` prints it (keys in docs/json.md).
    pub fn to_json(&self) -> Value {
        let e3 = |v: &[(f64, f64, f64)]| {
            v.iter().map(|e| json!({"exposure_ru": e.0, "mean": e.1, "p95": e.2})).collect::<Vec<_>>()
        };
        let pts: Vec<_> = self
            .points
            .iter()
            .map(|p| json!({"value": p.value, "errors": e3(&p.errors), "periodic_extension_error": e3(&p.extension)}))
            .collect();
        json!({"surface": self.surface, "method": self.method.name(), "against": self.against.name(),
            "param": self.param.name(), "value_unit": self.param.value_unit(), "error": "CIEDE2000 (ΔE00)",
            "points": pts, "held": self.held.to_json()})
    }

    /// The table `iridis sweep` prints.
    pub fn text(&self) -> String {
        let (param, points) = (self.param, &self.points);
        let mut s = String::new();
        let _ = writeln!(s, "{} against {}, sweeping {}:", self.method, self.against.name(), param.name());
        let _ = writeln!(s, "  {}", self.held.text(param));
        let line = |v: &[(f64, f64, f64)]| {
            v.iter().map(|e| format!("{} RU: ΔE00 mean {:.4}, p95 {:.4}", e.0, e.1, e.2)).collect::<Vec<_>>().join("; ")
        };
        for p in points {
            let _ = writeln!(s, "  {:>12}   {}", param.display(p.value), line(&p.errors));
        }
        let ext = "periodic-extension error (ground-truth-periodic vs ground-truth, finite aperture)";
        if param == Param::Coherence {
            let _ = writeln!(s, "{ext}:");
            for p in points {
                let _ = writeln!(s, "  {:>12}   {}", param.display(p.value), line(&p.extension));
            }
        } else if let Some(p) = points.first() {
            let _ = writeln!(s, "{ext}: {}", line(&p.extension));
        }
        s
    }
}

// ---------------------------------------------------------------------------------------------------------
// experiment laser

/// What `iridis experiment laser` asks of [`laser_run`].
#[derive(Debug, Clone)]
pub struct LaserRequest {
    pub method: Method,
    pub setup: LaserSetup,
    /// Diaphragm aperture: the window's coherence length (nm).
    pub aperture_nm: f64,
    /// The beam's spectrum (CSV: wavelength_nm, power); equal energy without one.
    pub spectrum: Option<PathBuf>,
    /// gold, none, or an n,k file.
    pub coating: String,
    pub exposures: Vec<f64>,
    pub dlambda_nm: f64,
    /// The u-v grid of the lookup table built for the beam (refused without `--method lookup`).
    pub table: TableGrid,
    /// The output image (PNG); `NAME_<E>RU.png` per exposure when there are several.
    pub output: PathBuf,
    /// A lookup table made for this surface, aperture and beam.
    pub table_path: Option<PathBuf>,
    /// Write the lookup table built for this beam here.
    pub save_table: Option<PathBuf>,
}

/// The laser experiment's result.
#[derive(Debug)]
pub struct LaserRun {
    pub surface: String,
    pub method: Method,
    pub coating: String,
    /// The screens written, one per exposure.
    pub images: Vec<PathBuf>,
    /// The coated mirror's brightness relative to an uncoated one.
    pub scale: f64,
    /// The brightest pixel's Y.
    pub max_y: f64,
    /// The geometry: the beam's incidence, the sample's azimuth, the screen, its pixels.
    pub setup: LaserSetup,
    /// The screen image (XYZ, row-major, `width_px × height_px`).
    pub image: Vec<Option<Xyz>>,
    /// How far apart the screen's view samples are against the light's lobes ([`ScreenSampling`]).
    pub sampling: ScreenSampling,
    /// The diaphragm's aperture (nm) and the beam's spectrum in words.
    pub aperture_nm: f64,
    pub beam: String,
}

/// The laser screen's view samples against the width of the light's lobes ([`screen_misses_lobes`]): in
/// `iridis experiment laser --json` as `sampling`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScreenSampling {
    /// The angle between neighbouring view samples at the screen's centre ([`LaserSetup::sample_spacing_rad`]).
    pub spacing_rad: f64,
    /// The coherence length behind the lobes' width ([`crate::brdf::lobe_coherence_nm`]); `None` for a method
    /// without a coherence window.
    pub coherence_nm: Option<f64>,
    /// σ of the narrowest lobe (380 nm), radians ([`iridis_diffraction::spectral::lobe_sigma_uv`]).
    pub lobe_sigma_rad: Option<f64>,
    /// How many times closer the samples must be to sample every lobe; `None` where they do
    /// ([`crate::brdf::lobe_shortfall`]).
    pub finer_by: Option<f64>,
}

impl ScreenSampling {
    pub fn of(setup: &LaserSetup, coherence_nm: Option<f64>) -> Self {
        let spacing_rad = setup.sample_spacing_rad();
        ScreenSampling {
            spacing_rad,
            coherence_nm,
            lobe_sigma_rad: coherence_nm.map(|c| iridis_diffraction::spectral::lobe_sigma_uv(380.0, c)),
            finer_by: coherence_nm.and_then(|c| crate::brdf::lobe_shortfall(spacing_rad, c)).map(|s| s.finer_by),
        }
    }

    /// The warning where the samples miss lobes ([`crate::brdf::lobe_shortfall`], with the view samples' angular
    /// spacing, [`LaserSetup::sample_spacing_rad`]): it names the `--subsamples` (and `--size`) that sample every
    /// lobe; `None` where they do.
    pub fn warning(&self, setup: &LaserSetup) -> Option<String> {
        use iridis_lab::laser::{MAX_SIDE_PX, MAX_SUBSAMPLES};
        let (finer_by, sigma, coherence_nm) = (self.finer_by?, self.lobe_sigma_rad?, self.coherence_nm?);
        // Samples a pixel side the screen needs; past the most a pixel takes, that many on more pixels.
        let per_pixel = setup.subsamples as f64 * finer_by;
        let pixels = (setup.width_px.max(setup.height_px) as f64 * per_pixel / MAX_SUBSAMPLES as f64).ceil();
        let remedy = if per_pixel <= MAX_SUBSAMPLES as f64 {
            format!("--subsamples {:.0} or more samples every lobe", per_pixel.ceil())
        } else if pixels <= MAX_SIDE_PX as f64 {
            format!("--subsamples {MAX_SUBSAMPLES} with --size {pixels:.0} or more samples every lobe")
        } else {
            "a smaller --aperture widens them".to_string()
        };
        Some(format!(
            "the screen's view samples are {:.2} mrad apart at its centre and this light's lobes {:.2} mrad wide (σ \
             of the window's |G|² at 380 nm, aperture {:.1} µm): a spot narrower than the samples' spacing can fall \
             between them and vanish from the image, or show at its peak; {remedy}",
            self.spacing_rad * 1e3,
            sigma * 1e3,
            coherence_nm / 1000.0
        ))
    }

    /// `sampling` of `iridis experiment laser --json` (keys in docs/json.md).
    pub fn to_json(&self) -> Value {
        json!({"view_spacing_mrad": self.spacing_rad * 1e3, "lobe_sigma_mrad": self.lobe_sigma_rad.map(|s| s * 1e3),
               "lobe_coherence_um": self.coherence_nm.map(|c| c / 1000.0),
               "samples_per_lobe_sigma": crate::brdf::SAMPLES_PER_LOBE_SIGMA, "finer_by": self.finer_by})
    }
}

/// The laser experiment of the paper's Figure 8: the screen image a camera records, one PNG per exposure.
pub fn laser_run(source: &Source, lab: &LabOptions, req: &LaserRequest, report: &dyn Report) -> Result<LaserRun> {
    let (method, exps) = (req.method, &req.exposures);
    if exps.is_empty() {
        bail!("--exposures: give at least one value");
    }
    refuse_repeats("--exposures", exps)?;
    // Named by the option given: the aperture is the window's coherence length, whose own check named neither.
    if !(req.aperture_nm.is_finite() && req.aperture_nm > 0.0) {
        bail!("--aperture {} nm: the diaphragm's aperture must be a positive length", req.aperture_nm);
    }
    let screens: Vec<PathBuf> = exps
        .iter()
        .map(|x| {
            if exps.len() == 1 {
                req.output.clone()
            } else {
                let stem = req.output.file_stem().and_then(|s| s.to_str()).unwrap_or("screen");
                req.output.with_file_name(format!("{stem}_{x}RU.png"))
            }
        })
        .collect();
    crate::output::format_of("-o", &req.output, &["png"])?;
    for p in &screens {
        crate::output::declare("-o", p, &["png"])?;
    }
    if (req.table_path.is_some() || req.save_table.is_some()) && method != Method::Lookup {
        bail!("--table and --save-table are lookup tables: use them with --method lookup, not {method}");
    }
    req.table.refuse_unless_lookup(method.name())?;
    lab.refuse_unused(&[method], false)?;
    if let Some(c) = lab.coherence_nm {
        bail!(
            "--coherence {len} would be ignored: the laser experiment's coherence window is the diaphragm's \
             aperture; give --aperture {len}",
            len = iridis_color::units::format_length(c)
        );
    }
    if req.table_path.is_some() && req.save_table.is_some() {
        bail!("--table reuses a table and --save-table writes the one built here: give one of them");
    }
    crate::output::declare_opt("--save-table", req.save_table.as_deref(), &["npz"])?;
    let spectrum = crate::lab::beam_spectrum(req.spectrum.as_deref(), report)?;
    let coating = crate::lab::coating(&req.coating)?;
    if coating.is_some() && lab.fresnel.trim() != crate::fresnel::DEFAULT_FRESNEL {
        bail!(
            "--fresnel {} would be ignored: the coating ({}) is the Fresnel term; --coating none takes --fresnel",
            lab.fresnel.trim(),
            req.coating
        );
    }
    let setup = &req.setup;
    let pixels = setup.pixels()?;
    let mut model = lab.clone();
    model.coherence_nm = Some(req.aperture_nm);
    let mut config = model.config()?;
    config.spectral = spectral("e", req.dlambda_nm, report)?;
    let scale = iridis_lab::laser::configure(&mut config, method, &spectrum, coating.as_ref(), Observer::Cie1931)?;
    config.table = req.table.params()?;
    config.table_path = req.table_path.clone();
    let b = workbench_with(source, &model, config, CoherenceFrom::Aperture(req.aperture_nm), report)?;
    let e = evaluator(&b, method, report)?;
    let sampling = ScreenSampling::of(setup, crate::brdf::lobe_coherence_nm(e.as_ref()));
    if let Some(w) = sampling.warning(setup) {
        report.warn(&w);
    }
    if let (Some(path), Some(lookup)) = (&req.save_table, e.as_lookup()) {
        crate::output::write_atomic(path, |w| Ok(lookup.table.write_npz(w)?))?;
        report.info(&format!("wrote {}", path.display()));
    }
    let mut img = render_pixels(e.as_ref(), &pixels, "screen", report);
    iridis_lab::laser::scale_image(&mut img, scale);
    let size = setup.width_px;
    let screen = setup.screen_width_nm;
    let half = screen / 2e6;
    let mut written = Vec::new();
    for (&x, path) in exps.iter().zip(screens) {
        let px = iridis_lab::image::to_rgb(&img, size, setup.height_px, x);
        let plot = iridis_plot::ImagePlot {
            title: format!(
                "{}: screen at {:.0} mm, beam {:.0}°, aperture {:.0} µm, {x} RU",
                short_name(source.name()),
                setup.distance_nm / 1e6,
                setup.incidence.to_degrees(),
                req.aperture_nm / 1000.0
            ),
            x_label: "along the beam (mm)".into(),
            y_label: "height (mm)".into(),
            x_range: (-half, half),
            y_range: (-half, half),
            pixels: &px,
            overlays: Vec::new(),
            colorbar: None,
            size: (720, 700),
        }
        .render()?;
        write_png_rgb8(&path, plot.width, plot.height, &plot.data)?;
        report.info(&format!("wrote {}", path.display()));
        written.push(path);
    }
    let max_y = img.iter().flatten().map(|x| x.y).fold(0.0, f64::max);
    Ok(LaserRun {
        surface: source.name().to_string(),
        method,
        coating: req.coating.clone(),
        images: written,
        scale,
        max_y,
        setup: setup.clone(),
        image: img,
        sampling,
        aperture_nm: req.aperture_nm,
        beam: match &req.spectrum {
            Some(p) => format!("{} (wavelength_nm, power)", p.display()),
            None => "equal energy (no --spectrum)".into(),
        },
    })
}

/// What the laser screen's samples miss at this coherence length (the aperture), if anything: as
/// `brdf_map::lobes_between_pixels` for a map ([`ScreenSampling`]).
pub fn screen_misses_lobes(setup: &LaserSetup, coherence_nm: f64) -> Option<String> {
    ScreenSampling::of(setup, Some(coherence_nm)).warning(setup)
}

impl LaserRun {
    /// As `iridis experiment laser --json` prints it (keys in docs/json.md).
    pub fn to_json(&self) -> Value {
        json!({"surface": self.surface, "method": self.method.name(), "images": self.images,
            "coating": self.coating, "gold_mirror_relative_brightness": self.scale, "max_y": self.max_y,
            "pixels": self.setup.width_px, "screen_mm": self.setup.screen_width_nm / 1e6,
            "distance_mm": self.setup.distance_nm / 1e6, "sampling": self.sampling.to_json(),
            "incidence_deg": self.setup.incidence.to_degrees(), "azimuth_deg": self.setup.azimuth.to_degrees(),
            "aperture_um": self.aperture_nm / 1000.0,
            "beam_spectrum": self.beam})
    }

    /// The line `iridis experiment laser` prints.
    pub fn text(&self) -> String {
        let (peak, scale) = (self.max_y, self.scale);
        format!(
            "{} method, coating {}; beam at {:.1}° (sample azimuth {:.1}°), aperture {:.1} µm, spectrum {}\n{}² \
             pixels, brightest Y = {peak:.4e} at 1 RU (saturates at {:.3e} RU; at 1 RU an uncoated perfect \
             mirror's spot just saturates); coated mirror brightness {scale:.3} of an uncoated one\n",
            self.method.name(),
            self.coating,
            self.setup.incidence.to_degrees(),
            self.setup.azimuth.to_degrees(),
            self.aperture_nm / 1000.0,
            self.beam,
            self.setup.width_px,
            1.0 / peak.max(1e-300)
        )
    }
}

// ---------------------------------------------------------------------------------------------------------
// demo

/// The demo's lab section: test-bench plots and Table-1-style numbers for the built-in blazed grating and
/// Elaphe-like surface, and a Table-2-style comparison on a small Elaphe-like patch.
pub fn demo_section(g: &mut crate::gallery::Gallery) -> Result<()> {
    let quiet = &crate::report::Quiet;
    g.section(
        "Virtual lab: test bench and method comparison (paper sec. 6.1 and 6.3)",
        "The test bench shines light at θi = 75° and records the reflectance over viewing angle θr for each \
         wavelength; the peak of the first order gives a period through the grating equation \
         m λ / d = sin θi − sin θr (Table 1 of the paper: blazed grating 2500.34 nm, Elaphe 1144.28 nm). \
         Below: the built-in blazed grating and Elaphe-like surface (small patches so the demo stays quick), \
         then CIEDE2000 errors of several methods against the ground truth (Table 2).",
    );
    let model = LabOptions { coherence_nm: Some(65_000.0), ..LabOptions::default() };
    let mut rows = Vec::new();
    let cases = [
        ("builtin:blazed?size=20um&pixel=50nm", 0.0f64, 65_000.0, "blazed grating (2500 nm)", "bench_blazed.png"),
        (
            "builtin:elaphe?size=20um&pixel=50nm",
            90.0,
            8_000.0,
            "Elaphe-like (1100 nm rows, along y)",
            "bench_elaphe.png",
        ),
    ];
    for (spec, az, coherence, label, file) in cases {
        let mut m = model.clone();
        m.coherence_nm = Some(coherence);
        let b = workbench(spec, &m, m.config()?, quiet)?;
        let e = evaluator(&b, Method::Reference, quiet)?;
        let setup = BenchSetup::new(75f64.to_radians(), az.to_radians(), 1, (380.0, 780.0, 10.0), (-60.0, 74.0, 0.05))?;
        let matrix = bench::reflectance_matrix(e.as_ref(), &setup, &|_| {})?;
        let r = bench::analyse(&matrix, &setup)?.on_patch(b.patch.extent_along(setup.azimuth), b.config.coherence_nm);
        let img = bench::plot(&matrix, &setup, &r, r.periodicity.mean, &format!("{label}: test bench, θi = 75°"))?;
        write_png_rgb8(&g.path(file), img.width, img.height, &img.data)?;
        g.image(
            file,
            &format!(
                "{label}: reflectance over viewing angle and wavelength, peak curve and grating equation \
                 (iridis testbench '{spec}' --azimuth {az}deg --coherence {}um --plot {file})",
                coherence / 1000.0
            ),
        );
        let hf = iridis_surface::load_surface(spec, &iridis_surface::LoadOptions::default())?;
        let analysis = iridis_surface::find_peaks(&hf, &iridis_surface::PeakOptions::default());
        let geometric =
            analysis.first().map(|p| format!("{:.1} nm at {:.0}°", p.period_nm, p.orientation_deg)).unwrap_or_default();
        rows.push(vec![
            label.to_string(),
            format!("{:.2}", r.periodicity.mean),
            format!("{:.3}", r.periodicity.variance),
            format!("{}/{}", r.peaks.len(), setup.wavelengths_nm.len()),
            geometric,
        ]);
    }
    g.table(
        &[
            "surface",
            "estimated period (nm)",
            "variance (nm²)",
            "wavelengths with a peak",
            "surface analysis (strongest period)",
        ],
        &rows,
    );
    // Table 2 in kind: a small Elaphe-like patch, 48 × 48 map at normal incidence.
    let spec = "builtin:elaphe?size=6um&pixel=60nm";
    let mut m = model.clone();
    m.coherence_nm = Some(3_000.0);
    let mut config = m.config()?;
    config.spectral = SpectralSetup::new(Illuminant::D65, Observer::Cie1931, 5.0)?;
    config.table = TableParams { uv_resolution: 201, uv_power: 5.0 };
    let b = workbench(spec, &m, config, quiet)?;
    let pixels = Pixels::brdf_map(0.0, 0.0, 48);
    let methods = [
        Method::Lookup,
        Method::Reference,
        Method::StamPeriodic(iridis_lab::stam::Bump::Rectangular),
        Method::StamGaussian,
    ];
    let c = comparison(&b, &methods, None, &pixels, &[1.0, 1000.0, 7500.0], quiet)?;
    let mut t = Vec::new();
    for r in &c.rows {
        let ours = c
            .rows
            .iter()
            .find(|x| x.method == "lookup" && x.exposure_ru == r.exposure_ru)
            .map(|x| x.mean)
            .unwrap_or(f64::NAN);
        t.push(vec![
            r.method.clone(),
            format!("{}", r.exposure_ru),
            format!("{:.3}", r.mean),
            format!("{:.3}", r.p95),
            format!("{:.2}", r.mean / ours),
        ]);
    }
    for r in &c.extension {
        t.push(vec![
            "periodic vs finite-aperture ground truth".into(),
            format!("{}", r.exposure_ru),
            format!("{:.3}", r.mean),
            format!("{:.3}", r.p95),
            String::new(),
        ]);
    }
    let truth = c.truth(Method::GroundTruthPeriodic);
    let img = map_plot(truth, 48, 1000.0, "ground truth (periodic extension) at 1000 RU")?;
    write_png_rgb8(&g.path("compare_truth.png"), img.width, img.height, &img.data)?;
    g.image(
        "compare_truth.png",
        &format!("{spec}: ground truth (the patch's periodic extension) BRDF map at normal incidence, 1000 RU"),
    );
    for (name, im) in &c.images {
        let de = iridis_lab::compare::delta_e_map(im, truth, 1000.0);
        let s = iridis_lab::compare::stats(&de);
        let h = heat_plot(&de, 48, &format!("ΔE00 {name} vs ground truth, 1000 RU"), s.max.max(1.0))?;
        let file = format!("compare_{name}_deltaE.png");
        write_png_rgb8(&g.path(&file), h.width, h.height, &h.data)?;
        g.image(&file, &format!("CIEDE2000 of {name} against the ground truth at 1000 RU (mean {:.2})", s.mean));
    }
    g.table(&["method", "exposure (RU)", "mean ΔE00", "95th percentile", "ratio to lookup (Table 2: E2/E1)"], &t);
    Ok(())
}
