//! The GPU path (issue 8): `iridis brdf-map … --gpu` and `iridis bench gpu`, over `iridis-gpu`.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use iridis_api::model::lookup_table;
use iridis_api::{ModelOptions, SurfaceOptions};
use iridis_color::{Encoding, ToneMap, Xyz};
use iridis_diffraction::encoding::TableEncoding;
use iridis_diffraction::evaluator::Evaluator;
use iridis_diffraction::geometry::direction;
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::{Fresnel, Shading};
use iridis_diffraction::{SpectralSetup, TaylorTerms};
use iridis_gpu::film::FilmPathUsed;
use iridis_gpu::scene::SceneFilm;
use iridis_gpu::{FilmFrame, FilmPath, FrameTime, Gpu, GpuFilm, GpuLookup, GpuScene};
use iridis_lab::methods::Method;
use iridis_thinfilm::accuracy::DeltaEStats;
use iridis_thinfilm::spectral::{dense_weights, sampled_weights, FULL_BAND_NM};
use serde_json::json;

use crate::cmd::brdf::{self, BrdfMapArgs, SurfaceOpts};
use crate::progress::{bar, Cli};

/// `iridis render --gpu`: the scene on the GPU with a progress bar over bands of rows; the image, the seconds
/// (upload, compile, render and read-back) and the adapter's name.
pub fn render_scene(
    scene: &iridis_render::Scene,
    w: u32,
    h: u32,
    spp: u32,
    film: SceneFilm,
) -> Result<(iridis_render::Image, f64, String)> {
    let r = iridis_api::gpu::render_scene(scene, w, h, spp, film, &Cli)?;
    Ok((r.image, r.seconds, r.adapter))
}

/// How `--spectral-samples N` shades films on the GPU: colour tables without it, else the direct evaluation at
/// N wavelength samples over 380–780 nm.
pub fn scene_film(spectral_samples: Option<usize>) -> Result<SceneFilm> {
    Ok(match spectral_samples {
        None => SceneFilm::default(),
        Some(n) => {
            sampled_weights(n, FULL_BAND_NM).with_context(|| format!("--spectral-samples {n}"))?;
            SceneFilm { path: FilmPath::Direct, spectral_samples: n }
        }
    })
}

/// Opens the GPU, with the driver hint when there is none.
fn open_gpu() -> Result<Gpu> {
    iridis_api::gpu::open()
}

/// `iridis precompute --gpu` (and a `--gpu` command that needs a table of a SURFACE): the lookup table built on
/// the GPU, with a progress bar.
pub fn build_table(
    terms: &TaylorTerms,
    spectral: &SpectralSetup,
    params: TableParams,
    name: &str,
) -> Result<LookupTable> {
    build_table_on(&open_gpu()?, terms, spectral, params, name)
}

fn build_table_on(
    gpu: &Gpu,
    terms: &TaylorTerms,
    spectral: &SpectralSetup,
    params: TableParams,
    name: &str,
) -> Result<LookupTable> {
    iridis_api::gpu::build_table(gpu, terms, spectral, params, name, &Cli)
}

/// `iridis brdf-map … --gpu`: the lookup method or a ground truth on the GPU, written exactly like the CPU's
/// map (the image is tone-mapped on the CPU from the GPU's XYZ, so `--raw` and `--exr` hold the GPU's numbers).
pub fn run_brdf_map(a: BrdfMapArgs, wi: [f64; 3], encoding: Encoding) -> Result<()> {
    let ground_truth = matches!(a.method.parse::<Method>(), Ok(m) if m.is_ground_truth());
    if a.method != "lookup" && !ground_truth {
        bail!(
            "--gpu renders the lookup method (the paper's shader) and the ground truths (--method ground-truth or \
             ground-truth-periodic); --method {} runs on the CPU only (leave out --gpu)",
            a.method
        );
    }
    if ground_truth {
        if a.table_precision.is_some() {
            bail!("--table-precision applies to the lookup method's table; --method {} has none", a.method);
        }
        return run_ground_truth_map(a, wi, encoding);
    }
    if a.shading.fresnel.trim().starts_with("stack:") || matches!(a.shading.fresnel.trim(), "gold" | "au") {
        bail!(
            "--gpu renders the lookup method, whose Fresnel factor must not depend on λ; a thin-film stack or \
             measured gold as Fresnel source needs --method reference (CPU) or ground-truth (CPU or --gpu)"
        );
    }
    let table_encoding: TableEncoding = match a.table_precision.as_deref() {
        Some(p) => p.parse()?,
        None => TableEncoding::GPU_DEFAULT,
    };
    if table_encoding == TableEncoding::F16 {
        eprintln!(
            "warning: --table-precision f16 stores the powers I_p in half precision, which the lookup sum's \
             cancellation turns into wrong colours (docs/gpu.md); chebK-f16 halves the memory without that"
        );
    }
    let fresnel = iridis_api::fresnel::parse_fresnel(&a.shading.fresnel)?;
    let params = TableParams { uv_resolution: a.uv_resolution, uv_power: a.uv_power };
    let start = std::time::Instant::now();
    let gpu = open_gpu()?;
    let table =
        iridis_api::gpu::lookup_table(&gpu, &a.input, &a.model.options(), params, &a.surface_opts.options(), &Cli)?;
    let tone = ToneMap { exposure_ru: a.exposure, encoding };
    let shading = &a.shading;
    let map = iridis_api::gpu::lookup_map(
        &gpu,
        &table,
        fresnel,
        !shading.no_shadowing,
        shading.fresnel_convention,
        table_encoding,
        wi,
        a.size,
        tone,
    )?;
    brdf::write_map_outputs(&a, &map.output.xyz, tone)?;
    crate::outln!(
        "wrote {} (lookup map on the GPU, {}², table in {}, {:.2} s in all, of which the map {:.2} ms on {})",
        a.output.display(),
        a.size,
        table_encoding.name(),
        start.elapsed().as_secs_f64(),
        map.map_seconds * 1e3,
        map.adapter
    )?;
    Ok(())
}

