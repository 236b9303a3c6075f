//! The calling convention of S. J. Byrnes' `tmm` package (<https://pypi.org/project/tmm/>, described in
//! arXiv:1603.02720), on iridis' physics: lists of complex indices and thicknesses with the two semi-infinite
//! media at the ends (`d = inf` there), one polarisation at a time, and tmm's conventions for everything it
//! reports — `r`, `t`, `R`, `T`, `power_entering`, the wave amplitudes `vw_list`, `kz_list` and the complex
//! angles `th_list`. The Python package's `iridis.tmm` is a thin binding of this module.
//!
//! Where tmm and the rest of iridis differ, this module follows tmm:
//! * `T` is the flux into the last medium even when it absorbs (Byrnes eq. 21–22); iridis' [`crate::Rta`]
//!   reports 0 there (`docs/PHYSICS.md`);
//! * `th_list` holds tmm's angles: `arcsin(n₀ sin θ₀ / n_j)` on the principal branch for the finite layers and
//!   the forward one for the two semi-infinite media; `kz_list` and `vw_list` follow that choice (the wave
//!   called forward in a layer is the one with `e^{+i k_z z}`). R and T do not depend on it.
//!
//! * complex angles: [`coh_tmm_complex`] takes `θ₀` complex and an absorbing first medium, as tmm does, when
//!   `n₀ sin θ₀` is real (tmm's condition; the incident wave is then uniform along the interfaces) and `θ₀` is
//!   the forward angle in `n₀`; `R`, `T` and `power_entering` use tmm's definitions (Byrnes eq. 21–23), in
//!   which `R + power_entering ≠ 1` when the first medium absorbs.
//!
//! Lengths are in any unit shared by the thicknesses and the wavelength (only `d/λ` enters).
//! Not reproduced: tmm's clamp of very opaque layers (`Im δ > 35` becomes 35, "1 photon in 10^30"), which
//! changes nothing above 1e-30.

use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI};

use num_complex::Complex64;
use rayon::prelude::*;
use wide::{f64x4, CmpGt, CmpLt, CmpNe};

use crate::error::ThinFilmError;
use crate::field::waves;
use crate::material::Material;
use crate::recurrence::{compose, fresnel, grazing_variants, Medium};
use crate::stack::{Layer, Stack};

/// tmm's `pol` argument.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pol {
    S,
    P,
}

impl Pol {
    /// `"s"` or `"p"`, with tmm's message otherwise.
    pub fn parse(s: &str) -> Result<Self, ThinFilmError> {
        match s {
            "s" => Ok(Pol::S),
            "p" => Ok(Pol::P),
            _ => Err(ThinFilmError::Invalid(format!("Polarization must be 's' or 'p' (got {s:?})"))),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Pol::S => "s",
            Pol::P => "p",
        }
    }
}

fn invalid(msg: String) -> ThinFilmError {
    ThinFilmError::Invalid(msg)
}

/// Checks `n_list` and `d_list` as tmm does (same length, `inf` at both ends), and what iridis needs besides:
/// finite thicknesses ≥ 0 inside, finite indices with `Re n > 0`, `κ ≥ 0` (no gain) and a lossless first medium.
pub fn check_lists(n: &[Complex64], d: &[f64]) -> Result<(), ThinFilmError> {
    check_lists_with(n, d, false)
}

/// [`check_lists`], with an absorbing first medium allowed (`absorbing_incident`, for complex angles).
fn check_lists_with(n: &[Complex64], d: &[f64], absorbing_incident: bool) -> Result<(), ThinFilmError> {
    if n.len() != d.len() || n.len() < 2 {
        return Err(invalid(format!(
            "Problem with n_list or d_list! (n_list has {} entries, d_list {}; both need the same number, at \
             least 2: the two semi-infinite media and the layers between)",
            n.len(),
            d.len()
        )));
    }
    if d[0] != f64::INFINITY || d[d.len() - 1] != f64::INFINITY {
        return Err(invalid(format!("d_list must start and end with inf! (got {} and {})", d[0], d[d.len() - 1])));
    }
    for (i, x) in d.iter().enumerate().take(d.len() - 1).skip(1) {
        if !(x.is_finite() && *x >= 0.0) {
            return Err(invalid(format!("d_list[{i}] = {x}: a layer thickness must be finite and ≥ 0")));
        }
    }
    for (i, x) in n.iter().enumerate() {
        if i == 0 && absorbing_incident {
            check_index(1, *x).map_err(|e| invalid(e.to_string().replacen("n_list[1]", "n_list[0]", 1)))?;
        } else {
            check_index(i, *x)?;
        }
    }
    Ok(())
}

fn check_index(i: usize, x: Complex64) -> Result<(), ThinFilmError> {
    if !(x.re.is_finite() && x.im.is_finite()) || x.re <= 0.0 {
        return Err(invalid(format!("n_list[{i}] = {x}: an index must be finite with a real part > 0")));
    }
    if x.norm() > crate::material::MAX_INDEX {
        return Err(invalid(format!(
            "n_list[{i}] = {x}: |n| is beyond {:e}, which no material reaches",
            crate::material::MAX_INDEX
        )));
    }
    if x.im < 0.0 {
        return Err(invalid(format!(
            "n_list[{i}] = {x}: Im n < 0 is gain; tmm's (and iridis') convention is n + iκ with κ ≥ 0 absorbing"
        )));
    }
    if i == 0 && x.im != 0.0 {
        return Err(invalid(format!(
            "Error in n0 or th0! n_list[0] = {x} absorbs: give th_0 as the complex angle that makes \
             n_list[0]·sin(th_0) real (tmm's convention, which iridis.tmm.coh_tmm accepts), e.g. \
             numpy.lib.scimath.arcsin(s / n_list[0]) for a real s"
        )));
    }
    Ok(())
}

