//! The report of a scan (`iridis report FILE -o DIR`, Python's `iridis.report`): from a new scan to its colours
//! in one call. It runs the steps a user would type as commands — `surface info`, `grating` at 0° and 45°,
//! `brdf-map`, `brdf vision`, `grating --compare`, `testbench` — as library calls, and records each step with
//! the command line that repeats it, so every figure in `DIR/index.html` comes with the exact command that
//! made it; their numbers (each step's `--json`) go to `DIR/report.json`.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, Context, Result};
use iridis_color::units::{parse_angle_rad, parse_positive_length_nm};
use iridis_color::{Encoding, ToneMap};
use iridis_diffraction::geometry::{direction, FresnelConvention};
use iridis_diffraction::table::{Precision, TableParams};
use serde_json::{json, Value};

use crate::grating::{grating, GratingMethod, GratingOptions};
use crate::report::{with_step, Collect, Kind, Report};
use crate::surface::{Source, SurfaceOptions};

/// What `iridis report` takes: the scan and how to read it (the surface options of every command, passed on to
/// each step's command line), the model's coherence as typed. With the feature `cli`, its arguments.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct ReportOptions {
    /// The scan (any SURFACE: an instrument file, .gwy, .npy, … or builtin:NAME).
    pub surface: String,
    /// Output folder: index.html, report.json and the figures.
    #[cfg_attr(feature = "cli", arg(short, long))]
    pub output: PathBuf,
    #[cfg_attr(feature = "cli", command(flatten))]
    pub surface_options: SurfaceOptions,
    /// Size of the BRDF maps in pixels.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 128))]
    pub size: usize,
    /// Coherence length for the model (default: the light's 65um; the BRDF maps of a smaller scan use half
    /// its shorter side, at least four of its strongest periods, and say so).
    #[cfg_attr(feature = "cli", arg(long))]
    pub coherence: Option<String>,
    /// The animal whose view of the colours the report shows: bluetit, avian-uv, avian-v, honeybee, human,
    /// ball-python.
    #[cfg_attr(feature = "cli", arg(long, default_value = "bluetit"))]
    pub visual: String,
    /// Leave out the test bench (the slowest step).
    #[cfg_attr(feature = "cli", arg(long))]
    pub no_testbench: bool,
}

impl ReportOptions {
    /// The options of `iridis report` with their defaults.
    pub fn new(surface: &str, output: &Path) -> Self {
        Self {
            surface: surface.to_string(),
            output: output.to_path_buf(),
            surface_options: SurfaceOptions::default(),
            size: 128,
            coherence: None,
            visual: "bluetit".into(),
            no_testbench: false,
        }
    }
}

/// The `"inputs"` of a step's JSON answer from its command line (the CLI's `--json` carries the command's
/// options; `None` leaves the answer as the library gives it).
pub type StepInputs<'a> = Option<&'a dyn Fn(&[String]) -> Option<Value>>;

/// A written report: `report.json`'s content, its verdict and warnings, where `index.html` is.
#[derive(Debug)]
pub struct ScanReport {
    pub json: Value,
    pub verdict: String,
    pub warnings: Vec<String>,
    pub index: PathBuf,
}

impl ScanReport {
    /// What `iridis report` prints (warnings apart).
    pub fn text(&self) -> String {
        format!(
            "report of {} in {}\n{}\n",
            self.json["surface"].as_str().unwrap_or(""),
            self.index.display(),
            self.verdict
        )
    }
}

/// One step: its command line (for the report) and the warnings it gave.
struct Step {
    title: String,
    args: Vec<String>,
    warnings: Vec<String>,
}

fn quote(a: &str) -> String {
    if a.chars().all(|c| c.is_ascii_alphanumeric() || "-_./:=,".contains(c)) {
        a.to_string()
    } else {
        format!("'{}'", a.replace('\'', "'\\''"))
    }
}

fn command_line(args: &[String]) -> String {
    args.iter().map(|x| quote(x)).collect::<Vec<_>>().join(" ")
}

/// A step's answer as its command prints it with `--json` (with the command's inputs where the front end
/// gives them), read back as the report reads it.
fn answer(mut v: Value, args: &[String], inputs: StepInputs<'_>) -> Value {
    if let (Some(f), Some(obj)) = (inputs, v.as_object_mut()) {
        if let Some(Value::Object(mut all)) = f(args) {
            if let Some(own) = obj.get("inputs").and_then(|i| i.as_object()) {
                all.extend(own.clone());
            }
            obj.insert("inputs".into(), Value::Object(all));
        }
    }
    serde_json::from_str(&crate::output::json_string(&v)).unwrap_or(v)
}

/// Runs one step under `report`'s step label, its own notes and warnings collected (its warnings go into the
/// report), a failure naming the command that failed.
fn run_step<T>(
    report: &dyn Report,
    title: &str,
    args: Vec<String>,
    f: impl FnOnce(&Collect) -> Result<(T, Vec<String>)>,
) -> Result<(Step, T)> {
    let said = Collect::default();
    let out = with_step(report, title, || f(&said));
    let mut warnings: Vec<String> =
        said.take().into_iter().filter(|(k, _)| *k == Kind::Warning).map(|(_, text)| text).collect();
    match out {
        Ok((v, more)) => {
            warnings.extend(more);
            Ok((Step { title: title.into(), args, warnings }, v))
        }
        Err(e) => Err(anyhow!("step '{title}' failed: iridis {}\nerror: {e:#}", command_line(&args))),
    }
}

