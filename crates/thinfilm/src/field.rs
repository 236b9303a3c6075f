//! Where the light goes inside a coherent stack: the forward and backward wave amplitudes in every medium,
//! the position-resolved Poynting flux, absorbed power density and |E|², the power absorbed in each layer,
//! and the ellipsometric angles ψ, Δ.
//!
//! The amplitudes come from the composite reflectivities Γ_j of Sussenbach eq. 3.1 kept at every interface:
//! below interface `B_j` the forward amplitude `v_j` satisfies `v_j (1 + r_j Γ_{j+1} e^{2iφ_j}) = t_j a_j`
//! (`a_j` the forward amplitude arriving from above; Stokes: the reflection from below is `−r_j`) and the
//! backward one is `w_j = v_j Γ_{j+1} e^{2iφ_j}`. The flux, absorption and field formulas are those of
//! Byrnes, "Multilayer optical calculations" (arXiv:1603.02720, section 4), which `tmm.position_resolved`
//! implements; the tests compare with it (`tools/gen_incoherent_fixtures.py`).

use num_complex::Complex64;
use serde::Serialize;

use crate::error::ThinFilmError;
use crate::recurrence::{fresnel, phase, Medium};
use crate::stack::Stack;

/// The waves of one polarisation: `v[j]`, `w[j]` forward/backward amplitudes at the top of medium `j`
/// (for `j = 0`, at the first interface: `v = 1`, `w = r`).
#[derive(Debug, Clone)]
pub(crate) struct Waves {
    pub(crate) v: Vec<Complex64>,
    pub(crate) w: Vec<Complex64>,
    p: bool,
}

/// The fields of a coherent stack at one wavelength and angle, both polarisations.
#[derive(Debug, Clone)]
pub struct Fields {
    media: Vec<Medium>,
    thicknesses: Vec<f64>,
    wavelength_nm: f64,
    s: Waves,
    p: Waves,
    /// `n₀ sin θ₀`, for `sin θ_j = n₀ sin θ₀ / n̂_j`.
    invariant: f64,
}

/// One point of a profile: normal Poynting flux (fraction of the incident power crossing the plane),
/// absorbed power density (fraction of the incident power per nm) and |E|² (incident |E| = 1), for s, p.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Point {
    pub z_nm: f64,
    /// 0 = incident medium, 1..=N layers, N + 1 = substrate.
    pub medium: usize,
    pub poynting_s: f64,
    pub poynting_p: f64,
    pub absorption_s: f64,
    pub absorption_p: f64,
    pub e2_s: f64,
    pub e2_p: f64,
}

impl Point {
    /// The point at depth `z_nm` in `medium` from each polarisation's (flux, absorbed density, |E|²).
    pub(crate) fn from_pols(z_nm: f64, medium: usize, s: [f64; 3], p: [f64; 3]) -> Self {
        Point {
            z_nm,
            medium,
            poynting_s: s[0],
            poynting_p: p[0],
            absorption_s: s[1],
            absorption_p: p[1],
            e2_s: s[2],
            e2_p: p[2],
        }
    }
    pub fn poynting(&self) -> f64 {
        0.5 * (self.poynting_s + self.poynting_p)
    }
    pub fn absorption(&self) -> f64 {
        0.5 * (self.absorption_s + self.absorption_p)
    }
    pub fn e2(&self) -> f64 {
        0.5 * (self.e2_s + self.e2_p)
    }
}

/// The fraction of the incident power absorbed in each layer and in the substrate (entering an absorbing
/// substrate; 0 otherwise), with R and T: `R + T + Σ layers + substrate = 1`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Absorption {
    pub layers_s: Vec<f64>,
    pub layers_p: Vec<f64>,
    pub substrate_s: f64,
    pub substrate_p: f64,
    pub r_s: f64,
    pub r_p: f64,
    pub t_s: f64,
    pub t_p: f64,
}

impl Absorption {
    /// Unpolarised absorption per layer.
    pub fn layers(&self) -> Vec<f64> {
        self.layers_s.iter().zip(&self.layers_p).map(|(s, p)| 0.5 * (s + p)).collect()
    }
    pub fn substrate(&self) -> f64 {
        0.5 * (self.substrate_s + self.substrate_p)
    }
    /// `R + T + Σ A − 1` (unpolarised): zero up to rounding.
    pub fn balance(&self) -> f64 {
        0.5 * (self.r_s + self.r_p + self.t_s + self.t_p) + self.layers().iter().sum::<f64>() + self.substrate() - 1.0
    }
}

