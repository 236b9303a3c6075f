//! `iridis brdf-map --gpu` and `iridis bench gpu` (issue 8). The tests that render need a Vulkan adapter
//! (lavapipe from `mesa-vulkan-drivers` on machines without a GPU); without one they fail, unless
//! `IRIDIS_SKIP_GPU=1`. The no-adapter test hides every Vulkan driver and runs anywhere.

use crate::common;

use std::process::Command;

use common::{assert_fails, delta_e_between, iridis, json_of, png_lab, tmp};
use iridis_color::Lab;

/// Tests that run the scene shader take turns: on lavapipe its first compilation takes about a minute of one
/// core, and Mesa's shader cache serves every later process only once one has finished it (processes that start
/// it together each compile it). The turn is taken in this process and, through a file lock next to Mesa's
/// cache, with the other test processes of tools/test.sh: the Python package's GPU render test runs beside this
/// binary and takes the same lock (crates/python/tests/test_render.py). Without it, in a fresh run (2026-11-27),
/// that test took 109 s, compiling the shader while this binary did.
static SCENE_SHADER: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// The turn at the scene shader: this process's, and the file lock of every process (released when dropped).
struct SceneShaderTurn {
    _process: std::sync::MutexGuard<'static, ()>,
    _file: Option<std::fs::File>,
}

/// The file the test processes lock: `$MESA_SHADER_CACHE_DIR/iridis-scene-shader.lock` (tools/test.sh sets the
/// folder), else in the temporary folder.
fn scene_shader_lock_file() -> Option<std::fs::File> {
    let dir =
        std::env::var_os("MESA_SHADER_CACHE_DIR").map(std::path::PathBuf::from).unwrap_or_else(std::env::temp_dir);
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(dir.join("iridis-scene-shader.lock"))
        .ok()?;
    // Without the lock (a file system without flock) the tests still run, only possibly compiling twice.
    rustix::fs::flock(&file, rustix::fs::FlockOperation::LockExclusive).ok()?;
    Some(file)
}

/// A test that runs the scene shader waits for its turn, then checks [`have_gpu`]: the turn to hold, or `None`
/// when the GPU tests are skipped.
fn scene_shader_turn() -> Option<SceneShaderTurn> {
    let process = SCENE_SHADER.lock().unwrap_or_else(|e| e.into_inner());
    let turn = SceneShaderTurn { _process: process, _file: scene_shader_lock_file() };
    have_gpu().then_some(turn)
}

