//! `iridis bench …`: speed measured against a peer in the same run (numpy for FFT work; the slower methods
//! for the lookup path). Nothing here is a test: tests never depend on wall-clock time.

use std::process::Command;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::{Args as ClapArgs, Subcommand};
use iridis_diffraction::evaluator::{Aperture, Evaluator, GroundTruth, Reference};
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::{Patch, Shading, SpectralSetup, TaylorTerms};
use serde_json::json;

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
    Gpu(super::gpu::GpuBench),
    /// Rendering: load and render time of every example scene (default 1024², 1 spp, all cores).
    #[command(after_help = "Examples:\n  iridis bench render\n  iridis bench render --size 512 --spp 4 --json")]
    Render(super::render::RenderBench),
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
    pub convergence_plot: Option<std::path::PathBuf>,
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

pub fn run(c: BenchCommand) -> Result<()> {
    match c {
        BenchCommand::Diffraction(a) => diffraction(a),
        BenchCommand::DiffractionAccuracy(a) => accuracy(a),
        BenchCommand::DiffractionMethods(a) => methods(a),
        BenchCommand::Gpu(a) => super::gpu::bench(a),
        BenchCommand::Render(a) => super::render::bench(a),
        BenchCommand::Grating(a) => grating(a),
    }
}

/// A reproducible rough surface: a sum of random gratings (σ_h ≈ 60 nm) at 65 nm per pixel.
fn bench_surface(n: usize) -> Result<Patch> {
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

/// Times the same Taylor-term FFTs in numpy (one thread: numpy's FFT is single-threaded).
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
    let map = iridis_diffraction::map::brdf_map(e, [0.0, 0.0, 1.0], size, &|_| {});
    let secs = start.elapsed().as_secs_f64();
    std::hint::black_box(map);
    (size * size) as f64 / secs
}

fn diffraction(a: DiffractionBench) -> Result<()> {
    let threads = rayon::current_num_threads();
    eprintln!("surface {}², {} terms, {threads} threads …", a.size, a.terms);
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
    eprintln!("numpy …");
    let numpy = numpy_fft_seconds(&patch, a.terms)?;

    let spectral = SpectralSetup::default();
    eprintln!("lookup tables {}² …", a.uv_resolution);
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
        eprintln!("lookup map {s}² …");
        maps.push(json!({"method": "lookup", "size": s, "pixels_per_second": map_rate(&lookup, s)}));
    }
    eprintln!("reference map 48² …");
    let ref_rate = map_rate(&reference, 48);
    maps.push(json!({"method": "reference", "size": 48, "pixels_per_second": ref_rate}));
    eprintln!("ground-truth map 8² …");
    let gt_rate = map_rate(&truth, 8);
    maps.push(json!({"method": "ground-truth", "size": 8, "pixels_per_second": gt_rate}));
    let lookup_rate = maps[0]["pixels_per_second"].as_f64().unwrap_or(0.0);

    let report = json!({
        "threads": threads,
        "surface": {"size": a.size, "terms": a.terms},
        "precompute_fft_seconds": {"iridis_all_threads": ours_all, "iridis_one_thread": ours_one, "numpy": numpy},
        "lookup_table_seconds": table_secs,
        "uv_resolution": a.uv_resolution,
        "maps": maps,
        "lookup_over_reference": lookup_rate / ref_rate,
        "lookup_over_ground_truth": lookup_rate / gt_rate,
    });
    if a.json {
        return crate::output::print_json(&report);
    }
    crate::outln!("diffraction benchmark ({threads} threads)")?;
    crate::outln!("  Taylor-term FFTs, {}², {} terms:", a.size, a.terms + 1)?;
    crate::outln!("    iridis, all threads   {ours_all:8.2} s")?;
    crate::outln!("    iridis, one thread    {ours_one:8.2} s")?;
    match numpy {
        Some(n) => crate::outln!(
            "    numpy (same work)     {n:8.2} s   → iridis is {:.1}× faster (one thread {:.1}×)",
            n / ours_all,
            n / ours_one
        ),
        None => crate::outln!("    numpy                 not available (python3 with numpy not found)"),
    }?;
    crate::outln!("  lookup tables {}² × {} powers: {table_secs:.1} s", a.uv_resolution, 2 * a.terms + 1)?;
    crate::outln!("  BRDF maps (pixels per second):")?;
    for m in report["maps"].as_array().into_iter().flatten() {
        crate::outln!(
            "    {:<13} {:>5}²  {:>14.0}",
            m["method"].as_str().unwrap_or(""),
            m["size"],
            m["pixels_per_second"].as_f64().unwrap_or(0.0)
        )?;
    }
    crate::outln!(
        "  lookup / reference: {:.0}×   lookup / ground truth: {:.0}×",
        lookup_rate / ref_rate,
        lookup_rate / gt_rate
    )?;
    Ok(())
}

