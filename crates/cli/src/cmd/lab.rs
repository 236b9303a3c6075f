//! `iridis testbench`, `iridis compare`, `iridis sweep`, `iridis experiment laser`: the virtual lab of issue 6
//! (paper sec. 6–7, thesis ch. 5) over `iridis-lab`.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::{Args as ClapArgs, Subcommand};
use iridis_api::lab::{comparison, evaluator, render_pixels, spectral, workbench, LabOptions};
use iridis_api::SurfaceOptions;
use iridis_color::units::parse_length_nm;
use iridis_color::{Illuminant, Observer, Xyz};
use iridis_diffraction::geometry::FresnelConvention;
use iridis_diffraction::table::TableParams;
use iridis_diffraction::SpectralSetup;
use iridis_lab::bench::{self, BenchSetup};
use iridis_lab::image::Pixels;
use iridis_lab::laser::LaserSetup;
use iridis_lab::methods::Method;
use iridis_lab::sweep::Param;
use serde_json::json;

use crate::args::{angle_rad, positive_length_nm};
use crate::output::{print_json, write_png_rgb8};
use crate::progress::{bar, Cli};

/// How to read SURFACE and the model's parameters, shared by the lab commands.
#[derive(Debug, Clone, ClapArgs)]
pub struct LabModel {
    /// Pixel size for image surfaces without physical units (e.g. 65nm).
    #[arg(long, value_parser = positive_length_nm)]
    pub pixel_size: Option<f64>,
    /// Height of full white for image surfaces (e.g. 300nm).
    #[arg(long, value_parser = positive_length_nm)]
    pub max_height: Option<f64>,
    /// Channel of a multi-channel file, by index or name (`iridis surface channels FILE` lists them).
    #[arg(long)]
    pub channel: Option<iridis_surface::formats::channel::ChannelSel>,
    /// Unit of heights in files that do not give one (.npy, text), e.g. m or nm.
    #[arg(long)]
    pub height_unit: Option<String>,
    /// Levelling before the model: plane (default for files), poly, lines, rows, mean or none (built-ins are
    /// used as generated unless this is given).
    #[arg(long)]
    pub level: Option<String>,
    #[command(flatten)]
    pub units: crate::args::UnitFlags,
    /// Coherence length 4σ_s of the window, a property of the light (default 65um, the paper's; a smaller
    /// patch is taken as one unit cell of a periodic surface; said in the output).
    #[arg(long, value_parser = positive_length_nm)]
    pub coherence: Option<f64>,
    /// Taylor terms: auto (remainder bound 1e-6) or N.
    #[arg(long, default_value = "auto")]
    pub terms: String,
    /// Fresnel factor: schlick[:N] (default schlick:1.5), index:N[+Ki], gold (measured) or a thin-film stack,
    /// e.g. "stack:air | keratin 300nm | n=1.56" (as brdf-map's --fresnel).
    #[arg(long, default_value = "schlick:1.5")]
    pub fresnel: String,
    /// How the Fresnel reflectance enters: physical (R once, the default) or paper (R², the paper's formula as
    /// printed, to reproduce its figures; docs/PHYSICS.md).
    #[arg(long, value_name = "physical|paper", default_value = "physical", value_parser = crate::cmd::brdf::fresnel_convention)]
    pub fresnel_convention: FresnelConvention,
    /// Leave out the Cook–Torrance shadowing term.
    #[arg(long)]
    pub no_shadowing: bool,
    /// ε of Stam's wavelength selection (paper: 0.01).
    #[arg(long, default_value_t = 0.01)]
    pub epsilon: f64,
}

impl LabModel {
    /// The facade's lab options.
    pub fn options(&self) -> LabOptions {
        LabOptions {
            surface: SurfaceOptions {
                pixel_size_nm: self.pixel_size,
                max_height_nm: self.max_height,
                channel: self.channel.clone(),
                height_unit: self.height_unit.clone(),
                level: self.level.clone(),
                override_units: self.units.override_units,
                as_height: self.units.as_height,
            },
            coherence_nm: self.coherence,
            terms: self.terms.clone(),
            fresnel: self.fresnel.clone(),
            convention: self.fresnel_convention,
            shadowing: !self.no_shadowing,
            stam_epsilon: self.epsilon,
        }
    }
}

/// A surface name short enough for a plot title.
fn short(spec: &str) -> String {
    let s = spec.strip_prefix("builtin:").unwrap_or(spec);
    let s = std::path::Path::new(s).file_name().and_then(|f| f.to_str()).unwrap_or(s);
    if s.chars().count() > 28 {
        format!("{}…", s.chars().take(27).collect::<String>())
    } else {
        s.to_string()
    }
}

fn parse_list<T>(s: &str, what: &str, f: impl Fn(&str) -> Result<T>) -> Result<Vec<T>> {
    let v: Vec<T> = s.split(',').filter(|p| !p.trim().is_empty()).map(|p| f(p.trim())).collect::<Result<_>>()?;
    if v.is_empty() {
        bail!("{what}: give at least one value");
    }
    Ok(v)
}

