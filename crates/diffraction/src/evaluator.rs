//! The evaluators: one interface, several methods (ARCHITECTURE.md). Each answers the colour (XYZ) for a pair
//! of directions and, where the method resolves wavelengths, the relative reflectance `ρ_λ = C |A|²`.

use std::sync::Arc;

use iridis_color::{SpectralWeights, Xyz};
use num_complex::Complex64;

use crate::geometry::{uvw, Shading, Vec3};
use crate::patch::Patch;
use crate::spectral::SpectralSetup;
use crate::taylor::TaylorTerms;
use crate::DiffractionError;

/// A diffraction BRDF model.
pub trait Evaluator: Send + Sync {
    /// Short name (`ground-truth`, `reference`, `lookup`, …).
    fn name(&self) -> &'static str;
    /// Relative reflectance `ρ_λ(ω_i, ω_r)`; `None` for methods that integrate over λ in advance.
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64>;
    /// CIE XYZ of the reflected light, `X = Σ_λ w_x(λ) ρ_λ` (paper eq. 9; a normal-incidence mirror has Y = 1).
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz;
    /// The precomputed tables behind this evaluator, if it is the lookup method: what a GPU uploads to evaluate
    /// the same numbers (`iridis-gpu`). Other methods have nothing to upload.
    fn as_lookup(&self) -> Option<&crate::table::Lookup> {
        None
    }
}

/// The thesis' reference shader (FLSS, Algorithm 3): at each λ of a uniform grid, the windowed DFT of every
/// Taylor term at `f = (−u/λ, −v/λ)` (eq. 8), the Taylor sum (eq. 6), shading, trapezoid over λ (eq. 9).
#[derive(Debug, Clone)]
pub struct Reference {
    pub terms: Arc<TaylorTerms>,
    pub shading: Shading,
    pub spectral: SpectralSetup,
}

impl Reference {
    /// `A(λ)` for the given directions (eq. 6 with eq. 8), using `scratch` of length `N + 1`.
    pub fn amplitude(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3, scratch: &mut [Complex64]) -> Complex64 {
        let [u, v, w] = uvw(wi, wr);
        let k = std::f64::consts::TAU / wavelength_nm;
        self.terms.windowed(-u / wavelength_nm, -v / wavelength_nm, scratch);
        // Σ_n (k w)^n / n! F_n by Horner's rule.
        let x = k * w;
        let n = self.terms.n_max;
        let mut acc = scratch[n];
        for m in (0..n).rev() {
            acc = acc * (x / (m + 1) as f64) + scratch[m];
        }
        acc
    }
}

impl Evaluator for Reference {
    fn name(&self) -> &'static str {
        "reference"
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        let mut scratch = vec![Complex64::new(0.0, 0.0); self.terms.n_max + 1];
        let a = self.amplitude(wavelength_nm, wi, wr, &mut scratch);
        Some(self.shading.factor(wavelength_nm, wi, wr) * a.norm_sqr())
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        if wi[2] <= 0.0 || wr[2] <= 0.0 {
            return Xyz::default();
        }
        let mut scratch = vec![Complex64::new(0.0, 0.0); self.terms.n_max + 1];
        let lambda_independent = !self.shading.fresnel.depends_on_wavelength();
        let c0 = self.shading.factor(500.0, wi, wr);
        let mut acc = [0.0; 3];
        for (&l, wt) in self.spectral.wavelengths().iter().zip(self.spectral.weights.weights()) {
            let a2 = self.amplitude(l, wi, wr, &mut scratch).norm_sqr();
            let rho = a2 * if lambda_independent { c0 } else { self.shading.factor(l, wi, wr) };
            for c in 0..3 {
                acc[c] += wt[c] * rho;
            }
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }
}

