//! Diffraction benches: the Taylor-term FFTs against numpy and BRDF maps per second of each method
//! ([`speed`], `iridis bench diffraction`), reference against ground truth at equal size ([`methods`],
//! `iridis bench diffraction-methods`), and every method's CIEDE2000 against the ground truth with the Taylor
//! series' convergence ([`accuracy`], `iridis bench diffraction-accuracy`).

use std::path::PathBuf;
use std::process::Command;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use iridis_color::Xyz;
use iridis_diffraction::evaluator::{Aperture, Evaluator, GroundTruth, Reference};
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::{Patch, Shading, SpectralSetup, TaylorTerms};
use serde_json::json;

use super::{disk_pixels, Bench, DeltaEStats};
use crate::report::Report;

/// The bench surface's side, in samples: at most 8192² (512 MiB of heights, as large as a scan is read).
pub const MAX_BENCH_SIZE: usize = 8192;
/// At least 8² samples, as the smallest map.
pub const MIN_BENCH_SIZE: usize = 8;

/// A reproducible rough surface: a sum of random gratings (σ_h ≈ 60 nm) at 65 nm per pixel.
pub fn bench_surface(n: usize) -> Result<Patch> {
    let mut seed = 0x1d1du64;
    let mut rnd = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let waves: Vec<[f64; 4]> = (0..24)
        .map(|_| {
            let period = 500.0 + 2500.0 * rnd();
            let angle = std::f64::consts::PI * rnd();
            [angle.cos() / period, angle.sin() / period, std::f64::consts::TAU * rnd(), 17.0 * (0.5 + rnd())]
        })
        .collect();
    let dx = 65.0;
    let mut h = vec![0.0; n * n];
    for r in 0..n {
        for c in 0..n {
            let (x, y) = (c as f64 * dx, r as f64 * dx);
            h[r * n + c] =
                waves.iter().map(|w| w[3] * (std::f64::consts::TAU * (w[0] * x + w[1] * y) + w[2]).sin()).sum();
        }
    }
    Ok(Patch::from_row_major(n, n, dx, dx, &h)?)
}

/// Times the same Taylor-term FFTs in numpy (one thread: numpy's FFT is single-threaded); `None` without
/// python3 and numpy.
fn numpy_fft_seconds(patch: &Patch, terms: usize) -> Result<Option<f64>> {
    use npyz::WriterBuilder;
    let dir = tempfile::tempdir()?;
    let path = dir.path().join("h.npy");
    {
        let f = std::io::BufWriter::new(std::fs::File::create(&path)?);
        let mut w = npyz::WriteOptions::new()
            .default_dtype()
            .shape(&[patch.rows as u64, patch.cols as u64])
            .writer(f)
            .begin_nd()?;
        w.extend(patch.heights.iter().copied())?;
        w.finish()?;
    }
    let script = format!(
        "import time, numpy as np\nh = np.load(r'{}')\nh = h - h.mean()\nt = time.perf_counter()\n\
         out = [np.fft.fft2((1j * h) ** n) / h.size for n in range({})]\nprint(time.perf_counter() - t)\n",
        path.display(),
        terms + 1
    );
    let out = match Command::new("python3").arg("-c").arg(&script).output() {
        Ok(o) if o.status.success() => o,
        _ => return Ok(None),
    };
    Ok(String::from_utf8_lossy(&out.stdout).trim().parse::<f64>().ok())
}

/// Pixels per second of a method on a map of `size²` (directions at normal incidence).
fn map_rate(e: &dyn Evaluator, size: usize) -> f64 {
    let start = Instant::now();
    let map = iridis_diffraction::map::brdf_map(e, [0.0, 0.0, 1.0], size, 1, &|_| {});
    let secs = start.elapsed().as_secs_f64();
    std::hint::black_box(map);
    (size * size) as f64 / secs
}

/// `iridis bench diffraction`'s options (with the feature `cli`, its flags).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct SpeedOptions {
    /// Height-field samples per side.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 1024))]
    pub size: usize,
    /// Taylor terms N (terms 0..N).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 40))]
    pub terms: usize,
    /// BRDF map sizes for the lookup method.
    #[cfg_attr(feature = "cli", arg(long, value_delimiter = ',', default_value = "512,1024"))]
    pub map_sizes: Vec<usize>,
    /// u-v resolution of the lookup tables.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 501))]
    pub uv_resolution: usize,
}

impl Default for SpeedOptions {
    fn default() -> Self {
        Self { size: 1024, terms: 40, map_sizes: vec![512, 1024], uv_resolution: 501 }
    }
}