/// `iridis brdf-map --method ground-truth[-periodic] --gpu`: `|A|²` per pixel and wavenumber on the GPU, the
/// colour (shading, any Fresnel source) on the CPU.
fn run_ground_truth_map(a: BrdfMapArgs, wi: [f64; 3], encoding: Encoding) -> Result<()> {
    let start = std::time::Instant::now();
    let shading = a.shading.shading()?;
    let params = TableParams { uv_resolution: a.uv_resolution, uv_power: a.uv_power };
    let e = iridis_api::brdf::make_evaluator(
        &a.input,
        &a.method,
        &a.model.options(),
        shading,
        params,
        Precision::F64,
        &a.surface_opts.options(),
        &Cli,
    )?;
    let gt = e.as_ground_truth().context("internal: a ground-truth method without a ground truth")?;
    let gpu = open_gpu()?;
    let pb = bar((a.size * a.size) as u64, &format!("{} map (GPU)", e.name()));
    let t = std::time::Instant::now();
    let xyz = iridis_gpu::ground_truth_map(&gpu, gt, wi, a.size, &|d| pb.set_position(d as u64))?;
    pb.finish_and_clear();
    let secs = t.elapsed().as_secs_f64();
    let tone = ToneMap { exposure_ru: a.exposure, encoding };
    brdf::write_map_outputs(&a, &xyz, tone)?;
    crate::outln!(
        "wrote {} ({} map on the GPU, {}², {:.2} s in all, of which the map {secs:.2} s on {})",
        a.output.display(),
        e.name(),
        a.size,
        start.elapsed().as_secs_f64(),
        gpu.adapter_name()
    )?;
    Ok(())
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

fn parse_size(s: &str, what: &str) -> Result<(usize, usize)> {
    let t = s.trim().to_ascii_lowercase();
    let parse = |v: &str| v.trim().parse::<usize>().ok().filter(|n| (1..=16384).contains(n));
    let (w, h) = match t.split_once('x') {
        Some((w, h)) => (parse(w), parse(h)),
        None => (parse(&t), parse(&t)),
    };
    match (w, h) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => bail!("{what} '{s}': write WIDTHxHEIGHT (e.g. 1920x1080) or one number, 1 to 16384"),
    }
}

/// The GPU's own timestamps of every frame, when the adapter has them.
fn gpu_times(times: &[FrameTime]) -> Option<Vec<Duration>> {
    times.iter().map(|t| t.gpu).collect()
}

/// Wall-clock frame times.
fn wall_times(times: &[FrameTime]) -> Vec<Duration> {
    times.iter().map(|t| t.wall).collect()
}

/// min, median, p99 (nearest rank) and mean, in ms.
fn stats(times: &[Duration]) -> [f64; 4] {
    let mut ms: Vec<f64> = times.iter().map(|d| d.as_secs_f64() * 1e3).collect();
    ms.sort_by(f64::total_cmp);
    let rank = |q: f64| ms[((q * ms.len() as f64).ceil() as usize).clamp(1, ms.len()) - 1];
    [ms[0], rank(0.5), rank(0.99), ms.iter().sum::<f64>() / ms.len() as f64]
}

fn time_frames(
    frames: usize,
    max_seconds: f64,
    mut run: impl FnMut(usize) -> Result<FrameTime>,
) -> Result<Vec<FrameTime>> {
    run(0)?; // warm-up: pipeline caches, first-touch of the buffers
    let start = std::time::Instant::now();
    let mut times = Vec::with_capacity(frames);
    while times.len() < frames.max(1) {
        times.push(run(times.len())?);
        if start.elapsed().as_secs_f64() > max_seconds {
            break;
        }
    }
    Ok(times)
}

/// Up to `n` pixel indices spread over `total`.
fn sample(total: usize, n: usize) -> Vec<usize> {
    let step = total.div_ceil(n).max(1);
    (0..total).step_by(step).collect()
}

/// Mean and 99th percentile of CIEDE2000 between displayed colours.
fn delta_e(a: &[Xyz], b: &[Xyz], exposure: f64) -> (f64, f64) {
    let [mean, p99, _] = delta_e_stats(a, b, exposure);
    (mean, p99)
}

/// Mean, 99th percentile and maximum of CIEDE2000 between displayed colours.
fn delta_e_stats(a: &[Xyz], b: &[Xyz], exposure: f64) -> [f64; 3] {
    let s = DeltaEStats::between(a, b, exposure);
    [s.mean, s.p99, s.max]
}

/// A smooth, deterministic grey texture (value noise, three octaves) for spatially varying thickness.
fn svt_noise(width: usize, height: usize) -> Vec<f32> {
    let hash = |x: i64, y: i64, o: i64| {
        let mut h = (x.wrapping_mul(374_761_393) ^ y.wrapping_mul(668_265_263) ^ o.wrapping_mul(2_147_483_647)) as u64;
        h = (h ^ (h >> 13)).wrapping_mul(1_274_126_177);
        ((h ^ (h >> 16)) & 0xffff) as f64 / 65535.0
    };
    let smooth = |t: f64| t * t * (3.0 - 2.0 * t);
    let mut out = Vec::with_capacity(width * height);
    for r in 0..height {
        for c in 0..width {
            let mut v = 0.0;
            let mut amp = 0.5;
            let mut scale = 1.0 / 160.0;
            for o in 0..3 {
                let (x, y) = (c as f64 * scale, r as f64 * scale);
                let (x0, y0) = (x.floor(), y.floor());
                let (fx, fy) = (smooth(x - x0), smooth(y - y0));
                let (xi, yi) = (x0 as i64, y0 as i64);
                let a = hash(xi, yi, o) * (1.0 - fx) + hash(xi + 1, yi, o) * fx;
                let b = hash(xi, yi + 1, o) * (1.0 - fx) + hash(xi + 1, yi + 1, o) * fx;
                v += amp * (a * (1.0 - fy) + b * fy);
                amp *= 0.5;
                scale *= 2.0;
            }
            out.push((v / 0.875).clamp(0.0, 1.0) as f32);
        }
    }
    out
}

