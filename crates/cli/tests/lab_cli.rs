//! The virtual-lab commands (`testbench`, `compare`) as a user runs them, including their refusals.
//! Sizes are small so that each call takes about a second in release.

mod common;
use common::{assert_fails, json_of};

/// A 1500 nm sine grating: the bench must read the period back through the grating equation
/// m λ / d = sin θ_i − sin θ_r, and write its plot.
#[test]
fn testbench_reads_a_sine_grating_period() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("bench.png");
    let j = json_of(&[
        "testbench",
        "builtin:sine?size=12um&pixel=50nm&period=1500nm",
        "--coherence",
        "8um",
        "--from",
        "450nm",
        "--to",
        "650nm",
        "--step",
        "50nm",
        "--angle-step",
        "0.1deg",
        "--plot",
        plot.to_str().unwrap(),
        "--json",
    ]);
    let mean = j["periodicity_nm"]["mean"].as_f64().unwrap();
    assert!((mean - 1500.0).abs() < 0.01 * 1500.0, "period {mean} nm");
    let peaks = j["peaks"].as_array().unwrap();
    assert_eq!(peaks.len(), 5, "{j}");
    for p in peaks {
        let (lambda, angle) = (p["wavelength_nm"].as_f64().unwrap(), p["angle_deg"].as_f64().unwrap());
        let predicted = (75f64.to_radians().sin() - lambda / 1500.0).asin().to_degrees();
        assert!((angle - predicted).abs() < 0.5, "λ {lambda}: peak at {angle}°, grating equation {predicted}°");
    }
    assert!(image::open(&plot).is_ok(), "plot is not a readable image");
}

/// `compare` reports every method at every exposure, and the reference sits far closer to the ground truth
/// than Stam's Gaussian model on a snake-like surface (the paper's Table 2 ordering).
#[test]
fn compare_orders_methods_as_the_paper_does() {
    let j = json_of(&[
        "compare",
        "builtin:elaphe?size=6um&pixel=60nm",
        "--methods",
        "reference,stam-gaussian",
        "--exposures",
        "1,1000",
        "--coherence",
        "2um",
        "--size",
        "16",
        "--json",
    ]);
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
}

#[test]
fn lab_commands_refuse_bad_input_clearly() {
    assert_fails(&["testbench", "builtin:blazed", "--method", "lookup"], &["no spectral reflectance"]);
    assert_fails(&["testbench", "builtin:blazed", "--method", "magic"], &["magic"]);
    assert_fails(&["testbench", "builtin:blazed", "--incidence", "75"], &["unit"]);
    assert_fails(&["testbench", "/no/such/scan.gwy"], &["/no/such/scan.gwy"]);
    assert_fails(&["compare", "builtin:blazed", "--methods", "lookup", "--exposures", "bright"], &["bright"]);
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
        let out = common::iridis(&[
            "brdf-map",
            "builtin:sine?size=6um&pixel=50nm&period=1500nm",
            "--method",
            method,
            "--coherence",
            "3um",
            "--size",
            "65",
            "-o",
            png.to_str().unwrap(),
            "--raw",
            raw.to_str().unwrap(),
        ]);
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
    assert_fails(&["brdf-map", "x.npz", "--method", "stam-gaussian", "-o", o], &["needs the height field"]);
    assert_fails(&["brdf-map", "builtin:sine", "--method", "stam", "-o", o], &["unknown method 'stam'", "nmm"]);
    assert!(!png.exists(), "a refused map left a file behind");
}
