//! The `iridis thinfilm` commands as a user runs them: documented keys, values checked against Sussenbach's
//! Figure 3.8, files written, and clean errors (exit code 2, one `error:` line naming the token) on bad input.

use crate::common;
use common::{assert_fails, iridis, json_of, ok, quoted, tmp, words, write_file};

#[test]
fn spectrum_json_matches_figure_3_8() {
    let out = iridis(&words(
        "thinfilm spectrum --stack 'air | water 635nm | air' --angle 1deg --from 400nm --to 690nm --step 10nm \
             --json",
    ));
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in ["wavelength_nm", "R", "T", "A", "Rs", "Rp", "Ts", "Tp"] {
        assert_eq!(v[key].as_array().map(Vec::len), Some(30), "{key}");
    }
    // Sussenbach Figure 3.8, first and last rows at 1°.
    assert!((v["R"][0].as_f64().unwrap() - 0.0334109).abs() < 1e-6);
    assert!((v["R"][29].as_f64().unwrap() - 0.0752091).abs() < 1e-6);
    assert!((v["T"][2].as_f64().unwrap() - 0.999626).abs() < 1e-6);
}

#[test]
fn table_csv_and_plots_are_written() {
    let scratch = tmp();
    let dir = scratch.path();
    let (csv, map) = (dir.join("t.csv"), dir.join("map.png"));
    let out = iridis(&words(&format!(
        "thinfilm table --stack 'air | water 635nm | air' --angles 1deg:90deg:1deg --from 400nm --to 690nm \
             --step 10nm -o {} --plot {}",
        quoted(&csv),
        quoted(&map)
    )));
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "angle_deg,wavelength_nm,R,T,A,Rs,Rp,Ts,Tp,psi_deg,delta_deg");
    assert_eq!(lines.len(), 1 + 90 * 30);
    // Row "2, 410" of Figure 3.8: R = 0.0109059.
    let row: Vec<f64> = lines[1 + 30 + 1].split(',').map(|x| x.parse().unwrap()).collect();
    assert_eq!((row[0], row[1]), (2.0, 410.0));
    assert!((row[2] - 0.0109059).abs() < 1e-6, "{row:?}");
    assert!(std::fs::read(&map).unwrap().starts_with(b"\x89PNG"));
    let spec = dir.join("oil.png");
    let out = iridis(&words(&format!(
        "thinfilm spectrum --stack 'air | gasoline 216nm | water 220nm | asphalt' --plot {} --csv",
        quoted(&spec)
    )));
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("wavelength_nm,R,T,A,Rs,Rp,Ts,Tp,psi_deg,delta_deg\n"));
    assert!(std::fs::read(&spec).unwrap().starts_with(b"\x89PNG"));
}

