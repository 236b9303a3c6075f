//! The unit tests of src/unit_cell.rs (the profile averaged along a direction), moved here so that `cargo test`
//! compiles the library once.

use iridis_api::unit_cell::*;
use iridis_diffraction::Patch;
use std::f64::consts::TAU;

#[test]
fn a_sine_at_an_angle_averages_to_its_profile_and_washes_out_across() {
    // h = A sin(2π (x cos φ + y sin φ)/Λ + p), φ = 30°, on a 20 nm grid (row 0 at the top, y up).
    let (rows, cols, d, period, amp, phi, p) = (150, 170, 20.0, 700.0, 40.0, 30f64.to_radians(), 0.7);
    let h: Vec<f64> = (0..rows * cols)
        .map(|k| {
            let (x, y) = ((k % cols) as f64 * d, (rows - 1 - k / cols) as f64 * d);
            amp * (TAU * (x * phi.cos() + y * phi.sin()) / period + p).sin()
        })
        .collect();
    let patch = Patch::from_row_major(rows, cols, d, d, &h).unwrap();
    let n = 32;
    let profile = averaged_profile(&patch, period, 30.0, n);
    // A bin averages the sine over its phase width 1/n: the closed form is the sine times sinc(π/n), less
    // the patch's mean (the field holds no whole number of periods).
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    let sinc = (std::f64::consts::PI / n as f64).sin() / (std::f64::consts::PI / n as f64);
    for (i, v) in profile.iter().enumerate() {
        let want = amp * sinc * (TAU * i as f64 / n as f64 + p).sin() - mean;
        assert!((v - want).abs() < 0.01 * amp, "bin {i}: {v} vs {want}");
    }
    // Along the wrong direction (the ridges' own) the phases mix and the profile nearly vanishes.
    let across = averaged_profile(&patch, period, 120.0, n);
    assert!(across.iter().all(|v| v.abs() < 0.1 * amp), "{across:?}");
}

/// A period of a whole number of pixels puts the samples' phases at k/q: binned finer, the bins between them were
/// interpolated (a 1100 nm sine at 100 nm pixels in 32 bins lost a third of its second order in Maxwell's
/// efficiencies). In as many bins as the phases fill, the profile is the sine's own samples.
#[test]
fn a_period_of_whole_pixels_keeps_its_own_samples() {
    let (rows, cols, d, period, amp) = (4, 100, 100.0, 1100.0, 50.0);
    let h: Vec<f64> = (0..rows * cols).map(|k| amp * (TAU * (k % cols) as f64 * d / period).sin()).collect();
    let patch = Patch::from_row_major(rows, cols, d, d, &h).unwrap();
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    let profile = averaged_profile_filled(&patch, period, 0.0, 32);
    assert_eq!(profile.len(), 11);
    for (i, v) in profile.iter().enumerate() {
        let want = amp * (TAU * i as f64 / 11.0).sin() - mean;
        assert!((v - want).abs() < 1e-9 * amp, "bin {i}: {v} vs {want}");
    }
    // Phases that fill every bin keep them all (the 30° sine above, 700 nm on 20 nm pixels).
    let tilted: Vec<f64> = (0..150 * 170).map(|k| ((k % 170) as f64 * 0.3 + (k / 170) as f64 * 0.2).sin()).collect();
    let tilted = Patch::from_row_major(150, 170, 20.0, 20.0, &tilted).unwrap();
    assert_eq!(averaged_profile_filled(&tilted, 700.0, 30.0, 32).len(), 32);
}