/// `iridis bench gpu SCENE`: frame times of the scene renderer against one CPU render of the same image.
fn bench_scene(a: &GpuBench, path: &std::path::Path) -> Result<()> {
    let (w, h) = parse_size(&a.size, "--size")?;
    let (w, h) = (w as u32, h as u32);
    let scene = crate::cmd::render::load(path)?;
    let gpu = open_gpu()?;
    let adapter = gpu.adapter_name();
    let a_samples = a.spectral_samples;
    let t = std::time::Instant::now();
    let g = GpuScene::new(&gpu, &scene)?;
    let setup_s = t.elapsed().as_secs_f64();
    let tone = ToneMap { exposure_ru: scene.output.exposure, encoding: scene.output.encoding };
    let frame = g.frame(w, h, 1, tone)?;
    if !a.json {
        crate::outln!("adapter: {adapter}")?;
        if gpu.is_software() {
            crate::outln!("  (a software adapter: these times measure the CPU, not a GPU)")?;
        }
        crate::outln!("scene {}: {w}×{h}, 1 spp; upload and shader compilation {setup_s:.2} s", path.display())?;
    }
    let times = time_frames(a.frames, a.max_seconds, |_| Ok(frame.run(&g)?))?;
    let img = frame.read_image(&g)?;
    // The same image with the films evaluated directly (the reference path), where the scene has films.
    let direct = if g.has_films() {
        let film = SceneFilm { path: FilmPath::Direct, spectral_samples: a.spectral_samples };
        let d = GpuScene::with_film(&gpu, &scene, film)?;
        let f = d.frame(w, h, 1, tone)?;
        let t = time_frames(a.frames, a.max_seconds, |_| Ok(f.run(&d)?))?;
        Some((t, f.read_image(&d)?))
    } else {
        None
    };
    let (cpu, cpu_s) = crate::cmd::render::render_with_bar(&scene, w, h, 1);
    let xyz = |i: &iridis_render::Image| -> Vec<Xyz> {
        i.data.iter().map(|p| Xyz::from_linear_srgb(p.map(|c| c as f64))).collect()
    };
    let (de_mean, de_p99) = delta_e(&xyz(&img), &xyz(&cpu), scene.output.exposure);
    let [mn, med, p99, mean] = stats(&wall_times(&times));
    let gts = gpu_times(&times).map(|t| stats(&t));
    let name = path.display().to_string();
    let direct = direct.map(|(t, di)| {
        let s = stats(&wall_times(&t));
        let de = DeltaEStats::between(&xyz(&img), &xyz(&di), scene.output.exposure);
        (t.len(), s, gpu_times(&t).map(|t| stats(&t)), de)
    });
    if let Some(dir) = &a.save {
        crate::output::write_png_rgb8(&dir.join("scene_gpu.png"), w, h, &frame.read_rgb8(&g)?)?;
    }
    if a.json {
        return crate::output::print_json(&json!({
            "adapter": adapter,
            "software_adapter": gpu.is_software(),
            "scene": name,
            "size": [w, h],
            "spp": 1,
            "setup_s": setup_s,
            "frames": times.len(),
            "ms": {"min": mn, "median": med, "p99": p99, "mean": mean},
            "gpu_timestamp_ms": gts.map(|[a, b, c, d]| json!({"min": a, "median": b, "p99": c, "mean": d})),
            "fps_median": 1e3 / med,
            "cpu": {"threads": rayon::current_num_threads(), "render_s": cpu_s, "cpu_over_gpu_median": cpu_s * 1e3 / med},
            "vs_cpu": {"pixels": (w * h), "exposure_ru": scene.output.exposure, "delta_e00_mean": de_mean, "delta_e00_p99": de_p99},
            "film_direct": direct.map(|(n, [a, b, c, d], g, de)| json!({
                "spectral_samples": a_samples,
                "frames": n,
                "ms": {"min": a, "median": b, "p99": c, "mean": d},
                "gpu_timestamp_ms": g.map(|[a, b, c, d]| json!({"min": a, "median": b, "p99": c, "mean": d})),
                "direct_over_table_median": b / med,
                "vs_table": {"delta_e00_mean": de.mean, "delta_e00_p99": de.p99, "delta_e00_max": de.max},
            })),
        }));
    }
    crate::outln!(
        "  {} frames: min {mn:.2} ms, median {med:.2} ms, p99 {p99:.2} ms ({:.1} fps at the median)",
        times.len(),
        1e3 / med
    )?;
    print_gpu_times(gts)?;
    crate::outln!(
        "  CPU renderer, same image ({} threads): {:.1} ms — CPU time / GPU median frame = {:.2}",
        rayon::current_num_threads(),
        cpu_s * 1e3,
        cpu_s * 1e3 / med
    )?;
    crate::outln!(
        "  vs CPU ({} pixels at {} RU): ΔE00 mean {de_mean:.4}, p99 {de_p99:.4}",
        w * h,
        scene.output.exposure
    )?;
    if let Some((n, [dmn, dmed, dp99, _], g, de)) = direct {
        crate::outln!(
            "  films evaluated directly ({a_samples} wavelength samples per hit), {n} frames: min {dmn:.2} ms, median \
             {dmed:.2} ms, p99 {dp99:.2} ms — {:.2}× the colour-table frame",
            dmed / med
        )?;
        print_gpu_times(g)?;
        crate::outln!("  colour tables vs direct: {de}")?;
    }
    Ok(())
}

