//! Taylor terms of the phase factor and the coherence-windowed DFT (paper eq. 5–8, PHYSICS.md).
//!
//! `p = exp(i k w h) = Σ_n (k w)^n / n! · (i h)^n` (eq. 5), so the far-field amplitude is
//! `A = Σ_n (k w)^n / n! · F_n` (eq. 6) with `F_n` the windowed spectrum of `(i h)^n` (eq. 7–8):
//! `F_n(f) = Σ_{s,t} c_n[s,t] · G(f − f_{s,t})`, `c_n` the Fourier-series coefficients (DFT / samples),
//! `G(f) = exp(−|f|²/(2σ_f²))`, `σ_f = 1/(2π σ_s)`, `4σ_s` the coherence length. The window convolves the
//! complex coefficients; bins within `4σ_f` of `f` contribute; frequencies beyond Nyquist give zero.

use num_complex::Complex64;
use rayon::prelude::*;
use rustfft::FftPlanner;

use crate::patch::Patch;
use crate::DiffractionError;

/// The number of Taylor terms `N` for which the remainder bound `(k_max · 2|h|max)^{N+1} / (N+1)! ≤ ε`
/// holds (PHYSICS.md), `k_max = 2π/λ_min`, since `|k w h| ≤ 2 k |h|`.
pub fn terms_for_bound(max_abs_height_nm: f64, lambda_min_nm: f64, epsilon: f64) -> usize {
    let x = 2.0 * std::f64::consts::TAU / lambda_min_nm * max_abs_height_nm;
    let mut term = x; // x^{N+1}/(N+1)! for N = 0
    let mut n = 0usize;
    while term > epsilon && n < 400 {
        n += 1;
        term *= x / (n + 1) as f64;
    }
    n
}

/// Fourier coefficients of `(i h)^n`, `n = 0..=N`, for one patch, with the coherence window.
#[derive(Debug, Clone)]
pub struct TaylorTerms {
    pub rows: usize,
    pub cols: usize,
    pub dx: f64,
    pub dy: f64,
    /// Highest term index `N`.
    pub n_max: usize,
    /// `σ_f` of the frequency-domain window (cycles/nm).
    pub sigma_f: f64,
    /// Coherence length `4σ_s` (nm).
    pub coherence_nm: f64,
    /// `max |h|` of the patch (nm).
    pub max_abs_height: f64,
    /// [`Patch::fingerprint`] of the patch the terms were computed from.
    pub fingerprint: String,
    /// `c_n[s,t]`, interleaved: index `(t · cols + s) · (N + 1) + n`, `s`, `t` the DFT bins along x and y.
    coeffs: Vec<Complex64>,
}

impl TaylorTerms {
    /// DFTs of `(i h)^n` for `n = 0..=n_max`, one term per thread, in `f64`.
    pub fn compute(patch: &Patch, n_max: usize, coherence_nm: f64) -> Result<Self, DiffractionError> {
        Self::compute_with_progress(patch, n_max, coherence_nm, &|_| {})
    }