/// The yardstick (the paper's "benchmark implementation", sec. 6.3): the coherence-windowed Fourier transform
/// of `p = exp(i k w h)` summed directly over the height samples at exactly the frequency each `(λ, ω_i, ω_r)`
/// needs — no Taylor series, no DFT grid:
/// `A(λ) = Σ_j g_j exp(i (2π/λ) D_j) / Σ_j g_j`, `D_j = w h_j + u x_j + v y_j` (PHYSICS.md's sign), with the
/// Gaussian window `g` (`4σ_s` = coherence length) centred on the patch and limited to it.
///
/// Speed: `D_j` does not depend on λ, so on a grid uniform in wavenumber `1/λ` the phasors of successive
/// wavelengths follow by one complex multiplication: one `sin_cos` per sample and direction pair instead of one
/// per sample and wavelength. The spectral integral uses that grid (trapezoid rule, twice as many samples as
/// the reference's 5 nm grid by default).
#[derive(Debug, Clone)]
pub struct GroundTruth {
    /// Sample positions relative to the patch centre and heights (nm), and window weights normalised to Σ g = 1.
    x: Vec<f64>,
    y: Vec<f64>,
    h: Vec<f64>,
    g: Vec<f64>,
    dx: f64,
    dy: f64,
    pub shading: Shading,
    /// Wavenumbers `1/λ` (1/nm), uniform, and their XYZ weights.
    wavenumbers: Vec<f64>,
    weights: SpectralWeights,
}

impl GroundTruth {
    /// Prepares the direct evaluation; `spectral_samples` points uniform in `1/λ` over the setup's range.
    pub fn new(
        patch: &Patch,
        coherence_nm: f64,
        shading: Shading,
        spectral: &SpectralSetup,
        spectral_samples: usize,
    ) -> Result<Self, DiffractionError> {
        if !(coherence_nm.is_finite() && coherence_nm > 0.0) {
            return Err(DiffractionError::Invalid(format!("coherence length {coherence_nm} nm must be positive")));
        }
        if spectral_samples < 2 {
            return Err(DiffractionError::Invalid("the ground truth needs at least two wavelengths".into()));
        }
        let sigma_s = coherence_nm / 4.0;
        let (xc, yc) = ((patch.cols - 1) as f64 * patch.dx / 2.0, (patch.rows - 1) as f64 * patch.dy / 2.0);
        let (mut x, mut y, mut g) = (Vec::new(), Vec::new(), Vec::new());
        for j in 0..patch.rows {
            for i in 0..patch.cols {
                let (px, py) = (i as f64 * patch.dx - xc, j as f64 * patch.dy - yc);
                x.push(px);
                y.push(py);
                g.push((-(px * px + py * py) / (2.0 * sigma_s * sigma_s)).exp());
            }
        }
        let gs: f64 = g.iter().sum();
        g.iter_mut().for_each(|v| *v /= gs);
        // Samples where the window has fallen below 1e-12 of its peak (beyond 7.4 σ_s) are left out of the sum:
        // together they change A by less than 1e-12 × (their count × peak weight), far below the f64 rounding
        // of a million-term sum, and with a window smaller than the patch they are most of the work (a
        // quarter-patch coherence length keeps 67 % of the samples). The normalisation above still counts them.
        let cut = 1e-12 * g.iter().fold(0.0f64, |m, &v| m.max(v));
        let keep: Vec<usize> = (0..g.len()).filter(|&k| g[k] >= cut).collect();
        let pick = |v: &[f64]| keep.iter().map(|&k| v[k]).collect::<Vec<f64>>();
        let (x, y, h, g) = (pick(&x), pick(&y), pick(&patch.heights), pick(&g));
        let lam = spectral.wavelengths();
        let (s_lo, s_hi) = (1.0 / lam[lam.len() - 1], 1.0 / lam[0]);
        let wavenumbers: Vec<f64> =
            (0..spectral_samples).map(|k| s_lo + (s_hi - s_lo) * k as f64 / (spectral_samples - 1) as f64).collect();
        let mut grid: Vec<f64> = wavenumbers.iter().map(|s| 1.0 / s).collect();
        grid.reverse(); // increasing λ
        let weights = SpectralWeights::new(&grid, spectral.illuminant, spectral.observer);
        Ok(Self { x, y, h, g, dx: patch.dx, dy: patch.dy, shading, wavenumbers, weights })
    }