pub fn bench(a: GpuBench) -> Result<()> {
    if !(a.max_seconds.is_finite() && a.max_seconds > 0.0) {
        bail!("--max-seconds {} must be positive", a.max_seconds);
    }
    let direct_weights = sampled_weights(a.spectral_samples, FULL_BAND_NM)
        .with_context(|| format!("--spectral-samples {}", a.spectral_samples))?;
    if let Some(p) = a.scene.clone() {
        return bench_scene(&a, &p);
    }
    let (mw, mh) = parse_size(&a.size, "--size")?;
    if mw != mh {
        bail!("--size {}: BRDF maps are square (the unit disk of view directions); use e.g. 1024x1024", a.size);
    }
    let (fw, fh) = parse_size(&a.film_size, "--film-size")?;
    if !(a.max_seconds.is_finite() && a.max_seconds > 0.0) {
        bail!("--max-seconds {} must be positive", a.max_seconds);
    }
    let stack: iridis_thinfilm::Stack = a.stack.parse().with_context(|| format!("--stack '{}'", a.stack))?;
    let encodings: Vec<TableEncoding> = a
        .table_precision
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.parse::<TableEncoding>().with_context(|| format!("--table-precision '{}'", a.table_precision)))
        .collect::<Result<_>>()?;
    if encodings.is_empty() {
        bail!("--table-precision: give at least one of f32, f16, chebK, chebK-f16");
    }
    if !(8..=4096).contains(&a.gt_size) || a.gt_cpu_pixels == 0 {
        bail!("--gt-size {} must be 8–4096 pixels and --gt-cpu-pixels at least 1", a.gt_size);
    }
    let gpu = open_gpu()?;
    let adapter = gpu.adapter_name();
    if !a.json {
        crate::outln!("adapter: {adapter}")?;
        if gpu.is_software() {
            crate::outln!("  (a software adapter: these times measure the CPU, not a GPU)")?;
        }
    }

    // Lookup diffraction.
    let model = ModelOptions::default();
    let table = match &a.table {
        Some(p) => LookupTable::load(p)?,
        None => {
            if !a.json {
                crate::outln!("building the lookup table of builtin:elaphe at 201² (pass --table to use your own) …")?;
            }
            let none = SurfaceOptions::default();
            lookup_table("builtin:elaphe", &model, TableParams { uv_resolution: 201, uv_power: 5.0 }, &none, &Cli)?
        }
    };
    let fresnel = Fresnel::default();
    let lookup = GpuLookup::encoded(&gpu, &table, fresnel.clone(), true, encodings[0], u64::MAX)?;
    let tone = ToneMap { exposure_ru: 1500.0, encoding: Encoding::Srgb };
    let frame = lookup.frame(mw, tone)?;
    let frames = a.frames;
    let light = |i: usize| direction(30f64.to_radians(), i as f64 * std::f64::consts::TAU / frames.max(1) as f64);
    let mut last_wi = light(0);
    let map_times = time_frames(frames, a.max_seconds, |i| {
        last_wi = light(i);
        Ok(frame.run(last_wi)?)
    })?;
    let map = frame.read()?;
    let cpu = Lookup::new(
        Arc::new(table.clone()),
        Shading { fresnel: Arc::new(fresnel.clone()), ..Shading::default() },
        Precision::F64,
    )?;
    let px: Vec<usize> = sample(mw * mw, 4096)
        .into_iter()
        .filter(|&i| iridis_diffraction::map::view_direction(i % mw, i / mw, mw).is_some())
        .collect();
    let cpu_px: Vec<Xyz> = px
        .iter()
        .map(|&i| {
            let wr = iridis_diffraction::map::view_direction(i % mw, i / mw, mw).unwrap_or([0.0, 0.0, 1.0]);
            cpu.xyz(last_wi, wr)
        })
        .collect();
    let gpu_px: Vec<Xyz> = px.iter().map(|&i| map.xyz[i]).collect();
    let map_de = delta_e_stats(&gpu_px, &cpu_px, 1500.0);
    let [mn, med, p99, mean] = stats(&wall_times(&map_times));
    let map_gpu = gpu_times(&map_times).map(|t| stats(&t));
    // The other encodings of the table, each timed and checked the same way in this run.
    let mut encoded = vec![EncodingRun {
        encoding: encodings[0],
        table_mb: lookup.table_bytes() as f64 / 1e6,
        frames: map_times.len(),
        ms: [mn, med, p99, mean],
        delta_e00: map_de,
    }];
    for &e in &encodings[1..] {
        let l = GpuLookup::encoded(&gpu, &table, fresnel.clone(), true, e, u64::MAX)?;
        let f = l.frame(mw, tone)?;
        let times = time_frames(frames, a.max_seconds, |i| Ok(f.run(light(i))?))?;
        let m = f.read()?;
        // The last frame's light (time_frames warms up with frame 0, then runs frames 0, 1, …).
        let last = light(times.len().saturating_sub(1));
        let cpu_e: Vec<Xyz> = px
            .iter()
            .map(|&i| {
                let wr = iridis_diffraction::map::view_direction(i % mw, i / mw, mw).unwrap_or([0.0, 0.0, 1.0]);
                cpu.xyz(last, wr)
            })
            .collect();
        let gpu_e: Vec<Xyz> = px.iter().map(|&i| m.xyz[i]).collect();
        encoded.push(EncodingRun {
            encoding: e,
            table_mb: l.table_bytes() as f64 / 1e6,
            frames: times.len(),
            ms: stats(&wall_times(&times)),
            delta_e00: delta_e_stats(&gpu_e, &cpu_e, 1500.0),
        });
    }

    // Thin film: the fast path (colour table) and the direct path, in the same run.
    let dense = dense_weights();
    let film_frame = FilmFrame {
        width: fw,
        height: fh,
        angle_rad: (0.0, 80f64.to_radians()),
        offset_nm: (-300.0, 300.0),
        svt: Some((100.0, svt_noise(fw, fh))),
    };
    let film_tone = ToneMap { exposure_ru: 5.0, encoding: Encoding::Srgb };
    let fast = GpuFilm::new(&gpu, &stack, &dense)?;
    let fast_run = fast.frame(&film_frame, film_tone)?;
    let fast_times = time_frames(frames, a.max_seconds, |_| Ok(fast_run.run()?))?;
    let fast_out = fast_run.read()?;
    let direct = GpuFilm::new(&gpu, &stack, &direct_weights)?.with_path(FilmPath::Direct);
    let direct_run = direct.frame(&film_frame, film_tone)?;
    let direct_times = time_frames(frames, a.max_seconds, |_| Ok(direct_run.run()?))?;
    let direct_out = direct_run.read()?;
    let fpx = sample(fw * fh, 2048);
    let cpu_dense = iridis_gpu::film::cpu_reference(&stack, &dense, &film_frame, &fpx)?;
    let cpu_direct = if a.spectral_samples == 81 {
        cpu_dense.clone()
    } else {
        iridis_gpu::film::cpu_reference(&stack, &direct_weights, &film_frame, &fpx)?
    };
    let reflected = |v: &[(Xyz, Xyz)]| -> Vec<Xyz> { v.iter().map(|p| p.0).collect() };
    let at = |out: &[Xyz]| -> Vec<Xyz> { fpx.iter().map(|&i| out[i]).collect() };
    let ymax = cpu_dense.iter().map(|x| x.0.y).fold(1e-6f64, f64::max);
    let fast_de = delta_e(&at(&fast_out.reflected), &reflected(&cpu_dense), 1.0 / ymax);
    let direct_de = delta_e(&at(&direct_out.reflected), &reflected(&cpu_direct), 1.0 / ymax);
    // The fast path against the direct one over every pixel, the brightest direct pixel at Y = 1.
    let frame_ymax = direct_out.reflected.iter().map(|x| x.y).fold(1e-6f64, f64::max);
    let vs_direct = DeltaEStats::between(&fast_out.reflected, &direct_out.reflected, 1.0 / frame_ymax);
    let [fmn, fmed, fp99, fmean] = stats(&wall_times(&fast_times));
    let fast_gpu = gpu_times(&fast_times).map(|t| stats(&t));
    let [dmn, dmed, dp99, dmean] = stats(&wall_times(&direct_times));
    let direct_gpu = gpu_times(&direct_times).map(|t| stats(&t));
    let (grid, build_ms, fallback) = match fast_run.path() {
        FilmPathUsed::Table { grid, build } => (Some(*grid), Some(build.as_secs_f64() * 1e3), None),
        FilmPathUsed::Direct { why } => (None, None, why.clone()),
    };
    let ms_json = |s: Option<[f64; 4]>| s.map(|[a, b, c, d]| json!({"min": a, "median": b, "p99": c, "mean": d}));
    if let Some(dir) = &a.save {
        crate::output::write_png_rgb8(&dir.join("lookup_map.png"), mw as u32, mw as u32, &map.rgb8)?;
        crate::output::write_png_rgb8(&dir.join("film_frame.png"), fw as u32, fh as u32, &fast_out.rgb8)?;
        crate::output::write_png_rgb8(&dir.join("film_frame_direct.png"), fw as u32, fh as u32, &direct_out.rgb8)?;
    }

    if a.json {
        let build = bench_table_build(&gpu, &a, true)?;
        let truth = bench_ground_truth(&gpu, &a, true)?;
        return crate::output::print_json(&json!({
            "adapter": adapter,
            "software_adapter": gpu.is_software(),
            "lookup": {
                "table": a.table.as_ref().map(|p| p.display().to_string()).unwrap_or_else(|| "builtin:elaphe (201²)".into()),
                "uv_resolution": table.meta.uv_resolution,
                "taylor_terms": table.meta.taylor_terms,
                "table_mb": lookup.table_bytes() as f64 / 1e6,
                "size": [mw, mh],
                "frames": map_times.len(),
                "ms": {"min": mn, "median": med, "p99": p99, "mean": mean},
                "gpu_timestamp_ms": ms_json(map_gpu),
                "fps_median": 1e3 / med,
                "vs_cpu": {"pixels": px.len(), "exposure_ru": 1500.0, "delta_e00_mean": map_de[0], "delta_e00_p99": map_de[1]},
                "encodings": encoded.iter().map(|e| json!({
                    "encoding": e.encoding.name(),
                    "table_mb": e.table_mb,
                    "frames": e.frames,
                    "ms": ms_json(Some(e.ms)),
                    "fps_median": 1e3 / e.ms[1],
                    "median_over_first": e.ms[1] / encoded[0].ms[1],
                    "delta_e00_mean": e.delta_e00[0],
                    "delta_e00_p99": e.delta_e00[1],
                    "delta_e00_max": e.delta_e00[2],
                })).collect::<Vec<_>>(),
            },
            "film": {
                "stack": stack.to_string(),
                "size": [fw, fh],
                "table": {
                    "cos_nodes": grid.map(|g| g.cos_nodes),
                    "offset_nodes": grid.map(|g| g.offset_nodes),
                    "offset_nm": grid.map(|g| [g.offset_nm.0, g.offset_nm.1]),
                    "build_ms": build_ms,
                    "fallback": fallback,
                    "frames": fast_times.len(),
                    "ms": {"min": fmn, "median": fmed, "p99": fp99, "mean": fmean},
                    "gpu_timestamp_ms": ms_json(fast_gpu),
                    "fps_median": 1e3 / fmed,
                    "vs_cpu": {"pixels": fpx.len(), "exposure_ru": 1.0 / ymax, "delta_e00_mean": fast_de.0, "delta_e00_p99": fast_de.1},
                    "vs_direct": {"pixels": fw * fh, "exposure_ru": 1.0 / frame_ymax, "delta_e00_mean": vs_direct.mean, "delta_e00_p99": vs_direct.p99, "delta_e00_max": vs_direct.max},
                },
                "direct": {
                    "wavelengths": direct_weights.wavelengths_nm().len(),
                    "frames": direct_times.len(),
                    "ms": {"min": dmn, "median": dmed, "p99": dp99, "mean": dmean},
                    "gpu_timestamp_ms": ms_json(direct_gpu),
                    "fps_median": 1e3 / dmed,
                    "vs_cpu": {"pixels": fpx.len(), "exposure_ru": 1.0 / ymax, "delta_e00_mean": direct_de.0, "delta_e00_p99": direct_de.1},
                },
                "direct_over_table_median": dmed / fmed,
            },
            "table_build": build,
            "ground_truth": truth,
        }));
    }
    crate::outln!(
        "lookup diffraction, {mw}×{mh} map, table {}² × {} powers ({:.1} MB), {} frames:",
        table.meta.uv_resolution,
        table.powers(),
        lookup.table_bytes() as f64 / 1e6,
        map_times.len()
    )?;
    crate::outln!(
        "  frame time min {mn:.2} ms, median {med:.2} ms, p99 {p99:.2} ms ({:.1} fps at the median)",
        1e3 / med
    )?;
    print_gpu_times(map_gpu)?;
    crate::outln!(
        "  vs CPU (lookup, f64; {} pixels at 1500 RU): ΔE00 mean {:.4}, p99 {:.4}",
        px.len(),
        map_de[0],
        map_de[1]
    )?;
    if encoded.len() > 1 {
        crate::outln!("  table encodings (same map, same pixels; ΔE00 against the CPU's f64 lookup at 1500 RU):")?;
        for e in &encoded {
            crate::outln!(
                "    {:<10} {:>8.1} MB  median {:>9.2} ms ({:.2}× the first)  ΔE00 mean {:.4}, p99 {:.4}, max {:.4}",
                e.encoding.name(),
                e.table_mb,
                e.ms[1],
                e.ms[1] / encoded[0].ms[1],
                e.delta_e00[0],
                e.delta_e00[1],
                e.delta_e00[2]
            )?;
        }
    }
    crate::outln!("thin film {stack}, {fw}×{fh}, gradient + SVT:")?;
    crate::outln!("  fast path: {}; {} frames:", fast_run.path(), fast_times.len())?;
    crate::outln!(
        "    frame time min {fmn:.2} ms, median {fmed:.2} ms, p99 {fp99:.2} ms ({:.1} fps at the median)",
        1e3 / fmed
    )?;
    print_gpu_times_at(fast_gpu, "    ")?;
    crate::outln!(
        "    vs CPU (Stack::evaluate_offset, f64, 81 samples; {} pixels): ΔE00 mean {:.4}, p99 {:.4}",
        fpx.len(),
        fast_de.0,
        fast_de.1
    )?;
    crate::outln!("    vs the direct path (every pixel): {vs_direct}")?;
    crate::outln!(
        "  direct path, {} wavelength samples per pixel; {} frames:",
        direct_weights.wavelengths_nm().len(),
        direct_times.len()
    )?;
    crate::outln!(
        "    frame time min {dmn:.2} ms, median {dmed:.2} ms, p99 {dp99:.2} ms ({:.1} fps at the median)",
        1e3 / dmed
    )?;
    print_gpu_times_at(direct_gpu, "    ")?;
    crate::outln!(
        "    vs CPU (f64, the same samples; {} pixels): ΔE00 mean {:.4}, p99 {:.4}",
        fpx.len(),
        direct_de.0,
        direct_de.1
    )?;
    crate::outln!("  direct / fast median frame time: {:.1}×", dmed / fmed)?;
    bench_table_build(&gpu, &a, false)?;
    bench_ground_truth(&gpu, &a, false)?;
    Ok(())
}

