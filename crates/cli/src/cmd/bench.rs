//! `iridis bench …`: speed measured against a peer in the same run, accuracy against the ground truth. Each
//! bench is one library call (`iridis_api::bench`, which Python's `python -m iridis.bench NAME` calls too);
//! this module parses its options and prints its text or JSON. Nothing here is a test: tests never depend on
//! wall-clock time.

use anyhow::Result;
use clap::{Args as ClapArgs, Subcommand};
use iridis_api::bench::{self, diffraction, gpu, render};

use crate::progress::Cli;

#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Diffraction: precompute against numpy, BRDF maps per second for lookup, reference and ground truth.
    #[command(after_help = "\
Examples:
  iridis bench diffraction                         1024² surface, 40 terms, maps at 512² and 1024²
  iridis bench diffraction --size 512 --terms 20 --json")]
    Diffraction(Run<diffraction::SpeedOptions>),
    /// Diffraction accuracy: CIEDE2000 of lookup (f64, f32, linear grid) and reference against the ground truth,
    /// and the Taylor convergence of the reference with N.
    #[command(after_help = "\
The ground truth is that of the methods' own model by default: the direct windowed sum over the patch's
periodic extension, which the DFT-based methods approximate (--aperture finite: the window cut at the patch
edge instead). The periodic-extension error, periodic against finite-aperture ground truth, is reported as its
own row (method periodic-extension).

Examples:
  iridis bench diffraction-accuracy                                  built-in surfaces, 24² maps
  iridis bench diffraction-accuracy --surface builtin:blazed --map-size 48 --json
  iridis bench diffraction-accuracy --surface 'builtin:elaphe?size=10um' --coherence 65um --aperture finite
  iridis bench diffraction-accuracy --convergence-plot convergence.png")]
    DiffractionAccuracy(Run<diffraction::AccuracyOptions>),
    /// Reference against ground truth at equal size: the same surfaces (512² and 1024² samples), the same
    /// map size, maps per second of each, all cores.
    #[command(after_help = "\
The ground truth sums the windowed exp(i k w h) directly over every sample for every pixel and wavenumber;
the reference evaluates the Taylor-term DFTs near each pixel's frequency (after computing them once, which
is timed separately). Both run on all cores (rayon over map rows).

Examples:
  iridis bench diffraction-methods                              512² and 1024² patches, 16² maps
  iridis bench diffraction-methods --patch-sizes 256,512 --map-size 24 --json")]
    DiffractionMethods(Run<diffraction::MethodsOptions>),
    /// GPU frame times (min, median, p99) of the lookup diffraction map and the thin-film frame, headless.
    #[command(after_help = "\
Times the two shaders headless (no window): the lookup diffraction BRDF map (paper eq. 10-12) and the
thin-film frame (Sussenbach ch. 4: thickness gradient and SVT texture) on both film paths in the same run:
the fast path (a colour table over angle x thickness, built on the GPU, then a bilinear lookup per pixel)
and the direct path (the recurrence at --spectral-samples wavelengths per pixel, 81 by default: the
reference), with the CIEDE2000 between the two.
A frame is one dispatch from submission to completion (wall clock; also the GPU's own timestamps around the
pass where the adapter has them); the light circles the normal at 30° from frame to
frame. Each shader runs --frames frames or --max-seconds, whichever ends first, after one warm-up frame,
and the last frame is checked against the CPU (CIEDE2000 over up to 4096 pixels). --table-precision times
the lookup map once per table encoding (f32, f16, chebK, chebK-f16), each against the CPU's f64 lookup.

Then the diffraction work that is not a frame, each against the CPU in the same run: the lookup table of
--build-surface built on all CPU cores (f64) and on the GPU (f32) — seconds, speed-up, the largest relative
error — and the ground truth of --gt-surface (finite aperture and periodic) as a --gt-size map on the GPU
against --gt-cpu-pixels of its pixels on the CPU — pixels per second, speed-up, CIEDE2000 — and the phase
arithmetic of the ground-truth shader against f64. The defaults are small (lavapipe runs on the CPU); on a
GPU the paper's sizes are --build-surface builtin:elaphe --build-uv-resolution 501 --gt-surface
builtin:elaphe --gt-size 101. Both surfaces are read with the surface flags (--channel, --pixel-size,
--level, …) before anything is timed.

With a SCENE (TOML or glTF), times the scene renderer instead (iridis render --gpu): --frames frames of
--size with 1 sample per pixel, min/median/p99, against one CPU render of the same image in the same run
(speed-up and CIEDE2000 between the two); a scene with smooth thin films is timed on both film paths.

