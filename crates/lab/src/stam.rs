//! Stam's (1999) analytic diffraction models, as the paper (sec. 6.3) restates and adapts them, behind the same
//! [`Evaluator`] interface as the measured-height-field methods, so every command can use them.
//!
//! Both return the relative reflectance of PHYSICS.md, `ρ_λ = C(ω_i, ω_r) · S(f)`, `f = (−u/λ, −v/λ)`, with the
//! same shading factor `C` and the normalisation in which a flat mirror gives `S = 1` at the mirror direction.
//!
//! * [`StamPeriodic`] — "periodic-like" surfaces: identical bumps on a regular lattice of periods `Δx × Δy`
//!   (the paper's variant with a regular arrangement along y instead of Stam's Poisson distribution, paper
//!   eq. 14–15). The spectral density is a sum of delta functions at the lattice orders,
//!   `S = Σ_{n,m} |c_{nm}|² δ(u/λ + n/Δx) δ(v/λ + m/Δy)` (eq. 14 up to the factor that turns the deltas into our
//!   normalisation), `c_{nm}` the Fourier coefficient of `p = exp(i k w h)` over one lattice cell. The paper's
//!   eq. 15 is the first-order (Born) form of `|c_{nm}|²`, `(a b / Δx Δy)² |Φ(2πna/Δx, 2πmb/Δy)|²` times
//!   `(k w H)²`; here `c_{nm}` is the exact Kirchhoff coefficient for the bump's closed form (rectangular box
//!   or triangular ridge), which reduces to eq. 15 when `k w H ≪ 1` ([`StamPeriodic::born`] gives that form).
//!   The deltas are realised by the paper's ε selection of wavelengths: the order numbers `n = −u Δx / λ` and
//!   `m = −v Δy / λ` must both lie within `ε` of integers, otherwise λ contributes nothing (paper sec. 6.3,
//!   Figure 11a–c: ε = 0.01 leaves gaps in the colour bands). The paper finds those wavelengths from the
//!   grating condition of each order, not on a wavelength grid; so does [`StamPeriodic::orders`]: for order
//!   `(n, m)` the condition `|−uΔx/λ − n| ≤ ε` holds on the interval `λ ∈ [a/(n+ε), a/(n−ε)]`, `a = −uΔx`,
//!   around the exact solution `λ_n = a/n` of `n λ = −u Δx` (the grating equation), likewise for `m`; the
//!   order shows on the intersection, and the colour integrates the weights over it in closed-form intervals
//!   ([`StamPeriodic::xyz`]) — the continuum limit of testing ε at grid wavelengths, which made the orders
//!   seen depend on Δλ (an order whose ε-band falls between two grid wavelengths vanished).
//! * [`StamGaussian`] — a Gaussian random surface (Stam eq. 12 as the paper uses it): for jointly Gaussian
//!   heights `⟨e^{ikw(h(r₁) − h(r₂))}⟩ = e^{−g(1 − C(r₁ − r₂))}`, `g = (k w σ_h)²`, `C` the normalised
//!   correlation function, so `S = e^{−g} Σ_m g^m/m! · FT{C^m}`. As in the paper, `C` is the measured height
//!   field's own (circular) autocorrelation, its transform the DFT, and the DFT impulses are turned into a
//!   continuous spectrum by the coherence window — at the level of power, `|G|² = exp(−|f|²/σ_f²)`, since
//!   the model only knows expected powers.

use std::sync::Arc;

use iridis_color::Xyz;
use iridis_diffraction::geometry::{uvw, Shading, Vec3};
use iridis_diffraction::{Evaluator, Patch, SpectralSetup};
use iridis_fft::dft2;
use num_complex::Complex64;

use crate::analysis::{dominant_period, Axis};
use crate::LabError;

/// The shape of Stam's bump.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bump {
    /// A box: height `H` over `|x| < a/2, |y| < b/2` (Stam 1999, Figure 6 left; paper Figure 11a–b).
    Rectangular,
    /// A triangular ridge: `H (1 − 2|x|/a)` over `|x| < a/2, |y| < b/2`, the same bounding box (paper
    /// Figure 11c).
    Triangular,
}

impl Bump {
    pub fn name(self) -> &'static str {
        match self {
            Bump::Rectangular => "rectangular",
            Bump::Triangular => "triangular",
        }
    }
}

