//! `iridis bench gpu`: the GPU's shaders timed headless against the CPU in the same run — the lookup BRDF map
//! (paper eq. 10–12) in each table encoding, the thin-film frame on both film paths (Sussenbach ch. 4), the
//! lookup table built on the GPU, the ground truth's map — or, with a scene, the scene renderer
//! ([`gpu`] dispatches).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use anyhow::{bail, Context, Result};
use iridis_color::{Encoding, ToneMap, Xyz};
use iridis_diffraction::encoding::TableEncoding;
use iridis_diffraction::evaluator::Evaluator;
use iridis_diffraction::geometry::direction;
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::{Aperture, Fresnel, GroundTruth, Patch, Shading, SpectralSetup};
use iridis_gpu::film::FilmPathUsed;
use iridis_gpu::scene::SceneFilm;
use iridis_gpu::{FilmFrame, FilmPath, FrameTime, Gpu, GpuFilm, GpuLookup, GpuScene};
use iridis_thinfilm::spectral::{dense_weights, sampled_weights, FULL_BAND_NM};
use serde_json::{json, Value};

use super::{disk_pixels, sample, view_of, Bench, DeltaEStats, FrameStats};
use crate::report::Report;
use crate::{ModelOptions, SurfaceOptions};

/// `iridis bench gpu`'s options (the CLI's defaults; with the feature `cli`, its flags).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct GpuBenchOptions {
    /// A scene (TOML or glTF) to time instead of the two shaders.
    pub scene: Option<PathBuf>,
    /// Lookup BRDF map size: 1024x1024 or 1024 (maps are square); with a SCENE, the image size.
    #[cfg_attr(feature = "cli", arg(long, default_value = "1024x1024"))]
    pub size: String,
    /// Frames timed per shader.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 500))]
    pub frames: usize,
    /// Stop a shader's loop after this many seconds (software drivers are slow).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 30.0))]
    pub max_seconds: f64,
    /// Lookup table (.npz from `iridis precompute`); default: builtin:elaphe precomputed here at 201².
    #[cfg_attr(feature = "cli", arg(long))]
    pub table: Option<PathBuf>,
    /// Thin-film frame size.
    #[cfg_attr(feature = "cli", arg(long, default_value = "1920x1080"))]
    pub film_size: String,
    /// Thin-film stack; every layer's thickness gets the frame's offset (gradient ±300 nm, SVT ±100 nm).
    #[cfg_attr(feature = "cli", arg(long, default_value = "air | water 500nm | air"))]
    pub stack: String,
    /// Wavelength samples (380-780 nm) of the direct film path that the fast path is timed against.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 81, value_name = "N"))]
    pub spectral_samples: usize,
    /// Also write the last frames as PNG into this folder: lookup_map.png (1500 RU) and film_frame.png (the
    /// fast path; film_frame_direct.png the direct one).
    #[cfg_attr(feature = "cli", arg(long))]
    pub save: Option<PathBuf>,
    /// Lookup table encodings to time, comma-separated (f32, f16, chebK, chebK-f16): the first is `lookup`'s,
    /// each is checked against the CPU's f64 lookup (default: the f32 powers and brdf-map's default).
    #[cfg_attr(feature = "cli", arg(long, default_value = "f32,cheb12"))]
    pub table_precision: String,
    /// Surface whose lookup table is built on the CPU and on the GPU (times and agreement).
    #[cfg_attr(feature = "cli", arg(long, default_value = "builtin:elaphe?size=10um"))]
    pub build_surface: String,
    /// u-v resolution of that table.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 31))]
    pub build_uv_resolution: usize,
    /// Surface whose ground truth (finite aperture and periodic) is rendered on the GPU and the CPU.
    #[cfg_attr(feature = "cli", arg(long, default_value = "builtin:elaphe?size=3um&pixel=65nm"))]
    pub gt_surface: String,
    /// Size of the ground truth's BRDF map on the GPU.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 12))]
    pub gt_size: usize,
    /// Pixels of that map the CPU evaluates (spread over it) for its rate and the CIEDE2000.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 32))]
    pub gt_cpu_pixels: usize,
    // How --build-surface and --gt-surface are read: a file's channel, pixel size, height unit, levelling.
    #[cfg_attr(feature = "cli", command(flatten))]
    pub surface_options: SurfaceOptions,
}

