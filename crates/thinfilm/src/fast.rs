//! The real-time variant of Sussenbach chapter 4 (Algorithms 3 and 4): for a fixed incidence angle and
//! wavelength-invariant indices, the per-interface Fresnel amplitudes (eq. 3.7–3.10) and the partial phases
//! `n̂_j s_{z,j}` are computed once ("precalculation stage"); each wavelength then costs only the phases
//! `φ_j = (2π/λ) n̂_j s_{z,j} d_j` (eq. 3.5) and the recurrence (eq. 3.1–3.2). When every medium is
//! dielectric and no layer is beyond its critical angle, all interface values are real and only γ and τ are
//! complex (section 4.4, "media are strictly dielectric"). The numbers are those of [`Stack::evaluate`]
//! (tested to 1e-13).
//!
//! Thickness offsets per sample give spatially varying thickness (section 4.2, eq. 4.3).

use num_complex::Complex64;

use crate::error::ThinFilmError;
use crate::recurrence::{fresnel, grazing_variants, recur, transmission_factor, Medium, Rta};
use crate::stack::Stack;

#[derive(Debug, Clone)]
enum Interfaces {
    /// `[r_s, r_p, t_s, t_p]` per interface and `n_j s_{z,j}` per layer, all real.
    Real { rt: Vec<[f64; 4]>, q: Vec<f64> },
    /// The general case (absorbing media, evanescent layers).
    Complex { rt: Vec<[Complex64; 4]>, q: Vec<Complex64> },
}

/// A stack prepared for one incidence angle (and, for dispersive materials, one wavelength).
#[derive(Debug, Clone)]
pub struct Prepared {
    /// One set, or two for a layer at its critical angle (averaged, see `recurrence::grazing_variants`).
    sets: Vec<Interfaces>,
    thicknesses: Vec<f64>,
    t_factor: f64,
    /// `Some(λ)` when the indices were taken at one wavelength (dispersive stack).
    wavelength_nm: Option<f64>,
}

impl Stack {
    /// Prepares a wavelength-invariant stack for one incidence angle (chapter 4's assumption 3).
    pub fn prepare(&self, angle_rad: f64) -> Result<Prepared, ThinFilmError> {
        if !self.is_wavelength_invariant() {
            return Err(ThinFilmError::Invalid(
                "the fast path needs wavelength-invariant indices; use prepare_at(λ, θ) for a dispersive stack".into(),
            ));
        }
        Prepared::new(self, 550.0, angle_rad, None)
    }

    /// Prepares any stack for one wavelength and angle, e.g. to evaluate many thickness offsets (SVT).
    pub fn prepare_at(&self, wavelength_nm: f64, angle_rad: f64) -> Result<Prepared, ThinFilmError> {
        Prepared::new(self, wavelength_nm, angle_rad, Some(wavelength_nm))
    }
}

impl Prepared {
    fn new(stack: &Stack, wavelength_nm: f64, angle_rad: f64, at: Option<f64>) -> Result<Self, ThinFilmError> {
        if stack.has_incoherent() {
            return Err(ThinFilmError::Invalid(
                "the fast path is for coherent stacks; a stack with an inc: layer uses Stack::evaluate".into(),
            ));
        }
        let media: Vec<Medium> = stack.media(wavelength_nm, angle_rad)?;
        let n = stack.layers.len();
        let sets = match grazing_variants(&media) {
            Some([plus, minus]) => vec![interfaces(&plus), interfaces(&minus)],
            None => vec![interfaces(&media)],
        };
        Ok(Self {
            sets,
            thicknesses: stack.thicknesses(),
            t_factor: transmission_factor(media[0], media[n + 1]),
            wavelength_nm: at,
        })
    }

    /// True when the real-arithmetic path is used (dielectric stack, no evanescent layer).
    pub fn is_real(&self) -> bool {
        self.sets.iter().all(|s| matches!(s, Interfaces::Real { .. }))
    }

    fn check(&self, wavelength_nm: f64) -> Result<(), ThinFilmError> {
        if !(wavelength_nm.is_finite() && wavelength_nm > 0.0) {
            return Err(ThinFilmError::Invalid(format!("wavelength {wavelength_nm} nm must be positive")));
        }
        if let Some(w) = self.wavelength_nm {
            if (w - wavelength_nm).abs() > 1e-9 * w {
                return Err(ThinFilmError::Invalid(format!(
                    "this stack was prepared at {w} nm (dispersive materials); prepare it again for {wavelength_nm} nm"
                )));
            }
        }
        Ok(())
    }

