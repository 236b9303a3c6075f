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
  2. iridis grating FILE --light 0deg / 45deg --from 380nm --to 780nm --orders-above 0.01: the scan as
     one unit cell, how much of the light it diffracts and the colour of its mirror reflection
  3. iridis brdf-map FILE --method reference --incidence 0deg / 45deg --auto-exposure, under D65: the
     structure's colours (only when it diffracts at least 0.1 % of the reflected light)
  4. iridis brdf vision FILE --visual bluetit --strip vision.png: how a bird (--visual) sees the colours
     in each direction of the plane of the strongest period, ΔS in JND against the mirror direction
  5. iridis grating FILE --unit-cell auto --compare: how far the scalar model behind the maps is from
     Maxwell's equations (the C-method) on the scan's own profile (likewise)
  6. iridis testbench FILE --json --plot testbench.png: the period from the grating equation (paper 6.1),
     along the orientation of the strongest period (likewise)
The report opens with a sentence on what the scan does to visible light. Warnings (pixels too coarse for
the visible band, units assumed, NaN lines) are collected with their numbers. Files are plane-levelled
unless --level says otherwise.

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
    /// Coherence length for the model (default: the light's 65um; the BRDF maps of a smaller scan use half
    /// its shorter side, at least four of its strongest periods, and say so).
    #[arg(long)]
    pub coherence: Option<String>,
    /// The animal whose view of the colours the report shows: bluetit, avian-uv, avian-v, honeybee, human,
    /// ball-python.
    #[arg(long, default_value = "bluetit")]
    pub visual: String,
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