fn length(flag: &str, s: &Option<String>) -> Result<Option<f64>> {
    s.as_deref().map(|v| parse_positive_length_nm(v).map_err(|e| anyhow!("--{flag} '{v}': {}", e.0))).transpose()
}

fn angle(s: &str) -> Result<f64> {
    parse_angle_rad(s).map_err(|e| anyhow!("{s}: {}", e.0))
}

/// A BRDF map under D65 by the reference method, exposed from its own numbers, written as an image and as a
/// figure with axes (what `iridis brdf-map --method reference --auto-exposure --plot` writes).
#[allow(clippy::too_many_arguments)]
fn brdf_map_figure(
    surface: &str,
    surf: &SurfaceOptions,
    coherence_nm: Option<f64>,
    incidence: (f64, f64),
    size: usize,
    image: &Path,
    plot: &Path,
    report: &dyn Report,
) -> Result<Vec<String>> {
    let wi = direction(incidence.0, incidence.1);
    let model = crate::ModelOptions { coherence_nm, light: Some(wi), ..crate::ModelOptions::default() };
    let shading = crate::fresnel::shading(crate::fresnel::DEFAULT_FRESNEL, FresnelConvention::Physical, true)?;
    let params = TableParams { uv_resolution: 501, uv_power: 5.0 };
    let setup = crate::brdf::EvaluatorSetup {
        method: "reference",
        model: &model,
        shading,
        params,
        precision: Precision::F64,
        surface: surf,
    };
    let (e, _) = crate::brdf::map_evaluator(surface, setup, wi, report)?;
    let xyz = crate::brdf::render_map(e.as_ref(), wi, size, 1, report);
    let mut exposure = 1500.0;
    let mut warnings = Vec::new();
    match crate::brdf::auto_exposure(&xyz, size) {
        Some(auto) => exposure = auto.exposure_ru,
        None => warnings.push(crate::brdf_map::black_map("reference", size, Some(exposure))),
    }
    let tone = ToneMap { exposure_ru: exposure, encoding: Encoding::parse("srgb").map_err(anyhow::Error::msg)? };
    let rgb = crate::brdf_map::map_to_rgb8(&xyz, tone);
    crate::output::write_png_rgb8(image, size as u32, size as u32, &rgb)?;
    let name = Path::new(surface).file_name().map_or(surface.to_string(), |f| f.to_string_lossy().into());
    let (t, p) = (wi[2].clamp(-1.0, 1.0).acos().to_degrees(), wi[1].atan2(wi[0]).to_degrees());
    let title = format!("{name} · θi {t:.0}° φi {p:.0}° · {} · D65 · {exposure:.3e} RU", e.name());
    let pixels = iridis_plot::RgbImage { width: size as u32, height: size as u32, data: rgb };
    let fig = crate::lab_run::view_plot(&pixels, &title, None, (560, 600))?;
    crate::output::write_png_rgb8(plot, fig.width, fig.height, &fig.data)?;
    Ok(warnings)
}