/// The Taylor-term FFTs (all threads, one thread, numpy), the lookup tables, and BRDF maps per second of
/// lookup, reference and ground truth on [`bench_surface`].
pub fn speed(a: &SpeedOptions, report: &dyn Report) -> Result<Bench> {
    // The surface is size² samples and every term's FFT as large: checked before any is allocated (10¹² was a
    // capacity-overflow panic, 10⁵ an 80 GB allocation that aborted).
    if !(MIN_BENCH_SIZE..=MAX_BENCH_SIZE).contains(&a.size) {
        bail!("--size {}: the bench surface's side must be from {MIN_BENCH_SIZE} to {MAX_BENCH_SIZE} samples", a.size);
    }
    for &s in &a.map_sizes {
        crate::brdf_map::check_size_of("--map-sizes", s)?;
    }
    let threads = rayon::current_num_threads();
    report.info(&format!("surface {}², {} terms, {threads} threads …", a.size, a.terms));
    let patch = bench_surface(a.size)?;
    let coherence = 65_000.0;
    let t = Instant::now();
    let terms = TaylorTerms::compute(&patch, a.terms, coherence)?;
    let ours_all = t.elapsed().as_secs_f64();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().context("thread pool")?;
    let t = Instant::now();
    let one = pool.install(|| TaylorTerms::compute(&patch, a.terms, coherence))?;
    let ours_one = t.elapsed().as_secs_f64();
    drop(one);
    report.info("numpy …");
    let numpy = numpy_fft_seconds(&patch, a.terms)?;

    let spectral = SpectralSetup::default();
    report.info(&format!("lookup tables {}² …", a.uv_resolution));
    let t = Instant::now();
    let params = TableParams { uv_resolution: a.uv_resolution, uv_power: 5.0 };
    let table = LookupTable::build(&terms, &spectral, params, "bench", &|_| {})?;
    let table_secs = t.elapsed().as_secs_f64();
    let lookup = Lookup::new(Arc::new(table), Shading::default(), Precision::F64)?;
    let terms = Arc::new(terms);
    let reference = Reference { terms, shading: Shading::default(), spectral: spectral.clone() };
    let truth =
        GroundTruth::new(&patch, coherence, Shading::default(), &spectral, 2 * spectral.wavelengths().len() - 1)?;

    let mut maps = Vec::new();
    for &s in &a.map_sizes {
        report.info(&format!("lookup map {s}² …"));
        maps.push(("lookup", s, map_rate(&lookup, s)));
    }
    report.info("reference map 48² …");
    let ref_rate = map_rate(&reference, 48);
    maps.push(("reference", 48, ref_rate));
    report.info("ground-truth map 8² …");
    let gt_rate = map_rate(&truth, 8);
    maps.push(("ground-truth", 8, gt_rate));
    let lookup_rate = maps[0].2;

    let json = json!({
        "threads": threads,
        "surface": {"size": a.size, "terms": a.terms},
        "precompute_fft_seconds": {"iridis_all_threads": ours_all, "iridis_one_thread": ours_one, "numpy": numpy},
        "lookup_table_seconds": table_secs,
        "uv_resolution": a.uv_resolution,
        "maps": maps.iter().map(|(m, s, r)| json!({"method": m, "size": s, "pixels_per_second": r})).collect::<Vec<_>>(),
        "lookup_over_reference": lookup_rate / ref_rate,
        "lookup_over_ground_truth": lookup_rate / gt_rate,
    });
    let mut t = vec![
        format!("diffraction benchmark ({threads} threads)"),
        format!("  Taylor-term FFTs, {}², N = {} ({} FFTs, powers p = 0…{}):", a.size, a.terms, a.terms + 1, a.terms),
        format!("    iridis, all threads   {:8.2} ms", 1e3 * ours_all),
        format!("    iridis, one thread    {:8.2} ms", 1e3 * ours_one),
        match numpy {
            Some(n) => format!(
                "    numpy (same work)     {:8.2} ms   → iridis is {:.1}× faster (one thread {:.1}×)",
                1e3 * n,
                n / ours_all,
                n / ours_one
            ),
            None => "    numpy                 not available (python3 with numpy not found)".to_string(),
        },
        format!("  lookup tables {}² × {} powers: {:.1} ms", a.uv_resolution, 2 * a.terms + 1, 1e3 * table_secs),
        "  BRDF maps (pixels per second):".to_string(),
    ];
    // The size unpadded, as the first release printed it (a JSON number ignores the width).
    t.extend(maps.iter().map(|(m, s, r)| format!("    {m:<13} {s}²  {r:>14.0}")));
    t.push(format!(
        "  lookup / reference: {:.0}×   lookup / ground truth: {:.0}×",
        lookup_rate / ref_rate,
        lookup_rate / gt_rate
    ));
    Ok(Bench::new(t, json))
}