/// Reference and ground truth on the same patches and map size: seconds per map and maps per second.
fn methods(a: MethodsBench) -> Result<()> {
    use iridis_diffraction::taylor::terms_for_bound;
    if !(4..=256).contains(&a.map_size) {
        anyhow::bail!("--map-size {} must be between 4 and 256 (the ground truth is slow)", a.map_size);
    }
    let threads = rayon::current_num_threads();
    let spectral = SpectralSetup::default();
    let mut rows = Vec::new();
    for &n in &a.patch_sizes {
        if !(64..=4096).contains(&n) {
            anyhow::bail!("--patch-sizes: {n} must be between 64 and 4096");
        }
        let patch = bench_surface(n)?;
        // The window a quarter of the patch side, as in `bench diffraction-accuracy`: inside the patch, so both
        // methods see the same surface.
        let coherence = n as f64 * patch.dx / 4.0;
        let terms_n = terms_for_bound(patch.max_abs_height, 380.0, 1e-6);
        eprintln!("{n}² patch: Taylor terms (N = {terms_n}) …");
        let t = Instant::now();
        let terms = Arc::new(TaylorTerms::compute(&patch, terms_n, coherence)?);
        let terms_secs = t.elapsed().as_secs_f64();
        let reference = Reference { terms, shading: Shading::default(), spectral: spectral.clone() };
        let samples = 2 * spectral.wavelengths().len() - 1;
        let truth = GroundTruth::new(&patch, coherence, Shading::default(), &spectral, samples)?;
        eprintln!("{n}² patch: reference map {}² …", a.map_size);
        let ref_secs = a.map_size.pow(2) as f64 / map_rate(&reference, a.map_size);
        eprintln!("{n}² patch: ground-truth map {}² …", a.map_size);
        let gt_secs = a.map_size.pow(2) as f64 / map_rate(&truth, a.map_size);
        rows.push(json!({
            "patch": n, "taylor_terms": terms_n, "coherence_nm": coherence, "wavenumbers": samples,
            "map_size": a.map_size, "reference_precompute_seconds": terms_secs,
            "reference_seconds_per_map": ref_secs, "ground_truth_seconds_per_map": gt_secs,
            "reference_maps_per_second": 1.0 / ref_secs, "ground_truth_maps_per_second": 1.0 / gt_secs,
            "reference_over_ground_truth": gt_secs / ref_secs,
        }));
    }
    let report = json!({ "threads": threads, "results": rows });
    if a.json {
        return crate::output::print_json(&report);
    }
    crate::outln!("reference vs ground truth, {}² maps, {threads} threads", a.map_size)?;
    crate::outln!("  patch   N   precompute   reference          ground truth       reference faster by")?;
    for r in rows {
        let f = |k: &str| r[k].as_f64().unwrap_or(f64::NAN);
        crate::outln!(
            "  {:>5}² {:>3}   {:>7.2} s   {:>8.3} s/map ({:>7.3}/s)   {:>8.1} s/map ({:>7.4}/s)   {:>8.0}×",
            r["patch"],
            r["taylor_terms"],
            f("reference_precompute_seconds"),
            f("reference_seconds_per_map"),
            f("reference_maps_per_second"),
            f("ground_truth_seconds_per_map"),
            f("ground_truth_maps_per_second"),
            f("reference_over_ground_truth")
        )?;
    }
    Ok(())
}

/// Mean and 95th percentile of CIEDE2000 between two XYZ maps at an exposure (pixels inside the disk).
pub fn delta_e_stats(a: &[iridis_color::Xyz], b: &[iridis_color::Xyz], exposure: f64, size: usize) -> (f64, f64) {
    use iridis_color::integrate::white_point;
    use iridis_color::{Illuminant, Lab, Observer};
    let white = white_point(Illuminant::D65, Observer::Cie1931);
    // Colours as displayed: exposure, clipped to the sRGB gamut's unit cube, back to XYZ.
    let shown = |x: iridis_color::Xyz| {
        let rgb = x.scale(exposure).to_linear_srgb().map(|c| c.clamp(0.0, 1.0));
        Lab::from_xyz(iridis_color::Xyz::from_linear_srgb(rgb), white)
    };
    let mut d: Vec<f64> = (0..size * size)
        .filter(|&i| iridis_diffraction::map::view_direction(i % size, i / size, size).is_some())
        .map(|i| iridis_color::lab::delta_e_2000(shown(a[i]), shown(b[i])))
        .collect();
    d.sort_by(|x, y| x.total_cmp(y));
    let mean = d.iter().sum::<f64>() / d.len().max(1) as f64;
    let p95 = d.get(((d.len() as f64 * 0.95) as usize).min(d.len().saturating_sub(1))).copied().unwrap_or(0.0);
    (mean, p95)
}

