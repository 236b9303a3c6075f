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
