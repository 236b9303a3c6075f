//! Taylor terms of the phase factor and the coherence-windowed DFT (paper eq. 5–8, PHYSICS.md).
//!
//! `p = exp(i k w h) = Σ_n (k w)^n / n! · (i h)^n` (eq. 5), so the far-field amplitude is
//! `A = Σ_n (k w)^n / n! · F_n` (eq. 6) with `F_n` the windowed spectrum of `(i h)^n` (eq. 7–8):
//! `F_n(f) = Σ_{s,t} c_n[s,t] · G(f − f_{s,t})`, `c_n` the Fourier-series coefficients (DFT / samples),
//! `G(f) = exp(−|f|²/(2σ_f²))`, `σ_f = 1/(2π σ_s)`, `4σ_s` the coherence length. The window convolves the
//! complex coefficients; bins within `4σ_f` of `f` contribute; frequencies beyond Nyquist give zero.

use num_complex::Complex64;
use rayon::prelude::*;

use crate::patch::Patch;
use crate::DiffractionError;

/// The largest rounding error, relative to the amplitude, that the Taylor sum may carry before
/// [`terms_for_bound`] refuses the relief (docs/PHYSICS.md, "Taylor terms").
pub const MAX_TAYLOR_ROUNDING: f64 = 1e-4;

/// The number of Taylor terms `N` for which the remainder bound `(k_max · 2|h|max)^{N+1} / (N+1)! ≤ ε`
/// holds (PHYSICS.md), `k_max = 2π/λ_min`, since `|k w h| ≤ 2 k |h|`.
///
/// Refuses a relief too deep for the expansion at `λ_min`: its terms grow to `~x^x/x!` (`x = 2 k_max |h|max`)
/// and cancel to an amplitude of at most 1, so the sum keeps about `ε_f64 · e^x` of rounding — beyond
/// [`MAX_TAYLOR_ROUNDING`] (`x > 26.8`, e.g. `|h|max` above 810 nm at 380 nm) the answer would be noise, and
/// further on the coefficients `|h|^n` overflow into NaN.
pub fn terms_for_bound(max_abs_height_nm: f64, lambda_min_nm: f64, epsilon: f64) -> Result<usize, DiffractionError> {
    let x = phase_depth(max_abs_height_nm, lambda_min_nm);
    let rounding = f64::EPSILON * x.exp();
    if rounding.is_nan() || rounding > MAX_TAYLOR_ROUNDING {
        let x_max = (MAX_TAYLOR_ROUNDING / f64::EPSILON).ln();
        return Err(DiffractionError::Invalid(format!(
            "the relief reaches {max_abs_height_nm:.0} nm from its mean height, too deep for the Taylor expansion \
             (paper eq. 5) at {lambda_min_nm} nm: its terms grow to about e^{x:.0} before they cancel, so double \
             precision leaves {} of the amplitude as rounding noise (at most {MAX_TAYLOR_ROUNDING:.0e} \
             is accepted; the limit is 2k|h|max ≤ {x_max:.1}, |h|max ≤ {:.0} nm here). Use a method that sums \
             exp(i k w h) directly (ground-truth for BRDFs, rigorous for order efficiencies) or longer wavelengths{}",
            if rounding.is_finite() { format!("{rounding:.0e}") } else { "over 1e308 times".into() },
            x_max * lambda_min_nm / (2.0 * std::f64::consts::TAU),
            // Below the far UV the likelier cause is a unit: 0.55 "nm" meant µm.
            if lambda_min_nm < 20.0 { " (wavelengths are in nm: 0.55 is µm, 5.5e-7 metres)" } else { "" }
        )));
    }
    let mut term = x; // x^{N+1}/(N+1)! for N = 0
    let mut n = 0usize;
    while term > epsilon {
        n += 1;
        term *= x / (n + 1) as f64;
    }
    Ok(n)
}

/// `x = k_max · 2|h|max`, `k_max = 2π/λ_min`: the largest `|k w h|` the expansion must reach.
fn phase_depth(max_abs_height_nm: f64, lambda_min_nm: f64) -> f64 {
    2.0 * std::f64::consts::TAU / lambda_min_nm * max_abs_height_nm
}