impl Default for GpuBenchOptions {
    fn default() -> Self {
        Self {
            scene: None,
            size: "1024x1024".into(),
            frames: 500,
            max_seconds: 30.0,
            table: None,
            film_size: "1920x1080".into(),
            stack: "air | water 500nm | air".into(),
            spectral_samples: 81,
            save: None,
            table_precision: "f32,cheb12".into(),
            build_surface: "builtin:elaphe?size=10um".into(),
            build_uv_resolution: 31,
            gt_surface: "builtin:elaphe?size=3um&pixel=65nm".into(),
            gt_size: 12,
            gt_cpu_pixels: 32,
            surface_options: SurfaceOptions::default(),
        }
    }
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

/// Wall-clock and (where the adapter has timestamp queries) GPU statistics of a run of frames.
struct Timed {
    frames: usize,
    wall: FrameStats,
    gpu: Option<FrameStats>,
}

impl Timed {
    fn of(times: &[FrameTime]) -> Self {
        let wall: Vec<Duration> = times.iter().map(|t| t.wall).collect();
        let gpu: Option<Vec<Duration>> = times.iter().map(|t| t.gpu).collect();
        Self { frames: times.len(), wall: FrameStats::of(&wall), gpu: gpu.map(|g| FrameStats::of(&g)) }
    }

    fn gpu_json(&self) -> Value {
        self.gpu.map(FrameStats::to_json).into()
    }

    /// The wall-clock frame times' line.
    fn wall_line(&self, indent: &str) -> String {
        let w = &self.wall;
        format!(
            "{indent}frame time min {:.2} ms, median {:.2} ms, p99 {:.2} ms ({:.1} fps at the median)",
            w.min,
            w.median,
            w.p99,
            1e3 / w.median
        )
    }

    /// The GPU timestamps' line, or that the adapter has none.
    fn gpu_line(&self, indent: &str) -> String {
        match self.gpu {
            Some(s) => format!(
                "{indent}GPU timestamps of the pass: min {:.2} ms, median {:.2} ms, p99 {:.2} ms",
                s.min, s.median, s.p99
            ),
            None => format!("{indent}(the adapter has no timestamp queries: wall clock only)"),
        }
    }

