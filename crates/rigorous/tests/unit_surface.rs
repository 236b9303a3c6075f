//! The unit tests of src/surface.rs (the band-limited interpolant of the sampled heights), moved here so that
//! `cargo test` compiles the library once.

use iridis_rigorous::surface::FineSurface;
use num_complex::Complex64 as C64;

#[test]
fn interpolant_of_a_sine_has_the_analytic_slope() {
    let n = 16;
    let period = 1000.0;
    let amp = 50.0;
    let h: Vec<f64> = (0..n).map(|i| amp * (2.0 * std::f64::consts::PI * i as f64 / n as f64).sin()).collect();
    let s = FineSurface::from_samples(n, 1, &h, period, 1.0, 1.0, 64, 1);
    for i in 0..64 {
        let x = i as f64 / 64.0 * period;
        let k = 2.0 * std::f64::consts::PI / period;
        assert!((s.a[i] - amp * (k * x).sin()).abs() < 1e-9);
        assert!((s.ax[i] - amp * k * (k * x).cos()).abs() < 1e-12);
    }
    let c = s.coeffs_of(|a, _, _| C64::new(a, 0.0));
    assert!((c.get(1, 0) - C64::new(0.0, -amp / 2.0)).norm() < 1e-9);
    assert!(c.get(2, 0).norm() < 1e-9);
}
