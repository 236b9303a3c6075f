//! The smooth illumination model of Hirayama et al. (Sussenbach, section 3.1): complex cosines from Snell's
//! law, Fresnel amplitudes at each interface, the composite reflectivity/transmissivity recurrence from the
//! bottom of the stack to the top, and the conversion of amplitudes to powers.
//!
//! Indexing follows the thesis (Figure 3.1): media `0` (incident, "medium A") … `N + 1` (substrate,
//! "medium B"); layer `j` (1 ≤ j ≤ N) has thickness `d_j`; interface `B_j` separates media `j − 1` and `j`.
//!
//! The pieces are public so that other models reuse them: the LSRS model (Sussenbach section 3.2) replaces
//! the seed of eq. 3.3 by a rough-surface reflectivity (eq. 3.16) and runs the same recurrence (eq. 3.15 is
//! eq. 3.1), and the diffraction crate uses a stack's amplitudes as its Fresnel term.

use std::f64::consts::PI;

use num_complex::Complex64;
use serde::Serialize;

/// Below this `|s_z|` a layer counts as grazing (at its critical angle); see [`compose`].
pub const GRAZING_COS: f64 = 1e-5;

/// One medium at one wavelength and incidence: its index `n̂_j` and the cosine `s_{z,j}` of the
/// propagation angle inside it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Medium {
    pub n: Complex64,
    pub cos: Complex64,
}

impl Medium {
    /// The medium of index `n` crossed by light whose Snell invariant is `n₀ sin θ₀`.
    pub fn new(n: Complex64, n0_sin0: f64) -> Self {
        Self { n, cos: cosine(n0_sin0, n) }
    }
}

/// The cosine of the angle in a medium of index `n̂` (Sussenbach eq. 3.6): `s_x = n₀ sin θ₀ / n̂`,
/// `s_z = √(1 − s_x²)`, on the branch of the forward-travelling (or decaying) wave, `Im(n̂ s_z) > 0`, or
/// `Re(n̂ s_z) > 0` when that imaginary part vanishes. The branch matters for the substrate (it decides
/// the direction of the transmitted wave); inside a finite layer both branches give the same R and T.
pub fn cosine(n0_sin0: f64, n: Complex64) -> Complex64 {
    let sx = Complex64::new(n0_sin0, 0.0) / n;
    let c = (Complex64::new(1.0, 0.0) - sx * sx).sqrt();
    let q = n * c;
    let forward = if q.im.abs() > 100.0 * f64::EPSILON * q.norm().max(1.0) { q.im > 0.0 } else { q.re > 0.0 };
    if forward || (q.re == 0.0 && q.im == 0.0) {
        c
    } else {
        -c
    }
}

/// The cosine inside a finite layer: [`cosine`] (kept as a separate name for the callers that build
/// layers; grazing layers are handled in [`compose`]).
pub fn layer_cosine(n0_sin0: f64, n: Complex64) -> Complex64 {
    cosine(n0_sin0, n)
}

/// For a stack with a layer at (or within ~1e-5 of) its critical angle, two copies of the media whose
/// grazing layers have `s_z² ± δ²` (δ = [`GRAZING_COS`]) instead of `s_z²`; `None` when no layer grazes.
///
/// Why: at grazing incidence inside layer `j` the Fresnel amplitudes of its two interfaces tend to ±1 and
/// eq. 3.1 divides two small differences (0/0 exactly at the critical angle), losing about
/// `ε / |s_{z,j}|` of precision. The layer's effect on the stack (its characteristic matrix) is an even,
/// analytic function of `s_{z,j}`, so the mean of the two shifted evaluations equals the true value to
/// O(δ⁴) while each of them is well conditioned (precision ~ε/δ ≈ 1e-11).
pub fn grazing_variants(media: &[Medium]) -> Option<[Vec<Medium>; 2]> {
    let inner = 1..media.len().saturating_sub(1);
    if !media[inner.clone()].iter().any(|m| m.cos.norm() < GRAZING_COS) {
        return None;
    }
    let d2 = GRAZING_COS * GRAZING_COS;
    let mut plus = media.to_vec();
    let mut minus = media.to_vec();
    for j in inner {
        if media[j].cos.norm() < GRAZING_COS {
            let c2 = media[j].cos * media[j].cos;
            plus[j].cos = forward((c2 + d2).sqrt(), media[j].n);
            minus[j].cos = forward((c2 - d2).sqrt(), media[j].n);
        }
    }
    Some([plus, minus])
}

