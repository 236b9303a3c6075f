//! The unit tests of src/area.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::area::*;
use iridis_render::math::*;
use iridis_render::sampling::{next2, seed};

fn shapes() -> Vec<Shape> {
    vec![
        Shape::Sphere { center: [0.3, 2.0, -0.5], radius: 0.7 },
        Shape::Disk { center: [0.0, 1.5, 0.4], normal: normalize([0.2, -1.0, 0.1]), radius: 0.6 },
        Shape::Rectangle {
            center: [-0.4, 1.2, 0.0],
            normal: [0.0, -1.0, 0.0],
            tangent: normalize([1.0, 0.0, 1.0]),
            size: [1.2, 0.5],
        },
    ]
}

#[test]
fn samples_hit_the_light_and_their_pdf_matches() {
    let p = [0.1, 0.0, 0.2];
    for s in shapes() {
        seed(3, 0);
        for _ in 0..2000 {
            let x = s.sample(p, next2()).expect("the point sees the light");
            let t = s.intersect(p, x.wi, f64::INFINITY).expect("a sampled direction meets the light");
            assert!((t - x.dist).abs() < 1e-9 * (1.0 + t), "{s:?}: {t} vs {}", x.dist);
            let q = s.pdf(p, x.wi);
            assert!((q - x.pdf).abs() < 1e-9 * x.pdf, "{s:?}: pdf {q} vs {}", x.pdf);
        }
    }
}

#[test]
fn the_pdf_integrates_to_one_over_the_sphere_of_directions() {
    // ∫ pdf dω over a fine (θ, φ) grid = 1: the sampled directions cover the light's solid angle exactly.
    let p = [0.1, 0.0, 0.2];
    for s in shapes() {
        let acc = crate::unit_sampling::sphere_integral(1600, 800, |d| s.pdf(p, d));
        assert!((acc - 1.0).abs() < 0.01, "{s:?}: ∫ pdf = {acc}");
    }
}

#[test]
fn representative_irradiance_is_exact_where_stated() {
    // A sphere of radius r at distance d: E/π = L r²/d² = ∫ L cos dω / π over its cone about the normal.
    let s = Shape::Sphere { center: [0.0, 3.0, 0.0], radius: 1.0 };
    let r = s.representative([0.0; 3]).unwrap();
    assert!((r.e_per_radiance - 1.0 / 9.0).abs() < 1e-15);
    assert!((r.solid_angle - std::f64::consts::TAU * (1.0 - (8.0f64 / 9.0).sqrt())).abs() < 1e-12);
    // A disk of radius 1 at distance 2 on its axis: r² / (r² + d²) = 1/5.
    let d = Shape::Disk { center: [0.0, 2.0, 0.0], normal: [0.0, -1.0, 0.0], radius: 1.0 };
    assert!((d.representative([0.0; 3]).unwrap().e_per_radiance - 0.2).abs() < 1e-15);
    // Behind a disk: nothing.
    assert!(d.representative([0.0, 3.0, 0.0]).is_none());
    assert!(d.sample([0.0, 3.0, 0.0], [0.3, 0.3]).is_none());
}
