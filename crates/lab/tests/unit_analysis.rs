//! The unit tests of src/analysis.rs (period analysis), moved here so that `cargo test` compiles the library once.

use iridis_diffraction::Patch;
use iridis_lab::analysis::{dominant_period, Axis};

#[test]
fn sine_period_is_found_along_its_axis_only() {
    // 8 whole periods of 750 nm along x; constant along y.
    let (rows, cols, dx) = (4, 160, 37.5);
    let h: Vec<f64> =
        (0..rows * cols).map(|k| 30.0 * (std::f64::consts::TAU * (k % cols) as f64 * dx / 750.0).sin()).collect();
    let patch = Patch::from_row_major(rows, cols, dx, dx, &h).unwrap();
    let p = dominant_period(&patch, Axis::X).unwrap();
    assert!((p.period_nm - 750.0).abs() < 1e-6, "{p:?}");
    assert!(p.strength > 0.999);
    assert!(dominant_period(&patch, Axis::Y).is_none());
}
