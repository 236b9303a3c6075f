//! `iridis`: a thin command-line shell over the iridis library crates. Each subcommand lives in its own
//! module under `cmd/`; shared output helpers (atomic file writes, JSON) live in `output.rs`.

// The argument structs' doc comments are the `--help` text, where `θ[,φ]` and `schlick[:N]` are syntax, not
// links.
#![allow(rustdoc::broken_intra_doc_links)]

mod args;
mod cmd;
mod help;
mod output;
mod progress;
mod runtime_dir;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

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
  iridis vision data/examples/vision_spectra.csv --visual bluetit

SURFACE arguments take a file — AFM instrument files (Bruker .spm/.000, Asylum .ibw, JPK .jpk, WSxM .stp/.top,
Nanonis .sxm, Gwyddion .gwy/.gsf; --channel NAME|N, `iridis surface channels FILE`), numpy .npy/.npz, PNG/TIFF,
text — or a built-in, one of builtin:blazed|sine|cd|elaphe|xenopeltis|gaussian (iridis surface --help). Lengths
and angles carry units: 65nm, 0.43um, 65µm, 75deg. The light's direction is --light or --incidence, and the
spectral integral's step --step or --dlambda: the same option under either name wherever a diffraction
command asks for it.")]
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
    #[command(
        subcommand,
        after_help = "\
Examples:
  iridis color xyz data/examples/colorchecker_green.csv --json     XYZ, xyY, CIELAB, sRGB of a reflectance
  iridis color xyz data/cie/d65.csv --emissive                     colour of a light source
  iridis color delta-e 50,2.6772,-79.7751 50,0,-82.7485            CIEDE2000 between two CIELAB colours"
    )]
    Color(cmd::color::ColorCommand),
    /// Lookup tables for a height field: DFTs of the Taylor terms and I_p(u, v) (paper eq. 5–12).
    Precompute(cmd::brdf::PrecomputeArgs),
    /// BRDF map of a height field or table: colour for every view direction (paper sec. 7).
    BrdfMap(cmd::brdf::BrdfMapArgs),
    /// Point queries of the diffraction BRDF: ρ(λ) and XYZ for one pair of directions.
    #[command(
        subcommand,
        after_help = "\
Examples:
  iridis brdf eval builtin:sine --light 30deg --view 10deg,180deg --json"
    )]
    Brdf(cmd::brdf::BrdfCommand),
    /// Speed, measured against a peer in the same run.
    #[command(
        subcommand,
        after_help = "\
Examples:
  iridis bench diffraction --size 512 --terms 20      precompute against numpy, BRDF maps per second
  iridis bench diffraction-accuracy --json            CIEDE2000 of lookup and reference against ground truth
  iridis bench gpu                                    GPU frame times: diffraction map and thin-film frame
  iridis bench render --size 512                      render time of every example scene
  iridis bench grating                                rigorous orders (C-method) against grcwa, 1-D and 2-D
  iridis thinfilm bench                               thin-film evaluations per second against Python tmm"
    )]
    Bench(cmd::bench::BenchCommand),
    /// Thin-film interference: spectra, tables, colours, the soap-film chart, absorption profiles, fitting.
    #[command(
        subcommand,
        after_help = "\
Examples:
  iridis thinfilm spectrum --stack \"air | water 348nm | air\" --plot soap.png
  iridis thinfilm spectrum --stack \"air | MgF2 100nm | inc:BK7 1mm | air\" --json
  iridis thinfilm profile --stack \"air | Au 30nm | glass\" --wavelength 500nm --plot au.png
  iridis thinfilm fit measured.csv --stack \"air | SiO2 {d1=100nm:50nm..500nm} | Si\" --plot fit.png
  iridis thinfilm color --stack \"air | water 348nm | air\" --json
  iridis thinfilm color --stack \"air | water 348nm | Si\" --roughness 25nm --correlation 300nm
  iridis thinfilm chart --stack \"air | water {d} | air\" --thickness 0nm:2000nm:2nm -o chart.png
  iridis thinfilm materials --at 550nm"
    )]
    Thinfilm(cmd::thinfilm::ThinfilmCommand),
    /// Height fields: inspect (sizes, periods), generate nanostructures, convert formats.
    #[command(subcommand, after_help = format!("\
Examples:
  iridis surface info builtin:elaphe --image elaphe.png      sizes, periods and orientations
  iridis surface generate blazed --period 2500nm -o b.npy    a nanostructure height field
  iridis surface convert scan.gwy scan.npy                   between formats

