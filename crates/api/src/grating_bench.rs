//! `iridis bench grating`: the rigorous solver (`iridis-rigorous`, the C-method) timed on a 1-D and a 2-D
//! grating against grcwa (PyPI, staircase RCWA) in the same run, at equal accuracy, on one core, and the
//! solver's throughput over many wavelengths on one core and on all cores.
//!
//! Accuracy: our timed answer against the same problem with more Fourier orders (the library's
//! [`iridis_rigorous::benchmark`]); the peer walks a ladder of (orders, slices) until every propagating
//! efficiency above 1e-3 is within 1 % of that reference (then 0.1 %), and its time at the first rung that
//! meets each level is compared with ours. On a
//! metal the peer's error is measured on TE only: staircase RCWA does not converge in TM there (Popov et al.,
//! JOSA A 19, 33, 2002), which the ladder's `error_tm` shows. Python is optional: without it, or without
//! grcwa, the peer is skipped with a note.

use std::process::Command;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use iridis_rigorous::{BenchCase, BenchReport, Problem};
use serde_json::{json, Value};

use crate::report::Report;

/// What `iridis bench grating` asks.
#[derive(Debug, Clone)]
pub struct GratingBenchOptions {
    /// Timed solves per case (the best counts).
    pub repeats: usize,
    /// The Python that runs the peer; `None`: no peer.
    pub python: Option<String>,
    /// The peer's ladder stops after a rung that took longer than this (seconds, TE and TM together).
    pub peer_seconds: f64,
    /// Problems (wavelengths 400–700 nm) of the throughput measurement per case.
    pub batch: usize,
    /// Tiny cases (a 10 nm sine, a 10 nm crossed sine of period 300 nm), one repeat and two wavelengths in the
    /// throughput: shows the command works, measures nothing.
    pub quick: bool,
}

impl Default for GratingBenchOptions {
    fn default() -> Self {
        Self { repeats: 3, python: Some("python3".into()), peer_seconds: 60.0, batch: 8, quick: false }
    }
}

/// The cases: the library's standard ones (a sine of a/Λ = 0.1 on metal ε = −20 + 1i and on glass, a crossed
/// sine on glass), or tiny ones for `quick`: glass only, 10 nm deep, the crossed sine at a period of 300 nm
/// (fewer propagating orders, so a small truncation).
pub fn cases(quick: bool) -> Vec<BenchCase> {
    let mut c = BenchCase::standard();
    if quick {
        c.retain(|c| c.eps[0] > 0.0);
        for c in c.iter_mut() {
            c.amplitude_nm = 10.0;
            if c.two_d {
                c.period_nm = 300.0;
            }
            c.name = format!("{} (quick: 10 nm, Λ = {} nm)", c.name, c.period_nm);
        }
    }
    c
}

/// The grcwa side: one case through a ladder of (orders, slices) rungs, each rung solved for TE and TM; JSON on
/// stdout (`error` when numpy or grcwa is missing).
const GRCWA_SCRIPT: &str = r#"
import json, sys, time
try:
    import numpy as np, grcwa
except Exception as e:
    print(json.dumps({"error": "no grcwa/numpy in this Python (pip install grcwa): %s" % e})); sys.exit(0)
from importlib.metadata import version
grcwa.set_backend("numpy")
spec = json.loads(sys.argv[1])
case, ref = spec["case"], spec["reference"]
p, a, two_d = case["period_nm"], case["amplitude_nm"], case["two_d"]
eps = complex(case["eps"][0], case["eps"][1])
metal = case["eps"][0] < 0

def solve(n_orders, slices, pol, nx):
    l2 = [0, p] if two_d else [0, p * 1e-3]
    obj = grcwa.obj(n_orders, [p, 0], l2, 1.0 / case["wavelength_nm"], np.radians(case["theta_i_deg"]),
                    np.radians(case["phi_i_deg"] + 180.0), verbose=0)
    obj.Add_LayerUniform(0, 1.0)
    for _ in range(slices):
        obj.Add_LayerGrid(2 * a / slices, nx, nx if two_d else 1)
    obj.Add_LayerUniform(0, eps)
    obj.Init_Setup(Gmethod=0)
    x = np.arange(nx) * p / nx
    k = 2 * np.pi / p
    if two_d:
        X, Y = np.meshgrid(x, x, indexing="ij")
        h = 0.5 * a * (np.sin(k * X) + np.sin(k * Y))
        grids = [np.where(h > a - (j + 0.5) * 2 * a / slices, eps, 1.0 + 0j).flatten() for j in range(slices)]
    else:
        h = a * np.sin(k * x)
        grids = [np.where(h > a - (j + 0.5) * 2 * a / slices, eps, 1.0 + 0j) for j in range(slices)]
    obj.GridLayer_geteps(np.concatenate(grids))
    if pol == "te":
        obj.MakeExcitationPlanewave(0, 0, 1, 0, order=0)
    else:
        obj.MakeExcitationPlanewave(1, 0, 0, 0, order=0)
    R, T = obj.RT_Solve(normalize=1, byorder=1)
    out = {}
    for i, g in enumerate(obj.G):
        out[(int(g[0]), int(g[1]) if two_d else 0, False)] = float(R[i])
        out[(int(g[0]), int(g[1]) if two_d else 0, True)] = float(T[i])
    return out