fn exposures(s: &str) -> Result<Vec<f64>> {
    parse_list(s, "--exposures", |p| match p.trim_end_matches("RU").trim_end_matches("ru").parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => bail!("--exposures: '{p}' is not a positive exposure in RU (e.g. 1,1000,7500)"),
    })
}

// ---------------------------------------------------------------------------------------------------------
// testbench

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
The virtual test bench (paper sec. 6.1, Table 1, Figure 7; thesis ch. 5): light in the x-z plane at θ_i, the
viewer in the same plane at signed θ_r (positive on the specular side). For each wavelength the reflectance
over θ_r is computed (thesis eq. 5.5), the peak viewing angle of the chosen order found, and the periodicity
d_λ = m λ / (sin θ_i − sin θ_r) (eq. 5.6 in this frame) reported with its mean and variance over λ, and its
uncertainty: half a DFT step d²/(2L) when the patch is smaller than the coherence window (L its extent along
the direction; the patch is then one unit cell of a periodic surface), else the window's resolution.
--azimuth rotates the surface about its normal: 0deg measures periods along x, 90deg along y; without it the
bench measures along the orientation of the surface's strongest period (what `iridis surface info` finds).
Without --period the strongest response away from the mirror direction is taken as the first order.

JSON: {\"periodicity_nm\": {\"mean\", \"variance\", \"relative_spread\", \"definite\"}, \"order\",
\"incidence_deg\", \"azimuth_deg\", \"peaks\": [{\"wavelength_nm\", \"angle_deg\", \"period_nm\"}],
\"ridges\": [{\"period_nm\", \"variance\", …}]}
(ridges lists competing sub-structure periods when there is more than one, as for Xenopeltis; definite is
false, with a warning, when d_λ spreads by more than 1 % of its mean: the direction has no period, as along
the Elaphe-like fingers.)

Examples:
  iridis testbench builtin:blazed --plot blazed_bench.png
  iridis testbench 'builtin:elaphe?size=20um&pixel=50nm' --azimuth 90deg --coherence 10um --json
  iridis testbench builtin:elaphe --azimuth 0deg   # along the fingers: no definite period (a warning)
  iridis testbench 'builtin:xenopeltis?size=20um&pixel=50nm' --azimuth 90deg --coherence 10um --plot x.png
  iridis testbench scan.gwy --method ground-truth --from 400nm --to 700nm --step 20nm --min-angle 20deg
  iridis testbench builtin:sine --method rigorous --unit-cell auto --step 20nm

--method rigorous: the unit cell (SURFACE as one period, or with --unit-cell auto the scan's dominant period
averaged along its ridges) with each order's lobe carrying Maxwell's efficiency (the C-method over
--material); the period is then the cell's, known to the SURFACE's resolution.")]
pub struct TestbenchArgs {
    /// Height field: a file (.gwy, .npy, PNG, TIFF, text) or builtin:NAME.
    pub surface: String,
    /// Method: reference (thesis FLSS), ground-truth (slow), nmm, pq, stam-periodic[-triangular], stam-gaussian,
    /// or rigorous (the unit cell's orders carrying Maxwell's efficiencies: --material, --unit-cell).
    #[arg(long, default_value = "reference")]
    pub method: String,
    #[command(flatten)]
    pub rigorous: crate::args::RigorousOpts,
    /// Angle of incidence θ_i.
    #[arg(long, value_parser = angle_rad, default_value = "75deg")]
    pub incidence: f64,
    /// Rotation of the surface about its normal: 0deg measures periods along x, 90deg along y [default: the
    /// orientation of the surface's strongest period, as `iridis surface info` finds it].
    #[arg(long, value_parser = angle_rad, allow_hyphen_values = true)]
    pub azimuth: Option<f64>,
    /// Diffraction order m (non-zero; m > 0 lies between the mirror direction and the normal).
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub order: i32,
    /// First wavelength.
    #[arg(long, value_parser = positive_length_nm, default_value = "380nm")]
    pub from: f64,
    /// Last wavelength.
    #[arg(long, value_parser = positive_length_nm, default_value = "780nm")]
    pub to: f64,
    /// Wavelength step.
    #[arg(long, value_parser = positive_length_nm, default_value = "5nm")]
    pub step: f64,
    /// Viewing-angle step.
    #[arg(long, value_parser = angle_rad, default_value = "0.05deg")]
    pub angle_step: f64,
    /// Smallest viewing angle.
    #[arg(long, value_parser = angle_rad, default_value = "-89deg", allow_hyphen_values = true)]
    pub min_angle: f64,
    /// Largest viewing angle.
    #[arg(long, value_parser = angle_rad, default_value = "89deg", allow_hyphen_values = true)]
    pub max_angle: f64,
    /// Known period: centre the order's window on it and draw its grating-equation curve.
    #[arg(long, value_parser = positive_length_nm)]
    pub period: Option<f64>,
    /// Longest period considered (responses closer to the mirror direction are ignored); default the smaller
    /// of 10 µm and 0.785 × coherence (the mirror lobe's 2σ_f).
    #[arg(long, value_parser = positive_length_nm)]
    pub max_period: Option<f64>,
    /// Write the Figure-7 plot (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub model: LabModel,
}

pub fn run_testbench(a: TestbenchArgs) -> Result<()> {
    let rigorous = a.method == iridis_api::brdf::RIGOROUS;
    let mut model = iridis_api::ModelOptions::default();
    let paper = a.model.fresnel_convention == FresnelConvention::Paper;
    a.rigorous.apply(&a.method, &a.model.fresnel, paper, &mut model)?;
    if !rigorous {
        if a.rigorous.material.is_some() || model.unit_cell_auto {
            bail!("--material and --unit-cell auto are the rigorous method's: add --method rigorous");
        }
        iridis_api::lab::check_spectral(a.method.parse::<Method>()?)?;
    }
    crate::output::declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    let mut setup = BenchSetup::new(
        a.incidence,
        a.azimuth.unwrap_or(0.0),
        a.order,
        (a.from, a.to, a.step),
        (a.min_angle.to_degrees(), a.max_angle.to_degrees(), a.angle_step.to_degrees()),
    )?;
    setup.period_hint_nm = a.period;
    let source = iridis_api::surface::Source::Spec(a.surface.clone());
    let along_dominant = a.azimuth.is_none();
    let lab = a.model.options();
    let t = if rigorous {
        iridis_api::lab::testbench_rigorous(&source, &lab, &model, setup, along_dominant, a.max_period, &Cli)?
    } else {
        let m: Method = a.method.parse()?;
        iridis_api::lab::testbench(&source, &lab, m, setup, along_dominant, a.max_period, &Cli)?
    };
    let method = a.method.as_str();
    if let Some(r) = &t.rigorous {
        eprintln!("note: {}", r.sentence());
    }
    let extent_nm = t.extent_nm;
    let rigorous_json = t.rigorous.as_ref().map(|r| r.to_json());
    let (b, setup, matrix, result) = (t.workbench, t.setup, t.matrix, t.result);
    let curve = a.period.unwrap_or(result.periodicity.mean);
    if let Some(path) = &a.plot {
        let name = short(&a.surface);
        let title = format!(
            "{name} ({method}), θi {:.0}°, φ {:.0}°: d = {:.2} nm, var {:.3}",
            a.incidence.to_degrees(),
            setup.azimuth.to_degrees(),
            result.periodicity.mean,
            result.periodicity.variance
        );
        let img = bench::plot(&matrix, &setup, &result, curve, &title)?;
        write_png_rgb8(path, img.width, img.height, &img.data)?;
        eprintln!("wrote {}", path.display());
    }
    if a.json {
        let mut j = result.to_json();
        j["method"] = json!(method);
        j["surface"] = json!(a.surface);
        j["rigorous"] = rigorous_json.unwrap_or(serde_json::Value::Null);
        return print_json(&j);
    }
    crate::outln!(
        "{} with {}: order {}, θi = {:.2}°, azimuth {:.2}°, {} of {} wavelengths with a peak",
        a.surface,
        method,
        a.order,
        a.incidence.to_degrees(),
        setup.azimuth.to_degrees(),
        result.peaks.len(),
        setup.wavelengths_nm.len()
    )?;
    let extent_um = extent_nm / 1000.0;
    crate::outln!(
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
    )?;
    if result.ridges.len() > 1 {
        for (k, r) in result.ridges.iter().enumerate() {
            crate::outln!(
                "ridge {}      {:.2} nm, variance {:.3} nm², {} wavelengths, mean peak ρ {:.3e}",
                k + 1,
                r.period_nm,
                r.variance,
                r.wavelengths,
                r.strength
            )?;
        }
    }
    crate::outln!("  λ (nm)   θr (deg)   d_λ (nm)")?;
    let stride = (result.peaks.len() / 12).max(1);
    for p in result.peaks.iter().step_by(stride) {
        crate::outln!("  {:6.1}   {:8.3}   {:8.2}", p.wavelength_nm, p.angle_deg, p.period_nm)?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------------------
// compare

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
CIELAB errors between methods (paper sec. 6.3, Table 2): each method's BRDF map (light at --incidence, the
paper's layout: pixel (x, y) views (x, y, √(1 − x² − y²))) is displayed at each exposure (XYZ × E → linear
sRGB, clipped → CIELAB against the D65 white) and compared per pixel by CIEDE2000. The table gives mean and
95th percentile per method and exposure, and the ratio of each method's mean to the first method's (Table 2's
E2/E1).

Against what: by default (--against model) each method against the ground truth of the model it approximates:
the periodic extension of the patch (ground-truth-periodic) for all of them — reference, lookup, NMM and PQ use
the patch's DFT, which sees it repeated; Stam's models are fitted through its DFT (periodogram, circular
autocorrelation) and have no edge. --against ground-truth compares with the finite aperture instead (the
window cut at the patch edge), --against METHOD with any method. The periodic-extension error (periodic
against finite-aperture ground truth) is printed on its own line: where the window is as wide as the patch it
is the models' own difference, which no approximation of either can remove.

JSON: {\"results\": [{\"method\", \"against\", \"exposure_ru\", \"mean\", \"p95\", \"max\", \"ratio\"}],
\"periodic_extension_error\": [{\"exposure_ru\", \"mean\", \"p95\", \"max\"}], \"against\", …}

Examples:
  iridis compare 'builtin:elaphe?size=12um&pixel=60nm' --coherence 4um --size 64
  iridis compare 'builtin:elaphe?size=12um&pixel=60nm' --methods reference,stam-gaussian --json
  iridis compare 'builtin:elaphe?size=12um&pixel=60nm' --against ground-truth   # the finite aperture
  iridis precompute scan.gwy -o scan.npz && iridis compare scan.gwy --methods lookup,reference --table scan.npz --maps errors/
  iridis compare builtin:elaphe --methods lookup --gpu --json   # Table 2's size (101², 3 exposures) on the GPU

--gpu builds the lookup tables and renders both ground truths on the GPU (f32; ΔE00 against the CPU's f64
below 0.01, docs/gpu.md); the other methods stay on the CPU.")]
pub struct CompareArgs {
    /// Height field: a file or builtin:NAME.
    pub surface: String,
    /// Methods to compare, comma-separated: ground-truth, reference, lookup, nmm, pq, stam-periodic,
    /// stam-periodic-triangular, stam-gaussian.
    #[arg(long, default_value = "lookup,reference,stam-periodic,stam-gaussian")]
    pub methods: String,
    /// What each method is compared with: model (the ground truth of the method's own model, the periodic
    /// extension), ground-truth (the finite aperture), ground-truth-periodic, or any method.
    #[arg(long, default_value = "model")]
    pub against: String,
    /// Exposures in RU, comma-separated.
    #[arg(long, default_value = "1,1000,7500")]
    pub exposures: String,
    /// Light direction θ[,φ].
    #[arg(long, default_value = "0deg")]
    pub incidence: String,
    /// Map size in pixels (the paper: 101).
    #[arg(long, default_value_t = 101)]
    pub size: usize,
    /// Wavelength step of the spectral integral.
    #[arg(long, value_parser = positive_length_nm, default_value = "5nm")]
    pub dlambda: f64,
    /// Illuminant: d65, d50, a, e.
    #[arg(long, default_value = "d65")]
    pub illuminant: String,
    /// u-v samples per axis of the lookup table built in memory.
    #[arg(long, default_value_t = 501)]
    pub uv_resolution: usize,
    /// Exponent of the lookup table's u-v grid.
    #[arg(long, default_value_t = 5.0)]
    pub uv_power: f64,
    /// A precomputed lookup table (from `iridis precompute`) for the lookup method.
    #[arg(long)]
    pub table: Option<PathBuf>,
    /// Write the maps and ΔE heat maps into this folder.
    #[arg(long)]
    pub maps: Option<PathBuf>,
    /// Build the lookup tables and render the ground truths on the GPU (Vulkan; lavapipe without a GPU).
    #[arg(long)]
    pub gpu: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub model: LabModel,
}

fn heat_plot(map: &[Option<f64>], size: usize, title: &str, max: f64) -> Result<iridis_plot::RgbImage> {
    let px = iridis_lab::image::heat(map, size, size, max);
    Ok(iridis_plot::ImagePlot {
        title: title.into(),
        x_label: "x = sin θr cos φr".into(),
        y_label: "y = sin θr sin φr".into(),
        x_range: (-1.0, 1.0),
        y_range: (-1.0, 1.0),
        pixels: &px,
        overlays: Vec::new(),
        colorbar: Some(iridis_plot::ColorBar { label: "ΔE00".into(), min: 0.0, max, map: iridis_plot::magma }),
        size: (620, 520),
    }
    .render()?)
}

fn map_plot(img: &[Option<Xyz>], size: usize, exposure: f64, title: &str) -> Result<iridis_plot::RgbImage> {
    let px = iridis_lab::image::to_rgb(img, size, size, exposure);
    Ok(iridis_plot::ImagePlot {
        title: title.into(),
        x_label: "x = sin θr cos φr".into(),
        y_label: "y = sin θr sin φr".into(),
        x_range: (-1.0, 1.0),
        y_range: (-1.0, 1.0),
        pixels: &px,
        overlays: Vec::new(),
        colorbar: None,
        size: (520, 520),
    }
    .render()?)
}

pub fn run_compare(a: CompareArgs) -> Result<()> {
    let methods = parse_list(&a.methods, "--methods", |s| Ok(s.parse::<Method>()?))?;
    let against = iridis_api::lab::parse_against(&a.against)?;
    let exps = exposures(&a.exposures)?;
    let (theta, phi) = crate::args::polar_azimuth("incidence", &a.incidence)?;
    if !(8..=2048).contains(&a.size) {
        bail!("--size {} must be 8–2048 pixels", a.size);
    }
    if let Some(d) = &a.maps {
        std::fs::create_dir_all(d).with_context(|| format!("cannot create {}", d.display()))?;
    }
    let opts = a.model.options();
    let mut config = opts.config()?;
    config.spectral = spectral(&a.illuminant, a.dlambda, &Cli)?;
    config.table = TableParams { uv_resolution: a.uv_resolution, uv_power: a.uv_power };
    config.table_path = a.table.clone();
    config.accelerator = iridis_api::lab::gpu_accelerator(a.gpu, &Cli)?;
    let b = workbench(&a.surface, &opts, config, &Cli)?;
    let pixels = Pixels::brdf_map(theta, phi, a.size);
    let c = comparison(&b, &methods, against, &pixels, &exps, &Cli)?;
    if let Some(dir) = &a.maps {
        for &e in &exps {
            for (m, img) in &c.truths {
                let t = map_plot(img, a.size, e, &format!("{} at {e} RU", m.name()))?;
                write_png_rgb8(&dir.join(format!("{}_{e}RU.png", m.name())), t.width, t.height, &t.data)?;
            }
            for (name, img) in &c.images {
                let m = map_plot(img, a.size, e, &format!("{name} at {e} RU"))?;
                write_png_rgb8(&dir.join(format!("{name}_{e}RU.png",)), m.width, m.height, &m.data)?;
                let truth = name.parse::<Method>().map(|m| against.unwrap_or(m.model_truth()))?;
                let de = iridis_lab::compare::delta_e_map(img, c.truth(truth), e);
                let s = iridis_lab::compare::stats(&de);
                let h = heat_plot(
                    &de,
                    a.size,
                    &format!("ΔE00 {name} vs {} at {e} RU (mean {:.2})", truth.name(), s.mean),
                    s.max.max(1.0),
                )?;
                write_png_rgb8(&dir.join(format!("{name}_{e}RU_deltaE.png")), h.width, h.height, &h.data)?;
            }
        }
        eprintln!("wrote maps to {}", dir.display());
    }
    let first = |e: f64| c.first_mean(e);
    if a.json {
        let deg = iridis_color::units::degrees(theta);
        return print_json(&c.to_json(&a.surface, against, a.size, deg, b.config.coherence_nm));
    }
    crate::outln!(
        "CIEDE2000 against {} ({}×{} BRDF map, θi = {:.1}°):",
        match against {
            None => "the ground truth of each method's model".to_string(),
            Some(m) => m.name().to_string(),
        },
        a.size,
        a.size,
        theta.to_degrees()
    )?;
    crate::outln!(
        "  {:<26} {:<22} {:>10} {:>10} {:>10} {:>10}",
        "method",
        "against",
        "exposure",
        "mean",
        "p95",
        "ratio"
    )?;
    for r in &c.rows {
        crate::outln!(
            "  {:<26} {:<22} {:>7} RU {:>10.4} {:>10.4} {:>10.3}",
            r.method,
            r.against,
            r.exposure_ru,
            r.mean,
            r.p95,
            r.mean / first(r.exposure_ru)
        )?;
    }
    let ext: Vec<String> =
        c.extension.iter().map(|r| format!("{} RU: mean {:.4}, p95 {:.4}", r.exposure_ru, r.mean, r.p95)).collect();
    crate::outln!(
        "periodic-extension error (ground-truth-periodic vs ground-truth, finite aperture): {}",
        ext.join("; ")
    )?;
    Ok(())
}

// ---------------------------------------------------------------------------------------------------------
// sweep

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Convergence sweeps (paper sec. 7, Figures 14–17): the method's BRDF map for each value of one parameter, its
CIEDE2000 error against the ground truth (mean and 95th percentile per exposure), a contact sheet of the maps
and an error-against-parameter plot. The ground truth is by default that of the method's own model, the
patch's periodic extension (see `iridis compare --help`); --against ground-truth takes the finite aperture.
Each value also reports the periodic-extension error (periodic against finite-aperture ground truth).

Parameters: terms (reference, lookup, nmm, pq), dlambda (all but ground-truth; values with units, 1nm,5nm,…),
coherence (all; with units, 5um,20um,65um; the ground truth follows), uv-power and uv-resolution (lookup).

Examples:
  iridis sweep 'builtin:xenopeltis?size=10um&pixel=50nm' --param terms --values 2,5,10,20 --coherence 3um -o terms.png
  iridis sweep 'builtin:blazed?size=10um&pixel=50nm' --param coherence --values 2um,5um,10um -o coh.png
  iridis sweep 'builtin:elaphe?size=10um&pixel=50nm' --method lookup --param uv-power --values 1,3,5 -o uv.png --json
  iridis sweep 'builtin:elaphe?size=10um&pixel=50nm' --method lookup --param uv-resolution --values 51,101 --gpu -o r.png

--gpu builds the lookup tables and renders the ground truths on the GPU; the other methods stay on the CPU.")]
pub struct SweepArgs {
    /// Height field: a file or builtin:NAME.
    pub surface: String,
    /// The parameter: terms, dlambda, coherence, uv-power, uv-resolution.
    #[arg(long)]
    pub param: String,
    /// Values, comma-separated (lengths with units).
    #[arg(long)]
    pub values: String,
    /// The method swept.
    #[arg(long, default_value = "reference")]
    pub method: String,
    /// The ground truth: model (that of the method's own model, the periodic extension), ground-truth (the
    /// finite aperture) or ground-truth-periodic.
    #[arg(long, default_value = "model")]
    pub against: String,
    /// Exposures in RU for the error (the contact sheet uses the first).
    #[arg(long, default_value = "1000")]
    pub exposures: String,
    /// Light direction θ[,φ].
    #[arg(long, default_value = "0deg")]
    pub incidence: String,
    /// Map size in pixels.
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Wavelength step (when not swept).
    #[arg(long, value_parser = positive_length_nm, default_value = "5nm")]
    pub dlambda: f64,
    /// u-v samples per axis for lookup (when not swept).
    #[arg(long, default_value_t = 201)]
    pub uv_resolution: usize,
    /// u-v exponent for lookup (when not swept).
    #[arg(long, default_value_t = 5.0)]
    pub uv_power: f64,
    /// Contact sheet (PNG).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Error-against-parameter plot (PNG); default: the contact sheet's name with _error.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Build the lookup tables and render the ground truths on the GPU (Vulkan; lavapipe without a GPU).
    #[arg(long)]
    pub gpu: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub model: LabModel,
}

pub fn run_sweep(a: SweepArgs) -> Result<()> {
    let method: Method = a.method.parse()?;
    let param: Param = a.param.parse()?;
    if !param.applies_to(method) {
        let who: Vec<&str> = Method::ALL.iter().filter(|m| param.applies_to(**m)).map(|m| m.name()).collect();
        bail!("the {method} method has no parameter '{}'; it applies to: {}", param.name(), who.join(", "));
    }
    let values = parse_list(&a.values, "--values", |s| match param {
        Param::DLambda | Param::Coherence => parse_length_nm(s).map_err(|e| anyhow::anyhow!("--values: {e}")),
        _ => s.parse::<f64>().map_err(|_| anyhow::anyhow!("--values: '{s}' is not a number")),
    })?;
    iridis_lab::sweep::check_values(param, &values)?;
    let against = match a.against.trim().to_ascii_lowercase().as_str() {
        "model" | "own" => method.model_truth(),
        other => match other.parse::<Method>() {
            Ok(m) if m.is_ground_truth() => m,
            _ => bail!("--against '{}': expected model, ground-truth or ground-truth-periodic", a.against),
        },
    };
    let exps = exposures(&a.exposures)?;
    let (theta, phi) = crate::args::polar_azimuth("incidence", &a.incidence)?;
    if !(8..=1024).contains(&a.size) {
        bail!("--size {} must be 8–1024 pixels", a.size);
    }
    crate::output::declare("-o", &a.output, &["png"])?;
    let plot_path = a.plot.clone().unwrap_or_else(|| {
        let stem = a.output.file_stem().and_then(|s| s.to_str()).unwrap_or("sweep");
        a.output.with_file_name(format!("{stem}_error.png"))
    });
    crate::output::declare("--plot", &plot_path, &["png"])?;
    let opts = a.model.options();
    let mut config = opts.config()?;
    config.spectral = spectral("d65", a.dlambda, &Cli)?;
    config.table = TableParams { uv_resolution: a.uv_resolution, uv_power: a.uv_power };
    config.accelerator = iridis_api::lab::gpu_accelerator(a.gpu, &Cli)?;
    let b = workbench(&a.surface, &opts, config, &Cli)?;
    let pixels = Pixels::brdf_map(theta, phi, a.size);
    let pb = bar(values.len() as u64, &format!("sweep {}", param.name()));
    let (_, points) =
        iridis_lab::sweep::run(&b, method, param, &values, &pixels, &exps, against, &|d| pb.set_position(d as u64))?;
    pb.finish_and_clear();
    let sheet = iridis_lab::sweep::contact_sheet(param, method, &points, &pixels, exps[0])?;
    let plot = iridis_lab::sweep::error_plot(param, method, &points)?;
    write_png_rgb8(&a.output, sheet.width, sheet.height, &sheet.data)?;
    write_png_rgb8(&plot_path, plot.width, plot.height, &plot.data)?;
    eprintln!("wrote {} and {}", a.output.display(), plot_path.display());
    if a.json {
        let pts: Vec<_> = points
            .iter()
            .map(|p| {
                let e3 = |v: &[(f64, f64, f64)]| {
                    v.iter().map(|e| json!({"exposure_ru": e.0, "mean": e.1, "p95": e.2})).collect::<Vec<_>>()
                };
                json!({"value": p.value, "errors": e3(&p.errors), "periodic_extension_error": e3(&p.extension)})
            })
            .collect();
        return print_json(&json!({"surface": a.surface, "method": method.name(), "against": against.name(),
            "param": param.name(), "points": pts}));
    }
    crate::outln!("{} against {}, sweeping {}:", method, against.name(), param.name())?;
    let line = |v: &[(f64, f64, f64)]| {
        v.iter().map(|e| format!("{} RU: mean {:.4}, p95 {:.4}", e.0, e.1, e.2)).collect::<Vec<_>>().join("; ")
    };
    for p in &points {
        crate::outln!("  {:>12}   {}", param.display(p.value), line(&p.errors))?;
    }
    if param == Param::Coherence {
        crate::outln!("periodic-extension error (ground-truth-periodic vs ground-truth, finite aperture):")?;
        for p in &points {
            crate::outln!("  {:>12}   {}", param.display(p.value), line(&p.extension))?;
        }
    } else if let Some(p) = points.first() {
        crate::outln!(
            "periodic-extension error (ground-truth-periodic vs ground-truth, finite aperture): {}",
            line(&p.extension)
        )?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------------------
// experiment laser

#[derive(Debug, Subcommand)]
pub enum ExperimentCommand {
    /// The laser experiment of the paper's Figure 8: the screen image a camera records.
    #[command(after_help = "\
A vertical sample, a horizontal supercontinuum beam at --incidence (45°) through a diaphragm whose aperture
(65–100 µm) is the coherence window, a white screen parallel to the beam at --distance; the mirror reflection
hits the screen's centre. Each pixel averages --subsamples² view directions (its solid angle). The beam's
spectrum comes from a CSV (wavelength_nm, power); without one an equal-energy spectrum is used. --coating gold
(default) puts gold's complex index (Johnson & Christy 1972) into the Fresnel term; --coating none leaves the
surface uncoated with the --fresnel model. Exposure: 1 RU saturates white for an uncoated perfect mirror.
The image's x axis runs along the beam, y up; one PNG per exposure (NAME_<E>RU.png when several).

Examples:
  iridis experiment laser 'builtin:elaphe?size=40um&pixel=80nm' --aperture 40um -o elaphe_screen.png
  iridis experiment laser scan.gwy --spectrum fianium_sc450.csv --aperture 100um --exposures 1000,7500 -o s.png
  iridis experiment laser 'builtin:xenopeltis?size=30um&pixel=60nm' --azimuth 90deg --size 151 -o x.png --json
  iridis experiment laser scan.gwy --spectrum sc450.csv --method lookup --save-table scan_sc450.npz -o s.png
  iridis experiment laser scan.gwy --spectrum sc450.csv --method lookup --table scan_sc450.npz -o s2.png

With --method lookup the table integrates the beam's spectrum (times the coating's normal-incidence
reflectance) in advance and records it; --save-table keeps it, --table reuses one, which must have been made
for this surface, aperture, beam and coating (any other table is refused, naming what differs).")]
    Laser(LaserArgs),
}

#[derive(Debug, ClapArgs)]
pub struct LaserArgs {
    /// Height field: a file or builtin:NAME.
    pub surface: String,
    /// Evaluation method.
    #[arg(long, default_value = "reference")]
    pub method: String,
    /// Angle between the beam and the sample normal.
    #[arg(long, value_parser = angle_rad, default_value = "45deg")]
    pub incidence: f64,
    /// Rotation of the sample about its normal.
    #[arg(long, value_parser = angle_rad, default_value = "0deg", allow_hyphen_values = true)]
    pub azimuth: f64,
    /// Diaphragm aperture: the coherence length of the window (overrides --coherence).
    #[arg(long, value_parser = positive_length_nm, default_value = "65um")]
    pub aperture: f64,
    /// Distance from the sample to the screen.
    #[arg(long, value_parser = positive_length_nm, default_value = "100mm")]
    pub distance: f64,
    /// Width (and height) of the screen area shown.
    #[arg(long, value_parser = positive_length_nm, default_value = "300mm")]
    pub screen: f64,
    /// Image size in pixels (the paper: 101).
    #[arg(long, default_value_t = 101)]
    pub size: usize,
    /// Samples per pixel side.
    #[arg(long, default_value_t = 3)]
    pub subsamples: usize,
    /// The beam's spectrum (CSV: wavelength_nm, power).
    #[arg(long)]
    pub spectrum: Option<PathBuf>,
    /// Coating: gold, none, or an n,k file (refractiveindex.info YAML or CSV wavelength_nm,n,k).
    #[arg(long, default_value = "gold")]
    pub coating: String,
    /// Exposures in RU, comma-separated.
    #[arg(long, default_value = "1,1000,7500")]
    pub exposures: String,
    /// Wavelength step of the spectral integral.
    #[arg(long, value_parser = positive_length_nm, default_value = "5nm")]
    pub dlambda: f64,
    /// Output image (PNG).
    #[arg(short, long)]
    pub output: PathBuf,
    /// A lookup table made for this surface, aperture and beam (by --save-table), for --method lookup.
    #[arg(long)]
    pub table: Option<PathBuf>,
    /// Write the lookup table built for this beam here (--method lookup).
    #[arg(long)]
    pub save_table: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub model: LabModel,
}

pub fn run_experiment(c: ExperimentCommand) -> Result<()> {
    match c {
        ExperimentCommand::Laser(a) => run_laser(a),
    }
}

fn run_laser(a: LaserArgs) -> Result<()> {
    let method: Method = a.method.parse()?;
    let exps = exposures(&a.exposures)?;
    let screens: Vec<PathBuf> = exps
        .iter()
        .map(|x| {
            if exps.len() == 1 {
                a.output.clone()
            } else {
                let stem = a.output.file_stem().and_then(|s| s.to_str()).unwrap_or("screen");
                a.output.with_file_name(format!("{stem}_{x}RU.png"))
            }
        })
        .collect();
    crate::output::format_of("-o", &a.output, &["png"])?;
    for p in &screens {
        crate::output::declare("-o", p, &["png"])?;
    }
    if (a.table.is_some() || a.save_table.is_some()) && method != Method::Lookup {
        bail!("--table and --save-table are lookup tables: use them with --method lookup, not {method}");
    }
    if a.table.is_some() && a.save_table.is_some() {
        bail!("--table reuses a table and --save-table writes the one built here: give one of them");
    }
    crate::output::declare_opt("--save-table", a.save_table.as_deref(), &["npz"])?;
    let spectrum = iridis_api::lab::beam_spectrum(a.spectrum.as_deref(), &Cli)?;
    let coating = iridis_api::lab::coating(&a.coating)?;
    let setup = LaserSetup {
        incidence: a.incidence,
        azimuth: a.azimuth,
        distance_nm: a.distance,
        screen_width_nm: a.screen,
        screen_height_nm: a.screen,
        width_px: a.size,
        height_px: a.size,
        subsamples: a.subsamples,
    };
    let pixels = setup.pixels()?;
    let mut model = a.model.options();
    model.coherence_nm = Some(a.aperture);
    let mut config = model.config()?;
    config.spectral = spectral("e", a.dlambda, &Cli)?;
    let scale = iridis_lab::laser::configure(&mut config, method, &spectrum, coating.as_ref(), Observer::Cie1931)?;
    config.table_path = a.table.clone();
    let b = workbench(&a.surface, &model, config, &Cli)?;
    let e = evaluator(&b, method, &Cli)?;
    if let (Some(path), Some(lookup)) = (&a.save_table, e.as_lookup()) {
        crate::output::write_atomic(path, |w| {
            let mut buf = std::io::Cursor::new(Vec::new());
            lookup.table.write_npz(&mut buf)?;
            std::io::Write::write_all(w, buf.get_ref())?;
            Ok(())
        })?;
        eprintln!("wrote {}", path.display());
    }
    let mut img = render_pixels(e.as_ref(), &pixels, "screen", &Cli);
    iridis_lab::laser::scale_image(&mut img, scale);
    let half = a.screen / 2e6;
    let mut written = Vec::new();
    for (&x, path) in exps.iter().zip(screens) {
        let px = iridis_lab::image::to_rgb(&img, a.size, a.size, x);
        let plot = iridis_plot::ImagePlot {
            title: format!(
                "{}: screen at {:.0} mm, beam {:.0}°, aperture {:.0} µm, {x} RU",
                short(&a.surface),
                a.distance / 1e6,
                a.incidence.to_degrees(),
                a.aperture / 1000.0
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
        eprintln!("wrote {}", path.display());
        written.push(path);
    }
    let ys: Vec<f64> = img.iter().flatten().map(|x| x.y).collect();
    let peak = ys.iter().cloned().fold(0.0, f64::max);
    if a.json {
        return print_json(&json!({"surface": a.surface, "method": method.name(), "images": written,
            "coating": a.coating, "gold_mirror_relative_brightness": scale, "max_y": peak,
            "pixels": a.size, "screen_mm": a.screen / 1e6, "distance_mm": a.distance / 1e6}));
    }
    crate::outln!(
        "{} pixels, brightest Y = {peak:.4e} (saturates at {:.3e} RU); coated mirror brightness {scale:.3} of an uncoated one",
        a.size * a.size,
        1.0 / peak.max(1e-300)
    )?;
    Ok(())
}

// ---------------------------------------------------------------------------------------------------------
// demo

/// The demo's lab section: test-bench plots and Table-1-style numbers for the built-in blazed grating and
/// Elaphe-like surface, and a Table-2-style comparison on a small Elaphe-like patch.
pub fn demo(g: &mut iridis_api::gallery::Gallery) -> Result<()> {
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
        let b = workbench(spec, &m, m.config()?, &Cli)?;
        let e = evaluator(&b, Method::Reference, &Cli)?;
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
    let b = workbench(spec, &m, config, &Cli)?;
    let pixels = Pixels::brdf_map(0.0, 0.0, 48);
    let methods = [
        Method::Lookup,
        Method::Reference,
        Method::StamPeriodic(iridis_lab::stam::Bump::Rectangular),
        Method::StamGaussian,
    ];
    let c = comparison(&b, &methods, None, &pixels, &[1.0, 1000.0, 7500.0], &Cli)?;
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