/// One table encoding's run of the lookup map.
struct EncodingRun {
    encoding: TableEncoding,
    table_mb: f64,
    frames: usize,
    /// min, median, p99, mean (ms).
    ms: [f64; 4],
    /// Against the CPU's f64 lookup: mean, p99, max.
    delta_e00: [f64; 3],
}

/// The lookup table of `--build-surface` built on the CPU (all cores) and on the GPU in the same run: times,
/// speed-up and the GPU table's error against the CPU's (`iridis_gpu::table_build::table_error`).
fn bench_table_build(gpu: &Gpu, a: &GpuBench, quiet: bool) -> Result<serde_json::Value> {
    let model = ModelOptions::default();
    let patch = iridis_api::surface::load_patch(&a.build_surface, &SurfaceOptions::default(), &Cli)?;
    let spectral = iridis_api::model::spectral_setup(&model, &Cli)?;
    let terms = iridis_api::model::taylor_terms(&patch, &model, &Cli)?;
    let params = TableParams { uv_resolution: a.build_uv_resolution, uv_power: 5.0 };
    let t = std::time::Instant::now();
    let cpu = iridis_api::model::build_table(&terms, &spectral, params, &a.build_surface, &Cli)?;
    let cpu_s = t.elapsed().as_secs_f64();
    let t = std::time::Instant::now();
    let on_gpu = iridis_gpu::build_table(gpu, &terms, &spectral, params, &a.build_surface, &|_| {})?;
    let gpu_s = t.elapsed().as_secs_f64();
    let err = iridis_gpu::table_build::table_error(&cpu, &on_gpu);
    if !quiet {
        crate::outln!(
            "lookup table build, {} ({}×{} samples, N = {}), {}² grid × {} wavelengths:",
            a.build_surface,
            patch.cols,
            patch.rows,
            terms.n_max,
            params.uv_resolution,
            spectral.wavelengths().len()
        )?;
        crate::outln!(
            "  CPU ({} threads, f64) {cpu_s:.2} s, GPU (f32, with upload, compilation and read-back) {gpu_s:.2} s: \
             CPU/GPU = {:.2}",
            rayon::current_num_threads(),
            cpu_s / gpu_s
        )?;
        crate::outln!(
            "  GPU table vs CPU: largest error relative to each power's largest |I_p| {:.2e}; relative to the \
             largest term 2^p |I_p| of the sum {:.2e}",
            err.per_power,
            err.of_sum
        )?;
    }
    Ok(json!({
        "surface": a.build_surface,
        "samples": [patch.cols, patch.rows],
        "taylor_terms": terms.n_max,
        "uv_resolution": params.uv_resolution,
        "wavelengths": spectral.wavelengths().len(),
        "cpu_threads": rayon::current_num_threads(),
        "cpu_s": cpu_s,
        "gpu_s": gpu_s,
        "cpu_over_gpu": cpu_s / gpu_s,
        "max_rel_error_per_power": err.per_power,
        "max_rel_error_of_sum": err.of_sum,
    }))
}

