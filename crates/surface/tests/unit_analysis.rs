//! The unit tests of src/analysis.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::analysis::*;

/// Sines at any offset from the FFT grid: the refined period is the generated one to 1e-3 bin. The
/// issue's case: 0.45–0.49 bin off the grid came out as the same 613.03 nm before.
#[test]
fn refinement_finds_off_grid_periods() {
    use iridis_surface::generate::{Generator, Grid};
    let size = 12_800.0; // 256 px of 50 nm
    for offset in [0.0, 0.05, 0.25, 0.45, 0.49, 0.5] {
        for angle in [0.0f64, 90.0] {
            let k = 20.0 + offset;
            let period = size / k;
            let grid =
                Grid { size_x_nm: size, size_y_nm: size, pixel_nm: 50.0, angle_rad: angle.to_radians(), seed: 1 };
            let hf = Generator::Sine { period_nm: period, depth_nm: 20.0 }.generate(&grid).unwrap();
            let p = &find_peaks(&hf, &PeakOptions::default())[0];
            // d = L/k, so δd = d²/L · δk: 1e-3 bin is d²/L · 1e-3.
            let tol = period * period / size * 1e-3;
            assert!(
                (p.period_nm - period).abs() < tol,
                "offset {offset}, {angle}°: {} vs {period} (±{tol})",
                p.period_nm
            );
            assert!((p.orientation_deg - angle).abs() < 0.01, "{}", p.orientation_deg);
        }
    }
}

/// A refined period lies within its stated uncertainty of the generated one, and the uncertainty is the
/// refinement's 1e-3 bin along the grating vector: on a 12.8 × 6.4 µm patch, a bin is 1/12.8 µm⁻¹ along x
/// and 1/6.4 µm⁻¹ along y, so the same period is twice as uncertain at 90° as at 0°.
#[test]
fn periods_carry_their_uncertainty_along_their_direction() {
    use iridis_surface::generate::{Generator, Grid};
    let period = 533.0;
    let mut u = Vec::new();
    for angle in [0.0f64, 90.0] {
        let grid =
            Grid { size_x_nm: 12_800.0, size_y_nm: 6_400.0, pixel_nm: 50.0, angle_rad: angle.to_radians(), seed: 1 };
        let hf = Generator::Sine { period_nm: period, depth_nm: 20.0 }.generate(&grid).unwrap();
        let p = &find_peaks(&hf, &PeakOptions::default())[0];
        assert_eq!(p.read_off, "refined");
        assert!((p.period_nm - period).abs() <= p.period_uncertainty_nm, "{angle}°: {p:?}");
        u.push(p.period_uncertainty_nm);
    }
    // 1e-3 bin: δd = d²·δf = 533² nm² × 1e-3 / 12 800 nm = 0.0222 nm along x.
    assert!((u[0] - 0.022_194).abs() < 1e-5, "{u:?}");
    assert!((u[1] / u[0] - 2.0).abs() < 1e-4, "{u:?}");
    assert!((extent_along_nm(12_800.0, 6_400.0, 0.0) - 12_800.0).abs() < 1e-9);
    assert!((extent_along_nm(12_800.0, 6_400.0, 90.0) - 6_400.0).abs() < 1e-6);
}

/// Read off the grid, a period `d = L/k` is uncertain by half the distance to its neighbours `L/(k ± 1)`
/// on the DFT grid, which is `d²/(2L)` to first order in `1/k`.
#[test]
fn a_grid_period_is_uncertain_by_half_a_dft_step() {
    let l = 65_000.0;
    for k in [20.0, 59.0, 200.0] {
        let d = l / k;
        let half_step = 0.25 * (l / (k - 1.0) - l / (k + 1.0));
        let u = period_uncertainty_nm(d, l, false);
        assert!((u / half_step - 1.0).abs() < 1.0 / (k * k) + 1e-12, "k {k}: {u} vs {half_step}");
    }
}

#[test]
fn values_are_rounded_to_their_uncertainty() {
    assert_eq!(with_uncertainty(1100.1934, 0.0186), "1100.193 ± 0.019");
    assert_eq!(with_uncertainty(1100.1934, 0.0286), "1100.19 ± 0.03");
    assert_eq!(with_uncertainty(1600.0004, 0.0141), "1600.000 ± 0.014");
    assert_eq!(with_uncertainty(2499.63, 9.6), "2500 ± 10");
    assert_eq!(with_uncertainty(2499.63, 43.0), "2500 ± 40");
    assert_eq!(with_uncertainty(531.2, 0.15), "531.20 ± 0.15");
}

/// A sine of fewer than four cycles across the patch is no period to read (its repeats are too few), and what
/// is left is rounding noise, not periods: a 2 µm sine on 4 and 6 µm patches listed "376 nm" and "151 nm" at
/// a share of variance of 1e-32, which the test bench then measured along and the report called the strongest
/// period. No period is listed now, and the variance is said to lie in longer structure; on 8 µm (four cycles)
/// the period is found as before.
#[test]
fn too_few_cycles_list_no_noise_and_say_where_the_variance_is() {
    use iridis_surface::generate::{Generator, Grid};
    let opts = PeakOptions::default();
    for (size, cycles) in [(4_000.0, 2.0), (6_000.0, 3.0), (8_000.0, 4.0)] {
        let grid = Grid { size_x_nm: size, size_y_nm: size, pixel_nm: 50.0, angle_rad: 0.0, seed: 1 };
        let hf = Generator::Sine { period_nm: 2000.0, depth_nm: 100.0 }.generate(&grid).unwrap();
        let peaks = find_peaks(&hf, &opts);
        let long = long_period_share(&hf, &opts);
        if cycles < 1.0 / opts.max_period_fraction {
            assert!(peaks.is_empty(), "{size} nm: {peaks:?}");
            assert!(long > 0.8, "{size} nm: {long}");
        } else {
            assert!((peaks[0].period_nm - 2000.0).abs() < 1.0 && peaks[0].power > 0.99, "{:?}", peaks[0]);
            // Only the Hann window's lobe at three cycles: powers 1/4 : 1/16 : 1/16, one side 1/6 of the line's.
            assert!((long - 1.0 / 6.0).abs() < 0.01, "{size} nm: {long}");
        }
    }
}