{}", cmd::surface::SURFACE_HELP))]
    Surface(cmd::surface::SurfaceCommand),
    /// Order efficiencies of a height field taken as one unit cell of a grating (TE, TM, unpolarised).
    Grating(cmd::grating::GratingArgs),
    /// Virtual test bench: peak viewing angles and periodicity per wavelength (paper sec. 6.1, Table 1).
    Testbench(cmd::lab::TestbenchArgs),
    /// CIELAB errors of methods against the ground truth (paper sec. 6.3, Table 2).
    Compare(cmd::lab::CompareArgs),
    /// Convergence sweeps over terms, Δλ, coherence, u-v power or resolution (paper Figures 14–17).
    Sweep(cmd::lab::SweepArgs),
    /// Simulated lab experiments (the laser experiment of paper Figure 8).
    #[command(
        subcommand,
        after_help = "\
Examples:
  iridis experiment laser 'builtin:elaphe?size=40um&pixel=80nm' --aperture 40um -o elaphe_screen.png"
    )]
    Experiment(cmd::lab::ExperimentCommand),
    /// Render a scene (TOML or glTF) on the CPU, or the GPU with --gpu: diffraction and thin-film materials on meshes.
    Render(cmd::render::RenderArgs),
    /// Interactive window: a scene or a BRDF map rendered on the GPU, with an egui panel.
    View(cmd::gpu::ViewArgs),
    /// From a scan to its colours: relief, roughness, periods, PSDF, BRDF maps, test bench in DIR/index.html.
    Report(cmd::report::ReportArgs),
    /// Colours as animals see them: quantum catches, colour spaces and distances ΔS, ΔL in JND (birds, bees, …).
    Vision(cmd::vision::VisionArgs),
    // New command groups are added here, one line each, with their module in cmd/.
}

/// Every option that takes a value takes a negative one too (`--exposure -1`, `--light -30deg`): the library
/// then says what the value may be, where clap would take `-1` for an unknown flag and suggest `-- -1`. Clap
/// knows a negative number but not one with a unit, so a value that starts with a minus and a digit, given
/// as the next word after an option that takes one, is attached to it (`--light=-30deg`) before clap parses.
fn attach_negative_values(cmd: &clap::Command, args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let negative = |s: &str| {
        let mut c = s.chars();
        c.next() == Some('-') && c.next().is_some_and(|d| d.is_ascii_digit() || d == '.')
    };
    let mut cmd = cmd;
    let mut out = Vec::with_capacity(args.len());
    let mut args = args.into_iter();
    out.extend(args.next()); // the program's name
    while let Some(arg) = args.next() {
        let Some(word) = arg.to_str().map(str::to_owned) else {
            out.push(arg);
            continue;
        };
        if word == "--" {
            out.push(arg);
            out.extend(args.by_ref());
            break;
        }
        if let Some(name) = word.strip_prefix("--").filter(|n| !n.contains('=')) {
            let named = |a: &clap::Arg| {
                a.get_long() == Some(name) || a.get_all_aliases().is_some_and(|all| all.contains(&name))
            };
            let takes_value = cmd.get_arguments().any(|a| named(a) && a.get_action().takes_values());
            if takes_value {
                match args.next() {
                    Some(v) if v.to_str().is_some_and(negative) => {
                        let mut joined = arg;
                        joined.push("=");
                        joined.push(v);
                        out.push(joined);
                    }
                    Some(v) => out.extend([arg, v]),
                    None => out.push(arg),
                }
                continue;
            }
        } else if let Some(sub) = cmd.find_subcommand(&word) {
            cmd = sub;
        }
        out.push(arg);
    }
    out
}

