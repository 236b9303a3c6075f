//! Stacks with incoherent layers (`inc:` in the stack syntax): a layer much thicker than the coherence length
//! of the light (a 1 mm glass slide under a lamp) does not interfere; the waves reflected at its two faces add
//! as intensities. The method is the one of `tmm.inc_tmm` (S. J. Byrnes, "Multilayer optical calculations",
//! arXiv:1603.02720, section 5): the stack is cut at its incoherent media into coherent groups; each group is
//! a coherent stack (the recurrence of [`crate::recurrence`]) with power coefficients `R`, `T` forwards and
//! backwards; an incoherent layer of thickness `d` passes the fraction `P = exp(−4π d Im(n̂ s_z) / λ)` of the
//! intensity per crossing; and the intensities bounce between the groups.
//!
//! Instead of Byrnes' 2 × 2 intensity transfer matrices (which divide by each group's `T`, undefined under
//! total internal reflection), the groups are combined from the bottom up by the incoherent analogue of
//! Sussenbach eq. 3.1–3.2, the sum of the geometric series of bounces:
//! `R' = R_f + T_f T_b P² R / (1 − R_b P² R)`, `T' = T_f P T / (1 − R_b P² R)`,
//! which is the same quantity (the fixtures of `tools/gen_incoherent_fixtures.py` compare it with `inc_tmm`).

use num_complex::Complex64;

use crate::error::ThinFilmError;
use crate::field::{locate, top_of, Absorption, Fields, Point, PolPowers};
use crate::intensity::{group_list, pass_of};
pub use crate::intensity::{group_powers, single_pass, GroupPowers};
use crate::recurrence::Medium;
use crate::stack::Stack;
pub use crate::stack::{evaluate_incoherent as evaluate, incoherent_media};

/// The groups between consecutive incoherent media, top first: their powers.
pub fn groups(
    stack: &Stack,
    media: &[Medium],
    thicknesses_nm: &[f64],
    wavelength_nm: f64,
) -> (Vec<usize>, Vec<GroupPowers>) {
    let inc = incoherent_media(stack);
    let g = group_list(media, thicknesses_nm, &inc, wavelength_nm);
    (inc, g)
}

/// Absorption per layer (coherent and incoherent) and in an absorbing substrate, with R and T, as
/// `tmm.inc_absorp_in_each_layer` (Byrnes section 5.3): each group is lit from above by the forward intensity
/// `F` arriving at it and from below by the backward intensity `B`; its layers absorb `F A_fwd + B A_bwd`
/// (the coherent per-layer absorption of [`Fields`] run forwards and backwards); an incoherent layer absorbs
/// the flux entering it at its top minus the flux leaving it at its bottom.
pub fn absorption(
    stack: &Stack,
    wavelength_nm: f64,
    angle_rad: f64,
    thicknesses_nm: &[f64],
) -> Result<Absorption, ThinFilmError> {
    stack.check_thicknesses(thicknesses_nm)?;
    let media = stack.media(wavelength_nm, angle_rad)?;
    let inc = incoherent_media(stack);
    let m = inc.len() - 1;
    let pass: Vec<f64> = inc.iter().map(|&i| pass_of(&media, thicknesses_nm, i, wavelength_nm)).collect();
    let fields = group_fields(&media, thicknesses_nm, &inc, wavelength_nm);
    let one = |p: bool| -> PolPowers {
        let f: Vec<PolPowers> = fields.iter().map(|x| x.0.powers(p)).collect();
        let b: Vec<PolPowers> = fields.iter().map(|x| x.1.powers(p)).collect();
        let Bounces { rc, down, up, .. } = bounces(&f, &b, &pass);
        // Net flux entering incoherent medium k at its top and leaving it at its bottom (tmm's conventions:
        // a bare interface passes T both ways; a coherent group is entered with its `entering` flux).
        let mut entering = vec![1.0; m + 1];
        let mut exiting = vec![0.0; m + 1];
        let mut layers = Vec::with_capacity(stack.layers.len());
        for g in 0..m {
            let (fw, bw) = (down[g], up[g + 1]);
            let bare = f[g].layers.is_empty();
            entering[g + 1] = fw * f[g].t - bw * if bare { b[g].t } else { b[g].entering };
            exiting[g] = if bare { entering[g + 1] } else { fw * f[g].entering - bw * b[g].t };
            if g > 0 {
                layers.push(entering[g] - exiting[g]);
            }
            let n = f[g].layers.len();
            layers.extend((0..n).map(|i| fw * f[g].layers[i] + bw * b[g].layers[n - 1 - i]));
        }
        PolPowers { r: rc[0], t: down[m], entering: 1.0 - rc[0], layers }
    };
    let opaque = media[media.len() - 1].n.im > 0.0;
    Ok(Absorption::from_powers(one(false), one(true), opaque))
}

