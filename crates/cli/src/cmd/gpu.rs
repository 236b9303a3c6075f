//! The GPU path (issue 8): `iridis brdf-map … --gpu` and `iridis bench gpu`, over `iridis-gpu`.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use iridis_api::model::lookup_table;
use iridis_api::{ModelOptions, SurfaceOptions};
use iridis_color::{Encoding, SpectralWeights, ToneMap, Xyz};
use iridis_diffraction::evaluator::Evaluator;
use iridis_diffraction::geometry::direction;
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::{Fresnel, Shading};
use iridis_gpu::{FilmFrame, FrameTime, Gpu, GpuFilm, GpuLookup, GpuScene};
use serde_json::json;

use crate::cmd::brdf::{self, BrdfMapArgs, SurfaceOpts};
use crate::progress::Cli;

/// `iridis render --gpu`: the scene on the GPU with a progress bar over bands of rows; the image, the seconds
/// (upload, compile, render and read-back) and the adapter's name.
pub fn render_scene(
    scene: &iridis_render::Scene,
    w: u32,
    h: u32,
    spp: u32,
) -> Result<(iridis_render::Image, f64, String)> {
    let r = iridis_api::gpu::render_scene(scene, w, h, spp, &Cli)?;
    Ok((r.image, r.seconds, r.adapter))
}

/// Opens the GPU, with the driver hint when there is none.
fn open_gpu() -> Result<Gpu> {
    iridis_api::gpu::open()
}

/// `iridis brdf-map … --gpu`: the lookup method on the GPU, written exactly like the CPU's map (the image is
/// tone-mapped on the CPU from the GPU's XYZ, so `--raw` and `--exr` hold the shader's numbers).
pub fn run_brdf_map(a: BrdfMapArgs, wi: [f64; 3], encoding: Encoding) -> Result<()> {
    if a.method != "lookup" {
        bail!("--gpu renders the lookup method (the paper's shader); --method {} runs on the CPU only", a.method);
    }
    if a.shading.fresnel.trim().starts_with("stack:") {
        bail!(
            "--gpu renders the lookup method, whose Fresnel factor must not depend on λ; a thin-film stack as \
             Fresnel source needs --method reference or ground-truth (CPU)"
        );
    }
    let fresnel = iridis_api::fresnel::parse_fresnel(&a.shading.fresnel)?;
    let params = TableParams { uv_resolution: a.uv_resolution, uv_power: a.uv_power };
    let start = std::time::Instant::now();
    let table = lookup_table(&a.input, &a.model.options(), params, &a.surface_opts.options(), &Cli)?;
    let tone = ToneMap { exposure_ru: a.exposure, encoding };
    let shading = &a.shading;
    let map = iridis_api::gpu::lookup_map(
        &table,
        fresnel,
        !shading.no_shadowing,
        shading.fresnel_convention,
        wi,
        a.size,
        tone,
    )?;
    brdf::write_map_outputs(&a, &map.output.xyz, tone)?;
    crate::outln!(
        "wrote {} (lookup map on the GPU, {}², {:.2} s in all, of which the map {:.2} ms on {})",
        a.output.display(),
        a.size,
        start.elapsed().as_secs_f64(),
        map.map_seconds * 1e3,
        map.adapter
    )?;
    Ok(())
}

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Times the two shaders headless (no window): the lookup diffraction BRDF map (paper eq. 10-12) and the
thin-film frame (Sussenbach ch. 4: recurrence per wavelength sample, thickness gradient and SVT texture).
A frame is one dispatch from submission to completion (wall clock; also the GPU's own timestamps around the
pass where the adapter has them); the light circles the normal at 30° from frame to
frame. Each shader runs --frames frames or --max-seconds, whichever ends first, after one warm-up frame,
and the last frame is checked against the CPU (CIEDE2000 over up to 4096 pixels).

With a SCENE (TOML or glTF), times the scene renderer instead (iridis render --gpu): --frames frames of
--size with 1 sample per pixel, min/median/p99, against one CPU render of the same image in the same run
(speed-up and CIEDE2000 between the two).

