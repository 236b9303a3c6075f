//! The thesis' texture blending (Dhillon's thesis, Algorithm 4) and the ambient term of the diffraction
//! material, against values worked out by hand from the thesis' formula:
//!
//! ```text
//! α = |F|, clamped to 1                      (lines 1–4; F: Schlick's Fresnel at the half vector)
//! c_out = (1 − w_diffuse)·c_diffraction + (1 − α)·c_texture + w_diffuse·c_texture   (lines 5–8)
//! ```
//!
//! with `c_texture` lit as a Lambertian surface (`texture · E · cos θ_i`) and, added once whatever the lights
//! do, `ambient · texture`. The diffraction colour comes from a stand-in evaluator that returns one fixed
//! colour for every pair of directions above the surface, so the blending is all that is tested.

use std::path::Path;
use std::sync::Arc;

use iridis_color::Xyz;
use iridis_diffraction::geometry::Vec3;
use iridis_diffraction::Evaluator;
use iridis_render::material::{Blend, ColorSource, Diffraction, Material, OrientRule, Orientation};
use iridis_render::parse_scene;

/// `c_diffraction` before irradiance and `scale_ru`: linear sRGB [0.02, 0.05, 0.01] above the surface.
struct Constant;
impl Evaluator for Constant {
    fn name(&self) -> &'static str {
        "constant"
    }
    fn reflectance(&self, _: f64, _: Vec3, _: Vec3) -> Option<f64> {
        None
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        if wi[2] > 0.0 && wr[2] > 0.0 {
            Xyz::from_linear_srgb([0.02, 0.05, 0.01])
        } else {
            Xyz::default()
        }
    }
}

/// A plane z = 0 seen straight down (ω_o = +z) under a directional light at θ_i = `theta_deg` in the xz plane,
/// 2 RU tinted [1, 0.5, 0.25]: irradiance E = [2, 1, 0.5].
fn shade(theta_deg: f64, w_diffuse: f64, ambient: f64) -> [f64; 3] {
    let t = theta_deg.to_radians();
    let text = format!(
        "[camera]\nkind = \"orthographic\"\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nup = [0, 1, 0]\n\
         [[light]]\nkind = \"directional\"\ndirection = [{}, 0, {}]\nintensity = 2\ncolor = [1, 0.5, 0.25]\n\
         [materials.m]\nkind = \"lambert\"\n\
         [[object]]\nkind = \"plane\"\nnormal = [0, 0, 1]\ntangent = [1, 0, 0]\nmaterial = \"m\"\n",
        t.sin(),
        t.cos()
    );
    let mut scene = parse_scene(&text, "algorithm4.toml", Path::new(".")).unwrap();
    scene.materials[0] = Material::Diffraction(Box::new(Diffraction {
        evaluator: Arc::new(Constant),
        orientation: Orientation { rule: OrientRule::Tangent, angle: 0.0 },
        scale_ru: 10.0,
        w_diffuse,
        texture: ColorSource::Const([0.6, 0.4, 0.2]),
        ambient,
        fresnel_n: 1.5,
        description: "constant".into(),
        blend: Blend::Algorithm4,
        extended: Default::default(),
    }));
    scene.primary([0.0, 0.0, 5.0], [0.0, 0.0, -1.0])
}

fn close(got: [f64; 3], want: [f64; 3]) {
    for k in 0..3 {
        assert!((got[k] - want[k]).abs() < 1e-12, "{got:?} vs {want:?}");
    }
}

#[test]
fn algorithm_4_blends_as_the_thesis_writes() {
    // θ_i = 60°, ω_o = n: the half vector is 30° from ω_i, so
    //   F_0 = ((1.5 − 1)/(1.5 + 1))² = 0.04,  α = 0.04 + 0.96 (1 − cos 30°)⁵ = 0.04004143654313937;
    //   c_diffraction = [0.02, 0.05, 0.01] · E · 10 = [0.4, 0.5, 0.05];
    //   c_texture = [0.6, 0.4, 0.2] · E · cos 60° = [0.6, 0.2, 0.05];
    //   ambient = 0.25 · [0.6, 0.4, 0.2] = [0.15, 0.1, 0.05].
    // w_diffuse = 0.3:
    //   R = 0.7·0.4  + (1 − α)·0.6  + 0.3·0.6  + 0.15 = 1.1859751380741161
    //   G = 0.7·0.5  + (1 − α)·0.2  + 0.3·0.2  + 0.1  = 0.7019917126913721
    //   B = 0.7·0.05 + (1 − α)·0.05 + 0.3·0.05 + 0.05 = 0.14799792817284302
    close(shade(60.0, 0.3, 0.25), [1.1859751380741161, 0.7019917126913721, 0.14799792817284302]);
    // w_diffuse = 0, no ambient: c_diffraction + (1 − α)·c_texture.
    //   = [0.4 + 0.9599585634568606·0.6, 0.5 + 0.9599585634568606·0.2, 0.05 + 0.9599585634568606·0.05]
    close(shade(60.0, 0.0, 0.0), [0.9759751380741164, 0.6919917126913722, 0.09799792817284303]);
    // w_diffuse = 1: no diffraction at all; (1 − α)·c_texture + c_texture.
    close(shade(60.0, 1.0, 0.0), [1.1759751380741164, 0.3919917126913721, 0.09799792817284303]);
    // Head-on light (θ_i = 0): the half vector is the normal, α = F_0 = 0.04; c_texture = [1.2, 0.4, 0.1],
    // c_diffraction = [0.4, 0.5, 0.05]; w_diffuse = 0.5: 0.5·c_d + 0.96·c_t + 0.5·c_t.
    close(shade(0.0, 0.5, 0.0), [0.2 + 1.46 * 1.2, 0.25 + 1.46 * 0.4, 0.025 + 1.46 * 0.1]);
}

#[test]
fn the_ambient_term_is_added_whatever_the_lights_do() {
    // A light below the surface (θ_i = 120°) reaches nothing: only ambient · texture = 0.4 · [0.6, 0.4, 0.2].
    close(shade(120.0, 0.3, 0.4), [0.24, 0.16, 0.08]);
    // And with the light above it, the ambient term adds exactly that on top of the lit value.
    let lit = shade(60.0, 0.3, 0.0);
    let with = shade(60.0, 0.3, 0.4);
    close(with, [lit[0] + 0.24, lit[1] + 0.16, lit[2] + 0.08]);
}