/// A regular lattice of identical bumps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lattice {
    /// Period along x (nm).
    pub period_x: f64,
    /// Period along y (nm); `None` for ridges that run along y without end (a 1-D grating).
    pub period_y: Option<f64>,
    /// Bump width `a` along x and length `b` along y (nm); `b` is ignored without `period_y`.
    pub width: f64,
    pub length: f64,
    /// Bump height `H` (nm).
    pub height: f64,
    pub bump: Bump,
}

/// `sin x / x`.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-8 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// `∫_0^L e^{iγx} dx`.
fn e_int(gamma: f64, len: f64) -> Complex64 {
    if (gamma * len).abs() < 1e-9 {
        Complex64::new(len, 0.5 * gamma * len * len)
    } else {
        (Complex64::new(0.0, gamma * len).exp() - 1.0) / Complex64::new(0.0, gamma)
    }
}

impl Lattice {
    /// Fraction of a cell the bump covers along x and y.
    fn fractions(&self) -> (f64, f64) {
        (self.width / self.period_x, self.period_y.map(|p| self.length / p).unwrap_or(1.0))
    }

    /// Variance of the unit-height lattice profile (for matching a measured RMS height).
    pub fn unit_variance(&self) -> f64 {
        let (fx, fy) = self.fractions();
        let f = fx * fy;
        match self.bump {
            Bump::Rectangular => f * (1.0 - f),
            // Tent in x: mean f/2, mean square f/3.
            Bump::Triangular => f / 3.0 - f * f / 4.0,
        }
    }