/// The ground truth of `--gt-surface` (both apertures) as a `--gt-size` BRDF map on the GPU, against the CPU on
/// up to `--gt-cpu-pixels` of its pixels in the same run: per-pixel rates, speed-up, CIEDE2000 at 1500 RU.
fn bench_ground_truth(gpu: &Gpu, a: &GpuBench, quiet: bool) -> Result<serde_json::Value> {
    use iridis_diffraction::{Aperture, GroundTruth};
    use rayon::prelude::*;
    let patch = iridis_api::surface::load_patch(&a.gt_surface, &SurfaceOptions::default(), &Cli)?;
    let coherence = iridis_api::model::coherence_for(&patch, None, &Cli);
    let spectral = SpectralSetup::default();
    let samples = 2 * spectral.wavelengths().len() - 1;
    let size = a.gt_size;
    let wi = direction(30f64.to_radians(), 0.0);
    let disk: Vec<usize> = (0..size * size)
        .filter(|&i| iridis_diffraction::map::view_direction(i % size, i / size, size).is_some())
        .collect();
    let picked: Vec<usize> = sample(disk.len(), a.gt_cpu_pixels).into_iter().map(|k| disk[k]).collect();
    if !quiet {
        crate::outln!(
            "ground truth, {} ({}×{} samples, coherence {:.1} µm), {size}² map ({} pixels) × {samples} wavenumbers:",
            a.gt_surface,
            patch.cols,
            patch.rows,
            coherence / 1000.0,
            disk.len()
        )?;
    }
    let mut out = serde_json::Map::new();
    out.insert("surface".into(), json!(a.gt_surface));
    out.insert("samples".into(), json!([patch.cols, patch.rows]));
    out.insert("size".into(), json!(size));
    out.insert("pixels".into(), json!(disk.len()));
    out.insert("wavenumbers".into(), json!(samples));
    for aperture in [Aperture::Finite, Aperture::Periodic] {
        let gt = GroundTruth::with_aperture(&patch, coherence, Shading::default(), &spectral, samples, aperture)?;
        let t = std::time::Instant::now();
        let map = iridis_gpu::ground_truth_map(gpu, &gt, wi, size, &|_| {})?;
        let gpu_s = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        let cpu: Vec<Xyz> = picked
            .par_iter()
            .map(|&i| {
                let wr = iridis_diffraction::map::view_direction(i % size, i / size, size).unwrap_or([0.0, 0.0, 1.0]);
                gt.xyz(wi, wr)
            })
            .collect();
        let cpu_s = t.elapsed().as_secs_f64();
        let gpu_px: Vec<Xyz> = picked.iter().map(|&i| map[i]).collect();
        let de = delta_e_stats(&gpu_px, &cpu, 1500.0);
        let (gpu_rate, cpu_rate) = (disk.len() as f64 / gpu_s, picked.len() as f64 / cpu_s);
        if !quiet {
            crate::outln!(
                "  {:<8} GPU {gpu_s:.2} s ({gpu_rate:.1} pixels/s, with upload and compilation); CPU ({} threads) \
                 {:.1} pixels/s on {} of them: GPU/CPU = {:.2}; ΔE00 at 1500 RU mean {:.4}, p99 {:.4}, max {:.4}",
                aperture.name(),
                rayon::current_num_threads(),
                cpu_rate,
                picked.len(),
                gpu_rate / cpu_rate,
                de[0],
                de[1],
                de[2]
            )?;
        }
        out.insert(
            aperture.name().into(),
            json!({
                "gpu_s": gpu_s,
                "gpu_pixels_per_s": gpu_rate,
                "cpu_pixels": picked.len(),
                "cpu_s": cpu_s,
                "cpu_pixels_per_s": cpu_rate,
                "gpu_over_cpu": gpu_rate / cpu_rate,
                "exposure_ru": 1500.0,
                "delta_e00_mean": de[0],
                "delta_e00_p99": de[1],
                "delta_e00_max": de[2],
            }),
        );
    }
    let phase = iridis_gpu::ground_truth::phase_accuracy(gpu, 100_000)?;
    if !quiet {
        crate::outln!("  phase arithmetic of the shader against f64 (100 000 cases): largest error {phase:.1e} rad")?;
    }
    out.insert("phase_error_rad".into(), json!(phase));
    Ok(serde_json::Value::Object(out))
}

