//! The unit tests of src/analysis.rs (period analysis), moved here so that `cargo test` compiles the library once.

use crate::common;

use iridis_lab::analysis::{dominant_period, Axis};

#[test]
fn sine_period_is_found_along_its_axis_only() {
    // 8 whole periods of 750 nm along x; constant along y.
    let patch = common::sine_along_x(4, 160, 37.5, 30.0, 750.0);
    let p = dominant_period(&patch, Axis::X).unwrap();
    assert!((p.period_nm - 750.0).abs() < 1e-6, "{p:?}");
    assert!(p.strength > 0.999);
    assert!(dominant_period(&patch, Axis::Y).is_none());
}
