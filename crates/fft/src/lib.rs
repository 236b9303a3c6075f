//! The FFTs of iridis: peak finding, spectral synthesis, the PSD and autocorrelation of a height field
//! (iridis-surface), the Taylor terms' spectra (iridis-diffraction), the lab's periodograms and the rigorous
//! solver's Fourier coefficients all transform through here.
//!
//! Why a crate of its own: rustfft's planner is generic over the float type, so every crate that calls it
//! compiles the whole planner again — every algorithm in scalar, SSE and AVX form, about 13 CPU-s at the
//! release profile (measured on the 2-core VM, 2026-11-27; 45 % of iridis-surface's LLVM IR). Behind these
//! non-generic functions it is compiled once. The transforms are rustfft's, unchanged.

use std::sync::Arc;

pub use rustfft::num_complex::Complex;
pub use rustfft::Fft;

/// The transform of length `n`: forward `X_k = Σ_j x_j e^{−2πi jk/n}`, or inverse with `e^{+2πi jk/n}` and no
/// `1/n`. `process` transforms a buffer in place, every consecutive chunk of length `n` of it.
pub fn plan(n: usize, inverse: bool) -> Arc<dyn Fft<f64>> {
    let mut planner = rustfft::FftPlanner::new();
    if inverse {
        planner.plan_fft_inverse(n)
    } else {
        planner.plan_fft_forward(n)
    }
}

/// In-place 2-D FFT of a row-major array (rows of length `cols`); `inverse` includes the `1/(rows·cols)`.
pub fn fft2(data: &mut [Complex<f64>], rows: usize, cols: usize, inverse: bool) {
    dft2(data, rows, cols, inverse);
    if inverse {
        let k = 1.0 / (rows * cols) as f64;
        data.iter_mut().for_each(|z| *z *= k);
    }
}

/// [`fft2`] without the normalisation: the plain sums `Σ x e^{∓2πi(…)}` both ways (an inverse after a forward
/// transform gives the input times `rows·cols`). The rows first, then the columns; one row (`rows == 1`) is a
/// 1-D transform.
pub fn dft2(data: &mut [Complex<f64>], rows: usize, cols: usize, inverse: bool) {
    plan(cols, inverse).process(data);
    if rows > 1 {
        let fr = plan(rows, inverse);
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
}
