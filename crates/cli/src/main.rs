//! `iridis`: a thin command-line shell over the iridis library crates. Each subcommand lives in its own
//! module under `cmd/`; shared output helpers (atomic file writes, JSON) live in `output.rs`.

mod args;
mod cmd;
mod output;
mod progress;

use clap::{Parser, Subcommand};

/// Structural colour: thin-film interference and diffraction from measured nanostructures.
#[derive(Debug, Parser)]
#[command(name = "iridis", version, about, long_about = None, after_help = "\
Examples:
  iridis demo --out gallery                         gallery of built-in examples, with index.html
  iridis surface info builtin:elaphe --image e.png  periods and orientations of a height field
  iridis precompute builtin:elaphe -o elaphe.npz    lookup tables (Taylor terms + DFT)
  iridis brdf-map elaphe.npz -o elaphe.png          BRDF map at normal incidence
  iridis testbench builtin:blazed --plot b.png      period from the grating equation (paper 6.1)
  iridis thinfilm color --stack \"air | water 348nm | air\" --json
  iridis color xyz data/examples/colorchecker_green.csv --json

SURFACE arguments take a file (.gwy, .npy, PNG/TIFF, text) or a built-in:
builtin:blazed|sine|cd|elaphe|xenopeltis|gaussian. Lengths and angles carry units:
65nm, 0.43um, 65µm, 75deg.")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

// Parsed once per run: the size difference between variants costs nothing worth boxing for.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Subcommand)]
enum Command {
    /// Run the main job on built-in data: a gallery of results with an index page.
    Demo(cmd::demo::Args),
    /// Colour science: spectrum → XYZ/sRGB/Lab, colour differences.
    #[command(subcommand)]
    Color(cmd::color::ColorCommand),
    /// Lookup tables for a height field: DFTs of the Taylor terms and I_p(u, v) (paper eq. 5–12).
    Precompute(cmd::brdf::PrecomputeArgs),
    /// BRDF map of a height field or table: colour for every view direction (paper sec. 7).
    BrdfMap(cmd::brdf::BrdfMapArgs),
    /// Speed, measured against a peer in the same run.
    #[command(subcommand)]
    Bench(cmd::bench::BenchCommand),
    /// Thin-film interference: spectra, angle × wavelength tables, film colours, the soap-film chart.
    #[command(subcommand)]
    Thinfilm(cmd::thinfilm::ThinfilmCommand),
    /// Height fields: inspect (sizes, periods), generate nanostructures, convert formats.
    #[command(subcommand, after_help = cmd::surface::SURFACE_HELP)]
    Surface(cmd::surface::SurfaceCommand),
    /// Virtual test bench: peak viewing angles and periodicity per wavelength (paper sec. 6.1, Table 1).
    Testbench(cmd::lab::TestbenchArgs),
    /// CIELAB errors of methods against the ground truth (paper sec. 6.3, Table 2).
    Compare(cmd::lab::CompareArgs),
    /// Convergence sweeps over terms, Δλ, coherence, u-v power or resolution (paper Figures 14–17).
    Sweep(cmd::lab::SweepArgs),
    /// Simulated lab experiments (the laser experiment of paper Figure 8).
    #[command(subcommand)]
    Experiment(cmd::lab::ExperimentCommand),
    /// Render a scene (TOML or glTF) on the CPU: diffraction and thin-film materials on meshes (issue 7).
    Render(cmd::render::RenderArgs),
    /// Interactive window: a scene or a BRDF map rendered on the GPU, with an egui panel (issue 8).
    View(cmd::gpu::ViewArgs),
    // New command groups are added here, one line each, with their module in cmd/.
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Demo(a) => cmd::demo::run(a),
        Command::Color(c) => cmd::color::run(c),
        Command::Testbench(a) => cmd::lab::run_testbench(a),
        Command::Compare(a) => cmd::lab::run_compare(a),
        Command::Sweep(a) => cmd::lab::run_sweep(a),
        Command::Experiment(c) => cmd::lab::run_experiment(c),
        Command::Surface(c) => cmd::surface::run(c),
        Command::Thinfilm(c) => cmd::thinfilm::run(c),
        Command::Bench(c) => cmd::bench::run(c),
        Command::Precompute(a) => cmd::brdf::run_precompute(a),
        Command::BrdfMap(a) => cmd::brdf::run_brdf_map(a),
        Command::Render(a) => cmd::render::run(a),
        Command::View(a) => cmd::gpu::run_view(a),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::from(2)
        }
    }
}
