//! The 2-D FFT every spectral computation of a height field goes through (peak finding, spectral synthesis,
//! the PSD and autocorrelation).

use rustfft::num_complex::Complex;
use rustfft::FftPlanner;

/// In-place 2-D FFT of a row-major array (rows of length `cols`); `inverse` includes the `1/(rows·cols)`.
pub fn fft2(data: &mut [Complex<f64>], rows: usize, cols: usize, inverse: bool) {
    dft2(data, rows, cols, inverse);
    if inverse {
        let k = 1.0 / (rows * cols) as f64;
        data.iter_mut().for_each(|z| *z *= k);
    }
}

/// [`fft2`] without the normalisation: the plain sums `Σ x e^{∓2πi(…)}` both ways (an inverse after a forward
/// transform gives the input times `rows·cols`).
pub fn dft2(data: &mut [Complex<f64>], rows: usize, cols: usize, inverse: bool) {
    let mut planner = FftPlanner::new();
    let (fr, fc) = if inverse {
        (planner.plan_fft_inverse(rows), planner.plan_fft_inverse(cols))
    } else {
        (planner.plan_fft_forward(rows), planner.plan_fft_forward(cols))
    };
    fc.process(data);
    let mut col = vec![Complex::new(0.0, 0.0); rows];
    for c in 0..cols {
        for r in 0..rows {
            col[r] = data[r * cols + c];
        }
        fr.process(&mut col);
        for r in 0..rows {
            data[r * cols + c] = col[r];
        }
    }
}
