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