    /// R, T at a wavelength with the stack's own thicknesses.
    pub fn evaluate(&self, wavelength_nm: f64) -> Result<Rta, ThinFilmError> {
        self.check(wavelength_nm)?;
        Ok(self.run(wavelength_nm, |j| self.thicknesses[j]))
    }

    /// Spatially varying thickness (eq. 4.3): every layer's thickness plus `offset_nm`, clamped at 0.
    pub fn evaluate_offset(&self, wavelength_nm: f64, offset_nm: f64) -> Result<Rta, ThinFilmError> {
        self.check(wavelength_nm)?;
        Ok(self.run(wavelength_nm, |j| (self.thicknesses[j] + offset_nm).max(0.0)))
    }

    /// R, T with other thicknesses (nm, one per layer).
    pub fn evaluate_thicknesses(&self, wavelength_nm: f64, thicknesses_nm: &[f64]) -> Result<Rta, ThinFilmError> {
        self.check(wavelength_nm)?;
        if thicknesses_nm.len() != self.thicknesses.len()
            || thicknesses_nm.iter().any(|d| !(d.is_finite() && *d >= 0.0))
        {
            return Err(ThinFilmError::Invalid(format!(
                "need {} finite thicknesses ≥ 0, got {:?}",
                self.thicknesses.len(),
                thicknesses_nm
            )));
        }
        Ok(self.run(wavelength_nm, |j| thicknesses_nm[j]))
    }

    /// The complex amplitudes `[r_s, r_p, t_s, t_p]` (the composite γ and τ at the top) at a wavelength with
    /// the stack's own thicknesses: what `tmm.coh_tmm` reports as `r` and `t`.
    pub fn amplitudes(&self, wavelength_nm: f64) -> Result<[Complex64; 4], ThinFilmError> {
        self.check(wavelength_nm)?;
        let d = |j: usize| self.thicknesses[j];
        Ok(if self.sets.len() == 1 {
            amplitudes(&self.sets[0], wavelength_nm, &d)
        } else {
            let a = amplitudes(&self.sets[0], wavelength_nm, &d);
            let b = amplitudes(&self.sets[1], wavelength_nm, &d);
            [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]), 0.5 * (a[3] + b[3])]
        })
    }

    #[inline]
    fn run(&self, wavelength_nm: f64, d: impl Fn(usize) -> f64) -> Rta {
        let [gs, gp, ts, tp] = if self.sets.len() == 1 {
            amplitudes(&self.sets[0], wavelength_nm, &d)
        } else {
            let a = amplitudes(&self.sets[0], wavelength_nm, &d);
            let b = amplitudes(&self.sets[1], wavelength_nm, &d);
            [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]), 0.5 * (a[3] + b[3])]
        };
        let f = self.t_factor;
        Rta { r_s: gs.norm_sqr(), r_p: gp.norm_sqr(), t_s: f * ts.norm_sqr(), t_p: f * tp.norm_sqr() }
    }
}

/// The precalculation stage (Algorithm 3): Fresnel amplitudes per interface, `n̂_j s_{z,j}` per layer.
fn interfaces(media: &[Medium]) -> Interfaces {
    let n = media.len() - 2;
    let all_real = media.iter().all(|m| m.n.im == 0.0 && m.cos.im == 0.0);
    let fr: Vec<_> = (1..=n + 1).map(|j| fresnel(media[j - 1], media[j])).collect();
    if all_real {
        Interfaces::Real {
            rt: fr.iter().map(|f| [f.r_s.re, f.r_p.re, f.t_s.re, f.t_p.re]).collect(),
            q: (1..=n).map(|j| (media[j].n * media[j].cos).re).collect(),
        }
    } else {
        Interfaces::Complex {
            rt: fr.iter().map(|f| [f.r_s, f.r_p, f.t_s, f.t_p]).collect(),
            q: (1..=n).map(|j| media[j].n * media[j].cos).collect(),
        }
    }
}

