//! `iridis bench …`: speed measured against a peer in the same run, accuracy against the ground truth. Each
//! bench is one library call (`iridis_api::bench`, which Python's `python -m iridis.bench NAME` calls too);
//! this module parses its options and prints its text or JSON. Nothing here is a test: tests never depend on
//! wall-clock time.

use std::path::PathBuf;

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
    Diffraction(DiffractionBench),
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
    DiffractionAccuracy(AccuracyBench),
    /// Reference against ground truth at equal size: the same surfaces (512² and 1024² samples), the same
    /// map size, maps per second of each, all cores.
    #[command(after_help = "\
The ground truth sums the windowed exp(i k w h) directly over every sample for every pixel and wavenumber;
the reference evaluates the Taylor-term DFTs near each pixel's frequency (after computing them once, which
is timed separately). Both run on all cores (rayon over map rows).

Examples:
  iridis bench diffraction-methods                              512² and 1024² patches, 16² maps
  iridis bench diffraction-methods --patch-sizes 256,512 --map-size 24 --json")]
    DiffractionMethods(MethodsBench),
    /// GPU frame times (min, median, p99) of the lookup diffraction map and the thin-film frame, headless.
    Gpu(GpuBench),
    /// Rendering: load and render time of every example scene (default 1024², 1 spp, all cores).
    #[command(after_help = "Examples:\n  iridis bench render\n  iridis bench render --size 512 --spp 4 --json")]
    Render(RenderBench),
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
crossed sine at Λ = 400 nm; one repeat, two wavelengths) to show the command works.

