//! Diffraction efficiencies of a periodic structure in the scalar (Kirchhoff) model: the height field taken
//! as **one unit cell** of a grating, its extent `(Lx, Ly)` the periods, so that light leaves in discrete
//! orders. What a spectrometer, a goniometer or a rigorous solver measures: the fraction of the incident power
//! in each order (`iridis grating`, docs/diffraction.md, "Order efficiencies").
//!
//! Orders (the convention of docs/PHYSICS.md, "Test bench"): light from `ω_i` (pointing to the light) leaves
//! in order `(m, n)` along `ω_r` with `ω_r,xy = −ω_i,xy + (m λ/Lx, n λ/Ly)`, i.e. `m λ/d = sin θ_i − sin θ_r`
//! in the plane of incidence with `θ_r` positive on the specular side. Only propagating orders (`|ω_r,xy| <
//! 1`) carry power.
//!
//! **Kirchhoff's efficiency** of order `G` (Beckmann's periodic-surface result, the discrete form of the
//! paper's eq. 2–4): the BRDF lobe of the order, `f_r cos θ_r` integrated over its solid angle (the
//! coherence window's `∫G² du dv = λ²/(4πσ_s²)` cancels the radiometric gain `4πσ_s²/λ²`, docs/PHYSICS.md),
//! is
//!
//! `η_G = R(θ_h) · K(ω_i, ω_r) · |c_G(w)|²`,  `K = (1 + ω_i·ω_r)² / (cos θ_i cos θ_r (cos θ_i + cos θ_r)²)`,
//!
//! with `c_G(w)` the Fourier coefficient of `exp(i k w h)` over the unit cell at the order's frequency
//! (`w = −(cos θ_i + cos θ_r)`, `k = 2π/λ`; paper eq. 5–8 without the window, evaluated from the Taylor terms'
//! DFTs) and `R` the Fresnel reflectance at the half-vector angle, per polarisation (s = TE, p = TM, with
//! respect to the plane of `ω_i` and `ω_r`; the scalar model does not mix them).
//!
//! **Energy.** `K` is 1 at the mirror direction but not an energy-conserving weight: at oblique light it
//! grows like `1/cos θ_i` for every other order, so a sine grating's orders sum to 1.25 of the light at 75°
//! (period 1100 nm, amplitude 60 nm) and 2.08 at 150 nm. Every incidence `a` of the grating's channels (the
//! directions `ω_i,xy + G` that its orders couple) and every exit `b` form a square matrix
//! `M[a][b] = K(a, b)|c_{a−b}(w)|²` — for a perfect reflector, the scattering matrix of powers. Lossless
//! scattering makes it doubly stochastic (every row sums to 1: energy; every column too: the reverse light,
//! by reciprocity). [`Normalisation::Energy`] scales it to that, `η = r_a M[a][b] s_b`, with the
//! Sinkhorn–Knopp iteration (Sinkhorn & Knopp, Pacific J. Math. 21, 343, 1967): both energy and reciprocity
//! then hold exactly, a flat mirror keeps `M = I` (Kirchhoff exact at the specular limit), and shallow
//! gratings change by second order in `k h`. It is the discrete, reciprocal form of Harvey–Shack's
//! renormalisation (Harvey & Pfisterer, Opt. Eng. 58, 087105, 2019). [`Normalisation::Kirchhoff`] keeps the
//! printed factor (for comparison).

use num_complex::Complex64;
use rayon::prelude::*;
use serde::Serialize;

use crate::geometry::{dot, FresnelSource, Vec3};
use crate::patch::Patch;
use crate::taylor::{terms_for_bound, Band, TaylorTerms};
use crate::DiffractionError;

/// Bound on the Taylor remainder of `c_G(w)` (`(2k|h|max)^{N+1}/(N+1)!`, docs/PHYSICS.md).
pub const TAYLOR_EPSILON: f64 = 1e-10;

/// Largest number of coupled channels for which the full Sinkhorn scaling runs (its matrix has this many
/// squared entries per wavelength); larger unit cells (a 20 µm scan has ~5000) take the row normalisation.
pub const MAX_SINKHORN_CHANNELS: usize = 600;

/// Most propagating orders a unit cell's model takes at one wavelength: a 100 µm crossed cell at 300 nm has
/// π (L/λ)² ≈ 3.5e5. A wavelength in metres read as nm (5.5e-7 "nm" over a 4 µm cell: 1.7e14 orders) asked for
/// gigabytes and aborted.
pub const MAX_ORDERS: f64 = 4e6;

/// How Kirchhoff's efficiencies are normalised (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Normalisation {
    /// The channel matrix scaled to be doubly stochastic (Sinkhorn–Knopp): energy and reciprocity exact.
    #[default]
    Energy,
    /// Kirchhoff's obliquity factor as printed (Beckmann; Stam's `F²G/w²`): reflects more than it receives
    /// at oblique light.
    Kirchhoff,
}

iridis_color::names! {
    Normalisation {
        Energy => "energy" | "energy-conserving",
        Kirchhoff => "kirchhoff" | "none" | "printed",
    }
    else |s| -> DiffractionError {
        DiffractionError::Invalid(format!(
            "normalisation '{s}': expected energy (the default: energy and reciprocity exact) or kirchhoff \
             (the obliquity factor as printed, not energy-conserving)"
        ))
    }
}

/// Efficiencies for TE (s) and TM (p) incident light and their mean (unpolarised light).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Efficiency {
    pub te: f64,
    pub tm: f64,
    pub unpolarized: f64,
}

