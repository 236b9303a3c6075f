//! The virtual-lab commands (`testbench`, `compare`) as a user runs them, including their refusals.
//! Sizes are small so that each call takes about a second in release.

use crate::common;
use common::{assert_fails, iridis, json_of, ok, quoted, words};

/// Each first-order peak of a bench lit at 75° stands where m λ / d = sin θ_i − sin θ_r puts it, within `tol_deg`.
fn assert_peaks_follow_the_grating_equation(peaks: &[serde_json::Value], period_nm: f64, tol_deg: f64) {
    for p in peaks {
        let (lambda, angle) = (p["wavelength_nm"].as_f64().unwrap(), p["angle_deg"].as_f64().unwrap());
        let predicted = (75f64.to_radians().sin() - lambda / period_nm).asin().to_degrees();
        assert!((angle - predicted).abs() < tol_deg, "λ {lambda}: peak at {angle}°, grating equation {predicted}°");
    }
}

/// A 1500 nm sine grating: the bench must read the period back through the grating equation
/// m λ / d = sin θ_i − sin θ_r, and write its plot.
#[test]
fn testbench_reads_a_sine_grating_period() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("bench.png");
    let j = json_of(&words(&format!(
        "testbench builtin:sine?size=12um&pixel=50nm&period=1500nm --coherence 8um --from 450nm --to 650nm \
             --step 50nm --angle-step 0.1deg --plot {} --json",
        quoted(&plot)
    )));
    let mean = j["periodicity_nm"]["mean"].as_f64().unwrap();
    assert!((mean - 1500.0).abs() < 0.01 * 1500.0, "period {mean} nm");
    let peaks = j["peaks"].as_array().unwrap();
    assert_eq!(peaks.len(), 5, "{j}");
    assert_peaks_follow_the_grating_equation(peaks, 1500.0, 0.5);
    assert!(image::open(&plot).is_ok(), "plot is not a readable image");
}

/// The rigorous test bench (the averaged unit cell's orders carrying Maxwell's efficiencies) finds the sine's
/// period as the scalar bench does: both from the grating equation, which holds for any model of the orders.
#[test]
fn rigorous_testbench_reads_the_sine_period_as_the_scalar_one() {
    let bench = |method: &str| {
        // 65 nm pixels on the 1100 nm period: 220 phases, so every bin of the averaged profile is filled.
        let mut args = vec!["testbench", "builtin:sine?size=13um&pixel=65nm", "--method", method, "--coherence", "8um"];
        args.extend(["--from", "450nm", "--to", "650nm", "--step", "50nm", "--angle-step", "0.1deg", "--json"]);
        if method == "rigorous" {
            args.extend(["--unit-cell", "auto"]);
        }
        let out = common::succeeds(&args);
        (
            serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap(),
            String::from_utf8_lossy(&out.stderr).to_string(),
        )
    };
    let ((r, said), (k, _)) = (bench("rigorous"), bench("reference"));
    // The 1.1 µm cell is smaller than the 8 µm window on purpose: no "periods uncertain by ± d²/(2L)" (550 nm
    // here) beside the bench's own ± of the window's resolution.
    assert!(said.contains("the cell repeats as the periodic surface") && !said.contains("d²/(2L)"), "{said}");
    // The cell was built at the period read off the scan's spectrum: the bench reads it back, said so.
    assert!(said.contains("the bench reads that period back through Maxwell's orders"), "{said}");
    let (a, b) = (r["periodicity_nm"]["mean"].as_f64().unwrap(), k["periodicity_nm"]["mean"].as_f64().unwrap());
    assert!((a - 1100.0).abs() < 0.01 * 1100.0 && (a - b).abs() < 0.01 * 1100.0, "rigorous {a} nm, scalar {b} nm");
    assert_eq!(r["peaks"].as_array().unwrap().len(), 5, "{r}");
    assert_eq!(r["method"], "rigorous");
    assert!(r["rigorous"]["unit_cell"].as_str().unwrap().contains("averaged"), "{}", r["rigorous"]);
    assert!(k["rigorous"].is_null());
}

/// `compare` reports every method at every exposure, and the reference sits far closer to the ground truth
/// than Stam's Gaussian model on a snake-like surface (the paper's Table 2 ordering).
#[test]
fn compare_orders_methods_as_the_paper_does() {
    let j = json_of(&words(
        "compare builtin:elaphe?size=6um&pixel=60nm --methods reference,stam-gaussian --exposures 1,1000 \
             --coherence 2um --size 16 --json",
    ));
    let rows = j["results"].as_array().unwrap_or_else(|| panic!("no results: {j}"));
    assert_eq!(rows.len(), 4, "{j}");
    let mean = |method: &str, ru: f64| {
        rows.iter()
            .find(|r| r["method"] == method && r["exposure_ru"].as_f64() == Some(ru))
            .and_then(|r| r["mean"].as_f64())
            .unwrap_or_else(|| panic!("no {method} at {ru} RU: {j}"))
    };
    assert!(mean("reference", 1000.0) < 0.5, "{j}");
    assert!(mean("stam-gaussian", 1000.0) > 5.0 * mean("reference", 1000.0), "{j}");
    // The text states the colours' light and observer and what its ratio column divides by.
    let out = common::succeeds(&words(
        "compare builtin:elaphe?size=6um&pixel=60nm --methods reference,stam-gaussian --exposures 1 \
             --coherence 2um --size 16",
    ));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("coherence 2.0 µm, D65, CIE 1931 observer, Δλ 5 nm):"), "{text}");
    assert!(text.contains("ratio: a row's mean over the first method's (reference) at the same exposure"), "{text}");
}

#[test]
fn lab_commands_refuse_bad_input_clearly() {
    assert_fails(&["testbench", "builtin:blazed", "--method", "lookup"], &["no spectral reflectance"]);
    assert_fails(&["testbench", "builtin:blazed", "--method", "magic"], &["magic"]);
    assert_fails(&["testbench", "builtin:blazed", "--incidence", "75"], &["unit"]);
    // Along its grooves the blazed grating has no period: the bench read a "definite" 500–6517 nm from peaks of
    // 1e-34 (round-off of cancelling sums). Nothing above 1e-12 of the mirror is light.
    assert_fails(
        &["testbench", "builtin:blazed?size=10um&pixel=100nm", "--coherence", "10um", "--azimuth", "90deg"],
        &["no light on the side of order 1", "no period along azimuth 90.0°"],
    );
    assert_fails(&["testbench", "/no/such/scan.gwy"], &["/no/such/scan.gwy"]);
    assert_fails(&["compare", "builtin:blazed", "--methods", "lookup", "--exposures", "bright"], &["bright"]);
}