/// Checks the angle (−π/2 ≤ θ₀ ≤ π/2: tmm's forward-angle condition for a lossless first medium) and the
/// wavelength.
pub fn check_angle_wavelength(th0: f64, lam: f64) -> Result<(), ThinFilmError> {
    if !(th0.is_finite() && th0.abs() <= FRAC_PI_2 + 1e-12) {
        return Err(invalid(format!(
            "Error in n0 or th0! th_0 = {th0} rad: light must arrive travelling forwards, |th_0| ≤ π/2"
        )));
    }
    if !(lam.is_finite() && lam > 0.0) {
        return Err(invalid(format!("lam_vac = {lam} must be finite and > 0")));
    }
    Ok(())
}

/// The media for iridis' recurrence: the incident one with `cos θ₀`, the others on the forward branch.
fn media_into(n: impl Iterator<Item = Complex64>, th0: f64, out: &mut Vec<Medium>) {
    out.clear();
    let a = th0.abs().min(FRAC_PI_2);
    let mut s = 0.0;
    for (j, x) in n.enumerate() {
        if j == 0 {
            s = x.re * a.sin();
            out.push(Medium { n: x, cos: Complex64::new(a.cos(), 0.0) });
        } else {
            out.push(Medium::new(x, s));
        }
    }
}

/// The normal flux of a unit wave in a medium (Byrnes eq. 21–22): `Re(n cos θ)` for s, `Re(n cos θ*)` for p.
fn flux(pol: Pol, m: Medium) -> f64 {
    match pol {
        Pol::S => (m.n * m.cos).re,
        Pol::P => (m.n * m.cos.conj()).re,
    }
}

/// `T` from `t` (tmm's `T_from_t`) and the power entering the first layer from `r` (`power_entering_from_r`).
fn powers(pol: Pol, r: Complex64, t: Complex64, first: Medium, last: Medium) -> (f64, f64, f64) {
    let f0 = flux(pol, first);
    let big_t = t.norm_sqr() * flux(pol, last) / f0;
    let one = Complex64::new(1.0, 0.0);
    let entering = match pol {
        Pol::S => (first.n * first.cos * (one + r.conj()) * (one - r)).re / f0,
        Pol::P => (first.n * first.cos.conj() * (one + r) * (one - r.conj())).re / f0,
    };
    (r.norm_sqr(), big_t, entering)
}

/// Everything `tmm.coh_tmm` reports, for one polarisation, wavelength and angle.
#[derive(Debug, Clone, PartialEq)]
pub struct Coherent {
    pub r: Complex64,
    pub t: Complex64,
    /// `R = |r|²`.
    pub big_r: f64,
    /// The flux into the last medium.
    pub big_t: f64,
    /// The flux into the first layer (`1 − R` when the incident medium is lossless).
    pub power_entering: f64,
    /// `[v_j, w_j]`: forward and backward amplitudes at the top of medium `j` (`[0, 0]` for the first, `[t, 0]`
    /// for the last).
    pub vw: Vec<[Complex64; 2]>,
    /// `k_z = 2π n_j cos θ_j / λ`.
    pub kz: Vec<Complex64>,
    /// The complex angles `θ_j`.
    pub th: Vec<Complex64>,
}

/// tmm's forward-angle test: `Im(n cos θ) > 0`, or `Re(n cos θ) > 0` when that imaginary part is ~0.
fn tmm_forward(n: Complex64, th: Complex64) -> bool {
    let q = n * th.cos();
    if q.im.abs() > 100.0 * f64::EPSILON {
        q.im > 0.0
    } else {
        q.re > 0.0
    }
}

/// The principal arcsin with C99's (and numpy's) value on the branch cut: for a real `|z| > 1` (zero
/// imaginary part, as tmm's `n₀ sin θ₀ / n_j` has for a lossless layer beyond its critical angle) the imaginary
/// part is `+acosh|z|`; num-complex's formula gives its conjugate there.
fn asin(z: Complex64) -> Complex64 {
    if z.im == 0.0 && z.re.abs() > 1.0 {
        Complex64::new(FRAC_PI_2.copysign(z.re), z.re.abs().acosh())
    } else {
        z.asin()
    }
}

/// `tmm.coh_tmm(pol, n, d, th0, lam)`.
pub fn coh_tmm(pol: Pol, n: &[Complex64], d: &[f64], th0: f64, lam: f64) -> Result<Coherent, ThinFilmError> {
    check_lists(n, d)?;
    check_angle_wavelength(th0, lam)?;
    let mut media = Vec::with_capacity(n.len());
    media_into(n.iter().copied(), th0, &mut media);
    Ok(coherent_from_media(pol, n, d, &media, n[0] * th0.sin(), lam))
}

/// `tmm.coh_tmm` with a complex `θ₀` (module documentation): the first medium may absorb when `n₀ sin θ₀` is
/// real (|Im| < 100 ε, tmm's test) and `θ₀` is the forward angle there (tmm's `is_forward_angle`). A real
/// `θ₀` with a lossless first medium is [`coh_tmm`].
pub fn coh_tmm_complex(
    pol: Pol,
    n: &[Complex64],
    d: &[f64],
    th0: Complex64,
    lam: f64,
) -> Result<Coherent, ThinFilmError> {
    if th0.im == 0.0 && n.first().is_some_and(|x| x.im == 0.0) {
        return coh_tmm(pol, n, d, th0.re, lam);
    }
    check_lists_with(n, d, true)?;
    if !(th0.re.is_finite() && th0.im.is_finite()) {
        return Err(invalid(format!("Error in n0 or th0! th_0 = {th0} must be finite")));
    }
    check_angle_wavelength(0.0, lam)?;
    let invariant = n[0] * th0.sin();
    if invariant.im.abs() >= 100.0 * f64::EPSILON {
        return Err(invalid(format!(
            "Error in n0 or th0! n_list[0]·sin(th_0) = {invariant} must be real (|Im| < 100 ε): the incident wave \
             must be uniform along the interfaces"
        )));
    }
    if !tmm_forward(n[0], th0) {
        return Err(invalid(format!(
            "Error in n0 or th0! th_0 = {th0} is not the forward-travelling angle in n_list[0] = {} (use π − th_0)",
            n[0]
        )));
    }
    let mut media = Vec::with_capacity(n.len());
    media.push(Medium { n: n[0], cos: th0.cos() });
    media.extend(n[1..].iter().map(|&x| Medium::new(x, invariant.re)));
    Ok(coherent_from_media(pol, n, d, &media, invariant, lam))
}

