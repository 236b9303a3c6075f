//! The dominant period of a height field along one axis, from its periodogram: the mean of `|DFT(line)|²`
//! over all lines along that axis, its strongest non-zero bin `k` refined by a parabola through the logarithms
//! of the bin and its neighbours (exact for a Gaussian peak), period `L / k` with `L` the patch extent.
//!
//! This is the "surface analysis" side of the test bench's check (issue 6): the bench measures a period
//! optically (grating equation), this measures it geometrically; they must agree.

use iridis_diffraction::Patch;
use num_complex::Complex64;

/// An axis of the height field: `X` along the columns, `Y` along the rows (y up, PHYSICS.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
}

/// The dominant period along an axis and how strongly it dominates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Period {
    /// Period (nm).
    pub period_nm: f64,
    /// Fraction of the line variance (mean power of the non-zero bins) in the peak bin and its two neighbours.
    pub strength: f64,
}

/// Mean periodogram along `axis`: `P[k] = mean over lines of |Σ_j h_j e^{−2πi jk/n}|² / n²`, `k = 0..=n/2`.
pub fn periodogram(patch: &Patch, axis: Axis) -> Vec<f64> {
    let (n, lines) = match axis {
        Axis::X => (patch.cols, patch.rows),
        Axis::Y => (patch.rows, patch.cols),
    };
    let fft = iridis_fft::plan(n, false);
    let mut acc = vec![0.0; n / 2 + 1];
    let mut buf = vec![Complex64::new(0.0, 0.0); n];
    for line in 0..lines {
        for (j, b) in buf.iter_mut().enumerate() {
            let h = match axis {
                Axis::X => patch.heights[line * patch.cols + j],
                Axis::Y => patch.heights[j * patch.cols + line],
            };
            *b = Complex64::new(h, 0.0);
        }
        fft.process(&mut buf);
        for (k, a) in acc.iter_mut().enumerate() {
            *a += buf[k].norm_sqr();
        }
    }
    let norm = 1.0 / (lines as f64 * (n * n) as f64);
    acc.iter_mut().for_each(|a| *a *= norm);
    acc
}

/// The dominant period along `axis`, or `None` when the height field does not vary along it (a 1-D grating
/// seen across its grooves) or has fewer than 4 samples on it.
pub fn dominant_period(patch: &Patch, axis: Axis) -> Option<Period> {
    let p = periodogram(patch, axis);
    if p.len() < 3 {
        return None;
    }
    let (n, d) = match axis {
        Axis::X => (patch.cols, patch.dx),
        Axis::Y => (patch.rows, patch.dy),
    };
    let total: f64 = p[1..].iter().sum();
    if total.is_nan() || total <= 1e-18 * patch.max_abs_height.powi(2).max(1e-300) {
        return None;
    }
    let (k, _) =
        p.iter().enumerate().skip(1).fold((1, f64::NEG_INFINITY), |b, (k, &v)| if v > b.1 { (k, v) } else { b });
    let kf = if k > 1 && k + 1 < p.len() && p[k - 1] > 1e-9 * p[k] && p[k + 1] > 1e-9 * p[k] {
        let (a, b, c) = (p[k - 1].ln(), p[k].ln(), p[k + 1].ln());
        let den = a - 2.0 * b + c;
        let delta = if den < 0.0 { (0.5 * (a - c) / den).clamp(-0.5, 0.5) } else { 0.0 };
        k as f64 + delta
    } else {
        k as f64
    };
    let near: f64 = p[k.saturating_sub(1).max(1)..(k + 2).min(p.len())].iter().sum();
    Some(Period { period_nm: n as f64 * d / kf, strength: near / total })
}