/// The remainder bound `x^{N+1} / (N+1)!` of `n` terms (`x = k_max · 2|h|max`), what [`terms_for_bound`]
/// brings below its `ε`: how far a given term count may leave the amplitude from its limit.
pub fn remainder_bound(max_abs_height_nm: f64, lambda_min_nm: f64, n: usize) -> f64 {
    let x = phase_depth(max_abs_height_nm, lambda_min_nm);
    (1..=n + 1).fold(1.0, |b, k| b * x / k as f64)
}

/// The DFT bins a [`TaylorTerms`] keeps: those whose frequency `(s/Lx, t/Ly)` lies within `radius` of `centre`
/// (cycles/nm). Light of wavelength `λ` between two directions above the surface reads frequencies within
/// `2/λ` of zero (and light from one direction within `1/λ` of `ω_i,xy/λ`), so a patch sampled finer than
/// `λ/4` has bins no light reaches: a band leaves them out of memory (a 50 nm scan keeps a fifth of its bins
/// for every direction pair, a twentieth for one light). Bins outside the band read as zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    pub centre: [f64; 2],
    pub radius: f64,
}

impl Band {
    /// Every bin.
    pub const ALL: Band = Band { centre: [0.0, 0.0], radius: f64::INFINITY };

    /// The frequencies `(ω_i + ω_r)_xy/λ` (either sign) of any two directions above the surface at wavelengths
    /// from `lambda_min_nm` up, widened by `margin` (cycles/nm; a coherence window's radius).
    pub fn directions(lambda_min_nm: f64, margin: f64) -> Band {
        Band { centre: [0.0, 0.0], radius: 2.0 / lambda_min_nm + margin }
    }

    /// The frequencies `(ω_i + ω_r)_xy/λ` of light from `wi` towards any direction above the surface at
    /// wavelengths from `lambda_min_nm` up, widened by `margin` (what the reference method's eq. 8 and a unit
    /// cell's row of light from `wi` read): the disks of radius `1/λ` about `ω_i,xy/λ` all hold the origin and
    /// grow with `1/λ`, so the shortest wavelength's holds them all.
    pub fn light(wi: [f64; 3], lambda_min_nm: f64, margin: f64) -> Band {
        let c = 1.0 / lambda_min_nm;
        Band { centre: [c * wi[0], c * wi[1]], radius: 1.0 / lambda_min_nm + margin }
    }
}

/// The radius `4σ_f` (cycles/nm) of the window of coherence length `coherence_nm` (eq. 8 takes the bins
/// within it): what a [`Band`] widens by for a windowed evaluator.
pub fn window_radius(coherence_nm: f64) -> f64 {
    4.0 / (std::f64::consts::TAU * coherence_nm / 4.0)
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
    /// The bins kept.
    pub band: Band,
    /// Per DFT row `t` (unsigned): its kept signed bins `s_lo..=s_hi` and the index of `s_lo` in the kept
    /// bins; `None` for a row with none.
    band_rows: Vec<Option<(i64, i64, usize)>>,
    /// `c_n[s,t]` of the kept bins, row by row (`t` unsigned increasing, `s` signed increasing), interleaved:
    /// `N + 1` coefficients per bin.
    coeffs: Vec<Complex64>,
    /// What a bin outside the band reads.
    zeros: Vec<Complex64>,
}

