//! The `iridis color` commands as a user runs them: output keys, values, and errors on bad input.

use crate::common;
use common::{assert_fails, iridis, json_of};

/// `text` written to `name` in a scratch folder, which is removed when the returned guard is dropped.
fn temp_csv(name: &str, text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = common::tmp();
    let p = dir.path().join(name);
    std::fs::write(&p, text).unwrap();
    (dir, p)
}

#[test]
fn xyz_json_has_the_documented_keys_and_a_white_reflector_is_white() {
    let (_scratch, p) = temp_csv("white.csv", "wavelength_nm,value\n300,1\n900,1\n");
    let out = iridis(&["color", "xyz", p.to_str().unwrap(), "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in ["XYZ", "xyY", "Lab", "linear_srgb", "srgb", "hex"] {
        assert!(!v[key].is_null(), "missing {key}");
    }
    assert!((v["XYZ"][1].as_f64().unwrap() - 1.0).abs() < 1e-12);
    assert!((v["Lab"][0].as_f64().unwrap() - 100.0).abs() < 1e-9);
    // D65 white (CIE 1931, Y = 1) by colour-science: x, y = 0.31271, 0.32902.
    assert!((v["xyY"][0].as_f64().unwrap() - 0.31271).abs() < 5e-5);
    assert_eq!(v["hex"], "#ffffff");
    // What the colour rests on, as the text says it: the file's range and samples, light, observer, Y = 1.
    assert_eq!(v["wavelength_range_nm"], serde_json::json!([300.0, 900.0]));
    assert_eq!(
        (v["samples"].as_u64(), v["illuminant"].as_str(), v["observer"].as_str()),
        (Some(2), Some("D65"), Some("1931"))
    );
    assert!(v["normalisation"].as_str().unwrap().contains("perfect white diffuser has Y = 1"), "{v}");
}

#[test]
fn an_emissive_light_is_seen_against_the_illuminants_white() {
    let lab = |extra: &[&str]| {
        let mut args = vec!["color", "xyz", "data/cie/a.csv", "--emissive", "--json"];
        args.extend_from_slice(extra);
        let v = json_of(&args);
        [0, 1, 2].map(|k| v["Lab"][k].as_f64().unwrap())
    };
    // Illuminant A judged against its own white: the white point itself.
    let own = lab(&["--illuminant", "a"]);
    assert!((own[0] - 100.0).abs() < 1e-6 && own[1].abs() < 1e-6 && own[2].abs() < 1e-6, "{own:?}");
    // Against D65 (the default): CIELAB of A's published chromaticity (CIE 15:2004, x, y = 0.44757, 0.40745)
    // with D65's (0.31271, 0.32902) as the white, by the CIELAB formula (both Y = 1, so L* = 100).
    let xyz = |x: f64, y: f64| [x / y, 1.0, (1.0 - x - y) / y];
    let (a, w) = (xyz(0.44757, 0.40745), xyz(0.31271, 0.32902));
    let f = |t: f64| t.cbrt();
    let expected = [100.0, 500.0 * (f(a[0] / w[0]) - 1.0), 200.0 * (1.0 - f(a[2] / w[2]))];
    let d65 = lab(&[]);
    for k in 0..3 {
        assert!((d65[k] - expected[k]).abs() < 0.1, "{d65:?} against {expected:?}");
    }
}

#[test]
fn delta_e_of_sharma_pair_1() {
    let out = iridis(&["color", "delta-e", "50,2.6772,-79.7751", "50,0,-82.7485", "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!((v["delta_e"].as_f64().unwrap() - 2.0425).abs() < 1e-4);
    let out = iridis(&["color", "delta-e", "-5,3,4", "-5,0,0", "--formula", "1976"]);
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), "5.0000 ΔE*ab (CIE 1976)");
}

#[test]
fn bad_input_gives_one_clear_line() {
    assert_fails(&["color", "xyz", "no/such/file.csv"], &["no/such/file.csv", "cannot read"]);
    let (_scratch, p) = temp_csv("bad.csv", "wavelength,value\n400,0.1\n410,oops\n");
    assert_fails(&["color", "xyz", p.to_str().unwrap()], &["bad.csv:3", "oops"]);
    let (_scratch, p) = temp_csv("nan.csv", "400,0.1\n410,NaN\n");
    assert_fails(&["color", "xyz", p.to_str().unwrap()], &["nan.csv:2", "NaN"]);
    let (_scratch, p) = temp_csv("order.csv", "400,0.1\n390,0.2\n");
    assert_fails(&["color", "xyz", p.to_str().unwrap()], &["order.csv:2", "increase"]);
    let (_scratch, p) = temp_csv("ok.csv", "400,0.1\n700,0.2\n");
    assert_fails(&["color", "xyz", p.to_str().unwrap(), "--illuminant", "f11"], &["f11", "d65"]);
    assert_fails(&["color", "xyz", p.to_str().unwrap(), "--observer", "1999"], &["1999", "1931"]);
    assert_fails(&["color", "delta-e", "50,1", "50,0,0"], &["50,1", "L,a,b"]);
    assert_fails(&["color", "delta-e", "50,1,0", "50,0,0", "--formula", "94"], &["'94'", "2000", "1976"]);
    assert_fails(&["color", "delta-e", "50,x,1", "50,0,0"], &["'x'"]);
    // Only the first line that is not a comment may be a header; rows need exactly two columns.
    let (_scratch, p) = temp_csv("late_header.csv", "# c\n400,0.5\n410,0.6\nwavelength,value\n420,0.7\n");
    assert_fails(&["color", "xyz", p.to_str().unwrap()], &["late_header.csv:4", "'wavelength'"]);
    let (_scratch, p) = temp_csv("three.csv", "wavelength,value\n400,0.5\n410,0.6,0.9\n420,0.7\n");
    assert_fails(&["color", "xyz", p.to_str().unwrap()], &["three.csv:3", "two columns", "found 3"]);
}

/// Negative values are used and said; where they make Y negative, that L* is no lightness is said too (a
/// spectrum of −1 printed L* = −903.3 = 903.3·Y/Yn without a word).
#[test]
fn negative_values_are_said() {
    let warning = |text: &str| {
        let (_dir, csv) = temp_csv("s.csv", text);
        let out = iridis(&["color", "xyz", csv.to_str().unwrap()]);
        assert!(out.status.success());
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let w = warning("wl,r\n380,-1\n780,-1\n");
    assert!(w.contains("has negative values (down to -1)") && w.contains("Y is then -1.0000"), "{w}");
    let w = warning("wl,r\n380,0.2\n500,-0.01\n780,0.3\n");
    assert!(w.contains("has negative values (down to -0.01); they were used as they are\n"), "{w}");
    assert!(warning("wl,r\n380,0.2\n780,0.3\n").is_empty());
}

/// A reflectance in percent (a flat 50) read as a fraction was 5000 %: L* 411 and a white sRGB, without a word.
/// Now it warns, and `--percent` reads it as 0.5: a flat reflectance's Y is its value (Y = 1 a perfect white).
#[test]
fn a_reflectance_in_percent_is_said_and_read_with_percent() {
    let (_dir, csv) = temp_csv("pct.csv", "wl,r\n380,50\n780,50\n");
    let p = csv.to_str().unwrap();
    let out = iridis(&["color", "xyz", p]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && stderr.contains("reaches 50, read as a reflectance of 5000 %"), "{stderr}");
    assert!(stderr.contains("give --percent"), "{stderr}");
    let out = iridis(&["color", "xyz", p, "--percent", "--json"]);
    assert!(out.status.success() && out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!((v["XYZ"][1].as_f64().unwrap() - 0.5).abs() < 1e-12, "{v}");
    assert_fails(&["color", "xyz", p, "--percent", "--emissive"], &["--percent", "--emissive"]);
}
