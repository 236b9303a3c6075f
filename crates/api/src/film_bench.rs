//! The thin-film benchmark (`iridis thinfilm bench`, Python's `iridis.film.bench`): (λ, θ) evaluations per
//! second on the general and the fast path against the Python `tmm` package in the same run, the fit of
//! tools/fit_scipy_compare.py timed, and a batch of 10⁶ points. Speed is measured against a peer, never
//! asserted in tests.

use std::fmt::Write as _;
use std::time::Instant;

use anyhow::{bail, Result};
use iridis_thinfilm::grid::{evaluate_grid, Path as GridPath};
use iridis_thinfilm::Stack;
use serde_json::json;

use crate::film::parse_stack;

/// The 2-layer stack: an oil slick on water over asphalt.
pub const BENCH_2: &str = "air | gasoline 216nm | water 220nm | asphalt";

/// The 20-layer stack: a quarter-wave mirror.
pub fn bench_20() -> String {
    // A 10-pair quarter-wave mirror for 550 nm: TiO2-like n = 2.35 and MgF2-like n = 1.38 on glass.
    let mut s = String::from("air");
    for _ in 0..10 {
        s += &format!(" | n=2.35 {}nm | n=1.38 {}nm", 550.0 / (4.0 * 2.35), 550.0 / (4.0 * 1.38));
    }
    s + " | n=1.5"
}

/// The Python side: the same stack and grid through tmm.coh_tmm (s and p per evaluation).
const TMM_SCRIPT: &str = r#"
import json, sys, time, math
try:
    import numpy as np, tmm
except Exception as e:
    print(json.dumps({"error": "python3 has no tmm/numpy: %s" % e})); sys.exit(0)
spec = json.loads(sys.argv[1])
ns = [complex(a, b) for a, b in spec["n"]]
ds = [float("inf")] + spec["d"] + [float("inf")]
lams = spec["wavelengths"]; ths = spec["angles"]
count = 0; t0 = time.perf_counter(); acc = 0.0
while True:
    for th in ths:
        for lam in lams:
            s = tmm.coh_tmm("s", ns, ds, th, lam); p = tmm.coh_tmm("p", ns, ds, th, lam)
            acc += s["R"] + p["R"] + s["T"] + p["T"]; count += 1
    if time.perf_counter() - t0 > spec["seconds"]:
        break
dt = time.perf_counter() - t0
print(json.dumps({"evals": count, "seconds": dt, "per_second": count / dt, "check": acc,
                  "tmm": __import__("importlib.metadata").metadata.version("tmm"), "python": sys.version.split()[0]}))
"#;

/// (λ, θ) evaluations per second of `stack` on the grid, repeated for at least `seconds`.
pub fn time_rust(
    stack: &Stack,
    angles: &[f64],
    wl: &[f64],
    path: GridPath,
    threads: bool,
    seconds: f64,
) -> Result<f64> {
    let mut n = 0usize;
    let t0 = Instant::now();
    let mut sink = 0.0;
    loop {
        let xs = evaluate_grid(stack, angles, wl, path, threads)?;
        sink += xs.iter().map(|x| x.r() + x.t()).sum::<f64>();
        n += xs.len();
        if t0.elapsed().as_secs_f64() >= seconds {
            break;
        }
    }
    std::hint::black_box(sink);
    Ok(n as f64 / t0.elapsed().as_secs_f64())
}

