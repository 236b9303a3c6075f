//! `iridis report FILE -o DIR`: from a new scan to its colours in one command. The report runs the same
//! commands a user would type (this binary, as child processes), so every figure in `DIR/index.html` comes
//! with the exact command that made it; their numbers go to `DIR/report.json`.

use std::path::PathBuf;
use std::process::Command;

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use serde_json::{json, Value};

use crate::progress::bar;

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Steps (each a command shown in the report, run with the same surface options):
  1. iridis surface info FILE --level L --image relief.png --psdf psdf.png --acf acf.png --json
     size, heights, roughness (Sq, Sa, Ssk, Sku, correlation length), periods and orientations, PSDF, ACF
  2. iridis brdf-map FILE --method reference --incidence 0deg / 45deg, under D65: the structure's colours
  3. iridis testbench FILE --json --plot testbench.png: the period from the grating equation (paper 6.1)
Warnings (patch smaller than the coherence area, pixels too coarse for the visible band, units assumed,
NaN lines) are collected with their numbers. Files are plane-levelled unless --level says otherwise.

Examples:
  iridis report scan.spm -o scan_report
  iridis report scan.jpk --channel height_trace --size 96 -o jpk_report
  iridis report scan.npy --pixel-size 5nm --height-unit m --level lines -o npy_report")]
pub struct ReportArgs {
    /// The scan (any SURFACE: an instrument file, .gwy, .npy, … or builtin:NAME).
    pub surface: String,
    /// Output folder: index.html, report.json and the figures.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Channel of a multi-channel file, by index or name.
    #[arg(long)]
    pub channel: Option<String>,
    /// Pixel size for files without one (e.g. 5nm).
    #[arg(long)]
    pub pixel_size: Option<String>,
    /// Unit of heights in files that do not give one (m, nm, …).
    #[arg(long)]
    pub height_unit: Option<String>,
    /// Levelling: plane (default for files), poly, lines, rows, mean or none.
    #[arg(long)]
    pub level: Option<String>,
    #[command(flatten)]
    pub units: crate::args::UnitFlags,
    /// Size of the BRDF maps in pixels.
    #[arg(long, default_value_t = 128)]
    pub size: usize,
    /// Coherence length for the model (default: the commands' own, 65um).
    #[arg(long)]
    pub coherence: Option<String>,
    /// Leave out the test bench (the slowest step).
    #[arg(long)]
    pub no_testbench: bool,
}

/// One step: its command line (for the report) and what it printed.
struct Step {
    title: String,
    args: Vec<String>,
    stdout: String,
    warnings: Vec<String>,
}

fn quote(a: &str) -> String {
    if a.chars().all(|c| c.is_ascii_alphanumeric() || "-_./:=,".contains(c)) {
        a.to_string()
    } else {
        format!("'{}'", a.replace('\'', "'\\''"))
    }
}

fn run_step(title: &str, args: Vec<String>) -> Result<Step> {
    let exe = std::env::current_exe().context("cannot find the iridis executable")?;
    let out =
        Command::new(exe).args(&args).output().with_context(|| format!("cannot run iridis {}", args.join(" ")))?;
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    if !out.status.success() {
        bail!(
            "step '{title}' failed: iridis {}\n{}",
            args.iter().map(|a| quote(a)).collect::<Vec<_>>().join(" "),
            stderr.trim()
        );
    }
    let warnings = stderr.lines().filter_map(|l| l.strip_prefix("warning: ")).map(str::to_string).collect();
    Ok(Step { title: title.into(), args, stdout: String::from_utf8_lossy(&out.stdout).into_owned(), warnings })
}

fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