fn forward(c: Complex64, n: Complex64) -> Complex64 {
    let q = n * c;
    if q.im < 0.0 || (q.im == 0.0 && q.re < 0.0) {
        -c
    } else {
        c
    }
}

/// Fresnel amplitude coefficients of one interface, from the upper medium `j − 1` into the lower medium `j`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fresnel {
    pub r_s: Complex64,
    pub r_p: Complex64,
    pub t_s: Complex64,
    pub t_p: Complex64,
}

/// The Fresnel equations at interface `B_j` (Sussenbach eq. 3.7–3.10; `p` = ∥, `s` = ⊥):
/// `r_p = (n̂_j s_{z,j−1} − n̂_{j−1} s_{z,j}) / (n̂_j s_{z,j−1} + n̂_{j−1} s_{z,j})` (3.7),
/// `r_s = (n̂_{j−1} s_{z,j−1} − n̂_j s_{z,j}) / (n̂_{j−1} s_{z,j−1} + n̂_j s_{z,j})` (3.8),
/// `t_p = 2 n̂_{j−1} s_{z,j−1} / (n̂_j s_{z,j−1} + n̂_{j−1} s_{z,j})` (3.9),
/// `t_s = 2 n̂_{j−1} s_{z,j−1} / (n̂_{j−1} s_{z,j−1} + n̂_j s_{z,j})` (3.10).
#[inline]
pub fn fresnel(upper: Medium, lower: Medium) -> Fresnel {
    let (ni, ci, nt, ct) = (upper.n, upper.cos, lower.n, lower.cos);
    let a = ni * ci; // n̂_{j−1} s_{z,j−1}
    let b = nt * ct; // n̂_j s_{z,j}
    let c = nt * ci; // n̂_j s_{z,j−1}
    let d = ni * ct; // n̂_{j−1} s_{z,j}
    let ds = 1.0 / (a + b);
    let dp = 1.0 / (c + d);
    Fresnel { r_p: (c - d) * dp, r_s: (a - b) * ds, t_p: 2.0 * a * dp, t_s: 2.0 * a * ds }
}

/// The phase difference across layer `j` (Sussenbach eq. 3.5): `φ_j = (2π/λ) n̂_j d_j s_{z,j}`.
#[inline]
pub fn phase(wavelength_nm: f64, layer: Medium, thickness_nm: f64) -> Complex64 {
    (2.0 * PI / wavelength_nm * thickness_nm) * layer.n * layer.cos
}

/// Composite reflectivity γ and transmissivity τ (amplitudes) of the part of the stack below some interface,
/// for both polarisations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Composite {
    pub gamma_s: Complex64,
    pub gamma_p: Complex64,
    pub tau_s: Complex64,
    pub tau_p: Complex64,
}

impl Composite {
    /// The seed of the recurrence (Sussenbach eq. 3.3–3.4): `γ₀ = r_{N+1}`, `τ₀ = t_{N+1}` at the bottom
    /// interface. The LSRS model (eq. 3.16) starts instead from a rough-surface reflectivity: build the
    /// `Composite` directly.
    pub fn seed(bottom: Fresnel) -> Self {
        Self { gamma_s: bottom.r_s, gamma_p: bottom.r_p, tau_s: bottom.t_s, tau_p: bottom.t_p }
    }