impl Efficiency {
    fn new(te: f64, tm: f64) -> Self {
        Self { te, tm, unpolarized: 0.5 * (te + tm) }
    }
    fn add(&mut self, o: Efficiency) {
        self.te += o.te;
        self.tm += o.tm;
        self.unpolarized += o.unpolarized;
    }
}

/// One propagating order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OrderEfficiency {
    pub wavelength_nm: f64,
    pub m: i64,
    pub n: i64,
    /// Polar angle of `ω_r` (degrees from the normal).
    pub theta_deg: f64,
    /// Azimuth of `ω_r` (degrees from +x, counter-clockwise seen from above, in `[0, 360)`).
    pub phi_deg: f64,
    pub efficiency: Efficiency,
}

/// The orders at one wavelength.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GratingAnswer {
    pub wavelength_nm: f64,
    /// Propagating orders, `m` then `n` increasing.
    pub orders: Vec<OrderEfficiency>,
    /// Their sum: the hemispherical reflectance.
    pub reflected_total: Efficiency,
    /// Channels the orders couple at this wavelength (the size of the scattering matrix).
    pub channels: usize,
    /// What normalised the efficiencies: `energy` (Sinkhorn), `energy-row` (this incidence's row only: energy
    /// exact, reciprocity approximate; more than [`MAX_SINKHORN_CHANNELS`] channels) or `kirchhoff`.
    pub normalisation: &'static str,
    /// Largest deviation of a row or column sum from 1 after the scaling (0 for `kirchhoff`).
    pub normalisation_residual: f64,
    /// Kirchhoff's own sum of this row, before any normalisation, for a perfect reflector: how much energy the
    /// printed obliquity factor creates (> 1) or loses.
    pub kirchhoff_sum: f64,
}

/// One row of a unit cell's channel matrix (light from one direction at one wavelength) with its
/// normalisation: what [`UnitCell::efficiencies`] turns into orders, and what makes a continuous evaluator's
/// lobes energy-conserving ([`LobeScaled`]).
#[derive(Debug, Clone)]
pub struct ChannelRow {
    pub wavelength_nm: f64,
    wi: Vec3,
    gx: f64,
    gy: f64,
    channels: Vec<(i64, i64)>,
    xy: Vec<[f64; 2]>,
    cos: Vec<f64>,
    /// Kirchhoff's `K|c|²` towards each exit channel (a perfect reflector's raw efficiencies).
    pub raw: Vec<f64>,
    /// The normalisation's factor of each entry: `η = raw · factor` (before the Fresnel factor).
    pub factor: Vec<f64>,
    pub applied: &'static str,
    pub residual: f64,
    pub kirchhoff_sum: f64,
}

impl ChannelRow {
    /// The index of the exit channel nearest the direction `wr` (the order whose lobe `wr` lies in), where a
    /// propagating channel is near.
    pub fn towards(&self, wr: Vec3) -> Option<usize> {
        // Exit channel h leaves along −(ω_i,xy + h·g).
        let m = ((-wr[0] - self.wi[0]) / self.gx).round() as i64;
        let n = if self.gy.is_finite() && self.gy > 0.0 { ((-wr[1] - self.wi[1]) / self.gy).round() as i64 } else { 0 };
        match self.channels.binary_search_by(|&(cm, cn)| (cm, cn).cmp(&(m, n))) {
            Ok(b) => Some(b),
            // A 1-D cell's channels keep n = 0 only.
            Err(_) => self.channels.binary_search_by(|&(cm, cn)| (cm, cn).cmp(&(m, 0))).ok(),
        }
    }

    /// The normalisation factor of the channel nearest the exit direction `wr` (a lobe's continuous
    /// directions take the factor of the order they surround); 1 where no propagating channel is near.
    pub fn factor_towards(&self, wr: Vec3) -> f64 {
        self.towards(wr).map_or(1.0, |b| self.factor[b])
    }

    /// The number of propagating channels.
    pub fn len(&self) -> usize {
        self.channels.len()
    }

    /// Whether no channel propagates (never: the light's own channel always does).
    pub fn is_empty(&self) -> bool {
        self.channels.is_empty()
    }

    /// The unit vector along which exit channel `b` leaves (its order's direction, the lobe's centre).
    pub fn exit(&self, b: usize) -> Vec3 {
        [-self.xy[b][0], -self.xy[b][1], self.cos[b]]
    }

    /// The order `(m, n)` of exit channel `b` in the convention of [`OrderEfficiency`].
    pub fn order(&self, b: usize) -> (i64, i64) {
        (-self.channels[b].0, -self.channels[b].1)
    }
}

/// Which axes of the unit cell carry structure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lines {
    /// Every row the same: a 1-D grating along x (orders `n ≠ 0` carry nothing).
    AlongX,
    /// Every column the same: a 1-D grating along y.
    AlongY,
    /// A crossed (2-D) grating.
    Crossed,
}

impl Lines {
    /// Which axes of `patch` carry structure: rows all the same make a 1-D grating along x, columns all the
    /// same one along y. "The same" within 1e-9 of the height range: plane levelling leaves rounding of 1e-14 nm
    /// between identical rows, which made a grating crossed along one axis and 1-D along the other.
    pub fn of(patch: &Patch) -> Lines {
        let h = &patch.heights;
        let (lo, hi) = h.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
        let tolerance = 1e-9 * (hi - lo);
        let same = |a: f64, b: f64| (a - b).abs() <= tolerance;
        let cols = patch.cols;
        let rows_same =
            (1..patch.rows).all(|j| h[j * cols..(j + 1) * cols].iter().zip(&h[..cols]).all(|(&a, &b)| same(a, b)));
        let cols_same = (0..patch.rows).all(|j| h[j * cols..(j + 1) * cols].windows(2).all(|w| same(w[0], w[1])));
        match (rows_same, cols_same) {
            (true, false) => Lines::AlongX,
            (false, true) => Lines::AlongY,
            _ => Lines::Crossed,
        }
    }
}