/// An option no method of the command reads is refused, naming the methods that would read it: `--terms` (the
/// ground truths and Stam's models use no Taylor terms), `--epsilon` (Stam's periodic models only), in the
/// laser experiment `--coherence` (its window is the diaphragm's `--aperture`), brdf-map's `--f32` (the
/// lookup sum on the CPU) with another method or `--gpu`, grating's `--normalisation` (the scalar model's)
/// with the rigorous method and `--acceptance` without a `--detector`, precompute's `--conserve-energy` (a
/// table integrates over λ in advance), vision's `--illuminant-units` with a built-in light and bench grating's
/// `--python`/`--peer-seconds` with `--no-python`. They changed nothing before.
#[test]
fn options_no_method_reads_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("x.png");
    let (s, o) = ("builtin:sine?size=4um&pixel=100nm", png.to_str().unwrap());
    let terms_users = "(reference, lookup, nmm, pq and rigorous do)";
    let cases: [(&[&str], &[&str]); 16] = [
        (&["testbench", s, "--method", "ground-truth", "--terms", "3"], &["--terms 3", "ground-truth", terms_users]),
        (&["testbench", s, "--method", "rigorous", "--epsilon", "0.1"], &["--epsilon 0.1", "rigorous method has"]),
        (
            &["compare", s, "--methods", "ground-truth,stam-gaussian", "--terms", "3"],
            &["--terms 3", "methods ground-truth, stam-gaussian use no", terms_users],
        ),
        (
            &["compare", s, "--methods", "reference,nmm", "--epsilon", "0.05"],
            &["--epsilon", "stam-periodic-triangular"],
        ),
        (
            &[
                "sweep",
                s,
                "--method",
                "stam-gaussian",
                "--param",
                "coherence",
                "--values",
                "2um",
                "--terms",
                "4",
                "-o",
                o,
            ],
            &["--terms 4", "stam-gaussian"],
        ),
        (&["experiment", "laser", s, "--method", "stam-gaussian", "--epsilon", "0.2", "-o", o], &["--epsilon 0.2"]),
        (&["experiment", "laser", s, "--coherence", "5um", "-o", o], &["--coherence 5um", "--aperture 5um"]),
        (
            &["brdf-map", s, "--method", "stam-periodic", "--terms", "4", "-o", o],
            &["--terms 4", "stam-periodic method"],
        ),
        (&["brdf-map", s, "--method", "reference", "--f32", "-o", o], &["--f32 would be ignored", "reference method"]),
        (&["brdf-map", s, "--method", "lookup", "--gpu", "--f32", "-o", o], &["--gpu evaluates in f32 already"]),
        (&["grating", s, "--method", "rigorous", "--normalisation", "energy"], &["--normalisation energy", "Maxwell"]),
        (&["precompute", s, "--conserve-energy", "-o", o], &["--conserve-energy would be ignored"]),
        (&["brdf", "vision", s, "--visual", "bluetit", "--views", "-20,20deg,20"], &["--views lists 20 twice"]),
        (&["brdf", "vision", s, "--visual", "bluetit", "--dlambda", "7nm"], &["--step", "whole number of 7 nm steps"]),
        (&["bench", "grating", "--quick", "--no-python", "--peer-seconds", "3"], &["--no-python", "--peer-seconds"]),
        (
            &[
                "vision",
                "../../data/examples/vision_spectra.csv",
                "--visual",
                "bluetit",
                "--illuminant-units",
                "energy",
            ],
            &["--illuminant-units would be ignored", "d65 is a built-in light"],
        ),
    ];
    for (args, words) in cases {
        assert_fails(args, words);
    }
    // clap's own message names the missing option on the line after `error:`.
    let out = iridis(&["grating", s, "--acceptance", "5deg"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && stderr.contains("required") && stderr.contains("--detector"), "{stderr}");
    let steps = ["grating", s, "--from", "380nm", "--to", "780nm", "--step", "500nm"];
    assert_fails(&steps, &["380–780 nm is not a whole number of 500 nm steps", "would be 380 nm"]);
    // A spectrum's step without the spectrum (one wavelength, 550 nm) would change nothing.
    let out = iridis(&["grating", s, "--step", "5nm"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && stderr.contains("required") && stderr.contains("--from"), "{stderr}");
    assert!(std::fs::read_dir(dir.path()).unwrap().count() == 0, "a refused run left a file");
}

/// A float64 `.npy` as written by `brdf-map --raw` ([size, size, 3], C order): the values after the header.
fn read_npy_f64(path: &std::path::Path) -> Vec<f64> {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..6], b"\x93NUMPY", "not a .npy file");
    let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = String::from_utf8_lossy(&bytes[10..10 + header_len]);
    assert!(header.contains("<f8"), "{header}");
    bytes[10 + header_len..].chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
}

/// `brdf-map` takes the lab's methods too (issue 6: every command takes every method). On a 1500 nm sine
/// grating lit at normal incidence, each method's brightest direction away from the mirror lobe must lie on
/// the grating's first order, sin θ_r = λ/d for λ in 380–780 nm (|x| ∈ [0.25, 0.52], y ≈ 0), and the map must
/// appear on both sides at the same |x|.
#[test]
fn brdf_map_draws_every_lab_method_where_the_grating_equation_says() {
    let dir = tempfile::tempdir().unwrap();
    // An odd size puts a row of pixels on y = 0 exactly: Stam's periodic model with its ε selection draws a 1-D
    // grating's orders as points on that line only.
    let size = 65usize;
    for method in ["nmm", "pq", "stam-periodic", "stam-periodic-triangular", "stam-gaussian"] {
        let png = dir.path().join(format!("{method}.png"));
        let raw = dir.path().join(format!("{method}.npy"));
        let out = common::iridis(&words(&format!(
            "brdf-map builtin:sine?size=6um&pixel=50nm&period=1500nm --method {method} --coherence 3um \
                 --size 65 -o {} --raw {}",
            quoted(&png),
            quoted(&raw)
        )));
        assert!(out.status.success(), "{method}: {}", String::from_utf8_lossy(&out.stderr));
        assert!(String::from_utf8_lossy(&out.stdout).contains(&format!("{method} map")), "{method}");
        assert!(image::open(&png).is_ok(), "{method}: PNG is not a readable image");
        let xyz = read_npy_f64(&raw);
        assert_eq!(xyz.len(), size * size * 3, "{method}");
        let coord = |i: usize| (2 * i + 1) as f64 / size as f64 - 1.0;
        let lum = |row: usize, col: usize| xyz[(row * size + col) * 3 + 1];
        // Brightest pixel outside the mirror lobe (|(x, y)| > 0.22; the lobe's tail there is ≲ 3 % of the order),
        // on each side: a sine has equal +1 and −1 orders (Jacobi–Anger: |J₋₁| = |J₁|), so both sides must have
        // one at the same |x| (within two pixels: the short window lets the orders' tails interfere).
        let brightest = |sign: f64| {
            let (mut best, mut at) = (f64::NEG_INFINITY, (0, 0));
            for row in 0..size {
                for col in 0..size {
                    let (x, y) = (coord(col), coord(row));
                    if x * sign > 0.0 && x * x + y * y > 0.22 * 0.22 && lum(row, col) > best {
                        (best, at) = (lum(row, col), (row, col));
                    }
                }
            }
            (best, coord(at.1), coord(at.0))
        };
        let sides = [brightest(1.0), brightest(-1.0)];
        for (y_max, x, y) in sides {
            assert!(y_max > 0.0, "{method}: empty map");
            assert!(y.abs() < 0.1 && (0.2..0.57).contains(&x.abs()), "{method}: brightest at ({x:.3}, {y:.3})");
        }
        assert!(
            (sides[0].1 + sides[1].1).abs() <= 4.0 / size as f64 + 1e-9,
            "{method}: first orders at x = {:.3} and {:.3}",
            sides[0].1,
            sides[1].1
        );
    }
}