    /// As [`TaylorTerms::compute`], calling `progress(terms_done)` as terms finish.
    pub fn compute_with_progress(
        patch: &Patch,
        n_max: usize,
        coherence_nm: f64,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Self, DiffractionError> {
        if !(coherence_nm.is_finite() && coherence_nm > 0.0) {
            return Err(DiffractionError::Invalid(format!("coherence length {coherence_nm} nm must be positive")));
        }
        let (rows, cols) = (patch.rows, patch.cols);
        let samples = rows * cols;
        let bytes = samples as f64 * (n_max + 1) as f64 * 16.0 * 2.0;
        if bytes > 16e9 {
            return Err(DiffractionError::Invalid(format!(
                "{rows}×{cols} samples with {} terms need {:.1} GB; use fewer terms or a smaller patch",
                n_max + 1,
                bytes / 1e9
            )));
        }
        let mut planner = FftPlanner::<f64>::new();
        let fft_x = planner.plan_fft_forward(cols);
        let fft_y = planner.plan_fft_forward(rows);
        let norm = 1.0 / samples as f64;
        // Centre the coherence window on the patch (as the ground truth does) rather than on its corner: by
        // the shift theorem, c[s,t] · exp(2πi f_{s,t} · x_c), x_c the patch centre. Computed once for all terms,
        // with the 1/samples normalisation folded in.
        let phase_x: Vec<f64> =
            (0..cols).map(|s| signed(s, cols) as f64 * (cols - 1) as f64 / (2 * cols) as f64).collect();
        let centring: Vec<Complex64> = (0..rows)
            .flat_map(|t| {
                let ty = signed(t, rows) as f64 * (rows - 1) as f64 / (2 * rows) as f64;
                let phase_x = &phase_x;
                (0..cols).map(move |s| {
                    let (sin, cos) = (std::f64::consts::TAU * (phase_x[s] + ty)).sin_cos();
                    Complex64::new(cos * norm, sin * norm)
                })
            })
            .collect();
        let done = std::sync::atomic::AtomicUsize::new(0);
        let terms: Vec<Vec<Complex64>> = (0..=n_max)
            .into_par_iter()
            .map(|n| {
                // (i h)^n = i^n h^n, evaluated directly (not by repeated products across threads).
                let i_n = match n % 4 {
                    0 => Complex64::new(1.0, 0.0),
                    1 => Complex64::new(0.0, 1.0),
                    2 => Complex64::new(-1.0, 0.0),
                    _ => Complex64::new(0.0, -1.0),
                };
                let mut data: Vec<Complex64> = patch.heights.iter().map(|&h| i_n * h.powi(n as i32)).collect();
                fft2(&mut data, rows, cols, fft_x.as_ref(), fft_y.as_ref());
                for (c, p) in data.iter_mut().zip(&centring) {
                    *c *= p;
                }
                let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                progress(d);
                data
            })
            .collect();
        let stride = n_max + 1;
        let mut coeffs = vec![Complex64::new(0.0, 0.0); samples * stride];
        coeffs.par_chunks_mut(stride).enumerate().for_each(|(bin, out)| {
            for (n, t) in terms.iter().enumerate() {
                out[n] = t[bin];
            }
        });
        let sigma_s = coherence_nm / 4.0;
        Ok(Self {
            rows,
            cols,
            dx: patch.dx,
            dy: patch.dy,
            n_max,
            sigma_f: 1.0 / (std::f64::consts::TAU * sigma_s),
            coherence_nm,
            max_abs_height: patch.max_abs_height,
            fingerprint: patch.fingerprint(),
            coeffs,
        })
    }

    /// `c_n` at DFT bin `(s, t)` for all n (bins indexed `0..cols`, `0..rows`).
    pub fn bin(&self, s: usize, t: usize) -> &[Complex64] {
        let stride = self.n_max + 1;
        let i = (t * self.cols + s) * stride;
        &self.coeffs[i..i + stride]
    }

    /// Whether frequency `f` (cycles/nm) lies within Nyquist on both axes.
    pub fn within_nyquist(&self, fx: f64, fy: f64) -> bool {
        fx.abs() <= 0.5 / self.dx && fy.abs() <= 0.5 / self.dy
    }

    /// Windowed spectra `F_n(f)` for all `n` at frequency `f = (fx, fy)` (cycles/nm), eq. 8, written into
    /// `out` (length `N + 1`). Bins are taken within `4σ_f` of `f` and never wrapped past Nyquist.
    pub fn windowed(&self, fx: f64, fy: f64, out: &mut [Complex64]) {
        for o in out.iter_mut() {
            *o = Complex64::new(0.0, 0.0);
        }
        if !self.within_nyquist(fx, fy) {
            return;
        }
        let (lx, ly) = self.extent();
        let r = self.window_radius();
        let inv2s2 = 1.0 / (2.0 * self.sigma_f * self.sigma_f);
        let (s0, s1) = window_bins(fx, r, lx, self.cols);
        let (t0, t1) = window_bins(fy, r, ly, self.rows);
        for t in t0..=t1 {
            let dfy = fy - t as f64 / ly;
            let ti = t.rem_euclid(self.rows as i64) as usize;
            for s in s0..=s1 {
                let dfx = fx - s as f64 / lx;
                let d2 = dfx * dfx + dfy * dfy;
                if d2 > r * r {
                    continue;
                }
                let g = (-d2 * inv2s2).exp();
                let si = s.rem_euclid(self.cols as i64) as usize;
                for (o, c) in out.iter_mut().zip(self.bin(si, ti)) {
                    *o += c * g;
                }
            }
        }
    }

    /// The patch's extent `(Lx, Ly)` (nm): DFT bin `s` sits at frequency `s / Lx`.
    pub fn extent(&self) -> (f64, f64) {
        (self.cols as f64 * self.dx, self.rows as f64 * self.dy)
    }

    /// Radius `4σ_f` (cycles/nm) within which [`TaylorTerms::windowed`] takes bins.
    pub fn window_radius(&self) -> f64 {
        4.0 * self.sigma_f
    }

    /// Every coefficient `c_n[s, t]`, interleaved as [`TaylorTerms::bin`] reads them: index
    /// `(t · cols + s) · (N + 1) + n` (what a GPU uploads to evaluate eq. 8 itself).
    pub fn coefficients(&self) -> &[Complex64] {
        &self.coeffs
    }

    /// Bytes held by the coefficients.
    pub fn memory_bytes(&self) -> usize {
        self.coeffs.len() * std::mem::size_of::<Complex64>()
    }
}

/// The signed DFT bins `s` along one axis whose frequencies `s / length` lie within `r` of `f`, among those the
/// DFT of `n` samples has (`−⌊(n−1)/2⌋ ..= ⌊n/2⌋`, never wrapped past Nyquist): `(first, last)`, empty when
/// `first > last`. The bins eq. 8's window takes at `f`.
pub fn window_bins(f: f64, r: f64, length: f64, n: usize) -> (i64, i64) {
    let (lo, hi) = (-(((n - 1) / 2) as i64), (n / 2) as i64);
    ((((f - r) * length).ceil() as i64).max(lo), (((f + r) * length).floor() as i64).min(hi))
}

/// Signed frequency index of DFT bin `k` of `n`: `0, 1, …, ⌊n/2⌋, −⌊(n−1)/2⌋, …, −1`.
fn signed(k: usize, n: usize) -> i64 {
    if k <= n / 2 {
        k as i64
    } else {
        k as i64 - n as i64
    }
}

/// In-place 2D forward DFT of a row-major `rows × cols` array (`Σ x e^{−2πi(...)}`).
fn fft2(
    data: &mut [Complex64],
    rows: usize,
    cols: usize,
    fft_x: &dyn rustfft::Fft<f64>,
    fft_y: &dyn rustfft::Fft<f64>,
) {
    fft_x.process(data); // rustfft processes consecutive chunks of its length: every row
    let mut t = vec![Complex64::new(0.0, 0.0); rows * cols];
    transpose(data, &mut t, rows, cols);
    fft_y.process(&mut t);
    transpose(&t, data, cols, rows);
}

fn transpose(src: &[Complex64], dst: &mut [Complex64], rows: usize, cols: usize) {
    const B: usize = 32;
    for r0 in (0..rows).step_by(B) {
        for c0 in (0..cols).step_by(B) {
            for r in r0..(r0 + B).min(rows) {
                for c in c0..(c0 + B).min(cols) {
                    dst[c * rows + r] = src[r * cols + c];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn term_count_meets_its_bound() {
        let n = terms_for_bound(150.0, 380.0, 1e-6);
        let x = 2.0 * std::f64::consts::TAU / 380.0 * 150.0;
        let bound = |n: usize| (1..=n + 1).fold(1.0, |acc, k| acc * x / k as f64);
        assert!(bound(n) <= 1e-6 && bound(n - 1) > 1e-6, "N = {n}");
    }

    #[test]
    fn flat_patch_has_unit_specular_amplitude() {
        let patch = Patch::from_row_major(8, 8, 50.0, 50.0, &[3.0; 64]).unwrap();
        let t = TaylorTerms::compute(&patch, 3, 65_000.0).unwrap();
        let mut out = vec![Complex64::new(0.0, 0.0); 4];
        t.windowed(0.0, 0.0, &mut out);
        assert!((out[0] - Complex64::new(1.0, 0.0)).norm() < 1e-15);
        assert!(out[1].norm() < 1e-15);
    }

    #[test]
    fn single_cosine_has_its_bins_at_its_frequency() {
        // h = cos(2π x / P): c_1 = DFT{i h}/N has magnitude 1/2 at s = ±cols/P and nothing elsewhere.
        let (rows, cols, dx) = (4, 64, 10.0);
        let period_px = 16.0;
        let h: Vec<f64> =
            (0..rows * cols).map(|k| (std::f64::consts::TAU * (k % cols) as f64 / period_px).cos()).collect();
        let patch = Patch::from_row_major(rows, cols, dx, dx, &h).unwrap();
        let t = TaylorTerms::compute(&patch, 1, 1e9).unwrap();
        let bin = (cols as f64 / period_px) as usize;
        // |c_1| = 1/2 at ±(cols/P); the window-centring phase only rotates them.
        assert!((t.bin(bin, 0)[1].norm() - 0.5).abs() < 1e-12);
        assert!((t.bin(cols - bin, 0)[1].norm() - 0.5).abs() < 1e-12);
        assert!(t.bin(bin + 1, 0)[1].norm() < 1e-12);
    }
}