/// A height field taken as one unit cell of a grating, with the Taylor terms of its phase factor.
#[derive(Debug, Clone)]
pub struct UnitCell {
    /// The Taylor terms of the cell's phase factor (read [`TaylorTerms::memory_bytes`] to see what a cell holds).
    pub terms: TaylorTerms,
    lines: Lines,
    /// The shortest wavelength the Taylor terms and the DFT bins serve (nm); rows below it are refused.
    lambda_min_nm: f64,
    /// Set by [`UnitCell::for_light`]: the one light direction whose rows the cell's bins serve.
    light: Option<Vec3>,
}

impl UnitCell {
    /// The unit cell of `patch` (its extent is the period along each axis), with Taylor terms for wavelengths
    /// down to `lambda_min_nm` (remainder ≤ [`TAYLOR_EPSILON`]), for light from any direction.
    pub fn new(patch: &Patch, lambda_min_nm: f64) -> Result<Self, DiffractionError> {
        check_wavelength(lambda_min_nm)?;
        check_order_count(Lines::of(patch), patch.extent(), lambda_min_nm)?;
        // Channels a, b couple through c_{a−b}, |a − b| < 2/λ in frequency: no other bin is read.
        Self::with_band(patch, lambda_min_nm, Band::directions(lambda_min_nm, 0.0), None)
    }

    /// The unit cell of `patch` for light from `wi` only, at `wavelengths_nm`: where every one of them has
    /// more than [`MAX_SINKHORN_CHANNELS`] channels (rows are normalised alone), its row reads only the bins
    /// within `1/λ` of `ω_i,xy/λ`, a quarter of those of [`UnitCell::new`] (a large scan's memory); its
    /// [`UnitCell::row`] refuses other light. Otherwise as [`UnitCell::new`].
    pub fn for_light(patch: &Patch, wi: Vec3, wavelengths_nm: &[f64]) -> Result<Self, DiffractionError> {
        let lambda_min = wavelengths_nm.iter().copied().fold(f64::INFINITY, f64::min);
        check_wavelength(lambda_min)?;
        let lines = Lines::of(patch);
        let (lx, ly) = patch.extent();
        check_order_count(lines, (lx, ly), lambda_min)?;
        let rows_alone = wavelengths_nm.iter().all(|&l| channels(lines, (lx, ly), wi, l).len() > MAX_SINKHORN_CHANNELS);
        if !rows_alone {
            return Self::new(patch, lambda_min);
        }
        Self::with_band(patch, lambda_min, Band::light(wi, lambda_min, 0.0), Some(wi))
    }

    fn with_band(patch: &Patch, lambda_min_nm: f64, band: Band, light: Option<Vec3>) -> Result<Self, DiffractionError> {
        let n = terms_for_bound(patch.max_abs_height, lambda_min_nm, TAYLOR_EPSILON)?;
        // The window is not used (the orders read the DFT bins themselves): any length it takes will do.
        let terms = TaylorTerms::compute_in_band(patch, n, crate::patch::MAX_COHERENCE_NM, band, &|_| {})?;
        Ok(Self { terms, lines: Lines::of(patch), lambda_min_nm, light })
    }

    /// The shortest wavelength whose rows the cell serves (nm): its Taylor terms meet [`TAYLOR_EPSILON`] there
    /// and its DFT bins hold every order that propagates there.
    pub fn lambda_min_nm(&self) -> f64 {
        self.lambda_min_nm
    }

    /// The periods `(Lx, Ly)` (nm).
    pub fn periods(&self) -> (f64, f64) {
        self.terms.extent()
    }

    pub fn lines(&self) -> Lines {
        self.lines
    }

    /// Taylor terms `N` (terms 0..N) behind `c_G(w)`.
    pub fn taylor_terms(&self) -> usize {
        self.terms.n_max
    }

    /// `c_G(w)`: the Fourier coefficient of `exp(i k w h)` at order `(m, n)`, zero beyond the grid's Nyquist.
    fn coefficient(&self, m: i64, n: i64, kw: f64) -> Complex64 {
        let t = &self.terms;
        let (cols, rows) = (t.cols as i64, t.rows as i64);
        if m > cols / 2 || -m > (cols - 1) / 2 || n > rows / 2 || -n > (rows - 1) / 2 {
            return Complex64::new(0.0, 0.0);
        }
        let c = t.bin(m.rem_euclid(cols) as usize, n.rem_euclid(rows) as usize);
        let mut acc = c[t.n_max];
        for j in (0..t.n_max).rev() {
            acc = acc * (kw / (j + 1) as f64) + c[j];
        }
        acc
    }

