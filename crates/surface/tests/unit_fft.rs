//! The tests of iridis-fft (through its re-export `iridis_surface::fft`), which has no test binary of its own.

use iridis_surface::fft::*;

#[test]
fn fft2_round_trips() {
    let (rows, cols) = (6, 10);
    let orig: Vec<Complex<f64>> = (0..rows * cols).map(|i| Complex::new((i as f64 * 0.7).sin(), 0.0)).collect();
    let mut d = orig.clone();
    fft2(&mut d, rows, cols, false);
    // DC bin is the sum.
    let sum: f64 = orig.iter().map(|z| z.re).sum();
    assert!((d[0].re - sum).abs() < 1e-9);
    fft2(&mut d, rows, cols, true);
    for (a, b) in d.iter().zip(&orig) {
        assert!((a - b).norm() < 1e-12);
    }
}