/// True when the GPU tests may run; panics with the driver hint when there is no adapter and no skip.
fn have_gpu() -> bool {
    let out = iridis(&["bench", "gpu", "--size", "8", "--film-size", "8x8", "--frames", "1", "--table", "none.npz"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !stderr.contains("no GPU adapter") {
        return true;
    }
    if std::env::var("IRIDIS_SKIP_GPU").as_deref() == Ok("1") {
        eprintln!("GPU test skipped (IRIDIS_SKIP_GPU=1): {stderr}");
        return false;
    }
    panic!("{stderr}\nThese tests need a Vulkan adapter; set IRIDIS_SKIP_GPU=1 to skip them.");
}

/// A small table: 8 µm blazed grating at 50 nm, coherence 8 µm, 61² grid.
fn small_table(dir: &std::path::Path) -> String {
    let t = dir.join("blazed.npz").display().to_string();
    let out = iridis(&[
        "precompute",
        "builtin:blazed?size=8um&pixel=50nm",
        "-o",
        &t,
        "--coherence",
        "8um",
        "--uv-resolution",
        "61",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    t
}

#[test]
fn no_adapter_is_a_clear_error_not_a_panic() {
    // Point the Vulkan loader at no driver at all.
    for args in [
        vec!["bench", "gpu", "--frames", "1"],
        vec!["brdf-map", "builtin:blazed?size=4um&pixel=50nm", "--gpu", "--size", "16", "-o", "/tmp/never.png"],
        vec!["render", "examples/gold_sphere.toml", "--gpu", "--size", "16x16", "-o", "/tmp/never.png"],
        vec!["bench", "gpu", "examples/gold_sphere.toml", "--size", "16x16", "--frames", "1"],
    ] {
        let out = common::command()
            .args(&args)
            .env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
            .env("VK_DRIVER_FILES", "/nonexistent/icd.json")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
        let error: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
        assert_eq!(error.len(), 1, "{stderr}");
        assert!(error[0].contains("no GPU adapter") && error[0].contains("mesa-vulkan-drivers"), "{}", error[0]);
    }
    assert!(!std::path::Path::new("/tmp/never.png").exists());
}

/// Without XDG_RUNTIME_DIR (a service, `sudo`, `env -i`) the graphics stack printed "error: XDG_RUNTIME_DIR is
/// invalid or not set in the environment." twice on every successful `--gpu` run; iridis now gives the process
/// a private one, so stderr holds only iridis' own lines — and none of them says "error".
#[test]
fn a_gpu_run_without_xdg_runtime_dir_prints_no_driver_noise() {
    if !have_gpu() {
        return;
    }
    let dir = tmp();
    let png = dir.path().join("g.png");
    for xdg in [None, Some("/nonexistent/run")] {
        let mut cmd = common::command();
        cmd.args(["brdf-map", "builtin:blazed?size=4um&pixel=50nm", "--gpu", "--size", "16"]).args([
            "--coherence",
            "4um",
            "--uv-resolution",
            "31",
            "-o",
            png.to_str().unwrap(),
        ]);
        match xdg {
            None => cmd.env_remove("XDG_RUNTIME_DIR"),
            Some(v) => cmd.env("XDG_RUNTIME_DIR", v),
        };
        let out = cmd.output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{stderr}");
        assert!(!stderr.contains("XDG_RUNTIME_DIR") && !stderr.contains("error"), "XDG_RUNTIME_DIR={xdg:?}: {stderr}");
        assert!(png.exists());
    }
}

/// docs/json.md's GPU sections against the real output (the others are checked by json_doc_cli.rs).
#[test]
fn gpu_json_matches_docs_json_md() {
    let Some(_turn) = scene_shader_turn() else { return };
    let (shapes, sections) = common::json_doc::read();
    let mut problems = Vec::new();
    let mut ran = 0;
    for s in sections.iter().filter(|s| s.gpu && !s.display) {
        let words = common::json_doc::split(&s.command);
        let args: Vec<&str> = words[1..].iter().map(String::as_str).collect();
        problems.extend(common::json_doc::check(s, &shapes, &json_of(&args)));
        ran += 1;
    }
    assert!(ran >= 2, "ran {ran}");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Asserts that a PNG written with `--gpu` shows the CPU's PNG: ΔE00 mean < 1 and p99 < 3. Prints the
/// statistics under `what`; returns the CPU image's pixels for the caller's own checks.
fn assert_gpu_png_matches_cpu(what: &str, cpu: &std::path::Path, gpu: &std::path::Path) -> Vec<Lab> {
    let (a, b) = (png_lab(cpu), png_lab(gpu));
    let d = delta_e_between(&a, &b);
    let (mean, p99) = (d.mean, d.p99);
    eprintln!("{what}: ΔE00 mean {mean:.4}, p99 {p99:.4}");
    assert!(mean < 1.0 && p99 < 3.0, "{what}: mean {mean}, p99 {p99}");
    a
}

#[test]
fn brdf_map_on_the_gpu_matches_the_cpu_image() {
    if !have_gpu() {
        return;
    }
    let dir = tmp();
    let table = small_table(dir.path());
    let cpu = dir.path().join("cpu.png");
    let gpu = dir.path().join("gpu.png");
    for (png, extra) in [(&cpu, None), (&gpu, Some("--gpu"))] {
        let mut args = vec!["brdf-map", &table, "--incidence", "20deg,30deg", "--size", "80", "--exposure", "1500"];
        let p = png.display().to_string();
        args.extend(["-o", &p]);
        args.extend(extra);
        let out = iridis(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    let a = assert_gpu_png_matches_cpu("brdf-map --gpu vs CPU (PNG)", &cpu, &gpu);
    assert_eq!(a.len(), 80 * 80);
    // The map is lit, so the comparison is not between two black images.
    assert!(a.iter().filter(|l| l.l > 20.0).count() > 200);
    // --subsamples: the GPU's 80² map averaged over 2 × 2 blocks against the CPU's 2² view samples a pixel.
    for (png, extra) in [(&cpu, None), (&gpu, Some("--gpu"))] {
        let p = png.display().to_string();
        let mut args = vec!["brdf-map", &table, "--incidence", "20deg,30deg", "--size", "40", "--subsamples", "2"];
        args.extend(["--exposure", "1500", "-o", &p]);
        args.extend(extra);
        let out = iridis(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    let a = assert_gpu_png_matches_cpu("brdf-map --gpu --subsamples 2 vs CPU (PNG)", &cpu, &gpu);
    assert!(a.len() == 40 * 40 && a.iter().filter(|l| l.l > 20.0).count() > 50);
    // --auto-exposure and --plot from the GPU's map (they were refused with --gpu): the exposure the CPU's map
    // chooses, to the GPU's f32, and the figure written.
    let chosen = |extra: Option<&str>| {
        let (plot, png) = (dir.path().join("plot.png"), dir.path().join("auto.png"));
        let (p, o) = (plot.display().to_string(), png.display().to_string());
        let mut args = vec!["brdf-map", &table, "--incidence", "20deg,30deg", "--size", "40", "--auto-exposure"];
        args.extend(["--plot", &p, "-o", &o]);
        args.extend(extra);
        let out = iridis(&args);
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success() && plot.exists() && png.exists(), "{stderr}");
        let line = stderr.lines().find(|l| l.contains("chosen from the map")).unwrap_or_else(|| panic!("{stderr}"));
        line.split_once("exposure ").unwrap().1.split(' ').next().unwrap().parse::<f64>().unwrap()
    };
    let (on_cpu, on_gpu) = (chosen(None), chosen(Some("--gpu")));
    assert!((on_gpu / on_cpu - 1.0).abs() < 1e-3, "auto exposure {on_gpu} RU on the GPU, {on_cpu} on the CPU");
}

#[test]
fn bench_gpu_reports_adapter_and_frame_times() {
    let Some(_turn) = scene_shader_turn() else { return };
    let dir = tmp();
    let table = small_table(dir.path());
    let v = json_of(&[
        "bench",
        "gpu",
        "--table",
        &table,
        "--size",
        "64x64",
        "--film-size",
        "96x48",
        "--frames",
        "4",
        "--save",
        dir.path().to_str().unwrap(),
        "--json",
    ]);
    assert!(!v["adapter"].as_str().unwrap().is_empty());
    for (part, p) in
        [("lookup", &v["lookup"]), ("film table", &v["film"]["table"]), ("film direct", &v["film"]["direct"])]
    {
        assert_eq!(p["frames"], 4, "{part}");
        let ms = &p["ms"];
        let (mn, med, p99) = (ms["min"].as_f64().unwrap(), ms["median"].as_f64().unwrap(), ms["p99"].as_f64().unwrap());
        assert!(mn > 0.0 && mn <= med && med <= p99, "{part}: {ms}");
        // The GPU's timestamps of the pass (where the adapter has them) lie inside submission → completion.
        if let Some(g) = p["gpu_timestamp_ms"].as_object() {
            let gmed = g["median"].as_f64().unwrap();
            assert!(gmed > 0.0 && gmed <= med + 0.01, "{part}: timestamps {gmed} ms vs wall {med} ms");
        }
        assert!(p["vs_cpu"]["delta_e00_mean"].as_f64().unwrap() < 1.0, "{part}: {p}");
        assert!(p["vs_cpu"]["delta_e00_p99"].as_f64().unwrap() < 3.0, "{part}: {p}");
    }
    assert_eq!(v["lookup"]["size"], serde_json::json!([64, 64]));
    assert_eq!(v["film"]["size"], serde_json::json!([96, 48]));
    // The fast path used its colour table and stays within issue 17's bound of the direct 81-sample frame.
    let t = &v["film"]["table"];
    assert!(t["cos_nodes"].as_u64().unwrap() >= 65 && t["fallback"].is_null(), "{t}");
    assert_eq!(v["film"]["direct"]["wavelengths"], 81);
    let d = &t["vs_direct"];
    assert!(d["delta_e00_mean"].as_f64().unwrap() < 0.1 && d["delta_e00_p99"].as_f64().unwrap() < 0.5, "{d}");
    assert!(v["film"]["direct_over_table_median"].as_f64().unwrap() > 0.0);
    let map = image::open(dir.path().join("lookup_map.png")).unwrap();
    let film = image::open(dir.path().join("film_frame.png")).unwrap();
    assert_eq!((map.width(), map.height(), film.width(), film.height()), (64, 64, 96, 48));
    assert_eq!(image::open(dir.path().join("film_frame_direct.png")).unwrap().width(), 96);
}

#[test]
fn gpu_options_are_checked() {
    assert_fails(&["bench", "gpu", "--size", "64x32"], &["square"]);
    assert_fails(&["bench", "gpu", "--film-size", "big"], &["WIDTHxHEIGHT"]);
    assert_fails(
        &["brdf-map", "builtin:blazed", "--gpu", "--method", "reference", "-o", "/tmp/x.png"],
        &["--gpu", "lookup"],
    );
    assert_fails(
        &["brdf-map", "builtin:blazed", "--gpu", "--fresnel", "stack:air | water 300nm | air", "-o", "/tmp/x.png"],
        &["--gpu", "λ"],
    );
    // --brdf with --gpu wrote no file and said nothing.
    let ground_truth = ["brdf-map", "builtin:blazed", "--gpu", "--method", "ground-truth", "-o", "/tmp/x.png"];
    assert_fails(&[&ground_truth[..], &["--brdf", "/tmp/f.npy"]].concat(), &["--brdf", "sr⁻¹", "leave out --gpu"]);
    assert_fails(&["view", "no_such_scene.toml"], &["no_such_scene.toml", "does not exist"]);
    assert_fails(&["view", "examples/gold_sphere.toml", "--check", "/tmp/shot.jpg"], &[".png"]);
    // What only shapes a SURFACE's table is refused with a scene (it would be ignored), before a window opens.
    assert_fails(
        &["view", "examples/gold_sphere.toml", "--uv-resolution", "101", "--level", "none"],
        &["is a scene", "--uv-resolution 101 --level none", "would be ignored"],
    );
    // --json prints the scripted check's report: without --check there is none.
    // (clap's message names the missing option on the line after `error:`.)
    let out = iridis(&["view", "examples/gold_sphere.toml", "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && stderr.contains("required") && stderr.contains("--check"), "{stderr}");
    assert_fails(&["bench", "gpu", "no_such_scene.toml"], &["no_such_scene.toml"]);
    assert_fails(&["bench", "gpu", "--spectral-samples", "1"], &["--spectral-samples 1", "2 to 4096"]);
    assert_fails(&["bench", "gpu", "--frames", "0"], &["--frames 0", "at least one"]);
    assert_fails(
        &["render", "examples/soap_bubble.toml", "-o", "/tmp/x.png", "--spectral-samples", "20"],
        &["--spectral-samples", "--gpu"],
    );
    assert_fails(
        &["render", "examples/soap_bubble.toml", "-o", "/tmp/x.png", "--gpu", "--spectral-samples", "0"],
        &["--spectral-samples 0", "2 to 4096"],
    );
    // What --gpu does not evaluate is refused, naming what it does.
    assert_fails(
        &["brdf-map", "builtin:blazed", "--gpu", "--method", "nmm", "-o", "/tmp/x.png"],
        &["--gpu", "lookup", "ground-truth", "CPU only"],
    );
    assert_fails(
        &["brdf-map", "builtin:blazed", "--table-precision", "f16", "-o", "/tmp/x.png"],
        &["--table-precision", "--gpu"],
    );
    assert_fails(
        &[
            "brdf-map",
            "builtin:blazed",
            "--gpu",
            "--method",
            "ground-truth",
            "--table-precision",
            "f16",
            "-o",
            "/tmp/x.png",
        ],
        &["--table-precision", "lookup"],
    );
    assert_fails(
        &["brdf-map", "builtin:blazed", "--gpu", "--table-precision", "f64", "-o", "/tmp/x.png"],
        &["f32", "chebK"],
    );
    assert_fails(&["bench", "gpu", "--table-precision", "cheb1"], &["--table-precision", "chebK"]);
    // Its surfaces are read with the surface flags, before a GPU is opened: a current is no height.
    let sxm = format!("{}/../surface/tests/fixtures/nanonis_synthetic.sxm", env!("CARGO_MANIFEST_DIR"));
    assert_fails(
        &["bench", "gpu", "--build-surface", &sxm, "--channel", "Current"],
        &["--build-surface", "--as-height"],
    );
    assert_fails(
        &["bench", "gpu", "--gt-surface", &sxm, "--channel", "Current", "--as-height"],
        &["--gt-surface", "give --height-unit"],
    );
    assert_fails(&["bench", "gpu", "examples/gold_sphere.toml", "--level", "none"], &["--level none would be ignored"]);
    // A scene is timed alone: the shaders' options would change nothing.
    assert_fails(
        &["bench", "gpu", "examples/gold_sphere.toml", "--gt-size", "8", "--stack", "air | water 300nm | air"],
        &["--stack, --gt-size would be ignored", "times the scene renderer only"],
    );
}

/// A table built by `precompute --gpu` against the CPU's, from the files.
#[test]
fn precompute_on_the_gpu_writes_the_cpu_table_in_f32() {
    if !have_gpu() {
        return;
    }
    let dir = tmp();
    let spec = "builtin:xenopeltis?size=5um&pixel=60nm";
    let mut tables = Vec::new();
    for extra in [None, Some("--gpu")] {
        let t = dir.path().join(format!("t{}.npz", tables.len())).display().to_string();
        let mut args = vec!["precompute", spec, "-o", &t, "--coherence", "2.5um", "--uv-resolution", "37"];
        args.extend(extra);
        let out = iridis(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        tables.push(iridis_diffraction::LookupTable::load(std::path::Path::new(&t)).unwrap());
    }
    assert!(tables[0].meta.built_on.is_none());
    assert!(tables[1].meta.built_on.as_deref().is_some_and(|a| !a.is_empty()));
    let err = iridis_gpu::table_build::table_error(&tables[0], &tables[1]);
    eprintln!("precompute --gpu vs CPU: {err:?}");
    // Measured in crates/gpu/tests/diffraction_gpu.rs: ≤ 8.2e-6 per power, ≤ 3.5e-7 of the sum.
    assert!(err.per_power < 5e-5 && err.of_sum < 3e-6, "{err:?}");
}

#[test]
fn ground_truth_maps_on_the_gpu_match_the_cpu_image() {
    if !have_gpu() {
        return;
    }
    let dir = tmp();
    for method in ["ground-truth", "ground-truth-periodic"] {
        let cpu = dir.path().join(format!("{method}_cpu.png"));
        let gpu = dir.path().join(format!("{method}_gpu.png"));
        for (png, extra) in [(&cpu, None), (&gpu, Some("--gpu"))] {
            let p = png.display().to_string();
            let mut args = vec![
                "brdf-map",
                "builtin:sine?size=3um&pixel=60nm",
                "--method",
                method,
                "--incidence",
                "20deg,10deg",
                "--size",
                "24",
                "--exposure",
                "50",
                // A window inside the 3 µm patch: lobes a 24² map resolves (under the light's 65 µm the
                // periodic patch's orders are narrower than a pixel).
                "--coherence",
                "1.5um",
                "-o",
                &p,
            ];
            args.extend(extra);
            let out = iridis(&args);
            assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        }
        let (a, b) = (png_lab(&cpu), png_lab(&gpu));
        let d = delta_e_between(&a, &b);
        let (mean, max) = (d.mean, d.max);
        eprintln!("{method}: brdf-map --gpu vs CPU (PNG): ΔE00 mean {mean:.4}, max {max:.4}");
        // 8-bit PNGs of maps that agree to ~1e-6 in |A|²: at most one level apart.
        assert!(mean < 0.05 && max < 1.0, "{method}: mean {mean}, max {max}");
        assert!(a.iter().filter(|l| l.l > 20.0).count() > 30, "{method}: the map must show something");
    }
}

/// `compare --gpu` (ground truths and lookup tables on the GPU) gives the CPU's Table 2.
#[test]
fn compare_and_sweep_on_the_gpu_give_the_cpu_numbers() {
    if !have_gpu() {
        return;
    }
    let surface = "builtin:elaphe?size=3um&pixel=60nm";
    let common = ["--methods", "lookup,reference", "--size", "16", "--uv-resolution", "41", "--json"];
    let mut runs = Vec::new();
    for extra in [None, Some("--gpu")] {
        let mut args = vec!["compare", surface];
        args.extend(common);
        args.extend(extra);
        runs.push(json_of(&args));
    }
    let rows = |v: &serde_json::Value| v["results"].as_array().unwrap().clone();
    let (cpu, gpu) = (rows(&runs[0]), rows(&runs[1]));
    assert_eq!(cpu.len(), gpu.len());
    for (c, g) in cpu.iter().zip(&gpu) {
        assert_eq!((&c["method"], &c["exposure_ru"]), (&g["method"], &g["exposure_ru"]));
        let (a, b) = (c["mean"].as_f64().unwrap(), g["mean"].as_f64().unwrap());
        eprintln!("{} at {} RU: mean ΔE00 {a:.4} (CPU) vs {b:.4} (GPU)", c["method"], c["exposure_ru"]);
        assert!((a - b).abs() < 2e-3, "{c} vs {g}");
    }
    for (c, g) in runs[0]["periodic_extension_error"]
        .as_array()
        .unwrap()
        .iter()
        .zip(runs[1]["periodic_extension_error"].as_array().unwrap())
    {
        let (a, b) = (c["mean"].as_f64().unwrap(), g["mean"].as_f64().unwrap());
        assert!((a - b).abs() < 2e-3, "{c} vs {g}");
    }
    let dir = tmp();
    let sheet = dir.path().join("sweep.png").display().to_string();
    let v = json_of(&[
        "sweep",
        surface,
        "--method",
        "lookup",
        "--param",
        "uv-resolution",
        "--values",
        "21,41",
        "--size",
        "16",
        "--gpu",
        "-o",
        &sheet,
        "--json",
    ]);
    assert_eq!(v["points"].as_array().unwrap().len(), 2);
}

#[test]
fn render_on_the_gpu_writes_the_cpu_image() {
    let Some(_turn) = scene_shader_turn() else { return };
    let dir = tmp();
    for scene in ["soap_bubble", "snake_xenopeltis"] {
        let cpu = dir.path().join(format!("{scene}_cpu.png"));
        let gpu = dir.path().join(format!("{scene}_gpu.png"));
        let toml = format!("examples/{scene}.toml");
        for (png, extra) in [(&cpu, None), (&gpu, Some("--gpu"))] {
            let p = png.display().to_string();
            let mut args = vec!["render", &toml, "--size", "64x48", "--spp", "2", "-o", &p];
            args.extend(extra);
            // The snake has no thin film: --spectral-samples changes nothing there, and says so.
            let direct = extra.is_some() && scene == "snake_xenopeltis";
            if direct {
                args.extend(["--spectral-samples", "41"]);
            }
            let out = iridis(&args);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "{stderr}");
            if extra.is_some() {
                assert!(String::from_utf8_lossy(&out.stdout).contains("on the GPU"));
            }
            assert_eq!(direct, stderr.contains("--spectral-samples 41 evaluates smooth thin films"), "{stderr}");
        }
        let a = assert_gpu_png_matches_cpu(&format!("{scene}: render --gpu vs CPU (PNG, 2 spp)"), &cpu, &gpu);
        assert_eq!(a.len(), 64 * 48);
        assert!(a.iter().filter(|l| l.l > 10.0).count() > 300, "{scene}: the image must show something");
    }
}

#[test]
fn bench_gpu_times_a_scene_against_the_cpu() {
    let Some(_turn) = scene_shader_turn() else { return };
    let v = json_of(&["bench", "gpu", "examples/soap_bubble.toml", "--size", "40x30", "--frames", "3", "--json"]);
    assert!(!v["adapter"].as_str().unwrap().is_empty());
    assert_eq!(v["size"], serde_json::json!([40, 30]));
    assert_eq!(v["frames"], 3);
    let ms = &v["ms"];
    let (mn, med, p99) = (ms["min"].as_f64().unwrap(), ms["median"].as_f64().unwrap(), ms["p99"].as_f64().unwrap());
    assert!(mn > 0.0 && mn <= med && med <= p99, "{ms}");
    assert!(v["cpu"]["render_s"].as_f64().unwrap() > 0.0);
    assert!(v["vs_cpu"]["delta_e00_mean"].as_f64().unwrap() < 1.0, "{v}");
    // A film scene is also timed with its films evaluated directly; the two images agree.
    let d = &v["film_direct"];
    assert_eq!((d["spectral_samples"].as_u64(), d["frames"].as_u64()), (Some(81), Some(3)), "{d}");
    assert!(d["vs_table"]["delta_e00_mean"].as_f64().unwrap() < 0.1, "{d}");
}

/// The viewer under a virtual X server (Xvfb) with lavapipe, on a BRDF map: `--check` drags, scrolls and presses
/// keys through egui's input path, and each input must change what the window shows; the screenshot is the whole
/// window. The frame goes through the same present pass and egui texture as a scene's.
#[test]
fn viewer_starts_renders_and_answers_input_under_xvfb() {
    if !have_gpu() {
        return;
    }
    viewer_check(&["builtin:blazed", "--uv-resolution", "64"]);
}

/// The viewer on a scene: the scene shader's frames, presented the same way.
#[test]
fn viewer_on_a_scene_under_xvfb() {
    let Some(_turn) = scene_shader_turn() else { return };
    viewer_check(&["examples/snake_elaphe.toml"]);
}

/// The viewer under Xvfb on `input` (the caller has checked [`have_gpu`]).
fn viewer_check(input: &[&str]) {
    if Command::new("xvfb-run").arg("--help").output().is_err() {
        if std::env::var("IRIDIS_SKIP_GPU").as_deref() == Ok("1") {
            eprintln!("viewer test skipped: no xvfb-run (IRIDIS_SKIP_GPU=1)");
            return;
        }
        panic!("the viewer test needs xvfb-run (apt-get install xvfb xauth); IRIDIS_SKIP_GPU=1 skips it");
    }
    let dir = tmp();
    let shot = dir.path().join("viewer.png");
    // A 640×480 screen holds the window at 640×480 (it asks for 1180×720): on lavapipe every frame costs CPU
    // per window pixel (measured: 11 frames of the snake, 19.5 CPU-s at 1180×720, 10.7 at 800×600, 6.9–8.8 at
    // 640×480), and what the check tests — inputs change the frame, the texture holds its pixels, a window-sized
    // screenshot — does not need the larger window.
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 640x480x24", env!("CARGO_BIN_EXE_iridis"), "view"])
        .args(input)
        .args(["--check", shot.to_str().unwrap(), "--json"])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .env("XDG_RUNTIME_DIR", dir.path())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["ok"], true, "{v}");
    assert_eq!(v["texture_equals_frame"], true, "{v}");
    // Its keys are the ones docs/json.md lists.
    let (shapes, sections) = common::json_doc::read();
    let doc = sections.iter().find(|s| s.display && s.command.starts_with("iridis view")).unwrap();
    let problems = common::json_doc::check(doc, &shapes, &v);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 4, "{v}");
    for s in steps {
        assert!(s["change"].as_f64().unwrap() > 0.0, "{s}");
    }
    let img = image::open(&shot).unwrap();
    assert!(img.width() >= 600 && img.height() >= 400, "{}×{}", img.width(), img.height());
}

/// `--frames 4294967296` reserved 137 GB for the timings up front and aborted: --max-seconds ends the run, as it
/// says. `--save` into a folder that does not exist makes it before the work (it failed after the whole run).
#[test]
fn a_huge_frame_count_ends_at_max_seconds_and_save_makes_its_folder() {
    let dir = tmp();
    let save = dir.path().join("new").join("folder");
    let out = iridis(&[
        "bench",
        "gpu",
        "examples/gold_sphere.toml",
        "--size",
        "8x8",
        "--frames",
        "4294967296",
        "--max-seconds",
        "0.2",
        "--save",
        save.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("memory allocation"), "{stderr}");
    assert!(save.join("scene_gpu.png").exists());
}