    /// The channel matrix's row of light from `wi` (unit vector, `wi[2] > 0`) at one wavelength: Kirchhoff's
    /// `K|c|²` towards every propagating channel and the factors `normalisation` multiplies them by.
    pub fn row(
        &self,
        wi: Vec3,
        wavelength_nm: f64,
        normalisation: Normalisation,
    ) -> Result<ChannelRow, DiffractionError> {
        let len = dot(wi, wi).sqrt();
        if !(wi.iter().all(|v| v.is_finite()) && (len - 1.0).abs() < 1e-9 && wi[2] > 0.0) {
            return Err(DiffractionError::Invalid(format!(
                "the light direction {wi:?} must be a unit vector above the surface"
            )));
        }
        if !(wavelength_nm.is_finite() && wavelength_nm > 0.0) {
            return Err(DiffractionError::Invalid(format!("wavelength {wavelength_nm} nm must be positive")));
        }
        if wavelength_nm < self.lambda_min_nm {
            // Shorter light couples orders whose bins the cell did not keep, through Taylor terms it did not take.
            return Err(DiffractionError::Invalid(format!(
                "this unit cell serves {} nm and longer; one for {wavelength_nm} nm is made with that wavelength",
                self.lambda_min_nm
            )));
        }
        if let Some(only) = self.light {
            if wi != only {
                return Err(DiffractionError::Invalid(format!(
                    "this unit cell keeps the DFT bins of light from {only:?} only (UnitCell::for_light); use \
                     UnitCell::new for other light"
                )));
            }
        }
        let (lx, ly) = self.periods();
        let (gx, gy) = (wavelength_nm / lx, wavelength_nm / ly);
        let channels = channels(self.lines, (lx, ly), wi, wavelength_nm);
        let here = channels.iter().position(|&c| c == (0, 0)).ok_or_else(|| {
            DiffractionError::Invalid("the light's own channel does not propagate (grazing light)".into())
        })?;
        // Channel g: light from a_g (xy = ω_i,xy + g) or exit along b_g = a_g mirrored in xy; same cosine.
        let xy: Vec<[f64; 2]> = channels.iter().map(|&(m, n)| [wi[0] + m as f64 * gx, wi[1] + n as f64 * gy]).collect();
        let cos: Vec<f64> = xy.iter().map(|p| (1.0 - p[0] * p[0] - p[1] * p[1]).max(0.0).sqrt()).collect();
        let k = std::f64::consts::TAU / wavelength_nm;
        let entry = |a: usize, b: usize| -> f64 {
            let (ca, cb) = (cos[a], cos[b]);
            // a·b with b the mirror of channel b's in-plane components.
            let ab = -(xy[a][0] * xy[b][0] + xy[a][1] * xy[b][1]) + ca * cb;
            let obliquity = (1.0 + ab).powi(2) / (ca * cb * (ca + cb).powi(2));
            let (m, n) = (channels[a].0 - channels[b].0, channels[a].1 - channels[b].1);
            obliquity * self.coefficient(m, n, -k * (ca + cb)).norm_sqr()
        };
        let p = channels.len();
        let raw: Vec<f64> = (0..p).map(|b| entry(here, b)).collect();
        let kirchhoff_sum: f64 = raw.iter().sum();
        let (factor, applied, residual): (Vec<f64>, &'static str, f64) = match normalisation {
            Normalisation::Kirchhoff => (vec![1.0; p], "kirchhoff", 0.0),
            Normalisation::Energy if p > MAX_SINKHORN_CHANNELS => (vec![1.0 / kirchhoff_sum; p], "energy-row", 0.0),
            Normalisation::Energy if self.light.is_some() => {
                return Err(DiffractionError::Invalid(format!(
                    "{p} channels at {wavelength_nm} nm: the full scaling needs every direction's bins, which this \
                     unit cell (UnitCell::for_light) does not keep; use UnitCell::new"
                )))
            }
            Normalisation::Energy => {
                let matrix: Vec<f64> = (0..p * p).into_par_iter().map(|i| entry(i / p, i % p)).collect::<Vec<f64>>();
                let (r, s, residual) = sinkhorn(&matrix, p);
                ((0..p).map(|b| r[here] * s[b]).collect(), "energy", residual)
            }
        };
        Ok(ChannelRow { wavelength_nm, wi, gx, gy, channels, xy, cos, raw, factor, applied, residual, kirchhoff_sum })
    }

    /// The efficiencies of every propagating order for light from `wi` (unit vector, `wi[2] > 0`) at one
    /// wavelength, the Fresnel reflectance from `fresnel` at the half-vector angle.
    pub fn efficiencies(
        &self,
        wi: Vec3,
        wavelength_nm: f64,
        fresnel: &dyn FresnelSource,
        normalisation: Normalisation,
    ) -> Result<GratingAnswer, DiffractionError> {
        let row = self.row(wi, wavelength_nm, normalisation)?;
        let ChannelRow { channels, xy, cos, raw, factor, applied, residual, kirchhoff_sum, .. } = row;
        let p = channels.len();
        let weights: Vec<f64> = raw.iter().zip(&factor).map(|(r, f)| r * f).collect();
        let mut orders = Vec::with_capacity(p);
        let mut total = Efficiency::default();
        for (b, &weight) in weights.iter().enumerate() {
            let wr = [-xy[b][0], -xy[b][1], cos[b]];
            let h = [wi[0] + wr[0], wi[1] + wr[1], wi[2] + wr[2]];
            let cos_h = dot(wi, h) / dot(h, h).sqrt();
            let [rs, rp] = fresnel.reflectance_sp(wavelength_nm, cos_h);
            let e = Efficiency::new(weight * rs, weight * rp);
            total.add(e);
            let (m, n) = (-channels[b].0, -channels[b].1);
            orders.push(OrderEfficiency {
                wavelength_nm,
                m,
                n,
                theta_deg: cos[b].clamp(-1.0, 1.0).acos().to_degrees(),
                // Along the normal the azimuth is undefined: 0, whatever round-off leaves in ω_r's x and y (an
                // order at θ_r = 0.000° read φ_r = 118.878°).
                phi_deg: if xy[b][0].hypot(xy[b][1]) < 1e-12 {
                    0.0
                } else {
                    wr[1].atan2(wr[0]).to_degrees().rem_euclid(360.0)
                },
                efficiency: e,
            });
        }
        orders.sort_by_key(|o| (o.m, o.n));
        Ok(GratingAnswer {
            wavelength_nm,
            orders,
            reflected_total: total,
            channels: p,
            normalisation: applied,
            normalisation_residual: residual,
            kirchhoff_sum,
        })
    }