/// The coherent fields of each group between consecutive incoherent media `inc`, lit from above and (the
/// group reversed) from below.
fn group_fields(media: &[Medium], thicknesses_nm: &[f64], inc: &[usize], wavelength_nm: f64) -> Vec<(Fields, Fields)> {
    inc.windows(2)
        .map(|w| {
            let gm = media[w[0]..=w[1]].to_vec();
            let gd = thicknesses_nm[w[0]..w[1] - 1].to_vec();
            let rev_m = gm.iter().rev().copied().collect();
            let rev_d = gd.iter().rev().copied().collect();
            (Fields::new(gm, gd, wavelength_nm), Fields::new(rev_m, rev_d, wavelength_nm))
        })
        .collect()
}

/// The intensities between the groups of one polarisation.
#[derive(Debug, Clone)]
struct Bounces {
    /// `rc[k]`: reflectance of everything below the bottom of incoherent medium k, seen from inside it.
    rc: Vec<f64>,
    /// `down[k]`: forward intensity at the bottom of incoherent medium k (the `F` lighting group k).
    down: Vec<f64>,
    /// `up[k]`: backward intensity at the top of incoherent medium k (the `B` lighting group k − 1).
    up: Vec<f64>,
    /// `top[k]`: forward intensity at the top of incoherent medium k, `F T_f + B R_b` of the group above
    /// (= `down[k] / P_k`, without the division, which fails where P underflows to 0).
    top: Vec<f64>,
}

/// The geometric series of bounces between the groups (`f`, `b`: each group lit from above / below).
fn bounces(f: &[PolPowers], b: &[PolPowers], pass: &[f64]) -> Bounces {
    let m = f.len();
    let mut rc = vec![0.0; m + 1];
    for k in (0..m).rev() {
        let pp = pass[k + 1] * pass[k + 1];
        rc[k] = f[k].r + f[k].t * b[k].t * pp * rc[k + 1] / (1.0 - b[k].r * pp * rc[k + 1]);
    }
    let (mut down, mut up) = (vec![0.0; m + 1], vec![0.0; m + 1]);
    down[0] = 1.0;
    for k in 0..m {
        let pk = pass[k + 1];
        down[k + 1] = pk * f[k].t * down[k] / (1.0 - b[k].r * pk * pk * rc[k + 1]);
        up[k + 1] = pk * rc[k + 1] * down[k + 1];
    }
    let mut top = vec![1.0; m + 1];
    for k in 0..m {
        top[k + 1] = down[k] * f[k].t + up[k + 1] * b[k].r;
    }
    Bounces { rc, down, up, top }
}

