//! The unit tests of src/math.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::math::*;

#[test]
fn rotations_are_right_handed() {
    let r = euler_xyz([0.0, 0.0, std::f64::consts::FRAC_PI_2]);
    let v = mat_vec(&r, [1.0, 0.0, 0.0]);
    assert!((v[1] - 1.0).abs() < 1e-12 && v[0].abs() < 1e-12);
    let w = rotate_about([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2);
    assert!((w[1] - 1.0).abs() < 1e-12);
    assert_eq!(reflect([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]), [0.0, 0.0, 1.0]);
    let d = reflect(normalize([1.0, 0.0, 1.0]), [0.0, 0.0, 1.0]);
    assert!((d[0] + std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-12);
}