    /// [`UnitCell::efficiencies`] at every wavelength, in parallel.
    pub fn spectrum(
        &self,
        wi: Vec3,
        wavelengths_nm: &[f64],
        fresnel: &dyn FresnelSource,
        normalisation: Normalisation,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Vec<GratingAnswer>, DiffractionError> {
        let done = std::sync::atomic::AtomicUsize::new(0);
        wavelengths_nm
            .par_iter()
            .map(|&l| {
                let a = self.efficiencies(wi, l, fresnel, normalisation);
                progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
                a
            })
            .collect()
    }
}

/// Refuses a cell with more than [`MAX_ORDERS`] propagating orders at `lambda_nm` (about `2L/λ` along a 1-D
/// grating, `π Lx Ly/λ²` for a crossed one), before any is listed.
fn check_order_count(lines: Lines, (lx, ly): (f64, f64), lambda_nm: f64) -> Result<(), DiffractionError> {
    let orders = match lines {
        Lines::AlongX => 2.0 * lx / lambda_nm,
        Lines::AlongY => 2.0 * ly / lambda_nm,
        Lines::Crossed => std::f64::consts::PI * (lx / lambda_nm) * (ly / lambda_nm),
    };
    if orders > MAX_ORDERS {
        return Err(DiffractionError::Invalid(format!(
            "about {orders:.1e} orders propagate at λ = {lambda_nm} nm over a {lx} × {ly} nm unit cell, more than the \
             {MAX_ORDERS:.0e} its model takes: wavelengths are in nm (0.55 is µm, 5.5e-7 metres); for a large scan \
             take one period (--unit-cell auto) or a smaller patch"
        )));
    }
    Ok(())
}

fn check_wavelength(lambda_min_nm: f64) -> Result<(), DiffractionError> {
    iridis_color::spectrum::check_light_nanometres(lambda_min_nm)
        .map_err(|e| DiffractionError::Invalid(e.to_string()))?;
    if lambda_min_nm.is_finite() && lambda_min_nm > 0.0 {
        Ok(())
    } else {
        Err(DiffractionError::Invalid(format!("shortest wavelength {lambda_min_nm} nm must be positive")))
    }
}

/// The lattice vectors `(m, n)` of a cell of periods `(Lx, Ly)` whose channels `ω_i,xy + (mλ/Lx, nλ/Ly)`
/// propagate, `m` then `n` increasing; a 1-D grating keeps its own axis only.
fn channels(lines: Lines, (lx, ly): (f64, f64), wi: Vec3, wavelength_nm: f64) -> Vec<(i64, i64)> {
    let (gx, gy) = (wavelength_nm / lx, wavelength_nm / ly);
    let range = |c: f64, g: f64| ((-1.0 - c) / g).ceil() as i64..=((1.0 - c) / g).floor() as i64;
    let (mr, nr) = match lines {
        Lines::AlongX => (range(wi[0], gx), 0..=0),
        Lines::AlongY => (0..=0, range(wi[1], gy)),
        Lines::Crossed => (range(wi[0], gx), range(wi[1], gy)),
    };
    let mut out = Vec::new();
    for n in nr {
        for m in mr.clone() {
            let (x, y) = (wi[0] + m as f64 * gx, wi[1] + n as f64 * gy);
            if x * x + y * y < 1.0 - 1e-12 {
                out.push((m, n));
            }
        }
    }
    out.sort_by_key(|&(m, n)| (m, n));
    out
}

/// What each diffraction lobe of a continuous evaluator should carry: for light from `ω_i` at `λ`, a factor per
/// propagating order of the unit cell that scales the order's Kirchhoff lobe (the window-shaped lobe of the
/// patch's periodic extension, which carries `η_G` of [`UnitCell::efficiencies`] with [`Normalisation::Kirchhoff`]),
/// so that the lobe carries the provider's target energy instead. Two providers: [`SinkhornEnergy`] (the
/// energy-normalised channel matrix) and the rigorous efficiencies of Maxwell's equations (`iridis-api`, which
/// may depend on `iridis-rigorous`).
pub trait LobeEnergy: Send + Sync {
    /// Short name: `energy` or `rigorous`.
    fn name(&self) -> &'static str;
    /// The row of `cell`'s channels for light from `wi` at `wavelength_nm`, its `factor` the scale of each exit
    /// channel's lobe, with the TE and TM shares of each lobe where the provider knows them.
    fn scale(&self, cell: &UnitCell, wavelength_nm: f64, wi: Vec3) -> Result<ScaledRow, DiffractionError>;
}

/// A row of lobe factors ([`LobeEnergy::scale`]).
#[derive(Debug, Clone)]
pub struct ScaledRow {
    /// The channels, Kirchhoff's raw entries and the lobe factors (`row.factor`).
    pub row: ChannelRow,
    /// Per exit channel, `[η_TE/η, η_TM/η]` of its order (mean 1): how the lobe's unpolarised energy divides
    /// between TE (s) and TM (p) incident light. `None`: as the inner evaluator's Fresnel factor says.
    pub shares: Option<Vec<[f64; 2]>>,
}

/// The energy-normalised channel matrix as the lobes' target ([`UnitCell::row`] with [`Normalisation::Energy`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct SinkhornEnergy;

impl LobeEnergy for SinkhornEnergy {
    fn name(&self) -> &'static str {
        "energy"
    }
    fn scale(&self, cell: &UnitCell, wavelength_nm: f64, wi: Vec3) -> Result<ScaledRow, DiffractionError> {
        Ok(ScaledRow { row: cell.row(wi, wavelength_nm, Normalisation::Energy)?, shares: None })
    }
}

