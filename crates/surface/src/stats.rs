//! Roughness statistics, autocorrelation and power spectral density, as Gwyddion's "Statistical
//! Quantities" and "Statistical Functions" define them (Gwyddion user guide, ch. 4.4), on the field as given
//! (level it first: `prep::level_plane`).
//!
//! * `Sq` (rms), `Sa` (mean |z − z̄|), skewness `Ssk = Σ(z−z̄)³/(N Sq³)`, excess kurtosis
//!   `Sku − 3 = Σ(z−z̄)⁴/(N Sq⁴) − 3`, `Sz` (max − min); ISO 25178 names.
//! * ACF `G(m, n) = Σ z(r, c) z(r+m, c+n) / ((R−|m|)(C−|n|))` of the mean-removed field, computed through a
//!   zero-padded FFT (no wrap-around); the radial ACF averages it over annuli.
//! * Correlation length τ: the first lag where the radial ACF falls to `G(0)/e`. For the Gaussian ACF
//!   `σ² exp(−r²/τ²)` that the rough-film model takes, this is its τ, and `G(0) = σ²`.
//! * PSDF `W(kx, ky) = |Σ z e^{−2πi(kx x + ky y)}|² · dx dy / (R C)` (nm⁴, k in cycles/nm), normalised so that
//!   `Σ W Δkx Δky = Sq²` (Parseval); the radial PSDF averages it over annuli of |k|.

use iridis_fft::Complex;
use serde::Serialize;

use crate::fft::fft2;
use crate::HeightField;

/// Height statistics of a (levelled) field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Roughness {
    pub sq_nm: f64,
    pub sa_nm: f64,
    pub skewness: f64,
    pub excess_kurtosis: f64,
    pub sz_nm: f64,
    /// Lag at which the radial ACF falls to 1/e of its value at 0 (nm); `None` when it never does within half
    /// the smaller extent (the field is too small for its correlation length, or periodic).
    pub correlation_length_nm: Option<f64>,
}

/// A function on a regular 2-D grid of lags or frequencies, row-major, centred: index `(rows/2, cols/2)` is 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid2 {
    pub rows: usize,
    pub cols: usize,
    /// Step along x (columns) and y (rows): nm for the ACF, cycles/nm for the PSDF.
    pub dx: f64,
    pub dy: f64,
    pub values: Vec<f64>,
}

/// A radial profile: `values[i]` is the average over the annulus around `step · i`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Radial {
    pub step: f64,
    pub values: Vec<f64>,
}

fn centred(hf: &HeightField) -> Vec<f64> {
    let m = hf.mean();
    hf.heights_nm.iter().map(|h| h - m).collect()
}

/// Height statistics and the correlation length.
pub fn roughness(hf: &HeightField) -> Roughness {
    let z = centred(hf);
    let n = z.len() as f64;
    let sq = (z.iter().map(|v| v * v).sum::<f64>() / n).sqrt();
    let sa = z.iter().map(|v| v.abs()).sum::<f64>() / n;
    let (lo, hi) = hf.min_max();
    let (skewness, excess_kurtosis) = if sq > 0.0 {
        (
            z.iter().map(|v| v.powi(3)).sum::<f64>() / (n * sq.powi(3)),
            z.iter().map(|v| v.powi(4)).sum::<f64>() / (n * sq.powi(4)) - 3.0,
        )
    } else {
        (0.0, 0.0)
    };
    let radial = radial_of(&acf(hf));
    Roughness {
        sq_nm: sq,
        sa_nm: sa,
        skewness,
        excess_kurtosis,
        sz_nm: hi - lo,
        correlation_length_nm: decay_length(&radial),
    }
}

