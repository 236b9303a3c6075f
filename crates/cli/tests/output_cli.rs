//! Outputs keep their promises (issue 20, items 5, 6, 10): all outputs of a run or none, every path checked
//! before any computing, one path never used twice, the format of every output follows its extension (or the
//! output is refused with the list of supported ones), and JSON that echoes its inputs with arrays on a line.

use crate::common;

use std::path::Path;

use common::{assert_fails, iridis, json_of, tmp};

/// A small surface: the map commands finish in well under a second on it.
const SMALL: &str = "builtin:sine?size=4um&pixel=50nm";
const SMALL_MODEL: [&str; 4] = ["--coherence", "4um", "--uv-resolution", "31"];

fn p(dir: &Path, name: &str) -> String {
    dir.join(name).display().to_string()
}

/// Nothing at all in the folder: no output, no temporary file left behind.
fn assert_empty(dir: &Path) {
    let left: Vec<_> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert!(left.is_empty(), "left in {}: {left:?}", dir.display());
}

#[test]
fn a_bad_second_output_leaves_no_first_output() {
    let d = tmp();
    let new = p(d.path(), "new.png");
    for (flag, bad) in [("--raw", "/nonexistent/x.npy"), ("--exr", "/nonexistent/x.exr")] {
        let mut args = vec!["brdf-map", SMALL, "--size", "16", "-o", &new, flag, bad];
        args.extend(SMALL_MODEL);
        assert_fails(&args, &["/nonexistent", "does not exist"]);
        assert_empty(d.path());
    }
    assert_fails(
        &["render", "examples/soap_bubble.toml", "--size", "8x8", "-o", &new, "--exr", "/nonexistent/x.exr"],
        &["/nonexistent", "does not exist"],
    );
    assert_empty(d.path());
    // The same with a good second output writes both.
    let raw = p(d.path(), "x.npy");
    let mut args = vec!["brdf-map", SMALL, "--size", "16", "-o", &new, "--raw", &raw];
    args.extend(SMALL_MODEL);
    let out = iridis(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(Path::new(&new).exists() && Path::new(&raw).exists());
}

/// The paths are checked before any computing: a run that would take minutes (the ground truth of the full
/// Elaphe patch at 512²) fails at once. "At once" is read from what the run said, not from a clock: the error is
/// its only line, before even the note that loading the surface makes.
#[test]
fn outputs_are_checked_before_the_work() {
    for args in [
        &["brdf-map", "builtin:elaphe", "--method", "ground-truth", "-o", "/nonexistent/m.png"][..],
        &["precompute", "builtin:elaphe", "-o", "/nonexistent/t.npz"],
        &["report", "builtin:elaphe", "-o", "/dev/null"],
    ] {
        let out = iridis(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{args:?}: more than the refusal: {stderr}");
    }
    // Where the output is good the surface is loaded with a note first: the count above means something.
    let d = tmp();
    let good = p(d.path(), "m.png");
    let mut args = vec!["brdf-map", SMALL, "--size", "16", "-o", &good];
    args.extend(SMALL_MODEL);
    let out = iridis(&args);
    assert!(String::from_utf8_lossy(&out.stderr)
        .lines()
        .next()
        .unwrap_or("")
        .ends_with("levelling: none (built-ins are used as generated)"));
    // A folder output given a file's name says which it needs.
    let file = p(d.path(), "notes.txt");
    std::fs::write(&file, "mine").unwrap();
    assert_fails(
        &["report", SMALL, "-o", &file, "--size", "16"],
        &["cannot create", "it is a file, and this output is a folder"],
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
}

#[test]
fn one_path_for_two_outputs_is_refused() {
    let d = tmp();
    let m = p(d.path(), "m.exr");
    let same = format!("{}/./m.exr", d.path().display());
    let mut args = vec!["brdf-map", SMALL, "--size", "16", "-o", &m, "--exr", &same];
    args.extend(SMALL_MODEL);
    assert_fails(&args, &["same file"]);
    let png = p(d.path(), "r.png");
    assert_fails(
        &[
            "render",
            "examples/soap_bubble.toml",
            "--size",
            "8x8",
            "-o",
            &png.replace("r.png", "r.exr"),
            "--exr",
            &png.replace("r.png", "r.exr"),
        ],
        &["same file"],
    );
    assert_fails(&["surface", "generate", "sine", "--size", "2um", "-o", &png, "--image", &png], &["same file"]);
    assert_empty(d.path());
}

/// Every command with file outputs: a name whose extension it does not write is refused, naming the ones
/// it writes, and nothing is written.
#[test]
fn every_output_format_follows_its_extension_or_is_refused() {
    let d = tmp();
    let f = |n: &str| p(d.path(), n);
    let film = "air | water {d} | air";
    let cases: Vec<(Vec<String>, Vec<&str>)> = vec![
        (vec!["brdf-map".into(), SMALL.into(), "-o".into(), f("m.jpg")], vec!["m.jpg", ".png", ".exr", ".npy"]),
        (
            vec!["brdf-map".into(), SMALL.into(), "-o".into(), f("m.png"), "--raw".into(), f("m.txt")],
            vec!["--raw", ".npy"],
        ),
        (
            vec!["brdf-map".into(), SMALL.into(), "-o".into(), f("m.png"), "--exr".into(), f("m.tif")],
            vec!["--exr", ".exr"],
        ),
        (vec!["precompute".into(), SMALL.into(), "-o".into(), f("t.npy")], vec!["-o", ".npz"]),
        (vec!["render".into(), "examples/soap_bubble.toml".into(), "-o".into(), f("r.jpg")], vec![".png", ".exr"]),
        (
            vec![
                "render".into(),
                "examples/soap_bubble.toml".into(),
                "-o".into(),
                f("r.png"),
                "--exr".into(),
                f("r.png2"),
            ],
            vec!["--exr", ".exr"],
        ),
        (
            vec!["thinfilm".into(), "chart".into(), "--stack".into(), film.into(), "-o".into(), f("c.pdf")],
            vec!["-o", ".png"],
        ),
        (
            vec![
                "thinfilm".into(),
                "chart".into(),
                "--stack".into(),
                film.into(),
                "-o".into(),
                f("c.png"),
                "--csv".into(),
                f("c.txt"),
            ],
            vec!["--csv", ".csv"],
        ),
        (
            vec![
                "thinfilm".into(),
                "spectrum".into(),
                "--stack".into(),
                "air | water 300nm | air".into(),
                "--plot".into(),
                f("s.svg"),
            ],
            vec!["--plot", ".png"],
        ),
        (
            vec![
                "thinfilm".into(),
                "table".into(),
                "--stack".into(),
                "air | water 300nm | air".into(),
                "-o".into(),
                f("t.txt"),
            ],
            vec!["-o", ".csv"],
        ),
        (
            vec![
                "thinfilm".into(),
                "table".into(),
                "--stack".into(),
                "air | water 300nm | air".into(),
                "--plot".into(),
                f("t.jpg"),
            ],
            vec!["--plot", ".png"],
        ),
        (
            vec![
                "thinfilm".into(),
                "profile".into(),
                "--stack".into(),
                "air | Au 30nm | glass".into(),
                "--wavelength".into(),
                "500nm".into(),
                "--plot".into(),
                f("p.pdf"),
            ],
            vec!["--plot", ".png"],
        ),
        (
            vec!["surface".into(), "generate".into(), "sine".into(), "-o".into(), f("s.jpg")],
            vec![".gwy", ".npy", ".png", ".txt"],
        ),
        (
            vec![
                "surface".into(),
                "generate".into(),
                "sine".into(),
                "-o".into(),
                f("s.npy"),
                "--image".into(),
                f("s.svg"),
            ],
            vec!["--image", ".png"],
        ),
        (
            vec!["surface".into(), "info".into(), "builtin:sine".into(), "--psdf".into(), f("p.jpg")],
            vec!["--psdf", ".png"],
        ),
        (vec!["surface".into(), "convert".into(), "builtin:sine".into(), f("s.tiff")], vec![".gwy", ".npz"]),
        (vec!["testbench".into(), SMALL.into(), "--plot".into(), f("b.svg")], vec!["--plot", ".png"]),
        (
            vec![
                "sweep".into(),
                SMALL.into(),
                "--param".into(),
                "terms".into(),
                "--values".into(),
                "2".into(),
                "-o".into(),
                f("s.jpg"),
            ],
            vec!["-o", ".png"],
        ),
        (vec!["experiment".into(), "laser".into(), SMALL.into(), "-o".into(), f("l.jpg")], vec!["-o", ".png"]),
        (vec!["bench".into(), "diffraction-accuracy".into(), "--convergence-plot".into(), f("c.pdf")], vec![".png"]),
    ];
    for (args, needles) in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_fails(&args, needles);
    }
    assert_empty(d.path());
}

/// `brdf-map -o` writes the format its extension names: PNG, OpenEXR or NumPy, the same map in each.
#[test]
fn brdf_map_writes_png_exr_or_npy_by_extension() {
    let d = tmp();
    for (name, magic) in
        [("m.png", &b"\x89PNG"[..]), ("m.exr", &[0x76, 0x2f, 0x31, 0x01][..]), ("m.npy", &b"\x93NUMPY"[..])]
    {
        let out_path = p(d.path(), name);
        let mut args = vec!["brdf-map", SMALL, "--size", "16", "-o", &out_path];
        args.extend(SMALL_MODEL);
        let out = iridis(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let bytes = std::fs::read(&out_path).unwrap();
        assert_eq!(&bytes[..magic.len()], magic, "{name}");
    }
    // The .npy holds the linear XYZ map that --raw writes (float64, 16 × 16 × 3).
    let raw = p(d.path(), "raw.npy");
    let png = p(d.path(), "n.png");
    let mut args = vec!["brdf-map", SMALL, "--size", "16", "-o", &png, "--raw", &raw];
    args.extend(SMALL_MODEL);
    assert!(iridis(&args).status.success());
    assert_eq!(std::fs::read(&raw).unwrap(), std::fs::read(p(d.path(), "m.npy")).unwrap());
}

/// `--json` answers carry their inputs, as typed or as defaults, and print arrays of numbers on one line.
#[test]
fn json_echoes_its_inputs_and_keeps_arrays_on_a_line() {
    let stack = "air | water 348nm | air";
    let v = json_of(&["thinfilm", "color", "--stack", stack, "--angle", "30deg", "--observer", "1964", "--json"]);
    let i = &v["inputs"];
    assert_eq!(i["stack"], stack);
    assert_eq!(i["angle"], "30deg");
    assert_eq!(i["observer"], "1964");
    assert_eq!(i["illuminant"], "d65", "a default is echoed too");
    assert_eq!((i["from"].as_str(), i["to"].as_str(), i["step"].as_str()), (Some("380nm"), Some("780nm"), Some("5nm")));
    assert_eq!(i["roughness"], serde_json::Value::Null, "an option not given and without default is null");
    assert!(i.get("json").is_none());

    let out = iridis(&["thinfilm", "spectrum", "--stack", stack, "--step", "10nm", "--json"]);
    let text = String::from_utf8_lossy(&out.stdout);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let n = v["wavelength_nm"].as_array().unwrap().len();
    assert_eq!(n, 41);
    // One line per array: the line of `R` holds all 41 numbers, and the whole answer is a few dozen lines.
    let r_line = text.lines().find(|l| l.trim_start().starts_with("\"R\": [")).unwrap();
    let inside = r_line.split_once('[').unwrap().1.split_once(']').unwrap().0;
    assert_eq!(inside.split(", ").count(), n, "{r_line}");
    assert!(text.lines().count() < 40, "{} lines", text.lines().count());
    assert_eq!(v["inputs"]["step"], "10nm");
    // Objects stay one key a line (a nested object is indented).
    assert!(text.contains("\n  \"inputs\": {\n    \""), "{text}");
}

/// `precompute` says how big the table will be before it builds and writes it, and the figure is the size
/// of the file it writes (res² × 3 × (2N+1) float64 values and a few small arrays).
#[test]
fn precompute_states_the_size_before_writing() {
    let d = tmp();
    let t = p(d.path(), "t.npz");
    let out = iridis(&["precompute", SMALL, "--coherence", "4um", "--uv-resolution", "41", "-o", &t]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let line = stderr.lines().find(|l| l.contains("will hold")).unwrap_or_else(|| panic!("{stderr}"));
    // "…/t.npz will hold 41² × 3 × 2N+1 values in f64: X MB"
    let powers: usize = line.split(" × ").nth(2).unwrap().split(' ').next().unwrap().parse().unwrap();
    let mb: f64 = line.rsplit(": ").next().unwrap().trim_end_matches(" MB").parse().unwrap();
    assert_eq!(mb, ((41 * 41 * 3 * powers * 8) as f64 / 1e5).round() / 10.0, "{line}");
    let size = std::fs::metadata(&t).unwrap().len() as f64 / 1e6;
    assert!((size - mb).abs() < 0.05 + 0.01 * mb, "file {size} MB, announced {mb} MB");
    // The reported time covers the whole run, table build included.
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains(" s)"), "{stdout}");
}

/// `brdf-map` reports the time of the whole run (loading, Taylor terms, table) next to the map's own.
#[test]
fn brdf_map_time_includes_the_preparation() {
    let d = tmp();
    let m = p(d.path(), "m.png");
    let mut args = vec!["brdf-map", SMALL, "--size", "16", "-o", &m];
    args.extend(SMALL_MODEL);
    let t = std::time::Instant::now();
    let out = iridis(&args);
    let wall = t.elapsed().as_secs_f64();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let secs = |after: &str| -> f64 {
        let rest = stdout.split(after).nth(1).unwrap_or_else(|| panic!("{stdout}"));
        rest.trim_start().split(' ').next().unwrap().parse().unwrap()
    };
    let (all, prepare) = (secs("16², "), secs("in all: "));
    assert!(all >= prepare && all <= wall + 0.01, "{stdout} (wall {wall:.2} s)");
    assert!(prepare > 0.0, "{stdout}");
}

/// Built-in tables of materials are cached under a key of their content: a second render finds the table
/// (no "computing" line), and the cache file is named by the built-in and a hash of what made it.
#[test]
fn builtin_tables_are_cached_under_a_content_key() {
    let d = tmp();
    let cache = d.path().join("cache");
    let png = p(d.path(), "s.png");
    // A small built-in with options (the key must follow them; the file is named by the built-in alone).
    let scene = p(d.path(), "s.toml");
    std::fs::write(
        &scene,
        "[camera]\nkind = \"hemisphere\"\ntarget = [0, 0, 0]\nnormal = [0, 0, 1]\n[[light]]\n\
         kind = \"directional\"\ndirection = [0.3, 0.2, 1]\n[materials.grating]\nkind = \"diffraction\"\n\
         table = \"builtin:sine?size=4um&pixel=50nm\"\nuv_resolution = 31\n[[object]]\nkind = \"plane\"\n\
         normal = [0, 0, 1]\ntangent = [1, 0, 0]\nmaterial = \"grating\"\n",
    )
    .unwrap();
    let run = || {
        let out = crate::common::command()
            .args(["render", &scene, "--size", "8x8", "-o", &png])
            .env("IRIDIS_CACHE", &cache)
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let first = run();
    assert!(first.contains("computing the table builtin:sine?size=4um&pixel=50nm"), "{first}");
    let files: Vec<String> =
        std::fs::read_dir(&cache).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    assert_eq!(files.len(), 1, "{files:?}");
    let hash = files[0].strip_prefix("sine-").and_then(|f| f.strip_suffix(".npz")).unwrap();
    assert!(hash.len() == 16 && hash.chars().all(|c| c.is_ascii_hexdigit()), "{files:?}");
    let second = run();
    assert!(!second.contains("computing"), "{second}");
}

/// Long work announces itself in a log too (stderr not a terminal, where the bars are hidden): a step still
/// running after the threshold (1 s; `IRIDIS_PROGRESS_AFTER_MS=0` here, so every step counts) says so in one
/// line and again when it is done — loading, Taylor terms and the lookup tables of `precompute`.
#[test]
fn long_steps_announce_themselves_in_a_log() {
    let d = tmp();
    let t = p(d.path(), "t.npz");
    let out = crate::common::command()
        .args(["precompute", SMALL, "--coherence", "4um", "--uv-resolution", "31", "-o", &t])
        .env("IRIDIS_PROGRESS_AFTER_MS", "0")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    for needle in [&format!("loading {SMALL}: "), "Taylor terms: done in", "lookup tables: done in", "/31 after "] {
        assert!(stderr.contains(needle), "no '{needle}' in {stderr}");
    }
    // With the default threshold a run this short prints none of them.
    let out = iridis(&["precompute", SMALL, "--coherence", "4um", "--uv-resolution", "31", "-o", &t]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("done in"), "{stderr}");
}

/// A report on a built-in levels its relief as its model steps do, not at all (built-ins are used as
/// generated): it plane-levelled the relief figure and said "levelling: plane" while every diffraction step used
/// the surface as generated.
#[test]
fn a_reports_levelling_is_its_model_steps() {
    let d = tmp();
    let out = p(d.path(), "r");
    common::succeeds(&["report", SMALL, "--size", "16", "-o", &out]);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(format!("{out}/report.json")).unwrap()).unwrap();
    assert_eq!(json["level"], "none", "{}", json["level"]);
    let html = std::fs::read_to_string(format!("{out}/index.html")).unwrap();
    assert!(html.contains("levelling: none."));
    // The maps' exposures are in RU, which the report now defines where it shows them.
    assert!(html.contains("1 RU shows a normal-incidence perfect mirror under the light as just white"));
}
