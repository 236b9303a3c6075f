//! Exact derivatives of R, T, ψ and Δ with respect to layer thicknesses and refractive indices, by
//! forward-mode automatic differentiation: every complex quantity of the model is carried with its partial
//! derivatives with respect to `K` real parameters (a "jet", `z + Σ_k ∂z/∂p_k ε_k`), through the same
//! equations as the value — Snell's cosines (Sussenbach eq. 3.6), the Fresnel amplitudes (eq. 3.7–3.10),
//! the phases (eq. 3.5), the recurrence (eq. 3.1–3.2), the powers (eq. 3.12–3.13), the incoherent cascade of
//! [`crate::incoherent`] and the ellipsometric angles of [`crate::field`] — so the derivatives are exact to
//! rounding, not finite-difference estimates.
//!
//! The parameters are real, so the chain rule holds for non-holomorphic steps too: `∂ z̄ = conj(∂z)`,
//! `∂|z|² = 2 Re(z̄ ∂z)`, `∂ arg z = Im(∂z / z)`. The caller says how each medium's index and each layer's
//! thickness depend on the parameters ([`Tangent`]); for Cauchy and Sellmeier coefficients
//! [`crate::material::Material::cauchy_gradient`] and [`crate::material::Material::sellmeier_gradient`] give `∂n/∂c`.
//!
//! A layer at its critical angle (`|s_z| < 1e-5`) is evaluated without the grazing treatment of
//! [`crate::recurrence::compose`]: there the derivative with respect to its index is unbounded anyway.

use std::ops::{Add, Div, Mul, Neg, Sub};

use num_complex::Complex64;

use crate::error::ThinFilmError;
use crate::recurrence::Medium;
use crate::stack::Stack;

const ZERO: Complex64 = Complex64::new(0.0, 0.0);

/// A complex value with its derivatives with respect to `K` real parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet<const K: usize> {
    pub v: Complex64,
    pub d: [Complex64; K],
}

impl<const K: usize> Jet<K> {
    /// A quantity that does not depend on the parameters.
    pub fn constant(v: Complex64) -> Self {
        Self { v, d: [ZERO; K] }
    }
    pub fn real(v: f64) -> Self {
        Self::constant(Complex64::new(v, 0.0))
    }
    /// The chain rule for a function with value `v` and complex derivative `f1` at `self.v`.
    fn chain(self, v: Complex64, f1: Complex64) -> Self {
        Self { v, d: self.d.map(|d| d * f1) }
    }
    fn each(self, v: Complex64, f: impl Fn(Complex64) -> Complex64) -> Self {
        Self { v, d: self.d.map(f) }
    }
    pub fn re(self) -> Self {
        self.each(Complex64::new(self.v.re, 0.0), |d| Complex64::new(d.re, 0.0))
    }
    pub fn im(self) -> Self {
        self.each(Complex64::new(self.v.im, 0.0), |d| Complex64::new(d.im, 0.0))
    }
    pub fn conj(self) -> Self {
        self.each(self.v.conj(), |d| d.conj())
    }
    /// `|z|²`, a real jet.
    pub fn norm_sqr(self) -> Self {
        let z = self.v;
        self.each(Complex64::new(z.norm_sqr(), 0.0), |d| Complex64::new(2.0 * (z.conj() * d).re, 0.0))
    }
    /// The principal square root (`∂√z = ∂z / (2√z)`).
    pub fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.chain(s, 0.5 / s)
    }
    pub fn exp(self) -> Self {
        let e = self.v.exp();
        self.chain(e, e)
    }
    pub fn scale(self, c: Complex64) -> Self {
        self.chain(self.v * c, c)
    }
    /// The derivatives' real parts (for a real jet: the gradient).
    pub fn gradient(&self) -> [f64; K] {
        self.d.map(|d| d.re)
    }
}

impl<const K: usize> Add for Jet<K> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let mut d = self.d;
        d.iter_mut().zip(o.d).for_each(|(a, b)| *a += b);
        Self { v: self.v + o.v, d }
    }
}

impl<const K: usize> Sub for Jet<K> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        let mut d = self.d;
        d.iter_mut().zip(o.d).for_each(|(a, b)| *a -= b);
        Self { v: self.v - o.v, d }
    }
}

impl<const K: usize> Neg for Jet<K> {
    type Output = Self;
    fn neg(self) -> Self {
        self.each(-self.v, |d| -d)
    }
}