Examples:
  iridis bench gpu examples/snake_elaphe.toml --size 1024x1024 --frames 500
  iridis bench gpu examples/soap_bubble.toml --size 1920x1080 --frames 50 --json
  iridis bench gpu                                      built-in Elaphe table (201²), 1024² map, 1920×1080 film
  iridis bench gpu --table elaphe.npz --size 1024x1024 --frames 500 --json
  iridis bench gpu --stack \"air | gasoline 216nm | water 220nm | asphalt\" --film-size 1280x720
  iridis bench gpu --size 512 --film-size 960x540 --frames 5 --save out/")]
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
    /// Also write the last frames as PNG into this folder: lookup_map.png (1500 RU) and film_frame.png.
    #[arg(long)]
    pub save: Option<PathBuf>,
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
    use iridis_color::integrate::white_point;
    use iridis_color::{Illuminant, Lab, Observer};
    let white = white_point(Illuminant::D65, Observer::Cie1931);
    let shown = |x: Xyz| {
        let rgb = x.scale(exposure).to_linear_srgb().map(|c| if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) });
        Lab::from_xyz(Xyz::from_linear_srgb(rgb), white)
    };
    let mut d: Vec<f64> = a.iter().zip(b).map(|(p, q)| iridis_color::lab::delta_e_2000(shown(*p), shown(*q))).collect();
    d.sort_by(f64::total_cmp);
    let mean = d.iter().sum::<f64>() / d.len().max(1) as f64;
    let p99 = d.get(((d.len() as f64 * 0.99) as usize).min(d.len().saturating_sub(1))).copied().unwrap_or(0.0);
    (mean, p99)
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
    let (cpu, cpu_s) = crate::cmd::render::render_with_bar(&scene, w, h, 1);
    let xyz = |i: &iridis_render::Image| -> Vec<Xyz> {
        i.data.iter().map(|p| Xyz::from_linear_srgb(p.map(|c| c as f64))).collect()
    };
    let (de_mean, de_p99) = delta_e(&xyz(&img), &xyz(&cpu), scene.output.exposure);
    let [mn, med, p99, mean] = stats(&wall_times(&times));
    let gts = gpu_times(&times).map(|t| stats(&t));
    let name = path.display().to_string();
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
    Ok(())
}