/// A continuous evaluator (reference, ground truth) whose lobes carry the energy a [`LobeEnergy`] gives: each
/// lobe, which surrounds an order of the patch taken as a unit cell, is scaled by that order's factor.
///
/// With [`SinkhornEnergy`] (the energy-normalised BRDF, [`LobeScaled::energy_normalised`]) the lobes of a
/// perfect reflector return the light within the lobe-versus-order accuracy, at every incidence, where
/// Kirchhoff's obliquity factor as printed returned up to twice it at grazing light (docs/PHYSICS.md, "Order
/// efficiencies"). The scaling is reciprocal where the full Sinkhorn scaling runs (up to
/// [`MAX_SINKHORN_CHANNELS`] channels); above, each light's row alone is scaled (energy exact, reciprocity
/// approximate). With rigorous efficiencies as the target, the lobes' shape is the light's window and their
/// energy Maxwell's (docs/PHYSICS.md, "The rigorous BRDF"). The relative `ρ` of the lookup method integrates
/// over λ in advance and cannot take a per-λ factor; it is not wrapped.
pub struct LobeScaled {
    inner: Box<dyn crate::Evaluator>,
    patch: Patch,
    /// The unit cell the lobes' factors come from; made again when a wavelength shorter than it serves is asked.
    cell: std::sync::RwLock<std::sync::Arc<UnitCell>>,
    spectral: crate::SpectralSetup,
    energy: std::sync::Arc<dyn LobeEnergy>,
    rows: std::sync::RwLock<std::collections::HashMap<[u64; 4], std::sync::Arc<ScaledRow>>>,
}

impl std::fmt::Debug for LobeScaled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LobeScaled")
            .field("inner", &self.inner.name())
            .field("energy", &self.energy.name())
            .field("cell", &self.cell().periods())
            .finish()
    }
}

impl LobeScaled {
    /// Wraps `inner`, an evaluator with a spectral reflectance, of the height field `patch` (one unit cell of
    /// its periodic extension); `spectral` is the wavelength grid and colour weights its colours integrate
    /// over; `energy` says what each lobe carries. The unit cell is set up for `spectral`'s shortest wavelength;
    /// a lobe asked at a shorter one (where more orders couple) has the cell made again for it first, which
    /// for a large scan takes seconds: a caller that knows it will ask below the grid says so with
    /// [`LobeScaled::down_to`].
    pub fn new(
        inner: Box<dyn crate::Evaluator>,
        patch: &Patch,
        spectral: crate::SpectralSetup,
        energy: std::sync::Arc<dyn LobeEnergy>,
    ) -> Result<Self, DiffractionError> {
        let lambda_min = spectral.wavelengths().first().copied().unwrap_or(380.0);
        Self::down_to(inner, patch, spectral, energy, lambda_min)
    }

    /// [`LobeScaled::new`] for lobes asked at wavelengths down to `lambda_min_nm`, which may lie below
    /// `spectral`'s grid (an animal's ultraviolet, from 300 nm): the unit cell's orders and Taylor terms are set
    /// up for the shorter wavelength, where more orders propagate.
    pub fn down_to(
        inner: Box<dyn crate::Evaluator>,
        patch: &Patch,
        spectral: crate::SpectralSetup,
        energy: std::sync::Arc<dyn LobeEnergy>,
        lambda_min_nm: f64,
    ) -> Result<Self, DiffractionError> {
        let first = spectral.wavelengths().first().copied().unwrap_or(380.0);
        let lambda_min = lambda_min_nm.min(first);
        if inner.reflectance(lambda_min, [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]).is_none() {
            return Err(DiffractionError::Invalid(format!(
                "the {} method integrates over wavelength in advance: its lobes cannot take a factor per wavelength; \
                 use reference or ground-truth for energy-normalised or rigorous BRDFs",
                inner.name()
            )));
        }
        let cell = std::sync::RwLock::new(std::sync::Arc::new(UnitCell::new(patch, lambda_min)?));
        Ok(Self { inner, patch: patch.clone(), cell, spectral, energy, rows: Default::default() })
    }

    /// The energy-normalised BRDF: `inner`'s lobes scaled by the Sinkhorn factors of `patch`'s channel matrix.
    pub fn energy_normalised(
        inner: Box<dyn crate::Evaluator>,
        patch: &Patch,
        spectral: crate::SpectralSetup,
    ) -> Result<Self, DiffractionError> {
        Self::new(inner, patch, spectral, std::sync::Arc::new(SinkhornEnergy))
    }