def error(res, pol):
    worst = 0.0
    for o in ref:
        if case["eps"][1] != 0 and o["transmitted"]:
            continue
        got = res.get((o["m"], o["n"], o["transmitted"]), 0.0)
        worst = max(worst, abs(got - o[pol]) / max(o[pol], 1e-3))
    return worst

nx = 128 if two_d else 2048
rungs = []
for n_orders, slices in spec["ladder"]:
    t = time.perf_counter()
    te = solve(n_orders, slices, "te", nx)
    tm = solve(n_orders, slices, "tm", nx)
    dt = time.perf_counter() - t
    e_te, e_tm = error(te, "te"), error(tm, "tm")
    rungs.append({"orders": n_orders, "slices": slices, "seconds": dt, "error": e_te if metal else max(e_te, e_tm),
                  "error_te": e_te, "error_tm": e_tm})
    if rungs[-1]["error"] <= spec["stop_error"] or dt > spec["max_seconds"]:
        break
print(json.dumps({"rungs": rungs, "grcwa": version("grcwa"), "numpy": np.__version__,
                  "python": sys.version.split()[0]}))
"#;

/// The peer's ladder of (orders, slices).
fn ladder(two_d: bool, quick: bool) -> Vec<(usize, usize)> {
    match (two_d, quick) {
        (true, true) => vec![(9, 2), (25, 4)],
        (false, true) => vec![(11, 4), (21, 8)],
        (true, false) => vec![(25, 6), (49, 10), (81, 16), (121, 20), (169, 30), (225, 40)],
        (false, false) => vec![(11, 10), (21, 20), (31, 30), (41, 40), (61, 60), (81, 80), (121, 120)],
    }
}