/// Writes the report of `o.surface` into `o.output` (index.html, report.json, the figures) through the run's
/// output set; each step is announced to `report` by its title, its own notes are dropped and its warnings
/// collected into the report's. `inputs` gives each step's JSON the options of its command line (the CLI's).
pub fn write_report(o: &ReportOptions, inputs: StepInputs<'_>, report: &dyn Report) -> Result<ScanReport> {
    // What a later step would refuse, refused before the first runs (a report of a large scan takes minutes).
    crate::brdf_map::check_size(o.size)?;
    // A scan that is not there is said as such, not as the failure of the first step's command line.
    if !o.surface.starts_with("builtin:") && !Path::new(&o.surface).exists() {
        // An I/O error in the chain: Python raises OSError for it, as for every unreadable file.
        let missing = format!("cannot read {}: no such file", o.surface);
        return Err(std::io::Error::new(std::io::ErrorKind::NotFound, missing).into());
    }
    let spec =
        iridis_vision::Spec { visual: Some(o.visual.clone()), illuminant: Some("d65".into()), ..Default::default() };
    spec.system().context("--visual")?;
    let dir = &o.output;
    crate::output::create_dir(dir)?;
    let path = |n: &str| dir.join(n);
    let file = |n: &str| path(n).to_string_lossy().into_owned();
    let coherence_nm = length("coherence", &o.coherence)?;
    let surf = &o.surface_options;
    let source = Source::Spec(o.surface.clone());
    let common = surf.flags();
    let mut model = common.clone();
    // As the model steps level it: a file plane-levelled, a built-in as generated (the relief of a built-in was
    // plane-levelled and the report said so, while its diffraction used it as generated).
    let relief_level = surf.level.clone().unwrap_or_else(|| iridis_surface::prep::default_level(&o.surface).into());
    if let Some(c) = &o.coherence {
        model.extend(["--coherence".to_string(), c.clone()]);
    }
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<String>>();
    let mut steps: Vec<Step> = Vec::new();

    // 1. The levelled relief, roughness, periods, PSDF and ACF.
    let mut args = s(&["surface", "info", &o.surface, "--json"]);
    if surf.level.is_none() {
        args.extend(s(&["--level", "plane"]));
    }
    args.extend(common.clone());
    // The same coherence as the model steps, so that the surface's note about it speaks of that one.
    if let Some(c) = &o.coherence {
        args.extend(["--coherence".to_string(), c.clone()]);
    }
    args.extend(s(&["--image", &file("relief.png"), "--psdf", &file("psdf.png"), "--acf", &file("acf.png")]));
    let (st, info) = run_step(report, "Levelled relief, roughness, periods, PSDF and ACF", args.clone(), |r| {
        let load = surf.load_options();
        let hf = crate::surface_info::level(crate::surface_info::load(&o.surface, &load, r)?, &relief_level)?;
        let figures = crate::surface_info::InfoFigures {
            image: Some(&path("relief.png")),
            psdf: Some(&path("psdf.png")),
            acf: Some(&path("acf.png")),
        };
        let coherence = coherence_nm.unwrap_or(iridis_surface::DEFAULT_COHERENCE_NM);
        let v = crate::surface_info::info_with_figures(&hf, &o.surface, 5, coherence, figures, r)?;
        // The reader's warnings as the later steps' loader says them ("SURFACE: …"), so that the report lists
        // each once.
        let w = crate::surface_info::info_warnings(&v)
            .into_iter()
            .map(|w| if hf.meta.warnings.contains(&w) { format!("{}: {w}", o.surface) } else { w })
            .collect();
        Ok((answer(v, &args, inputs), w))
    })?;
    steps.push(st);
    if let (Some(c), Some(px)) = (coherence_nm, info["pixel_size_nm"].as_array()) {
        let d = |k: usize| px.get(k).and_then(Value::as_f64).unwrap_or(0.0);
        iridis_diffraction::patch::check_coherence(c, d(0), d(1)).context("--coherence")?;
    }

    // A relief too deep for the Taylor expansion behind every later step has no scalar colours: the report
    // keeps its relief, roughness and periods and says which commands compute its colours instead.
    let too_deep = too_deep_for_taylor(&info);

    // 2. The scan as one unit cell of a grating: how much of the light it diffracts, and the colour of the rest.
    let spectrum = iridis_color::spectrum::uniform_grid(380.0, 780.0, 10.0)?;
    let mut unit_cells = Vec::new();
    let incidences: &[&str] = if too_deep.is_none() { &["0deg", "45deg"] } else { &[] };
    for &inc in incidences {
        let mut args =
            s(&["grating", &o.surface, "--light", inc, "--from", "380nm", "--to", "780nm", "--step", "10nm"]);
        // The report reads the totals and colours only: a large scan has ~10⁵ orders a wavelength.
        args.extend(s(&["--orders-above", "0.01"]));
        args.extend(common.clone());
        args.push("--json".into());
        let title = format!("Order efficiencies of the scan as a unit cell, light at {inc}");
        let opts = GratingOptions {
            method: GratingMethod::Kirchhoff,
            light: direction(angle(inc)?, 0.0),
            wavelengths_nm: spectrum.clone(),
            orders_above: 0.01,
            ..GratingOptions::default()
        };
        let (st, g) = run_step(report, &title, args.clone(), |r| {
            Ok((answer(grating(&source, surf, &opts, r)?.to_json(), &args, inputs), Vec::new()))
        })?;
        unit_cells.push(g);
        steps.push(st);
    }
    let grating_json = unit_cells;
    let share = |g: &Value| g["colour"]["diffracted_share"].as_f64().unwrap_or(0.0);
    // A random surface's spectral peaks are no periods of its structure (a spike's 27 nm was called one).
    let longest = crate::surface::structural_periods_nm(&info).into_iter().reduce(f64::max);
    let shares: Vec<f64> = grating_json.iter().map(share).collect();
    let diffracts = too_deep.is_none() && crate::grating::diffracts_visible_light(longest, &shares);
    // A patch under two wavelengths across with no period in it: its orders are those of its own few hundred
    // nanometres repeated, and it holds too little of the surface to say whether the surface repeats. Its shares
    // are given, no verdict (a 3 × 3-sample scan was said to diffract from 1.2 % at 45°).
    let narrowest = info["extent_nm"].as_array().into_iter().flatten().filter_map(Value::as_f64).reduce(f64::min);
    let undecided = diffracts && longest.is_none() && narrowest.is_some_and(|l| l < iridis_surface::TWO_WAVELENGTHS_NM);
    let mut maps = Vec::new();
    let mut bench: Option<Value> = None;
    let mut bench_failure: Option<String> = None;
    let mut scalar_error_json: Option<Value> = None;
    let mut vision: Option<Value> = None;
    let mut scalar_failure: Option<String> = None;
    let map_coherence = o.coherence.clone().or_else(|| {
        let (e, px) = (&info["extent_nm"], &info["pixel_size_nm"]);
        let period = crate::surface::structural_periods_nm(&info).first().copied().unwrap_or(0.0);
        crate::grating::map_coherence_nm([e[0].as_f64()?, e[1].as_f64()?], period, [px[0].as_f64()?, px[1].as_f64()?])
            .map(|c| format!("{:.3}um", c / 1000.0))
    });
    if diffracts {
        let map_coherence_nm = length("coherence", &map_coherence)?;
        // 3. The structure's colours: BRDF maps under D65.
        for (name, plot, inc) in
            [("brdf_0deg.png", "brdf_0deg_plot.png", "0deg"), ("brdf_45deg.png", "brdf_45deg_plot.png", "45deg,0deg")]
        {
            let mut args = s(&["brdf-map", &o.surface, "--method", "reference", "--incidence", inc, "--auto-exposure"]);
            args.extend(s(&["--size", &o.size.to_string(), "-o", &file(name), "--plot", &file(plot)]));
            args.extend(common.clone());
            if let Some(c) = &map_coherence {
                args.extend(["--coherence".to_string(), c.clone()]);
            }
            let mut parts = inc.split(',');
            let theta = angle(parts.next().unwrap_or("0deg"))?;
            let phi = parts.next().map(angle).transpose()?.unwrap_or(0.0);
            let (st, ()) = run_step(report, &format!("BRDF map under D65, light at {inc}"), args, |r| {
                let w = brdf_map_figure(
                    &o.surface,
                    surf,
                    map_coherence_nm,
                    (theta, phi),
                    o.size,
                    &path(name),
                    &path(plot),
                    r,
                )?;
                Ok(((), w))
            })?;
            steps.push(st);
            maps.push(plot);
        }
        // 4. How an animal sees the scan's colours in each direction of the plane of its strongest period.
        let mut args = s(&["brdf", "vision", &o.surface, "--visual", &o.visual, "--light", "0deg"]);
        args.extend(s(&["--strip", &file("vision.png"), "--json"]));
        args.extend(common.clone());
        if let Some(c) = &map_coherence {
            args.extend(["--coherence".to_string(), c.clone()]);
        }
        let title = format!("As a {} sees it: light at normal incidence, views along the strongest period", o.visual);
        let (st, v) = run_step(report, &title, args.clone(), |r| {
            let model = crate::ModelOptions { coherence_nm: map_coherence_nm, ..crate::ModelOptions::default() };
            let shading = crate::fresnel::shading(crate::fresnel::DEFAULT_FRESNEL, FresnelConvention::Physical, true)?;
            let views: Vec<f64> = (-6..=6).map(|k| 10.0 * k as f64).collect();
            let plane = crate::vision::PlaneViews { light_theta: 0.0, azimuth: None, views_deg: &views, spec: &spec };
            let v = crate::vision::along_plane(&source, surf, &model, shading.clone(), plane, r)?;
            let img = crate::brdf_vision::vision_strip(&v)?;
            crate::output::write_png_rgb8(&path("vision.png"), img.width, img.height, &img.data)?;
            // The window's own colours: a flat mirror of the scan's size under the same coherence changes colour
            // with direction too (its lobe's width goes with λ), up to 24 JND under 0.8 µm; the sentence
            // measures the scan against it.
            // Its grid is the scan's, as step 1 read it (no second read of the file).
            let count = |k: &str| info[k].as_u64().map(|n| n as usize).context("surface info's sample counts");
            let pixel = |k: usize| info["pixel_size_nm"][k].as_f64().context("surface info's pixel size");
            let (rows, cols) = (count("rows")?, count("cols")?);
            let flat =
                iridis_diffraction::Patch::from_row_major(rows, cols, pixel(0)?, pixel(1)?, &vec![0.0; rows * cols])?;
            let flat = Source::Patch { patch: flat, name: "a flat mirror of the scan's size".into() };
            let plane = crate::vision::PlaneViews { azimuth: Some(v.azimuth), ..plane };
            let reference = crate::vision::along_plane(&flat, surf, &model, shading, plane, &crate::report::Quiet)?;
            let mut json = v.to_json();
            let flat = reference.to_json();
            json["flat_mirror_delta_s_jnd"] = json!(largest_delta_s_from_mirror(&flat, None).map(|(d, _)| d));
            json["flat_mirror_lit_views"] = json!(lit_views(&flat));
            Ok((answer(json, &args, inputs), Vec::new()))
        })?;
        vision = Some(v);
        steps.push(st);
        maps.push("vision.png");
        // 6. The test bench: the period from the grating equation, along the strongest period.
        if !o.no_testbench {
            let mut args = s(&["testbench", &o.surface, "--json", "--plot", &file("testbench.png")]);
            args.extend(model.clone());
            let lab =
                crate::lab::LabOptions { surface: surf.clone(), coherence_nm, ..crate::lab::LabOptions::default() };
            let ang = |s: &str| angle(s).map(f64::to_degrees);
            let setup = iridis_lab::bench::BenchSetup::new(
                angle("75deg")?,
                0.0,
                1,
                (380.0, 780.0, 5.0),
                (ang("-89deg")?, ang("89deg")?, ang("0.05deg")?),
            )?;
            let req = crate::lab_run::TestbenchRequest {
                method: "reference".into(),
                rigorous: crate::ModelOptions::default(),
                setup,
                along_dominant: true,
                max_period_nm: None,
                plot: Some(path("testbench.png")),
            };
            let ran = run_step(
                report,
                "Test bench: the period from the grating equation (paper sec. 6.1)",
                args.clone(),
                |r| {
                    let t = crate::lab_run::testbench_run(&source, &lab, &req, r)?;
                    Ok((answer(t.to_json(), &args, inputs), Vec::new()))
                },
            );
            match ran {
                Ok((st, b)) => {
                    bench = Some(b);
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
    if too_deep.is_none() && (diffracts || longest.is_some()) {
        // 5. How far the scalar model (behind the maps and the mirror colour) is from Maxwell's equations on this
        // scan's own profile: wherever it has a period, diffracting or not (a 200 nm-deep 200 nm sine was called a
        // mirror of Y = 3.6 % where Maxwell's equations give 0.3 %).
        let mut args = s(&["grating", &o.surface, "--unit-cell", "auto", "--compare", "--light", "0deg"]);
        args.extend(s(&["--from", "380nm", "--to", "780nm", "--step", "10nm", "--material", "keratin"]));
        args.extend(common.clone());
        args.push("--json".into());
        let title = "The scalar model's error on this scan: rigorous (C-method) against Kirchhoff, normal incidence";
        let opts = GratingOptions {
            light: direction(0.0, 0.0),
            wavelengths_nm: spectrum.clone(),
            material: Some("keratin".into()),
            unit_cell_auto: true,
            ..GratingOptions::default()
        };
        let compared = run_step(report, title, args.clone(), |r| {
            let c = crate::grating_run::compare(&source, surf, &opts, r)?;
            Ok((answer(c.to_json(), &args, inputs), Vec::new()))
        });
        match compared {
            Ok((st, e)) => {
                scalar_error_json = Some(e);
                steps.push(st);
            }
            Err(e) => {
                let last = format!("{e:#}").lines().last().unwrap_or("").trim_start_matches("error: ").to_string();
                scalar_failure = Some(last);
            }
        }
    }
    let verdict = match &too_deep {
        Some(why) => deep_verdict(&o.surface, why),
        None if undecided => small_patch_verdict(&info, &grating_json),
        None => verdict(&info, &grating_json, diffracts, &relief_level),
    };
    let scalar = scalar_error_json.as_ref().map(scalar_sentence);
    let seen = vision.as_ref().map(vision_sentence);
    let mut warnings: Vec<String> = bench_failure.into_iter().collect();
    if let Some(f) = scalar_failure {
        warnings.push(format!("the scalar model's error could not be measured on this scan: {f}"));
    }
    if let Some(e) = &scalar_error_json {
        let worst = e["worst_relative_error"]["unpolarized"].as_f64().unwrap_or(0.0);
        let total = e["total_relative_error"].as_f64().unwrap_or(0.0);
        let de = e["delta_e00_diffracted"].as_f64().unwrap_or(0.0);
        if diffracts && (worst > crate::grating::SCALAR_WARN_RELATIVE || de > crate::grating::SCALAR_WARN_DELTA_E) {
            warnings.push(format!(
                "the scalar (Kirchhoff) model behind the BRDF maps is off by up to {:.0} % in an order's efficiency \
                 on this scan (ΔE00 {de:.1} in the colour of the diffracted light): for numbers, use `iridis grating \
                 --method rigorous --unit-cell auto`",
                100.0 * worst
            ));
        }
        if !diffracts && total > crate::grating::SCALAR_WARN_RELATIVE {
            // The mirror colour of a scan that does not diffract is the scalar model's too.
            warnings.push(format!(
                "the scalar (Kirchhoff) model behind the mirror colour is off by {:.0} % in the total reflectance on \
                 this scan's period against Maxwell's equations (on keratin): its reflectance Y is not to be trusted; \
                 `iridis grating --method rigorous --unit-cell auto` gives Maxwell's",
                100.0 * total
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
        .map(|st| json!({"title": st.title, "command": format!("iridis {}", command_line(&st.args))}))
        .collect();
    let mut figures = vec!["relief.png", "psdf.png", "acf.png"];
    figures.extend(maps.iter().copied());
    if bench.is_some() {
        figures.push("testbench.png");
    }
    let unit_cell: Vec<Value> = grating_json
        .iter()
        .map(|g| {
            json!({"light_theta_deg": g["light"]["theta_deg"], "diffracted_share": g["colour"]["diffracted_share"],
                   "specular": g["colour"]["specular"], "diffracted": g["colour"]["diffracted"]})
        })
        .collect();
    let json = json!({
        "surface": o.surface,
        "level": relief_level,
        "info": info,
        "unit_cell": unit_cell,
        "diffracts_visible_light": if too_deep.is_some() || undecided { Value::Null } else { json!(diffracts) },
        "too_deep_for_scalar_model": too_deep,
        "verdict": verdict,
        "reflectors": reflectors(),
        "map_coherence": map_coherence,
        "scalar_model_error": scalar_error_json,
        "scalar_model_sentence": scalar,
        "vision": vision,
        "vision_sentence": seen,
        "testbench": bench,
        "warnings": warnings,
        "commands": commands,
        "figures": figures,
    });
    crate::output::write_bytes(&path("report.json"), serde_json::to_string_pretty(&json)?.as_bytes())?;
    let index = path("index.html");
    crate::output::write_bytes(&index, html(&json, &steps).as_bytes())?;
    Ok(ScanReport { json, verdict, warnings, index })
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

/// What a report figure shows, in one sentence under it.
fn figure_caption(file: &str) -> &'static str {
    match file {
        "relief.png" => "The levelled heights, dark low to bright high (nm; scale bar and axes in µm).",
        "psdf.png" => "Power spectral density of the heights: each bright spot is a period, at 1/period from the centre.",
        "acf.png" => "Autocorrelation of the heights: its repeats are the periods, its fall-off the correlation length.",
        "brdf_0deg_plot.png" | "brdf_45deg_plot.png" => {
            "The colour reflected into each view direction (x = sin θr cos φr, y = sin θr sin φr; the disk is the \
             hemisphere) under D65, exposed so that the 99th percentile of the lit pixels is white (the brightest 1 % clip); \
             the exposure in the title is in RU, where 1 RU shows a normal-incidence perfect mirror under the light \
             as just white."
        }
        "vision.png" => "The colours of the strongest period's plane of incidence, as the animal named above sees them.",
        "testbench.png" => "The test bench: reflected intensity against the view angle; the first order's peak gives the period.",
        _ => "",
    }
}

/// How the animal sees the scan's colours across directions, in one sentence with its numbers.
/// The share of the brightest view's light (its mean reflectance factor over the band) below which a view's colour
/// is not counted: a hundred times dimmer than the highlight beside it, it is dark to the eye, while its relative
/// catches (which ΔS compares) still give it a hue (a flat mirror's faint window tails 20° away: 94 JND).
const SEEN_SHARE: f64 = 0.01;

/// The views of a `brdf vision` answer that get at least [`SEEN_SHARE`] of the brightest one's light.
fn lit_views(v: &Value) -> Vec<String> {
    let views = v["views"].as_array().map_or(&[][..], Vec::as_slice);
    let light = |x: &Value| -> f64 {
        let f = x["reflectance_factor"].as_array().map_or(&[][..], Vec::as_slice);
        f.iter().filter_map(Value::as_f64).sum::<f64>() / f.len().max(1) as f64
    };
    let brightest = views.iter().map(light).fold(0.0f64, f64::max);
    views
        .iter()
        .filter(|x| brightest > 0.0 && light(x) >= SEEN_SHARE * brightest)
        .filter_map(|x| x["name"].as_str().map(str::to_string))
        .collect()
}

/// The largest ΔS (JND) of a `brdf vision` answer's lit views ([`lit_views`]) against its mirror direction, and
/// that view's name; with `only`, among those views alone. `None` where no lit view but the mirror is left.
fn largest_delta_s_from_mirror(v: &Value, only: Option<&[String]>) -> Option<(f64, String)> {
    let lit = lit_views(v);
    let mirror = lit.iter().find(|n| n.starts_with("+0") || n.starts_with("-0")).cloned().unwrap_or("+0°".into());
    let counted = |n: &str| lit.iter().any(|l| l == n) && only.is_none_or(|o| o.iter().any(|x| x == n));
    let mut best: Option<(f64, String)> = None;
    for d in v["vision"]["distances"].as_array().into_iter().flatten() {
        let (a, b) = (d["a"].as_str().unwrap_or(""), d["b"].as_str().unwrap_or(""));
        let other = if a == mirror {
            b
        } else if b == mirror {
            a
        } else {
            continue;
        };
        if let (Some(ds), true) = (d["delta_s"].as_f64(), counted(other) && lit.contains(&mirror)) {
            if best.as_ref().is_none_or(|(x, _)| ds > *x) {
                best = Some((ds, other.to_string()));
            }
        }
    }
    best
}

fn vision_sentence(v: &Value) -> String {
    let name = v["vision"]["visual"]["name"].as_str().unwrap_or("the animal");
    let seen = |x: f64| {
        if x > 3.0 {
            "plain to it"
        } else if x > 1.0 {
            "just seen by it"
        } else {
            "below what it can tell apart"
        }
    };
    let head = format!("As a {name} sees it (receptor-noise-limited model, D65, 300–700 nm)");
    let rule = format!("directions that get at least {:.0} % of the brightest one's light", 100.0 * SEEN_SHARE);
    let Some((best, at)) = largest_delta_s_from_mirror(v, None) else {
        // The orders fall between the views (every 10°) or are a hundred times fainter than the mirror.
        return format!(
            "{head}, no direction sampled (every 10° in the plane of the strongest period) but the mirror's gets at \
             least {:.0} % of its light: the figure below shows the mirror's colour, and the diffracted orders fall \
             between the directions sampled or are fainter; the BRDF maps above show them.",
            100.0 * SEEN_SHARE
        );
    };
    let flat_lit: Vec<String> = v["flat_mirror_lit_views"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|x| x.as_str().map(str::to_string))
        .collect();
    let scan_lit = lit_views(v);
    // Views the structure lights where a flat mirror under the same window is dark: their colours are the
    // structure's whatever the window does.
    let structure_only: Vec<String> = scan_lit.iter().filter(|n| !flat_lit.contains(n)).cloned().collect();
    let flat = v["flat_mirror_delta_s_jnd"].as_f64();
    let window = match (largest_delta_s_from_mirror(v, Some(&structure_only)), flat) {
        (Some((s, there)), _) if !v["flat_mirror_lit_views"].is_null() => {
            let place = if there == at {
                "leaves that direction dark".to_string()
            } else {
                format!("leaves dark it changes by up to {s:.1} JND (at {there})")
            };
            let lead = if there == at { "" } else { "in directions " };
            format!(
                "; {lead}a flat mirror of the scan's size under the same coherence window {place}, so the iridescence \
                 is the structure's and {}",
                seen(s)
            )
        }
        (_, Some(f)) if best <= f + 1.0 => format!(
            "; a flat mirror of the scan's size under the same coherence window changes by {f:.1} JND in the same \
             directions, as much or more, so what the animal sees here is the window's own colours (the scan is \
             smaller than the light's coherence), not its structure's"
        ),
        (_, Some(f)) => format!(
            "; a flat mirror of the scan's size under the same coherence window changes by {f:.1} JND (the window's \
             own colours), less, so the iridescence is the structure's and {}",
            seen(best)
        ),
        (_, None) => format!(", so the iridescence is {}", seen(best)),
    };
    format!(
        "{head}, the scan's colour changes with the viewing direction by up to {best:.1} JND against the mirror \
         direction (at {at}, among the {rule}; 1 JND is just noticeable){window}: the figure below shows each \
         direction in false colour."
    )
}

/// The scalar model's error on the scan, in one sentence with its numbers.
fn scalar_sentence(e: &Value) -> String {
    let pct = |v: &Value| 100.0 * v.as_f64().unwrap_or(f64::NAN);
    let at = &e["worst_at"];
    format!(
        "Against Maxwell's equations (the C-method on the scan's strongest period, {:.0} nm, its profile averaged \
         along the ridges, on keratin, light at normal incidence), the scalar model behind the colours is off by up to \
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

/// Why the Taylor expansion refuses the levelled relief of `info` at the report's shortest wavelength (380 nm),
/// if it does: the same test as every step that would use it (`terms_for_bound` on `|h − mean|max`).
fn too_deep_for_taylor(info: &Value) -> Option<String> {
    let (max, min, mean) =
        (info["height_max_nm"].as_f64()?, info["height_min_nm"].as_f64()?, info["mean_nm"].as_f64()?);
    let h = (max - mean).max(mean - min);
    iridis_diffraction::taylor::terms_for_bound(h, 380.0, iridis_diffraction::grating::TAYLOR_EPSILON)
        .err()
        .map(|e| e.to_string())
}

/// The report's first sentence for a relief too deep for the scalar model: what it skipped and what to run.
fn deep_verdict(surface: &str, why: &str) -> String {
    let q = quote(surface);
    format!(
        "The scan's relief is too deep for the scalar model's Taylor expansion, so this report shows its relief, \
         roughness and periods but no colours: {why}. Its colours: `iridis grating {q} --method rigorous \
         --unit-cell auto --material keratin` (order efficiencies from Maxwell's equations) or `iridis brdf-map {q} \
         --method ground-truth -o map.png` (the BRDF map by the direct sum)."
    )
}

/// What the relief is made of in each step, in one place (`reflectors` in report.json, a line under the verdict):
/// the steps are the commands' defaults, and the scalar model's error is measured on a biological material.
fn reflectors() -> Value {
    let material = crate::rigorous_brdf::SCAN_MATERIAL;
    json!({
        "unit_cell": "n=1.5",
        "maps_and_vision": crate::fresnel::DEFAULT_FRESNEL,
        "scalar_model_error": material,
        "sentence": format!(
            "Reflectors: the unit cell's orders and the mirror colour are computed over n = 1.5 (its exact Fresnel \
             reflectances, `grating`'s default), the BRDF maps and the animal's view with Schlick's approximation for \
             n = 1.5 (`{}`, the maps' default), and the scalar model's error on {material} (Leertouwer et al. 2011), \
             the material of snake scales and feathers; each step's command line gives them.",
            crate::fresnel::DEFAULT_FRESNEL
        ),
    })
}

/// The first sentence for a patch too small to judge ([`iridis_surface::TWO_WAVELENGTHS_NM`], no period found):
/// the shares its few orders carry, and why they say nothing of the surface.
fn small_patch_verdict(info: &Value, grating: &[Value]) -> String {
    let share = |g: &Value| 100.0 * g["colour"]["diffracted_share"].as_f64().unwrap_or(0.0);
    let extent = |k: usize| info["extent_nm"][k].as_f64().unwrap_or(0.0);
    format!(
        "The scan is too small to tell whether the surface diffracts visible light: at {:.0} × {:.0} nm ({} × {} \
         samples) it is under two wavelengths (1100 nm) across and no period was found in it. Taken as one unit \
         cell of a periodic surface it sends {:.2} % of the light it reflects out of the mirror direction at normal \
         incidence and {:.2} % at 45° (D65, luminance-weighted; scalar model), into the few orders of its own \
         extent repeated, which the surface need not have: scan a larger area.",
        extent(0),
        extent(1),
        info["cols"],
        info["rows"],
        share(&grating[0]),
        share(&grating[1]),
    )
}

/// What the scan does to light, in words a biologist reads first.
fn verdict(info: &Value, grating: &[Value], diffracts: bool, level: &str) -> String {
    use crate::grating::FIRST_ORDER_AT_45_NM;
    let share = |g: &Value| 100.0 * g["colour"]["diffracted_share"].as_f64().unwrap_or(0.0);
    let periods = crate::surface::structural_periods_nm(info);
    let longest = periods.iter().fold(0.0f64, |m, &p| m.max(p));
    let specular = &grating[0]["colour"]["specular"];
    if diffracts {
        format!(
            "The scan diffracts visible light: taken as one unit cell of a periodic surface, it sends {:.2} % of the \
             light it reflects into orders other than the mirror direction at normal incidence and {:.2} % at 45° \
             (D65, luminance-weighted; scalar model); {}.",
            share(&grating[0]),
            share(&grating[1]),
            periods.first().map_or(
                "no period was found in it: its structure is longer than a quarter of the scan, or has no period \
                 (the notes say which)"
                    .to_string(),
                |p| format!("its strongest period is {p:.0} nm")
            )
        )
    } else {
        let why = if periods.is_empty() {
            "it has no dominant period".to_string()
        } else if longest < crate::grating::VISIBLE_PERIOD_NM {
            format!(
                "its periods ({} nm) are all shorter than half the shortest visible wavelength (190 nm), so no \
                 diffraction order of visible light can leave it",
                periods.iter().map(|p| format!("{p:.0}")).collect::<Vec<_>>().join(", ")
            )
        } else if longest < FIRST_ORDER_AT_45_NM {
            format!(
                "its longest period ({longest:.0} nm) is too short for a visible first order under the report's \
                 light at 0° and 45° (one needs d > λ/(1 + sin 45°) = {FIRST_ORDER_AT_45_NM:.0} nm at 380 nm); light \
                 nearer grazing can diffract from it (d > λ/2 = 190 nm)"
            )
        } else {
            format!(
                "its orders carry under {:.1} % of the light at 0° and 45° (longest period {longest:.0} nm)",
                100.0 * crate::grating::DIFFRACTS_SHARE
            )
        };
        // What leaves the mirror direction where no period of the scan has a visible order at these angles.
        let whither = match (periods.is_empty() || longest < FIRST_ORDER_AT_45_NM, level) {
            (false, _) => "",
            (true, "plane") => {
                " (into the orders of the scan's own extent: its edges and any tilt that plane levelling left on a \
                 periodic relief, not its structure)"
            }
            (true, _) => " (into the orders of the scan's own extent: its edges, not its structure)",
        };
        format!(
            "The scan diffracts no visible light: {why}. Taken as one unit cell of a periodic surface it sends {:.4} % \
             of the reflected light out of the mirror direction at normal incidence, {:.4} % at 45°{whither}. It looks \
             like a mirror of colour {} \
             (reflectance Y = {:.2} % at normal incidence, n = 1.5 under the relief), so no BRDF map is drawn, no \
             test bench is run and no animal's view across directions is taken (--size, --visual unused).",
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
    let name = Path::new(r["surface"].as_str().unwrap_or(""))
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    let mut h = String::from("<!doctype html><meta charset=utf-8><title>iridis report</title>\n<style>body{font-family:sans-serif;max-width:1000px;margin:auto}code{background:#eee;padding:2px}img{max-width:100%}.w{color:#a40}.swatch{display:inline-block;width:2em;height:1em;border:1px solid #888;vertical-align:middle}</style>\n");
    h += &format!("<h1>iridis report: {}</h1>\n", html_escape(&name));
    // No swatch where no mirror colour was computed (a relief too deep for the scalar model), rather than black.
    let swatch = r["unit_cell"][0]["specular"]["hex"]
        .as_str()
        .map_or(String::new(), |hex| format!(" <span class=swatch style=\"background:{hex}\"></span> (mirror colour)"));
    h += &format!("<p><b>{}</b>{swatch}</p>\n", html_escape(r["verdict"].as_str().unwrap_or("")));
    if r["too_deep_for_scalar_model"].is_null() {
        // A relief too deep for the scalar model has no colours, so no reflectors to name.
        h += &format!("<p>{}</p>\n", html_escape(r["reflectors"]["sentence"].as_str().unwrap_or("")));
    }
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
        let period = match (p["period_nm"].as_f64(), p["period_uncertainty_nm"].as_f64()) {
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
        h += &format!("<p><code>iridis {}</code></p>\n", html_escape(&command_line(&st.args)));
    }
    h
}
