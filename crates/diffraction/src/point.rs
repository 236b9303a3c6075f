//! Point queries: the BRDF of any evaluator for one pair of directions — the BRDF `f_r(λ)` in sr⁻¹ per
//! polarisation and the paper's relative reflectance `ρ(λ)` on a wavelength grid (where the method resolves
//! wavelengths), and the colour XYZ. What `iridis brdf eval` prints, for people who script.
//!
//! `f_r = R₀ ρ G(λ) / cos θ_i` with `G = A_eff/λ²` the window's gain ([`Evaluator::radiometric_gain`],
//! docs/PHYSICS.md "Units of ρ"), i.e. `f_r = R(θ_h) (1 + ω_i·ω_r)² |A|² G / (w² cos θ_i cos θ_r)` (times the
//! shadowing term), symmetric in `ω_i, ω_r`; per polarisation `R` is `R_s` or `R_p` at the half-vector angle
//! (the scalar model reflects each polarisation as the facet does, without converting one into the other),
//! unless the evaluator divides its `f_r` itself ([`Evaluator::polarisation`]: a rigorous BRDF's TE and TM
//! efficiencies).

use iridis_color::Xyz;

use crate::evaluator::Evaluator;
use crate::geometry::Vec3;
use crate::DiffractionError;

/// The BRDF per polarisation (sr⁻¹), one value per wavelength.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Brdf {
    /// s-polarised (TE) light.
    pub s: Vec<f64>,
    /// p-polarised (TM) light.
    pub p: Vec<f64>,
    /// Unpolarised light, `(s + p)/2`.
    pub unpolarized: Vec<f64>,
}

/// The answer of [`point_query`].
#[derive(Debug, Clone, PartialEq)]
pub struct PointQuery {
    /// The wavelengths of `reflectance` (nm).
    pub wavelengths_nm: Vec<f64>,
    /// The paper's relative reflectance `ρ(λ) = C |A(λ)|² = f_r cos θ_i / (R₀ G)` (eq. 4 with the `cos θ_i` of
    /// eq. 9: 1 at a flat mirror's peak at every λ); `None` for methods that integrate over λ in advance
    /// (lookup).
    pub reflectance: Option<Vec<f64>>,
    /// The BRDF `f_r(λ)` (sr⁻¹) per polarisation; `None` where the method has no spectral reflectance or no
    /// window gain (the lab's NMM, PQ and Stam models), or under the paper's `(R/R₀)²` convention (not a BRDF).
    pub brdf: Option<Brdf>,
    /// CIE XYZ of the reflected light (paper eq. 9; a normal-incidence mirror has `Y = 1`).
    pub xyz: Xyz,
}

/// Evaluates `e` for light from `wi` seen from `wr` (unit vectors away from the surface, both above it) at
/// every wavelength of `wavelengths_nm`.
pub fn point_query(
    e: &dyn Evaluator,
    wavelengths_nm: &[f64],
    wi: Vec3,
    wr: Vec3,
) -> Result<PointQuery, DiffractionError> {
    for (name, d) in [("light", wi), ("view", wr)] {
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if !(d.iter().all(|x| x.is_finite()) && (len - 1.0).abs() < 1e-9) {
            return Err(DiffractionError::Invalid(format!("the {name} direction {d:?} is not a unit vector")));
        }
        if d[2] <= 0.0 {
            return Err(DiffractionError::Invalid(format!(
                "the {name} direction is at or below the horizon (θ = {:.3}°): the BRDF is defined above the surface",
                d[2].clamp(-1.0, 1.0).acos().to_degrees()
            )));
        }
    }
    // A method either resolves wavelengths or it does not: ask once, then fill the grid.
    let resolves = e.reflectance(wavelengths_nm.first().copied().unwrap_or(550.0), wi, wr).is_some();
    let reflectance: Option<Vec<f64>> =
        resolves.then(|| wavelengths_nm.iter().map(|&l| e.reflectance(l, wi, wr).unwrap_or(0.0)).collect());
    let brdf = reflectance.as_ref().and_then(|rho| brdf(e, wavelengths_nm, rho, wi, wr));
    Ok(PointQuery { wavelengths_nm: wavelengths_nm.to_vec(), reflectance, brdf, xyz: e.xyz(wi, wr) })
}

