//! `iridis testbench`, `iridis compare`, `iridis sweep`, `iridis experiment laser`: the virtual lab of issue 6
//! (paper sec. 6–7, thesis ch. 5); the runs are the library's (`iridis_api::lab_run`).

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args as ClapArgs, Subcommand};
use iridis_api::lab_run::{self as run, parse_exposures, parse_list};
use iridis_api::model::TableGrid;
use iridis_api::surface::Source;
use iridis_lab::bench::BenchSetup;
use iridis_lab::laser::LaserSetup;
use iridis_lab::methods::Method;

use crate::args::{angle_rad, polar_azimuth, positive_length_nm};
use crate::output::print_answer;
use crate::progress::Cli;

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

JSON keys: docs/json.md, section `iridis testbench`. ridges lists competing sub-structure periods when there
is more than one, as for Xenopeltis; definite is false, with a warning, when d_λ spreads by more than 1 % of
its mean: the direction has no period, as along the Elaphe-like fingers.

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
    #[arg(long, alias = "light", value_parser = angle_rad, default_value = "75deg")]
    pub incidence: f64,
    /// Rotation of the surface about its normal: 0deg measures periods along x, 90deg along y [default: the
    /// orientation of the surface's strongest period, as `iridis surface info` finds it].
    #[arg(long, value_parser = angle_rad)]
    pub azimuth: Option<f64>,
    /// Diffraction order m (non-zero; m > 0 lies between the mirror direction and the normal).
    #[arg(long, default_value_t = 1)]
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
    #[arg(long, value_parser = angle_rad, default_value = "-89deg")]
    pub min_angle: f64,
    /// Largest viewing angle.
    #[arg(long, value_parser = angle_rad, default_value = "89deg")]
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
    pub model: iridis_api::lab::LabOptions,
}

pub fn run_testbench(a: TestbenchArgs) -> Result<()> {
    let mut rigorous = iridis_api::ModelOptions::default();
    a.rigorous.apply(&mut rigorous)?;
    let mut setup = BenchSetup::new(
        a.incidence,
        a.azimuth.unwrap_or(0.0),
        a.order,
        (a.from, a.to, a.step),
        (a.min_angle.to_degrees(), a.max_angle.to_degrees(), a.angle_step.to_degrees()),
    )?;
    setup.period_hint_nm = a.period;
    let req = run::TestbenchRequest {
        method: a.method.clone(),
        rigorous,
        setup,
        along_dominant: a.azimuth.is_none(),
        max_period_nm: a.max_period,
        plot: a.plot.clone(),
    };
    let t = run::testbench_run(&Source::Spec(a.surface.clone()), &a.model, &req, &Cli)?;
    print_answer(a.json, || Ok(t.to_json()), || t.text())
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

JSON keys: docs/json.md, section `iridis compare`.

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
    #[arg(long, alias = "light", default_value = "0deg")]
    pub incidence: String,
    /// Map size in pixels (the paper: 101).
    #[arg(long, default_value_t = 101)]
    pub size: usize,
    /// Wavelength step of the spectral integral.
    #[arg(long, alias = "step", value_parser = positive_length_nm, default_value = "5nm")]
    pub dlambda: f64,
    /// Illuminant: d65, d50, a, e.
    #[arg(long, default_value = "d65")]
    pub illuminant: String,
    #[command(flatten)]
    pub grid: TableGrid,
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
    pub model: iridis_api::lab::LabOptions,
}

pub fn run_compare(a: CompareArgs) -> Result<()> {
    let req = run::CompareRequest {
        methods: parse_list(&a.methods, "--methods", |s| Ok(s.parse::<Method>()?))?,
        against: iridis_api::lab::parse_against(&a.against)?,
        exposures: parse_exposures(&a.exposures)?,
        incidence: polar_azimuth("incidence", &a.incidence)?,
        size: a.size,
        illuminant: a.illuminant.clone(),
        dlambda_nm: a.dlambda,
        table: a.grid,
        table_path: a.table.clone(),
        gpu: a.gpu,
        maps: a.maps.clone(),
    };
    let c = run::compare_run(&Source::Spec(a.surface.clone()), &a.model, &req, &Cli)?;
    print_answer(a.json, || Ok(c.to_json()), || c.text())
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
    #[arg(long, alias = "light", default_value = "0deg")]
    pub incidence: String,
    /// Map size in pixels.
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Wavelength step [default: 5nm]; refused where swept.
    #[arg(long, alias = "step", value_parser = positive_length_nm)]
    pub dlambda: Option<f64>,
    /// u-v samples per axis of the lookup method's tables [default: 201]; refused where swept or with another
    /// method.
    #[arg(long, value_name = "N")]
    pub uv_resolution: Option<usize>,
    /// u-v exponent of the lookup method's tables [default: 5]; refused where swept or with another method.
    #[arg(long, value_name = "A")]
    pub uv_power: Option<f64>,
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
    pub model: iridis_api::lab::LabOptions,
}

pub fn run_sweep(a: SweepArgs) -> Result<()> {
    let param: iridis_lab::sweep::Param = a.param.parse()?;
    let req = run::SweepRequest {
        method: a.method.parse()?,
        param,
        values: run::parse_sweep_values(param, &a.values)?,
        against: a.against.clone(),
        exposures: parse_exposures(&a.exposures)?,
        incidence: polar_azimuth("incidence", &a.incidence)?,
        size: a.size,
        dlambda_nm: a.dlambda,
        table: TableGrid { uv_resolution: a.uv_resolution, uv_power: a.uv_power },
        gpu: a.gpu,
        output: a.output.clone(),
        plot: a.plot.clone(),
    };
    let s = run::sweep_run(&Source::Spec(a.surface.clone()), &a.model, &req, &Cli)?;
    print_answer(a.json, || Ok(s.to_json()), || s.text())
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
    #[arg(long, alias = "light", value_parser = angle_rad, default_value = "45deg")]
    pub incidence: f64,
    /// Rotation of the sample about its normal.
    #[arg(long, value_parser = angle_rad, default_value = "0deg")]
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
    #[arg(long, alias = "step", value_parser = positive_length_nm, default_value = "5nm")]
    pub dlambda: f64,
    /// Output image (PNG).
    #[arg(short, long)]
    pub output: PathBuf,
    // The lookup table built for the beam (--method lookup).
    #[command(flatten)]
    pub grid: TableGrid,
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
    pub model: iridis_api::lab::LabOptions,
}

pub fn run_experiment(c: ExperimentCommand) -> Result<()> {
    let ExperimentCommand::Laser(a) = c;
    let req = run::LaserRequest {
        method: a.method.parse()?,
        setup: LaserSetup {
            incidence: a.incidence,
            azimuth: a.azimuth,
            distance_nm: a.distance,
            screen_width_nm: a.screen,
            screen_height_nm: a.screen,
            width_px: a.size,
            height_px: a.size,
            subsamples: a.subsamples,
        },
        aperture_nm: a.aperture,
        spectrum: a.spectrum.clone(),
        coating: a.coating.clone(),
        exposures: parse_exposures(&a.exposures)?,
        dlambda_nm: a.dlambda,
        table: a.grid,
        output: a.output.clone(),
        table_path: a.table.clone(),
        save_table: a.save_table.clone(),
    };
    let l = run::laser_run(&Source::Spec(a.surface.clone()), &a.model, &req, &Cli)?;
    print_answer(a.json, || Ok(l.to_json()), || l.text())
}