fn main() -> std::process::ExitCode {
    // Parsed through the laid-out command (help.rs) so that every help page wraps its prose and keeps its
    // examples whole.
    let width = help::width();
    let command = help::layout(Cli::command()).term_width(width);
    let args = attach_negative_values(&command, std::env::args_os().collect());
    let matches = match command.try_get_matches_from(args) {
        Ok(m) => m,
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelp => {
            print!("{}", help::mend_widows(&e.render().to_string(), width));
            return std::process::ExitCode::SUCCESS;
        }
        Err(e) => e.exit(),
    };
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    output::set_inputs(&Cli::command(), &matches);
    // Before any thread or GPU driver starts: the drivers read XDG_RUNTIME_DIR (runtime_dir.rs).
    let _runtime_dir = runtime_dir::ensure();
    iridis_render::tables::set_table_progress(progress::reporter());
    let result = match cli.command {
        Command::Demo(a) => cmd::demo::run(a),
        Command::Color(c) => cmd::color::run(c),
        Command::Grating(a) => cmd::grating::run(a),
        Command::Testbench(a) => cmd::lab::run_testbench(a),
        Command::Compare(a) => cmd::lab::run_compare(a),
        Command::Sweep(a) => cmd::lab::run_sweep(a),
        Command::Experiment(c) => cmd::lab::run_experiment(c),
        Command::Surface(c) => cmd::surface::run(c),
        Command::Thinfilm(c) => cmd::thinfilm::run(c),
        Command::Bench(c) => cmd::bench::run(c),
        Command::Precompute(a) => cmd::brdf::run_precompute(a),
        Command::BrdfMap(a) => cmd::brdf::run_brdf_map(a),
        Command::Brdf(c) => cmd::brdf::run_brdf(c),
        Command::Render(a) => cmd::render::run(a),
        Command::View(a) => cmd::gpu::run_view(a),
        Command::Report(a) => cmd::report::run(a),
        Command::Vision(a) => cmd::vision::run(a),
    };
    // All of a run's files appear together, and only when the whole command succeeded (output.rs).
    let result = match result {
        Ok(()) => output::commit(),
        Err(e) => {
            output::discard();
            Err(e)
        }
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        // The reader of our standard output has gone (`iridis … | head`): that is how pipes end, not an error.
        Err(e) if output::is_broken_pipe(&e) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::from(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Cli;
    use clap::CommandFactory;

    /// Every command and subcommand (group pages included) shows examples in its `--help`.
    #[test]
    fn every_help_page_has_examples() {
        fn walk(cmd: &mut clap::Command, path: &str, missing: &mut Vec<String>, seen: &mut usize) {
            let path = if path.is_empty() { cmd.get_name().to_string() } else { format!("{path} {}", cmd.get_name()) };
            let help = cmd.render_long_help().to_string();
            *seen += 1;
            if !help.contains("Examples:") || !help.contains("iridis ") {
                missing.push(path.clone());
            }
            for sub in cmd.get_subcommands_mut() {
                if sub.get_name() == "help" {
                    continue; // clap's own `help` subcommand
                }
                walk(sub, &path, missing, seen);
            }
        }
        let mut cli = super::help::layout(Cli::command());
        cli.build();
        let (mut missing, mut seen) = (Vec::new(), 0);
        walk(&mut cli, "", &mut missing, &mut seen);
        assert!(seen > 20, "walked only {seen} commands");
        assert!(missing.is_empty(), "help pages without an Examples section: {missing:?}");
    }

    /// No command answers to one option name twice (an alias such as `--light` for `--incidence` included):
    /// clap checks this only in debug builds, and the tests run optimised.
    #[test]
    fn no_option_name_is_taken_twice() {
        fn walk(cmd: &clap::Command, path: &str, clashes: &mut Vec<String>) {
            let path = format!("{path} {}", cmd.get_name());
            let mut names: Vec<&str> = Vec::new();
            for a in cmd.get_arguments() {
                for name in a.get_long().into_iter().chain(a.get_all_aliases().unwrap_or_default()) {
                    if names.contains(&name) {
                        clashes.push(format!("{path}: --{name}"));
                    }
                    names.push(name);
                }
            }
            cmd.get_subcommands().for_each(|sub| walk(sub, &path, clashes));
        }
        let mut cli = Cli::command();
        cli.build();
        let mut clashes = Vec::new();
        walk(&cli, "", &mut clashes);
        assert!(clashes.is_empty(), "option names taken twice: {clashes:?}");
    }

    #[test]
    fn a_negative_value_is_attached_to_its_option() {
        let run = |line: &str| {
            let args = line.split(' ').map(std::ffi::OsString::from).collect();
            let out = super::attach_negative_values(&Cli::command(), args);
            out.iter().map(|a| a.to_str().unwrap()).collect::<Vec<_>>().join(" ")
        };
        // Through an alias, with a unit, and a list; a flag's next word and anything after `--` stay apart.
        assert_eq!(
            run("iridis brdf eval s.gwy --incidence -30deg --view -1,2 --json -5"),
            "iridis brdf eval s.gwy --incidence=-30deg --view=-1,2 --json -5"
        );
        assert_eq!(run("iridis render s.toml --exposure -1 -- -2"), "iridis render s.toml --exposure=-1 -- -2");
        // A word that is no negative number, and an option given with `=`, are left as they are.
        assert_eq!(run("iridis grating s --light -x --from=-3nm"), "iridis grating s --light -x --from=-3nm");
    }
}