impl TaylorTerms {
    /// DFTs of `(i h)^n` for `n = 0..=n_max`, in `f64`, every bin.
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
        Self::compute_in_band(patch, n_max, coherence_nm, Band::ALL, progress)
    }

    /// As [`TaylorTerms::compute_with_progress`], keeping only the bins of `band`: memory and time scale
    /// with the bins light reaches, not with the samples. The kept coefficients are bit for bit those of
    /// [`TaylorTerms::compute`] (the same row and column transforms, one term at a time).
    pub fn compute_in_band(
        patch: &Patch,
        n_max: usize,
        coherence_nm: f64,
        band: Band,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Self, DiffractionError> {
        patch.check_coherence(coherence_nm)?;
        if !(band.radius > 0.0 && band.centre.iter().all(|c| c.is_finite())) {
            return Err(DiffractionError::Invalid(format!("band {band:?}: needs a positive radius")));
        }
        let (rows, cols) = (patch.rows, patch.cols);
        let samples = rows * cols;
        // The coefficients of (i h)^n in nm: |h|max^N, summed over the samples by the DFT, must stay finite.
        let log_largest = n_max as f64 * patch.max_abs_height.max(1.0).ln() + (samples as f64).ln();
        if log_largest >= f64::MAX.ln() {
            return Err(DiffractionError::Invalid(format!(
                "{n_max} Taylor terms of a relief reaching {:.0} nm from its mean height: |h|^N ≈ 1e{:.0} \
                 overflows double precision; use fewer terms or a method that sums exp(i k w h) directly \
                 (ground-truth for BRDFs, rigorous for order efficiencies)",
                patch.max_abs_height,
                log_largest / std::f64::consts::LN_10
            )));
        }
        let (lx, ly) = (cols as f64 * patch.dx, rows as f64 * patch.dy);
        // The kept bins, row by row: signed s within the band and within the DFT's −⌊(n−1)/2⌋..=⌊n/2⌋.
        let (s_min, s_max) = (-(((cols - 1) / 2) as i64), (cols / 2) as i64);
        let mut band_rows = vec![None; rows];
        let mut kept = 0usize;
        for (t, row) in band_rows.iter_mut().enumerate() {
            let fy = signed(t, rows) as f64 / ly - band.centre[1];
            let half2 = band.radius * band.radius - fy * fy;
            if half2.is_nan() || half2 < 0.0 {
                continue;
            }
            let half = half2.sqrt();
            let lo = (((band.centre[0] - half) * lx).ceil() as i64).max(s_min);
            let hi = (((band.centre[0] + half) * lx).floor() as i64).min(s_max);
            if lo <= hi {
                *row = Some((lo, hi, kept));
                kept += (hi - lo + 1) as usize;
            }
        }
        let stride = n_max + 1;
        let bytes = kept as f64 * stride as f64 * 16.0;
        if bytes > 16e9 {
            return Err(DiffractionError::Invalid(format!(
                "{rows}×{cols} samples with {stride} terms need {:.1} GB; use fewer terms or a smaller patch",
                bytes / 1e9
            )));
        }
        // The columns (signed s) and DFT rows any kept bin needs.
        let (c_lo, c_hi) = band_rows.iter().flatten().fold((i64::MAX, i64::MIN), |(a, b), r| (a.min(r.0), b.max(r.1)));
        let width = if kept == 0 { 0 } else { (c_hi - c_lo + 1) as usize };
        let column_of = |k: usize| (c_lo + k as i64).rem_euclid(cols as i64) as usize;
        let fft_x = iridis_fft::plan(cols, false);
        let fft_y = iridis_fft::plan(rows, false);
        let norm = 1.0 / samples as f64;
        // Centre the coherence window on the patch (as the ground truth does) rather than on its corner: by
        // the shift theorem, c[s,t] · exp(2πi f_{s,t} · x_c), x_c the patch centre, with the 1/samples
        // normalisation folded in; for the kept bins, in their order.
        let centring: Vec<Complex64> = band_rows
            .iter()
            .enumerate()
            .filter_map(|(t, r)| r.map(|r| (t, r)))
            .flat_map(|(t, (lo, hi, _))| {
                let ty = signed(t, rows) as f64 * (rows - 1) as f64 / (2 * rows) as f64;
                (lo..=hi).map(move |s| {
                    let sx = s as f64 * (cols - 1) as f64 / (2 * cols) as f64;
                    let (sin, cos) = (std::f64::consts::TAU * (sx + ty)).sin_cos();
                    Complex64::new(cos * norm, sin * norm)
                })
            })
            .collect();
        let mut coeffs = vec![Complex64::new(0.0, 0.0); kept * stride];
        // One term at a time, its transforms in parallel: the row transforms keep the band's columns, the
        // column transforms run on those only.
        let mut by_rows = vec![Complex64::new(0.0, 0.0); rows * width];
        let mut by_cols = vec![Complex64::new(0.0, 0.0); width * rows];
        for n in 0..=n_max {
            if kept == 0 {
                progress(n + 1);
                continue;
            }
            // (i h)^n = i^n h^n, evaluated directly (not by repeated products).
            let i_n = match n % 4 {
                0 => Complex64::new(1.0, 0.0),
                1 => Complex64::new(0.0, 1.0),
                2 => Complex64::new(-1.0, 0.0),
                _ => Complex64::new(0.0, -1.0),
            };
            by_rows.par_chunks_mut(width).zip(patch.heights.par_chunks(cols)).for_each_init(
                || vec![Complex64::new(0.0, 0.0); cols],
                |line, (out, h)| {
                    for (l, &v) in line.iter_mut().zip(h) {
                        *l = i_n * v.powi(n as i32);
                    }
                    fft_x.process(line);
                    for (k, o) in out.iter_mut().enumerate() {
                        *o = line[column_of(k)];
                    }
                },
            );
            transpose(&by_rows, &mut by_cols, rows, width);
            by_cols.par_chunks_mut(rows * 8).for_each(|block| fft_y.process(block));
            // Scatter the kept bins (row by row, disjoint slices of the coefficients) with the centring.
            let mut rest = &mut coeffs[..];
            let mut parts = Vec::new();
            for (t, r) in band_rows.iter().enumerate() {
                if let Some((lo, hi, first)) = *r {
                    let (part, tail) = rest.split_at_mut((hi - lo + 1) as usize * stride);
                    parts.push((t, lo, first, part));
                    rest = tail;
                }
            }
            let by_cols = &by_cols;
            let centring = &centring;
            parts.into_par_iter().for_each(|(t, lo, first, part)| {
                for (j, bin) in part.chunks_mut(stride).enumerate() {
                    let k = (lo - c_lo) as usize + j;
                    bin[n] = by_cols[k * rows + t] * centring[first + j];
                }
            });
            progress(n + 1);
        }
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
            band,
            band_rows,
            coeffs,
            zeros: vec![Complex64::new(0.0, 0.0); stride],
        })
    }

    /// `c_n` at DFT bin `(s, t)` for all n (bins indexed `0..cols`, `0..rows`); zeros outside the band.
    pub fn bin(&self, s: usize, t: usize) -> &[Complex64] {
        let stride = self.n_max + 1;
        match self.band_rows[t] {
            Some((lo, hi, first)) => {
                let ss = signed(s, self.cols);
                if ss < lo || ss > hi {
                    return &self.zeros;
                }
                let i = (first + (ss - lo) as usize) * stride;
                &self.coeffs[i..i + stride]
            }
            None => &self.zeros,
        }
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
    /// `(t · cols + s) · (N + 1) + n`, zeros outside the band (what a GPU uploads to evaluate eq. 8 itself).
    pub fn coefficients(&self) -> Vec<Complex64> {
        let stride = self.n_max + 1;
        let mut all = vec![Complex64::new(0.0, 0.0); self.rows * self.cols * stride];
        for t in 0..self.rows {
            for s in 0..self.cols {
                let i = (t * self.cols + s) * stride;
                all[i..i + stride].copy_from_slice(self.bin(s, t));
            }
        }
        all
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
pub fn signed(k: usize, n: usize) -> i64 {
    if k <= n / 2 {
        k as i64
    } else {
        k as i64 - n as i64
    }
}

/// `dst` (`cols × rows`, row-major) = the transpose of `src` (`rows × cols`), in cache-sized blocks.
// Public but hidden: not API, reachable only for the Taylor terms' test in tests/ (`[lib] test = false`).
#[doc(hidden)]
pub fn transpose(src: &[Complex64], dst: &mut [Complex64], rows: usize, cols: usize) {
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
