//! What a new user trips over, each guarded: messages that say what is wrong (issue 20 items 2–4), and one
//! behaviour for one option across commands (item 11).

use crate::common;
use common::{assert_fails, iridis, json_of, quoted, words, ROUGH_FILM};

fn s(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn fresnel_gold_is_accepted_wherever_fresnel_is() {
    let dir = tempfile::tempdir().unwrap();
    let surf = "builtin:sine?size=4um&pixel=100nm";
    let png = dir.path().join("gold.png");
    for args in [
        vec!["brdf-map", surf, "--method", "reference", "--size", "8", "--fresnel", "gold", "-o", s(&png)],
        vec![
            "brdf",
            "eval",
            surf,
            "--method",
            "reference",
            "--light",
            "20deg",
            "--view",
            "20deg,180deg",
            "--fresnel",
            "gold",
        ],
        vec!["testbench", surf, "--from", "450nm", "--to", "650nm", "--step", "50nm", "--fresnel", "gold"],
    ] {
        let out = iridis(&args);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
    // One parser, one message: every command names the same choices.
    for cmd in [vec!["brdf-map", surf, "-o", s(&png)], vec!["testbench", surf]] {
        let mut args = cmd.clone();
        args.extend(["--fresnel", "silver"]);
        assert_fails(&args, &["--fresnel 'silver'", "schlick[:N], index:N[+Ki], gold or stack:STACK"]);
    }
}

#[test]
fn generate_takes_pixel_size_like_every_other_command() {
    let dir = tempfile::tempdir().unwrap();
    for flag in ["--pixel-size", "--pixel"] {
        let out = dir.path().join(format!("x{flag}.npy"));
        let v = json_of(&["surface", "generate", "sine", "--size", "2um", flag, "50nm", "-o", s(&out), "--json"]);
        // 2 µm at 50 nm per pixel: 40 × 40 samples.
        assert_eq!((v["rows"].as_u64(), v["cols"].as_u64()), (Some(40), Some(40)), "{flag}: {v}");
    }
    let help = String::from_utf8(iridis(&["surface", "generate", "--help"]).stdout).unwrap();
    assert!(help.contains("--pixel-size <PIXEL>") && !help.contains("--pixel <"), "{help}");
}

#[test]
fn messages_name_the_real_mistake() {
    // A trailing '|' is not "layer 2 has no thickness".
    assert_fails(&["thinfilm", "color", "--stack", "air | water 348nm | air |"], &["trailing '|' with no substrate"]);
    // A built-in's query string and a flag that disagree are refused, naming both.
    assert_fails(&["surface", "info", "builtin:sine?size=5um", "--size", "8um"], &["size 5um", "--size says 8um"]);
    // Over-size built-ins: a larger pixel or a smaller patch, not "crop or resample".
    let out = iridis(&["surface", "info", "builtin:sine?size=2mm"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("use a larger pixel or a smaller size") && !err.contains("crop"), "{err}");
    // nan is not a length, and 'nannm' is no suggestion.
    let out = iridis(&["surface", "info", "builtin:sine?size=nan"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && !err.contains("nannm") && err.contains("finite"), "{err}");
    // Grammar and the example of the right quantity.
    assert_fails(&["thinfilm", "color", "--stack", "air | water 348nm | air", "--angle", "30"], &["write an angle"]);
    assert_fails(
        &["thinfilm", "table", "--stack", "air | water 348nm | air", "--angles", "0deg:80deg"],
        &["e.g. 0deg:80deg:1deg"],
    );
}

#[test]
fn surface_notes_and_angles_read_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let v = json_of(&["surface", "info", "builtin:sine?size=6.4um&pixel=50nm&angle=30deg", "--json"]);
    let notes = v["notes"].to_string();
    // (No seed: a sine grating has no randomness, and the line reads back as a query string that would refuse
    // one.)
    assert!(notes.contains("\"sine period=1100nm depth=100nm size=6.4um pixel=50nm angle=30deg\""), "{notes}");
    // A Gwyddion file's extent, 128 × 50 nm = 6.4 µm, as its author wrote it (not 6.4000000000000006e-6).
    let gwy = dir.path().join("e.gwy");
    json_of(&["surface", "generate", "sine", "--size", "6.4um", "--pixel-size", "50nm", "-o", s(&gwy), "--json"]);
    let notes = json_of(&["surface", "info", s(&gwy), "--json"])["notes"].to_string();
    assert!(notes.contains("6.4e-6 × 6.4e-6 m") && !notes.contains("0000"), "{notes}");
    // Angles in JSON are the degrees typed, not their radian round trip.
    let v = json_of(&words(&format!("thinfilm color {ROUGH_FILM} --angle 30deg --json")));
    let r = &v["rough"];
    assert_eq!((r["light_deg"].as_f64(), r["view_deg"].as_f64()), (Some(30.0), Some(30.0)), "{v}");
}

#[test]
fn nk_csv_header_names_the_wavelength_unit() {
    let dir = tempfile::tempdir().unwrap();
    // A constant n = 1.5 table in µm; the film's colour must equal that of n=1.5 written inline.
    let csv = dir.path().join("film_um.csv");
    std::fs::write(&csv, "wavelength_um,n,k\n0.35,1.5,0\n0.85,1.5,0\n").unwrap();
    let spectrum = |film: &str| {
        json_of(&words(&format!("thinfilm spectrum --stack 'air | {film} 300nm | air' --from 400nm --to 700nm --json")))
    };
    let (from_file, inline) = (spectrum(&format!("file:{}", s(&csv))), spectrum("n=1.5"));
    let r = |v: &serde_json::Value| v["R"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect::<Vec<_>>();
    let (a, b) = (r(&from_file), r(&inline));
    assert_eq!(a.len(), b.len());
    assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12), "{a:?} vs {b:?}");
}

#[test]
fn ar_coating_table_map_is_not_black() {
    let dir = tempfile::tempdir().unwrap();
    let stack = "air | MgF2 100nm | BK7";
    // The share of near-black pixels (every channel < 40) of a map image.
    let dark = |scale: &str| {
        let png = dir.path().join(format!("ar_{scale}.png"));
        let csv = dir.path().join(format!("ar_{scale}.csv"));
        let out = iridis(&words(&format!(
            "thinfilm table --stack '{stack}' --angles 0deg:89deg:1deg --step 10nm --plot {} --scale {scale} -o {}",
            quoted(&png),
            quoted(&csv)
        )));
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let img = image::open(&png).unwrap().to_rgb8();
        let n = img.pixels().filter(|p| p.0.iter().all(|&c| c < 40)).count();
        n as f64 / (img.width() * img.height()) as f64
    };
    let (linear, auto, log) = (dark("linear"), dark("auto"), dark("log"));
    // R ≈ 1.3 % at normal incidence and ≈ 90 % at 89°: on a linear scale most of the map is black; auto
    // chooses the log scale, on which it is not.
    assert_eq!(auto, log);
    // A rough film's table draws its own map: --scale there is refused, not ignored (and without --plot
    // anywhere).
    let png = quoted(&dir.path().join("rough.png"));
    assert_fails(&words(&format!("thinfilm table {ROUGH_FILM} --scale log --plot {png}")), &["--scale"]);
    assert!(linear > 0.25 && log < 0.5 * linear, "dark share: linear {linear:.3}, log {log:.3}");
}
