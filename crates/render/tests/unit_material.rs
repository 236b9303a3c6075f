//! The unit tests of src/material.rs, moved here so that `cargo test` compiles the library once.

use iridis_color::{Illuminant, Observer};
use iridis_render::geometry::Hit;
use iridis_render::material::*;
use iridis_render::math::*;
use iridis_render::texture::Texture;
use iridis_thinfilm::color::FilmColorimeter;
use iridis_thinfilm::Stack;

/// Helmholtz reciprocity of the microfacet BRDF: `reflect` returns `π f cos θ_i`, so `reflect(ω_i, ω_o) / cos θ_i`
/// must equal `reflect(ω_o, ω_i) / cos θ_o` — for the GGX lobe, the Kulla–Conty multiple scattering and the
/// diffuse lobe that takes what the specular leaves, dielectric, metal and between, textured values included.
#[test]
fn microfacet_brdf_is_reciprocal() {
    let n = [0.0, 0.0, 1.0];
    let dir = |t: f64, p: f64| [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()];
    let mut worst = 0.0f64;
    for (rough, metallic, ior) in [(0.05, 0.0, 1.5), (0.3, 0.0, 2.4), (0.7, 1.0, 1.5), (1.0, 0.5, 1.5), (0.5, 0.0, 1.0)]
    {
        let m = Microfacet {
            color: ColorSource::Const([0.9, 0.6, 0.3]),
            roughness: rough,
            metallic,
            ior,
            metallic_roughness: None,
            normal_texture: None,
        };
        for (ti, pi, to, po) in
            [(0.2, 0.0, 1.1, 2.0), (1.3, 0.5, 0.4, 3.5), (0.7, 1.0, 0.75, 4.2), (1.45, 0.0, 1.4, 3.1)]
        {
            let (wi, wo) = (dir(ti, pi), dir(to, po));
            let a = m.reflect(n, wi, wo, [0.9, 0.6, 0.3]);
            let b = m.reflect(n, wo, wi, [0.9, 0.6, 0.3]);
            for k in 0..3 {
                let (fa, fb) = (a[k] / wi[2], b[k] / wo[2]);
                assert!(fa > 0.0, "{rough} {metallic}: no reflection");
                worst = worst.max((fa - fb).abs() / fa);
            }
        }
    }
    assert!(worst < 1e-12, "f(ω_i, ω_o) vs f(ω_o, ω_i): relative {worst}");
}

/// The film over its base as lights see it (glTF iridescence, `ThinFilm::over_base_light`): reciprocal, as
/// its GGX lobe and the `1 − R(v·h)` diffuse are symmetric in the two directions.
#[test]
fn film_over_base_brdf_is_reciprocal() {
    let stack: Stack = "air | n=1.3 300nm | n=1.5".parse().unwrap();
    let film = ThinFilm::new(stack, None, false).unwrap();
    let n = [0.0, 0.0, 1.0];
    let dir = |t: f64, p: f64| [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()];
    let mut worst = 0.0f64;
    for (rough, metallic) in [(0.3, 0.0), (0.8, 0.5), (0.05, 1.0)] {
        let base = Microfacet {
            color: ColorSource::Const([0.9, 0.6, 0.3]),
            roughness: rough,
            metallic,
            ior: 1.5,
            metallic_roughness: None,
            normal_texture: None,
        };
        for (ti, pi, to, po) in [(0.2, 0.0, 1.1, 2.0), (1.3, 0.5, 0.4, 3.5), (0.7, 1.0, 0.75, 4.2)] {
            let (wi, wo) = (dir(ti, pi), dir(to, po));
            let a = film.over_base_light(&base, [0.9, 0.6, 0.3], n, wi, wo, 0.0);
            let b = film.over_base_light(&base, [0.9, 0.6, 0.3], n, wo, wi, 0.0);
            for k in 0..3 {
                let (fa, fb) = (a[k] / wi[2], b[k] / wo[2]);
                assert!(fa > 0.0);
                worst = worst.max((fa - fb).abs() / fa);
            }
        }
    }
    assert!(worst < 1e-12, "relative {worst}");
}

#[test]
fn film_colours_match_the_colorimeter() {
    let stack: Stack = "air | water 400nm | air".parse().unwrap();
    let film = ThinFilm::new(stack.clone(), None, true).unwrap();
    let grid = iridis_color::spectrum::uniform_grid(380.0, 780.0, 5.0).unwrap();
    let cm = FilmColorimeter::new(&grid, Illuminant::D65, Observer::Cie1931);
    for deg in [0.0f64, 30.0, 70.0] {
        let want = cm.color(&stack.with_thickness(0, 450.0), deg.to_radians(), Default::default()).unwrap();
        let (r, t) = film.colors(deg.to_radians().cos(), 50.0);
        for (a, b) in [(r, want.reflected), (t, want.transmitted)] {
            assert!((a.x - b.x).abs() < 1e-9 && (a.y - b.y).abs() < 1e-9 && (a.z - b.z).abs() < 1e-9);
        }
    }
}