/// The rest of [`coh_tmm`] once the media are set: the recurrence, tmm's powers, angles, `k_z` and amplitudes.
fn coherent_from_media(
    pol: Pol,
    n: &[Complex64],
    d: &[f64],
    media: &[Medium],
    invariant: Complex64,
    lam: f64,
) -> Coherent {
    let inner = &d[1..d.len() - 1];
    let c = compose(media, inner, lam, None);
    let (r, t) = match pol {
        Pol::S => (c.gamma_s, c.tau_s),
        Pol::P => (c.gamma_p, c.tau_p),
    };
    let last = media.len() - 1;
    let (big_r, big_t, power_entering) = powers(pol, r, t, media[0], media[last]);

    // tmm's angles: principal arcsin, flipped to the forward wave in the two semi-infinite media.
    let th: Vec<Complex64> = n
        .iter()
        .enumerate()
        .map(|(j, &x)| {
            let a = asin(invariant / x);
            if (j == 0 || j == last) && !tmm_forward(x, a) {
                PI - a
            } else {
                a
            }
        })
        .collect();
    let tmm_media: Vec<Medium> = n.iter().zip(&th).map(|(&x, a)| Medium { n: x, cos: a.cos() }).collect();
    let kz = tmm_media.iter().map(|m| 2.0 * PI * m.n * m.cos / lam).collect();
    let wv = waves(&tmm_media, inner, lam, pol == Pol::P);
    let zero = Complex64::new(0.0, 0.0);
    let mut vw: Vec<[Complex64; 2]> = (0..n.len()).map(|j| [wv.v[j], wv.w[j]]).collect();
    vw[0] = [zero, zero];
    vw[last] = [t, zero];
    Coherent { r, t, big_r, big_t, power_entering, vw, kz, th }
}

/// `tmm.ellips`: `(ψ, Δ)` with `tan ψ e^{iΔ} = −r_p / r_s`.
pub fn ellips(n: &[Complex64], d: &[f64], th0: f64, lam: f64) -> Result<(f64, f64), ThinFilmError> {
    ellips_complex(n, d, Complex64::new(th0, 0.0), lam)
}

/// [`ellips`] with a complex `θ₀` ([`coh_tmm_complex`]).
pub fn ellips_complex(n: &[Complex64], d: &[f64], th0: Complex64, lam: f64) -> Result<(f64, f64), ThinFilmError> {
    let s = coh_tmm_complex(Pol::S, n, d, th0, lam)?;
    let p = coh_tmm_complex(Pol::P, n, d, th0, lam)?;
    Ok(crate::field::psi_delta(s.r, p.r))
}

/// A [`Stack`] of constant materials from tmm's lists; `incoherent[j]` marks tmm's `'i'` layers.
pub fn stack_from_lists(n: &[Complex64], d: &[f64], incoherent: Option<&[bool]>) -> Result<Stack, ThinFilmError> {
    check_lists(n, d)?;
    let m = |j: usize| Material::constant(format!("n={}", n[j]), n[j]);
    let layers = (1..n.len() - 1)
        .map(|j| Ok(Layer { material: m(j)?, thickness_nm: d[j], incoherent: incoherent.is_some_and(|c| c[j]) }))
        .collect::<Result<Vec<_>, ThinFilmError>>()?;
    Ok(Stack { incident: m(0)?, layers, substrate: m(n.len() - 1)? })
}

/// What `tmm.inc_tmm` and `tmm.inc_absorp_in_each_layer` report for one polarisation.
#[derive(Debug, Clone, PartialEq)]
pub struct Incoherent {
    pub big_r: f64,
    /// The flux into the last medium (absorbed there when it absorbs).
    pub big_t: f64,
    /// `[R, A_1, …, A_N, T]`, as `inc_absorp_in_each_layer`.
    pub absorp: Vec<f64>,
}

/// `tmm.inc_tmm(pol, n, d, c, th0, lam)` with `c[j]` = `'i'` (incoherent) or `'c'`; the ends must be `'i'`.
pub fn inc_tmm(
    pol: Pol,
    n: &[Complex64],
    d: &[f64],
    c: &[char],
    th0: f64,
    lam: f64,
) -> Result<Incoherent, ThinFilmError> {
    check_lists(n, d)?;
    if c.len() != n.len() {
        return Err(invalid(format!("List sizes do not match! (c_list has {}, n_list {})", c.len(), n.len())));
    }
    if c[0] != 'i' || c[c.len() - 1] != 'i' {
        return Err(invalid("c_list should start and end with \"i\"".into()));
    }
    if let Some(x) = c.iter().find(|x| **x != 'i' && **x != 'c') {
        return Err(invalid(format!("Error: c_list entries must be 'i' or 'c'! (got {x:?})")));
    }
    check_angle_wavelength(th0, lam)?;
    let inc: Vec<bool> = c.iter().map(|x| *x == 'i').collect();
    let stack = stack_from_lists(n, d, Some(&inc))?;
    let a = stack.absorption(lam, th0.abs())?;
    let (r, layers, sub, t) = match pol {
        Pol::S => (a.r_s, a.layers_s, a.substrate_s, a.t_s),
        Pol::P => (a.r_p, a.layers_p, a.substrate_p, a.t_p),
    };
    let mut absorp = Vec::with_capacity(n.len());
    absorp.push(r);
    absorp.extend(layers);
    absorp.push(sub + t);
    Ok(Incoherent { big_r: r, big_t: sub + t, absorp })
}