/// Where the light goes inside any stack, coherent or mixed: the position-resolved flux, absorbed power
/// density and |E|² (as [`Fields`] for a coherent stack, which it reproduces).
///
/// In a coherent group lit by the forward intensity `F` from above and the backward intensity `B` from
/// below (the two are mutually incoherent), every quantity is the intensity-weighted sum of the group's
/// coherent solutions lit from each side: absorption `F a_fwd(z) + B a_bwd(d − z)` (what
/// `tmm.inc_find_absorp_analytic_fn` computes), flux `F S_fwd − B S_bwd`, and |E|² likewise, each coherent
/// |E|² rescaled from its group's incident amplitude to the stack's (flux per unit |E|² is `Re(n̂ s_z)` for s,
/// `Re(n̂ s̄_z)` for p). In an incoherent layer with forward intensity `V` and backward intensity `W` at its
/// top (tmm's `VW_list`), the two beams decay by Beer–Lambert, `α = 4π Im(n̂ s_z)/λ`: flux
/// `V e^{−αz} − W e^{αz}`, absorption `α (V e^{−αz} + W e^{αz})`, |E|² the sum of the two beams' (no
/// interference term).
#[derive(Debug, Clone)]
pub struct Profile {
    media: Vec<Medium>,
    thicknesses: Vec<f64>,
    wavelength_nm: f64,
    inc: Vec<usize>,
    /// Per group: lit from above, lit from below (reversed media).
    fields: Vec<(Fields, Fields)>,
    /// Per polarisation (s, p): the intensities between the groups.
    light: [Bounces; 2],
}

impl Stack {
    /// The fraction of the incident power absorbed in each layer (coherent or `inc:`) and in an absorbing
    /// substrate, with R and T; for mixed stacks as `tmm.inc_absorp_in_each_layer`.
    pub fn absorption(&self, wavelength_nm: f64, angle_rad: f64) -> Result<Absorption, ThinFilmError> {
        absorption(self, wavelength_nm, angle_rad, &self.thicknesses())
    }

    /// The position-resolved profile of any stack ([`Profile`]).
    pub fn profile(&self, wavelength_nm: f64, angle_rad: f64) -> Result<Profile, ThinFilmError> {
        let media = self.media(wavelength_nm, angle_rad)?;
        let d = self.thicknesses();
        let inc = incoherent_media(self);
        let pass: Vec<f64> = inc.iter().map(|&i| pass_of(&media, &d, i, wavelength_nm)).collect();
        let fields = group_fields(&media, &d, &inc, wavelength_nm);
        let light = [false, true].map(|p| {
            let f: Vec<PolPowers> = fields.iter().map(|x| x.0.powers(p)).collect();
            let b: Vec<PolPowers> = fields.iter().map(|x| x.1.powers(p)).collect();
            bounces(&f, &b, &pass)
        });
        Ok(Profile { media, thicknesses: d, wavelength_nm, inc, fields, light })
    }
}

impl Profile {
    /// The total thickness of the layers (nm).
    pub fn depth_nm(&self) -> f64 {
        self.thicknesses.iter().sum()
    }

    /// The depth (nm) of the top of medium `j` below the first interface (0 for media 0 and 1).
    fn top(&self, j: usize) -> f64 {
        top_of(&self.thicknesses, j)
    }

    /// The values at depth `z_nm` below the first interface (negative: in the incident medium; beyond the
    /// last interface: in the substrate). At an interface, the medium below is used.
    pub fn at(&self, z_nm: f64) -> Point {
        let (j, dz) = locate(&self.thicknesses, z_nm);
        self.in_medium(j, dz)
    }

    /// Flux per unit |E|² of a wave in medium `m`, for s or p.
    fn flux_per_e2(m: Medium, p: bool) -> f64 {
        if p {
            (m.n * m.cos.conj()).re
        } else {
            (m.n * m.cos).re
        }
    }