impl Stack {
    /// The fields of a coherent stack (no `inc:` layer) at one wavelength (nm) and angle (rad).
    pub fn fields(&self, wavelength_nm: f64, angle_rad: f64) -> Result<Fields, ThinFilmError> {
        if self.has_incoherent() {
            return Err(ThinFilmError::Invalid(format!(
                "\"{self}\" has an incoherent (inc:) layer, so no single coherent field: use Stack::profile \
                 (intensities lit from both sides) or the absorption per layer, which handle both"
            )));
        }
        let media = self.media(wavelength_nm, angle_rad)?;
        Ok(Fields::new(media, self.thicknesses(), wavelength_nm))
    }

    /// Ellipsometric angles `(ψ, Δ)` in radians with tmm's `ellips` convention:
    /// `tan ψ e^{iΔ} = −r_p / r_s`, ψ ∈ [0, π/2], Δ ∈ (−π, π]. With iridis' (and tmm's) sign of `r_p`
    /// (Sussenbach eq. 3.7, `r_p = −r_s` at normal incidence) a bare substrate at normal incidence has Δ = 0.
    ///
    /// A stack with an incoherent (`inc:`) layer has no Δ: the light leaving it is an incoherent sum of
    /// beams with unrelated phases (partly depolarised), so no single phase difference between p and s
    /// exists; this returns an error that says so. Its ψ is defined: see [`Stack::psi`].
    pub fn ellipsometry(&self, wavelength_nm: f64, angle_rad: f64) -> Result<(f64, f64), ThinFilmError> {
        if self.has_incoherent() {
            return Err(no_delta_through_incoherent(self));
        }
        let a = self.amplitudes(wavelength_nm, angle_rad)?;
        Ok(psi_delta(a.r_s, a.r_p))
    }

    /// The ellipsometric ψ (radians) of any stack: `tan ψ = √(R_p / R_s)`. For a coherent stack this is
    /// `|r_p / r_s|`, the ψ of [`Stack::ellipsometry`]; with `inc:` layers it is what an ellipsometer's
    /// intensity ratio measures (the normalised Mueller element `N = −M₁₂/M₁₁ = cos 2ψ` of an incoherent
    /// sum of beams is `(R_s − R_p)/(R_s + R_p)`), while Δ is not defined.
    pub fn psi(&self, wavelength_nm: f64, angle_rad: f64) -> Result<f64, ThinFilmError> {
        if !self.has_incoherent() {
            return Ok(self.ellipsometry(wavelength_nm, angle_rad)?.0);
        }
        let x = self.evaluate(wavelength_nm, angle_rad)?;
        Ok((x.r_p / x.r_s).sqrt().atan())
    }
}

/// The error of asking for Δ of a stack with an incoherent layer.
pub(crate) fn no_delta_through_incoherent(stack: &Stack) -> ThinFilmError {
    ThinFilmError::Invalid(format!(
        "\"{stack}\" has an incoherent (inc:) layer, so its reflection has no Δ: the beams returned by the \
         incoherent layer add as intensities with unrelated phases (the light is partly depolarised), and no \
         single p–s phase difference exists. ψ is defined (tan ψ = √(R_p/R_s)); fit R, T, or make the layer \
         coherent if its thickness is below the coherence length"
    ))
}

/// `(ψ, Δ)` from `r_s`, `r_p` (see [`Stack::ellipsometry`]).
pub fn psi_delta(r_s: Complex64, r_p: Complex64) -> (f64, f64) {
    let rho = -r_p / r_s;
    (rho.norm().atan(), rho.arg())
}

/// What one polarisation does in a coherent stack (or group), per unit incident power, with tmm's flux
/// conventions (which also hold when the top medium absorbs, as inside a mixed stack):
/// `r` = |r|², `t` = flux into the last medium, `entering` = flux into the first layer, `layers` = absorbed
/// in each layer (flux in at its top minus flux out at its bottom).
#[derive(Debug, Clone, PartialEq)]
pub struct PolPowers {
    pub r: f64,
    pub t: f64,
    pub entering: f64,
    pub layers: Vec<f64>,
}