    /// The unit cell whose orders the lobes surround (for the shortest wavelength asked so far).
    pub fn cell(&self) -> std::sync::Arc<UnitCell> {
        self.cell.read().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// The unit cell that serves `λ`: the current one, or one made for `λ` when that is shorter than it serves.
    fn cell_for(&self, wavelength_nm: f64) -> Result<std::sync::Arc<UnitCell>, DiffractionError> {
        let cell = self.cell();
        if wavelength_nm >= cell.lambda_min_nm() {
            return Ok(cell);
        }
        let mut current = self.cell.write().unwrap_or_else(|e| e.into_inner());
        if wavelength_nm < current.lambda_min_nm() {
            // Rows cached so far stay valid: they were computed at wavelengths their cell served.
            *current = std::sync::Arc::new(UnitCell::new(&self.patch, wavelength_nm)?);
        }
        Ok(current.clone())
    }

    fn key(wavelength_nm: f64, wi: Vec3) -> [u64; 4] {
        [wavelength_nm.to_bits(), wi[0].to_bits(), wi[1].to_bits(), wi[2].to_bits()]
    }

    /// Computes the lobe factors of light from `wi` at every wavelength of the spectral grid, in parallel,
    /// before many views ask for them (a rigorous provider solves Maxwell's equations once per wavelength):
    /// `progress(done)` of [`LobeScaled::preparation_steps`]. Views of other lights compute theirs when asked.
    pub fn prepare(&self, wi: Vec3, progress: &(dyn Fn(usize) + Sync)) -> Result<(), DiffractionError> {
        let done = std::sync::atomic::AtomicUsize::new(0);
        // Made for the grid's shortest wavelength or a shorter one: it serves every wavelength of the grid.
        let cell = self.cell();
        let rows: Vec<([u64; 4], ScaledRow)> = self
            .spectral
            .wavelengths()
            .par_iter()
            .map(|&l| {
                let r = self.energy.scale(&cell, l, wi).map(|r| (Self::key(l, wi), r));
                progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
                r
            })
            .collect::<Result<_, _>>()?;
        let mut map = self.rows.write().unwrap_or_else(|e| e.into_inner());
        map.extend(rows.into_iter().map(|(k, r)| (k, std::sync::Arc::new(r))));
        Ok(())
    }

    /// The steps of [`LobeScaled::prepare`]: one per wavelength.
    pub fn preparation_steps(&self) -> usize {
        self.spectral.wavelengths().len()
    }

    /// The factors of light from `wi` at `λ`, computed once.
    fn row(&self, wavelength_nm: f64, wi: Vec3) -> Option<std::sync::Arc<ScaledRow>> {
        let key = Self::key(wavelength_nm, wi);
        // A lock poisoned by a panic elsewhere still holds whole rows (each is inserted at once).
        if let Some(r) = self.rows.read().unwrap_or_else(|e| e.into_inner()).get(&key) {
            return Some(r.clone());
        }
        let cell = self.cell_for(wavelength_nm).ok()?;
        let r = std::sync::Arc::new(self.energy.scale(&cell, wavelength_nm, wi).ok()?);
        self.rows.write().unwrap_or_else(|e| e.into_inner()).insert(key, r.clone());
        Some(r)
    }
}

impl crate::Evaluator for LobeScaled {
    fn name(&self) -> &'static str {
        self.inner.name()
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        let rho = self.inner.reflectance(wavelength_nm, wi, wr)?;
        if rho == 0.0 {
            return Some(0.0);
        }
        Some(rho * self.row(wavelength_nm, wi).map_or(1.0, |r| r.row.factor_towards(wr)))
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> iridis_color::Xyz {
        if wi[2] <= 0.0 || wr[2] <= 0.0 {
            return iridis_color::Xyz::default();
        }
        let mut acc = [0.0; 3];
        for (&l, w) in self.spectral.wavelengths().iter().zip(self.spectral.weights.weights()) {
            let rho = self.reflectance(l, wi, wr).unwrap_or(0.0);
            for c in 0..3 {
                acc[c] += w[c] * rho;
            }
        }
        iridis_color::Xyz::new(acc[0], acc[1], acc[2])
    }
    fn shading(&self) -> Option<&crate::Shading> {
        self.inner.shading()
    }
    fn radiometric_gain(&self, wavelength_nm: f64) -> Option<f64> {
        self.inner.radiometric_gain(wavelength_nm)
    }
    fn coherence_nm(&self) -> Option<f64> {
        self.inner.coherence_nm()
    }
    fn polarisation(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<[f64; 2]> {
        let r = self.row(wavelength_nm, wi);
        match r.as_ref().and_then(|r| Some((r.row.towards(wr)?, r.shares.as_ref()?))) {
            Some((b, shares)) => Some(shares[b]),
            None => self.inner.polarisation(wavelength_nm, wi, wr),
        }
    }
}

/// Sinkhorn–Knopp: `r`, `s` such that `r_a M[a][b] s_b` has every row and column summing to 1 (`M` square,
/// row-major, `p × p`, non-negative with positive diagonal); returns them and the largest deviation left.
///
/// Over-relaxed (Thibault, Chizat, Dossal & Papadakis, "Overrelaxed Sinkhorn–Knopp algorithm for regularized
/// optimal transport", Algorithms 14(5):143, 2021): each scaling moves `ω` times as far as Sinkhorn's in
/// logarithms, `r_a ← r_a^{1−ω} (1/(M s)_a)^ω`, which has the same fixed point. `ω` is chosen as for successive
/// over-relaxation of a two-block (2-cyclic) iteration (Hageman & Young, "Applied Iterative Methods", 1981,
/// ch. 9): the residual's rate `λ` observed at a factor `ω` gives the plain iteration's `μ²` by
/// `(λ + ω − 1)² = λ ω² μ²`, and the best factor is `ω = 2/(1 + √(1 − μ²))`; it starts from the plain steps'
/// rate and is raised from the relaxed steps' (the early rates understate the slowest mode). A large unit
/// cell's channel matrix (p ≈ 500–600, the snake scan's report) needed ~480 plain steps to 1e-13 and needs ~100.
/// Should the residual grow instead, the iteration returns to plain steps for good.
fn sinkhorn(m: &[f64], p: usize) -> (Vec<f64>, Vec<f64>, f64) {
    /// Plain steps before the first factor, relaxed steps between raises (the rate is read over the second half
    /// of each), and how many times the factor is set.
    const PLAIN_STEPS: usize = 8;
    const RELAXED_STEPS: usize = 16;
    const SETTINGS: usize = 4;
    let mut r = vec![1.0; p];
    let mut s = vec![1.0; p];
    let mut row = vec![0.0; p];
    let mut column = vec![0.0; p];
    let mut residual = f64::INFINITY;
    let mut omega: f64 = 1.0;
    let (mut since, mut settings, mut settled) = (0, 0, false);
    let (mut halfway, mut at_change) = (f64::NAN, f64::NAN);
    for _ in 0..20_000 {
        row_sums(m, p, |_, x, b| x * s[b], &mut row);
        relax(&mut r, &row, omega);
        column_sums(m, &r, &mut column);
        relax(&mut s, &column, omega);
        // Plain steps leave every column summing to 1 and the rows say how far from the fixed point; relaxed
        // ones leave both off.
        row_sums(m, p, |a, x, b| r[a] * x * s[b], &mut row);
        residual = row.iter().map(|sum| (sum - 1.0).abs()).fold(0.0, f64::max);
        if omega != 1.0 {
            column_sums(m, &r, &mut column);
            let columns = column.iter().zip(&s).map(|(sum, sb)| (sum * sb - 1.0).abs()).fold(0.0, f64::max);
            residual = residual.max(columns);
        }
        if residual < 1e-13 {
            break;
        }
        if omega != 1.0 && (residual.is_nan() || residual >= 100.0 * at_change) {
            // Diverging (or NaN): plain Sinkhorn for good, which always converges here.
            (omega, settled) = (1.0, true);
        }
        if settled {
            continue;
        }
        since += 1;
        let window = if settings == 0 { PLAIN_STEPS } else { RELAXED_STEPS };
        if since == window / 2 {
            halfway = residual;
        } else if since == window {
            let lambda = (residual / halfway).powf(2.0 / window as f64);
            let mu2 = (lambda + omega - 1.0).powi(2) / (lambda * omega * omega);
            if lambda < 1.0 && mu2 < 1.0 {
                omega = omega.max((2.0 / (1.0 + (1.0 - mu2).sqrt())).min(1.95));
            }
            (since, at_change) = (0, residual);
            settings += 1;
            settled = settings == SETTINGS || omega == 1.0;
        }
    }
    (r, s, residual)
}

/// One scaling of [`sinkhorn`]: `x_a ← x_a^{1−ω} (1/sum_a)^ω`; plain `x_a ← 1/sum_a` at `ω = 1` (bit for bit the
/// unrelaxed step); 0 where nothing reaches.
fn relax(x: &mut [f64], sums: &[f64], omega: f64) {
    for (xa, &sum) in x.iter_mut().zip(sums) {
        *xa = if sum <= 0.0 {
            0.0
        } else if omega == 1.0 || *xa <= 0.0 {
            1.0 / sum
        } else {
            *xa * (*xa * sum).powf(-omega)
        };
    }
}

/// `column[b] = Σ_a weight_a M[a][b]`, accumulated row by row: each column adds the same terms in the same order
/// (a = 0, 1, …) as a sum down the column would, but M is read in memory order (down the columns, the strided
/// reads were most of the iteration's time on large cells).
fn column_sums(m: &[f64], weight: &[f64], column: &mut [f64]) {
    let p = column.len();
    column.fill(0.0);
    for (a, &wa) in weight.iter().enumerate() {
        for (c, &x) in column.iter_mut().zip(&m[a * p..(a + 1) * p]) {
            *c += wa * x;
        }
    }
}

/// `out[a] = Σ_b term(a, M[a][b], b)`, each row's sum in order of `b`, four rows at a time (the last rows one by
/// one): their sums are independent chains of additions, so they run side by side instead of each waiting on its
/// own previous addition — the same additions in the same order, so the same sums. (A single loop over chunks
/// of up to four rows was 8–15 % slower: the compiler no longer unrolls the four chains.)
fn row_sums(m: &[f64], p: usize, term: impl Fn(usize, f64, usize) -> f64, out: &mut [f64]) {
    const ROWS: usize = 4;
    let mut a = 0;
    while a + ROWS <= p {
        let mut acc = [0.0; ROWS];
        for b in 0..p {
            for (k, acc) in acc.iter_mut().enumerate() {
                *acc += term(a + k, m[(a + k) * p + b], b);
            }
        }
        out[a..a + ROWS].copy_from_slice(&acc);
        a += ROWS;
    }
    for (a, o) in out.iter_mut().enumerate().skip(a) {
        *o = (0..p).map(|b| term(a, m[a * p + b], b)).sum();
    }
}