/// The indices of a batch: the same for every point, or one column per point (dispersive media), stored
/// medium-major: `data[j * points + i]` is medium `j` at point `i`.
#[derive(Debug, Clone, Copy)]
pub enum Indices<'a> {
    Constant(&'a [Complex64]),
    PerPoint { media: usize, data: &'a [Complex64] },
}

/// The results of [`coh_tmm_batch`], one entry per point.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Batch {
    pub r: Vec<Complex64>,
    pub t: Vec<Complex64>,
    pub big_r: Vec<f64>,
    pub big_t: Vec<f64>,
    pub power_entering: Vec<f64>,
}

/// Points per parallel task of [`coh_tmm_batch`] at least; a batch is cut into about four tasks per thread
/// (each task prepares the angles it meets once, so fewer, larger tasks repeat less of that work).
const MIN_CHUNK: usize = 4096;

/// One polarisation of a stack of constant indices prepared for one angle (Sussenbach's precalculation stage,
/// Algorithm 3, for the batch): the Fresnel amplitudes `(r_j, t_j)` of every interface and, per layer, the
/// phase per unit wavenumber `d_j n̂_j s_{z,j}` (eq. 3.5 without `2π/λ`), so that a point costs only the
/// phases' `e^{iφ}` and the recurrence (eq. 3.1–3.2) of the one polarisation asked for. One flat block of
/// numbers, read front to back at every point: `[Re r, Im r, Re t, Im t]` of interfaces `B_1 … B_{N+1}`, then
/// `Re(d_j n̂_j s_{z,j})` from the bottom layer up (zero-padded to a multiple of four), then
/// `Im(d_j n̂_j s_{z,j})` per layer, top to bottom (0 where a layer neither absorbs nor is evanescent).
#[derive(Debug, Clone)]
struct AngleKernel {
    layers: usize,
    data: Vec<f64>,
}

impl AngleKernel {
    fn new(pol: Pol, media: &[Medium], inner: &[f64]) -> Self {
        let layers = inner.len();
        let padded = layers.div_ceil(4) * 4;
        let mut data = Vec::with_capacity(4 * (layers + 1) + padded + layers);
        for j in 1..media.len() {
            let f = fresnel(media[j - 1], media[j]);
            let (r, t) = match pol {
                Pol::S => (f.r_s, f.t_s),
                Pol::P => (f.r_p, f.t_p),
            };
            data.extend([r.re, r.im, t.re, t.im]);
        }
        let phase: Vec<Complex64> =
            inner.iter().zip(&media[1..=layers]).map(|(&dj, mj)| dj * (mj.n * mj.cos)).collect();
        data.extend(phase.iter().rev().map(|q| q.re));
        data.resize(4 * (layers + 1) + padded, 0.0);
        data.extend(phase.iter().map(|q| q.im));
        Self { layers, data }
    }

    /// Eq. 3.1–3.2 from the bottom interface up, at wavenumber `k = 2π/λ`, in projective form: with
    /// `γ = N/D` and `τ = M/D` a layer is `N' = r D + N e^{2iφ}`, `D' = D + r N e^{2iφ}`, `M' = t e^{iφ} M`
    /// (the same algebra as `γ' = (r + γ e^{2iφ}) / (1 + r γ e^{2iφ})`, `τ' = t τ e^{iφ} / (1 + r γ e^{2iφ})`),
    /// so that no layer divides — one division at the top gives `(γ, τ)` — and `e^{iφ}` of four layers at a
    /// time: one SIMD `sin_cos` of their `Re φ`, times `e^{−Im φ}` where a layer decays.
    #[inline]
    fn amplitudes(&self, k: f64) -> (Complex64, Complex64) {
        let n = self.layers;
        let (rt, rest) = self.data.split_at(4 * (n + 1));
        let (phase_re_up, phase_im) = rest.split_at(rest.len() - n);
        let interface = |j: usize| {
            let x = &rt[4 * j..4 * j + 4];
            (Complex64::new(x[0], x[1]), Complex64::new(x[2], x[3]))
        };
        let (r0, t0) = interface(n);
        let (mut num, mut den, mut m) = (r0, Complex64::new(1.0, 0.0), t0);
        let kk = f64x4::splat(k);
        for (b, four) in phase_re_up.chunks_exact(4).enumerate() {
            let (sin, cos) = (kk * f64x4::new([four[0], four[1], four[2], four[3]])).sin_cos();
            let (sin, cos) = (sin.to_array(), cos.to_array());
            for l in 0..4.min(n - 4 * b) {
                let j = n - 1 - (4 * b + l);
                let mut e1 = Complex64::new(cos[l], sin[l]);
                if phase_im[j] != 0.0 {
                    // Im φ ≥ 0 on the forward branch: |e^{iφ}| ≤ 1, nothing overflows.
                    e1 *= (-k * phase_im[j]).exp();
                }
                let (r, t) = interface(j);
                let ne2 = num * (e1 * e1);
                num = r * den + ne2;
                den += r * ne2;
                m = t * e1 * m;
                // |D| can grow by up to 2× a layer: bring it back near 1 long before f64 would overflow.
                let size = den.norm_sqr();
                if !(1e-150..=1e150).contains(&size) {
                    let s = 1.0 / size.sqrt();
                    (num, den, m) = (num * s, den * s, m * s);
                }
            }
        }
        let inv = den.inv();
        (num * inv, m * inv)
    }