/// Runs the grcwa script; `Err` with a note when Python or grcwa is missing or fails.
// Public but hidden: not API, reachable only for its test in tests/ (`[lib] test = false`).
#[doc(hidden)]
pub fn run_grcwa(python: &str, spec: &Value, one_thread: bool) -> std::result::Result<Value, String> {
    let mut cmd = Command::new(python);
    cmd.arg("-c").arg(GRCWA_SCRIPT).arg(spec.to_string());
    if one_thread {
        for v in ["OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"] {
            cmd.env(v, "1");
        }
    }
    let out = cmd.output().map_err(|e| format!("{python} not found ({e}); grcwa not timed"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let v: Value = serde_json::from_str(text.trim()).map_err(|_| {
        let err = String::from_utf8_lossy(&out.stderr);
        format!("{python} failed: {}", err.trim().lines().last().unwrap_or("no output"))
    })?;
    if let Some(e) = v.get("error") {
        return Err(e.as_str().unwrap_or("grcwa failed").to_string());
    }
    Ok(v)
}

/// Solves per second of `problems` on one grating, in a pool of `threads` threads.
fn throughput(c: &BenchCase, problems: &[Problem], threads: usize) -> Result<f64> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().context("thread pool")?;
    let (grating, opts) = (c.grating(), c.options());
    let t = Instant::now();
    let answers = pool.install(|| iridis_rigorous::solve_batch(&grating, problems, &opts));
    let secs = t.elapsed().as_secs_f64();
    for a in answers {
        a?;
    }
    Ok(problems.len() as f64 / secs)
}

fn load_average() -> Option<Vec<f64>> {
    let s = std::fs::read_to_string("/proc/loadavg").ok()?;
    let v: Vec<f64> = s.split_whitespace().take(3).filter_map(|x| x.parse().ok()).collect();
    (v.len() == 3).then_some(v)
}

fn rung_json(r: Option<&Value>) -> Value {
    r.map_or(
        Value::Null,
        |r| json!({"orders": r["orders"], "slices": r["slices"], "seconds": r["seconds"], "error": r["error"]}),
    )
}

/// The peer's answer for one case: the ladder, the first rungs within 1 % and 0.1 %, the speed ratios.
fn peer(opts: &GratingBenchOptions, rep: &BenchReport, report: &dyn Report) -> Value {
    let case = &rep.case;
    let mut out = json!({
        "name": "grcwa", "version": Value::Null, "python": Value::Null, "status": "skipped", "note": Value::Null,
        "error_measured_on": if case.eps[0] < 0.0 { "TE (RCWA does not converge in TM on a metal)" } else { "TE and TM" },
        "ladder": [], "at_1_percent": Value::Null, "at_0_1_percent": Value::Null,
        "speedup_at_1_percent": Value::Null, "speedup_lower_bound": Value::Null,
    });
    let Some(python) = &opts.python else {
        out["note"] = json!("not run (--no-python)");
        return out;
    };
    report.info(&format!("grcwa: {} …", case.name));
    let spec = json!({
        "case": case, "reference": rep.reference, "ladder": ladder(case.two_d, opts.quick),
        "stop_error": 1e-3, "max_seconds": opts.peer_seconds,
    });
    let v = match run_grcwa(python, &spec, true) {
        Ok(v) => v,
        Err(note) => {
            out["note"] = json!(note);
            return out;
        }
    };
    let rungs = v["rungs"].as_array().cloned().unwrap_or_default();
    let first = |level: f64| rungs.iter().find(|r| r["error"].as_f64().is_some_and(|e| e <= level));
    let (one, tenth) = (first(1e-2), first(1e-3));
    out["status"] = json!("ok");
    out["version"] = v["grcwa"].clone();
    out["python"] = json!(format!(
        "Python {}, numpy {}; numpy on one thread",
        v["python"].as_str().unwrap_or("?"),
        v["numpy"].as_str().unwrap_or("?")
    ));
    out["ladder"] = json!(rungs);
    out["at_1_percent"] = rung_json(one);
    out["at_0_1_percent"] = rung_json(tenth);
    let ours = rep.seconds;
    match one {
        Some(r) => {
            out["speedup_at_1_percent"] = json!(r["seconds"].as_f64().unwrap_or(f64::NAN) / ours);
        }
        None => {
            let longest = rungs.iter().filter_map(|r| r["seconds"].as_f64()).fold(0.0, f64::max);
            out["speedup_lower_bound"] = json!(longest / ours);
            out["note"] = json!(format!(
                "grcwa did not reach 1 % on its ladder (best error {:.2e}); the ratio is a lower bound",
                rungs.iter().filter_map(|r| r["error"].as_f64()).fold(f64::INFINITY, f64::min)
            ));
        }
    }
    out
}

/// Times the cases (one thread), the throughput over wavelengths on one and on all threads, and the peer.
/// Every number comes back as JSON (keys in docs/json.md, "iridis bench grating").
pub fn bench_grating(opts: &GratingBenchOptions, report: &dyn Report) -> Result<Value> {
    if opts.repeats == 0 || opts.repeats > 100 {
        bail!("--repeats {} must be between 1 and 100", opts.repeats);
    }
    if !(opts.peer_seconds.is_finite() && opts.peer_seconds > 0.0) {
        bail!("--peer-seconds must be a positive number of seconds");
    }
    if opts.batch == 0 || opts.batch > 1000 {
        bail!("--batch {} must be between 1 and 1000", opts.batch);
    }
    let threads = rayon::current_num_threads();
    let (repeats, batch) = if opts.quick { (1, opts.batch.min(2)) } else { (opts.repeats, opts.batch) };
    let load_before = load_average();
    let cases = cases(opts.quick);
    let mut out = Vec::new();
    for case in &cases {
        report.info(&format!("iridis: {} …", case.name));
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().context("thread pool")?;
        let rep = one
            .install(|| iridis_rigorous::benchmark(std::slice::from_ref(case), repeats))?
            .pop()
            .context("the benchmark returned no report")?;
        let n = if case.two_d { batch.min(2 * threads).max(1) } else { batch };
        let problems: Vec<Problem> = (0..n)
            .map(|i| case.problem(if n == 1 { 550.0 } else { 400.0 + 300.0 * i as f64 / (n - 1) as f64 }))
            .collect();
        report.info(&format!("iridis: {} throughput over {n} wavelengths …", case.name));
        let t1 = throughput(case, &problems, 1)?;
        let tn = throughput(case, &problems, threads)?;
        let peer = peer(opts, &rep, report);
        out.push(json!({
            "name": case.name, "two_d": case.two_d, "period_nm": case.period_nm, "amplitude_nm": case.amplitude_nm,
            "wavelength_nm": case.wavelength_nm, "theta_i_deg": case.theta_i_deg, "phi_i_deg": case.phi_i_deg,
            "permittivity": case.eps,
            "iridis": {
                "orders": rep.orders, "harmonics": rep.harmonics, "seconds": rep.seconds, "repeats": rep.repeats,
                "estimated_error": rep.estimated_error, "measured_error": rep.measured_error,
            },
            "throughput": {
                "problems": n, "wavelengths_nm": [problems[0].wavelength_nm, problems[n - 1].wavelength_nm],
                "one_thread_per_second": t1, "all_threads_per_second": tn, "parallel_speedup": tn / t1,
            },
            "peers": [peer],
        }));
    }
    Ok(json!({
        "threads": threads,
        "load_average": {"before": load_before, "after": load_average()},
        "method": "C-method (iridis-rigorous); time per solve: TE and TM together, the whole automatic order search, best of the repeats, one thread",
        "accuracy": "largest error of a propagating efficiency against the C-method with more orders, relative above η = 1e-3 (absolute ×1e3 below)",
        "cases": out,
    }))
}

/// The text of `iridis bench grating` from [`bench_grating`]'s JSON.
pub fn text(v: &Value) -> String {
    let mut t = Vec::new();
    let f = |v: &Value| v.as_f64().unwrap_or(f64::NAN);
    t.push(format!(
        "rigorous order efficiencies: iridis (C-method) against grcwa (RCWA), equal accuracy; {} threads",
        v["threads"]
    ));
    for c in v["cases"].as_array().into_iter().flatten() {
        let i = &c["iridis"];
        let tp = &c["throughput"];
        t.push(format!(
            "{}: λ {} nm, θ {}°, φ {}°",
            c["name"].as_str().unwrap_or(""),
            c["wavelength_nm"],
            c["theta_i_deg"],
            c["phi_i_deg"]
        ));
        t.push(format!(
            "  iridis   orders {} ({} harmonics): {:.4} s per solve (one thread, TE+TM), error {:.1e} (estimated {:.1e})",
            i["orders"],
            i["harmonics"],
            f(&i["seconds"]),
            f(&i["measured_error"]),
            f(&i["estimated_error"])
        ));
        t.push(format!(
            "           {} wavelengths {}–{} nm: {:.2} solves/s on one thread, {:.2} on all ({:.1}×)",
            tp["problems"],
            tp["wavelengths_nm"][0],
            tp["wavelengths_nm"][1],
            f(&tp["one_thread_per_second"]),
            f(&tp["all_threads_per_second"]),
            f(&tp["parallel_speedup"])
        ));
        for p in c["peers"].as_array().into_iter().flatten() {
            let name = p["name"].as_str().unwrap_or("peer");
            if p["status"] != "ok" {
                t.push(format!("  {name}    skipped: {}", p["note"].as_str().unwrap_or("")));
                continue;
            }
            t.push(format!(
                "  {name} {} ({}; error on {}):",
                p["version"].as_str().unwrap_or(""),
                p["python"].as_str().unwrap_or(""),
                p["error_measured_on"].as_str().unwrap_or("")
            ));
            for r in p["ladder"].as_array().into_iter().flatten() {
                t.push(format!(
                    "    {:>4} orders, {:>4} slices: {:>9.3} s, error {:.1e} (TE {:.1e}, TM {:.1e})",
                    // A JSON value's Display ignores the width: padded as text.
                    r["orders"].to_string(),
                    r["slices"].to_string(),
                    f(&r["seconds"]),
                    f(&r["error"]),
                    f(&r["error_te"]),
                    f(&r["error_tm"])
                ));
            }
            let level = |k: &str| {
                let r = &p[k];
                if r.is_null() {
                    "not reached".to_string()
                } else {
                    format!("{}/{} orders/slices, {:.3} s", r["orders"], r["slices"], f(&r["seconds"]))
                }
            };
            t.push(format!("    within 1 %: {}; within 0.1 %: {}", level("at_1_percent"), level("at_0_1_percent")));
            match (p["speedup_at_1_percent"].as_f64(), p["speedup_lower_bound"].as_f64()) {
                (Some(s), _) => t.push(format!("    iridis is {s:.0}× faster at 1 % (one thread each)")),
                (None, Some(b)) => {
                    t.push(format!("    iridis is more than {b:.0}× faster ({})", p["note"].as_str().unwrap_or("")))
                }
                _ => {}
            }
        }
    }
    t.push(format!("load average before / after: {} / {}", v["load_average"]["before"], v["load_average"]["after"]));
    t.join("\n")
}