    /// The factor of a coefficient along y: `(b/Δy) sinc(π m b/Δy)`, `fy = b/Δy`; without a y period the ridge
    /// fills the cell (`δ_{m0}`).
    fn y_factor(&self, m: i64, fy: f64) -> f64 {
        match self.period_y {
            Some(_) => fy * sinc(std::f64::consts::PI * m as f64 * fy),
            None => {
                if m == 0 {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }

    /// The Fourier coefficient `c_{nm}` of `p = exp(i α h/H)` over one cell, `α = k w H` (exact Kirchhoff form):
    /// `c_{nm} = δ_{n0} δ_{m0} + (1/(Δx Δy)) ∫∫_bump (e^{iα h/H} − 1) e^{−2πi(nx/Δx + my/Δy)} dx dy`.
    pub fn coefficient(&self, n: i64, m: i64, alpha: f64) -> Complex64 {
        let (fx, fy) = self.fractions();
        let (a, dx) = (self.width, self.period_x);
        let y = self.y_factor(m, fy);
        let beta = std::f64::consts::TAU * n as f64 / dx;
        let x = match self.bump {
            Bump::Rectangular => (Complex64::new(0.0, alpha).exp() - 1.0) * fx * sinc(beta * a / 2.0),
            Bump::Triangular => {
                // ∫_{−a/2}^{a/2} e^{iα(1 − 2|x|/a)} e^{−iβx} dx = e^{iα} [E(−2α/a − β) + E(−2α/a + β)],
                // E(γ) = ∫_0^{a/2} e^{iγx} dx; minus the box ∫ e^{−iβx} dx = a sinc(βa/2).
                let g = 2.0 * alpha / a;
                let tent = Complex64::new(0.0, alpha).exp() * (e_int(-g - beta, a / 2.0) + e_int(-g + beta, a / 2.0));
                (tent - a * sinc(beta * a / 2.0)) / dx
            }
        };
        let delta = if n == 0 && m == 0 { 1.0 } else { 0.0 };
        Complex64::new(delta, 0.0) + x * y
    }

    /// The first-order (Born) coefficient of paper eq. 15: `i α · (1/(ΔxΔy)) ∫∫ h/H e^{−2πi(…)}` (plus the
    /// mirror's 1 at n = m = 0), valid for `α = k w H ≪ 1`.
    pub fn born_coefficient(&self, n: i64, m: i64, alpha: f64) -> Complex64 {
        let (fx, fy) = self.fractions();
        let y = self.y_factor(m, fy);
        let phi = match self.bump {
            Bump::Rectangular => fx * sinc(std::f64::consts::PI * n as f64 * fx),
            // FT of a tent of base a: (a/2) sinc²(βa/4).
            Bump::Triangular => 0.5 * fx * sinc(std::f64::consts::PI * n as f64 * fx / 2.0).powi(2),
        };
        let delta = if n == 0 && m == 0 { 1.0 } else { 0.0 };
        Complex64::new(delta, alpha * phi * y)
    }
}

/// One diffraction order seen in a direction: its numbers, the exact wavelength of its grating condition, and
/// the band of wavelengths (within the setup's range) over which both order numbers are within ε of `(n, m)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Order {
    pub n: i64,
    pub m: i64,
    /// `λ` with `n λ = −u Δx` (or `m λ = −v Δy` when `n = 0`); `None` when neither has a solution (`n = m = 0`).
    pub wavelength_nm: Option<f64>,
    /// `[lo, hi]` (nm), `lo < hi`.
    pub band_nm: (f64, f64),
}

/// The wavelengths at which `a/λ` lies within `ε` of the integer `n`: an interval (possibly unbounded above).
fn order_interval(a: f64, n: i64, eps: f64) -> Option<(f64, f64)> {
    if n == 0 {
        return Some(if a == 0.0 { (0.0, f64::INFINITY) } else { (a.abs() / eps, f64::INFINITY) });
    }
    let nf = n as f64;
    if a == 0.0 || a.signum() != nf.signum() {
        return None;
    }
    let (e1, e2) = (a / (nf + eps), a / (nf - eps));
    Some((e1.min(e2), e1.max(e2)))
}

/// The integers `n` for which `a/λ` comes within `ε` of `n` for some `λ` in `[lo, hi]`.
fn order_range(a: f64, lo: f64, hi: f64, eps: f64) -> std::ops::RangeInclusive<i64> {
    let (x, y) = (a / lo, a / hi);
    ((x.min(y) - eps).ceil() as i64)..=((x.max(y) + eps).floor() as i64)
}

/// Stam's periodic-bump model with the paper's ε selection of wavelengths.
#[derive(Debug, Clone)]
pub struct StamPeriodic {
    pub lattice: Lattice,
    /// Tolerance of the order numbers (paper: 0.01).
    pub epsilon: f64,
    /// Coherence length (nm): the scale of the selection along y for a lattice without a y period.
    pub coherence_nm: f64,
    /// Use the first-order (Born) coefficients of eq. 15 instead of the exact Kirchhoff ones.
    pub born: bool,
    pub shading: Shading,
    pub spectral: SpectralSetup,
}

impl StamPeriodic {
    /// Fits the model to a measured patch as the paper does for Elaphe: the dominant periods along x and y
    /// ([`dominant_period`]; along y only if it holds at least 1 % of the x direction's power), bump width and
    /// length half of the periods ("height and width as half of the respective periodicities", Figure 11),
    /// and the height `H` that gives the lattice the patch's RMS height.
    pub fn fit(
        patch: &Patch,
        bump: Bump,
        epsilon: f64,
        coherence_nm: f64,
        shading: Shading,
        spectral: SpectralSetup,
    ) -> Result<Self, LabError> {
        let px = dominant_period(patch, Axis::X).ok_or_else(|| {
            LabError::invalid("the surface does not vary along x; Stam's periodic model needs a period along x")
        })?;
        let py = dominant_period(patch, Axis::Y);
        let power = |axis| crate::analysis::periodogram(patch, axis)[1..].iter().sum::<f64>();
        let period_y = match py {
            Some(p) if power(Axis::Y) >= 0.01 * power(Axis::X) => Some(p.period_nm),
            _ => None,
        };
        let rms = (patch.heights.iter().map(|h| h * h).sum::<f64>() / patch.heights.len() as f64).sqrt();
        let mut lattice = Lattice {
            period_x: px.period_nm,
            period_y,
            width: px.period_nm / 2.0,
            length: period_y.unwrap_or(1.0) / 2.0,
            height: 1.0,
            bump,
        };
        lattice.height = rms / lattice.unit_variance().sqrt();
        Self::new(lattice, epsilon, coherence_nm, shading, spectral)
    }

    pub fn new(
        lattice: Lattice,
        epsilon: f64,
        coherence_nm: f64,
        shading: Shading,
        spectral: SpectralSetup,
    ) -> Result<Self, LabError> {
        let ok = |v: f64| v.is_finite() && v > 0.0;
        if !(ok(lattice.period_x)
            && ok(lattice.width)
            && lattice.width <= lattice.period_x
            && lattice.height.is_finite())
        {
            return Err(LabError::invalid(format!("bad lattice {lattice:?}: need 0 < width ≤ period")));
        }
        if let Some(py) = lattice.period_y {
            if !(ok(py) && ok(lattice.length) && lattice.length <= py) {
                return Err(LabError::invalid(format!("bad lattice {lattice:?}: need 0 < length ≤ period")));
            }
        }
        if !(epsilon.is_finite() && epsilon > 0.0 && epsilon <= 0.5) {
            return Err(LabError::invalid(format!("ε = {epsilon} must be in (0, 0.5]")));
        }
        if !ok(coherence_nm) {
            return Err(LabError::invalid(format!("coherence length {coherence_nm} nm must be positive")));
        }
        Ok(Self { lattice, epsilon, coherence_nm, born: false, shading, spectral })
    }

    /// The orders seen from `(wi, wr)` within the wavelength range `[lo, hi]` (nm), each with its grating
    /// wavelength and ε band (see the module's notes). Without a y period the ridge's transform along y is
    /// `δ_{m0}`, and the selection along y uses the coherence length as the scale (as [`Self::density`]).
    pub fn orders(&self, wi: Vec3, wr: Vec3, lo: f64, hi: f64) -> Vec<Order> {
        let [u, v, _] = uvw(wi, wr);
        let (ax, ay) = (-u * self.lattice.period_x, -v * self.lattice.period_y.unwrap_or(self.coherence_nm));
        let ms = if self.lattice.period_y.is_some() { order_range(ay, lo, hi, self.epsilon) } else { 0..=0 };
        let mut out = Vec::new();
        for n in order_range(ax, lo, hi, self.epsilon) {
            let Some((xl, xh)) = order_interval(ax, n, self.epsilon) else { continue };
            for m in ms.clone() {
                let Some((yl, yh)) = order_interval(ay, m, self.epsilon) else { continue };
                let (bl, bh) = (xl.max(yl).max(lo), xh.min(yh).min(hi));
                if bh <= bl {
                    continue;
                }
                let wavelength_nm = if n != 0 {
                    Some(ax / n as f64)
                } else if m != 0 {
                    Some(ay / m as f64)
                } else {
                    None
                };
                out.push(Order { n, m, wavelength_nm, band_nm: (bl, bh) });
            }
        }
        out
    }

    /// The spectral density at frequency `f` (cycles/nm) for `α = k w H`: `|c_{nm}|²` when both order numbers
    /// are within ε of integers `(n, m)`, else 0.
    pub fn density(&self, fx: f64, fy: f64, alpha: f64) -> f64 {
        let nr = fx * self.lattice.period_x;
        let n = nr.round();
        if (nr - n).abs() > self.epsilon {
            return 0.0;
        }
        let mr = fy * self.lattice.period_y.unwrap_or(self.coherence_nm);
        let m = mr.round();
        if (mr - m).abs() > self.epsilon {
            return 0.0;
        }
        let c = if self.born {
            self.lattice.born_coefficient(n as i64, m as i64, alpha)
        } else {
            self.lattice.coefficient(n as i64, m as i64, alpha)
        };
        c.norm_sqr()
    }
}

impl Evaluator for StamPeriodic {
    fn name(&self) -> &'static str {
        match self.lattice.bump {
            Bump::Rectangular => "stam-periodic",
            Bump::Triangular => "stam-periodic-triangular",
        }
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        let [u, v, w] = uvw(wi, wr);
        let alpha = std::f64::consts::TAU / wavelength_nm * w * self.lattice.height;
        Some(self.shading.factor(wavelength_nm, wi, wr) * self.density(-u / wavelength_nm, -v / wavelength_nm, alpha))
    }
    /// `X = ∫ w̄_x(λ) ρ_λ dλ` over each order's ε band ([`Self::orders`]), `w̄` the colour weights per nm
    /// (the setup's weights over their trapezoid widths, linear between grid wavelengths), by two-point
    /// Gauss–Legendre on pieces at most 1 nm wide: the grid only carries the weights' shape, never decides which
    /// orders show.
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        if wi[2] <= 0.0 || wr[2] <= 0.0 {
            return Xyz::default();
        }
        let grid = self.spectral.wavelengths();
        let (lo, hi) = (grid[0], grid[grid.len() - 1]);
        let trap = iridis_color::spectrum::trapezoid_weights(grid);
        let weights = self.spectral.weights.weights();
        let density = |l: f64| -> [f64; 3] {
            let k = grid.partition_point(|&g| g <= l).clamp(1, grid.len() - 1);
            let t = ((l - grid[k - 1]) / (grid[k] - grid[k - 1])).clamp(0.0, 1.0);
            let d = |j: usize, c: usize| weights[j][c] / trap[j];
            [0, 1, 2].map(|c| d(k - 1, c) * (1.0 - t) + d(k, c) * t)
        };
        let [_, _, w] = uvw(wi, wr);
        let mut acc = [0.0; 3];
        let g = 0.5 / 3f64.sqrt();
        for o in self.orders(wi, wr, lo, hi) {
            let (a, b) = o.band_nm;
            let pieces = ((b - a) / 1.0).ceil().max(1.0) as usize;
            let h = (b - a) / pieces as f64;
            for p in 0..pieces {
                let mid = a + (p as f64 + 0.5) * h;
                for l in [mid - g * h, mid + g * h] {
                    let alpha = std::f64::consts::TAU / l * w * self.lattice.height;
                    let c = if self.born {
                        self.lattice.born_coefficient(o.n, o.m, alpha)
                    } else {
                        self.lattice.coefficient(o.n, o.m, alpha)
                    };
                    let rho = self.shading.factor(l, wi, wr) * c.norm_sqr();
                    let d = density(l);
                    for ch in 0..3 {
                        acc[ch] += 0.5 * h * d[ch] * rho;
                    }
                }
            }
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }
}

/// `X = Σ_λ w_x(λ) ρ_λ` on the setup's grid (paper eq. 9) for a model with a spectral reflectance.
pub(crate) fn spectral_xyz(e: &dyn Evaluator, spectral: &SpectralSetup, _shading: &Shading, wi: Vec3, wr: Vec3) -> Xyz {
    if wi[2] <= 0.0 || wr[2] <= 0.0 {
        return Xyz::default();
    }
    let mut acc = [0.0; 3];
    for (&l, wt) in spectral.wavelengths().iter().zip(spectral.weights.weights()) {
        let rho = e.reflectance(l, wi, wr).unwrap_or(0.0);
        if rho != 0.0 {
            for c in 0..3 {
                acc[c] += wt[c] * rho;
            }
        }
    }
    Xyz::new(acc[0], acc[1], acc[2])
}

/// Stam's Gaussian random surface built from a height field's correlation function, with the coherence window.
#[derive(Debug, Clone)]
pub struct StamGaussian {
    rows: usize,
    cols: usize,
    lx: f64,
    ly: f64,
    dx: f64,
    dy: f64,
    /// RMS height `σ_h` (nm).
    pub sigma_h: f64,
    /// `D_m[bin] = DFT{C^m}/samples` (real), `m = 0..=M`, interleaved per bin.
    d: Arc<Vec<f64>>,
    m_max: usize,
    sigma_f: f64,
    pub shading: Shading,
    pub spectral: SpectralSetup,
}

impl StamGaussian {
    /// Correlation function `C = R/σ_h²` from the patch's circular autocorrelation `R = IDFT(|DFT h|²)/N`,
    /// the DFTs of `C^m` for `m = 0..=M` with `M` past the Poisson tail of `g_max = (2·2π/λ_min·σ_h)²`.
    pub fn new(patch: &Patch, coherence_nm: f64, shading: Shading, spectral: SpectralSetup) -> Result<Self, LabError> {
        patch.check_coherence(coherence_nm)?;
        let (rows, cols) = (patch.rows, patch.cols);
        let n = rows * cols;
        let sigma2 = patch.heights.iter().map(|h| h * h).sum::<f64>() / n as f64;
        let sigma_h = sigma2.sqrt();
        let lambda_min = spectral.wavelengths()[0];
        let g_max = (2.0 * std::f64::consts::TAU / lambda_min * sigma_h).powi(2);
        let m_max = ((g_max + 10.0 * g_max.sqrt() + 10.0).ceil() as usize).min(400);
        if (n as f64) * (m_max + 1) as f64 * 8.0 > 8e9 {
            return Err(LabError::invalid(format!(
                "{rows}×{cols} samples with {} correlation powers need too much memory; use a smaller patch",
                m_max + 1
            )));
        }
        // Normalised correlation function.
        let mut c: Vec<Complex64> = patch.heights.iter().map(|&h| Complex64::new(h, 0.0)).collect();
        dft2(&mut c, rows, cols, false);
        c.iter_mut().for_each(|z| *z = Complex64::new(z.norm_sqr(), 0.0));
        dft2(&mut c, rows, cols, true);
        let corr: Vec<f64> =
            if sigma2 > 0.0 { c.iter().map(|z| z.re / (n as f64 * n as f64 * sigma2)).collect() } else { vec![0.0; n] };
        let stride = m_max + 1;
        let mut d = vec![0.0; n * stride];
        let mut power: Vec<f64> = vec![1.0; n];
        for m in 0..=m_max {
            let mut buf: Vec<Complex64> = power.iter().map(|&p| Complex64::new(p, 0.0)).collect();
            dft2(&mut buf, rows, cols, false);
            for (bin, z) in buf.iter().enumerate() {
                d[bin * stride + m] = z.re / n as f64;
            }
            power.iter_mut().zip(&corr).for_each(|(p, c)| *p *= c);
        }
        Ok(Self {
            rows,
            cols,
            lx: cols as f64 * patch.dx,
            ly: rows as f64 * patch.dy,
            dx: patch.dx,
            dy: patch.dy,
            sigma_h,
            d: Arc::new(d),
            m_max,
            sigma_f: 1.0 / (std::f64::consts::TAU * coherence_nm / 4.0),
            shading,
            spectral,
        })
    }