/// A method that cannot make a map of a surface says why; a table cannot feed the lab's methods.
#[test]
fn brdf_map_refuses_lab_methods_it_cannot_serve() {
    let dir = tempfile::tempdir().unwrap();
    let flat = dir.path().join("flat.txt");
    std::fs::write(&flat, (0..16).map(|_| vec!["0"; 16].join(" ") + "\n").collect::<String>()).unwrap();
    std::fs::write(dir.path().join("flat.txt.json"), r#"{"pixel_size_nm": 50, "height_unit": "nm"}"#).unwrap();
    let png = dir.path().join("x.png");
    let (f, o) = (flat.to_str().unwrap(), png.to_str().unwrap());
    assert_fails(&["brdf-map", f, "--method", "nmm", "--coherence", "1um", "-o", o], &["nmm", "grating period"]);
    assert_fails(&["brdf-map", f, "--method", "stam-periodic", "--coherence", "1um", "-o", o], &["period along x"]);
    assert_fails(&["brdf-map", "builtin:sine", "--method", "pq", "--terms", "0", "-o", o], &["--terms"]);
    // A real table (recognised by content): the lab's methods need the height field behind it.
    let table = dir.path().join("t.npz");
    let t = table.to_str().unwrap();
    let out = iridis(&["precompute", "builtin:sine?size=4um&pixel=100nm", "--uv-resolution", "31", "-o", t]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_fails(&["brdf-map", t, "--method", "stam-gaussian", "-o", o], &["needs the height field"]);
    assert_fails(&["brdf-map", "builtin:sine", "--method", "stam", "-o", o], &["unknown method 'stam'", "nmm"]);
    assert!(!png.exists(), "a refused map left a file behind");
}

/// Mean ΔE of a sweep's JSON point at one exposure.
fn sweep_mean(j: &serde_json::Value, value: f64, ru: f64) -> f64 {
    j["points"]
        .as_array()
        .unwrap_or_else(|| panic!("no points: {j}"))
        .iter()
        .find(|p| p["value"].as_f64() == Some(value))
        .and_then(|p| p["errors"].as_array()?.iter().find(|e| e["exposure_ru"].as_f64() == Some(ru)))
        .and_then(|e| e["mean"].as_f64())
        .unwrap_or_else(|| panic!("no point {value} at {ru} RU: {j}"))
}

/// `sweep --param coherence`: the ground truth is recomputed at each coherence length, and the reference is
/// the Taylor expansion of the same integral (remainder bound 1e-6), so its error stays bounded — far below one
/// just-noticeable difference — at every value (measured on this 6 µm blazed patch, 16² map: mean ΔE00 ≤ 0.004 at
/// 1 RU, ≤ 0.06 at 1000 RU; the 24² map gave the same, ≤ 0.004 and ≤ 0.07, for twice the ground truth's time).
#[test]
fn sweep_coherence_keeps_the_reference_on_the_ground_truth() {
    let dir = tempfile::tempdir().unwrap();
    let (sheet, plot) = (dir.path().join("c.png"), dir.path().join("c_err.png"));
    let out = common::succeeds(&words(&format!(
        "sweep builtin:blazed?size=6um&pixel=50nm --param coherence --values 1um,2um,3um --size 16 \
             --exposures 1,1000 -o {} --plot {} --json",
        quoted(&sheet),
        quoted(&plot)
    )));
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // The note states the swept values, not the paper's 65 µm default the sweep never used.
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("note: coherence swept over 1 µm, 2 µm, 3 µm (--values)") && !err.contains("65 µm"), "{err}");
    assert_eq!(j["param"], "coherence", "{j}");
    // What was held, resolved: the sweeps' 201² u-v grid, the default 5 nm step, N counted from `auto`.
    let held = &j["held"];
    assert_eq!((held["uv_resolution"].as_u64(), held["dlambda_nm"].as_f64()), (Some(201), Some(5.0)), "{held}");
    assert!(held["taylor_terms"].as_u64().is_some_and(|n| n >= 1) && held["illuminant"] == "D65", "{held}");
    assert_eq!(j["method"], "reference", "{j}");
    assert!(j["surface"].as_str().is_some_and(|s| s.contains("blazed")), "{j}");
    let points = j["points"].as_array().unwrap();
    assert_eq!(points.len(), 3, "{j}");
    for p in points {
        let errors = p["errors"].as_array().unwrap();
        assert_eq!(errors.len(), 2, "{p}");
        assert!(errors.iter().all(|e| e["p95"].as_f64().is_some_and(f64::is_finite)), "{p}");
    }
    for nm in [1000.0, 2000.0, 3000.0] {
        assert!(sweep_mean(&j, nm, 1.0) < 0.05, "coherence {nm} nm at 1 RU: {j}");
        assert!(sweep_mean(&j, nm, 1000.0) < 0.3, "coherence {nm} nm at 1000 RU: {j}");
    }
    for png in [&sheet, &plot] {
        assert!(image::open(png).is_ok(), "{} is not a readable image", png.display());
    }
}

/// `sweep --param uv-power` on a grating whose first orders sit near the u-v origin (4 µm period: |u| ≈ 0.1–0.2)
/// with peaks ~0.06 wide in u: a linear 51² grid (spacing 0.08) undersamples them, the non-linear grids
/// (`2 u_i^a`, spacing ≈ 0.04 there for a = 3) do not — the paper's reason for a = 5 (sec. 5, Figure 14).
/// Measured mean ΔE00 at 1 RU: 0.73 (a = 1), 0.10 (a = 3), 0.16 (a = 5).
#[test]
fn sweep_uv_power_non_linear_grid_beats_linear_near_the_origin() {
    let dir = tempfile::tempdir().unwrap();
    let sheet = dir.path().join("uv.png");
    let j = json_of(&words(&format!(
        "sweep builtin:sine?size=12um&pixel=100nm&period=4000nm --method lookup --param uv-power \
             --values 1,3,5 --coherence 6um --size 24 --uv-resolution 51 --exposures 1,1000 -o {} --json",
        quoted(&sheet)
    )));
    assert_eq!(j["param"], "uv-power", "{j}");
    assert_eq!(j["method"], "lookup", "{j}");
    let linear = sweep_mean(&j, 1.0, 1.0);
    for a in [3.0, 5.0] {
        assert!(sweep_mean(&j, a, 1.0) < linear / 3.0, "a = {a}: {j}");
        assert!(sweep_mean(&j, a, 1000.0) < sweep_mean(&j, 1.0, 1000.0), "a = {a}: {j}");
    }
    // The error plot defaults to the sheet's name with _error.
    assert!(image::open(&sheet).is_ok() && image::open(dir.path().join("uv_error.png")).is_ok());
}

#[test]
fn sweep_refuses_bad_input_clearly() {
    let s = "builtin:sine?size=6um&pixel=100nm";
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s.png");
    let o = out.to_str().unwrap();
    assert_fails(
        &["sweep", s, "--param", "uv-power", "--values", "1,3", "-o", o],
        &["no parameter 'uv-power'", "lookup"],
    );
    assert_fails(&["sweep", s, "--param", "coherence", "--values", "2um,abc", "-o", o], &["--values", "abc"]);
    assert_fails(&["sweep", s, "--param", "coherence", "--values", "2", "-o", o], &["no unit"]);
    assert_fails(&["sweep", s, "--param", "colour", "--values", "1", "-o", o], &["colour", "uv-power"]);
    assert_fails(&["sweep", s, "--method", "lookup", "--param", "uv-power", "--values", "0", "-o", o], &["uv-power"]);
    assert_fails(&["sweep", s, "--param", "coherence", "--values", ",", "-o", o], &["--values"]);
    // A u-v grid where no table is built from it would be ignored: refused, naming why.
    assert_fails(
        &["sweep", s, "--param", "terms", "--values", "2", "--uv-resolution", "51", "-o", o],
        &["--uv-resolution 51 would be ignored", "the reference method builds no lookup table"],
    );
    let swept = ["sweep", s, "--method", "lookup", "--param", "uv-resolution", "--values", "21,41"];
    assert_fails(&[&swept[..], &["--uv-resolution", "51", "-o", o]].concat(), &["the parameter swept"]);
    for (param, values, given) in [
        ("dlambda", "2nm,5nm", ["--dlambda", "10nm"]),
        ("coherence", "2um", ["--coherence", "3um"]),
        ("terms", "2", ["--terms", "4"]),
    ] {
        let args = ["sweep", s, "--param", param, "--values", values, given[0], given[1], "-o", o];
        assert_fails(&args, &[&format!("{} ", given[0]), "would be ignored", "the parameter swept"]);
    }
    assert!(!out.exists(), "a refused sweep left a file behind");
    let compare = ["compare", s, "--methods", "reference,stam-periodic", "--size", "8"];
    assert_fails(&[&compare[..], &["--uv-power", "2"]].concat(), &["--uv-power 2 would be ignored", "add lookup"]);
    assert_fails(&[&compare[..], &["--table", "t.npz"]].concat(), &["--table t.npz would be ignored"]);
    // A value named twice would repeat its work and its row; a method compared with itself reads 0 by
    // construction (and every ratio to it infinite).
    let twice = [("--methods", "reference,reference", "reference"), ("--exposures", "1,1RU", "1")];
    for (flag, values, v) in twice {
        assert_fails(&["compare", s, flag, values, "--size", "8"], &[&format!("{flag} lists {v} twice")]);
    }
    assert_fails(&["sweep", s, "--param", "terms", "--values", "2,3,2", "-o", o], &["--values lists 2 twice"]);
    assert_fails(&["experiment", "laser", s, "--exposures", "1,1", "-o", o], &["--exposures lists 1 twice"]);
    assert_fails(
        &["compare", s, "--methods", "lookup,reference", "--against", "reference", "--size", "8"],
        &["reference would be compared with itself (it is --against)"],
    );
    assert_fails(
        &["compare", s, "--methods", "ground-truth-periodic,reference", "--size", "8"],
        &["ground-truth-periodic would be compared with itself", "with --against model"],
    );
    // A coherence window narrower than a pixel (σ_s = coherence/4 < 100 nm here): refused before any work,
    // a swept value too, whatever its place in the list.
    let short = ["a coherence length of 300 nm is shorter than this scan's 100 nm pixels", "at least 400 nm"];
    assert_fails(&["compare", s, "--coherence", "300nm", "--size", "8"], &short);
    assert_fails(&["sweep", s, "--param", "coherence", "--values", "2um,0.3um", "-o", o], &short);
    assert!(iridis(&["compare", s, "--methods", "reference", "--coherence", "400nm", "--size", "8"]).status.success());
    let laser = ["experiment", "laser", s, "--method", "reference", "--uv-resolution", "31", "-o", o];
    assert_fails(&laser, &["--uv-resolution 31 would be ignored", "reference method"]);
    // A grid out of range is refused before the Taylor terms (it was refused by the table's build, after them).
    for cmd in [&["precompute", s, "-o", o][..], &["brdf-map", s, "--method", "lookup", "-o", o]] {
        let stderr = String::from_utf8_lossy(&iridis(&[cmd, &["--uv-resolution", "2"]].concat()).stderr).to_string();
        assert!(stderr.starts_with("error: u-v resolution 2 must be between 3 and 4001"), "{cmd:?}: {stderr}");
    }
    let eval = ["brdf", "eval", s, "--light", "0deg", "--view", "10deg", "--uv-resolution", "31"];
    assert_fails(&eval, &["--uv-resolution 31 would be ignored", "reference method"]);
}

/// `experiment laser` with a tiny laser spectrum (a 530–535 nm band) on a 1000 nm sine grating, two
/// exposures. Gold's normal-incidence reflectance at 532.5 nm from Johnson & Christy's table (n, k interpolated
/// between 520.9 nm: 0.62 + 2.081i and 548.6 nm: 0.43 + 2.455i, so n = 0.540, k = 2.238) by Fresnel's
/// R = ((n − 1)² + k²)/((n + 1)² + k²) = 0.7073 must be the coated mirror's relative brightness, and the
/// brightest pixel must dim by about as much (gold's reflectance changes little with angle, paper Figure 9).
#[test]
fn experiment_laser_with_a_green_beam_on_gold() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("green.csv");
    std::fs::write(&csv, "wavelength_nm,power\n520,0\n529,0\n530,1\n535,1\n536,0\n545,0\n").unwrap();
    let run = |coating: &str, exposures: &str, name: &str| {
        let out = dir.path().join(name);
        let j = json_of(&words(&format!(
            "experiment laser builtin:sine?size=12um&pixel=50nm&period=1000nm --spectrum {} --aperture 6um \
                 --size 21 --subsamples 1 --dlambda 1nm --coating {coating} --exposures {exposures} -o {} --json",
            quoted(&csv),
            quoted(&out)
        )));
        for key in ["surface", "method", "images", "coating", "gold_mirror_relative_brightness", "max_y", "pixels"] {
            assert!(!j[key].is_null(), "no '{key}' in {j}");
        }
        assert_eq!(j["pixels"], 21, "{j}");
        // The beam behind the numbers: the paper's 45°, the aperture and the spectrum given.
        assert_eq!((j["incidence_deg"].as_f64(), j["aperture_um"].as_f64()), (Some(45.0), Some(6.0)), "{j}");
        assert!(j["beam_spectrum"].as_str().unwrap().contains("green.csv"), "{j}");
        j
    };
    let gold = run("gold", "1000,7500", "screen.png");
    let images: Vec<&str> = gold["images"].as_array().unwrap().iter().filter_map(|v| v.as_str()).collect();
    assert_eq!(images.len(), 2, "{gold}");
    for (img, ru) in images.iter().zip(["1000", "7500"]) {
        assert!(img.ends_with(&format!("screen_{ru}RU.png")), "{img}");
        assert!(image::open(img).is_ok(), "{img} is not a readable image");
    }
    let r_gold = {
        let (n, k) = (0.540f64, 2.238f64);
        ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k)
    };
    let scale = gold["gold_mirror_relative_brightness"].as_f64().unwrap();
    assert!((scale - r_gold).abs() < 0.005, "gold mirror {scale} vs Fresnel {r_gold:.4}");
    let bare = run("none", "1000", "bare.png");
    assert_eq!(bare["gold_mirror_relative_brightness"].as_f64(), Some(1.0), "{bare}");
    let dim = gold["max_y"].as_f64().unwrap() / bare["max_y"].as_f64().unwrap();
    assert!((dim - r_gold).abs() < 0.05 * r_gold, "brightest pixel dims by {dim:.4}, gold reflects {r_gold:.4}");
}