/// The composite reflectivities below every interface, then the amplitudes from the top down.
pub(crate) fn waves(media: &[Medium], d: &[f64], wavelength_nm: f64, p: bool) -> Waves {
    let n = d.len();
    let rt = |j: usize| {
        let f = fresnel(media[j - 1], media[j]);
        if p {
            (f.r_p, f.t_p)
        } else {
            (f.r_s, f.t_s)
        }
    };
    // gamma[j] = Γ_j seen from medium j − 1 at interface B_j, j = 1..=N + 1; gamma[N + 2] = 0.
    let mut gamma = vec![Complex64::new(0.0, 0.0); n + 3];
    gamma[n + 1] = rt(n + 1).0;
    // e2[j] = e^{2iφ_j} for the layers (1..=N).
    let mut e1 = vec![Complex64::new(1.0, 0.0); n + 2];
    for j in (1..=n).rev() {
        let phi = phase(wavelength_nm, media[j], d[j - 1]);
        e1[j] = Complex64::from_polar((-phi.im).exp(), phi.re);
        let g = gamma[j + 1] * e1[j] * e1[j];
        let r = rt(j).0;
        gamma[j] = (r + g) / (1.0 + r * g);
    }
    let mut v = vec![Complex64::new(0.0, 0.0); n + 2];
    let mut w = v.clone();
    v[0] = Complex64::new(1.0, 0.0);
    w[0] = gamma[1];
    let mut arriving = Complex64::new(1.0, 0.0);
    for j in 1..=n + 1 {
        let (r, t) = rt(j);
        let g = if j <= n { gamma[j + 1] * e1[j] * e1[j] } else { Complex64::new(0.0, 0.0) };
        v[j] = arriving * t / (1.0 + r * g);
        w[j] = v[j] * g;
        arriving = v[j] * e1[j];
    }
    Waves { v, w, p }
}

impl Fields {
    /// The fields of the media (incident first; it may absorb inside a mixed stack) with these thicknesses.
    pub fn new(media: Vec<Medium>, thicknesses: Vec<f64>, wavelength_nm: f64) -> Self {
        let s = waves(&media, &thicknesses, wavelength_nm, false);
        let p = waves(&media, &thicknesses, wavelength_nm, true);
        let invariant = (media[0].n * (Complex64::new(1.0, 0.0) - media[0].cos * media[0].cos).sqrt()).re;
        Fields { media, thicknesses, wavelength_nm, s, p, invariant }
    }

    /// [`PolPowers`] for s (`p = false`) or p.
    pub fn powers(&self, p: bool) -> PolPowers {
        let wv = if p { &self.p } else { &self.s };
        let n = self.thicknesses.len();
        let m0 = self.media[0];
        if (if p { (m0.n * m0.cos.conj()).re } else { (m0.n * m0.cos).re }) <= 0.0 {
            // Lit from an evanescent medium (a group seen from a substrate beyond its critical angle): no
            // power arrives, and the fluxes relative to the incident one are undefined.
            return PolPowers { r: 0.0, t: 0.0, entering: 0.0, layers: vec![0.0; n] };
        }
        // Flux at the top of media 1..=N+1, and leaving medium 0 (equal to the first by continuity; tmm's
        // `power_entering`, used for the first layer as tmm does).
        let flux: Vec<f64> = (1..=n + 1).map(|j| self.one(wv, j, 0.0)[0]).collect();
        let entering = self.one(wv, 0, 0.0)[0];
        let mut layers = Vec::with_capacity(n);
        let mut above = entering;
        for &below in &flux[1..] {
            layers.push(above - below);
            above = below;
        }
        PolPowers { r: wv.w[0].norm_sqr(), t: flux[n], entering, layers }
    }

    /// The depth (nm) of the top of medium `j` below the first interface (0 for media 0 and 1).
    fn top(&self, j: usize) -> f64 {
        top_of(&self.thicknesses, j)
    }

    /// The total thickness of the layers (nm).
    pub fn depth_nm(&self) -> f64 {
        self.thicknesses.iter().sum()
    }

    /// The values at depth `z_nm` below the first interface (negative: in the incident medium; beyond the
    /// last interface: in the substrate). At an interface, the medium below is used.
    pub fn at(&self, z_nm: f64) -> Point {
        let (j, dz) = locate(&self.thicknesses, z_nm);
        self.in_medium(j, dz)
    }

    /// The values in medium `j` at `dz` nm below its top (tmm's `position_resolved(layer, distance)`).
    pub fn in_medium(&self, j: usize, dz: f64) -> Point {
        Point::from_pols(self.top(j) + dz, j, self.one(&self.s, j, dz), self.one(&self.p, j, dz))
    }