/// `f_r` per polarisation from the relative `ρ` (module documentation).
fn brdf(e: &dyn Evaluator, wavelengths_nm: &[f64], rho: &[f64], wi: Vec3, wr: Vec3) -> Option<Brdf> {
    let shading = e.shading()?;
    if shading.convention != crate::geometry::FresnelConvention::Physical {
        return None;
    }
    let h = [wi[0] + wr[0], wi[1] + wr[1], wi[2] + wr[2]];
    let cos_h = crate::geometry::dot(wi, h) / crate::geometry::dot(h, h).sqrt();
    let r0 = shading.fresnel.normal_reflectance();
    let (mut s, mut p, mut u) = (Vec::new(), Vec::new(), Vec::new());
    for (&l, &rho) in wavelengths_nm.iter().zip(rho) {
        let f = r0 * rho * e.radiometric_gain(l)? / wi[2];
        let (fs, fp) = match e.polarisation(l, wi, wr) {
            Some([s, p]) => (f * s, f * p),
            None => {
                let r = shading.fresnel.reflectance(l, cos_h);
                let [rs, rp] = shading.fresnel.reflectance_sp(l, cos_h);
                if r > 0.0 {
                    (f * rs / r, f * rp / r)
                } else {
                    (0.0, 0.0)
                }
            }
        };
        s.push(fs);
        p.push(fp);
        u.push(0.5 * (fs + fp));
    }
    Some(Brdf { s, p, unpolarized: u })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::evaluator::GroundTruth;
    use crate::geometry::{direction, Shading};
    use crate::{Patch, SpectralSetup};

    #[test]
    fn a_flat_mirror_answers_one_at_normal_incidence_and_refuses_the_horizon() {
        let patch = Patch::from_row_major(16, 16, 100.0, 100.0, &vec![0.0; 256]).unwrap();
        let spectral = SpectralSetup::default();
        let gt = GroundTruth::new(&patch, 1000.0, Shading::default(), &spectral, 41).unwrap();
        let n = [0.0, 0.0, 1.0];
        let q = point_query(&gt, spectral.wavelengths(), n, n).unwrap();
        let rho = q.reflectance.unwrap();
        assert_eq!(rho.len(), spectral.wavelengths().len());
        assert!(rho.iter().all(|r| (r - 1.0).abs() < 1e-12), "{rho:?}");
        assert!((q.xyz.y - 1.0).abs() < 1e-9, "{:?}", q.xyz);
        assert!(point_query(&gt, &[500.0], n, direction(std::f64::consts::FRAC_PI_2 + 0.1, 0.0)).is_err());
        assert!(point_query(&gt, &[500.0], [0.0, 0.0, 2.0], n).is_err());
    }

    #[test]
    fn the_brdf_of_a_flat_mirror_is_its_fresnel_reflectance_over_the_lobes_solid_angle() {
        // The mirror lobe's f_r integrates to R over du dv = cos θ_r dω_r, and ∫G² du dv = λ²/(4πσ_s²), so its
        // peak is f_r = R(θ) · 4πσ_s²/λ²: on the periodic lattice of a flat patch, s and p from the exact Fresnel
        // of glass at 60°.
        let patch = Patch::from_row_major(16, 16, 100.0, 100.0, &vec![0.0; 256]).unwrap();
        let glass = crate::Fresnel::Index { n: num_complex::Complex64::new(1.5, 0.0) };
        let shading = Shading { fresnel: std::sync::Arc::new(glass), shadowing: false, ..Shading::default() };
        let spectral = SpectralSetup::default();
        let gt = GroundTruth::with_aperture(&patch, 8000.0, shading, &spectral, 41, crate::Aperture::Periodic).unwrap();
        let wi = direction(60f64.to_radians(), 0.0);
        let wr = direction(60f64.to_radians(), std::f64::consts::PI);
        let q = point_query(&gt, &[500.0], wi, wr).unwrap();
        let b = q.brdf.unwrap();
        let [rs, rp] = crate::geometry::fresnel_sp(num_complex::Complex64::new(1.5, 0.0), 0.5);
        let gain = 4.0 * std::f64::consts::PI * 2000.0f64.powi(2) / 500.0f64.powi(2);
        assert!((b.s[0] / (rs * gain) - 1.0).abs() < 1e-9, "{b:?}");
        assert!((b.p[0] / (rp * gain) - 1.0).abs() < 1e-9, "{b:?}");
    }
}