Examples:
  iridis bench grating
  iridis bench grating --python /tmp/rcwa-venv/bin/python --peer-seconds 30
  iridis bench grating --quick --no-python --json")]
    Grating(GratingBench),
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
    #[arg(long)]
    pub no_python: bool,
    /// grcwa's ladder stops after a rung (TE and TM) that took longer than this many seconds.
    #[arg(long, default_value_t = 60.0)]
    pub peer_seconds: f64,
    /// Wavelengths solved in the throughput measurement (one and all threads); the 2-D case takes at most
    /// twice the thread count.
    #[arg(long, default_value_t = 8)]
    pub batch: usize,
    /// Tiny cases (10 nm deep, glass only, the crossed sine at Λ = 400 nm), one repeat, two wavelengths and a
    /// short ladder: shows the command works, measures nothing.
    #[arg(long)]
    pub quick: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct AccuracyBench {
    /// Surfaces to measure (repeat the flag); default: the built-in blazed, cd, elaphe and xenopeltis.
    #[arg(long)]
    pub surface: Vec<String>,
    /// Side of the BRDF maps compared pixel by pixel (the ground truth is slow: keep it small).
    #[arg(long, default_value_t = 24)]
    pub map_size: usize,
    /// Coherence length; the default (a quarter of the patch side) keeps the window inside the patch, where
    /// the two ground truths agree, and the finite one's work small.
    #[arg(long, value_parser = crate::args::positive_length_nm)]
    pub coherence: Option<f64>,
    /// The ground truth compared against: periodic (the methods' own model) or finite (the window cut at the
    /// patch edge).
    #[arg(long, default_value = "periodic")]
    pub aperture: String,
    /// Exposures (RU) at which colours are compared.
    #[arg(long, value_delimiter = ',', default_value = "1,1000,7500")]
    pub exposures: Vec<f64>,
    /// u-v resolution of the tables.
    #[arg(long, default_value_t = 301)]
    pub uv_resolution: usize,
    /// Write the plot of error against the number of Taylor terms here.
    #[arg(long)]
    pub convergence_plot: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct MethodsBench {
    /// Height-field samples per side (65 nm per pixel), one measurement each.
    #[arg(long, value_delimiter = ',', default_value = "512,1024")]
    pub patch_sizes: Vec<usize>,
    /// Side of the BRDF maps both methods render.
    #[arg(long, default_value_t = 16)]
    pub map_size: usize,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct DiffractionBench {
    /// Height-field samples per side.
    #[arg(long, default_value_t = 1024)]
    pub size: usize,
    /// Taylor terms N (terms 0..N).
    #[arg(long, default_value_t = 40)]
    pub terms: usize,
    /// BRDF map sizes for the lookup method.
    #[arg(long, value_delimiter = ',', default_value = "512,1024")]
    pub map_sizes: Vec<usize>,
    /// u-v resolution of the lookup tables.
    #[arg(long, default_value_t = 501)]
    pub uv_resolution: usize,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
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
builtin:elaphe --gt-size 101.

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
pub struct GpuBench {
    /// A scene (TOML or glTF) to time instead of the two shaders.
    pub scene: Option<PathBuf>,
    /// Lookup BRDF map size: 1024x1024 or 1024 (maps are square); with a SCENE, the image size.
    #[arg(long, default_value = "1024x1024")]
    pub size: String,
    /// Frames timed per shader.
    #[arg(long, default_value_t = 500)]
    pub frames: usize,
    /// Stop a shader's loop after this many seconds (software drivers are slow).
    #[arg(long, default_value_t = 30.0)]
    pub max_seconds: f64,
    /// Lookup table (.npz from `iridis precompute`); default: builtin:elaphe precomputed here at 201².
    #[arg(long)]
    pub table: Option<PathBuf>,
    /// Thin-film frame size.
    #[arg(long, default_value = "1920x1080")]
    pub film_size: String,
    /// Thin-film stack; every layer's thickness gets the frame's offset (gradient ±300 nm, SVT ±100 nm).
    #[arg(long, default_value = "air | water 500nm | air")]
    pub stack: String,
    /// Wavelength samples (380-780 nm) of the direct film path that the fast path is timed against.
    #[arg(long, default_value_t = 81, value_name = "N")]
    pub spectral_samples: usize,
    /// Also write the last frames as PNG into this folder: lookup_map.png (1500 RU) and film_frame.png (the
    /// fast path; film_frame_direct.png the direct one).
    #[arg(long)]
    pub save: Option<PathBuf>,
    /// Lookup table encodings to time, comma-separated (f32, f16, chebK, chebK-f16): the first is `lookup`'s,
    /// each is checked against the CPU's f64 lookup (default: the f32 powers and brdf-map's default).
    #[arg(long, default_value = "f32,cheb12")]
    pub table_precision: String,
    /// Surface whose lookup table is built on the CPU and on the GPU (times and agreement).
    #[arg(long, default_value = "builtin:elaphe?size=10um")]
    pub build_surface: String,
    /// u-v resolution of that table.
    #[arg(long, default_value_t = 31)]
    pub build_uv_resolution: usize,
    /// Surface whose ground truth (finite aperture and periodic) is rendered on the GPU and the CPU.
    #[arg(long, default_value = "builtin:elaphe?size=3um&pixel=65nm")]
    pub gt_surface: String,
    /// Size of the ground truth's BRDF map on the GPU.
    #[arg(long, default_value_t = 12)]
    pub gt_size: usize,
    /// Pixels of that map the CPU evaluates (spread over it) for its rate and the CIEDE2000.
    #[arg(long, default_value_t = 32)]
    pub gt_cpu_pixels: usize,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct RenderBench {
    /// Image side (square images).
    #[arg(long, default_value_t = 1024)]
    pub size: u32,
    /// Samples per pixel.
    #[arg(long, default_value_t = 1)]
    pub spp: u32,
    /// Scenes to time (default: every example, embedded in the binary).
    #[arg(long)]
    pub scene: Vec<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

pub fn run(c: BenchCommand) -> Result<()> {
    let (b, json) = match c {
        BenchCommand::Diffraction(a) => {
            let o = diffraction::SpeedOptions {
                size: a.size,
                terms: a.terms,
                map_sizes: a.map_sizes,
                uv_resolution: a.uv_resolution,
            };
            (diffraction::speed(&o, &Cli)?, a.json)
        }
        BenchCommand::DiffractionAccuracy(a) => {
            let o = diffraction::AccuracyOptions {
                surfaces: a.surface,
                map_size: a.map_size,
                coherence_nm: a.coherence,
                aperture: a.aperture,
                exposures: a.exposures,
                uv_resolution: a.uv_resolution,
                convergence_plot: a.convergence_plot,
            };
            (diffraction::accuracy(&o, &Cli)?, a.json)
        }
        BenchCommand::DiffractionMethods(a) => {
            let o = diffraction::MethodsOptions { patch_sizes: a.patch_sizes, map_size: a.map_size };
            (diffraction::methods(&o, &Cli)?, a.json)
        }
        BenchCommand::Gpu(a) => {
            let o = gpu::GpuBenchOptions {
                scene: a.scene,
                size: a.size,
                frames: a.frames,
                max_seconds: a.max_seconds,
                table: a.table,
                film_size: a.film_size,
                stack: a.stack,
                spectral_samples: a.spectral_samples,
                save: a.save,
                table_precision: a.table_precision,
                build_surface: a.build_surface,
                build_uv_resolution: a.build_uv_resolution,
                gt_surface: a.gt_surface,
                gt_size: a.gt_size,
                gt_cpu_pixels: a.gt_cpu_pixels,
            };
            (gpu::gpu(&o, &Cli)?, a.json)
        }
        BenchCommand::Render(a) => {
            let o = render::RenderOptions { size: a.size, spp: a.spp, scenes: a.scene };
            (render::render(&o, &Cli)?, a.json)
        }
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
