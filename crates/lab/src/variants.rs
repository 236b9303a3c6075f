//! The thesis' shading variants (Single 2014), for comparison with the reference (FLSS) they derive from.
//!
//! * [`Nmm`] (thesis sec. 4.5.2, Figure 4.11): the spectral integral of eq. 3.33 sampled only at the
//!   wavelengths where a grating of period `d` diffracts towards the pixel, `λ_n = d|u|/n` for the integers
//!   `N_min = d|u|/λ_max ≤ n ≤ d|u|/λ_min = N_max` (and likewise with `v`). The thesis gives no weights for
//!   these non-uniform samples; here each stands for the whole diffraction peak it sits on: a peak of the
//!   windowed spectrum `|G|² = exp(−|Δf|²/σ_f²)` crossed along the ray `f = (u, v)/λ` has
//!   `∫ dλ = √π σ_f λ² / |(u, v)|`, which multiplies the colour-matching density at `λ_n`. Close to the mirror
//!   direction (`|(u, v)| < ε`, where there are too few orders) the thesis returns white; here the full
//!   reference integral is used instead. The spectral reflectance is the reference's, so on the test bench NMM
//!   and FLSS agree (as in thesis Table 5.1).
//! * [`Pq`] (thesis sec. 3.6, 4.5.3, Algorithm 5, App. C.2): the patch of size `T₁ × T₂` is assumed repeated
//!   `N₁ × N₂` times, so its spectrum is multiplied by `Σ_{n=0}^{N−1} e^{−iωnT}` per axis (eq. 3.38–3.41) and
//!   the DTFT between DFT bins is recovered by sinc interpolation over the one-neighbourhood (eq. 3.43,
//!   Algorithm 5). Here `N = round(coherence / T)` (at least 1) replaces the coherence window, the Dirichlet
//!   factor is normalised by `N` (a mirror keeps ρ = 1), and its modulus is taken in closed form,
//!   `|sin(NωT/2) / sin(ωT/2)|` — the thesis' eq. 3.42 writes the imaginary part of the product of two
//!   complex numbers as `p₁p₂ + q₁q₂`, which is not the product; the modulus is what Algorithm 5 uses.

use std::sync::Arc;

use iridis_color::spectrum::{interpolate_linear, trapezoid_weights};
use iridis_color::Xyz;
use iridis_diffraction::geometry::{uvw, Shading, Vec3};
use iridis_diffraction::{Evaluator, Reference, SpectralSetup, TaylorTerms};
use num_complex::Complex64;

use crate::LabError;

/// The NMM variant: the reference evaluated only at the grating's diffraction wavelengths.
#[derive(Debug, Clone)]
pub struct Nmm {
    pub reference: Reference,
    /// Grating periods along x and y (nm); an axis without one contributes no wavelengths.
    pub period_x: Option<f64>,
    pub period_y: Option<f64>,
    /// Radius in (u, v) around the mirror direction handled by the full integral.
    pub epsilon_uv: f64,
    /// Colour-matching densities per nm on the reference's grid (weights / trapezoid widths), per channel.
    density: Arc<[Vec<f64>; 3]>,
}

impl Nmm {
    pub fn new(reference: Reference, period_x: Option<f64>, period_y: Option<f64>) -> Result<Self, LabError> {
        for p in [period_x, period_y].into_iter().flatten() {
            if !(p.is_finite() && p > 0.0) {
                return Err(LabError::invalid(format!("NMM period {p} nm must be positive")));
            }
        }
        if period_x.is_none() && period_y.is_none() {
            return Err(LabError::invalid(
                "the NMM variant needs a grating period along x or y, and the surface has none (it is flat); give one \
                 with --period where the command has it",
            ));
        }
        let grid = reference.spectral.wavelengths();
        let trap = trapezoid_weights(grid);
        let weights = reference.spectral.weights.weights();
        let channel = |c: usize| -> Vec<f64> {
            weights.iter().zip(&trap).map(|(w, &t)| if t > 0.0 { w[c] / t } else { 0.0 }).collect()
        };
        let density = [channel(0), channel(1), channel(2)];
        Ok(Self { reference, period_x, period_y, epsilon_uv: 0.02, density: Arc::new(density) })
    }

    /// The selected wavelengths for `(u, v)` (thesis eq. after 4.13), inside the reference's range.
    pub fn wavelengths(&self, u: f64, v: f64) -> Vec<f64> {
        let grid = self.reference.spectral.wavelengths();
        let (lmin, lmax) = (grid[0], grid[grid.len() - 1]);
        let mut out = Vec::new();
        for (d, c) in [(self.period_x, u.abs()), (self.period_y, v.abs())] {
            let Some(d) = d else { continue };
            if c < 1e-12 {
                continue;
            }
            let (n0, n1) = ((d * c / lmax).ceil() as i64, (d * c / lmin).floor() as i64);
            for n in n0.max(1)..=n1 {
                out.push(d * c / n as f64);
            }
        }
        out.sort_by(|a, b| a.total_cmp(b));
        out.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        out
    }

