//! The unit tests of src/laser.rs (the laser experiment's geometry and metal reflectance), moved here so that
//! `cargo test` compiles the library once.

use iridis_diffraction::geometry::Vec3;
use iridis_lab::laser::{LaserSetup, MetalFresnel};
use iridis_thinfilm::Material;

#[test]
fn the_screen_centre_sees_the_mirror_direction_and_the_beam_axis_is_horizontal() {
    let s = LaserSetup::default();
    let (wi, mirror, e1, e2) = s.frame();
    let (wr, w) = s.view(0.0, 0.0).unwrap();
    for k in 0..3 {
        assert!((wr[k] - mirror[k]).abs() < 1e-12);
    }
    assert!((w - 1.0).abs() < 1e-12);
    // The screen is parallel to the beam: e₁ is the beam's direction and perpendicular to the mirror ray.
    let dot = |a: Vec3, b: Vec3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    assert!(dot(mirror, e1).abs() < 1e-12 && dot(mirror, e2).abs() < 1e-12 && dot(e1, e2).abs() < 1e-12);
    assert!((dot(e1, wi) + 1.0).abs() < 1e-12);
    // At 45° the mirror ray is perpendicular to the beam (the screen catches it head-on).
    assert!(dot(mirror, [-wi[0], -wi[1], -wi[2]]).abs() < 1e-12);
}

#[test]
fn gold_is_yellow_red_in_reflection() {
    // Johnson & Christy gold reflects far more red than blue at normal incidence (≈ 0.4 at 450 nm,
    // ≈ 0.95 at 700 nm); the exact Fresnel formula on the tabulated index must reproduce that ordering
    // and bounds (0 < R < 1).
    let gold = MetalFresnel::new(Material::builtin("gold").unwrap(), 380.0, 780.0).unwrap();
    let (b, r) = (gold.normal_reflectance(450.0), gold.normal_reflectance(700.0));
    assert!(b > 0.2 && b < 0.6 && r > 0.9 && r < 1.0, "R(450) = {b}, R(700) = {r}");
}