    /// Byrnes eq. 14–19 (arXiv:1603.02720): `E_f = v e^{i k_z z}`, `E_b = w e^{−i k_z z}`; normal flux,
    /// absorbed density and |E|² relative to the incident wave.
    fn one(&self, wv: &Waves, j: usize, dz: f64) -> [f64; 3] {
        let m = self.media[j];
        let m0 = self.media[0];
        let kz = 2.0 * std::f64::consts::PI / self.wavelength_nm * m.n * m.cos;
        let i = Complex64::new(0.0, 1.0);
        let ef = wv.v[j] * (i * kz * dz).exp();
        let eb = wv.w[j] * (-i * kz * dz).exp();
        if !wv.p {
            let norm = (m0.n * m0.cos).re;
            let poyn = (m.n * m.cos * (ef + eb).conj() * (ef - eb)).re / norm;
            let absor = (m.n * m.cos * kz * (ef + eb).norm_sqr()).im / norm;
            [poyn, absor, (ef + eb).norm_sqr()]
        } else {
            let norm = (m0.n * m0.cos.conj()).re;
            let poyn = (m.n * m.cos.conj() * (ef + eb) * (ef - eb).conj()).re / norm;
            let absor = (m.n * m.cos.conj() * (kz * (ef - eb).norm_sqr() - kz.conj() * (ef + eb).norm_sqr())).im / norm;
            let sin = Complex64::new(self.invariant, 0.0) / m.n;
            let ex = (ef - eb) * m.cos;
            let ez = (-ef - eb) * sin;
            [poyn, absor, ex.norm_sqr() + ez.norm_sqr()]
        }
    }

    /// Power absorbed per layer (flux in at the top minus flux out at the bottom), into the substrate, R, T.
    pub fn absorption(&self) -> Absorption {
        let opaque = self.media[self.media.len() - 1].n.im > 0.0;
        Absorption::from_powers(self.powers(false), self.powers(true), opaque)
    }
}

impl Absorption {
    /// From the powers of s and p; the flux into an absorbing substrate counts as its absorption (T = 0).
    pub fn from_powers(s: PolPowers, p: PolPowers, opaque_substrate: bool) -> Self {
        let split = |t: f64| if opaque_substrate { (t, 0.0) } else { (0.0, t) };
        let ((substrate_s, t_s), (substrate_p, t_p)) = (split(s.t), split(p.t));
        Absorption { layers_s: s.layers, layers_p: p.layers, substrate_s, substrate_p, r_s: s.r, r_p: p.r, t_s, t_p }
    }
}

/// The depth (nm) of the top of medium `j` below the first interface (0 for media 0 and 1), given the layers'
/// thicknesses.
pub(crate) fn top_of(thicknesses: &[f64], j: usize) -> f64 {
    thicknesses[..j.saturating_sub(1).min(thicknesses.len())].iter().sum()
}

/// The medium that holds depth `z_nm` below the first interface and the depth below its top: medium 0 (the
/// incident medium) for negative depths, the substrate beyond the last interface, and at an interface the medium
/// below. One pass over the layers.
pub(crate) fn locate(thicknesses: &[f64], z_nm: f64) -> (usize, f64) {
    if z_nm < 0.0 {
        return (0, z_nm);
    }
    let mut top = 0.0;
    for (k, &d) in thicknesses.iter().enumerate() {
        if z_nm < top + d {
            return (k + 1, z_nm - top);
        }
        top += d;
    }
    (thicknesses.len() + 1, z_nm - top)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bare_substrate_psi_delta() {
        // Air → n = 1.5 at 60°: tan ψ = |r_p / r_s| from Fresnel, Δ = 0 or π (real coefficients): r_s < 0
        // always, r_p (eq. 3.7) > 0 below Brewster's angle 56.3° (Δ = 0) and < 0 beyond it (Δ = π).
        let s = Stack::parse("air | n=1.5").unwrap();
        let th = 60f64.to_radians();
        let ct = (1.0 - (th.sin() / 1.5).powi(2)).sqrt();
        let rs = (th.cos() - 1.5 * ct) / (th.cos() + 1.5 * ct);
        let rp = (1.5 * th.cos() - ct) / (1.5 * th.cos() + ct);
        let (psi, delta) = s.ellipsometry(550.0, th).unwrap();
        assert!((psi - (rp / rs).abs().atan()).abs() < 1e-14, "{psi}");
        assert!((delta - std::f64::consts::PI).abs() < 1e-14, "{delta}");
        assert!(s.ellipsometry(550.0, 40f64.to_radians()).unwrap().1.abs() < 1e-14);
    }

    #[test]
    fn lossless_flux_is_constant_and_balance_holds() {
        let s = Stack::parse("air | n=1.38 100nm | n=2.3 60nm | n=1.52").unwrap();
        let f = s.fields(500.0, 0.5).unwrap();
        let x = s.evaluate(500.0, 0.5).unwrap();
        for z in [0.0, 30.0, 99.0, 100.0, 150.0, 170.0] {
            let p = f.at(z);
            assert!((p.poynting_s - x.t_s).abs() < 1e-13 && (p.poynting_p - x.t_p).abs() < 1e-13, "{p:?}");
            assert!(p.absorption().abs() < 1e-15);
        }
        let a = f.absorption();
        assert!((a.r_s - x.r_s).abs() < 1e-14 && (a.t_p - x.t_p).abs() < 1e-13);
        assert!(a.balance().abs() < 1e-13);
    }
}