/// `--coating none` takes `--fresnel` (it was ignored: every Fresnel model gave the same screen). On a mirror (a
/// 0.1 nm sine), the spot at the screen's centre is lit at 45°, and the relative reflectance carries the Fresnel
/// factor against normal incidence: Schlick's `(R₀ + (1 − R₀)(1 − cos 45°)⁵)/R₀` = 1.0517 for n = 1.5 against a
/// near-perfect conductor's 1. With a coating, which is the Fresnel term, `--fresnel` is refused.
#[test]
fn experiment_laser_uncoated_takes_the_fresnel_model() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m.png");
    let o = out.to_str().unwrap();
    let s = "builtin:sine?size=4um&pixel=100nm&depth=0.1nm";
    let max_y = |fresnel: &str| {
        let j = json_of(&[
            "experiment",
            "laser",
            s,
            "--aperture",
            "4um",
            "--size",
            "11",
            "--subsamples",
            "1",
            "--coating",
            "none",
            "--fresnel",
            fresnel,
            "--exposures",
            "1000",
            "-o",
            o,
            "--json",
        ]);
        j["max_y"].as_f64().unwrap()
    };
    let r0 = 0.04f64;
    let schlick = (r0 + (1.0 - r0) * (1.0 - 0.5f64.sqrt()).powi(5)) / r0;
    let ratio = max_y("schlick:1.5") / max_y("index:0.0001+30i");
    assert!((ratio - schlick).abs() < 1e-3, "{ratio} against Schlick's {schlick}");
    assert_fails(
        &["experiment", "laser", s, "--fresnel", "schlick:3", "-o", o],
        &["--fresnel schlick:3", "--coating none"],
    );
}