/// `iridis bench diffraction-methods`' options (with the feature `cli`, its flags).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct MethodsOptions {
    /// Height-field samples per side (65 nm per pixel), one measurement each.
    #[cfg_attr(feature = "cli", arg(long, value_delimiter = ',', default_value = "512,1024"))]
    pub patch_sizes: Vec<usize>,
    /// Side of the BRDF maps both methods render.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 16))]
    pub map_size: usize,
}

impl Default for MethodsOptions {
    fn default() -> Self {
        Self { patch_sizes: vec![512, 1024], map_size: 16 }
    }
}

/// Reference and ground truth on the same patches and map size: seconds per map and maps per second.
pub fn methods(a: &MethodsOptions, report: &dyn Report) -> Result<Bench> {
    use iridis_diffraction::taylor::terms_for_bound;
    if !(4..=256).contains(&a.map_size) {
        bail!("--map-size {} must be between 4 and 256 (the ground truth is slow)", a.map_size);
    }
    let threads = rayon::current_num_threads();
    let spectral = SpectralSetup::default();
    let mut rows = Vec::new();
    let mut t = vec![
        format!("reference vs ground truth, {}² maps, {threads} threads", a.map_size),
        "  patch   N   precompute   reference          ground truth       reference faster by".to_string(),
    ];
    for &n in &a.patch_sizes {
        if !(64..=4096).contains(&n) {
            bail!("--patch-sizes: {n} must be between 64 and 4096");
        }
        let patch = bench_surface(n)?;
        // The window a quarter of the patch side, as in `bench diffraction-accuracy`: inside the patch, so both
        // methods see the same surface.
        let coherence = n as f64 * patch.dx / 4.0;
        let terms_n = terms_for_bound(patch.max_abs_height, 380.0, 1e-6)?;
        report.info(&format!("{n}² patch: Taylor terms (N = {terms_n}) …"));
        let start = Instant::now();
        let terms = Arc::new(TaylorTerms::compute(&patch, terms_n, coherence)?);
        let terms_secs = start.elapsed().as_secs_f64();
        let reference = Reference { terms, shading: Shading::default(), spectral: spectral.clone() };
        let samples = 2 * spectral.wavelengths().len() - 1;
        let truth = GroundTruth::new(&patch, coherence, Shading::default(), &spectral, samples)?;
        report.info(&format!("{n}² patch: reference map {}² …", a.map_size));
        let ref_secs = a.map_size.pow(2) as f64 / map_rate(&reference, a.map_size);
        report.info(&format!("{n}² patch: ground-truth map {}² …", a.map_size));
        let gt_secs = a.map_size.pow(2) as f64 / map_rate(&truth, a.map_size);
        t.push(format!(
            "  {n}² {terms_n}   {terms_secs:>7.2} s   {ref_secs:>8.3} s/map ({:>7.3}/s)   {gt_secs:>8.1} s/map \
             ({:>7.4}/s)   {:>8.0}×",
            1.0 / ref_secs,
            1.0 / gt_secs,
            gt_secs / ref_secs
        ));
        rows.push(json!({
            "patch": n, "taylor_terms": terms_n, "coherence_nm": coherence, "wavenumbers": samples,
            "map_size": a.map_size, "reference_precompute_seconds": terms_secs,
            "reference_seconds_per_map": ref_secs, "ground_truth_seconds_per_map": gt_secs,
            "reference_maps_per_second": 1.0 / ref_secs, "ground_truth_maps_per_second": 1.0 / gt_secs,
            "reference_over_ground_truth": gt_secs / ref_secs,
        }));
    }
    Ok(Bench::new(t, json!({ "threads": threads, "results": rows })))
}