/// A value rounded to its uncertainty's leading digit (two where that digit is 1), with the uncertainty.
fn with_uncertainty(value: f64, u: f64) -> String {
    if !(u.is_finite() && u > 0.0) {
        return format!("{value:.1}");
    }
    let mut digits = -(u.log10().floor() as i32);
    if u * 10f64.powi(digits) < 2.0 {
        digits += 1;
    }
    let d = digits.max(0) as usize;
    let r = |x: f64| (x * 10f64.powi(digits)).round() / 10f64.powi(digits);
    format!("{:.d$} ± {:.d$}", r(value), r(u))
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
    // Only a level that was asked for is passed on: the model commands say "the default for files" otherwise.
    if let Some(l) = &a.level {
        common.extend(["--level".to_string(), l.clone()]);
    }
    let mut model = common.clone();
    let relief_level = a.level.clone().unwrap_or_else(|| "plane".into());
    if let Some(c) = &a.coherence {
        model.extend(["--coherence".to_string(), c.clone()]);
    }
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<String>>();
    let pb = bar(if a.no_testbench { 7 } else { 8 }, "report");
    let mut steps: Vec<Step> = Vec::new();
    let step = |title: &str, args: Vec<String>| -> Result<Step> {
        pb.set_message(title.to_string());
        let r = run_step(title, args);
        pb.inc(1);
        r
    };
    let mut info = s(&["surface", "info", &a.surface, "--json"]);
    if a.level.is_none() {
        info.extend(s(&["--level", "plane"]));
    }
    info.extend(common.clone());
    // The same coherence as the model steps, so that the surface's note about it speaks of that one.
    if let Some(c) = &a.coherence {
        info.extend(["--coherence".to_string(), c.clone()]);
    }
    info.extend(s(&["--image", &file("relief.png"), "--psdf", &file("psdf.png"), "--acf", &file("acf.png")]));
    steps.push(step("Levelled relief, roughness, periods, PSDF and ACF", info)?);
    // The scan as one unit cell of a grating: how much of the light it diffracts, and the colour of the rest.
    let mut grating = Vec::new();
    for inc in ["0deg", "45deg"] {
        let mut g = s(&["grating", &a.surface, "--light", inc, "--from", "380nm", "--to", "780nm", "--step", "10nm"]);
        // The report reads the totals and colours only: a large scan has ~10⁵ orders a wavelength.
        g.extend(s(&["--orders-above", "0.01"]));
        g.extend(common.clone());
        g.push("--json".into());
        let st = step(&format!("Order efficiencies of the scan as a unit cell, light at {inc}"), g)?;
        grating.push(serde_json::from_str::<Value>(&st.stdout).context("grating printed no JSON")?);
        steps.push(st);
    }
    let share = |g: &Value| g["colour"]["diffracted_share"].as_f64().unwrap_or(0.0);
    let info: Value = serde_json::from_str(&steps[0].stdout).context("surface info printed no JSON")?;
    let longest =
        info["peaks"].as_array().into_iter().flatten().filter_map(|p| p["period_nm"].as_f64()).fold(0.0f64, f64::max);
    let shares: Vec<f64> = grating.iter().map(share).collect();
    let diffracts = iridis_api::grating::diffracts_visible_light(longest, &shares);
    let mut maps = Vec::new();
    let mut bench: Option<Value> = None;
    let mut bench_failure: Option<String> = None;
    let mut scalar_error: Option<Value> = None;
    let mut vision: Option<Value> = None;
    let mut scalar_failure: Option<String> = None;
    let map_coherence = a.coherence.clone().or_else(|| {
        let e = &info["extent_nm"];
        let period = info["peaks"][0]["period_nm"].as_f64().unwrap_or(0.0);
        iridis_api::grating::map_coherence_nm([e[0].as_f64()?, e[1].as_f64()?], period)
            .map(|c| format!("{:.3}um", c / 1000.0))
    });
    if diffracts {
        for (name, plot, inc) in
            [("brdf_0deg.png", "brdf_0deg_plot.png", "0deg"), ("brdf_45deg.png", "brdf_45deg_plot.png", "45deg,0deg")]
        {
            let mut b = s(&["brdf-map", &a.surface, "--method", "reference", "--incidence", inc, "--auto-exposure"]);
            b.extend(s(&["--size", &a.size.to_string(), "-o", &file(name), "--plot", &file(plot)]));
            b.extend(common.clone());
            if let Some(c) = &map_coherence {
                b.extend(["--coherence".to_string(), c.clone()]);
            }
            steps.push(step(&format!("BRDF map under D65, light at {inc}"), b)?);
            maps.push(plot);
        }
        // How an animal sees the scan's colours in each direction of the plane of its strongest period.
        let mut v = s(&["brdf", "vision", &a.surface, "--visual", &a.visual, "--light", "0deg"]);
        v.extend(s(&["--strip", &file("vision.png"), "--json"]));
        v.extend(common.clone());
        if let Some(c) = &map_coherence {
            v.extend(["--coherence".to_string(), c.clone()]);
        }
        let st = step(
            &format!("As a {} sees it: light at normal incidence, views along the strongest period", a.visual),
            v,
        )?;
        vision = serde_json::from_str(&st.stdout).ok();
        steps.push(st);
        maps.push("vision.png");
        // How far the scalar model (behind the maps) is from Maxwell's equations on this scan's own profile.
        let mut c = s(&["grating", &a.surface, "--unit-cell", "auto", "--compare", "--light", "0deg"]);
        c.extend(s(&["--from", "380nm", "--to", "780nm", "--step", "10nm", "--material", "keratin"]));
        c.extend(common.clone());
        c.push("--json".into());
        let title = "The scalar model's error on this scan: rigorous (C-method) against Kirchhoff, normal incidence";
        match step(title, c) {
            Ok(st) => {
                scalar_error = serde_json::from_str(&st.stdout).ok();
                steps.push(st);
            }
            Err(e) => scalar_failure = Some(format!("{e:#}").lines().last().unwrap_or("").to_string()),
        }
        if !a.no_testbench {
            let mut t = s(&["testbench", &a.surface, "--json", "--plot", &file("testbench.png")]);
            t.extend(model.clone());
            match step("Test bench: the period from the grating equation (paper sec. 6.1)", t) {
                Ok(st) => {
                    bench = serde_json::from_str(&st.stdout).ok();
                    steps.push(st);
                }
                Err(e) => {
                    bench_failure = Some(format!(
                        "the test bench found no first order to read a period from ({}); the scan's diffraction is \
                         too weak or its periods too long or too short for light at 75°",
                        e.to_string().lines().last().unwrap_or("").trim_start_matches("error: ")
                    ))
                }
            }
        }
    }
    pb.finish_and_clear();
    let verdict = verdict(&info, &grating, diffracts);
    let scalar = scalar_error.as_ref().map(scalar_sentence);
    let seen = vision.as_ref().map(vision_sentence);
    let mut warnings: Vec<String> = bench_failure.into_iter().collect();
    if let Some(f) = scalar_failure {
        warnings.push(format!("the scalar model's error could not be measured on this scan: {f}"));
    }
    if let Some(e) = &scalar_error {
        let worst = e["worst_relative_error"]["unpolarized"].as_f64().unwrap_or(0.0);
        let de = e["delta_e00_diffracted"].as_f64().unwrap_or(0.0);
        if worst > iridis_api::grating::SCALAR_WARN_RELATIVE || de > iridis_api::grating::SCALAR_WARN_DELTA_E {
            warnings.push(format!(
                "the scalar (Kirchhoff) model behind the BRDF maps is off by up to {:.0} % in an order's efficiency \
                 on this scan (ΔE00 {de:.1} in the colour of the diffracted light): for numbers, use `iridis grating \
                 --method rigorous --unit-cell auto`",
                100.0 * worst
            ));
        }
    }
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
    let mut figures = vec!["relief.png", "psdf.png", "acf.png"];
    figures.extend(maps.iter().copied());
    if bench.is_some() {
        figures.push("testbench.png");
    }
    let unit_cell: Vec<Value> = grating
        .iter()
        .map(|g| {
            json!({"light_theta_deg": g["light"]["theta_deg"], "diffracted_share": g["colour"]["diffracted_share"],
                   "specular": g["colour"]["specular"], "diffracted": g["colour"]["diffracted"]})
        })
        .collect();
    let report = json!({
        "surface": a.surface,
        "level": relief_level,
        "info": info,
        "unit_cell": unit_cell,
        "diffracts_visible_light": diffracts,
        "verdict": verdict,
        "map_coherence": map_coherence,
        "scalar_model_error": scalar_error,
        "scalar_model_sentence": scalar,
        "vision": vision,
        "vision_sentence": seen,
        "testbench": bench,
        "warnings": warnings,
        "commands": commands,
        "figures": figures,
    });
    crate::output::write_bytes(&dir.join("report.json"), serde_json::to_string_pretty(&report)?.as_bytes())?;
    crate::output::write_bytes(&dir.join("index.html"), html(&report, &steps).as_bytes())?;
    crate::outln!("report of {} in {}", a.surface, dir.join("index.html").display())?;
    crate::outln!("{verdict}")?;
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    Ok(())
}