pub fn run(a: ReportArgs) -> Result<()> {
    let dir = &a.output;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let file = |n: &str| dir.join(n).to_string_lossy().into_owned();
    let mut common: Vec<String> = Vec::new();
    for (flag, v) in [("--channel", &a.channel), ("--pixel-size", &a.pixel_size), ("--height-unit", &a.height_unit)] {
        if let Some(v) = v {
            common.extend([flag.to_string(), v.clone()]);
        }
    }
    for (flag, on) in [("--override-units", a.units.override_units), ("--as-height", a.units.as_height)] {
        if on {
            common.push(flag.to_string());
        }
    }
    let mut model = common.clone();
    // Only a level that was asked for is passed on: the model commands say "the default for files" otherwise.
    if let Some(l) = &a.level {
        model.extend(["--level".to_string(), l.clone()]);
    }
    let relief_level = a.level.clone().unwrap_or_else(|| "plane".into());
    if let Some(c) = &a.coherence {
        model.extend(["--coherence".to_string(), c.clone()]);
    }
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<String>>();
    let mut plan: Vec<(String, Vec<String>)> = Vec::new();
    let mut info = s(&["surface", "info", &a.surface, "--level", &relief_level, "--json"]);
    info.extend(common.clone());
    // The same coherence as the model steps, so that the surface's note about it speaks of that one.
    if let Some(c) = &a.coherence {
        info.extend(["--coherence".to_string(), c.clone()]);
    }
    info.extend(s(&["--image", &file("relief.png"), "--psdf", &file("psdf.png"), "--acf", &file("acf.png")]));
    plan.push(("Levelled relief, roughness, periods, PSDF and ACF".into(), info));
    for (name, inc) in [("brdf_0deg.png", "0deg"), ("brdf_45deg.png", "45deg,0deg")] {
        let mut b = s(&["brdf-map", &a.surface, "--method", "reference", "--incidence", inc]);
        b.extend(s(&["--size", &a.size.to_string(), "-o", &file(name)]));
        b.extend(model.clone());
        plan.push((format!("BRDF map under D65, light at {inc}"), b));
    }
    if !a.no_testbench {
        let mut t = s(&["testbench", &a.surface, "--json", "--plot", &file("testbench.png")]);
        t.extend(model.clone());
        plan.push(("Test bench: the period from the grating equation (paper sec. 6.1)".into(), t));
    }
    let pb = bar(plan.len() as u64, "report");
    let mut steps = Vec::new();
    let mut failed: Vec<String> = Vec::new();
    for (i, (title, args)) in plan.into_iter().enumerate() {
        pb.set_message(title.clone());
        match run_step(&title, args) {
            Ok(st) => steps.push(st),
            // The test bench finds no order when the periods are below the visible band: say so, go on.
            Err(e) if i == 3 => failed.push(format!("{e:#}")),
            Err(e) => return Err(e),
        }
        pb.inc(1);
    }
    pb.finish_and_clear();
    let info: Value = serde_json::from_str(&steps[0].stdout).context("surface info printed no JSON")?;
    let bench: Option<Value> = steps.get(3).and_then(|st| serde_json::from_str(&st.stdout).ok());
    let mut warnings: Vec<String> = failed;
    for st in &steps {
        for w in &st.warnings {
            if !warnings.contains(w) {
                warnings.push(w.clone());
            }
        }
    }
    let commands: Vec<Value> = steps
        .iter()
        .map(|st| json!({"title": st.title, "command": format!("iridis {}", st.args.iter().map(|x| quote(x)).collect::<Vec<_>>().join(" "))}))
        .collect();
    let mut figures = vec!["relief.png", "psdf.png", "acf.png", "brdf_0deg.png", "brdf_45deg.png"];
    if steps.len() > 3 {
        figures.push("testbench.png");
    }
    let report = json!({
        "surface": a.surface,
        "level": relief_level,
        "info": info,
        "testbench": bench,
        "warnings": warnings,
        "commands": commands,
        "figures": figures,
    });
    crate::output::write_bytes(&dir.join("report.json"), serde_json::to_string_pretty(&report)?.as_bytes())?;
    crate::output::write_bytes(&dir.join("index.html"), html(&report, &steps).as_bytes())?;
    crate::outln!("report of {} in {}", a.surface, dir.join("index.html").display())?;
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    Ok(())
}

fn html(r: &Value, steps: &[Step]) -> String {
    let info = &r["info"];
    let f = |v: &Value| v.as_f64().map_or("–".to_string(), |x| format!("{x:.4}"));
    let mut h = String::from("<!doctype html><meta charset=utf-8><title>iridis report</title>\n<style>body{font-family:sans-serif;max-width:1000px;margin:auto}code{background:#eee;padding:2px}img{max-width:100%}.w{color:#a40}</style>\n");
    h += &format!("<h1>iridis report: {}</h1>\n", html_escape(r["surface"].as_str().unwrap_or("")));
    h += &format!(
        "<p>{} × {} samples, pixel {} × {} nm, heights {}–{} nm; levelling: {}.</p>\n",
        info["cols"],
        info["rows"],
        f(&info["pixel_size_nm"][0]),
        f(&info["pixel_size_nm"][1]),
        f(&info["height_min_nm"]),
        f(&info["height_max_nm"]),
        html_escape(r["level"].as_str().unwrap_or(""))
    );
    let ro = &info["roughness"];
    h += &format!(
        "<p>Roughness: Sq {} nm, Sa {} nm, Ssk {}, Sku−3 {}, correlation length τ {} nm.</p>\n",
        f(&ro["sq_nm"]),
        f(&ro["sa_nm"]),
        f(&ro["skewness"]),
        f(&ro["excess_kurtosis"]),
        f(&ro["correlation_length_nm"])
    );
    h += "<table border=1 cellpadding=4><tr><th>period (nm)</th><th>orientation (°)</th><th>share of variance</th></tr>\n";
    for p in info["peaks"].as_array().into_iter().flatten() {
        h += &format!(
            "<tr><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            f(&p["period_nm"]),
            f(&p["orientation_deg"]),
            f(&p["power"])
        );
    }
    h += "</table>\n";
    let pm = &r["testbench"]["periodicity_nm"];
    if pm.is_object() {
        h += &format!(
            "<p>Test bench: periodicity {} ± {} nm (the patch's DFT grid, d²/L; variance {} nm², {}).</p>\n",
            f(&pm["mean"]),
            f(&pm["uncertainty"]),
            f(&pm["variance"]),
            if pm["definite"].as_bool() == Some(true) { "definite" } else { "not definite" }
        );
    }
    for w in r["warnings"].as_array().into_iter().flatten() {
        h += &format!("<p class=w>warning: {}</p>\n", html_escape(w.as_str().unwrap_or("")));
    }
    let figs: [(&str, usize); 6] = [
        ("relief.png", 0),
        ("psdf.png", 0),
        ("acf.png", 0),
        ("brdf_0deg.png", 1),
        ("brdf_45deg.png", 2),
        ("testbench.png", 3),
    ];
    for (img, step) in figs {
        let Some(st) = steps.get(step) else { continue };
        h += &format!(
            "<h2>{}</h2><img src=\"{img}\"><p><code>iridis {}</code></p>\n",
            html_escape(&st.title),
            html_escape(&st.args.iter().map(|x| quote(x)).collect::<Vec<_>>().join(" "))
        );
    }
    h
}
