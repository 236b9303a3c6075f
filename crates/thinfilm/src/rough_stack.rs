//! The rough stack — a film whose bottom interface is rough ([`crate::htsg`]) — and the coherent optics of one
//! side of it: the media, Fresnel coefficients and phases above the rough interface at one angle (`Side`) and
//! the power transmittance through the layers between medium 0 and the interface. [`crate::rough`] evaluates
//! the LSRS model on it, [`crate::rough_multiple`] the light scattered more than once inside the film.

use std::f64::consts::PI;

use num_complex::Complex64;

use crate::error::ThinFilmError;
use crate::htsg::Htsg;
use crate::recurrence::{fresnel, phase, Composite, Fresnel, Medium};
use crate::stack::Stack;

/// How the diffuse light crosses the smooth layers above the rough interface (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DiffuseTransport {
    /// Single scattering: power transmittances down at `θ_l` and up at `θ_v`, multiple reflections on both
    /// paths, the `n²` radiance factor (eq. R1–R6): reciprocal; the light that the layers send back to the
    /// rough interface, and the light scattered beyond the escape cone, is dropped. The default of
    /// [`RoughStack::new`] (renderers evaluate it per sample); front ends default to [`Self::Multiple`].
    #[default]
    Reciprocal,
    /// Single scattering plus every further scattering at the rough interface of the light the layers turn
    /// back and of the light trapped beyond the escape cone ([`crate::rough_multiple`], eq. M1–M9):
    /// reciprocal, and a lossless film on a lossless substrate reflects all the light.
    Multiple,
    /// Sussenbach's eq. 3.18–3.19 as printed (compatibility only: creates energy, not reciprocal).
    ThesisPrinted,
}

impl DiffuseTransport {
    /// Parses `reciprocal` or `thesis`.
    pub fn parse(s: &str) -> Result<Self, ThinFilmError> {
        match s.trim().to_ascii_lowercase().as_str() {
            "multiple" => Ok(Self::Multiple),
            "reciprocal" | "single" => Ok(Self::Reciprocal),
            "thesis" | "thesis-printed" => Ok(Self::ThesisPrinted),
            other => Err(ThinFilmError::Invalid(format!(
                "diffuse transport '{other}': expected 'multiple' (every scattering inside the film), 'single' \
                 (alias 'reciprocal': one scattering at the rough interface) or 'thesis' (eq. 3.18–3.19 as printed; \
                 not energy-conserving)"
            ))),
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Self::Multiple => "multiple",
            Self::Reciprocal => "single",
            Self::ThesisPrinted => "thesis",
        }
    }
}

/// A thin-film stack whose bottom interface (last layer | substrate) is rough.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughStack {
    pub stack: Stack,
    pub htsg: Htsg,
    pub transport: DiffuseTransport,
}

/// One angle at one wavelength: the media, the downward Fresnel amplitudes of every interface, the phases
/// of every layer, and the real direction in medium `N`.
pub(crate) struct Side {
    pub(crate) media: Vec<Medium>,
    /// Interface `B_j` (`j = 1 … N + 1`) at index `j − 1`, from medium `j − 1` into `j`.
    pub(crate) down: Vec<Fresnel>,
    /// `φ_j` (eq. 3.5) at index `j − 1`.
    pub(crate) phi: Vec<Complex64>,
    /// `(sin θ_N, cos θ_N)` in medium `N`, `None` where light is evanescent there.
    pub(crate) dir: Option<(f64, f64)>,
}

impl Side {
    pub(crate) fn new(stack: &Stack, wavelength_nm: f64, angle_rad: f64) -> Result<Self, ThinFilmError> {
        let media = stack.media(wavelength_nm, angle_rad)?;
        let n = stack.layers.len();
        let down = (1..=n + 1).map(|j| fresnel(media[j - 1], media[j])).collect();
        let phi = (1..=n).map(|j| phase(wavelength_nm, media[j], stack.layers[j - 1].thickness_nm)).collect();
        let invariant = media[0].n.re * angle_rad.min(PI / 2.0).sin();
        let sin_n = invariant / media[n].n.re;
        // A grazing direction (cos below 1e-12, e.g. θ = 90° where cos(π/2) rounds to 6e-17) is exactly
        // grazing: the rough interface is then fully shadowed (S = 0).
        let dir = if sin_n <= 1.0 {
            let cos = (1.0 - sin_n * sin_n).sqrt();
            Some((sin_n, if cos < 1e-12 { 0.0 } else { cos }))
        } else {
            None
        };
        Ok(Self { media, down, phi, dir })
    }