    /// [`AngleKernel::amplitudes`] for four points at once, vectorised across the points, as SIMD lanes
    /// `[Re γ, Im γ, Re τ, Im τ]`: lane `l` runs `kernels[l]` (kernels of one stack, so of one layer count; the
    /// angles may differ) at wavenumber `kk[l]`.
    /// Every layer costs one SIMD `sin_cos` for the four points, and one SIMD `exp` where a layer decays —
    /// where the per-point kernel spends a `sin_cos` per four layers and a scalar `exp` per absorbing layer,
    /// which for the few layers of most films leaves lanes idle (issue 29: a 2-layer absorbing stack).
    #[inline]
    fn amplitudes4_lanes(kernels: [&AngleKernel; 4], kk: f64x4) -> [f64x4; 4] {
        let n = kernels[0].layers;
        let base = 4 * (n + 1);
        let im_at = base + n.div_ceil(4) * 4;
        let lanes =
            |f: &dyn Fn(&AngleKernel) -> f64| f64x4::new([f(kernels[0]), f(kernels[1]), f(kernels[2]), f(kernels[3])]);
        let (one, zero) = (f64x4::splat(1.0), f64x4::splat(0.0));
        let (mut num_re, mut num_im) = (lanes(&|q| q.data[4 * n]), lanes(&|q| q.data[4 * n + 1]));
        let (mut den_re, mut den_im) = (one, zero);
        let (mut m_re, mut m_im) = (lanes(&|q| q.data[4 * n + 2]), lanes(&|q| q.data[4 * n + 3]));
        for j in (0..n).rev() {
            let (sin, cos) = (kk * lanes(&|q| q.data[base + n - 1 - j])).sin_cos();
            let (mut e_re, mut e_im) = (cos, sin);
            let decay = lanes(&|q| q.data[im_at + j]);
            if decay.cmp_ne(zero).any() {
                // Im φ ≥ 0 on the forward branch: |e^{iφ}| ≤ 1, nothing overflows.
                let d = (-(kk * decay)).exp();
                e_re *= d;
                e_im *= d;
            }
            let (r_re, r_im) = (lanes(&|q| q.data[4 * j]), lanes(&|q| q.data[4 * j + 1]));
            let (t_re, t_im) = (lanes(&|q| q.data[4 * j + 2]), lanes(&|q| q.data[4 * j + 3]));
            let (e2_re, e2_im) = (e_re * e_re - e_im * e_im, 2.0 * e_re * e_im);
            let (ne_re, ne_im) = (num_re * e2_re - num_im * e2_im, num_re * e2_im + num_im * e2_re);
            let (rd_re, rd_im) = (r_re * den_re - r_im * den_im, r_re * den_im + r_im * den_re);
            let (rn_re, rn_im) = (r_re * ne_re - r_im * ne_im, r_re * ne_im + r_im * ne_re);
            num_re = rd_re + ne_re;
            num_im = rd_im + ne_im;
            den_re += rn_re;
            den_im += rn_im;
            let (te_re, te_im) = (t_re * e_re - t_im * e_im, t_re * e_im + t_im * e_re);
            (m_re, m_im) = (te_re * m_re - te_im * m_im, te_re * m_im + te_im * m_re);
            // |D| can grow by up to 2× a layer: bring it back near 1 long before f64 would overflow.
            let size = den_re * den_re + den_im * den_im;
            let out = size.cmp_gt(f64x4::splat(1e150)) | size.cmp_lt(f64x4::splat(1e-150));
            if out.any() {
                let s = out.blend(one / size.sqrt(), one);
                (num_re, num_im, den_re, den_im, m_re, m_im) =
                    (num_re * s, num_im * s, den_re * s, den_im * s, m_re * s, m_im * s);
            }
        }
        let size = den_re * den_re + den_im * den_im;
        let (inv_re, inv_im) = (den_re / size, -den_im / size);
        [
            num_re * inv_re - num_im * inv_im,
            num_re * inv_im + num_im * inv_re,
            m_re * inv_re - m_im * inv_im,
            m_re * inv_im + m_im * inv_re,
        ]
    }
}

/// One angle of the batch: its kernel (and a second one, averaged with it, when a layer grazes:
/// `recurrence::grazing_variants`), and what turns amplitudes into tmm's powers there ([`powers`], with the
/// per-angle factors taken out of the loop over points).
#[derive(Debug, Clone)]
struct AngleEntry {
    kernel: AngleKernel,
    grazing: Option<AngleKernel>,
    /// `flux(last) / flux(first)`: `T = |t|²` times this.
    t_factor: f64,
    /// `n₀ cos θ₀` (conjugated cosine for p) over `flux(first)`: `power_entering = Re(this · (1 ± r̄)(1 ∓ r))`.
    entering: Complex64,
}

impl AngleEntry {
    fn new(pol: Pol, n: &[Complex64], d: &[f64], angle: f64, media: &mut Vec<Medium>) -> Self {
        media_into(n.iter().copied(), angle, media);
        let inner = &d[1..d.len() - 1];
        let (kernel, grazing) = match grazing_variants(media) {
            Some([plus, minus]) => (AngleKernel::new(pol, &plus, inner), Some(AngleKernel::new(pol, &minus, inner))),
            None => (AngleKernel::new(pol, media, inner), None),
        };
        let (first, last) = (media[0], media[media.len() - 1]);
        let f0 = flux(pol, first);
        let entering = match pol {
            Pol::S => first.n * first.cos,
            Pol::P => first.n * first.cos.conj(),
        } / f0;
        Self { kernel, grazing, t_factor: flux(pol, last) / f0, entering }
    }

    /// `r`, `t`, `R`, `T` and `power_entering` at one wavelength.
    #[inline]
    fn point(&self, pol: Pol, lam: f64) -> (Complex64, Complex64, f64, f64, f64) {
        let k = 2.0 * PI / lam;
        let (r, t) = match &self.grazing {
            None => self.kernel.amplitudes(k),
            Some(other) => {
                let (x, y) = (self.kernel.amplitudes(k), other.amplitudes(k));
                (0.5 * (x.0 + y.0), 0.5 * (x.1 + y.1))
            }
        };
        self.outputs(pol, r, t)
    }

    /// tmm's outputs from the amplitudes at this angle.
    #[inline]
    fn outputs(&self, pol: Pol, r: Complex64, t: Complex64) -> (Complex64, Complex64, f64, f64, f64) {
        let one = Complex64::new(1.0, 0.0);
        let entering = match pol {
            Pol::S => (self.entering * (one + r.conj()) * (one - r)).re,
            Pol::P => (self.entering * (one + r) * (one - r.conj())).re,
        };
        (r, t, r.norm_sqr(), t.norm_sqr() * self.t_factor, entering)
    }
}