#[test]
fn color_json_keys_and_a_lossless_film_conserves_colour() {
    let out = iridis(&["thinfilm", "color", "--stack", "air | water 348nm | air", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for side in ["reflected", "transmitted"] {
        for key in ["XYZ", "Lab", "srgb", "hex"] {
            assert!(!v[side][key].is_null(), "{side}.{key}");
        }
    }
    // R + T = 1 at every wavelength, so reflected + transmitted XYZ is the illuminant's white (Y = 1).
    let y = v["reflected"]["XYZ"][1].as_f64().unwrap() + v["transmitted"]["XYZ"][1].as_f64().unwrap();
    assert!((y - 1.0).abs() < 1e-12, "{y}");
}

#[test]
fn chart_is_written() {
    let scratch = tmp();
    let dir = scratch.path();
    let png = dir.join("chart.png");
    let csv = dir.join("chart.csv");
    let out = iridis(&words(&format!(
        "thinfilm chart --stack 'air | water {{d}} | air' --thickness 0nm:1000nm:5nm -o {} --csv {}",
        quoted(&png),
        quoted(&csv)
    )));
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(text.lines().count(), 1 + 201);
    // A film of zero thickness reflects nothing: Y = 0 in the first row.
    let first: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
    assert_eq!(first[0], "0");
    assert!(first[2].parse::<f64>().unwrap().abs() < 1e-15);
    // The exposure each band's hex is shown at is in the file (the reflected band's is the chart's own, printed):
    // the same film's hex differed between two charts with nothing to say why.
    let printed = String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    let exposure: f64 = first[5].parse().unwrap();
    assert!(printed.contains(&format!("at exposure {exposure:.3} RU")), "{exposure}: {printed}");
    assert_eq!(first[10], "1");
}

#[test]
fn bad_input_names_the_token() {
    assert_fails(
        &["thinfilm", "spectrum", "--stack", "air | wter 635nm | air"],
        &["'wter'", "column 7", "unknown material"],
    );
    assert_fails(&["thinfilm", "spectrum", "--stack", "air | water | air"], &["no thickness", "column 7"]);
    assert_fails(&["thinfilm", "spectrum", "--stack", "air | water -3nm | air"], &["'-3nm'", "negative"]);
    assert_fails(
        &["thinfilm", "spectrum", "--stack", "air | water 300nm | air", "--angle", "-10deg"],
        &["incidence angle -10° is outside 0°–90°"],
    );
    assert_fails(
        &["thinfilm", "spectrum", "--stack", "air | water 3nm air"],
        &["no thickness", "missing '|'", "'3nm'"],
    );
    assert_fails(&["thinfilm", "spectrum", "--stack", "air | n=1.5-0.2i 10nm | air"], &["κ", "'n=1.5-0.2i'"]);
    // A lossless metal is written as the limit it is (it said only "n = 0 must be > 0").
    assert_fails(&["thinfilm", "spectrum", "--stack", "air | n=0+4.47i"], &["lossless metal", "n=0.001+4.47i"]);
    assert_fails(&["thinfilm", "spectrum", "--stack", "n=1.5+0.1i | water 10nm | air"], &["lossless", "column 1"]);
    assert_fails(
        &["thinfilm", "spectrum", "--stack", "air | Si 108nm | glass", "--to", "900nm"],
        &["layer 1 of 1: material 'si'", "830 nm", "206.6–826.6 nm", "no extrapolation"],
    );
    assert_fails(
        &["thinfilm", "color", "--stack", "air | water 100nm | rutile 50nm | glass"],
        &["layer 2 of 2: material 'rutile'", "430"],
    );
    assert_fails(
        &["thinfilm", "spectrum", "--stack", "Au | water 100nm | glass"],
        &["incident medium 'au' (gold, Johnson & Christy 1972", "built-in library", "absorbs", "lossless"],
    );
    assert_fails(&["thinfilm", "chart", "--stack", "air | water 5nm | air"], &["{d}"]);
    // A colour of one wavelength was black (XYZ 0, exit 0): refused, as a spectrum of one wavelength is not.
    let one = ["--from", "500nm", "--to", "500nm"];
    assert_fails(&[&["thinfilm", "color", "--stack", "air | water 300nm | air"][..], &one].concat(), &["only 500 nm"]);
    // A range's end is a sample: a step that does not divide it is refused (it stopped short of --to before).
    let (stack, steps) = ("air | water 300nm | air", "400–700 nm is not a whole number of 7 nm steps");
    let spectrum = ["thinfilm", "spectrum", "--stack", stack, "--from", "400nm", "--to", "700nm", "--step", "7nm"];
    assert_fails(&spectrum, &[steps, "the last wavelength would be 694 nm"]);
    assert_fails(&["thinfilm", "table", "--stack", stack, "--angles", "0deg:80deg:30deg"], &["--angles", "2.667"]);
    let scratch = tmp();
    let dir = scratch.path();
    let bad = dir.join("bad.yml");
    std::fs::write(&bad, "DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.5 0\n        0.5 oops 0\n")
        .unwrap();
    let stack = format!("air | file:{} 40nm | glass", bad.display());
    assert_fails(&["thinfilm", "spectrum", "--stack", &stack], &["line 5", "'oops'", "column 7"]);
    let gain = dir.join("gain.csv");
    std::fs::write(&gain, "wavelength_nm,n,k\n300,1.5,0\n900,1.5,-0.1\n").unwrap();
    let stack = format!("air | file:{} 40nm | glass", gain.display());
    assert_fails(&["thinfilm", "spectrum", "--stack", &stack], &["gain.csv, line 3", "κ = -0.1"]);
    let gain = dir.join("gain.yml");
    std::fs::write(&gain, "DATA:\n  - type: tabulated nk\n    data: |\n        0.3 1.5 0\n        0.9 1.5 -0.1\n")
        .unwrap();
    let stack = format!("air | file:{} 40nm | glass", gain.display());
    assert_fails(&["thinfilm", "spectrum", "--stack", &stack], &["gain.yml, line 5", "κ = -0.1"]);
}

#[test]
fn measured_files_are_read() {
    let out =
        iridis(&["thinfilm", "spectrum", "--stack", "air | file:data/materials/au_johnson.yml 40nm | glass", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let a: Vec<f64> = v["A"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert!(a.iter().all(|&x| x > 0.0 && x < 1.0), "a gold film absorbs");
}

/// Issue 3's example stack, exactly as written there, from the repository root: `data/gold.yml` is a link to
/// `data/materials/au_johnson.yml` (Johnson & Christy 1972), so it gives the built-in `Au` to the last digit.
#[test]
fn issue_example_gold_file_works() {
    let spectrum = |stack: &str| {
        let out = iridis(&["thinfilm", "spectrum", "--stack", stack, "--json"]);
        assert!(out.status.success(), "{stack}: {}", String::from_utf8_lossy(&out.stderr));
        let mut v = serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap();
        assert_eq!(v["inputs"]["stack"], stack);
        // The stacks are written differently (the inputs, and the stack as parsed: a file names its path).
        v.as_object_mut().unwrap().remove("inputs");
        v.as_object_mut().unwrap().remove("stack");
        v
    };
    let file = spectrum("air | file:data/gold.yml 40nm | glass");
    let builtin = spectrum("air | Au 40nm | glass");
    assert_eq!(file, builtin);
    // 40 nm of gold on glass: a partial mirror, reflecting red (700 nm) far more than blue (400 nm), which it
    // absorbs (gold's interband absorption below ~500 nm).
    let r = |nm: f64| {
        let i = file["wavelength_nm"].as_array().unwrap().iter().position(|w| w.as_f64() == Some(nm)).unwrap();
        (file["R"][i].as_f64().unwrap(), file["A"][i].as_f64().unwrap())
    };
    assert!(r(700.0).0 > 0.8 && r(400.0).0 < 0.5, "{:?} {:?}", r(400.0), r(700.0));
    assert!(r(400.0).1 > 0.4 && r(700.0).1 < 0.1, "{:?} {:?}", r(400.0), r(700.0));
}

/// `iridis … --json | head -c 10`: the reader closes the pipe after a few bytes; iridis must end cleanly
/// (exit 0, no panic message), not panic in `println!`. The output (~4000 wavelengths × 8 keys) is far larger
/// than a pipe's buffer, so the write is still under way when the pipe closes.
#[test]
fn closed_stdout_pipe_is_a_clean_exit() {
    use std::io::Read;
    use std::process::Stdio;
    for extra in [&["--json"][..], &["--csv"][..]] {
        let mut child = crate::common::command()
            .args(["thinfilm", "spectrum", "--stack", "air | water 348nm | air", "--step", "0.1nm"])
            .args(["--from", "380nm", "--to", "780nm"])
            .args(extra)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("cannot run iridis");
        let mut stdout = child.stdout.take().unwrap();
        let mut first = [0u8; 10];
        stdout.read_exact(&mut first).unwrap();
        drop(stdout); // what `head -c 10` does after 10 bytes
        let out = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{extra:?}: {stderr}");
        assert!(!stderr.contains("panicked") && !stderr.contains("error"), "{extra:?}: {stderr}");
    }
}

fn spectrum_at(stack: &str, angle: &str, nm: f64, pol: &str) -> serde_json::Value {
    let w = format!("{nm}nm");
    let out = iridis(&words(&format!(
        "thinfilm spectrum --stack '{stack}' --angle {angle} --from {w} --to {w} --polarization {pol} --json"
    )));
    assert!(out.status.success(), "{stack} {pol}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

fn first(v: &serde_json::Value, key: &str) -> f64 {
    v[key][0].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

/// `--polarization s|p`: R and T are the chosen polarisation's, equal to the Fresnel equations for a bare
/// interface (air → n = 1.5 at 60°, and Rp = 0 at Brewster's angle atan 1.5).
#[test]
fn polarization_s_and_p_follow_fresnel_at_a_bare_interface() {
    let (n, theta) = (1.5f64, 60f64.to_radians());
    let (ci, si) = (theta.cos(), theta.sin());
    let ct = (1.0 - (si / n).powi(2)).sqrt();
    let rs = ((ci - n * ct) / (ci + n * ct)).powi(2);
    let rp = ((n * ci - ct) / (n * ci + ct)).powi(2);
    for (pol, want) in [("s", rs), ("p", rp)] {
        let v = spectrum_at("air | n=1.5", "60deg", 500.0, pol);
        assert!((first(&v, "R") - want).abs() < 1e-12, "{pol}: {} vs Fresnel {want}", first(&v, "R"));
        assert!((first(&v, "T") - (1.0 - want)).abs() < 1e-12, "{pol}: lossless, T = 1 − R");
        assert_eq!(first(&v, "R"), first(&v, &format!("R{pol}")));
    }
    let brewster = format!("{}rad", 1.5f64.atan());
    let v = spectrum_at("air | n=1.5", &brewster, 500.0, "p");
    assert!(first(&v, "R") < 1e-20, "Rp at Brewster's angle: {}", first(&v, "R"));
    assert!(first(&spectrum_at("air | n=1.5", &brewster, 500.0, "s"), "R") > 0.1);
}

/// `--polarization s|p` on multilayer stacks: R and T against the `tmm` package (fixture from
/// tools/gen_thinfilm_fixtures.py), lossless and absorbing, at oblique incidence.
#[test]
fn polarization_s_and_p_agree_with_tmm() {
    let doc: serde_json::Value =
        serde_json::from_str(include_str!("../../thinfilm/tests/fixtures/tmm_reference.json")).unwrap();
    let cases: Vec<&serde_json::Value> = doc["cases"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["kind"] == "random" && c["angle_rad"].as_f64().unwrap() > 0.3)
        .filter(|c| c["layers"].as_u64().unwrap() <= 4 && c["absorbing_substrate"] == false)
        .take(4)
        .collect();
    assert_eq!(cases.len(), 4);
    for c in cases {
        let stack = c["stack"].as_str().unwrap();
        let angle = format!("{}rad", c["angle_rad"].as_f64().unwrap());
        let nm = c["wavelength_nm"].as_f64().unwrap();
        for pol in ["s", "p"] {
            let v = spectrum_at(stack, &angle, nm, pol);
            for key in ["R", "T"] {
                let want = c[pol][key].as_f64().unwrap();
                let got = first(&v, key);
                assert!((got - want).abs() < 1e-9, "{stack} at {angle}, {nm} nm, {pol}: {key} {got} vs tmm {want}");
            }
        }
    }
}

#[test]
fn incoherent_slide_and_psi_delta_in_spectrum() {
    // A bare 1 mm slide, incoherent: R = 2ρ/(1 + ρ) with ρ = 0.04 (n = 1.5) at normal incidence.
    let v = json_of(&words("thinfilm spectrum --stack 'air | inc:n=1.5 1mm | air' --from 500nm --to 520nm --json"));
    assert!((v["R"][0].as_f64().unwrap() - 0.08 / 1.04).abs() < 1e-12, "{}", v["R"][0]);
    // Through an incoherent layer Δ is undefined (null) and tan ψ = √(R_p/R_s): at normal incidence R_p = R_s.
    assert!(v["delta_deg"].is_null(), "no Δ for an incoherent stack");
    assert!((v["psi_deg"][0].as_f64().unwrap() - 45.0).abs() < 1e-12, "{}", v["psi_deg"]);
    // ψ/Δ of a bare n = 1.5 substrate at 60° (beyond Brewster: Δ = 180°), tan ψ = |r_p/r_s| from Fresnel.
    let v = json_of(&words("thinfilm spectrum --stack 'air | n=1.5' --angle 60deg --from 500nm --to 500nm --json"));
    let th = 60f64.to_radians();
    let ct = (1.0 - (th.sin() / 1.5).powi(2)).sqrt();
    let rs = (th.cos() - 1.5 * ct) / (th.cos() + 1.5 * ct);
    let rp = (1.5 * th.cos() - ct) / (1.5 * th.cos() + ct);
    assert!((v["psi_deg"][0].as_f64().unwrap() - (rp / rs).abs().atan().to_degrees()).abs() < 1e-10);
    assert!((v["delta_deg"][0].as_f64().unwrap().abs() - 180.0).abs() < 1e-10);
}

#[test]
fn aliasing_and_thick_layers_are_warned_about() {
    let out = iridis(&["thinfilm", "spectrum", "--stack", "air | water 20um | air", "--csv"]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("warning: layer 1 (water 20000 nm)") && err.contains("--step 1.3nm"), "{err}");
    let out = iridis(&["thinfilm", "color", "--stack", "air | MgF2 100nm | BK7 1mm | air"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("inc:bk7 1000000nm") && err.contains("coherence length"), "{err}");
    // Fine grids and incoherent slides say nothing.
    let out = iridis(&["thinfilm", "color", "--stack", "air | MgF2 100nm | inc:BK7 1mm | air"]);
    assert!(out.status.success() && out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn profile_balances_energy() {
    let v = json_of(&["thinfilm", "profile", "--stack", "air | Au 30nm | glass", "--wavelength", "500nm", "--json"]);
    let a: f64 = v["A_layers"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).sum();
    let (r, t) = (v["R"].as_f64().unwrap(), v["T"].as_f64().unwrap());
    assert!((r + t + a - 1.0).abs() < 1e-12 && a > 0.2, "R {r} T {t} A {a}");
    // Same R and T as the spectrum command.
    let s = json_of(&words("thinfilm spectrum --stack 'air | Au 30nm | glass' --from 500nm --to 500nm --json"));
    assert!((s["R"][0].as_f64().unwrap() - r).abs() < 1e-12 && (s["T"][0].as_f64().unwrap() - t).abs() < 1e-12);
    // The profile's absorbed density integrates to the layer's absorption (trapezoid, 2000 points).
    let v = json_of(&words("thinfilm profile --stack 'air | Au 30nm | glass' --wavelength 500nm --points 2301 --json"));
    let z: Vec<f64> = v["profile"]["z_nm"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    let d: Vec<f64> =
        v["profile"]["absorption_per_nm"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    let integral: f64 = (1..z.len()).map(|i| 0.5 * (d[i] + d[i - 1]) * (z[i] - z[i - 1])).sum();
    assert!((integral - a).abs() < 5e-3 * a, "∫ {integral} vs {a}");
    // Mixed stacks: a profile too; in the coherent Si film it integrates to the film's absorption.
    let v = json_of(&words(
        "thinfilm profile --stack 'air | Si 50nm | inc:n=1.5+0.0001i 2um | air' --wavelength 550nm \
             --points 22001 --json",
    ));
    assert!(v["balance"].as_f64().unwrap().abs() < 1e-12);
    let z: Vec<f64> = v["profile"]["z_nm"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    let d: Vec<f64> =
        v["profile"]["absorption_per_nm"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    let integral: f64 = (1..z.len())
        .filter(|&i| z[i] <= 50.0 && z[i - 1] >= 0.0)
        .map(|i| 0.5 * (d[i] + d[i - 1]) * (z[i] - z[i - 1]))
        .sum();
    let a_si = v["A_layers"][0].as_f64().unwrap();
    // A depth window: the films on a 1 mm slide, sampled every 20 nm from 20 nm above them.
    let v = json_of(&words(
        "thinfilm profile --stack 'air | TiO2 60nm | Si 50nm | inc:glass 1mm | air' --wavelength 550nm \
             --depth=-20nm:200nm --points 12 --json",
    ));
    let zs: Vec<f64> = v["profile"]["z_nm"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert_eq!((zs[0], zs[1], zs[11]), (-20.0, 0.0, 200.0));
    // In the lossless glass the flux is T; above the stack it is 1 − R.
    let flux = &v["profile"]["flux"];
    assert!((flux[11].as_f64().unwrap() - v["T"].as_f64().unwrap()).abs() < 1e-12);
    assert!((flux[0].as_f64().unwrap() - (1.0 - v["R"].as_f64().unwrap())).abs() < 1e-12);
    // Without --depth (the help's example) the window ends 100 nm into the slide and says so; the millimetre
    // spread the 400 samples 2.5 µm apart before, none in the films.
    let out = iridis(&words(
        "thinfilm profile --stack 'air | TiO2 60nm | Si 50nm | inc:glass 1mm | air' --wavelength 550nm --json",
    ));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("note: the depth window ends 100 nm into layer 3 (inc:glass 1000000 nm)"), "{err}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let z = v["profile"]["z_nm"].as_array().unwrap();
    assert_eq!((z[0].as_f64(), z[399].as_f64()), (Some(-100.0), Some(210.0)));
    assert_eq!(v["notes"].as_array().unwrap().len(), 1);
    assert_fails(
        &["thinfilm", "profile", "--stack", "air | TiO2 60nm | air", "--wavelength", "550nm", "--depth=200nm:20nm"],
        &["--depth 200 nm:20 nm is empty"],
    );
    // (to the grid's 0.1 nm resolution at the film's faces; the library tests integrate exactly)
    assert!((integral - a_si).abs() < 5e-3 * a_si, "∫ {integral} vs {a_si}");
    let scratch = tmp();
    let dir = scratch.path();
    let png = dir.join("profile.png");
    let out = iridis(&words(&format!(
        "thinfilm profile --stack 'air | Si 108nm | glass' --wavelength 450nm --plot {}",
        quoted(&png)
    )));
    assert!(out.status.success() && std::fs::metadata(&png).unwrap().len() > 1000);
}

#[test]
fn fit_recovers_the_scipy_optimum_and_refuses_bad_input() {
    let csv = concat!(env!("CARGO_MANIFEST_DIR"), "/../filmfit/tests/fixtures/scipy_fit.csv");
    let stack = "air | cauchy:{A=1.5:1.3..1.7},{B=0.004:0..0.02} {d=330nm:100nm..600nm} | n=3.88+0.02i";
    let v = json_of(&["thinfilm", "fit", csv, "--stack", stack, "--sigma", "0.002", "--json"]);
    // scipy least_squares on the same data (crates/filmfit/tests/fixtures/scipy_fit.json).
    let d = v["values"][2].as_f64().unwrap();
    assert!((d - 312.16741253638287).abs() < 1e-4, "{v}");
    assert!((v["sigma"][2].as_f64().unwrap() - 0.12091036442066286).abs() < 1e-6);
    assert_eq!(v["dof"], 398);
    assert_eq!(v["jacobian"], "exact");
    let scratch = tmp();
    let dir = scratch.path();
    let png = dir.join("fit.png");
    let out = iridis(&["thinfilm", "fit", csv, "--stack", stack, "--plot", png.to_str().unwrap()]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("correlation") && text.contains("χ²") && std::fs::metadata(&png).unwrap().len() > 1000,
        "{text}"
    );
    // Bad input: a clear message each.
    let t_only = dir.join("t_only.csv");
    std::fs::write(&t_only, "wavelength_nm,T\n400,0.9\n500,0.91\n").unwrap();
    assert_fails(
        &["thinfilm", "fit", t_only.to_str().unwrap(), "--stack", stack],
        &["no measured column 'R'", "line 1"],
    );
    assert_fails(&["thinfilm", "fit", csv, "--stack", "air | SiO2 {d1=100nm} | Si"], &["'d1' has no range"]);
    assert_fails(&["thinfilm", "fit", csv, "--stack", "air | SiO2 {d1=100nm:500nm..50nm} | Si"], &["is empty"]);
    assert_fails(
        &["thinfilm", "fit", csv, "--stack", "air | SiO2 {d1=100nm:-5nm..500nm} | Si"],
        &["cannot be negative"],
    );
    assert_fails(
        &["thinfilm", "fit", csv, "--stack", "inc:air | SiO2 {d1=100nm:5nm..500nm} | Si"],
        &["incident medium is semi-infinite"],
    );
    assert_fails(&["thinfilm", "fit", "/nonexistent.csv", "--stack", stack], &["cannot read /nonexistent.csv"]);
    assert_fails(&["thinfilm", "fit", csv, "--stack", stack, "--quantity", "X"], &["use R, T or psi-delta"]);
    assert_fails(&["thinfilm", "spectrum", "--stack", "inc:air | BK7 1mm | air"], &["semi-infinite", "column 1"]);
}

/// Issue 29: a spectrometer export (metadata lines, tab-separated, `Wavelength (nm)`, reflectance in percent,
/// 400–1000 nm) generated from 150 nm of SiO₂ on Green's silicon with 0.1 % noise.
#[test]
fn fit_reads_real_files_and_names_the_material_that_does_not_cover_them() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../python/tests/fixtures/measured_sio2_si.txt");
    let stack = "air | SiO2 {d=120nm:50nm..300nm} | si-green";
    let v = json_of(&["thinfilm", "fit", file, "--stack", stack, "--sigma", "0.1", "--json"]);
    let (d, s) = (v["values"][0].as_f64().unwrap(), v["sigma"][0].as_f64().unwrap());
    assert!((d - 150.0).abs() < 3.0 * s && s < 0.1, "{d} ± {s}");
    assert!((v["reduced_chi2"].as_f64().unwrap() - 1.0).abs() < 0.35, "{v}");
    assert_eq!(v["read"]["percent"], true);
    let notes: Vec<&str> = v["read"]["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap()).collect();
    assert_eq!(notes[0], "tab-separated, header on line 3, 2 line(s) before it skipped");
    assert!(notes.iter().any(|n| n.contains("percent (header 'Reflectance (%)')")), "{notes:?}");
    // Aspnes' silicon ends at 826.6 nm: the error names it, its range, a material that covers the file, and
    // the window that would fit; with that window the fit runs (and lands within 0.5 nm: another Si dataset).
    assert_fails(
        &["thinfilm", "fit", file, "--stack", "air | SiO2 {d=120nm:50nm..300nm} | Si"],
        &["substrate 'si' has data for 206.6–826.6 nm only", "si-green (250–1450 nm) covers it", "--to 826.6nm"],
    );
    let w = json_of(&words(&format!(
        "thinfilm fit '{file}' --stack 'air | SiO2 {{d=120nm:50nm..300nm}} | Si' --to 826nm --json"
    )));
    assert!(
        (w["values"][0].as_f64().unwrap() - 150.0).abs() < 0.5 && w["wavelength_nm"].as_array().unwrap().len() == 86
    );
    // The same numbers as a headerless comma file in fractions, columns chosen by number.
    let scratch = tmp();
    let dir = scratch.path();
    let plain = dir.join("plain.csv");
    let text = std::fs::read_to_string(file).unwrap();
    let rows: Vec<String> = text
        .lines()
        .skip(3)
        .map(|l| {
            let (a, b) = l.split_once('\t').unwrap();
            format!("{a},0,{}", b.parse::<f64>().unwrap() / 100.0)
        })
        .collect();
    std::fs::write(&plain, rows.join("\n")).unwrap();
    let p = plain.to_str().unwrap();
    let x = json_of(&["thinfilm", "fit", p, "--stack", stack, "--columns", "1,3", "--sigma", "0.001", "--json"]);
    assert!((x["values"][0].as_f64().unwrap() - d).abs() < 1e-6, "{x}");
    assert_eq!(x["read"]["percent"], false);
    assert_fails(&["thinfilm", "fit", p, "--stack", stack, "--columns", "1"], &["give 2 columns"]);
    assert_fails(&["thinfilm", "fit", p, "--stack", stack, "--from", "1200nm"], &["no wavelength of the file"]);
}

#[test]
fn fit_weights_are_inverse_variances() {
    // --weights w (w = 1/σ²) as a number, a column of the CSV and a separate file: the same fit as --sigma.
    let csv = concat!(env!("CARGO_MANIFEST_DIR"), "/../filmfit/tests/fixtures/scipy_fit.csv");
    let stack = "air | cauchy:{A=1.5:1.3..1.7},{B=0.004:0..0.02} {d=330nm:100nm..600nm} | n=3.88+0.02i";
    let fit = |extra: &[&str]| {
        let mut args = vec!["thinfilm", "fit", csv, "--stack", stack, "--grid", "1", "--json"];
        args.extend_from_slice(extra);
        json_of(&args)
    };
    let by_sigma = fit(&["--sigma", "0.002"]);
    let text = std::fs::read_to_string(csv).unwrap();
    let scratch = tmp();
    let dir = scratch.path();
    // The same data with a weight column (σ = 0.002 → w = 250000) and as a separate weights file.
    let mut with_w = String::new();
    let mut file_w = String::from("wavelength_nm,w\n");
    for line in text.lines() {
        if line.starts_with('#') || line.trim().is_empty() {
            with_w.push_str(line);
        } else if line.starts_with("wavelength") {
            with_w.push_str(&format!("{line},w"));
        } else {
            with_w.push_str(&format!("{line},250000"));
            file_w.push_str(&format!("{},250000\n", line.split(',').next().unwrap()));
        }
        with_w.push('\n');
    }
    let col_csv = dir.join("weighted.csv");
    std::fs::write(&col_csv, &with_w).unwrap();
    let w_file = dir.join("weights.csv");
    std::fs::write(&w_file, &file_w).unwrap();
    let mut args = vec!["thinfilm", "fit", col_csv.to_str().unwrap(), "--stack", stack, "--grid", "1", "--json"];
    args.extend(["--weights", "w"]);
    let by_column = json_of(&args);
    for v in [fit(&["--weights", "250000"]), by_column, fit(&["--weights", w_file.to_str().unwrap()])] {
        for k in 0..3 {
            let (a, b) = (v["values"][k].as_f64().unwrap(), by_sigma["values"][k].as_f64().unwrap());
            let (sa, sb) = (v["sigma"][k].as_f64().unwrap(), by_sigma["sigma"][k].as_f64().unwrap());
            assert!((a - b).abs() < 1e-6 * sb && (sa / sb - 1.0).abs() < 1e-9, "{v}");
        }
        assert!(v["sigma_given"].as_bool().unwrap());
        assert!((v["chi2"].as_f64().unwrap() - by_sigma["chi2"].as_f64().unwrap()).abs() < 1e-6);
    }
    // Bad weights: a clear message each.
    assert_fails(
        &["thinfilm", "fit", csv, "--stack", stack, "--weights", "0"],
        &["--weights 0", "must be a finite number > 0"],
    );
    assert_fails(
        &["thinfilm", "fit", csv, "--stack", stack, "--weights", "nocolumn"],
        &["--weights 'nocolumn' is neither a number, a column of", "nor a file"],
    );
    assert_fails(
        &["thinfilm", "fit", csv, "--stack", stack, "--weights", "1", "--sigma", "1"],
        &["cannot be used with"],
    );
    std::fs::write(&w_file, "wavelength_nm,w\n400,1\n").unwrap();
    assert_fails(
        &["thinfilm", "fit", csv, "--stack", stack, "--weights", w_file.to_str().unwrap()],
        &["1 rows of weights for 401 measured wavelengths"],
    );
    // ψ/Δ cannot be fitted through an incoherent layer: Δ is undefined there.
    let ell = dir.join("ellips.csv");
    std::fs::write(&ell, "wavelength_nm,psi,delta\n400,30,100\n500,31,101\n600,32,102\n").unwrap();
    assert_fails(
        &words(&format!(
            "thinfilm fit {} --stack 'air | n=2.1 {{d=150nm:50nm..400nm}} | inc:BK7 1mm | air' \
             --quantity psi-delta --angle 70deg",
            quoted(&ell)
        )),
        &["has no Δ", "incoherent"],
    );
    // ψ and Δ are angles: --percent would change nothing.
    assert_fails(
        &words(&format!(
            "thinfilm fit {} --stack 'air | n=2.1 {{d=150nm:50nm..400nm}} | Si' --quantity psi-delta --angle 70deg \
             --percent",
            quoted(&ell)
        )),
        &["--percent would be ignored", "angles in degrees"],
    );
}

/// A computed spectrum fitted without σ: χ²/dof is round-off (~1e-34), and the text and the JSON both say why the
/// uncertainties are nil (the JSON had only `sigma_given: false`; the text's note needed χ² exactly 0); a small χ²
/// prints in exponent form, not as 0.0000.
#[test]
fn an_exact_fit_says_why_its_uncertainties_are_zero() {
    let dir = tmp();
    let csv = dir.path().join("computed.csv");
    let s =
        json_of(&words("thinfilm spectrum --stack 'air | SiO2 150nm | Si' --from 400nm --to 700nm --step 10nm --json"));
    let rows: Vec<String> = s["wavelength_nm"]
        .as_array()
        .unwrap()
        .iter()
        .zip(s["R"].as_array().unwrap())
        .map(|(l, r)| format!("{},{}", l.as_f64().unwrap(), r.as_f64().unwrap()))
        .collect();
    std::fs::write(&csv, format!("wavelength_nm,R\n{}\n", rows.join("\n"))).unwrap();
    let args = ["thinfilm", "fit", csv.to_str().unwrap(), "--stack", "air | SiO2 {d=120nm:50nm..300nm} | Si"];
    let text = String::from_utf8_lossy(&common::succeeds(&args).stdout).into_owned();
    assert!(text.contains("note: the model meets the data to round-off (χ²/dof = "), "{text}");
    let v = json_of(&[&args[..], &["--json"]].concat());
    let notes: Vec<&str> = v["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap()).collect();
    assert!(notes.len() == 2 && notes[0].contains("estimated from the scatter"), "{notes:?}");
    // A constant offset of 3e-4 in R that no thickness removes: χ²/dof of order 1e-7, printed with its digits.
    let offset = dir.path().join("offset.csv");
    let shifted: Vec<String> = rows
        .iter()
        .map(|r| {
            let (l, x) = r.split_once(',').unwrap();
            format!("{l},{}", x.parse::<f64>().unwrap() + 3e-4)
        })
        .collect();
    std::fs::write(&offset, format!("wavelength_nm,R\n{}\n", shifted.join("\n"))).unwrap();
    let args = ["thinfilm", "fit", offset.to_str().unwrap(), "--stack", "air | SiO2 {d=120nm:50nm..300nm} | Si"];
    let text = String::from_utf8_lossy(&common::succeeds(&args).stdout).into_owned();
    let line = text.lines().find(|l| l.starts_with("χ² = ")).unwrap();
    let reduced = line.rsplit("χ²/dof = ").next().unwrap().trim_end_matches(')');
    assert!(reduced.contains("e-") && reduced.parse::<f64>().unwrap() > 0.0, "{line}");
}

/// Rows at one wavelength: nineteen at 500 nm cannot fix a thickness (a film's reflectance repeats with it, so
/// any of a family fits; "121.5 ± 4.8 nm" was printed), refused; a few repeats among many wavelengths are said.
#[test]
fn repeated_wavelengths_in_a_fit_are_said_or_refused() {
    let dir = tempfile::tempdir().unwrap();
    let one: String = (0..19).map(|i| format!("500,{}\n", 0.1 + 0.01 * i as f64)).collect();
    let one = write_file(dir.path(), "one.csv", &format!("wavelength_nm,R\n{one}"));
    let stack = "air | SiO2 {d1=100nm:50nm..500nm} | Si";
    assert_fails(
        &["thinfilm", "fit", &one, "--stack", stack],
        &["19 rows at 1 distinct wavelength cannot fix 1 fitted parameter"],
    );
    let rows: String = (40..70).map(|k| format!("{},0.2\n", 10 * k)).collect::<String>() + "500,0.21\n600,0.19\n";
    let some = write_file(dir.path(), "some.csv", &format!("wavelength_nm,R\n{rows}"));
    let out = ok(&["thinfilm", "fit", &some, "--stack", stack]);
    assert!(out.contains("warning: 2 of the 32 rows repeat a wavelength already read"), "{out}");
}

/// The built-in constants (water 1.33, glass 1.5, …) are visible-band figures: used at 100–120 nm they are warned
/// (water absorbs there; it was taken as 1.33 in silence), an index the user wrote (n=1.4) is not. A grid ending
/// under 20 nm is X-rays or µm by mistake: said, with the range in nm.
#[test]
fn a_constant_index_far_from_the_visible_is_warned() {
    let out = ok(&["thinfilm", "spectrum", "--stack", "air | water 348nm | air", "--from", "100nm", "--to", "120nm"]);
    assert!(
        out.contains("warning: water is a constant index (a visible-band figure), used here at 100–120 nm"),
        "{out}"
    );
    let out = ok(&words("thinfilm spectrum --stack 'air | n=1.38 100nm | glass' --from 0.4nm --to 0.7nm --step 0.1nm"));
    assert!(out.contains("warning: the wavelengths end at 0.7 nm: X-rays, and glass is a constant index"), "{out}");
    assert!(out.contains("if you meant µm, the range in nm is 400–700"), "{out}");
    let out = ok(&["thinfilm", "spectrum", "--stack", "air | n=1.4 348nm | air", "--from", "100nm", "--to", "120nm"]);
    assert!(!out.contains("constant index"), "{out}");
    let out = ok(&["thinfilm", "spectrum", "--stack", "air | water 348nm | air"]);
    assert!(!out.contains("constant index"), "{out}");
}