/// `iridis bench diffraction-accuracy`'s options (with the feature `cli`, its flags).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct AccuracyOptions {
    /// Surfaces to measure (repeat the flag); default: the built-in blazed, cd, elaphe and xenopeltis.
    #[cfg_attr(feature = "cli", arg(long = "surface", value_name = "SURFACE"))]
    pub surfaces: Vec<String>,
    /// Side of the BRDF maps compared pixel by pixel (the ground truth is slow: keep it small).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 24))]
    pub map_size: usize,
    /// Coherence length; the default (a quarter of the patch side) keeps the window inside the patch, where
    /// the two ground truths agree, and the finite one's work small.
    #[cfg_attr(feature = "cli", arg(long = "coherence", value_name = "COHERENCE"))]
    #[cfg_attr(feature = "cli", arg(value_parser = crate::args::positive_length_nm))]
    pub coherence_nm: Option<f64>,
    /// The ground truth compared against: periodic (the methods' own model) or finite (the window cut at the
    /// patch edge).
    #[cfg_attr(feature = "cli", arg(long, default_value = "periodic"))]
    pub aperture: String,
    /// Exposures (RU) at which colours are compared.
    #[cfg_attr(feature = "cli", arg(long, value_delimiter = ',', default_value = "1,1000,7500"))]
    pub exposures: Vec<f64>,
    /// u-v resolution of the tables.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 301))]
    pub uv_resolution: usize,
    /// Write the plot of error against the number of Taylor terms here.
    #[cfg_attr(feature = "cli", arg(long))]
    pub convergence_plot: Option<PathBuf>,
    // How each SURFACE is read: a file's pixel size, an image's height of white, its channel, the levelling.
    #[cfg_attr(feature = "cli", command(flatten))]
    pub surface_options: crate::SurfaceOptions,
}

impl Default for AccuracyOptions {
    fn default() -> Self {
        Self {
            surfaces: Vec::new(),
            map_size: 24,
            coherence_nm: None,
            aperture: "periodic".into(),
            exposures: vec![1.0, 1000.0, 7500.0],
            uv_resolution: 301,
            convergence_plot: None,
            surface_options: crate::SurfaceOptions::default(),
        }
    }
}

/// Mean and 95th percentile of the displayed CIEDE2000 between two XYZ maps over the pixels inside the disk.
fn map_delta_e(a: &[Xyz], b: &[Xyz], exposure: f64, size: usize) -> (f64, f64) {
    let disk = disk_pixels(size);
    let pick = |m: &[Xyz]| -> Vec<Xyz> { disk.iter().map(|&i| m[i]).collect() };
    let s = DeltaEStats::between(&pick(a), &pick(b), exposure);
    (s.mean, s.p95)
}