    /// The values in medium `j` at `dz` nm below its top (for the incident medium: `dz ≤ 0` above the first
    /// interface), both polarisations.
    pub fn in_medium(&self, j: usize, dz: f64) -> Point {
        let last = self.media.len() - 1;
        let z_nm = self.top(j) + dz;
        let (s, p) = if let Some(k) = self.inc.iter().position(|&i| i == j && i != 0 && i != last) {
            (self.incoherent_layer(k, dz, false), self.incoherent_layer(k, dz, true))
        } else {
            let g = self.inc.windows(2).position(|w| w[0] <= j && j <= w[1]).expect("every medium is in a group");
            (self.coherent(g, j, dz, false), self.coherent(g, j, dz, true))
        };
        Point::from_pols(z_nm, j, s, p)
    }

    /// [flux, absorption density, |E|²] in incoherent medium `inc[k]` at `dz` below its top.
    fn incoherent_layer(&self, k: usize, dz: f64, p: bool) -> [f64; 3] {
        let j = self.inc[k];
        let m = self.media[j];
        let light = &self.light[usize::from(p)];
        // Each beam from where it enters (forward: the top; backward: the bottom), so nothing overflows in
        // a layer that absorbs everything.
        let v = light.top[k];
        let w_bottom = light.rc[k] * light.down[k];
        let alpha = 4.0 * std::f64::consts::PI * (m.n * m.cos).im / self.wavelength_nm;
        let d = self.thicknesses[j - 1];
        let (fwd, bwd) = (v * (-alpha * dz).exp(), w_bottom * (-alpha * (d - dz)).exp());
        let norm = Self::flux_per_e2(self.media[0], p);
        let per = Self::flux_per_e2(m, p);
        let shape = if p { m.cos.norm_sqr() + (Complex64::new(self.invariant(), 0.0) / m.n).norm_sqr() } else { 1.0 };
        let e2 = if per > 0.0 { (fwd + bwd) * norm / per * shape } else { 0.0 };
        [fwd - bwd, alpha * (fwd + bwd), e2]
    }

    /// `n₀ sin θ₀`.
    fn invariant(&self) -> f64 {
        let m0 = self.media[0];
        (m0.n * (Complex64::new(1.0, 0.0) - m0.cos * m0.cos).sqrt()).re
    }