fn print_gpu_times(s: Option<[f64; 4]>) -> Result<()> {
    print_gpu_times_at(s, "  ")
}

fn print_gpu_times_at(s: Option<[f64; 4]>, indent: &str) -> Result<()> {
    match s {
        Some([mn, med, p99, _]) => {
            crate::outln!("{indent}GPU timestamps of the pass: min {mn:.2} ms, median {med:.2} ms, p99 {p99:.2} ms")
        }
        None => crate::outln!("{indent}(the adapter has no timestamp queries: wall clock only)"),
    }
}

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Opens a window that renders on the GPU (the shaders of `iridis render --gpu` and `brdf-map --gpu`): a
scene (.toml, .gltf, .glb), reloaded when the file changes, or the BRDF map of a lookup table (.npz from
`iridis precompute`) or of a SURFACE (its table is built first). The panel sets the exposure (RU) and gamma,
the thin films' thickness, layer IOR and SVT strength, and shows each diffraction table's BRDF map at a
chosen incidence; the frame time is shown below. Drag to orbit, right-drag (or shift-drag) to move the
light, wheel to zoom, R resets, H toggles the help, Esc quits. On a BRDF map, drag to turn the light's
incidence and the wheel sets the exposure.

Needs a display and a Vulkan driver; on a headless machine: xvfb-run -a iridis view SCENE.
--check drives the window with synthetic input (a drag to orbit, a right-drag for the light, the wheel,
the H key), checks that each changed what is shown, saves a screenshot of the window and exits (non-zero
if an input did nothing): the scripted check that CI runs under Xvfb with lavapipe.