/// The angles one task of the batch has met, found by their bits: a direct-mapped table of recent ones in front
/// of a hash map (one multiplication to look up; the batch looks an angle up at every point).
#[derive(Debug)]
struct AngleCache {
    /// `(bits, index + 1)`; index + 1 = 0: empty.
    recent: Vec<(u64, usize)>,
    index: AngleMap,
    entries: Vec<AngleEntry>,
}

impl AngleCache {
    const SLOTS: usize = 256;

    fn new() -> Self {
        Self { recent: vec![(0, 0); Self::SLOTS], index: AngleMap::default(), entries: Vec::new() }
    }

    #[inline]
    fn get(&mut self, angle: f64, make: impl FnOnce(f64) -> AngleEntry) -> &AngleEntry {
        let e = self.position(angle, make);
        &self.entries[e]
    }

    /// The index of the angle's entry in `entries`, made the first time.
    #[inline]
    fn position(&mut self, angle: f64, make: impl FnOnce(f64) -> AngleEntry) -> usize {
        let bits = angle.to_bits();
        let slot = (bits.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 56) as usize;
        let (b, e) = self.recent[slot];
        if e != 0 && b == bits {
            return e - 1;
        }
        let entries = &mut self.entries;
        let e = *self.index.entry(bits).or_insert_with(|| {
            entries.push(make(angle));
            entries.len() - 1
        });
        self.recent[slot] = (bits, e + 1);
        e
    }
}

/// A hasher for angles' bit patterns: one multiplication (std's SipHash, built against hostile keys, costs
/// more than the recurrence of a thin layer).
#[derive(Debug, Default, Clone, Copy)]
struct AngleHasher(u64);

impl std::hash::Hasher for AngleHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(5) ^ b as u64).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (x ^ (x >> 29)).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

type AngleMap = HashMap<u64, usize, std::hash::BuildHasherDefault<AngleHasher>>;