/// What a report figure shows, in one sentence under it.
fn figure_caption(file: &str) -> &'static str {
    match file {
        "relief.png" => "The levelled heights, dark low to bright high (nm; scale bar and axes in µm).",
        "psdf.png" => "Power spectral density of the heights: each bright spot is a period, at 1/period from the centre.",
        "acf.png" => "Autocorrelation of the heights: its repeats are the periods, its fall-off the correlation length.",
        "brdf_0deg_plot.png" | "brdf_45deg_plot.png" => {
            "The colour reflected into each view direction (x = sin θr cos φr, y = sin θr sin φr; the disk is the \
             hemisphere) under D65, exposed so that the 99th percentile of the lit pixels is white (the brightest 1 % clip)."
        }
        "vision.png" => "The colours of the strongest period's plane of incidence, as the animal named above sees them.",
        "testbench.png" => "The test bench: reflected intensity against the view angle; the first order's peak gives the period.",
        _ => "",
    }
}

/// How the animal sees the scan's colours across directions, in one sentence with its numbers.
fn vision_sentence(v: &Value) -> String {
    let an = &v["vision"];
    let name = an["visual"]["name"].as_str().unwrap_or("the animal");
    let views: Vec<&str> = v["views"].as_array().into_iter().flatten().filter_map(|x| x["name"].as_str()).collect();
    let mirror = views.iter().copied().find(|n| n.starts_with("+0") || n.starts_with("-0")).unwrap_or("+0°");
    let (mut best, mut at) = (0.0f64, "");
    for d in an["distances"].as_array().into_iter().flatten() {
        let (a, b) = (d["a"].as_str().unwrap_or(""), d["b"].as_str().unwrap_or(""));
        if let (Some(ds), true) = (d["delta_s"].as_f64(), a == mirror || b == mirror) {
            if ds > best {
                best = ds;
                at = if a == mirror { b } else { a };
            }
        }
    }
    format!(
        "As a {name} sees it (receptor-noise-limited model, D65, 300–700 nm), the scan's colour changes with the \
         viewing direction by up to {best:.1} JND against the mirror direction (at {at}; 1 JND is just noticeable, \
         {}): the figure below shows each direction in false colour.",
        if best > 3.0 {
            "so the iridescence is plain to it"
        } else if best > 1.0 {
            "so it can tell the directions apart"
        } else {
            "below what it can tell apart"
        }
    )
}