Examples:
  iridis bench gpu examples/snake_elaphe.toml --size 1024x1024 --frames 500
  iridis bench gpu examples/soap_bubble.toml --size 1920x1080 --frames 50 --json
  iridis bench gpu                                      built-in Elaphe table (201²), 1024² map, 1920×1080 film
  iridis bench gpu --table elaphe.npz --size 1024x1024 --frames 500 --json
  iridis bench gpu --stack \"air | gasoline 216nm | water 220nm | asphalt\" --film-size 1280x720
  iridis bench gpu --size 512 --film-size 960x540 --frames 5 --save out/
  iridis bench gpu --table-precision f32,cheb12,cheb12-f16 --size 1024 --frames 200
  iridis bench gpu --build-surface builtin:elaphe --build-uv-resolution 501 --gt-surface builtin:elaphe --gt-size 101")]
    Gpu(Run<gpu::GpuBenchOptions>),
    /// Rendering: load and render time of every example scene (default 1024², 1 spp, all cores).
    #[command(after_help = "Examples:\n  iridis bench render\n  iridis bench render --size 512 --spp 4 --json")]
    Render(Run<render::RenderOptions>),
    /// Rigorous order efficiencies (the C-method) against grcwa (Python, RCWA) at equal accuracy, 1-D and 2-D.
    #[command(after_help = "\
Cases: a sine of period 1000 nm and amplitude 100 nm (a/Λ = 0.1) at 550 nm, 30°, on a metal (ε = −20 + 1i) and
on glass (n = 1.5), and a crossed sine h = 25 nm (sin Kx + sin Ky) on glass at 30°, azimuth 20°. iridis is
timed on one thread (TE and TM, the whole automatic order search, best of --repeats), its accuracy measured
against the same problem with more orders. grcwa (pip install grcwa) runs through a ladder of orders and
slices, numpy on one thread, until every propagating efficiency above 1e-3 is within 1 % of that answer
(then 0.1 %); the speed ratio is at the first rung within 1 %. On the metal grcwa's error is taken on TE:
staircase RCWA does not converge in TM there (its TM error is listed). Throughput: solves per second over
wavelengths 400–700 nm on one thread and on all threads. Without Python or grcwa the peer is skipped with a
note. The default run takes minutes (grcwa's larger rungs); --quick runs tiny cases (10 nm deep, glass, the
crossed sine at Λ = 300 nm; one repeat, two wavelengths) to show the command works.

Examples:
  iridis bench grating
  iridis bench grating --python /tmp/rcwa-venv/bin/python --peer-seconds 30
  iridis bench grating --quick --no-python --json")]
    Grating(GratingBench),
}

/// A bench's options, the library's, and `--json`.
#[derive(Debug, ClapArgs)]
pub struct Run<T: ClapArgs> {
    #[command(flatten)]
    pub options: T,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct GratingBench {
    /// Timed solves per case; the best counts.
    #[arg(long, default_value_t = 3)]
    pub repeats: usize,
    /// The Python interpreter with grcwa and numpy.
    #[arg(long, default_value = "python3")]
    pub python: String,
    /// Do not time grcwa.
    #[arg(long, conflicts_with_all = ["python", "peer_seconds"])]
    pub no_python: bool,
    /// grcwa's ladder stops after a rung (TE and TM) that took longer than this many seconds.
    #[arg(long, default_value_t = 60.0)]
    pub peer_seconds: f64,
    /// Wavelengths solved in the throughput measurement (one and all threads); the 2-D case takes at most
    /// twice the thread count.
    #[arg(long, default_value_t = 8)]
    pub batch: usize,
    /// Tiny cases (10 nm deep, glass only, the crossed sine at Λ = 300 nm), one repeat, two wavelengths and a
    /// short ladder: shows the command works, measures nothing.
    #[arg(long)]
    pub quick: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

pub fn run(c: BenchCommand) -> Result<()> {
    let (b, json) = match c {
        BenchCommand::Diffraction(a) => (diffraction::speed(&a.options, &Cli)?, a.json),
        BenchCommand::DiffractionAccuracy(a) => (diffraction::accuracy(&a.options, &Cli)?, a.json),
        BenchCommand::DiffractionMethods(a) => (diffraction::methods(&a.options, &Cli)?, a.json),
        BenchCommand::Gpu(a) => (gpu::gpu(&a.options, &Cli)?, a.json),
        BenchCommand::Render(a) => (render::render(&a.options, &Cli)?, a.json),
        BenchCommand::Grating(a) => {
            let o = bench::GratingBenchOptions {
                repeats: a.repeats,
                python: (!a.no_python).then_some(a.python),
                peer_seconds: a.peer_seconds,
                batch: a.batch,
                quick: a.quick,
            };
            (bench::grating(&o, &Cli)?, a.json)
        }
    };
    crate::output::print_answer(json, || Ok(b.to_json()), || b.text().to_string())
}