    /// [flux, absorption density, |E|²] in medium `j` of coherent group `g` at `dz` below its top.
    fn coherent(&self, g: usize, j: usize, dz: f64, p: bool) -> [f64; 3] {
        let (a, b) = (self.inc[g], self.inc[g + 1]);
        let light = &self.light[usize::from(p)];
        let (big_f, big_b) = (light.down[g], light.up[g + 1]);
        let (fwd, bwd) = &self.fields[g];
        // Position in the reversed group: from the bottom of a finite layer; below the last interface
        // (of the reversed media) for the semi-infinite ends.
        let end = j == 0 || j == self.media.len() - 1;
        let dz_b = if end { -dz } else { self.thicknesses[j - 1] - dz };
        let norm = Self::flux_per_e2(self.media[0], p);
        let pick =
            |x: Point| if p { [x.poynting_p, x.absorption_p, x.e2_p] } else { [x.poynting_s, x.absorption_s, x.e2_s] };
        let mut out = [0.0; 3];
        // Zero intensity contributes nothing (and a group lit from an evanescent side has no normalisation).
        if big_f != 0.0 {
            let [s, ab, e] = pick(fwd.in_medium(j - a, dz));
            let scale = norm / Self::flux_per_e2(self.media[a], p);
            out = [big_f * s, big_f * ab, big_f * scale * e];
        }
        if big_b != 0.0 {
            let [s, ab, e] = pick(bwd.in_medium(b - j, dz_b));
            let scale = norm / Self::flux_per_e2(self.media[b], p);
            out = [out[0] - big_b * s, out[1] + big_b * ab, out[2] + big_b * scale * e];
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bare_slide_adds_intensities() {
        // A lossless slab in air at normal incidence, incoherently: R = 2ρ / (1 + ρ) with ρ the single-face
        // reflectance ((n − 1)/(n + 1))² (the geometric series of bounces; e.g. Born & Wolf §7.6 limit).
        let s = Stack::parse("air | inc:n=1.5 1mm | air").unwrap();
        let x = s.evaluate(550.0, 0.0).unwrap();
        let rho: f64 = 0.04;
        assert!((x.r() - 2.0 * rho / (1.0 + rho)).abs() < 1e-15, "{x:?}");
        assert!((x.r() + x.t() - 1.0).abs() < 1e-15);
        // Its thickness does not matter when it does not absorb.
        let y = Stack::parse("air | inc:n=1.5 3nm | air").unwrap().evaluate(550.0, 0.0).unwrap();
        assert!((x.r() - y.r()).abs() < 1e-15);
    }

    #[test]
    fn absorbing_slab_closed_form() {
        // Absorbing slab (κ small), normal incidence: R = ρ + (1 − ρ)² P² ρ / (1 − ρ² P²), T = (1 − ρ)² P / (1 − ρ² P²)
        // with ρ the face reflectance |(n̂ − 1)/(n̂ + 1)|² and P = exp(−4π κ d / λ).
        let (n, k, d, w) = (1.5, 1e-4, 1e6, 600.0);
        let s = Stack::parse(&format!("air | inc:n={n}+{k}i {d}nm | air")).unwrap();
        let x = s.evaluate(w, 0.0).unwrap();
        let nn = Complex64::new(n, k);
        let rho = ((nn - 1.0) / (nn + 1.0)).norm_sqr();
        let p = (-4.0 * std::f64::consts::PI * k * d / w).exp();
        // Into the slab the transmitted flux is (1 − ρ) only when n̂ is real; Byrnes' T_from_t gives
        // |t|² Re(n̂)/1 = 1 − ρ − (cross term); for κ = 1e-4 the difference is below 1e-8.
        let r = rho + (1.0 - rho).powi(2) * p * p * rho / (1.0 - rho * rho * p * p);
        let t = (1.0 - rho).powi(2) * p / (1.0 - rho * rho * p * p);
        assert!((x.r() - r).abs() < 1e-8 && (x.t() - t).abs() < 1e-8, "{x:?} vs {r} {t}");
    }

    #[test]
    fn opaque_incoherent_layer_has_a_finite_profile() {
        // κ = 0.1 over 1 mm: P = exp(−2500) underflows to 0; the light entering the slab decays by
        // Beer–Lambert, α = 4πκ/λ, and none comes out.
        let s = Stack::parse("air | n=2 50nm | inc:n=1.5+0.1i 1mm | air").unwrap();
        let prof = s.profile(500.0, 0.0).unwrap();
        let entering = prof.in_medium(2, 0.0).poynting();
        let alpha = 4.0 * std::f64::consts::PI * 0.1 / 500.0;
        for dz in [0.0, 10.0, 100.0, 1e4, 1e6] {
            let p = prof.in_medium(2, dz);
            assert!(p.absorption().is_finite() && p.e2().is_finite() && p.poynting().is_finite(), "{p:?}");
            let want = entering * (-alpha * dz).exp();
            assert!((p.poynting() - want).abs() < 1e-15 && (p.absorption() - alpha * want).abs() < 1e-15, "{p:?}");
        }
        let x = s.evaluate(500.0, 0.0).unwrap();
        assert!(x.t() == 0.0 && (entering - (1.0 - x.r())).abs() < 1e-12);
    }

    #[test]
    fn coherent_stack_gives_the_coherent_answer() {
        let s = Stack::parse("air | n=1.38 100nm | n=2.1 80nm | n=1.5").unwrap();
        let a = s.evaluate(512.0, 0.4).unwrap();
        let b = evaluate(&s, 512.0, 0.4, &s.thicknesses()).unwrap();
        assert!((a.r_s - b.r_s).abs() < 1e-15 && (a.t_p - b.t_p).abs() < 1e-15);
    }
}