    fn density_at(&self, l: f64, c: usize) -> f64 {
        let grid = self.reference.spectral.wavelengths();
        if l < grid[0] || l > grid[grid.len() - 1] {
            return 0.0;
        }
        interpolate_linear(grid, &self.density[c], l)
    }
}

impl Evaluator for Nmm {
    fn name(&self) -> &'static str {
        "nmm"
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        self.reference.reflectance(wavelength_nm, wi, wr)
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        if wi[2] <= 0.0 || wr[2] <= 0.0 {
            return Xyz::default();
        }
        let [u, v, _] = uvw(wi, wr);
        let r = u.hypot(v);
        if r < self.epsilon_uv {
            return self.reference.xyz(wi, wr);
        }
        let sigma_f = self.reference.terms.sigma_f;
        let mut acc = [0.0; 3];
        for l in self.wavelengths(u, v) {
            let rho = self.reference.reflectance(l, wi, wr).unwrap_or(0.0);
            let width = std::f64::consts::PI.sqrt() * sigma_f * l * l / r;
            for (c, a) in acc.iter_mut().enumerate() {
                *a += self.density_at(l, c) * width * rho;
            }
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }
}

/// The PQ variant: periodic replication of the patch with sinc interpolation between DFT bins.
#[derive(Debug, Clone)]
pub struct Pq {
    pub terms: Arc<TaylorTerms>,
    pub shading: Shading,
    pub spectral: SpectralSetup,
    /// Replicas `N₁`, `N₂` along x and y.
    pub replicas: (usize, usize),
}

fn sinc_pi(x: f64) -> f64 {
    if x.abs() < 1e-9 {
        1.0
    } else {
        (std::f64::consts::PI * x).sin() / (std::f64::consts::PI * x)
    }
}

/// `|Σ_{n=0}^{N−1} e^{−2πi x n}| / N = |sin(πNx) / (N sin(πx))|`, `x` in cycles per replica.
fn dirichlet(x: f64, n: usize) -> f64 {
    let s = (std::f64::consts::PI * x).sin();
    if s.abs() < 1e-12 {
        1.0
    } else {
        ((std::f64::consts::PI * n as f64 * x).sin() / (n as f64 * s)).abs()
    }
}

impl Pq {
    /// Replicas from the coherence length: `N = max(1, round(coherence / T))` per axis.
    pub fn new(terms: Arc<TaylorTerms>, shading: Shading, spectral: SpectralSetup) -> Self {
        let (tx, ty) = (terms.cols as f64 * terms.dx, terms.rows as f64 * terms.dy);
        let n = |t: f64| ((terms.coherence_nm / t).round() as usize).max(1);
        let replicas = (n(tx), n(ty));
        Self { terms, shading, spectral, replicas }
    }

    /// The PQ amplitude at wavelength λ (modulus is what matters).
    pub fn amplitude(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> f64 {
        let t = &self.terms;
        let [u, v, w] = uvw(wi, wr);
        let (fx, fy) = (-u / wavelength_nm, -v / wavelength_nm);
        if !t.within_nyquist(fx, fy) {
            return 0.0;
        }
        let (px, py) = (fx * t.cols as f64 * t.dx, fy * t.rows as f64 * t.dy);
        let (s0, t0) = (px.round() as i64, py.round() as i64);
        let (smin, smax) = (-(((t.cols - 1) / 2) as i64), (t.cols / 2) as i64);
        let (tmin, tmax) = (-(((t.rows - 1) / 2) as i64), (t.rows / 2) as i64);
        let n = t.n_max;
        let mut f = vec![Complex64::new(0.0, 0.0); n + 1];
        for tt in (t0 - 1).max(tmin)..=(t0 + 1).min(tmax) {
            let wy = sinc_pi(py - tt as f64);
            for ss in (s0 - 1).max(smin)..=(s0 + 1).min(smax) {
                let wgt = sinc_pi(px - ss as f64) * wy;
                let bin = t.bin(ss.rem_euclid(t.cols as i64) as usize, tt.rem_euclid(t.rows as i64) as usize);
                for (o, c) in f.iter_mut().zip(bin) {
                    *o += c * wgt;
                }
            }
        }
        let x = std::f64::consts::TAU / wavelength_nm * w;
        let mut acc = f[n];
        for m in (0..n).rev() {
            acc = acc * (x / (m + 1) as f64) + f[m];
        }
        acc.norm() * dirichlet(px, self.replicas.0) * dirichlet(py, self.replicas.1)
    }
}

impl Evaluator for Pq {
    fn name(&self) -> &'static str {
        "pq"
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        Some(self.shading.factor(wavelength_nm, wi, wr) * self.amplitude(wavelength_nm, wi, wr).powi(2))
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        crate::stam::spectral_xyz(self, &self.spectral, &self.shading, wi, wr)
    }
}
