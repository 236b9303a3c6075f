//! Point queries: the BRDF of any evaluator for one pair of directions — the spectral relative reflectance
//! `ρ(λ)` on a wavelength grid (where the method resolves wavelengths) and the colour XYZ. What `iridis brdf
//! eval` prints, for people who script.

use iridis_color::Xyz;

use crate::evaluator::Evaluator;
use crate::geometry::Vec3;
use crate::DiffractionError;

/// The answer of [`point_query`].
#[derive(Debug, Clone, PartialEq)]
pub struct PointQuery {
    /// The wavelengths of `reflectance` (nm).
    pub wavelengths_nm: Vec<f64>,
    /// `ρ(λ) = C |A(λ)|²` (paper eq. 4); `None` for methods that integrate over λ in advance (lookup).
    pub reflectance: Option<Vec<f64>>,
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
    let reflectance =
        resolves.then(|| wavelengths_nm.iter().map(|&l| e.reflectance(l, wi, wr).unwrap_or(0.0)).collect());
    Ok(PointQuery { wavelengths_nm: wavelengths_nm.to_vec(), reflectance, xyz: e.xyz(wi, wr) })
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
}