/// The scalar model's error on the scan, in one sentence with its numbers.
fn scalar_sentence(e: &Value) -> String {
    let pct = |v: &Value| 100.0 * v.as_f64().unwrap_or(f64::NAN);
    let at = &e["worst_at"];
    format!(
        "Against Maxwell's equations (the C-method on the scan's strongest period, {:.0} nm, its profile averaged \
         along the ridges, on keratin, light at normal incidence), the scalar model behind the maps is off by up to \
         {:.1} % in an order's efficiency (unpolarised; TE {:.1} %, TM {:.1} %{}), {:.1} % in the total reflectance, \
         and by ΔE00 {} in the colour of the diffracted light ({} for the mirror reflection).",
        e["unit_cell"]["period_x_nm"].as_f64().unwrap_or(f64::NAN),
        pct(&e["worst_relative_error"]["unpolarized"]),
        pct(&e["worst_relative_error"]["te"]),
        pct(&e["worst_relative_error"]["tm"]),
        if at.is_object() {
            format!("; worst: order {} at {} nm", at["m"], at["wavelength_nm"])
        } else {
            String::new()
        },
        pct(&e["total_relative_error"]),
        e["delta_e00_diffracted"].as_f64().map_or("–".into(), |d| format!("{d:.2}")),
        e["delta_e00_specular"].as_f64().map_or("–".into(), |d| format!("{d:.2}"))
    )
}

/// What the scan does to light, in words a biologist reads first.
fn verdict(info: &Value, grating: &[Value], diffracts: bool) -> String {
    let share = |g: &Value| 100.0 * g["colour"]["diffracted_share"].as_f64().unwrap_or(0.0);
    let periods: Vec<f64> =
        info["peaks"].as_array().into_iter().flatten().filter_map(|p| p["period_nm"].as_f64()).collect();
    let longest = periods.iter().fold(0.0f64, |m, &p| m.max(p));
    let specular = &grating[0]["colour"]["specular"];
    if diffracts {
        format!(
            "The scan diffracts visible light: taken as one unit cell of a periodic surface, it sends {:.2} % of the \
             light it reflects into orders other than the mirror direction at normal incidence and {:.2} % at 45° \
             (D65, luminance-weighted; scalar model); its strongest period is {}.",
            share(&grating[0]),
            share(&grating[1]),
            periods.first().map_or("none".to_string(), |p| format!("{p:.0} nm"))
        )
    } else {
        let why = if periods.is_empty() {
            "it has no dominant period".to_string()
        } else if longest < iridis_api::grating::VISIBLE_PERIOD_NM {
            format!(
                "its periods ({} nm) are all shorter than half the shortest visible wavelength (190 nm), so no \
                 diffraction order of visible light can leave it",
                periods.iter().map(|p| format!("{p:.0}")).collect::<Vec<_>>().join(", ")
            )
        } else {
            format!("its relief is too shallow to send light into its orders (longest period {longest:.0} nm)")
        };
        format!(
            "The scan diffracts no visible light: {why}. Taken as one unit cell of a periodic surface it sends {:.4} % \
             of the reflected light out of the mirror direction at normal incidence, {:.4} % at 45° (into the orders \
             of the scan's own extent: its edges, not its structure). It looks like a mirror of colour {} \
             (reflectance Y = {:.2} % at normal incidence, n = 1.5 under the relief), so no BRDF map is drawn and no \
             test bench is run.",
            share(&grating[0]),
            share(&grating[1]),
            specular["hex"].as_str().unwrap_or("?"),
            100.0 * specular["XYZ"][1].as_f64().unwrap_or(0.0)
        )
    }
}

