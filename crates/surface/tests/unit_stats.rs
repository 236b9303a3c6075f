//! The unit tests of src/stats.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::generate::{Generator, Grid};
use iridis_surface::stats::*;

#[test]
fn parseval_and_sine_closed_forms() {
    // A sine of amplitude A over whole periods: Sq = A/√2, Sa = 2A/π, Ssk = 0, excess kurtosis = −1.5,
    // and its PSDF holds all of Sq² at |k| = 1/period.
    let (a, period) = (10.0, 800.0);
    let grid = Grid { size_x_nm: 16_000.0, size_y_nm: 8_000.0, pixel_nm: 50.0, angle_rad: 0.0, seed: 1 };
    let hf = Generator::Sine { period_nm: period, depth_nm: 2.0 * a }.generate(&grid).unwrap();
    let r = roughness(&hf);
    assert!((r.sq_nm - a / 2f64.sqrt()).abs() < 1e-9, "{}", r.sq_nm);
    assert!((r.sa_nm - 2.0 * a / std::f64::consts::PI).abs() < 0.01 * a, "{}", r.sa_nm);
    assert!(r.skewness.abs() < 1e-9 && (r.excess_kurtosis + 1.5).abs() < 1e-9, "{r:?}");
    let w = psdf(&hf);
    let total: f64 = w.values.iter().sum::<f64>() * w.dx * w.dy;
    assert!((total - r.sq_nm * r.sq_nm).abs() < 1e-9 * total, "Parseval: {total} vs {}", r.sq_nm.powi(2));
    let radial = radial_of(&w);
    let peak = radial.values.iter().enumerate().max_by(|x, y| x.1.total_cmp(y.1)).unwrap().0;
    assert!((peak as f64 * radial.step - 1.0 / period).abs() < 0.5 * radial.step, "peak at bin {peak}");
    // The ACF of a sine is (A²/2) cos(2π x / period): 0 at a quarter period, −A²/2 at half.
    let g = acf(&hf);
    let at = |n: usize| g.values[(g.rows / 2) * g.cols + g.cols / 2 + n];
    assert!((at(0) - a * a / 2.0).abs() < 1e-9);
    assert!(at(4).abs() < 0.01 * a * a, "{}", at(4));
    assert!((at(8) + a * a / 2.0).abs() < 0.01 * a * a, "{}", at(8));
}

#[test]
fn gaussian_surface_gives_its_sigma_and_tau() {
    // The generator's surface has the ACF σ² exp(−r²/τ²): Sq ≈ σ and the 1/e length ≈ τ.
    let (sigma, tau) = (20.0, 300.0);
    for seed in [1, 2] {
        let grid = Grid { size_x_nm: 20_000.0, size_y_nm: 20_000.0, pixel_nm: 40.0, angle_rad: 0.0, seed };
        let hf = Generator::Gaussian { rms_nm: sigma, corr_nm: tau }.generate(&grid).unwrap();
        let r = roughness(&hf);
        assert!((r.sq_nm / sigma - 1.0).abs() < 0.05, "seed {seed}: Sq {}", r.sq_nm);
        let t = r.correlation_length_nm.unwrap();
        assert!((t / tau - 1.0).abs() < 0.08, "seed {seed}: τ {t}");
        assert!(r.skewness.abs() < 0.1 && r.excess_kurtosis.abs() < 0.2, "{r:?}");
    }
}