Examples:
  iridis view examples/snake_elaphe.toml
  iridis view examples/soap_bubble.toml
  iridis view elaphe.npz                       BRDF map of a precomputed table
  iridis view builtin:blazed                   builds a 201² table first
  xvfb-run -a iridis view examples/soap_bubble.toml --check viewer.png --json")]
pub struct ViewArgs {
    /// A scene (.toml, .gltf, .glb), a lookup table (.npz) or a SURFACE.
    pub input: String,
    /// u-v resolution of the table built when INPUT is a surface.
    #[arg(long, default_value_t = 201)]
    pub uv_resolution: usize,
    /// Scripted check: drive the window with synthetic input, save a screenshot (PNG) here, exit.
    #[arg(long)]
    pub check: Option<PathBuf>,
    /// With --check: print the check's report as JSON.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub surface_opts: SurfaceOpts,
}

fn load_for_view(p: &std::path::Path) -> std::result::Result<iridis_render::Scene, String> {
    iridis_render::load_scene(p).map_err(|e| e.to_string())
}

pub fn run_view(a: ViewArgs) -> Result<()> {
    use iridis_gpu::viewer::{run, ViewInput, ViewOptions};
    crate::output::declare_opt("--check", a.check.as_deref(), &["png"])?;
    let path = std::path::Path::new(&a.input);
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let input = if matches!(ext.as_deref(), Some("toml" | "gltf" | "glb")) {
        if !path.exists() {
            bail!("scene {} does not exist", path.display());
        }
        ViewInput::Scene(path.to_path_buf())
    } else {
        let params = TableParams { uv_resolution: a.uv_resolution, uv_power: 5.0 };
        let table = lookup_table(&a.input, &ModelOptions::default(), params, &a.surface_opts.options(), &Cli)?;
        ViewInput::Table { table: Box::new(table), name: a.input.clone() }
    };
    let report = run(input, ViewOptions { check: a.check.clone() }, load_for_view).map_err(anyhow::Error::msg)?;
    let (Some(r), Some(shot)) = (report, &a.check) else { return Ok(()) };
    if let Some((w, h, rgba)) = &r.screenshot {
        let rgb: Vec<u8> = rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
        crate::output::write_png_rgb8(shot, *w as u32, *h as u32, &rgb)?;
    }
    let ok = r.steps.len() == 4 && r.steps.iter().all(|(_, d)| *d > 0.0) && r.texture_equals_frame;
    if a.json {
        crate::output::print_json(&json!({
            "adapter": r.adapter,
            "frames": r.frames,
            "frame_ms_median": r.frame_ms,
            "gpu_ms_median": r.gpu_ms,
            "readback_ms_median": r.readback_ms,
            "texture_equals_frame": r.texture_equals_frame,
            "steps": r.steps.iter().map(|(n, d)| json!({"input": n, "change": d})).collect::<Vec<_>>(),
            "screenshot": shot.display().to_string(),
            "ok": ok,
        }))?;
    } else {
        crate::outln!("viewer check on {}: {} frames, median {:.1} ms", r.adapter, r.frames, r.frame_ms)?;
        if let Some(g) = r.gpu_ms {
            crate::outln!("  render pass (GPU timestamps): median {g:.2} ms")?;
        }
        crate::outln!(
            "  frames shown without a readback: the texture {} the frame; a readback would add a median {:.2} ms",
            if r.texture_equals_frame { "equals" } else { "DIFFERS FROM" },
            r.readback_ms
        )?;
        for (n, d) in &r.steps {
            crate::outln!("  {n}: change {d:.3}")?;
        }
        crate::outln!("wrote {}", shot.display())?;
    }
    if !r.texture_equals_frame {
        bail!("the texture the window drew differs from the rendered frame (a present-pass defect)");
    }
    if !ok {
        bail!("the viewer did not answer every input (a change of 0 above)");
    }
    Ok(())
}