/// CIEDE2000 of lookup (f64, f32, linear grid) and reference against the ground truth, the periodic
/// extension's own error, and the reference's convergence with the number of Taylor terms.
pub fn accuracy(a: &AccuracyOptions, report: &dyn Report) -> Result<Bench> {
    crate::output::declare_opt("--convergence-plot", a.convergence_plot.as_deref(), &["png"])?;
    // A 1² map is the normal direction alone: its "error" of 0 at 1000 RU is two clipped whites.
    crate::brdf_map::check_size_of("--map-size", a.map_size)?;
    let surfaces = if a.surfaces.is_empty() {
        vec!["builtin:blazed".to_string(), "builtin:cd".into(), "builtin:elaphe".into(), "builtin:xenopeltis".into()]
    } else {
        a.surfaces.clone()
    };
    let spectral = SpectralSetup::default();
    let shading = Shading::default();
    let aperture: Aperture = a.aperture.parse()?;
    let truth_name = if aperture == Aperture::Periodic { "ground-truth-periodic" } else { "ground-truth" };
    let mut rows = Vec::new();
    let mut convergence = Vec::new();
    let wi = [0.0, 0.0, 1.0];
    let map = |e: &dyn Evaluator| iridis_diffraction::map::brdf_map(e, wi, a.map_size, 1, &|_| {});
    for spec in &surfaces {
        let patch = crate::surface::load_patch(spec, &a.surface_options, report)?;
        let (ex, ey) = patch.extent();
        let coherence = a.coherence_nm.unwrap_or(ex.min(ey) / 4.0);
        report.info(&format!(
            "{spec}: {}×{} samples, coherence {:.1} µm …",
            patch.cols,
            patch.rows,
            coherence / 1000.0
        ));
        let n = iridis_diffraction::taylor::terms_for_bound(patch.max_abs_height, 380.0, 1e-6)?;
        let terms = TaylorTerms::compute(&patch, n, coherence)?;
        let samples = 2 * spectral.wavelengths().len() - 1;
        let both = [Aperture::Periodic, Aperture::Finite].map(|ap| {
            GroundTruth::with_aperture(&patch, coherence, shading.clone(), &spectral, samples, ap).map(|t| map(&t))
        });
        let [periodic, finite] = both;
        let (periodic, finite) = (periodic?, finite?);
        for &x in &a.exposures {
            let (mean, p95) = map_delta_e(&periodic, &finite, x, a.map_size);
            rows.push(json!({"surface": spec, "method": "periodic-extension", "against": "ground-truth",
                "exposure_ru": x, "mean": mean, "p95": p95}));
        }
        let gt = if aperture == Aperture::Periodic { periodic } else { finite };
        if crate::lit::dark_at_every_exposure(&gt, &a.exposures) {
            // Rows of 0 against a black truth read as perfect agreement (the docs' --map-size 8 example).
            report.warn(&format!(
                "{spec}: the ground truth's {0}² map is black at every exposure, so its rows compare nothing: at a \
                 coherence of {1:.1} µm each lobe is narrower than a pixel; give a larger --map-size or a shorter \
                 --coherence",
                a.map_size,
                coherence / 1000.0
            ));
        }
        let mut methods: Vec<(String, Vec<Xyz>)> = Vec::new();
        for (label, power) in [("lookup", 5.0), ("lookup-linear-grid", 1.0)] {
            let params = TableParams { uv_resolution: a.uv_resolution, uv_power: power };
            let table = Arc::new(LookupTable::build(&terms, &spectral, params, spec, &|_| {})?);
            methods.push((label.into(), map(&Lookup::new(table.clone(), shading.clone(), Precision::F64)?)));
            if power == 5.0 {
                methods.push(("lookup-f32".into(), map(&Lookup::new(table, shading.clone(), Precision::F32)?)));
            }
        }
        let terms = Arc::new(terms);
        let reference = Reference { terms: terms.clone(), shading: shading.clone(), spectral: spectral.clone() };
        methods.push(("reference".into(), map(&reference)));
        for (label, m) in &methods {
            for &x in &a.exposures {
                let (mean, p95) = map_delta_e(m, &gt, x, a.map_size);
                rows.push(json!({"surface": spec, "method": label, "against": truth_name, "exposure_ru": x,
                    "mean": mean, "p95": p95}));
            }
        }
        // Convergence of the Taylor sum: reference with N' terms against the ground truth at 1000 RU.
        let mut curve = Vec::new();
        for k in (0..=n).step_by((n / 10).max(1)).chain(std::iter::once(n)) {
            let t = Arc::new(TaylorTerms::compute(&patch, k, coherence)?);
            let r = Reference { terms: t, shading: shading.clone(), spectral: spectral.clone() };
            let (mean, _) = map_delta_e(&map(&r), &gt, 1000.0, a.map_size);
            curve.push((k as f64, mean));
        }
        curve.dedup_by(|x, y| x.0 == y.0);
        convergence.push((spec.clone(), curve));
    }
    if let Some(path) = &a.convergence_plot {
        let mut plot = iridis_plot::LinePlot::new(
            "Taylor series convergence (reference vs ground truth, 1000 RU)",
            "Taylor terms N",
            "mean CIEDE2000",
        );
        for (name, curve) in &convergence {
            let xs: Vec<f64> = curve.iter().map(|p| p.0).collect();
            let ys: Vec<f64> = curve.iter().map(|p| p.1.max(1e-4).log10()).collect();
            plot = plot.series(iridis_plot::Series::new(name.clone(), &xs, &ys));
        }
        plot.y_label = "log10 mean CIEDE2000".into();
        let img = plot.render()?;
        crate::output::write_png_rgb8(path, img.width, img.height, &img.data)?;
        report.info(&format!("wrote {}", path.display()));
    }
    let mut t = vec![format!(
        "CIEDE2000 against {truth_name} ({}² maps, normal incidence); periodic-extension: {} vs {}",
        a.map_size, "ground-truth-periodic", "ground-truth (finite aperture)"
    )];
    let names: Vec<&str> = rows.iter().map(|r| r["surface"].as_str().unwrap_or("")).collect();
    let w = super::name_column_width("surface", names.iter().copied());
    t.push(format!("{:<w$} {:<20} {:<22} {:>8} {:>10} {:>10}", "surface", "method", "against", "RU", "mean", "p95"));
    for (r, name) in rows.iter().zip(&names) {
        t.push(format!(
            "{:<w$} {:<20} {:<22} {:>8.1} {:>10.4} {:>10.4}",
            name,
            r["method"].as_str().unwrap_or(""),
            r["against"].as_str().unwrap_or(""),
            r["exposure_ru"].as_f64().unwrap_or(f64::NAN),
            r["mean"].as_f64().unwrap_or(f64::NAN),
            r["p95"].as_f64().unwrap_or(f64::NAN)
        ));
    }
    let json = json!({
        "map_size": a.map_size,
        "against": truth_name,
        "uv_resolution": a.uv_resolution,
        "results": rows,
        "convergence": convergence.iter().map(|(s, c)| json!({"surface": s, "terms_vs_mean_delta_e": c})).collect::<Vec<_>>(),
    });
    Ok(Bench::new(t, json))
}