    /// The run's lines: wall clock, GPU timestamps, and its colours' difference from the CPU's (`cpu`: what the
    /// CPU computed, on how many pixels).
    fn vs_cpu_lines(&self, indent: &str, cpu: &str, de: &DeltaEStats) -> [String; 3] {
        let vs = format!("{indent}vs CPU ({cpu}): ΔE00 mean {:.4}, p99 {:.4}", de.mean, de.p99);
        [self.wall_line(indent), self.gpu_line(indent), vs]
    }
}

/// Runs one warm-up frame, then up to `frames` frames or `max_seconds`, whichever ends first.
fn time_frames(
    frames: usize,
    max_seconds: f64,
    mut run: impl FnMut(usize) -> Result<FrameTime>,
) -> Result<Vec<FrameTime>> {
    run(0)?; // warm-up: pipeline caches, first-touch of the buffers
    let start = std::time::Instant::now();
    // Not `with_capacity(frames)`: --frames 4294967296 asked for 137 GB up front and aborted; --max-seconds ends
    // long runs.
    let mut times = Vec::new();
    while times.len() < frames.max(1) {
        times.push(run(times.len())?);
        if start.elapsed().as_secs_f64() > max_seconds {
            break;
        }
    }
    Ok(times)
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

/// The adapter's lines: its name, and that a software adapter measures the CPU.
fn adapter_lines(gpu: &Gpu) -> Vec<String> {
    let mut t = vec![format!("adapter: {}", gpu.adapter_name())];
    if gpu.is_software() {
        t.push("  (a software adapter: these times measure the CPU, not a GPU)".into());
    }
    t
}

/// `iridis bench gpu [SCENE]`: the scene renderer with a scene, else the shaders, the table build and the
/// ground truth.
pub fn gpu(a: &GpuBenchOptions, report: &dyn Report) -> Result<Bench> {
    if !(a.max_seconds.is_finite() && a.max_seconds > 0.0) {
        bail!("--max-seconds {} must be positive", a.max_seconds);
    }
    if a.frames == 0 {
        bail!("--frames 0: time at least one frame (each run also renders one untimed warm-up frame)");
    }
    // Before any work, as `compare --maps` does: the folder is made (it failed after the whole run before).
    if let Some(dir) = &a.save {
        crate::output::create_dir(dir).context("--save")?;
    }
    let direct_weights = sampled_weights(a.spectral_samples, FULL_BAND_NM)
        .with_context(|| format!("--spectral-samples {}", a.spectral_samples))?;
    if let Some(p) = &a.scene {
        // A scene is timed alone: the shaders' options, set away from their defaults, would be ignored.
        let d = GpuBenchOptions::default();
        let shaders: Vec<&str> = [
            ("--table", a.table.is_some()),
            ("--film-size", a.film_size != d.film_size),
            ("--stack", a.stack != d.stack),
            ("--table-precision", a.table_precision != d.table_precision),
            ("--build-surface", a.build_surface != d.build_surface),
            ("--build-uv-resolution", a.build_uv_resolution != d.build_uv_resolution),
            ("--gt-surface", a.gt_surface != d.gt_surface),
            ("--gt-size", a.gt_size != d.gt_size),
            ("--gt-cpu-pixels", a.gt_cpu_pixels != d.gt_cpu_pixels),
        ]
        .into_iter()
        .filter_map(|(flag, given)| given.then_some(flag))
        .collect();
        if !shaders.is_empty() {
            bail!(
                "{} would be ignored: with a SCENE, bench gpu times the scene renderer only (its size, frames, \
                 --max-seconds, --spectral-samples and --save apply)",
                shaders.join(", ")
            );
        }
        // A scene names its own surfaces and tables: the surface flags would be ignored.
        let given = a.surface_options.flags();
        if !given.is_empty() {
            bail!(
                "{} would be ignored: with a SCENE, bench gpu reads no --build-surface or --gt-surface",
                given.join(" ")
            );
        }
        return scene(a, p, report);
    }
    let (mw, mh) = parse_size(&a.size, "--size")?;
    if mw != mh {
        bail!("--size {}: BRDF maps are square (the unit disk of view directions); use e.g. 1024x1024", a.size);
    }
    let (fw, fh) = parse_size(&a.film_size, "--film-size")?;
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
    // Both surfaces are read before anything is timed: a wrong path or option fails at once, not minutes later.
    // One set of options serves both: a built-in beside a file leaves the file-reading ones to the file.
    let options_for = |spec: &str, other: &str| match (spec.starts_with("builtin:"), other.starts_with("builtin:")) {
        (true, false) => a.surface_options.without_file_options(),
        _ => a.surface_options.clone(),
    };
    let (build, gt) = (&a.build_surface, &a.gt_surface);
    let build_patch = crate::surface::load_patch(build, &options_for(build, gt), report).context("--build-surface")?;
    let gt_patch = crate::surface::load_patch(gt, &options_for(gt, build), report).context("--gt-surface")?;
    let gpu = crate::gpu::open()?;
    let mut t = adapter_lines(&gpu);

    // Lookup diffraction.
    let table = match &a.table {
        Some(p) => LookupTable::load(p)?,
        None => {
            t.push("building the lookup table of builtin:elaphe at 201² (pass --table to use your own) …".into());
            let params = TableParams { uv_resolution: 201, uv_power: 5.0 };
            let none = SurfaceOptions::default();
            crate::model::lookup_table(None, "builtin:elaphe", &ModelOptions::default(), params, &none, report)?
        }
    };
    let fresnel = Fresnel::default();
    let tone = ToneMap { exposure_ru: 1500.0, encoding: Encoding::Srgb };
    let frames = a.frames;
    let light = |i: usize| direction(30f64.to_radians(), i as f64 * std::f64::consts::TAU / frames.max(1) as f64);
    let cpu = Lookup::new(
        Arc::new(table.clone()),
        Shading { fresnel: Arc::new(fresnel.clone()), ..Shading::default() },
        Precision::F64,
    )?;
    let px: Vec<usize> = sample(mw * mw, 4096)
        .into_iter()
        .filter(|&i| iridis_diffraction::map::view_direction(i % mw, i / mw, mw).is_some())
        .collect();
    // Each encoding of the table timed and checked against the CPU's f64 lookup the same way in this run.
    let mut encoded = Vec::new();
    let mut first_map = None;
    for &e in &encodings {
        let l = GpuLookup::encoded(&gpu, &table, fresnel.clone(), true, e, u64::MAX)?;
        let f = l.frame(mw, tone)?;
        let times = time_frames(frames, a.max_seconds, |i| Ok(f.run(light(i))?))?;
        let m = f.read()?;
        // The last frame's light (time_frames warms up with frame 0, then runs frames 0, 1, …).
        let last = light(times.len().saturating_sub(1));
        let cpu_e: Vec<Xyz> = px.iter().map(|&i| cpu.xyz(last, view_of(i, mw))).collect();
        let gpu_e: Vec<Xyz> = px.iter().map(|&i| m.xyz[i]).collect();
        encoded.push((
            e,
            l.table_bytes() as f64 / 1e6,
            Timed::of(&times),
            DeltaEStats::between(&gpu_e, &cpu_e, 1500.0),
        ));
        first_map.get_or_insert(m);
    }
    let map = first_map.context("internal: no table encoding timed")?;
    let (_, lookup_mb, map_t, map_de) = &encoded[0];
    let first_median = map_t.wall.median;

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
    let fast_t = Timed::of(&time_frames(frames, a.max_seconds, |_| Ok(fast_run.run()?))?);
    let fast_out = fast_run.read()?;
    let direct = GpuFilm::new(&gpu, &stack, &direct_weights)?.with_path(FilmPath::Direct);
    let direct_run = direct.frame(&film_frame, film_tone)?;
    let direct_t = Timed::of(&time_frames(frames, a.max_seconds, |_| Ok(direct_run.run()?))?);
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
    let fast_de = DeltaEStats::between(&at(&fast_out.reflected), &reflected(&cpu_dense), 1.0 / ymax);
    let direct_de = DeltaEStats::between(&at(&direct_out.reflected), &reflected(&cpu_direct), 1.0 / ymax);
    // The fast path against the direct one over every pixel, the brightest direct pixel at Y = 1.
    let frame_ymax = direct_out.reflected.iter().map(|x| x.y).fold(1e-6f64, f64::max);
    let vs_direct = DeltaEStats::between(&fast_out.reflected, &direct_out.reflected, 1.0 / frame_ymax);
    let (fmed, dmed) = (fast_t.wall.median, direct_t.wall.median);
    let (grid, build_ms, fallback) = match fast_run.path() {
        FilmPathUsed::Table { grid, build } => (Some(*grid), Some(build.as_secs_f64() * 1e3), None),
        FilmPathUsed::Direct { why } => (None, None, why.clone()),
    };
    if let Some(dir) = &a.save {
        crate::output::write_png_rgb8(&dir.join("lookup_map.png"), mw as u32, mw as u32, &map.rgb8)?;
        crate::output::write_png_rgb8(&dir.join("film_frame.png"), fw as u32, fh as u32, &fast_out.rgb8)?;
        crate::output::write_png_rgb8(&dir.join("film_frame_direct.png"), fw as u32, fh as u32, &direct_out.rgb8)?;
    }

    t.push(format!(
        "lookup diffraction, {mw}×{mh} map, table {}² × {} powers ({lookup_mb:.1} MB), {} frames:",
        table.meta.uv_resolution,
        table.powers(),
        map_t.frames
    ));
    t.extend(map_t.vs_cpu_lines("  ", &format!("lookup, f64; {} pixels at 1500 RU", px.len()), map_de));
    if encoded.len() > 1 {
        t.push("  table encodings (same map, same pixels; ΔE00 against the CPU's f64 lookup at 1500 RU):".into());
        for (e, mb, tm, de) in &encoded {
            t.push(format!(
                "    {:<10} {mb:>8.1} MB  median {:>9.2} ms ({:.2}× the first)  ΔE00 mean {:.4}, p99 {:.4}, max {:.4}",
                e.name(),
                tm.wall.median,
                tm.wall.median / first_median,
                de.mean,
                de.p99,
                de.max
            ));
        }
    }
    t.push(format!("thin film {stack}, {fw}×{fh}, gradient + SVT:"));
    t.push(format!("  fast path: {}; {} frames:", fast_run.path(), fast_t.frames));
    let cpu = format!("Stack::evaluate_offset, f64, 81 samples; {} pixels", fpx.len());
    t.extend(fast_t.vs_cpu_lines("    ", &cpu, &fast_de));
    t.push(format!("    vs the direct path (every pixel): {vs_direct}"));
    t.push(format!(
        "  direct path, {} wavelength samples per pixel; {} frames:",
        direct_weights.wavelengths_nm().len(),
        direct_t.frames
    ));
    t.extend(direct_t.vs_cpu_lines("    ", &format!("f64, the same samples; {} pixels", fpx.len()), &direct_de));
    t.push(format!("  direct / fast median frame time: {:.1}×", dmed / fmed));
    let (build, build_lines) = table_build(&gpu, a, &build_patch, report)?;
    let (truth, truth_lines) = ground_truth(&gpu, a, &gt_patch, report)?;
    t.extend(build_lines);
    t.extend(truth_lines);

    let json = json!({
        "adapter": gpu.adapter_name(),
        "software_adapter": gpu.is_software(),
        "lookup": {
            "table": a.table.as_ref().map(|p| p.display().to_string()).unwrap_or_else(|| "builtin:elaphe (201²)".into()),
            "uv_resolution": table.meta.uv_resolution,
            "taylor_terms": table.meta.taylor_terms,
            "table_mb": lookup_mb,
            "size": [mw, mh],
            "frames": map_t.frames,
            "ms": map_t.wall.to_json(),
            "gpu_timestamp_ms": map_t.gpu_json(),
            "fps_median": 1e3 / first_median,
            "vs_cpu": {"pixels": px.len(), "exposure_ru": 1500.0, "delta_e00_mean": map_de.mean, "delta_e00_p99": map_de.p99},
            "encodings": encoded.iter().map(|(e, mb, tm, de)| json!({
                "encoding": e.name(),
                "table_mb": mb,
                "frames": tm.frames,
                "ms": tm.wall.to_json(),
                "fps_median": 1e3 / tm.wall.median,
                "median_over_first": tm.wall.median / first_median,
                "delta_e00_mean": de.mean,
                "delta_e00_p99": de.p99,
                "delta_e00_max": de.max,
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
                "frames": fast_t.frames,
                "ms": fast_t.wall.to_json(),
                "gpu_timestamp_ms": fast_t.gpu_json(),
                "fps_median": 1e3 / fmed,
                "vs_cpu": {"pixels": fpx.len(), "exposure_ru": 1.0 / ymax, "delta_e00_mean": fast_de.mean, "delta_e00_p99": fast_de.p99},
                "vs_direct": {"pixels": fw * fh, "exposure_ru": 1.0 / frame_ymax, "delta_e00_mean": vs_direct.mean, "delta_e00_p99": vs_direct.p99, "delta_e00_max": vs_direct.max},
            },
            "direct": {
                "wavelengths": direct_weights.wavelengths_nm().len(),
                "frames": direct_t.frames,
                "ms": direct_t.wall.to_json(),
                "gpu_timestamp_ms": direct_t.gpu_json(),
                "fps_median": 1e3 / dmed,
                "vs_cpu": {"pixels": fpx.len(), "exposure_ru": 1.0 / ymax, "delta_e00_mean": direct_de.mean, "delta_e00_p99": direct_de.p99},
            },
            "direct_over_table_median": dmed / fmed,
        },
        "table_build": build,
        "ground_truth": truth,
    });
    Ok(Bench::new(t, json))
}

/// `iridis bench gpu SCENE`: frame times of the scene renderer against one CPU render of the same image.
fn scene(a: &GpuBenchOptions, path: &Path, report: &dyn Report) -> Result<Bench> {
    let (w, h) = parse_size(&a.size, "--size")?;
    let (w, h) = (w as u32, h as u32);
    let scene = crate::scene::load(path, &Default::default(), report)?;
    let gpu = crate::gpu::open()?;
    let start = std::time::Instant::now();
    let g = GpuScene::new(&gpu, &scene)?;
    let setup_s = start.elapsed().as_secs_f64();
    let tone = ToneMap { exposure_ru: scene.output.exposure, encoding: scene.output.encoding };
    let frame = g.frame(w, h, 1, tone)?;
    let mut t = adapter_lines(&gpu);
    t.push(format!("scene {}: {w}×{h}, 1 spp; upload and shader compilation {setup_s:.2} s", path.display()));
    let times = Timed::of(&time_frames(a.frames, a.max_seconds, |_| Ok(frame.run(&g)?))?);
    let img = frame.read_image(&g)?;
    // The same image with the films evaluated directly (the reference path), where the scene has films.
    let direct = if g.has_films() {
        let film = SceneFilm { path: FilmPath::Direct, spectral_samples: a.spectral_samples };
        let d = GpuScene::with_film(&gpu, &scene, film)?;
        let f = d.frame(w, h, 1, tone)?;
        let dt = Timed::of(&time_frames(a.frames, a.max_seconds, |_| Ok(f.run(&d)?))?);
        Some((dt, f.read_image(&d)?))
    } else {
        None
    };
    let (cpu, cpu_s) = crate::scene::render_cpu(&scene, w, h, 1, report);
    let gpu_xyz = img.to_xyz();
    let de = DeltaEStats::between(&gpu_xyz, &cpu.to_xyz(), scene.output.exposure);
    let direct = direct.map(|(dt, di)| (dt, DeltaEStats::between(&gpu_xyz, &di.to_xyz(), scene.output.exposure)));
    if let Some(dir) = &a.save {
        crate::output::write_png_rgb8(&dir.join("scene_gpu.png"), w, h, &frame.read_rgb8(&g)?)?;
    }
    let s = times.wall;
    let threads = rayon::current_num_threads();
    t.push(format!(
        "  {} frames: min {:.2} ms, median {:.2} ms, p99 {:.2} ms ({:.1} fps at the median)",
        times.frames,
        s.min,
        s.median,
        s.p99,
        1e3 / s.median
    ));
    t.push(times.gpu_line("  "));
    t.push(format!(
        "  CPU renderer, same image ({threads} threads): {:.1} ms — CPU time / GPU median frame = {:.2}",
        cpu_s * 1e3,
        cpu_s * 1e3 / s.median
    ));
    t.push(format!(
        "  vs CPU ({} pixels at {} RU): ΔE00 mean {:.4}, p99 {:.4}",
        w * h,
        scene.output.exposure,
        de.mean,
        de.p99
    ));
    if let Some((dt, dde)) = &direct {
        let d = dt.wall;
        t.push(format!(
            "  films evaluated directly ({} wavelength samples per hit), {} frames: min {:.2} ms, median {:.2} ms, \
             p99 {:.2} ms — {:.2}× the colour-table frame",
            a.spectral_samples,
            dt.frames,
            d.min,
            d.median,
            d.p99,
            d.median / s.median
        ));
        t.push(dt.gpu_line("  "));
        t.push(format!("  colour tables vs direct: {dde}"));
    }
    let json = json!({
        "adapter": gpu.adapter_name(),
        "software_adapter": gpu.is_software(),
        "scene": path.display().to_string(),
        "size": [w, h],
        "spp": 1,
        "setup_s": setup_s,
        "frames": times.frames,
        "ms": s.to_json(),
        "gpu_timestamp_ms": times.gpu_json(),
        "fps_median": 1e3 / s.median,
        "cpu": {"threads": threads, "render_s": cpu_s, "cpu_over_gpu_median": cpu_s * 1e3 / s.median},
        "vs_cpu": {"pixels": (w * h), "exposure_ru": scene.output.exposure, "delta_e00_mean": de.mean, "delta_e00_p99": de.p99},
        "film_direct": direct.map(|(dt, dde)| json!({
            "spectral_samples": a.spectral_samples,
            "frames": dt.frames,
            "ms": dt.wall.to_json(),
            "gpu_timestamp_ms": dt.gpu_json(),
            "direct_over_table_median": dt.wall.median / s.median,
            "vs_table": {"delta_e00_mean": dde.mean, "delta_e00_p99": dde.p99, "delta_e00_max": dde.max},
        })),
    });
    Ok(Bench::new(t, json))
}

/// The lookup table of `build_surface` built on the CPU (all cores) and on the GPU in the same run: times,
/// speed-up and the GPU table's error against the CPU's (`iridis_gpu::table_build::table_error`).
fn table_build(gpu: &Gpu, a: &GpuBenchOptions, patch: &Patch, report: &dyn Report) -> Result<(Value, Vec<String>)> {
    let model = ModelOptions::default();
    let spectral = crate::model::spectral_setup(&model, report)?;
    let terms = crate::model::taylor_terms(patch, &model, report)?;
    let params = TableParams { uv_resolution: a.build_uv_resolution, uv_power: 5.0 };
    let t = std::time::Instant::now();
    let cpu = crate::model::build_table(None, &terms, &spectral, params, &a.build_surface, report)?;
    let cpu_s = t.elapsed().as_secs_f64();
    let t = std::time::Instant::now();
    let on_gpu = iridis_gpu::build_table(gpu, &terms, &spectral, params, &a.build_surface, &|_| {})?;
    let gpu_s = t.elapsed().as_secs_f64();
    let err = iridis_gpu::table_build::table_error(&cpu, &on_gpu);
    let threads = rayon::current_num_threads();
    let lines = vec![
        format!(
            "lookup table build, {} ({}×{} samples, N = {}), {}² grid × {} wavelengths:",
            a.build_surface,
            patch.cols,
            patch.rows,
            terms.n_max,
            params.uv_resolution,
            spectral.wavelengths().len()
        ),
        format!(
            "  CPU ({threads} threads, f64) {cpu_s:.2} s, GPU (f32, with upload, compilation and read-back) \
             {gpu_s:.2} s: CPU/GPU = {:.2}",
            cpu_s / gpu_s
        ),
        format!(
            "  GPU table vs CPU: largest error relative to each power's largest |I_p| {:.2e}; relative to the \
             largest term 2^p |I_p| of the sum {:.2e}",
            err.per_power, err.of_sum
        ),
    ];
    let json = json!({
        "surface": a.build_surface,
        "samples": [patch.cols, patch.rows],
        "taylor_terms": terms.n_max,
        "uv_resolution": params.uv_resolution,
        "wavelengths": spectral.wavelengths().len(),
        "cpu_threads": threads,
        "cpu_s": cpu_s,
        "gpu_s": gpu_s,
        "cpu_over_gpu": cpu_s / gpu_s,
        "max_rel_error_per_power": err.per_power,
        "max_rel_error_of_sum": err.of_sum,
    });
    Ok((json, lines))
}

/// The ground truth of `gt_surface` (both apertures) as a `gt_size` BRDF map on the GPU, against the CPU on
/// up to `gt_cpu_pixels` of its pixels in the same run: per-pixel rates, speed-up, CIEDE2000 at 1500 RU.
fn ground_truth(gpu: &Gpu, a: &GpuBenchOptions, patch: &Patch, report: &dyn Report) -> Result<(Value, Vec<String>)> {
    use rayon::prelude::*;
    let coherence = crate::model::coherence_for(patch, None, report)?;
    let spectral = SpectralSetup::default();
    let samples = 2 * spectral.wavelengths().len() - 1;
    let size = a.gt_size;
    let wi = direction(30f64.to_radians(), 0.0);
    let disk = disk_pixels(size);
    let picked: Vec<usize> = sample(disk.len(), a.gt_cpu_pixels).into_iter().map(|k| disk[k]).collect();
    let threads = rayon::current_num_threads();
    let mut lines = vec![format!(
        "ground truth, {} ({}×{} samples, coherence {:.1} µm), {size}² map ({} pixels) × {samples} wavenumbers:",
        a.gt_surface,
        patch.cols,
        patch.rows,
        coherence / 1000.0,
        disk.len()
    )];
    let mut out = serde_json::Map::new();
    out.insert("surface".into(), json!(a.gt_surface));
    out.insert("samples".into(), json!([patch.cols, patch.rows]));
    out.insert("size".into(), json!(size));
    out.insert("pixels".into(), json!(disk.len()));
    out.insert("wavenumbers".into(), json!(samples));
    for aperture in [Aperture::Finite, Aperture::Periodic] {
        let gt = GroundTruth::with_aperture(patch, coherence, Shading::default(), &spectral, samples, aperture)?;
        let t = std::time::Instant::now();
        let map = iridis_gpu::ground_truth_map(gpu, &gt, wi, size, &|_| {})?;
        let gpu_s = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        let cpu: Vec<Xyz> = picked.par_iter().map(|&i| gt.xyz(wi, view_of(i, size))).collect();
        let cpu_s = t.elapsed().as_secs_f64();
        let gpu_px: Vec<Xyz> = picked.iter().map(|&i| map[i]).collect();
        let de = DeltaEStats::between(&gpu_px, &cpu, 1500.0);
        let (gpu_rate, cpu_rate) = (disk.len() as f64 / gpu_s, picked.len() as f64 / cpu_s);
        lines.push(format!(
            "  {:<8} GPU {gpu_s:.2} s ({gpu_rate:.1} pixels/s, with upload and compilation); CPU ({threads} threads) \
             {cpu_rate:.1} pixels/s on {} of them: GPU/CPU = {:.2}; ΔE00 at 1500 RU mean {:.4}, p99 {:.4}, max {:.4}",
            aperture.name(),
            picked.len(),
            gpu_rate / cpu_rate,
            de.mean,
            de.p99,
            de.max
        ));
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
                "delta_e00_mean": de.mean,
                "delta_e00_p99": de.p99,
                "delta_e00_max": de.max,
            }),
        );
    }
    let phase = iridis_gpu::ground_truth::phase_accuracy(gpu, 100_000)?;
    lines.push(format!("  phase arithmetic of the shader against f64 (100 000 cases): largest error {phase:.1e} rad"));
    out.insert("phase_error_rad".into(), json!(phase));
    Ok((Value::Object(out), lines))
}