fn accuracy(a: AccuracyBench) -> Result<()> {
    crate::output::declare_opt("--convergence-plot", a.convergence_plot.as_deref(), &["png"])?;
    use iridis_api::surface::load_patch;
    let surfaces = if a.surface.is_empty() {
        vec!["builtin:blazed".to_string(), "builtin:cd".into(), "builtin:elaphe".into(), "builtin:xenopeltis".into()]
    } else {
        a.surface.clone()
    };
    let spectral = SpectralSetup::default();
    let shading = Shading::default();
    let aperture: Aperture = a.aperture.parse()?;
    let truth_name = if aperture == Aperture::Periodic { "ground-truth-periodic" } else { "ground-truth" };
    let mut rows = Vec::new();
    let mut convergence = Vec::new();
    let wi = [0.0, 0.0, 1.0];
    let map = |e: &dyn Evaluator| iridis_diffraction::map::brdf_map(e, wi, a.map_size, &|_| {});
    for spec in &surfaces {
        let patch = load_patch(spec, &Default::default(), &crate::progress::Cli)?;
        let (ex, ey) = patch.extent();
        let coherence = a.coherence.unwrap_or(ex.min(ey) / 4.0);
        eprintln!("{spec}: {}×{} samples, coherence {:.1} µm …", patch.cols, patch.rows, coherence / 1000.0);
        let n = iridis_diffraction::taylor::terms_for_bound(patch.max_abs_height, 380.0, 1e-6);
        let terms = TaylorTerms::compute(&patch, n, coherence)?;
        let samples = 2 * spectral.wavelengths().len() - 1;
        let both = [Aperture::Periodic, Aperture::Finite].map(|ap| {
            GroundTruth::with_aperture(&patch, coherence, shading.clone(), &spectral, samples, ap).map(|t| map(&t))
        });
        let [periodic, finite] = both;
        let (periodic, finite) = (periodic?, finite?);
        for &x in &a.exposures {
            let (mean, p95) = delta_e_stats(&periodic, &finite, x, a.map_size);
            rows.push(json!({"surface": spec, "method": "periodic-extension", "against": "ground-truth",
                "exposure_ru": x, "mean": mean, "p95": p95}));
        }
        let gt = if aperture == Aperture::Periodic { periodic } else { finite };
        let mut methods: Vec<(String, Vec<iridis_color::Xyz>)> = Vec::new();
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
                let (mean, p95) = delta_e_stats(m, &gt, x, a.map_size);
                rows.push(json!({"surface": spec, "method": label, "against": truth_name, "exposure_ru": x,
                    "mean": mean, "p95": p95}));
            }
        }
        // Convergence of the Taylor sum: reference with N' terms against the ground truth at 1000 RU.
        let mut curve = Vec::new();
        for k in (0..=n).step_by((n / 10).max(1)).chain(std::iter::once(n)) {
            let t = Arc::new(TaylorTerms::compute(&patch, k, coherence)?);
            let r = Reference { terms: t, shading: shading.clone(), spectral: spectral.clone() };
            let (mean, _) = delta_e_stats(&map(&r), &gt, 1000.0, a.map_size);
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
        eprintln!("wrote {}", path.display());
    }
    let report = json!({
        "map_size": a.map_size,
        "against": truth_name,
        "uv_resolution": a.uv_resolution,
        "results": rows,
        "convergence": convergence.iter().map(|(s, c)| json!({"surface": s, "terms_vs_mean_delta_e": c})).collect::<Vec<_>>(),
    });
    if a.json {
        return crate::output::print_json(&report);
    }
    crate::outln!(
        "CIEDE2000 against {truth_name} ({}² maps, normal incidence); periodic-extension: {} vs {}",
        a.map_size,
        "ground-truth-periodic",
        "ground-truth (finite aperture)"
    )?;
    crate::outln!("{:<22} {:<20} {:<22} {:>8} {:>10} {:>10}", "surface", "method", "against", "RU", "mean", "p95")?;
    for r in &rows {
        crate::outln!(
            "{:<22} {:<20} {:<22} {:>8} {:>10.4} {:>10.4}",
            r["surface"].as_str().unwrap_or(""),
            r["method"].as_str().unwrap_or(""),
            r["against"].as_str().unwrap_or(""),
            r["exposure_ru"],
            r["mean"].as_f64().unwrap_or(f64::NAN),
            r["p95"].as_f64().unwrap_or(f64::NAN)
        )?;
    }
    Ok(())
}