#[test]
fn experiment_laser_refuses_bad_input_clearly() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s.png");
    let o = out.to_str().unwrap();
    let (bad, empty) = (dir.path().join("bad.csv"), dir.path().join("empty.csv"));
    std::fs::write(&bad, "wavelength_nm,power\n520,0\n530,abc\n").unwrap();
    std::fs::write(&empty, "wavelength_nm,power\n").unwrap();
    let s = "builtin:sine?size=6um&pixel=100nm";
    let missing = dir.path().join("no_such_laser.csv");
    let m = missing.to_str().unwrap();
    assert_fails(&["experiment", "laser", s, "--spectrum", m, "-o", o], &["no_such_laser.csv", "cannot read"]);
    assert_fails(&["experiment", "laser", s, "--spectrum", bad.to_str().unwrap(), "-o", o], &["bad.csv:3", "'abc'"]);
    assert_fails(&["experiment", "laser", s, "--spectrum", empty.to_str().unwrap(), "-o", o], &["at least two"]);
    assert_fails(&["experiment", "laser", s, "--coating", "no_such_nk.yml", "-o", o], &["--coating", "no_such_nk.yml"]);
    assert_fails(&["experiment", "laser", s, "--exposures", "1000,dim", "-o", o], &["dim"]);
    assert!(!out.exists() && std::fs::read_dir(dir.path()).unwrap().count() == 2, "a refused run left a file");
}