/// The same work in Python's tmm (spawning `python3`): its JSON answer, or why it did not run.
pub fn time_tmm(
    stack: &Stack,
    angles: &[f64],
    wl: &[f64],
    seconds: f64,
) -> std::result::Result<serde_json::Value, String> {
    let n: Vec<[f64; 2]> = stack
        .materials()
        .map(|m| m.index_at(550.0).map(|z| [z.re, z.im]).map_err(|e| e.to_string()))
        .collect::<std::result::Result<_, _>>()?;
    let spec = json!({ "n": n, "d": stack.thicknesses(), "wavelengths": wl, "angles": angles, "seconds": seconds });
    let out = std::process::Command::new("python3")
        .arg("-c")
        .arg(TMM_SCRIPT)
        .arg(spec.to_string())
        .output()
        .map_err(|e| format!("python3 not found ({e}); tmm not timed"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let v: serde_json::Value = serde_json::from_str(text.trim())
        .map_err(|_| format!("python3 failed: {}", String::from_utf8_lossy(&out.stderr).trim()))?;
    if let Some(e) = v.get("error") {
        return Err(e.as_str().unwrap_or("tmm failed").to_string());
    }
    Ok(v)
}

/// `iridis thinfilm bench` (Python's `iridis.film.bench`): (λ, θ) evaluations per second of a 2-layer and a
/// 20-layer stack on the general and the fast path, one thread and all, against Python's tmm (spawning
/// `python3`, unless `no_python`); a fit of 3 parameters; a batch of 10⁶ points ([`bench_batch`]: fewer
/// below 1 s). Each Rust measurement runs for at least `seconds`.
pub fn bench(seconds: f64, no_python: bool) -> Result<FilmBench> {
    // About a dozen measurements each run for at least `seconds`: an hour of them is the most taken.
    if !(seconds.is_finite() && seconds > 0.0 && seconds <= 300.0) {
        bail!(
            "--seconds {}: must be positive and at most 300 s (each of about 12 measurements runs that long)",
            iridis_color::spectrum::short_number(seconds)
        );
    }
    let threads = iridis_thinfilm::grid::threads();
    let wl: Vec<f64> = (0..81).map(|i| 380.0 + 5.0 * i as f64).collect();
    let angles: Vec<f64> = (0..90).map(|d| f64::to_radians(d as f64)).collect();
    // tmm is slow: give it a sub-grid (the per-evaluation cost does not depend on the grid).
    let wl_py: Vec<f64> = wl.iter().step_by(8).copied().collect();
    let angles_py: Vec<f64> = angles.iter().step_by(9).copied().collect();
    let mut results = Vec::new();
    for (label, text) in
        [("2 layers (oil slick)", BENCH_2.to_string()), ("20 layers (quarter-wave mirror)", bench_20())]
    {
        let stack = parse_stack(&text)?;
        let g1 = time_rust(&stack, &angles, &wl, GridPath::General, false, seconds)?;
        let gn = time_rust(&stack, &angles, &wl, GridPath::General, true, seconds)?;
        let f1 = time_rust(&stack, &angles, &wl, GridPath::Auto, false, seconds)?;
        let fnn = time_rust(&stack, &angles, &wl, GridPath::Auto, true, seconds)?;
        let py = if no_python {
            Err("not run (--no-python)".to_string())
        } else {
            time_tmm(&stack, &angles_py, &wl_py, seconds.max(1.0))
        };
        let tmm = py.as_ref().ok().and_then(|v| v["per_second"].as_f64());
        results.push(json!({
            "stack": label,
            "layers": stack.layers.len(),
            "rust_general_1_thread": g1,
            "rust_general_all_threads": gn,
            "rust_fast_1_thread": f1,
            "rust_fast_all_threads": fnn,
            "tmm_1_thread": tmm,
            "tmm_note": match &py { Ok(v) => format!("tmm {} on Python {}", v["tmm"].as_str().unwrap_or("?"), v["python"].as_str().unwrap_or("?")), Err(e) => e.clone() },
            "speedup_general_1_thread": tmm.map(|t| g1 / t),
            "speedup_fast_1_thread": tmm.map(|t| f1 / t),
        }));
    }
    let fit = bench_fit(seconds)?;
    let batch = bench_batch(seconds)?;
    Ok(FilmBench(json!({
        "threads": threads, "unit": "(λ, θ) evaluations per second, R and T for s and p", "results": results,
        "fit": fit, "batch": batch,
    })))
}

/// The measurements of [`fn@bench`], as `--json` prints them.
#[derive(Debug, Clone)]
pub struct FilmBench(pub serde_json::Value);

impl FilmBench {
    /// What `--json` prints.
    pub fn to_json(&self) -> serde_json::Value {
        self.0.clone()
    }

    /// The table for people.
    pub fn text(&self) -> String {
        let (v, mut o) = (&self.0, String::new());
        let num = |x: &serde_json::Value| x.as_f64().unwrap_or(0.0);
        let or_dash = |x: Option<f64>| x.map(|v| format!("{v:.0}")).unwrap_or_else(|| "—".into());
        let _ = writeln!(o, "(λ, θ) evaluations per second (R and T, s and p); all threads = {}", v["threads"]);
        let _ = writeln!(
            o,
            "{:<34} {:>14} {:>14} {:>14} {:>14} {:>12} {:>9}",
            "stack", "general 1 thr", "general all", "fast 1 thr", "fast all", "tmm (Python)", "× tmm"
        );
        let results = v["results"].as_array().cloned().unwrap_or_default();
        for r in &results {
            let _ = writeln!(
                o,
                "{:<34} {:>14.0} {:>14.0} {:>14.0} {:>14.0} {:>12} {:>9}",
                r["stack"].as_str().unwrap_or(""),
                num(&r["rust_general_1_thread"]),
                num(&r["rust_general_all_threads"]),
                num(&r["rust_fast_1_thread"]),
                num(&r["rust_fast_all_threads"]),
                or_dash(r["tmm_1_thread"].as_f64()),
                or_dash(r["speedup_general_1_thread"].as_f64()),
            );
        }
        if let Some(note) = results.first().and_then(|r| r["tmm_note"].as_str()) {
            let _ = writeln!(o, "tmm: {note}");
        }
        let _ = writeln!(o, "× tmm compares the general path on one thread with tmm on one thread.");
        let (fit, batch) = (&v["fit"], &v["batch"]);
        let ms = |k: &str| 1e3 * fit[k].as_f64().unwrap_or(f64::NAN);
        let _ = writeln!(
            o,
            "fit, 3 parameters on 401 wavelengths (tools/fit_scipy_compare.py's data): {:.2} ms from one start, \
             {:.2} ms with the multi-start search ({} starts), exact derivatives; with finite differences {:.2} ms \
             and {:.2} ms; scipy least_squares + tmm: see docs/thinfilm.md",
            ms("single_start_seconds"),
            ms("multi_start_seconds"),
            fit["multi_start_starts"],
            ms("single_start_fd_seconds"),
            ms("multi_start_fd_seconds"),
        );
        let _ = writeln!(
            o,
            "batch of {} (λ, θ) points, 20 layers, all threads: fast path {:.3} s, general path {:.3} s",
            match batch["points"].as_u64() {
                Some(1_000_000) => "10⁶".to_string(),
                Some(p) => p.to_string(),
                None => "?".to_string(),
            },
            batch["fast_seconds"].as_f64().unwrap_or(f64::NAN),
            batch["general_seconds"].as_f64().unwrap_or(f64::NAN)
        );
        o
    }
}

/// The fit of tools/fit_scipy_compare.py (the same CSV), timed from one start and with the search.
pub fn bench_fit(seconds: f64) -> Result<serde_json::Value> {
    use iridis_filmfit::{fit, Derivatives, FitOptions, Measured, Quantity, Template};
    const CSV: &str = include_str!("../../filmfit/tests/fixtures/scipy_fit.csv");
    const STACK: &str = "air | cauchy:{A=1.5:1.3..1.7},{B=0.004:0..0.02} {d=330nm:100nm..600nm} | n=3.88+0.02i";
    let t = Template::parse(STACK)?;
    let mut data = Measured::from_csv(CSV, "scipy_fit.csv", Quantity::R, None)?;
    data.sigma = Some(vec![0.002; data.values.len()]);
    let mut out = json!({ "stack": STACK, "wavelengths": data.values.len(), "parameters": 3 });
    // Exact derivatives (the default) and the finite-difference fallback, for comparison.
    let runs = [
        ("single_start", 1, Derivatives::Exact),
        ("multi_start", 0, Derivatives::Exact),
        ("single_start_fd", 1, Derivatives::FiniteDifferences),
        ("multi_start_fd", 0, Derivatives::FiniteDifferences),
    ];
    for (key, grid, derivatives) in runs {
        let opt = FitOptions { grid, derivatives, ..FitOptions::default() };
        let (mut n, t0) = (0usize, Instant::now());
        let mut last = None;
        while n == 0 || t0.elapsed().as_secs_f64() < seconds {
            last = Some(fit(&t, &data, &opt)?);
            n += 1;
        }
        let r = last.expect("ran at least once");
        out[format!("{key}_seconds")] = json!(t0.elapsed().as_secs_f64() / n as f64);
        out[format!("{key}_starts")] = json!(r.starts_tried);
        out[format!("{key}_values")] = json!(r.values);
        out[format!("{key}_evaluations")] = json!(r.evaluations);
    }
    Ok(out)
}

/// 10⁶ (λ, θ) evaluations of the 20-layer stack, all threads: 1000 angles × 1000 wavelengths at `seconds` ≥ 1
/// (the default), that share of the angles below (at least 10), so that a short bench is short.
pub fn bench_batch(seconds: f64) -> Result<serde_json::Value> {
    let stack = parse_stack(&bench_20())?;
    let n = ((1000.0 * seconds.min(1.0)).round() as usize).max(10);
    let angles: Vec<f64> = (0..n).map(|i| f64::to_radians(89.0 * i as f64 / (n - 1) as f64)).collect();
    let wl: Vec<f64> = (0..1000).map(|i| 380.0 + 0.4 * i as f64).collect();
    let mut out = json!({ "points": angles.len() * wl.len(), "layers": stack.layers.len(), "threads": iridis_thinfilm::grid::threads() });
    for (key, path) in [("fast_seconds", GridPath::Auto), ("general_seconds", GridPath::General)] {
        let t0 = Instant::now();
        let xs = evaluate_grid(&stack, &angles, &wl, path, true)?;
        std::hint::black_box(xs.iter().map(|x| x.r()).sum::<f64>());
        out[key] = json!(t0.elapsed().as_secs_f64());
    }
    Ok(out)
}