fn grating(a: GratingBench) -> Result<()> {
    let opts = iridis_api::grating_bench::GratingBenchOptions {
        repeats: a.repeats,
        python: (!a.no_python).then_some(a.python.clone()),
        peer_seconds: a.peer_seconds,
        batch: a.batch,
        quick: a.quick,
    };
    let v = iridis_api::grating_bench::bench_grating(&opts, &crate::progress::Cli)?;
    if a.json {
        return crate::output::print_json(&v);
    }
    let f = |v: &serde_json::Value| v.as_f64().unwrap_or(f64::NAN);
    crate::outln!(
        "rigorous order efficiencies: iridis (C-method) against grcwa (RCWA), equal accuracy; {} threads",
        v["threads"]
    )?;
    for c in v["cases"].as_array().into_iter().flatten() {
        let i = &c["iridis"];
        let t = &c["throughput"];
        crate::outln!(
            "{}: λ {} nm, θ {}°, φ {}°",
            c["name"].as_str().unwrap_or(""),
            c["wavelength_nm"],
            c["theta_i_deg"],
            c["phi_i_deg"]
        )?;
        crate::outln!(
            "  iridis   orders {} ({} harmonics): {:.4} s per solve (one thread, TE+TM), error {:.1e} (estimated {:.1e})",
            i["orders"],
            i["harmonics"],
            f(&i["seconds"]),
            f(&i["measured_error"]),
            f(&i["estimated_error"])
        )?;
        crate::outln!(
            "           {} wavelengths {}–{} nm: {:.2} solves/s on one thread, {:.2} on all ({:.1}×)",
            t["problems"],
            t["wavelengths_nm"][0],
            t["wavelengths_nm"][1],
            f(&t["one_thread_per_second"]),
            f(&t["all_threads_per_second"]),
            f(&t["parallel_speedup"])
        )?;
        for p in c["peers"].as_array().into_iter().flatten() {
            let name = p["name"].as_str().unwrap_or("peer");
            if p["status"] != "ok" {
                crate::outln!("  {name}    skipped: {}", p["note"].as_str().unwrap_or(""))?;
                continue;
            }
            crate::outln!(
                "  {name} {} ({}; error on {}):",
                p["version"].as_str().unwrap_or(""),
                p["python"].as_str().unwrap_or(""),
                p["error_measured_on"].as_str().unwrap_or("")
            )?;
            for r in p["ladder"].as_array().into_iter().flatten() {
                crate::outln!(
                    "    {:>4} orders, {:>4} slices: {:>9.3} s, error {:.1e} (TE {:.1e}, TM {:.1e})",
                    r["orders"],
                    r["slices"],
                    f(&r["seconds"]),
                    f(&r["error"]),
                    f(&r["error_te"]),
                    f(&r["error_tm"])
                )?;
            }
            let level = |k: &str| {
                let r = &p[k];
                if r.is_null() {
                    "not reached".to_string()
                } else {
                    format!("{}/{} orders/slices, {:.3} s", r["orders"], r["slices"], f(&r["seconds"]))
                }
            };
            crate::outln!("    within 1 %: {}; within 0.1 %: {}", level("at_1_percent"), level("at_0_1_percent"))?;
            match (p["speedup_at_1_percent"].as_f64(), p["speedup_lower_bound"].as_f64()) {
                (Some(s), _) => crate::outln!("    iridis is {s:.0}× faster at 1 % (one thread each)")?,
                (None, Some(b)) => {
                    crate::outln!("    iridis is more than {b:.0}× faster ({})", p["note"].as_str().unwrap_or(""))?
                }
                _ => {}
            }
        }
    }
    crate::outln!("load average before / after: {} / {}", v["load_average"]["before"], v["load_average"]["after"])?;
    Ok(())
}