/// The paper's Table 1 setup on the built-in blazed grating (65 µm patch, 2500 nm period, θ_i = 75°, first
/// order, 380–780 nm in 5 nm steps): the bench must give 2500 ± 1 nm with a variance no larger than the
/// paper's 0.16 nm² (measured: 2500.81 nm, 0.0084 nm²), and every peak must sit on the grating equation
/// sin θ_r = sin 75° − λ / 2500 nm.
#[test]
fn testbench_measures_the_builtin_blazed_grating_at_2500nm() {
    let j = json_of(&["testbench", "builtin:blazed", "--json"]);
    assert_eq!(j["order"], 1, "{j}");
    assert_eq!(j["incidence_deg"].as_f64(), Some(75.0), "{j}");
    let (mean, variance) =
        (j["periodicity_nm"]["mean"].as_f64().unwrap(), j["periodicity_nm"]["variance"].as_f64().unwrap());
    assert!((mean - 2500.0).abs() <= 1.0, "period {mean} nm");
    assert!(variance <= 0.16, "variance {variance} nm²");
    let peaks = j["peaks"].as_array().unwrap();
    assert_eq!(peaks.len(), 81, "one peak per wavelength 380–780 nm: {j}");
    assert_peaks_follow_the_grating_equation(peaks, 2500.0, 0.02);
    for p in peaks {
        assert!((p["period_nm"].as_f64().unwrap() - 2500.0).abs() < 2.0, "{p}");
    }
}

/// Paper Figure 7(d) / Table 1: across the fingers Xenopeltis shows several ridges, sub-regions with slightly
/// different periods (605.89 and 536.13 nm in the paper). The built-in Xenopeltis is made of grains whose
/// across-finger spacing is 550 nm × (1 + 0.08 g), g a normal deviate clamped to ±2 (iridis-surface's
/// generator), so the bench across the fingers (azimuth 90°) must list more than one ridge, each at a distinct
/// period inside 462–638 nm. Measured on the default patch: 554.8, 600.9, 611.6 and 515.8 nm.
#[test]
fn testbench_finds_several_ridges_across_xenopeltis_fingers() {
    let j = json_of(&["testbench", "builtin:xenopeltis", "--azimuth", "90deg", "--json"]);
    let ridges: Vec<f64> = j["ridges"]
        .as_array()
        .unwrap_or_else(|| panic!("no ridges: {j}"))
        .iter()
        .map(|r| r["period_nm"].as_f64().unwrap())
        .collect();
    assert!(ridges.len() >= 2, "one ridge only: {j}");
    for (i, p) in ridges.iter().enumerate() {
        assert!((462.0..=638.0).contains(p), "ridge at {p} nm outside the generator's across-finger spacings: {j}");
        for q in &ridges[..i] {
            assert!((p - q).abs() > 0.015 * q, "ridges {q} and {p} nm are the same period: {j}");
        }
    }
}

