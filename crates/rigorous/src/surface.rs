//! The grating surface as smooth periodic functions: the band-limited (trigonometric) interpolant of the sampled
//! heights, its slopes, and the Fourier coefficients of the functions the C-method needs.
//!
//! Lengths here are normalised by the vacuum wavenumber `k0 = 2π/λ`, so a height `h` (nm) becomes `a = k0 h`;
//! slopes are dimensionless and unchanged.

use iridis_fft::dft2;
use num_complex::Complex64 as C64;

/// A periodic surface sampled on a fine grid of `lx × ly` points over one unit cell (`ly = 1` for a 1-D profile),
/// row index `j` along y, column `i` along x, stored `[j * lx + i]`.
#[derive(Debug, Clone)]
pub struct FineSurface {
    pub lx: usize,
    pub ly: usize,
    /// Normalised height `a = k0 h` at the fine grid points, mean removed.
    pub a: Vec<f64>,
    /// Slope `∂h/∂x`.
    pub ax: Vec<f64>,
    /// Slope `∂h/∂y` (zero for a 1-D profile).
    pub ay: Vec<f64>,
}

/// Fourier coefficients of a periodic function on an `lx × ly` grid, indexed by wrapped harmonic numbers.
#[derive(Debug, Clone)]
pub struct Coeffs {
    lx: usize,
    ly: usize,
    c: Vec<C64>,
}

impl Coeffs {
    /// Coefficient of `exp(i (p Kx x + q Ky y))`; harmonics beyond the grid's band are zero.
    pub fn get(&self, p: i64, q: i64) -> C64 {
        let (lx, ly) = (self.lx as i64, self.ly as i64);
        let q_out = if ly == 1 { q != 0 } else { 2 * q.abs() >= ly };
        if 2 * p.abs() >= lx || q_out {
            return C64::new(0.0, 0.0);
        }
        let i = p.rem_euclid(lx) as usize;
        let j = q.rem_euclid(ly) as usize;
        self.c[j * self.lx + i]
    }
}

/// Forward 2-D DFT divided by the number of points: the Fourier-series coefficients of the sampled function.
pub(crate) fn fourier_coeffs(lx: usize, ly: usize, values: &[C64]) -> Coeffs {
    let mut data = values.to_vec();
    dft2(&mut data, ly, lx, false);
    let scale = 1.0 / (lx * ly) as f64;
    for v in &mut data {
        *v *= scale;
    }
    Coeffs { lx, ly, c: data }
}

/// Signed harmonic number of DFT bin `k` of `n`.
fn signed(k: usize, n: usize) -> i64 {
    if 2 * k > n {
        k as i64 - n as i64
    } else {
        k as i64
    }
}

impl FineSurface {
    /// The trigonometric interpolant of `heights_nm` (an `sy × sx` grid, `[j * sx + i]`, x along `i`, y along `j`,
    /// both increasing; the period's end not repeated) evaluated with its slopes on an `lx × ly` grid
    /// (`lx ≥ sx`, `ly ≥ sy`). `k0` is `2π/λ` (nm⁻¹); `period_x_nm`, `period_y_nm` the unit cell.
    ///
    /// A Nyquist harmonic of an even-sized grid is split evenly between ±N/2 so that the interpolant is real and
    /// passes through the samples.
    pub fn from_samples(
        sx: usize,
        sy: usize,
        heights_nm: &[f64],
        period_x_nm: f64,
        period_y_nm: f64,
        k0: f64,
        lx: usize,
        ly: usize,
    ) -> Self {
        debug_assert!(lx >= sx && ly >= sy && heights_nm.len() == sx * sy);
        let mean = heights_nm.iter().sum::<f64>() / heights_nm.len() as f64;
        let vals: Vec<C64> = heights_nm.iter().map(|&h| C64::new(h - mean, 0.0)).collect();
        let mut spec = vals;
        dft2(&mut spec, sy, sx, false);
        let norm = 1.0 / (sx * sy) as f64;
        // Zero-padded spectra of h, ∂h/∂x and ∂h/∂y on the fine grid.
        let mut h = vec![C64::new(0.0, 0.0); lx * ly];
        let mut hx = h.clone();
        let mut hy = h.clone();
        let kx = 2.0 * std::f64::consts::PI / period_x_nm;
        let ky = 2.0 * std::f64::consts::PI / period_y_nm;
        for j in 0..sy {
            let q = signed(j, sy);
            let nyq_y = sy > 1 && 2 * j == sy;
            for i in 0..sx {
                let p = signed(i, sx);
                let nyq_x = 2 * i == sx;
                let c = spec[j * sx + i] * norm;
                // Each Nyquist harmonic is split in two halves at ±N/2.
                let ps: Vec<i64> = if nyq_x { vec![p, -p] } else { vec![p] };
                let qs: Vec<i64> = if nyq_y { vec![q, -q] } else { vec![q] };
                let share = c / (ps.len() * qs.len()) as f64;
                for &pp in &ps {
                    for &qq in &qs {
                        let fi = pp.rem_euclid(lx as i64) as usize;
                        let fj = qq.rem_euclid(ly as i64) as usize;
                        let idx = fj * lx + fi;
                        h[idx] += share;
                        hx[idx] += share * C64::new(0.0, pp as f64 * kx);
                        hy[idx] += share * C64::new(0.0, qq as f64 * ky);
                    }
                }
            }
        }
        dft2(&mut h, ly, lx, true);
        dft2(&mut hx, ly, lx, true);
        dft2(&mut hy, ly, lx, true);
        FineSurface {
            lx,
            ly,
            a: h.iter().map(|v| v.re * k0).collect(),
            ax: hx.iter().map(|v| v.re).collect(),
            ay: if sy > 1 { hy.iter().map(|v| v.re).collect() } else { vec![0.0; lx * ly] },
        }
    }

    /// Fourier coefficients of `f(a, ax, ay)` evaluated pointwise on the fine grid.
    pub fn coeffs_of(&self, f: impl Fn(f64, f64, f64) -> C64) -> Coeffs {
        let vals: Vec<C64> = (0..self.a.len()).map(|k| f(self.a[k], self.ax[k], self.ay[k])).collect();
        fourier_coeffs(self.lx, self.ly, &vals)
    }
}
