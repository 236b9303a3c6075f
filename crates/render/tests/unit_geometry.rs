//! The unit tests of src/geometry.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::geometry::*;
use iridis_render::math::*;

#[test]
fn sphere_hit_has_an_orthonormal_frame() {
    let s = Sphere { center: [0.0, 0.0, 0.0], radius: 2.0, material: 0 };
    let h = s.intersect([0.3, 0.4, 10.0], [0.0, 0.0, -1.0], f64::INFINITY).unwrap();
    assert!((length(h.p) - 2.0).abs() < 1e-12 && h.front);
    let t = h.tangent.unwrap();
    assert!(dot(t, h.n).abs() < 1e-12 && (length(t) - 1.0).abs() < 1e-12);
    // From inside, the normal faces the ray.
    let h = s.intersect([0.0; 3], [0.0, 0.0, 1.0], f64::INFINITY).unwrap();
    assert!(!h.front && h.n[2] < 0.0);
}

#[test]
fn triangle_hits_and_misses() {
    let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let (t, u, v) = intersect_triangle([0.2, 0.3, 1.0], [0.0, 0.0, -1.0], a, b, c, 10.0).unwrap();
    assert!((t - 1.0).abs() < 1e-12 && (u - 0.2).abs() < 1e-12 && (v - 0.3).abs() < 1e-12);
    assert!(intersect_triangle([0.8, 0.8, 1.0], [0.0, 0.0, -1.0], a, b, c, 10.0).is_none());
    assert!(intersect_triangle([0.2, 0.3, 1.0], [0.0, 0.0, -1.0], a, b, c, 0.5).is_none());
}