pub fn bench(a: GpuBench) -> Result<()> {
    if !(a.max_seconds.is_finite() && a.max_seconds > 0.0) {
        bail!("--max-seconds {} must be positive", a.max_seconds);
    }
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
    let lookup = GpuLookup::new(&gpu, &table, fresnel.clone(), true)?;
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
        Shading { fresnel: Arc::new(fresnel), ..Shading::default() },
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
    let map_de = delta_e(&gpu_px, &cpu_px, 1500.0);
    let [mn, med, p99, mean] = stats(&wall_times(&map_times));
    let map_gpu = gpu_times(&map_times).map(|t| stats(&t));

    // Thin film.
    let grid = iridis_color::spectrum::uniform_grid(380.0, 780.0, 5.0)?;
    let weights = SpectralWeights::new(&grid, iridis_color::Illuminant::D65, iridis_color::Observer::Cie1931);
    let film = GpuFilm::new(&gpu, &stack, &weights)?;
    let film_frame = FilmFrame {
        width: fw,
        height: fh,
        angle_rad: (0.0, 80f64.to_radians()),
        offset_nm: (-300.0, 300.0),
        svt: Some((100.0, svt_noise(fw, fh))),
    };
    let run = film.frame(&film_frame, ToneMap { exposure_ru: 5.0, encoding: Encoding::Srgb })?;
    let film_times = time_frames(frames, a.max_seconds, |_| Ok(run.run()?))?;
    let out = run.read()?;
    let fpx = sample(fw * fh, 2048);
    let cpu_film = iridis_gpu::film::cpu_reference(&stack, &weights, &film_frame, &fpx)?;
    let cpu_r: Vec<Xyz> = cpu_film.iter().map(|p| p.0).collect();
    let gpu_r: Vec<Xyz> = fpx.iter().map(|&i| out.reflected[i]).collect();
    let ymax = cpu_r.iter().map(|x| x.y).fold(1e-6f64, f64::max);
    let film_de = delta_e(&gpu_r, &cpu_r, 1.0 / ymax);
    let [fmn, fmed, fp99, fmean] = stats(&wall_times(&film_times));
    let film_gpu = gpu_times(&film_times).map(|t| stats(&t));
    let ms_json = |s: Option<[f64; 4]>| s.map(|[a, b, c, d]| json!({"min": a, "median": b, "p99": c, "mean": d}));
    if let Some(dir) = &a.save {
        crate::output::write_png_rgb8(&dir.join("lookup_map.png"), mw as u32, mw as u32, &map.rgb8)?;
        crate::output::write_png_rgb8(&dir.join("film_frame.png"), fw as u32, fh as u32, &out.rgb8)?;
    }

    if a.json {
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
                "vs_cpu": {"pixels": px.len(), "exposure_ru": 1500.0, "delta_e00_mean": map_de.0, "delta_e00_p99": map_de.1},
            },
            "film": {
                "stack": stack.to_string(),
                "wavelengths": grid.len(),
                "size": [fw, fh],
                "frames": film_times.len(),
                "ms": {"min": fmn, "median": fmed, "p99": fp99, "mean": fmean},
                "gpu_timestamp_ms": ms_json(film_gpu),
                "fps_median": 1e3 / fmed,
                "vs_cpu": {"pixels": fpx.len(), "exposure_ru": 1.0 / ymax, "delta_e00_mean": film_de.0, "delta_e00_p99": film_de.1},
            },
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
        map_de.0,
        map_de.1
    )?;
    crate::outln!(
        "thin film {stack}, {fw}×{fh}, {} wavelengths, gradient + SVT, {} frames:",
        grid.len(),
        film_times.len()
    )?;
    crate::outln!(
        "  frame time min {fmn:.2} ms, median {fmed:.2} ms, p99 {fp99:.2} ms ({:.1} fps at the median)",
        1e3 / fmed
    )?;
    print_gpu_times(film_gpu)?;
    crate::outln!(
        "  vs CPU (Stack::evaluate_offset, f64; {} pixels): ΔE00 mean {:.4}, p99 {:.4}",
        fpx.len(),
        film_de.0,
        film_de.1
    )?;
    Ok(())
}

fn print_gpu_times(s: Option<[f64; 4]>) -> Result<()> {
    match s {
        Some([mn, med, p99, _]) => {
            crate::outln!("  GPU timestamps of the pass: min {mn:.2} ms, median {med:.2} ms, p99 {p99:.2} ms")
        }
        None => crate::outln!("  (the adapter has no timestamp queries: wall clock only)"),
    }
}

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Opens a window that renders on the GPU (the shaders of `iridis render --gpu` and `brdf-map --gpu`): a
scene (.toml, .gltf, .glb), reloaded when the file changes, or the BRDF map of a lookup table (.npz from
`iridis precompute`) or of a SURFACE (its table is built first). The panel sets the exposure (RU) and gamma,
the thin films' thickness, layer IOR and SVT strength, and shows each diffraction table's BRDF map at a
chosen incidence; the frame time is shown below. Drag to orbit, right-drag (or shift-drag) to move the
light, wheel to zoom, R resets, H toggles the help, Esc quits.

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
    let ok = r.steps.len() == 4 && r.steps.iter().all(|(_, d)| *d > 0.0);
    if a.json {
        crate::output::print_json(&json!({
            "adapter": r.adapter,
            "frames": r.frames,
            "frame_ms_median": r.frame_ms,
            "steps": r.steps.iter().map(|(n, d)| json!({"input": n, "change": d})).collect::<Vec<_>>(),
            "screenshot": shot.display().to_string(),
            "ok": ok,
        }))?;
    } else {
        crate::outln!("viewer check on {}: {} frames, median {:.1} ms", r.adapter, r.frames, r.frame_ms)?;
        for (n, d) in &r.steps {
            crate::outln!("  {n}: change {d:.3}")?;
        }
        crate::outln!("wrote {}", shot.display())?;
    }
    if !ok {
        bail!("the viewer did not answer every input (a change of 0 above)");
    }
    Ok(())
}