/// The 2-D ACF for lags up to half the extent each way (`rows/2`, `cols/2`), nm².
pub fn acf(hf: &HeightField) -> Grid2 {
    let (r, c) = (hf.rows, hf.cols);
    let (pr, pc) = (2 * r, 2 * c);
    let z = centred(hf);
    let mut buf = vec![Complex::new(0.0, 0.0); pr * pc];
    for i in 0..r {
        for j in 0..c {
            buf[i * pc + j] = Complex::new(z[i * c + j], 0.0);
        }
    }
    fft2(&mut buf, pr, pc, false);
    buf.iter_mut().for_each(|v| *v = Complex::new(v.norm_sqr(), 0.0));
    fft2(&mut buf, pr, pc, true);
    let (hr, hc) = (r / 2, c / 2);
    let (rows, cols) = (2 * hr + 1, 2 * hc + 1);
    let mut values = vec![0.0; rows * cols];
    for a in 0..rows {
        let m = a as i64 - hr as i64;
        for b in 0..cols {
            let n = b as i64 - hc as i64;
            let s = buf[(m.rem_euclid(pr as i64) as usize) * pc + n.rem_euclid(pc as i64) as usize].re;
            let count = ((r as i64 - m.abs()) * (c as i64 - n.abs())) as f64;
            values[a * cols + b] = s / count;
        }
    }
    Grid2 { rows, cols, dx: hf.dx_nm, dy: hf.dy_nm, values }
}

/// The 2-D PSDF on the FFT grid, centred (nm⁴ against cycles/nm).
pub fn psdf(hf: &HeightField) -> Grid2 {
    let (r, c) = (hf.rows, hf.cols);
    let z = centred(hf);
    let mut buf: Vec<Complex<f64>> = z.iter().map(|&v| Complex::new(v, 0.0)).collect();
    fft2(&mut buf, r, c, false);
    let k = hf.dx_nm * hf.dy_nm / (r * c) as f64;
    let mut values = vec![0.0; r * c];
    // Shift zero frequency to (r/2, c/2); row index grows with −ky (rows run downwards, y upwards), which for
    // the power of a real field is the same as +ky mirrored: |F(k)| = |F(−k)|.
    for i in 0..r {
        for j in 0..c {
            let (si, sj) = ((i + r / 2) % r, (j + c / 2) % c);
            values[si * c + sj] = buf[i * c + j].norm_sqr() * k;
        }
    }
    Grid2 { rows: r, cols: c, dx: 1.0 / (c as f64 * hf.dx_nm), dy: 1.0 / (r as f64 * hf.dy_nm), values }
}

/// Annular average of a centred grid, in steps of the coarser axis step, out to the smaller half extent.
pub fn radial_of(g: &Grid2) -> Radial {
    let step = g.dx.max(g.dy);
    let (cr, cc) = (g.rows / 2, g.cols / 2);
    let reach = (cr as f64 * g.dy).min(cc as f64 * g.dx);
    let n = (reach / step).floor() as usize + 1;
    let mut sum = vec![0.0; n];
    let mut count = vec![0usize; n];
    for a in 0..g.rows {
        let y = (a as f64 - cr as f64) * g.dy;
        for b in 0..g.cols {
            let x = (b as f64 - cc as f64) * g.dx;
            let i = ((x.hypot(y) / step) + 0.5).floor() as usize;
            if i < n {
                sum[i] += g.values[a * g.cols + b];
                count[i] += 1;
            }
        }
    }
    Radial { step, values: sum.iter().zip(&count).map(|(s, &k)| if k > 0 { s / k as f64 } else { 0.0 }).collect() }
}

/// First radius where a radial ACF falls to `1/e` of its value at 0, linearly interpolated.
pub fn decay_length(r: &Radial) -> Option<f64> {
    let g0 = *r.values.first()?;
    if g0 <= 0.0 {
        return None;
    }
    let t = g0 / std::f64::consts::E;
    for i in 1..r.values.len() {
        let (a, b) = (r.values[i - 1], r.values[i]);
        if b <= t {
            return Some(r.step * ((i - 1) as f64 + (a - t) / (a - b)));
        }
    }
    None
}
