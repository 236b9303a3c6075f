//! The unit tests of src/point.rs (single-point queries), moved here so that `cargo test` compiles the library once.

use iridis_diffraction::evaluator::GroundTruth;
use iridis_diffraction::geometry::{direction, Shading};
use iridis_diffraction::point::*;
use iridis_diffraction::{Patch, SpectralSetup};

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
    let glass = iridis_diffraction::Fresnel::Index { n: num_complex::Complex64::new(1.5, 0.0) };
    let shading = Shading { fresnel: std::sync::Arc::new(glass), shadowing: false, ..Shading::default() };
    let spectral = SpectralSetup::default();
    let gt = GroundTruth::with_aperture(&patch, 8000.0, shading, &spectral, 41, iridis_diffraction::Aperture::Periodic)
        .unwrap();
    let wi = direction(60f64.to_radians(), 0.0);
    let wr = direction(60f64.to_radians(), std::f64::consts::PI);
    let q = point_query(&gt, &[500.0], wi, wr).unwrap();
    let b = q.brdf.unwrap();
    let [rs, rp] = iridis_diffraction::geometry::fresnel_sp(num_complex::Complex64::new(1.5, 0.0), 0.5);
    let gain = 4.0 * std::f64::consts::PI * 2000.0f64.powi(2) / 500.0f64.powi(2);
    assert!((b.s[0] / (rs * gain) - 1.0).abs() < 1e-9, "{b:?}");
    assert!((b.p[0] / (rp * gain) - 1.0).abs() < 1e-9, "{b:?}");
}