impl<const K: usize> Mul for Jet<K> {
    type Output = Self;
    // The product rule adds: (ab)' = a'b + ab'.
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn mul(self, o: Self) -> Self {
        let mut d = self.d;
        d.iter_mut().zip(o.d).for_each(|(a, b)| *a = *a * o.v + self.v * b);
        Self { v: self.v * o.v, d }
    }
}

impl<const K: usize> Div for Jet<K> {
    type Output = Self;
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, o: Self) -> Self {
        // (a/b)' = (a' − (a/b) b') / b
        let inv = 1.0 / o.v;
        let q = self.v * inv;
        let mut d = self.d;
        d.iter_mut().zip(o.d).for_each(|(a, b)| *a = (*a - q * b) * inv);
        Self { v: q, d }
    }
}

impl<const K: usize> Add<f64> for Jet<K> {
    type Output = Self;
    fn add(self, o: f64) -> Self {
        Self { v: self.v + o, d: self.d }
    }
}

impl<const K: usize> Mul<f64> for Jet<K> {
    type Output = Self;
    fn mul(self, o: f64) -> Self {
        self.scale(Complex64::new(o, 0.0))
    }
}

/// How the media and thicknesses depend on the `K` parameters: `index[j][k] = ∂n̂_j/∂p_k` for the `N + 2`
/// media (incident first) and `thickness[j][k] = ∂d_j/∂p_k` (nm per unit) for the `N` layers.
#[derive(Debug, Clone, PartialEq)]
pub struct Tangent<const K: usize> {
    pub index: Vec<[Complex64; K]>,
    pub thickness: Vec<[f64; K]>,
}

impl<const K: usize> Tangent<K> {
    /// No dependence (fill in the entries of the parameters).
    pub fn zero(layers: usize) -> Self {
        Self { index: vec![[ZERO; K]; layers + 2], thickness: vec![[0.0; K]; layers] }
    }
}

/// Powers with their derivatives (real jets): `r_s`, `r_p`, `t_s`, `t_p` as in [`crate::Rta`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RtaJet<const K: usize> {
    pub r_s: Jet<K>,
    pub r_p: Jet<K>,
    pub t_s: Jet<K>,
    pub t_p: Jet<K>,
}

impl<const K: usize> RtaJet<K> {
    /// Unpolarised reflectance `(R_s + R_p)/2`.
    pub fn r(&self) -> Jet<K> {
        (self.r_s + self.r_p) * 0.5
    }
    /// Unpolarised transmittance.
    pub fn t(&self) -> Jet<K> {
        (self.t_s + self.t_p) * 0.5
    }
}

#[derive(Clone, Copy)]
struct MJ<const K: usize> {
    n: Jet<K>,
    cos: Jet<K>,
}

/// The media as jets: indices from the stack with the caller's derivatives; cosines by Snell's law
/// (eq. 3.6) on the branch that [`Stack::media`] chose.
fn media_jets<const K: usize>(media: &[Medium], tan: &Tangent<K>, angle_rad: f64) -> Vec<MJ<K>> {
    let n0 = Jet { v: media[0].n, d: tan.index[0] };
    let sin0 = angle_rad.min(std::f64::consts::FRAC_PI_2).sin();
    let s = n0.re() * sin0; // the Snell invariant n₀ sin θ₀ (n₀ real)
    media
        .iter()
        .enumerate()
        .map(|(j, m)| {
            let n = Jet { v: m.n, d: tan.index[j] };
            if j == 0 {
                return MJ { n, cos: Jet::constant(m.cos) };
            }
            let sx = s / n;
            let c = (Jet::real(1.0) - sx * sx).sqrt();
            // Same branch as the value path (the forward-travelling wave).
            let c = if (c.v - m.cos).norm() <= (c.v + m.cos).norm() { c } else { -c };
            MJ { n, cos: c }
        })
        .collect()
}

struct FresnelJet<const K: usize> {
    r_s: Jet<K>,
    r_p: Jet<K>,
    t_s: Jet<K>,
    t_p: Jet<K>,
}

/// Sussenbach eq. 3.7–3.10 (as [`crate::recurrence::fresnel`]).
fn fresnel<const K: usize>(upper: MJ<K>, lower: MJ<K>) -> FresnelJet<K> {
    let a = upper.n * upper.cos;
    let b = lower.n * lower.cos;
    let c = lower.n * upper.cos;
    let d = upper.n * lower.cos;
    let (ds, dp) = (a + b, c + d);
    FresnelJet { r_p: (c - d) / dp, r_s: (a - b) / ds, t_p: (a * 2.0) / dp, t_s: (a * 2.0) / ds }
}