/// The simulation stage (Algorithm 4): composite amplitudes `[γ_s, γ_p, τ_s, τ_p]` at one wavelength.
#[inline]
fn amplitudes(set: &Interfaces, wavelength_nm: f64, d: &impl Fn(usize) -> f64) -> [Complex64; 4] {
    let k = 2.0 * std::f64::consts::PI / wavelength_nm;
    match set {
        Interfaces::Real { rt, q } => {
            let n = q.len();
            // Seed (eq. 3.3–3.4), then eq. 3.1–3.2 with real r, t and φ: only γ, τ are complex.
            let b = rt[n];
            let (mut gs, mut gp) = ((b[0], 0.0), (b[1], 0.0));
            let (mut ts, mut tp) = ((b[2], 0.0), (b[3], 0.0));
            for j in (0..n).rev() {
                let phi = k * q[j] * d(j); // eq. 3.5 with the precalculated n_j s_{z,j}
                let (s1, c1) = phi.sin_cos();
                let (s2, c2) = (2.0 * s1 * c1, c1 * c1 - s1 * s1);
                let [r_s, r_p, t_s, t_p] = rt[j];
                (gs, ts) = recur_real(r_s, t_s, gs, ts, (c1, s1), (c2, s2));
                (gp, tp) = recur_real(r_p, t_p, gp, tp, (c1, s1), (c2, s2));
            }
            let z = |v: (f64, f64)| Complex64::new(v.0, v.1);
            [z(gs), z(gp), z(ts), z(tp)]
        }
        Interfaces::Complex { rt, q } => {
            let n = q.len();
            let b = rt[n];
            let (mut gs, mut gp, mut ts, mut tp) = (b[0], b[1], b[2], b[3]);
            for j in (0..n).rev() {
                let phi = (k * d(j)) * q[j];
                let e1 = Complex64::from_polar((-phi.im).exp(), phi.re);
                let e2 = e1 * e1;
                let [r_s, r_p, t_s, t_p] = rt[j];
                (gs, ts) = recur(r_s, t_s, gs, ts, e1, e2);
                (gp, tp) = recur(r_p, t_p, gp, tp, e1, e2);
            }
            [gs, gp, ts, tp]
        }
    }
}

/// Eq. 3.1–3.2 with real `r`, `t`; `γ`, `τ` as (re, im); `e1 = e^{iφ}`, `e2 = e^{2iφ}` as (cos, sin).
#[inline(always)]
fn recur_real(
    r: f64,
    t: f64,
    g: (f64, f64),
    tau: (f64, f64),
    e1: (f64, f64),
    e2: (f64, f64),
) -> ((f64, f64), (f64, f64)) {
    // γ e^{2iφ}
    let (a, b) = (g.0 * e2.0 - g.1 * e2.1, g.0 * e2.1 + g.1 * e2.0);
    // denominator 1 + r γ e^{2iφ}
    let (dr, di) = (1.0 + r * a, r * b);
    let inv = 1.0 / (dr * dr + di * di);
    // numerator r + γ e^{2iφ}
    let (nr, ni) = (r + a, b);
    let gamma = ((nr * dr + ni * di) * inv, (ni * dr - nr * di) * inv);
    // t τ e^{iφ} / denominator
    let (ur, ui) = (t * (tau.0 * e1.0 - tau.1 * e1.1), t * (tau.0 * e1.1 + tau.1 * e1.0));
    let tau = ((ur * dr + ui * di) * inv, (ui * dr - ur * di) * inv);
    (gamma, tau)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_numbers_as_the_general_path() {
        for (s, real) in [
            ("air | gasoline 216nm | water 220nm | asphalt", true),
            ("air | n=1.38 100nm | n=0.2+3.4i", false),
            ("n=1.5 | n=1.0 300nm | n=1.5", true), // real below the critical angle, complex beyond
        ] {
            let stack = Stack::parse(s).unwrap();
            for deg in [0.0, 10.0, 35.0, 41.0, 42.0, 60.0, 89.9, 90.0] {
                let th = f64::to_radians(deg);
                let p = stack.prepare(th).unwrap();
                if deg < 41.0 {
                    assert_eq!(p.is_real(), real, "{s} at {deg}°");
                }
                for w in [380.0, 455.5, 550.0, 780.0] {
                    let a = stack.evaluate(w, th).unwrap();
                    let b = p.evaluate(w).unwrap();
                    for (x, y) in [(a.r_s, b.r_s), (a.r_p, b.r_p), (a.t_s, b.t_s), (a.t_p, b.t_p)] {
                        assert!((x - y).abs() < 1e-13, "{s} at {deg}°, {w} nm: {x} vs {y}");
                    }
                    let o = stack.evaluate_offset(w, th, 37.0).unwrap();
                    let q = p.evaluate_offset(w, 37.0).unwrap();
                    assert!((o.r() - q.r()).abs() < 1e-13 && (o.t() - q.t()).abs() < 1e-13);
                }
            }
        }
    }

    #[test]
    fn dispersive_stacks_need_prepare_at() {
        let s = Stack::parse("air | Si 108nm | glass").unwrap();
        assert!(s.prepare(0.1).is_err());
        let p = s.prepare_at(500.0, 0.1).unwrap();
        let a = s.evaluate_offset(500.0, 0.1, -20.0).unwrap();
        let b = p.evaluate_offset(500.0, -20.0).unwrap();
        assert!((a.r() - b.r()).abs() < 1e-13);
        assert!(p.evaluate(600.0).is_err());
    }
}