fn html(r: &Value, steps: &[Step]) -> String {
    let info = &r["info"];
    let f = |v: &Value| v.as_f64().map_or("–".to_string(), |x| format!("{x:.4}"));
    let name = std::path::Path::new(r["surface"].as_str().unwrap_or(""))
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    let mut h = String::from("<!doctype html><meta charset=utf-8><title>iridis report</title>\n<style>body{font-family:sans-serif;max-width:1000px;margin:auto}code{background:#eee;padding:2px}img{max-width:100%}.w{color:#a40}.swatch{display:inline-block;width:2em;height:1em;border:1px solid #888;vertical-align:middle}</style>\n");
    h += &format!("<h1>iridis report: {}</h1>\n", html_escape(&name));
    let swatch = r["unit_cell"][0]["specular"]["hex"].as_str().unwrap_or("#000000");
    h += &format!(
        "<p><b>{}</b> <span class=swatch style=\"background:{swatch}\"></span> (mirror colour)</p>\n",
        html_escape(r["verdict"].as_str().unwrap_or(""))
    );
    if let (Some(c), true) = (r["map_coherence"].as_str(), r["diffracts_visible_light"] == json!(true)) {
        h += &format!(
            "<p>The BRDF maps are drawn with a coherence window of {c}: half the scan's shorter side (at least four \
             of its strongest periods), so that each pixel sees the scan's spectrum. Under the light's own 65 µm the \
             scan, smaller than that, is one unit cell of a periodic surface whose discrete orders are narrower than \
             a pixel.</p>\n"
        );
    }
    if let Some(sentence) = r["vision_sentence"].as_str() {
        h += &format!("<p>{}</p>\n", html_escape(sentence));
    }
    if let Some(sentence) = r["scalar_model_sentence"].as_str() {
        h += &format!("<p>{}</p>\n", html_escape(sentence));
    }
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
        let period = match (p["period_nm"].as_f64(), p["uncertainty_nm"].as_f64()) {
            (Some(d), Some(u)) => with_uncertainty(d, u),
            (Some(d), None) => format!("{d:.1}"),
            _ => "–".into(),
        };
        h += &format!(
            "<tr><td>{period}</td><td>{:.1}</td><td>{:.3}</td></tr>\n",
            p["orientation_deg"].as_f64().unwrap_or(f64::NAN),
            p["power"].as_f64().unwrap_or(f64::NAN)
        );
    }
    h += "</table>\n";
    let pm = &r["testbench"]["periodicity_nm"];
    if pm.is_object() {
        h += &format!(
            "<p>Test bench along azimuth {:.1}°: periodicity {} nm ({}, {}).</p>\n",
            r["testbench"]["azimuth_deg"].as_f64().unwrap_or(f64::NAN),
            with_uncertainty(pm["mean"].as_f64().unwrap_or(f64::NAN), pm["uncertainty"].as_f64().unwrap_or(f64::NAN)),
            if pm["quantised"].as_bool() == Some(true) {
                "± half a DFT step of the patch along that direction"
            } else {
                "± the coherence window's resolution"
            },
            if pm["definite"].as_bool() == Some(true) { "one definite period" } else { "no definite period" }
        );
    }
    for w in r["warnings"].as_array().into_iter().flatten() {
        h += &format!("<p class=w>warning: {}</p>\n", html_escape(w.as_str().unwrap_or("")));
    }
    // One heading per step, its figures under it, then the command that made them.
    for st in steps {
        let figs: Vec<&str> = r["figures"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|f| f.as_str())
            .filter(|f| st.args.iter().any(|a| a.ends_with(&format!("/{f}")) || a == f))
            .collect();
        h += &format!("<h2>{}</h2>\n", html_escape(&st.title));
        for img in figs {
            let c = html_escape(figure_caption(img));
            h += &format!("<figure><img src=\"{img}\" alt=\"{c}\"><figcaption>{c}</figcaption></figure>\n");
        }
        h += &format!(
            "<p><code>iridis {}</code></p>\n",
            html_escape(&st.args.iter().map(|x| quote(x)).collect::<Vec<_>>().join(" "))
        );
    }
    h
}