#[test]
fn orientation_rules_give_the_expected_axis() {
    let hit = Hit {
        t: 1.0,
        p: [0.0; 3],
        n: [0.0, 0.0, 1.0],
        ng: [0.0, 0.0, 1.0],
        front: true,
        uv: [0.3, 0.3],
        tangent: Some([1.0, 0.0, 0.0]),
        tangent_sign: 1.0,
        along: Some([0.0, 1.0, 0.0]),
        material: 0,
    };
    // A vector texture pointing along +G = the bitangent n × t = +y.
    let tex = vec![Texture::Checker { a: [0.5, 1.0, 0.5], b: [0.5, 1.0, 0.5], n: 1.0 }];
    let close = |a: V3, b: V3| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12);
    let o = |rule, angle| Orientation { rule, angle }.tangent(&hit, &tex);
    assert!(close(o(OrientRule::Texture(0), 0.0), [0.0, 1.0, 0.0]));
    assert!(close(o(OrientRule::Tangent, 0.0), [1.0, 0.0, 0.0]));
    assert!(close(o(OrientRule::Along, 0.0), [0.0, 1.0, 0.0]));
    // +90° about the normal turns t into n × t.
    assert!(close(o(OrientRule::Tangent, std::f64::consts::FRAC_PI_2), [0.0, 1.0, 0.0]));
    // A world direction is projected onto the surface.
    assert!(close(o(OrientRule::Direction([1.0, 1.0, 5.0]), 0.0), normalize([1.0, 1.0, 0.0])));
}

#[test]
fn microfacet_lobes_integrate_to_their_environment_weights() {
    // ∫ f cos θ_i dω_i by brute force over a (θ_i, φ_i) grid — independent of the energy table's half-vector
    // quadrature — against env_weights (specular + diffuse share), which the environment shading uses.
    // A white dielectric or metal reflects everything: 1 (the white furnace for lights).
    let n = [0.0, 0.0, 1.0];
    let cases: [(f64, f64, [f64; 3]); 6] = [
        (0.3, 0.0, [1.0; 3]),
        (0.6, 0.0, [1.0; 3]),
        (1.0, 0.0, [1.0; 3]),
        (0.5, 1.0, [1.0; 3]),
        (0.5, 1.0, [1.0, 0.78, 0.34]),
        (0.8, 0.5, [0.5, 0.6, 0.7]),
    ];
    for (rough, metallic, albedo) in cases {
        let m = Microfacet {
            color: ColorSource::Const(albedo),
            roughness: rough,
            metallic,
            ior: 1.5,
            metallic_roughness: None,
            normal_texture: None,
        };
        for mu_o in [1.0f64, 0.6, 0.25] {
            let wo = [(1.0 - mu_o * mu_o).sqrt(), 0.0, mu_o];
            let (nt, np) = (900, 360);
            let mut acc = [0.0; 3];
            for i in 0..nt {
                let th = std::f64::consts::FRAC_PI_2 * (i as f64 + 0.5) / nt as f64;
                let dw = th.sin() * std::f64::consts::FRAC_PI_2 / nt as f64 * std::f64::consts::TAU / np as f64;
                for j in 0..np {
                    let ph = std::f64::consts::TAU * (j as f64 + 0.5) / np as f64;
                    let wi = [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()];
                    let r = m.reflect(n, wi, wo, albedo);
                    acc = add(acc, mul(r, dw / std::f64::consts::PI));
                }
            }
            let (spec, diff) = m.env_weights(mu_o, albedo);
            for k in 0..3 {
                let want = spec[k] + diff[k];
                assert!(
                    (acc[k] - want).abs() < 0.015,
                    "roughness {rough}, metallic {metallic}, μ_o {mu_o}: ∫ = {acc:?}, weights {want}"
                );
                if albedo == [1.0; 3] {
                    assert!((want - 1.0).abs() < 1e-9, "{want}");
                }
            }
        }
    }
}

#[test]
fn microfacet_is_bounded_and_lambert_like_when_rough() {
    let m = Microfacet {
        color: ColorSource::Const([0.5; 3]),
        roughness: 1.0,
        metallic: 0.0,
        ior: 1.5,
        metallic_roughness: None,
        normal_texture: None,
    };
    let n = [0.0, 0.0, 1.0];
    let r = m.reflect(n, n, n, [0.5; 3]);
    assert!(r[0] > 0.45 && r[0] < 0.6, "{r:?}");
    let gold = Microfacet {
        color: ColorSource::Const([1.0, 0.8, 0.3]),
        roughness: 0.2,
        metallic: 1.0,
        ior: 1.5,
        metallic_roughness: None,
        normal_texture: None,
    };
    let f = gold.mirror_fresnel(1.0, [1.0, 0.8, 0.3]);
    assert_eq!(f, [1.0, 0.8, 0.3]);
}
