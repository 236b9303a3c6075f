//! `iridis thinfilm … --roughness σ --correlation τ` (the LSRS model) as a user runs it: documented keys,
//! the smooth limit, the specular part below the smooth R, the table's size, and clean errors (exit code 2,
//! one `error:` line) for bad roughness and parameters outside the HTSG model's validity.

use crate::common;
use common::{assert_fails, iridis, json_of};

const STACK: &str = "air | water 348nm | Si";
const GRID: [&str; 6] = ["--from", "400nm", "--to", "700nm", "--step", "50nm"];

fn f(v: &serde_json::Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

#[test]
fn listing_3_6_spectrum_reports_specular_and_diffuse_separately() {
    let mut args = vec!["thinfilm", "spectrum", "--stack", STACK, "--angle", "30deg", "--json"];
    args.extend(GRID);
    args.extend(["--roughness", "25nm", "--correlation", "300nm", "--d-iterations", "5"]);
    let v = json_of(&args);
    let (r, s, d) = (f(&v["R_smooth"]), f(&v["specular"]), f(&v["diffuse_per_sr"]));
    assert_eq!(r.len(), 7);
    for i in 0..r.len() {
        assert!(s[i] < r[i] && s[i] > 0.0 && d[i] > 0.0, "{i}: {} {} {}", r[i], s[i], d[i]);
    }
    // Shorter wavelengths scatter more: (σ/λ)².
    assert!(d[0] > d[6]);
    assert!(v["diffuse_error_bound_per_sr"].as_f64().unwrap() < 1e-3);
}

#[test]
fn vanishing_roughness_is_the_smooth_model() {
    let mut args = vec!["thinfilm", "spectrum", "--stack", STACK, "--angle", "45deg", "--json"];
    args.extend(GRID);
    args.extend(["--roughness", "0.000001nm", "--correlation", "300nm"]);
    let v = json_of(&args);
    let mut smooth = vec!["thinfilm", "spectrum", "--stack", STACK, "--angle", "45deg", "--json"];
    smooth.extend(GRID);
    let w = json_of(&smooth);
    for (a, b) in f(&v["specular"]).iter().zip(f(&w["R"])) {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
    assert!(f(&v["diffuse_per_sr"]).iter().all(|d| *d < 1e-12));
}

#[test]
fn table_has_every_view_light_wavelength() {
    let out = iridis(&[
        "thinfilm",
        "table",
        "--stack",
        STACK,
        "--angles",
        "0deg:90deg:30deg",
        "--light-angles",
        "10deg:50deg:20deg",
        "--from",
        "400nm",
        "--to",
        "500nm",
        "--step",
        "50nm",
        "--roughness",
        "25nm",
        "--correlation",
        "300nm",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("view_deg,light_deg,wavelength_nm,specular,diffuse_per_sr"));
    assert_eq!(lines.count(), 4 * 3 * 3);
}

#[test]
fn bad_roughness_is_a_clear_error() {
    let base = ["thinfilm", "spectrum", "--stack", STACK];
    let run = |extra: &[&str], needle: &str| {
        let mut a = base.to_vec();
        a.extend(extra);
        assert_fails(&a, &[needle]);
    };
    run(&["--roughness", "0nm", "--correlation", "300nm"], "σ = 0 nm");
    run(&["--roughness=-5nm", "--correlation", "300nm"], "σ = -5 nm");
    run(&["--roughness", "25nm", "--correlation", "0nm"], "τ = 0 nm");
    run(&["--roughness", "25nm", "--correlation", "30nm"], "slope");
    run(&["--roughness", "100nm", "--correlation", "250nm"], "curvature");
    run(&["--roughness", "25nm"], "required"); // clap names --correlation on the next line
    run(&["--roughness", "25", "--correlation", "300nm"], "unit");
    run(&["--roughness", "25nm", "--correlation", "300nm", "--polarization", "s"], "unpolarised");
    // What the rough model would ignore is refused by the library (Python says the same), naming it.
    let rough = ["--roughness", "25nm", "--correlation", "300nm"];
    for (cmd, extra, needle) in [
        (
            "spectrum",
            &["--polarization", "s"][..],
            "--polarization s would be ignored: with a rough substrate the spectrum",
        ),
        ("color", &["--polarization", "p"], "--polarization p would be ignored: with a rough substrate the colours"),
        ("color", &["--visual", "bluetit"], "--visual bluetit takes a smooth film's spectra"),
        ("spectrum", &["--spectra", "never.csv"], "--spectra writes a smooth film's R and T"),
        ("spectrum", &["--light-angles", "0deg:10deg:5deg"], "--light-angles is for 'table'"),
        ("table", &["--light-angle", "10deg"], "--light-angle is for 'spectrum' and 'color'"),
        ("bench", &["--no-python"], "--no-python would be ignored: the rough bench"),
        ("bench", &["--light-angle", "30deg"], "--light-angle 30° would be ignored: the rough bench"),
    ] {
        let stack: &[&str] = if cmd == "bench" { &[] } else { &["--stack", STACK] };
        assert_fails(&[&["thinfilm", cmd][..], stack, &rough, extra].concat(), &[needle]);
    }
    assert!(!std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../never.csv")).exists());
    // The diffuse light's options without a rough substrate: refused (clap names --roughness on the next
    // lines), not ignored as before; so is the table's --scale without a --plot.
    for (cmd, extra) in [
        ("spectrum", ["--light-angle", "30deg"]),
        ("color", ["--azimuth", "90deg"]),
        ("chart", ["--d-iterations", "5"]),
        ("table", ["--diffuse-transport", "single"]),
        ("table", ["--light-angles", "0deg:10deg:5deg"]),
        ("table", ["--scale", "log"]),
    ] {
        let out = iridis(&[&["thinfilm", cmd, "--stack", STACK][..], &extra[..]].concat());
        let stderr = String::from_utf8_lossy(&out.stderr);
        let wanted = if extra[0] == "--scale" { "--plot" } else { "--roughness" };
        assert!(out.status.code() == Some(2) && stderr.contains("required") && stderr.contains(wanted), "{stderr}");
    }
}

fn xyz(v: &serde_json::Value) -> Vec<f64> {
    f(&v["XYZ"])
}

/// `thinfilm color --roughness 25nm --correlation 300nm` (Listing 3.6's σ and τ): the smooth film's colour,
/// the rough film's specular colour and its diffuse colour are reported separately; the specular part is
/// darker than the smooth film (light goes into the diffuse lobe), and the smooth part is exactly the colour
/// `thinfilm color` reports without roughness. Smooth and rough films answer with the same keys.
#[test]
fn color_reports_smooth_specular_and_diffuse() {
    let v =
        json_of(&["thinfilm", "color", "--stack", STACK, "--roughness", "25nm", "--correlation", "300nm", "--json"]);
    for part in ["reflected", "transmitted", "specular", "diffuse"] {
        for key in ["XYZ", "xyY", "Lab", "linear_srgb", "srgb", "hex"] {
            assert!(!v[part][key].is_null(), "{part}.{key} in {v}");
        }
    }
    assert_eq!((v["rough"]["roughness_nm"].as_f64(), v["rough"]["correlation_nm"].as_f64()), (Some(25.0), Some(300.0)));
    let plain = json_of(&["thinfilm", "color", "--stack", STACK, "--json"]);
    let keys = |v: &serde_json::Value| v.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
    assert_eq!(keys(&v), keys(&plain), "one shape for smooth and rough films");
    assert!(plain["rough"].is_null());
    assert_eq!(xyz(&v["reflected"]), xyz(&plain["reflected"]));
    assert_eq!(xyz(&v["transmitted"]), xyz(&plain["transmitted"]));
    // A smooth film reflects specularly only: its specular colour is its reflected colour, its diffuse black.
    assert_eq!(xyz(&plain["specular"]), xyz(&plain["reflected"]));
    assert_eq!(xyz(&plain["diffuse"]), [0.0; 3]);
    let (smooth, spec, diff) = (xyz(&v["reflected"]), xyz(&v["specular"]), xyz(&v["diffuse"]));
    for c in 0..3 {
        assert!(spec[c] > 0.0 && spec[c] < smooth[c], "{spec:?} vs {smooth:?}");
        assert!(diff[c] > 0.0, "{diff:?}");
    }
    // The text output names the three parts too.
    let out = iridis(&["thinfilm", "color", "--stack", STACK, "--roughness", "25nm", "--correlation", "300nm"]);
    let text = String::from_utf8_lossy(&out.stdout);
    for needle in ["smooth film, reflected", "rough film, specular", "rough film, diffuse"] {
        assert!(text.contains(needle), "{text}");
    }
}

/// σ → 0: the rough film's specular colour is the smooth colour (to 1e-9) and the diffuse colour vanishes.
#[test]
fn color_smooth_limit() {
    let v = json_of(&[
        "thinfilm",
        "color",
        "--stack",
        STACK,
        "--angle",
        "30deg",
        "--roughness",
        "0.000001nm",
        "--correlation",
        "300nm",
        "--json",
    ]);
    let smooth = json_of(&["thinfilm", "color", "--stack", STACK, "--angle", "30deg", "--json"]);
    let (a, b) = (xyz(&v["specular"]), xyz(&smooth["reflected"]));
    for c in 0..3 {
        assert!((a[c] - b[c]).abs() < 1e-9, "{a:?} vs {b:?}");
        assert!(xyz(&v["diffuse"])[c].abs() < 1e-12);
    }
    assert_eq!(v["specular"]["hex"], smooth["reflected"]["hex"]);
}

/// A bare rough substrate at normal incidence: HTSG's specular term is the smooth Fresnel reflectance times
/// exp(−(4πσ cos θ/λ)²) (He et al. 1991; the shadowing factor is 1 at normal incidence).
#[test]
fn bare_rough_specular_follows_the_roughness_factor() {
    let mut args = vec!["thinfilm", "spectrum", "--stack", "air | Si", "--json"];
    args.extend(GRID);
    args.extend(["--roughness", "25nm", "--correlation", "300nm"]);
    let v = json_of(&args);
    let (w, s, r) = (f(&v["wavelength_nm"]), f(&v["specular"]), f(&v["R_smooth"]));
    for i in 0..w.len() {
        let g = (4.0 * std::f64::consts::PI * 25.0 / w[i]).powi(2);
        assert!((s[i] / r[i] - (-g).exp()).abs() < 1e-12, "{} nm: {} vs {}", w[i], s[i] / r[i], (-g).exp());
    }
}

fn chart_csv(extra: &[&str], name: &str) -> Vec<Vec<String>> {
    let dir = common::tmp();
    let (png, csv) = (dir.path().join(format!("{name}.png")), dir.path().join(format!("{name}.csv")));
    let mut args = vec!["thinfilm", "chart", "--stack", "air | water {d} | Si"];
    if !extra.contains(&"--thickness") {
        args.extend(["--thickness", "0nm:600nm:20nm"]);
    }
    args.extend(["-o", png.to_str().unwrap(), "--csv", csv.to_str().unwrap()]);
    args.extend(extra);
    let out = iridis(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    std::fs::read_to_string(&csv).unwrap().lines().map(|l| l.split(',').map(str::to_string).collect()).collect()
}

/// `thinfilm chart --roughness σ --correlation τ`: the bands are the specular and the diffuse colour; as σ → 0
/// the specular band is the smooth chart's reflected band (to 1e-9) and the diffuse band is black. Single
/// scattering keeps the 31 × 81 evaluations fast (the multiple-scattering state costs ~10 ms per thickness and
/// wavelength; its limits are tested in crates/thinfilm/src/rough_multiple.rs, and one band of it below).
#[test]
fn chart_with_roughness_and_its_smooth_limit() {
    let one = ["--roughness", "25nm", "--correlation", "300nm", "--thickness", "300nm:320nm:20nm"];
    let multi = chart_csv(&one, "multiple");
    let single = chart_csv(&[&one[..], &["--diffuse-transport", "single"]].concat(), "single");
    assert_eq!(multi.len(), 1 + 2);
    for (m, s) in multi[1..].iter().zip(&single[1..]) {
        // The specular band does not depend on the transport; the diffuse band gains the light the film
        // turns back (silicon absorbs most of it: a few per cent).
        assert_eq!(m[1..5], s[1..5]);
        let (dm, ds): (f64, f64) = (m[7].parse().unwrap(), s[7].parse().unwrap());
        assert!(dm > 0.9 * ds && dm < 1.2 * ds, "diffuse Y {dm} vs single {ds}");
    }
    let rough = chart_csv(&["--roughness", "25nm", "--correlation", "300nm", "--diffuse-transport", "single"], "rough");
    assert_eq!(
        rough[0].join(","),
        "thickness_nm,S_X,S_Y,S_Z,S_hex,S_hex_exposure_RU,D_X,D_Y,D_Z,D_hex,D_hex_exposure_RU"
    );
    assert_eq!(rough.len(), 1 + 31);
    assert!(rough[1..].iter().all(|r| r[7].parse::<f64>().unwrap() > 0.01), "a rough film scatters");
    // The diffuse band's hex is at 1 RU (Y = 1 a white matte surface), said in every row.
    assert!(rough[1..].iter().all(|r| r[10] == "1"), "{:?}", rough[1]);
    let limit =
        chart_csv(&["--roughness", "0.000001nm", "--correlation", "300nm", "--diffuse-transport", "single"], "limit");
    let smooth = chart_csv(&[], "smooth");
    assert_eq!(
        smooth[0].join(","),
        "thickness_nm,R_X,R_Y,R_Z,R_hex,R_hex_exposure_RU,T_X,T_Y,T_Z,T_hex,T_hex_exposure_RU"
    );
    for (l, s) in limit[1..].iter().zip(&smooth[1..]) {
        assert_eq!(l[0], s[0]);
        for c in 1..4 {
            let (a, b): (f64, f64) = (l[c].parse().unwrap(), s[c].parse().unwrap());
            assert!((a - b).abs() < 1e-9, "d = {} nm: {a} vs smooth {b}", l[0]);
            assert!(l[c + 5].parse::<f64>().unwrap().abs() < 1e-12, "diffuse vanishes");
        }
    }
}

/// The README's film table is what the CLI prints: its commands (the code block above the table) are run with
/// `--json` and every row's hex colour and L\*a\*b\* (one decimal, as printed there) must match. Issue 32: the
/// rough diffuse row kept the old, twice-too-bright `#89bcfb` after the model changed.
#[test]
fn the_readmes_film_table_is_what_the_cli_prints() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md")).unwrap();
    let command = |tag: &str| -> Vec<String> {
        let line = readme
            .lines()
            .find(|l| l.starts_with("iridis thinfilm color") && l.trim_end().ends_with(tag))
            .unwrap_or_else(|| panic!("no README command tagged {tag}"));
        let cmd = line.split(" #").next().unwrap();
        let mut w = common::json_doc::split(cmd);
        w.remove(0);
        w.push("--json".into());
        w
    };
    let run = |tag: &str| {
        let w = command(tag);
        json_of(&w.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let (smooth, rough) = (run("# smooth"), run("# rough"));
    let rows = [
        ("smooth", &smooth["reflected"]),
        ("rough, specular part k_r", &rough["specular"]),
        ("rough, diffuse part π·k_d", &rough["diffuse"]),
    ];
    for (name, c) in rows {
        let row = readme
            .lines()
            .find(|l| l.starts_with(&format!("| {name} |")))
            .unwrap_or_else(|| panic!("no README row '{name}'"));
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let lab: Vec<f64> = c["Lab"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        let want_lab = lab.iter().map(|v| format!("{v:.1}").replace('-', "−")).collect::<Vec<_>>().join(", ");
        let want_hex = format!("`{}`", c["hex"].as_str().unwrap());
        assert_eq!((cells[2], cells[3]), (want_hex.as_str(), want_lab.as_str()), "README row '{name}'");
    }
}