/// `coh_tmm` at many (θ₀, λ) points (`th0` and `lam` of equal length): `r`, `t`, `R`, `T`, `power_entering`
/// as `coh_tmm` gives them, in parallel over chunks of points. With constant indices each chunk prepares every
/// angle it meets once (`AngleEntry`: the chapter 4 fast path for the one polarisation asked for) and reuses
/// it for the points at that angle.
pub fn coh_tmm_batch(pol: Pol, n: Indices<'_>, d: &[f64], th0: &[f64], lam: &[f64]) -> Result<Batch, ThinFilmError> {
    let points = th0.len();
    if lam.len() != points {
        return Err(invalid(format!("{} angles but {} wavelengths", points, lam.len())));
    }
    let media_count = match n {
        Indices::Constant(x) => x.len(),
        Indices::PerPoint { media, data } => {
            if data.len() != media * points {
                return Err(invalid(format!(
                    "n_list has {} values; {media} media × {points} points need {}",
                    data.len(),
                    media * points
                )));
            }
            media
        }
    };
    if points == 0 {
        if let Indices::Constant(x) = n {
            check_lists(x, d)?;
        }
        return Ok(Batch::default());
    }
    let first_n: Vec<Complex64> = match n {
        Indices::Constant(x) => x.to_vec(),
        Indices::PerPoint { data, .. } => (0..media_count).map(|j| data[j * points]).collect(),
    };
    check_lists(&first_n, d)?;
    let inner = &d[1..d.len() - 1];
    let zero = Complex64::new(0.0, 0.0);
    let mut out = Batch {
        r: vec![zero; points],
        t: vec![zero; points],
        big_r: vec![0.0; points],
        big_t: vec![0.0; points],
        power_entering: vec![0.0; points],
    };
    let pick = |a: [Complex64; 4]| match pol {
        Pol::S => (a[0], a[2]),
        Pol::P => (a[1], a[3]),
    };
    let chunk = MIN_CHUNK.max(points.div_ceil(4 * rayon::current_num_threads()));
    out.r
        .par_chunks_mut(chunk)
        .zip(out.t.par_chunks_mut(chunk))
        .zip(out.big_r.par_chunks_mut(chunk))
        .zip(out.big_t.par_chunks_mut(chunk))
        .zip(out.power_entering.par_chunks_mut(chunk))
        .enumerate()
        .try_for_each(|(c, ((((r, t), big_r), big_t), pe))| -> Result<(), ThinFilmError> {
            let start = c * chunk;
            let mut media = Vec::with_capacity(media_count);
            // Per angle in this chunk: its kernel, prepared the first time the angle comes.
            let mut cache = AngleCache::new();
            // Constant indices: four points at a time through the vectorised kernel (lanes may have different
            // angles), the rest — and any four with a grazing layer, whose two kernels are averaged — one by one.
            let mut next = 0;
            if let Indices::Constant(x) = n {
                // The chunk's angles and wavelengths are checked first, in one pass (the error names the first bad
                // point); the loop below then has no error path. Consecutive points often share their angle
                // (spectra): the last angle's entry is kept without a lookup.
                let (th_c, lam_c) = (&th0[start..start + r.len()], &lam[start..start + r.len()]);
                if th_c.iter().zip(lam_c).any(|(&a, &l)| check_angle_wavelength(a, l).is_err()) {
                    let k = (0..r.len()).find(|&k| check_angle_wavelength(th_c[k], lam_c[k]).is_err()).unwrap_or(0);
                    check_angle_wavelength(th_c[k], lam_c[k])
                        .map_err(|e| invalid(format!("{e} (at point {} of the batch)", start + k)))?;
                }
                let mut last: Option<(u64, usize)> = None;
                while next + 4 <= r.len() {
                    let mut e = [0usize; 4];
                    for l in 0..4 {
                        let a = th_c[next + l].abs().min(FRAC_PI_2);
                        e[l] = match last {
                            Some((bits, idx)) if bits == a.to_bits() => idx,
                            _ => {
                                let idx = cache.position(a, |a| AngleEntry::new(pol, x, d, a, &mut media));
                                last = Some((a.to_bits(), idx));
                                idx
                            }
                        };
                    }
                    let entries = e.map(|e| &cache.entries[e]);
                    if entries.iter().any(|x| x.grazing.is_some()) {
                        break;
                    }
                    let i = start + next;
                    let kk = f64x4::splat(2.0 * PI) / f64x4::new([lam[i], lam[i + 1], lam[i + 2], lam[i + 3]]);
                    let [g_re, g_im, t_re, t_im] = AngleKernel::amplitudes4_lanes(entries.map(|x| &x.kernel), kk);
                    // R = |γ|², T = |τ|² flux(last)/flux(first), and the power entering (AngleEntry::outputs) as
                    // lanes: (1 ± r̄)(1 ∓ r) = 1 − |r|² ∓ 2i Im r for s and p.
                    let big_r4 = g_re * g_re + g_im * g_im;
                    let tf = f64x4::new(entries.map(|x| x.t_factor));
                    let big_t4 = (t_re * t_re + t_im * t_im) * tf;
                    let (e_re, e_im) =
                        (f64x4::new(entries.map(|x| x.entering.re)), f64x4::new(entries.map(|x| x.entering.im)));
                    let sign = if pol == Pol::S { 2.0 } else { -2.0 };
                    let pe4 = e_re * (f64x4::splat(1.0) - big_r4) + f64x4::splat(sign) * e_im * g_im;
                    let (gr, gi, tr, ti) = (g_re.to_array(), g_im.to_array(), t_re.to_array(), t_im.to_array());
                    let (x_r, x_t, x_pe) = (big_r4.to_array(), big_t4.to_array(), pe4.to_array());
                    for l in 0..4 {
                        let k = next + l;
                        r[k] = Complex64::new(gr[l], gi[l]);
                        t[k] = Complex64::new(tr[l], ti[l]);
                        big_r[k] = x_r[l];
                        big_t[k] = x_t[l];
                        pe[k] = x_pe[l];
                    }
                    next += 4;
                }
            }
            for k in next..r.len() {
                let i = start + k;
                check_angle_wavelength(th0[i], lam[i])
                    .map_err(|e| invalid(format!("{e} (at point {i} of the batch)")))?;
                let (rr, tt, x_r, x_t, x_pe) = match n {
                    Indices::Constant(x) => {
                        let a = th0[i].abs().min(FRAC_PI_2);
                        cache.get(a, |a| AngleEntry::new(pol, x, d, a, &mut media)).point(pol, lam[i])
                    }
                    Indices::PerPoint { data, .. } => {
                        for j in 0..media_count {
                            check_index(j, data[j * points + i])
                                .map_err(|e| invalid(format!("{e} (at point {i} of the batch)")))?;
                        }
                        media_into((0..media_count).map(|j| data[j * points + i]), th0[i], &mut media);
                        let c = compose(&media, inner, lam[i], None);
                        let (rr, tt) = pick([c.gamma_s, c.gamma_p, c.tau_s, c.tau_p]);
                        let (x_r, x_t, x_pe) = powers(pol, rr, tt, media[0], media[media.len() - 1]);
                        (rr, tt, x_r, x_t, x_pe)
                    }
                };
                r[k] = rr;

                t[k] = tt;
                big_r[k] = x_r;
                big_t[k] = x_t;
                pe[k] = x_pe;
            }
            Ok(())
        })?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::c64 as c;

    #[test]
    fn single_interface_is_fresnel() {
        // Air → glass at normal incidence: r_s = (1 − 1.5)/(1 + 1.5) = −0.2, R = 0.04, T = 0.96.
        let x = coh_tmm(Pol::S, &[c(1.0, 0.0), c(1.5, 0.0)], &[f64::INFINITY; 2], 0.0, 500.0).unwrap();
        assert!((x.r - c(-0.2, 0.0)).norm() < 1e-15 && (x.big_r - 0.04).abs() < 1e-15);
        assert!((x.big_t - 0.96).abs() < 1e-15 && (x.power_entering - 0.96).abs() < 1e-15);
        assert_eq!(x.vw[1], [x.t, c(0.0, 0.0)]);
    }

    #[test]
    fn batch_equals_single_calls() {
        let n = [c(1.0, 0.0), c(2.1, 0.0), c(1.4, 0.02), c(3.5, 0.3)];
        let d = [f64::INFINITY, 120.0, 333.0, f64::INFINITY];
        let th: Vec<f64> = (0..40).map(|i| (i % 8) as f64 * 0.2).collect();
        let lam: Vec<f64> = (0..40).map(|i| 380.0 + 10.0 * i as f64).collect();
        for pol in [Pol::S, Pol::P] {
            let b = coh_tmm_batch(pol, Indices::Constant(&n), &d, &th, &lam).unwrap();
            let e = coh_tmm_batch(pol, Indices::Constant(&n), &d, &[], &[]).unwrap();
            assert!(e.r.is_empty());
            for i in 0..40 {
                let one = coh_tmm(pol, &n, &d, th[i], lam[i]).unwrap();
                assert!((b.r[i] - one.r).norm() < 1e-13 && (b.t[i] - one.t).norm() < 1e-13);
                assert!(
                    (b.big_t[i] - one.big_t).abs() < 1e-13 && (b.power_entering[i] - one.power_entering).abs() < 1e-13
                );
            }
        }
    }

    #[test]
    fn batch_equals_single_calls_at_and_beyond_a_critical_angle() {
        // A lossless layer of lower index: real phases below its critical angle (the sin_cos path), evanescent
        // beyond it (the exp path), and grazing at it (two kernels averaged, recurrence::grazing_variants);
        // the per-point path (dispersive indices) on the same points as a third opinion.
        let n = [c(1.5, 0.0), c(1.0, 0.0), c(2.0, 0.01), c(1.5, 0.0)];
        let d = [f64::INFINITY, 300.0, 80.0, f64::INFINITY];
        let critical = (1.0f64 / 1.5).asin();
        let th: Vec<f64> = [0.0, 0.3, critical - 1e-7, critical, critical + 1e-7, 0.9, 1.2, -0.3]
            .iter()
            .flat_map(|&a| [a; 3])
            .collect();
        let lam: Vec<f64> = (0..th.len()).map(|i| 400.0 + 13.0 * i as f64).collect();
        let per_point: Vec<Complex64> = n.iter().flat_map(|&x| vec![x; th.len()]).collect();
        for pol in [Pol::S, Pol::P] {
            let b = coh_tmm_batch(pol, Indices::Constant(&n), &d, &th, &lam).unwrap();
            let q = coh_tmm_batch(pol, Indices::PerPoint { media: n.len(), data: &per_point }, &d, &th, &lam).unwrap();
            for i in 0..th.len() {
                let one = coh_tmm(pol, &n, &d, th[i], lam[i]).unwrap();
                // Within ~ε/δ of each other at the critical angle (δ = GRAZING_COS: the variants' conditioning).
                for (x, y) in [(b.r[i], one.r), (b.t[i], one.t), (q.r[i], one.r), (q.t[i], one.t)] {
                    assert!((x - y).norm() < 1e-11, "{pol:?} θ {} λ {}: {x} vs {y}", th[i], lam[i]);
                }
                for (x, y) in
                    [(b.big_r[i], one.big_r), (b.big_t[i], one.big_t), (b.power_entering[i], one.power_entering)]
                {
                    assert!((x - y).abs() < 1e-11, "{pol:?} θ {} λ {}: {x} vs {y}", th[i], lam[i]);
                }
            }
        }
    }

    #[test]
    fn four_point_kernel_equals_single_calls_on_deep_stacks() {
        // 60 layers (high/low pairs, absorbing and evanescent ones among them, a thick metal that makes |D| grow
        // past the rescaling threshold), angles differing within every group of four, and a tail of points
        // that is not a multiple of four.
        let mut n = vec![c(1.0, 0.0)];
        let mut d = vec![f64::INFINITY];
        for j in 0..30 {
            n.extend([c(2.3, 0.001 * j as f64), c(1.38, 0.0)]);
            d.extend([55.0 + j as f64, 93.0]);
        }
        n[40] = c(0.2, 3.4);
        d[40] = 3000.0;
        n.push(c(1.52, 0.0));
        d.push(f64::INFINITY);
        let th: Vec<f64> = (0..23).map(|i| (i % 7) as f64 * 0.21).collect();
        let lam: Vec<f64> = (0..23).map(|i| 350.0 + 31.0 * i as f64).collect();
        for pol in [Pol::S, Pol::P] {
            let b = coh_tmm_batch(pol, Indices::Constant(&n), &d, &th, &lam).unwrap();
            for i in 0..th.len() {
                let one = coh_tmm(pol, &n, &d, th[i], lam[i]).unwrap();
                assert!((b.r[i] - one.r).norm() < 1e-12 * (1.0 + one.r.norm()), "{pol:?} {i}: {} vs {}", b.r[i], one.r);
                assert!(
                    (b.t[i] - one.t).norm() <= 1e-12 * one.t.norm() + 1e-300,
                    "{pol:?} {i}: {} vs {}",
                    b.t[i],
                    one.t
                );
                assert!(
                    (b.big_r[i] - one.big_r).abs() < 1e-12 && (b.power_entering[i] - one.power_entering).abs() < 1e-12
                );
            }
        }
    }

    #[test]
    fn complex_angles_as_tmm_takes_them() {
        // A real angle written as complex is the real calculation; an absorbing first medium takes the complex
        // angle that makes n₀ sin θ₀ real (tmm's convention) and is refused otherwise.
        let n = [c(1.0, 0.0), c(2.0, 0.1), c(1.5, 0.0)];
        let d = [f64::INFINITY, 200.0, f64::INFINITY];
        let a = coh_tmm(Pol::P, &n, &d, 0.4, 500.0).unwrap();
        let b = coh_tmm_complex(Pol::P, &n, &d, c(0.4, 0.0), 500.0).unwrap();
        assert_eq!(a, b);
        let n0 = c(1.5, 0.02);
        let th0 = asin(c(0.6, 0.0) / n0);
        let x = coh_tmm_complex(Pol::S, &[n0, c(2.0, 0.0), c(1.0, 0.0)], &d, th0, 500.0).unwrap();
        assert!(x.big_r > 0.0 && x.big_r < 1.0 && (x.th[1] - asin(c(0.3, 0.0))).norm() < 1e-12, "{x:?}");
        assert!(coh_tmm_complex(Pol::S, &[n0, c(2.0, 0.0), c(1.0, 0.0)], &d, c(0.4, 0.0), 500.0).is_err());
        assert!(coh_tmm(Pol::S, &[n0, c(2.0, 0.0), c(1.0, 0.0)], &d, 0.4, 500.0).is_err());
    }

    #[test]
    fn bad_lists_are_refused_with_tmm_messages() {
        let e = coh_tmm(Pol::S, &[c(1.0, 0.0), c(1.5, 0.0)], &[0.0, f64::INFINITY], 0.0, 500.0).unwrap_err();
        assert!(e.to_string().starts_with("d_list must start and end with inf!"), "{e}");
        let e = coh_tmm(Pol::S, &[c(1.0, 0.0)], &[f64::INFINITY, f64::INFINITY], 0.0, 500.0).unwrap_err();
        assert!(e.to_string().starts_with("Problem with n_list or d_list!"), "{e}");
        assert!(Pol::parse("x").unwrap_err().to_string().starts_with("Polarization must be 's' or 'p'"));
    }
}