    pub(crate) fn n(&self) -> usize {
        self.phi.len()
    }

    /// The specular seed (eq. 3.16; module documentation).
    pub(crate) fn seed(&self, htsg: &Htsg, k: f64) -> Composite {
        let amp = match self.dir {
            Some((_, cos)) => htsg.specular_amplitude(cos, k).0,
            None => 1.0,
        };
        let b = &self.down[self.n()];
        Composite { gamma_s: b.r_s * amp, gamma_p: b.r_p * amp, tau_s: b.t_s, tau_p: b.t_p }
    }

    /// The composite specular reflectivity at the top of the stack (eq. 3.15), from the seed `γ_{s,0}` up.
    pub(crate) fn specular(&self, seed: &Composite) -> Composite {
        (1..=self.n()).rev().fold(*seed, |gs, j| gs.step(&self.down[j - 1], self.phi[j - 1]))
    }

    /// Fresnel amplitudes of interface `B_j` from below (medium `j` into `j − 1`).
    pub(crate) fn up(&self, j: usize) -> Fresnel {
        fresnel(self.media[j], self.media[j - 1])
    }
}

pub(crate) fn cis(phi: Complex64) -> Complex64 {
    // e^{iφ}, |·| ≤ 1 on the forward branch (Im φ ≥ 0)
    Complex64::from_polar((-phi.im).exp(), phi.re)
}

/// `T = |D||U|` per polarisation (⊥, ∥): the power transmittance between medium 0 and the rough interface at
/// this side's angle, with the multiple reflections between the stack and the interface's specular
/// reflection `seed` (docs/rough-films.md eq. R3–R4). Per layer, from the rough interface up:
/// `|t_j t'_j| |e^{iφ_j}|² / |1 + r_j γ_{s,N−j} e^{2iφ_j}|²`, `t'_j` the upward amplitude. `|D||U|` rather than
/// `|D|² Re(n_N cos θ_N)/(n₀ cos θ₀)`: the same for real indices, and finite at grazing incidence.
pub(crate) fn side_transmittance(side: &Side, seed: &Composite) -> [f64; 2] {
    through_layers(side, seed, |t, t_up| t.norm() * t_up.norm())
}

/// `Π_j τ_j |e^{iφ_j}|² / |1 + r_j γ_{s,N−j} e^{2iφ_j}|²` per polarisation (⊥, ∥), layer by layer from the rough
/// interface up, `γ_s` stepped up from `seed`: the multiple reflections every crossing of a layer goes through.
/// `τ_j = tau(t_j, t'_j)` is the crossing's power factor from the downward and upward amplitudes.
fn through_layers(side: &Side, seed: &Composite, tau: impl Fn(Complex64, Complex64) -> f64) -> [f64; 2] {
    let mut f = [1.0, 1.0];
    let mut gs = *seed;
    for j in (1..=side.n()).rev() {
        let (down, up) = (side.down[j - 1], side.up(j));
        let e = (-2.0 * side.phi[j - 1].im).exp();
        let e2 = cis(2.0 * side.phi[j - 1]);
        f[0] *= tau(down.t_s, up.t_s) * e / (1.0 + down.r_s * gs.gamma_s * e2).norm_sqr();
        f[1] *= tau(down.t_p, up.t_p) * e / (1.0 + down.r_p * gs.gamma_p * e2).norm_sqr();
        gs = gs.step(&down, side.phi[j - 1]);
    }
    f
}

/// `Π_j |t_j e^{iφ_j}|²` per polarisation (⊥, ∥): the view-side factor of eq. 3.19 as printed.
pub(crate) fn down_factor(v: &Side) -> [f64; 2] {
    let mut f = [1.0, 1.0];
    for j in 1..=v.n() {
        let e = (-2.0 * v.phi[j - 1].im).exp();
        f[0] *= v.down[j - 1].t_s.norm_sqr() * e;
        f[1] *= v.down[j - 1].t_p.norm_sqr() * e;
    }
    f
}

/// `Π_j |t'_j e^{iφ_j} / (1 + r_j γ_{s,N−j} e^{2iφ_j})|²` per polarisation: the light-side factor of eq. 3.18–3.19.
pub(crate) fn up_factor(l: &Side, seed: &Composite) -> [f64; 2] {
    through_layers(l, seed, |_, t_up| t_up.norm_sqr())
}