    /// One step of the recurrence through layer `j` and its upper interface `B_j` (Sussenbach eq. 3.1–3.2):
    /// `γ' = (r_j + γ e^{2iφ_j}) / (1 + r_j γ e^{2iφ_j})`, `τ' = t_j τ e^{iφ_j} / (1 + r_j γ e^{2iφ_j})`.
    #[inline]
    pub fn step(self, top: &Fresnel, phi: Complex64) -> Self {
        // e^{iφ} with Im φ ≥ 0 on the forward branch, so |e^{iφ}| ≤ 1 and nothing overflows.
        let e1 = Complex64::from_polar((-phi.im).exp(), phi.re);
        let e2 = e1 * e1;
        let (gamma_s, tau_s) = recur(top.r_s, top.t_s, self.gamma_s, self.tau_s, e1, e2);
        let (gamma_p, tau_p) = recur(top.r_p, top.t_p, self.gamma_p, self.tau_p, e1, e2);
        Self { gamma_s, gamma_p, tau_s, tau_p }
    }
}

/// Eq. 3.1 and 3.2 for one polarisation, with `e1 = e^{iφ}` and `e2 = e^{2iφ}`.
#[inline]
pub fn recur(
    r: Complex64,
    t: Complex64,
    gamma: Complex64,
    tau: Complex64,
    e1: Complex64,
    e2: Complex64,
) -> (Complex64, Complex64) {
    let g = gamma * e2;
    let inv = 1.0 / (1.0 + r * g);
    ((r + g) * inv, t * tau * e1 * inv)
}

/// Runs the recurrence over a whole stack: `media` are the `N + 2` media (incident first), `thicknesses`
/// the `N` layer thicknesses in nm. `seed` replaces the bottom interface's Fresnel amplitudes (eq. 3.3–3.4)
/// when given. Returns the composite amplitudes at the top, γ_N and τ_N.
pub fn compose(media: &[Medium], thicknesses: &[f64], wavelength_nm: f64, seed: Option<Composite>) -> Composite {
    if let Some([plus, minus]) = grazing_variants(media) {
        let a = compose_plain(&plus, thicknesses, wavelength_nm, seed);
        let b = compose_plain(&minus, thicknesses, wavelength_nm, seed);
        return Composite {
            gamma_s: 0.5 * (a.gamma_s + b.gamma_s),
            gamma_p: 0.5 * (a.gamma_p + b.gamma_p),
            tau_s: 0.5 * (a.tau_s + b.tau_s),
            tau_p: 0.5 * (a.tau_p + b.tau_p),
        };
    }
    compose_plain(media, thicknesses, wavelength_nm, seed)
}

/// [`compose`] without the grazing-layer treatment.
pub fn compose_plain(media: &[Medium], thicknesses: &[f64], wavelength_nm: f64, seed: Option<Composite>) -> Composite {
    let n = thicknesses.len();
    debug_assert_eq!(media.len(), n + 2);
    let mut c = seed.unwrap_or_else(|| Composite::seed(fresnel(media[n], media[n + 1])));
    for j in (1..=n).rev() {
        let top = fresnel(media[j - 1], media[j]);
        c = c.step(&top, phase(wavelength_nm, media[j], thicknesses[j - 1]));
    }
    c
}

/// Complex amplitude reflection and transmission coefficients of a whole stack (the composite reflectivity
/// γ_N and transmissivity τ_N of Sussenbach eq. 3.1–3.2), with the media at both ends that convert them to
/// powers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Amplitudes {
    pub r_s: Complex64,
    pub r_p: Complex64,
    pub t_s: Complex64,
    pub t_p: Complex64,
    /// The incident medium (real index) and the substrate.
    pub incident: Medium,
    pub substrate: Medium,
}

impl Amplitudes {
    pub fn new(c: Composite, incident: Medium, substrate: Medium) -> Self {
        Self { r_s: c.gamma_s, r_p: c.gamma_p, t_s: c.tau_s, t_p: c.tau_p, incident, substrate }
    }

    /// The factor of eq. 3.13, `Re(n̂_{N+1} s_{z,N+1}) / (n₀ s_{z,0})`; zero for an absorbing substrate (an
    /// infinitely thick absorber transmits nothing, Sussenbach section 3.1.1) and for an evanescent one
    /// (total internal reflection).
    pub fn transmission_factor(&self) -> f64 {
        transmission_factor(self.incident, self.substrate)
    }

