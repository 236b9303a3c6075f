//! The incoherent addition of intensities (S. J. Byrnes, "Multilayer optical calculations", arXiv:1603.02720,
//! section 5): the power coefficients of the coherent groups between incoherent media, the single-pass
//! transmission of an incoherent layer, and the groups combined from the bottom up by the incoherent analogue of
//! Sussenbach eq. 3.1–3.2 (module [`crate::incoherent`] explains the method). Below [`crate::stack`], which
//! evaluates stacks with `inc:` layers through it.

use num_complex::Complex64;

use crate::recurrence::{compose, Medium, Rta};

/// Power coefficients of one coherent group (or bare interface) between two incoherent media, for s and p:
/// `[R_f, T_f, R_b, T_b]` (forwards: from the upper medium; backwards: from the lower one).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroupPowers {
    pub s: [f64; 4],
    pub p: [f64; 4],
}

/// `Re(n̂ s_z)` (s) or `Re(n̂ conj(s_z))` (p): the normal power flux of a unit wave, as in tmm's `T_from_t`
/// (Byrnes eq. 21–22); they differ only in absorbing media.
fn flux(m: Medium, p: bool) -> f64 {
    if p {
        (m.n * m.cos.conj()).re
    } else {
        (m.n * m.cos).re
    }
}

/// `|t|²` times the ratio of fluxes, or 0 where no power flows (an evanescent medium).
fn power_t(t: Complex64, upper: Medium, lower: Medium, p: bool) -> f64 {
    let (a, b) = (flux(upper, p), flux(lower, p));
    if a <= 0.0 || b <= 0.0 {
        0.0
    } else {
        t.norm_sqr() * b / a
    }
}

/// The powers of the coherent group `media` (its incoherent ends included) with the inner thicknesses.
pub fn group_powers(media: &[Medium], thicknesses_nm: &[f64], wavelength_nm: f64) -> GroupPowers {
    let f = compose(media, thicknesses_nm, wavelength_nm, None);
    let rev_media: Vec<Medium> = media.iter().rev().copied().collect();
    let rev_d: Vec<f64> = thicknesses_nm.iter().rev().copied().collect();
    let b = compose(&rev_media, &rev_d, wavelength_nm, None);
    let (top, bottom) = (media[0], media[media.len() - 1]);
    GroupPowers {
        s: [
            f.gamma_s.norm_sqr(),
            power_t(f.tau_s, top, bottom, false),
            b.gamma_s.norm_sqr(),
            power_t(b.tau_s, bottom, top, false),
        ],
        p: [
            f.gamma_p.norm_sqr(),
            power_t(f.tau_p, top, bottom, true),
            b.gamma_p.norm_sqr(),
            power_t(b.tau_p, bottom, top, true),
        ],
    }
}

/// The single-pass intensity transmission of an incoherent layer, `exp(−4π d Im(n̂ s_z) / λ)`
/// (Byrnes section 5; `Im(n̂ s_z) ≥ 0` on the forward branch).
pub fn single_pass(m: Medium, thickness_nm: f64, wavelength_nm: f64) -> f64 {
    (-4.0 * std::f64::consts::PI * thickness_nm * (m.n * m.cos).im / wavelength_nm).exp()
}

/// The powers of each coherent group between consecutive incoherent media `inc` (indices into `media`),
/// top first.
pub(crate) fn group_list(
    media: &[Medium],
    thicknesses_nm: &[f64],
    inc: &[usize],
    wavelength_nm: f64,
) -> Vec<GroupPowers> {
    inc.windows(2).map(|w| group_powers(&media[w[0]..=w[1]], &thicknesses_nm[w[0]..w[1] - 1], wavelength_nm)).collect()
}

/// Reflectance and transmittance of `media` cut at the incoherent media `inc` into coherent groups, with the
/// layer thicknesses. T into an absorbing substrate is 0 (the light entering it is absorbed; `docs/PHYSICS.md`).
pub(crate) fn rta(media: &[Medium], thicknesses_nm: &[f64], inc: &[usize], wavelength_nm: f64) -> Rta {
    let g = group_list(media, thicknesses_nm, inc, wavelength_nm);
    let pass: Vec<f64> = inc.iter().map(|&i| pass_of(media, thicknesses_nm, i, wavelength_nm)).collect();
    let (r_s, t_s) = cascade(g.iter().map(|x| x.s), &pass);
    let (r_p, t_p) = cascade(g.iter().map(|x| x.p), &pass);
    let opaque = media[media.len() - 1].n.im > 0.0;
    let z = |t: f64| if opaque { 0.0 } else { t };
    Rta { r_s, r_p, t_s: z(t_s), t_p: z(t_p) }
}

/// `P` of incoherent medium `i` (1 for the semi-infinite ends).
pub(crate) fn pass_of(media: &[Medium], thicknesses_nm: &[f64], i: usize, wavelength_nm: f64) -> f64 {
    if i == 0 || i == media.len() - 1 {
        1.0
    } else {
        single_pass(media[i], thicknesses_nm[i - 1], wavelength_nm)
    }
}

/// Combines the groups from the bottom up (module documentation); `pass[k]` is `P` of incoherent medium `k`.
pub(crate) fn cascade(
    groups: impl DoubleEndedIterator<Item = [f64; 4]> + ExactSizeIterator,
    pass: &[f64],
) -> (f64, f64) {
    let m = groups.len();
    let mut it = groups.rev();
    let [rf, tf, _, _] = it.next().expect("at least one group");
    let (mut r, mut t) = (rf, tf);
    for (k, [rf, tf, rb, tb]) in (0..m - 1).rev().zip(it) {
        let p = pass[k + 1];
        let inv = 1.0 / (1.0 - rb * p * p * r);
        (r, t) = (rf + tf * tb * p * p * r * inv, tf * p * t * inv);
    }
    (r, t)
}