/// The Elaphe-like built-in has fingers along x in rows 1100 nm apart along y. Across the fingers
/// (`--azimuth 90deg`, the bench measuring along y) it must give the row spacing, 1100 nm (the generator's
/// `spacing`; paper Table 1: 1144.28 nm for the real shed) with a definite period. Along the fingers
/// (`0deg`) there is no period — finger lengths are 4000 nm × U(0.5, 1.5) with random gaps, and the paper
/// (sec. 7) notes the fingers "do not exhibit any definite periodicity along the finger direction" — so the
/// bench must say so (measured: d_λ spreads by ≈ 8.5 % of its mean) instead of passing the mean off as one.
#[test]
fn testbench_on_elaphe_across_and_along_the_fingers() {
    let across = json_of(&["testbench", "builtin:elaphe", "--azimuth", "90deg", "--json"]);
    let p = &across["periodicity_nm"];
    assert!((p["mean"].as_f64().unwrap() - 1100.0).abs() < 0.01 * 1100.0, "{across}");
    assert_eq!(p["definite"], true, "{across}");
    let out = common::iridis(&["testbench", "builtin:elaphe", "--azimuth", "0deg", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let along: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let p = &along["periodicity_nm"];
    assert_eq!(p["definite"], false, "{along}");
    // Either the peaks spread (the thesis' measure), or they sit on one DFT spike of the finite patch while
    // other ridges are nearly as strong (with the Fresnel factor once, issue 14, the 2820 nm spike wins at every
    // λ: spread 0.12 %, but 1.26× the next ridge).
    let ridges = along["ridges"].as_array().unwrap();
    let dominance = if ridges.len() > 1 {
        ridges[0]["strength"].as_f64().unwrap() / ridges[1]["strength"].as_f64().unwrap()
    } else {
        f64::INFINITY
    };
    assert!(p["relative_spread"].as_f64().unwrap() > 0.01 || dominance < 1.5, "{along}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("no definite period"), "{stderr}");
}

/// `compare --maps DIR` writes, per exposure, the truth's map and each method's map and CIEDE2000 heat map,
/// all readable images (a map plot is larger than the map itself: axes and title around it).
#[test]
fn compare_writes_maps_and_delta_e_heat_maps() {
    let dir = tempfile::tempdir().unwrap();
    let maps = dir.path().join("maps");
    let j = json_of(&words(&format!(
        "compare builtin:elaphe?size=6um&pixel=60nm --methods reference,stam-gaussian --exposures 1,1000 \
             --coherence 2um --size 16 --maps {} --json",
        quoted(&maps)
    )));
    assert_eq!(j["results"].as_array().map(Vec::len), Some(4), "{j}");
    let mut expected = Vec::new();
    for ru in ["1", "1000"] {
        // Both ground truths: the periodic one the methods are compared with, the finite aperture for the
        // periodic-extension error.
        expected.push(format!("ground-truth_{ru}RU.png"));
        expected.push(format!("ground-truth-periodic_{ru}RU.png"));
        for m in ["reference", "stam-gaussian"] {
            expected.push(format!("{m}_{ru}RU.png"));
            expected.push(format!("{m}_{ru}RU_deltaE.png"));
        }
    }
    let mut found: Vec<String> =
        std::fs::read_dir(&maps).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    found.sort();
    expected.sort();
    assert_eq!(found, expected);
    for f in &expected {
        let img = image::open(maps.join(f)).unwrap_or_else(|e| panic!("{f} is not a readable image: {e}"));
        assert!(img.width() > 16 && img.height() > 16, "{f}: {}×{}", img.width(), img.height());
    }
}

/// Where the ground truth shows as clipped white on most of the map (a 400 nm window spreads the sine's light
/// over the hemisphere; at 1000 RU every pixel clips), `compare` says so, and a ratio to a first method whose
/// mean is 0 is left out (`—`, JSON null), never NaN or ∞.
#[test]
fn compare_says_when_the_truth_is_clipped_white_and_divides_by_no_zero() {
    let out = iridis(&words(
        "compare builtin:sine?size=6um&pixel=100nm --methods reference,stam-gaussian --coherence 400nm --size 8 \
         --exposures 1,1000 --json",
    ));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: at 1000 RU the ground-truth-periodic image shows as white (clipped) on"),
        "{stderr}"
    );
    assert!(!stderr.contains("at 1 RU the"), "{stderr}");
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = j["results"].as_array().unwrap();
    for r in rows {
        let e = r["exposure_ru"].as_f64().unwrap();
        let first = rows.iter().find(|f| f["exposure_ru"] == r["exposure_ru"]).unwrap()["mean"].as_f64().unwrap();
        match r["ratio"].as_f64() {
            Some(q) => assert!(first > 0.0 && (q - r["mean"].as_f64().unwrap() / first).abs() < 1e-12, "{r}"),
            None => assert!(first == 0.0 && e == 1000.0, "a ratio left out with a first mean of {first}: {r}"),
        }
    }
    assert!(rows.iter().any(|r| r["ratio"].is_null()), "{j}");
}

/// `compare` measures each method against the ground truth of its own model (the periodic extension) and
/// prints the periodic-extension error beside it. With the window twice as wide as the patch the two models
/// part by several ΔE00 — which the reference, an approximation of the periodic model, must not be charged
/// with: against its own ground truth it is within a small fraction of one ΔE00.
#[test]
fn compare_measures_each_method_against_its_own_model() {
    let base = ["compare", "builtin:blazed?size=6um&pixel=50nm", "--methods", "reference", "--exposures", "1000"];
    let args = |extra: &[&'static str]| -> Vec<&'static str> {
        let mut v: Vec<&str> = base.to_vec();
        v.extend_from_slice(&["--coherence", "12um", "--size", "16", "--json"]);
        v.extend_from_slice(extra);
        v
    };
    let j = json_of(&args(&[]));
    assert_eq!(j["against"], "model", "{j}");
    let row = &j["results"][0];
    assert_eq!(row["against"], "ground-truth-periodic", "{j}");
    let own = row["mean"].as_f64().unwrap();
    let ext = j["periodic_extension_error"][0]["mean"].as_f64().unwrap_or_else(|| panic!("no extension error: {j}"));
    assert!(own < 0.2, "reference vs its own model's ground truth: {own} ({j})");
    assert!(ext > 1.0, "periodic vs finite aperture with a window twice the patch: {ext} ({j})");
    // Against the finite aperture: the model mismatch shows up as the method's error.
    let f = json_of(&args(&["--against", "ground-truth"]));
    assert_eq!(f["results"][0]["against"], "ground-truth", "{f}");
    let finite = f["results"][0]["mean"].as_f64().unwrap();
    assert!(
        finite > 0.5 * ext && finite > 5.0 * own,
        "reference vs finite aperture {finite}, extension {ext}, own {own}"
    );
    assert_fails(&["compare", "builtin:blazed", "--against", "nothing"], &["--against", "nothing", "model"]);
}

/// A table from `precompute` is checked against everything `compare` would build it from; each mismatch is
/// refused, naming the field. The matching table is accepted.
#[test]
fn compare_refuses_a_table_that_does_not_match_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let t = dir.path().join("t.npz");
    let t = t.to_str().unwrap();
    let surface = "builtin:sine?size=4um&pixel=100nm&period=1000nm";
    let build = ["--coherence", "4um", "--step", "10nm", "--uv-resolution", "41"];
    let mut pre = vec!["precompute", surface, "-o", t];
    pre.extend_from_slice(&build);
    let out = common::iridis(&pre);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let run = |surface: &str, extra: &[&str]| -> Vec<String> {
        let mut v: Vec<String> =
            ["compare", surface, "--methods", "lookup", "--size", "8"].iter().map(|s| s.to_string()).collect();
        let mut opts: Vec<(&str, &str)> = vec![
            ("--table", t),
            ("--coherence", "4um"),
            ("--dlambda", "10nm"),
            ("--uv-resolution", "41"),
            ("--exposures", "1000"),
        ];
        for pair in extra.chunks(2) {
            opts.retain(|o| o.0 != pair[0]);
            opts.push((pair[0], pair[1]));
        }
        for (k, val) in opts {
            v.push(k.into());
            v.push(val.into());
        }
        v
    };
    let ok = run(surface, &[]);
    let ok: Vec<&str> = ok.iter().map(|s| s.as_str()).collect();
    let out = common::iridis(&ok);
    assert!(out.status.success(), "the matching table was refused: {}", String::from_utf8_lossy(&out.stderr));
    for (surf, extra, field) in [
        ("builtin:sine?size=4um&pixel=100nm&period=800nm", vec![], "surface fingerprint"),
        ("builtin:sine?size=5um&pixel=100nm&period=1000nm", vec![], "size"),
        ("builtin:sine?size=4um&pixel=80nm&period=1000nm", vec![], "pixel size"),
        (surface, vec!["--coherence", "5um"], "coherence"),
        (surface, vec!["--illuminant", "a"], "illuminant"),
        (surface, vec!["--dlambda", "5nm"], "wavelength step"),
        (surface, vec!["--terms", "3"], "Taylor terms"),
        (surface, vec!["--uv-resolution", "31"], "u-v grid"),
        (surface, vec!["--uv-power", "2"], "u-v grid"),
    ] {
        let args = run(surf, &extra);
        let args: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        assert_fails(&args, &[field, "t.npz", "iridis precompute"]);
    }
    // The observer: compare always uses CIE 1931, a table made for 1964 is refused.
    let t64 = dir.path().join("t64.npz");
    let mut pre = vec!["precompute", surface, "-o", t64.to_str().unwrap(), "--observer", "1964"];
    pre.extend_from_slice(&build);
    assert!(common::iridis(&pre).status.success());
    let args = run(surface, &["--table", t64.to_str().unwrap()]);
    let args: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
    assert_fails(&args, &["observer", "t64.npz"]);
}

/// `experiment laser --method lookup` builds its table for the beam and records the beam's spectrum (not
/// illuminant E): saved with --save-table it is accepted for the same beam, refused for another beam and a
/// D65 table from `precompute` is refused by its illuminant.
#[test]
fn laser_tables_record_the_beam_and_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let (green, red) = (dir.path().join("green.csv"), dir.path().join("red.csv"));
    std::fs::write(&green, "wavelength_nm,power\n520,0\n529,0\n530,1\n535,1\n536,0\n545,0\n").unwrap();
    std::fs::write(&red, "wavelength_nm,power\n620,0\n629,0\n630,1\n635,1\n636,0\n645,0\n").unwrap();
    let surface = "builtin:sine?size=4um&pixel=100nm&period=1000nm";
    let table = dir.path().join("laser.npz");
    let out = dir.path().join("s.png");
    let laser = |spectrum: &std::path::Path, extra: &[&str]| -> std::process::Output {
        let mut v = vec![
            "experiment",
            "laser",
            surface,
            "--method",
            "lookup",
            "--spectrum",
            spectrum.to_str().unwrap(),
            "--aperture",
            "4um",
            "--dlambda",
            "10nm",
            "--uv-resolution",
            "31",
            "--size",
            "9",
            "--subsamples",
            "1",
            "--exposures",
            "1000",
            "-o",
            out.to_str().unwrap(),
        ];
        v.extend_from_slice(extra);
        common::iridis(&v)
    };
    let r = laser(&green, &["--save-table", table.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(r.status.success(), "{err}");
    // The window is the diaphragm's: not "as given" (no --coherence was).
    assert!(err.contains("note: coherence 4 µm (the diaphragm's aperture, --aperture)"), "{err}");
    // The text names the method and coating behind its numbers (the JSON did, the text did not).
    assert!(String::from_utf8_lossy(&r.stdout).starts_with("lookup method, coating gold; beam at 45.0°"));
    let t = iridis_diffraction::table::LookupTable::load(&table).unwrap();
    assert_eq!(t.meta.illuminant, "light", "{:?}", t.meta);
    let light = t.meta.light_spectrum.as_ref().expect("the beam's spectrum is recorded");
    // The green band (times gold's reflectance) and nothing at 600 nm.
    let at = |l: f64| light[t.wavelengths_nm.iter().position(|&x| (x - l).abs() < 1e-9).unwrap()];
    assert!(at(530.0) > 0.5 && at(600.0) == 0.0, "{light:?}");
    let r = laser(&green, &["--table", table.to_str().unwrap()]);
    assert!(r.status.success(), "the same beam's table was refused: {}", String::from_utf8_lossy(&r.stderr));
    let mut args = vec!["experiment", "laser", surface, "--method", "lookup", "--spectrum", red.to_str().unwrap()];
    let tail =
        ["--aperture", "4um", "--dlambda", "10nm", "--uv-resolution", "31", "--size", "9", "--subsamples", "1", "-o"];
    args.extend_from_slice(&tail);
    args.extend_from_slice(&[out.to_str().unwrap(), "--table", table.to_str().unwrap()]);
    assert_fails(&args, &["light spectrum", "laser.npz"]);
    let d65 = dir.path().join("d65.npz");
    // A small D65 table (31² u-v nodes, not the default 501², as the beam's above): only its illuminant differs.
    let pre = [
        "precompute",
        surface,
        "-o",
        d65.to_str().unwrap(),
        "--coherence",
        "4um",
        "--step",
        "10nm",
        "--uv-resolution",
        "31",
    ];
    assert!(common::iridis(&pre).status.success());
    let mut args = vec!["experiment", "laser", surface, "--method", "lookup", "--spectrum", green.to_str().unwrap()];
    args.extend_from_slice(&tail);
    args.extend_from_slice(&[out.to_str().unwrap(), "--table", d65.to_str().unwrap()]);
    assert_fails(&args, &["illuminant", "d65.npz"]);
    assert_fails(
        &["experiment", "laser", surface, "--table", d65.to_str().unwrap(), "-o", out.to_str().unwrap()],
        &["--method lookup"],
    );
}

/// A patch smaller than the paper's 65 µm coherence: the coherence stays the light's (65 µm unless given,
/// said every time), the patch is the periodic model's unit cell (said once, no warning), and the test bench
/// states the period's uncertainty from the patch's extent along the measured direction, d²/(2L).
#[test]
fn a_small_patch_keeps_the_lights_coherence_and_is_a_unit_cell() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("m.png");
    let spec = "builtin:sine?size=6.4um&pixel=50nm&period=1000nm";
    // A small table (the default 501² is most of the time; the notes are what is tested).
    let out = iridis(&["brdf-map", spec, "--size", "8", "--uv-resolution", "31", "-o", map.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("coherence 65 µm (the paper's default") && err.contains("one unit cell of a periodic"),
        "{err}"
    );
    assert!(!err.contains("warning: patch"), "a unit cell is no warning: {err}");
    let out =
        iridis(&words(&format!("brdf-map {spec} --size 8 --uv-resolution 31 --coherence 3um -o {}", quoted(&map))));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && err.contains("coherence 3 µm (as given)") && !err.contains("unit cell"), "{err}");
    let j = json_of(&["testbench", spec, "--from", "450nm", "--to", "650nm", "--step", "50nm", "--json"]);
    assert_eq!(j["coherence_nm"].as_f64(), Some(65_000.0));
    assert_eq!(j["patch_extent_nm"].as_f64(), Some(6400.0));
    let (d, u) = (j["periodicity_nm"]["mean"].as_f64().unwrap(), j["periodicity_nm"]["uncertainty"].as_f64().unwrap());
    assert!((u - d * d / 12_800.0).abs() < 1e-9, "± {u} for {d}");
    // 6.4 periods in the cell: the orders sit at 6400/k nm; the sine's 1000 nm lies within the stated ±.
    assert!((d - 1000.0).abs() <= u, "{d} ± {u}");
}

/// Two maps black at every exposure agree to ΔE00 0 and say nothing: a 16² map of a 4 µm sine under the light's
/// 65 µm coherence (its lobes ~1e-3 wide in u, the pixels 0.125 apart) is said to be that, not left to read as
/// perfect agreement.
#[test]
fn black_maps_compared_are_said() {
    let compare = |extra: &[&str]| {
        let base = ["compare", "builtin:sine?size=4um&pixel=50nm", "--methods", "reference", "--size", "16"];
        ok(&[&base[..], &["--exposures", "1"], extra].concat())
    };
    let out = compare(&[]);
    assert!(
        out.contains("warning: reference and ground-truth-periodic are both black at every exposure on this 16² map"),
        "{out}"
    );
    // A window inside the patch widens the lobes over the pixels: nothing to say.
    let out = compare(&["--coherence", "1um"]);
    assert!(!out.contains("black at every exposure"), "{out}");
}

/// A viewing range of 2.2° (radians typed as degrees) holds one peak of unknown order: the bench read order 4 as
/// order 1 and called 625 nm "definite" for a 2500 nm grating. It says the range cannot tell its orders apart.
#[test]
fn a_narrow_viewing_range_is_said() {
    let out = ok(&[
        "testbench",
        "builtin:blazed?size=20um&pixel=50nm",
        "--min-angle",
        "-1deg",
        "--max-angle",
        "1.2deg",
        "--angle-step",
        "0.01deg",
        "--step",
        "50nm",
    ]);
    assert!(
        out.contains("warning: the viewing angles span -1°…1.2° only: a peak there may be another order than 1"),
        "{out}"
    );
}