/// `e^{iφ_j}` with `φ_j = (2π/λ) n̂_j d_j s_{z,j}` (eq. 3.5).
fn phase_factor<const K: usize>(m: MJ<K>, d: Jet<K>, wavelength_nm: f64) -> Jet<K> {
    let phi = m.n * m.cos * d * (2.0 * std::f64::consts::PI / wavelength_nm);
    phi.scale(Complex64::new(0.0, 1.0)).exp()
}

/// The recurrence (eq. 3.1–3.4) over a coherent stack or group: `(γ_s, γ_p, τ_s, τ_p)` at the top.
fn compose<const K: usize>(m: &[MJ<K>], d: &[Jet<K>], wavelength_nm: f64) -> [Jet<K>; 4] {
    let n = d.len();
    let f = fresnel(m[n], m[n + 1]);
    let (mut gs, mut gp, mut ts, mut tp) = (f.r_s, f.r_p, f.t_s, f.t_p);
    for j in (1..=n).rev() {
        let top = fresnel(m[j - 1], m[j]);
        let e1 = phase_factor(m[j], d[j - 1], wavelength_nm);
        let e2 = e1 * e1;
        let step = |r: Jet<K>, t: Jet<K>, g: Jet<K>, tau: Jet<K>| {
            let g2 = g * e2;
            let den = r * g2 + 1.0;
            ((r + g2) / den, t * tau * e1 / den)
        };
        (gs, ts) = step(top.r_s, top.t_s, gs, ts);
        (gp, tp) = step(top.r_p, top.t_p, gp, tp);
    }
    [gs, gp, ts, tp]
}

/// The normal flux of a unit wave, `Re(n̂ s_z)` (s) or `Re(n̂ conj(s_z))` (p), as in `incoherent`.
fn flux<const K: usize>(m: MJ<K>, p: bool) -> Jet<K> {
    if p {
        (m.n * m.cos.conj()).re()
    } else {
        (m.n * m.cos).re()
    }
}

/// `|t|²` times the flux ratio, 0 where no power flows.
fn power_t<const K: usize>(t: Jet<K>, upper: MJ<K>, lower: MJ<K>, p: bool) -> Jet<K> {
    let (a, b) = (flux(upper, p), flux(lower, p));
    if a.v.re <= 0.0 || b.v.re <= 0.0 {
        Jet::real(0.0)
    } else {
        t.norm_sqr() * b / a
    }
}

impl Stack {
    fn jet_inputs<const K: usize>(
        &self,
        wavelength_nm: f64,
        angle_rad: f64,
        tan: &Tangent<K>,
    ) -> Result<(Vec<MJ<K>>, Vec<Jet<K>>), ThinFilmError> {
        let n = self.layers.len();
        if tan.index.len() != n + 2 || tan.thickness.len() != n {
            return Err(ThinFilmError::Invalid(format!(
                "a tangent for {} media and {} layers given for a stack of {} layers",
                tan.index.len(),
                tan.thickness.len(),
                n
            )));
        }
        let media = self.media(wavelength_nm, angle_rad)?;
        let m = media_jets(&media, tan, angle_rad);
        let d = self
            .layers
            .iter()
            .zip(&tan.thickness)
            .map(|(l, t)| Jet { v: Complex64::new(l.thickness_nm, 0.0), d: t.map(|x| Complex64::new(x, 0.0)) })
            .collect();
        Ok((m, d))
    }