    fn nyquist_ok(&self, u: f64, v: f64, wavelength_nm: f64) -> bool {
        (u / wavelength_nm).abs() <= 0.5 / self.dx && (v / wavelength_nm).abs() <= 0.5 / self.dy
    }

    /// `A` at each of the given wavenumbers (1/nm), equally spaced, by the phasor recurrence.
    fn amplitudes(&self, wi: Vec3, wr: Vec3, s0: f64, ds: f64, count: usize) -> Vec<Complex64> {
        let [u, v, w] = uvw(wi, wr);
        let mut acc = vec![Complex64::new(0.0, 0.0); count];
        let tau = std::f64::consts::TAU;
        // Four samples at a time: four independent phasor recurrences keep the multipliers busy.
        const LANES: usize = 4;
        let n = self.h.len();
        let mut j = 0;
        while j < n {
            let lanes = LANES.min(n - j);
            let mut z = [Complex64::new(0.0, 0.0); LANES];
            let mut r = [Complex64::new(1.0, 0.0); LANES];
            for l in 0..lanes {
                let k = j + l;
                let d = w * self.h[k] + u * self.x[k] + v * self.y[k];
                let (s, c) = (tau * s0 * d).sin_cos();
                let (rs, rc) = (tau * ds * d).sin_cos();
                z[l] = Complex64::new(c * self.g[k], s * self.g[k]);
                r[l] = Complex64::new(rc, rs);
            }
            for a in acc.iter_mut() {
                *a += (z[0] + z[1]) + (z[2] + z[3]);
                for l in 0..LANES {
                    z[l] *= r[l];
                }
            }
            j += LANES;
        }
        for (k, a) in acc.iter_mut().enumerate() {
            let lambda = 1.0 / (s0 + ds * k as f64);
            if !self.nyquist_ok(u, v, lambda) {
                *a = Complex64::new(0.0, 0.0);
            }
        }
        acc
    }

    /// The same yardstick lit by an arbitrary light spectrum `light(λ)` (a laser, a measured lamp) instead of
    /// the setup's illuminant: the colour weights are rebuilt on the same wavelength grid with
    /// [`SpectralWeights::with_light`] (a mirror at normal incidence keeps `Y = 1`).
    pub fn with_light(mut self, light: impl Fn(f64) -> f64, observer: iridis_color::Observer) -> Self {
        let grid = self.weights.wavelengths_nm().to_vec();
        self.weights = SpectralWeights::with_light(&grid, light, observer);
        self
    }

    /// `A(λ)` at one wavelength.
    pub fn amplitude(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Complex64 {
        self.amplitudes(wi, wr, 1.0 / wavelength_nm, 0.0, 1)[0]
    }
}

impl Evaluator for GroundTruth {
    fn name(&self) -> &'static str {
        "ground-truth"
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        Some(self.shading.factor(wavelength_nm, wi, wr) * self.amplitude(wavelength_nm, wi, wr).norm_sqr())
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        if wi[2] <= 0.0 || wr[2] <= 0.0 {
            return Xyz::default();
        }
        let n = self.wavenumbers.len();
        let ds = self.wavenumbers[1] - self.wavenumbers[0];
        let amps = self.amplitudes(wi, wr, self.wavenumbers[0], ds, n);
        let lambda_independent = !self.shading.fresnel.depends_on_wavelength();
        let c0 = self.shading.factor(500.0, wi, wr);
        let mut acc = [0.0; 3];
        // The weights are in increasing λ, the amplitudes in increasing wavenumber.
        for (k, wt) in self.weights.weights().iter().enumerate() {
            let a = amps[n - 1 - k];
            let l = self.weights.wavelengths_nm()[k];
            let rho = a.norm_sqr() * if lambda_independent { c0 } else { self.shading.factor(l, wi, wr) };
            for c in 0..3 {
                acc[c] += wt[c] * rho;
            }
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }
}