    /// Reflectance and transmittance (eq. 3.12–3.13, per polarisation).
    pub fn powers(&self) -> Rta {
        let f = self.transmission_factor();
        Rta {
            r_s: self.r_s.norm_sqr(),
            r_p: self.r_p.norm_sqr(),
            t_s: f * self.t_s.norm_sqr(),
            t_p: f * self.t_p.norm_sqr(),
        }
    }
}

/// See [`Amplitudes::transmission_factor`].
pub fn transmission_factor(incident: Medium, substrate: Medium) -> f64 {
    if substrate.n.im > 0.0 {
        return 0.0;
    }
    let num = (substrate.n * substrate.cos).re;
    let den = (incident.n * incident.cos).re;
    if num <= 0.0 || den <= 0.0 {
        0.0
    } else {
        num / den
    }
}

/// Reflectance and transmittance (powers) of a stack for s (⊥) and p (∥) polarised light.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Rta {
    pub r_s: f64,
    pub r_p: f64,
    pub t_s: f64,
    pub t_p: f64,
}

impl Rta {
    /// Unpolarised reflectance (eq. 3.12): `(|γ_∥|² + |γ_⊥|²) / 2`.
    pub fn r(&self) -> f64 {
        0.5 * (self.r_s + self.r_p)
    }
    /// Unpolarised transmittance (eq. 3.13).
    pub fn t(&self) -> f64 {
        0.5 * (self.t_s + self.t_p)
    }
    /// Unpolarised absorptance `1 − R − T` (light absorbed in the layers or entering an absorbing substrate).
    pub fn a(&self) -> f64 {
        1.0 - self.r() - self.t()
    }
    pub fn a_s(&self) -> f64 {
        1.0 - self.r_s - self.t_s
    }
    pub fn a_p(&self) -> f64 {
        1.0 - self.r_p - self.t_p
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::c64 as c;

    #[test]
    fn single_interface_is_fresnel() {
        // Air → glass at normal incidence: R = ((1 − 1.5)/(1 + 1.5))² = 0.04, T = 0.96.
        let a = Medium::new(c(1.0, 0.0), 0.0);
        let g = Medium::new(c(1.5, 0.0), 0.0);
        let amp = Amplitudes::new(compose(&[a, g], &[], 550.0, None), a, g);
        let p = amp.powers();
        assert!((p.r() - 0.04).abs() < 1e-15 && (p.t() - 0.96).abs() < 1e-15);
        // Brewster's angle: r_p = 0 at tan θ = 1.5.
        let th = 1.5f64.atan();
        let a = Medium::new(c(1.0, 0.0), th.sin());
        let g = Medium::new(c(1.5, 0.0), th.sin());
        assert!(fresnel(a, g).r_p.norm() < 1e-15);
    }

    #[test]
    fn quarter_wave_antireflection() {
        // A λ/4 layer of n = √1.5 on n = 1.5 reflects nothing at λ (normal incidence).
        let nl = 1.5f64.sqrt();
        let s = 0.0;
        let media = [Medium::new(c(1.0, 0.0), s), Medium::new(c(nl, 0.0), s), Medium::new(c(1.5, 0.0), s)];
        let g = compose(&media, &[550.0 / (4.0 * nl)], 550.0, None);
        assert!(g.gamma_s.norm() < 1e-15 && g.gamma_p.norm() < 1e-15);
    }

    #[test]
    fn forward_branch() {
        // Metal: Im(n cos) > 0. Glass to air beyond the critical angle: cos purely imaginary, Im > 0.
        let q = c(0.2, 3.4) * cosine(0.5, c(0.2, 3.4));
        assert!(q.im > 0.0);
        let cz = cosine(1.5 * 60f64.to_radians().sin(), c(1.0, 0.0));
        assert!(cz.re.abs() < 1e-15 && cz.im > 0.0);
    }
}