    /// [`Stack::evaluate`] with the derivatives of `R_s, R_p, T_s, T_p` (coherent and `inc:` stacks).
    pub fn evaluate_jet<const K: usize>(
        &self,
        wavelength_nm: f64,
        angle_rad: f64,
        tan: &Tangent<K>,
    ) -> Result<RtaJet<K>, ThinFilmError> {
        let (m, d) = self.jet_inputs(wavelength_nm, angle_rad, tan)?;
        let opaque = m[m.len() - 1].n.v.im > 0.0;
        let zero_if_opaque = |t: Jet<K>| if opaque { Jet::real(0.0) } else { t };
        if !self.has_incoherent() {
            let [gs, gp, ts, tp] = compose(&m, &d, wavelength_nm);
            let (top, bottom) = (m[0], m[m.len() - 1]);
            // Eq. 3.13's factor Re(n̂_{N+1} s_{z,N+1}) / (n₀ s_{z,0}), as `transmission_factor`.
            let num = (bottom.n * bottom.cos).re();
            let den = (top.n * top.cos).re();
            let factor = if num.v.re <= 0.0 || den.v.re <= 0.0 { Jet::real(0.0) } else { num / den };
            return Ok(RtaJet {
                r_s: gs.norm_sqr(),
                r_p: gp.norm_sqr(),
                t_s: zero_if_opaque(factor * ts.norm_sqr()),
                t_p: zero_if_opaque(factor * tp.norm_sqr()),
            });
        }
        // Incoherent media and the coherent groups between them (crate::incoherent).
        let inc = crate::incoherent::incoherent_media(self);
        let groups: Vec<[[Jet<K>; 4]; 2]> = inc
            .windows(2)
            .map(|w| {
                let gm = &m[w[0]..=w[1]];
                let gd = &d[w[0]..w[1] - 1];
                let rm: Vec<MJ<K>> = gm.iter().rev().copied().collect();
                let rd: Vec<Jet<K>> = gd.iter().rev().copied().collect();
                let f = compose(gm, gd, wavelength_nm);
                let b = compose(&rm, &rd, wavelength_nm);
                let (top, bottom) = (gm[0], gm[gm.len() - 1]);
                let pol = |k: usize, p: bool| {
                    [
                        f[k].norm_sqr(),
                        power_t(f[k + 2], top, bottom, p),
                        b[k].norm_sqr(),
                        power_t(b[k + 2], bottom, top, p),
                    ]
                };
                [pol(0, false), pol(1, true)]
            })
            .collect();
        // Single-pass transmission exp(−4π d Im(n̂ s_z)/λ) of every incoherent medium (1 at the ends).
        let pass: Vec<Jet<K>> = inc
            .iter()
            .map(|&i| {
                if i == 0 || i == m.len() - 1 {
                    Jet::real(1.0)
                } else {
                    ((m[i].n * m[i].cos).im() * d[i - 1] * (-4.0 * std::f64::consts::PI / wavelength_nm)).exp()
                }
            })
            .collect();
        let cascade = |pol: usize| {
            let [rf, tf, _, _] = groups[groups.len() - 1][pol];
            let (mut r, mut t) = (rf, tf);
            for k in (0..groups.len() - 1).rev() {
                let [rf, tf, rb, tb] = groups[k][pol];
                let pp = pass[k + 1] * pass[k + 1];
                let den = Jet::real(1.0) - rb * pp * r;
                (r, t) = (rf + tf * tb * pp * r / den, tf * pass[k + 1] * t / den);
            }
            (r, t)
        };
        let ((r_s, t_s), (r_p, t_p)) = (cascade(0), cascade(1));
        Ok(RtaJet { r_s, r_p, t_s: zero_if_opaque(t_s), t_p: zero_if_opaque(t_p) })
    }

    /// [`Stack::ellipsometry`] with derivatives: `(ψ, Δ)` in radians as real jets (coherent stacks; see
    /// [`Stack::ellipsometry`] for stacks with `inc:` layers, which have ψ but no Δ).
    pub fn ellipsometry_jet<const K: usize>(
        &self,
        wavelength_nm: f64,
        angle_rad: f64,
        tan: &Tangent<K>,
    ) -> Result<(Jet<K>, Jet<K>), ThinFilmError> {
        if self.has_incoherent() {
            return Err(crate::field::no_delta_through_incoherent(self));
        }
        let (m, d) = self.jet_inputs(wavelength_nm, angle_rad, tan)?;
        let [gs, gp, _, _] = compose(&m, &d, wavelength_nm);
        // ρ = −r_p/r_s = tan ψ e^{iΔ}: ψ = atan|ρ|, ∂ψ = ∂|ρ| / (1 + |ρ|²); Δ = arg ρ, ∂Δ = Im(∂ρ/ρ).
        let rho = -gp / gs;
        let abs = rho.norm_sqr().sqrt().re();
        let psi = abs.each(Complex64::new(abs.v.re.atan(), 0.0), |x| x / (1.0 + abs.v.re * abs.v.re));
        let delta = rho.each(Complex64::new(rho.v.arg(), 0.0), |x| Complex64::new((x / rho.v).im, 0.0));
        Ok((psi, delta))
    }
}