    /// Expected windowed power `S(f) = e^{−g} Σ_m g^m/m! Σ_bins D_m exp(−|f − f_bin|²/σ_f²)` at `f` (cycles/nm).
    pub fn density(&self, fx: f64, fy: f64, g: f64) -> f64 {
        if fx.abs() > 0.5 / self.dx || fy.abs() > 0.5 / self.dy {
            return 0.0;
        }
        let r = 2.0 * std::f64::consts::SQRT_2 * self.sigma_f; // exp(−r²/σ_f²) = e^{−8}
        let inv = 1.0 / (self.sigma_f * self.sigma_f);
        let (smin, smax) = (-(((self.cols - 1) / 2) as i64), (self.cols / 2) as i64);
        let (tmin, tmax) = (-(((self.rows - 1) / 2) as i64), (self.rows / 2) as i64);
        let s0 = (((fx - r) * self.lx).ceil() as i64).max(smin);
        let s1 = (((fx + r) * self.lx).floor() as i64).min(smax);
        let t0 = (((fy - r) * self.ly).ceil() as i64).max(tmin);
        let t1 = (((fy + r) * self.ly).floor() as i64).min(tmax);
        let stride = self.m_max + 1;
        // Poisson weights e^{−g} g^m / m!.
        let mut weights = Vec::with_capacity(stride);
        let mut p = (-g).exp();
        for m in 0..stride {
            if m > 0 {
                p *= g / m as f64;
            }
            weights.push(p);
        }
        let mut acc = 0.0;
        for t in t0..=t1 {
            let dfy = fy - t as f64 / self.ly;
            let ti = t.rem_euclid(self.rows as i64) as usize;
            for s in s0..=s1 {
                let dfx = fx - s as f64 / self.lx;
                let d2 = dfx * dfx + dfy * dfy;
                if d2 > r * r {
                    continue;
                }
                let win = (-d2 * inv).exp();
                let si = s.rem_euclid(self.cols as i64) as usize;
                let bin = &self.d[(ti * self.cols + si) * stride..(ti * self.cols + si + 1) * stride];
                let sum: f64 = bin.iter().zip(&weights).map(|(a, b)| a * b).sum();
                acc += win * sum;
            }
        }
        acc.max(0.0)
    }
}

impl Evaluator for StamGaussian {
    fn name(&self) -> &'static str {
        "stam-gaussian"
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        let [u, v, w] = uvw(wi, wr);
        let g = (std::f64::consts::TAU / wavelength_nm * w * self.sigma_h).powi(2);
        Some(self.shading.factor(wavelength_nm, wi, wr) * self.density(-u / wavelength_nm, -v / wavelength_nm, g))
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        spectral_xyz(self, &self.spectral, &self.shading, wi, wr)
    }
}
