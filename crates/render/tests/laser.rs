//! The laser light (paper sec. 6.2): the spot of a beam on a diffraction sample lights the scene with the
//! sample's reflection. A white Lambertian screen shows, per pixel, `ρ·cos θ_s · P·F(ω_i, ω_o)·cos θ_o /
//! (cos θ_i · r²)`: the BRDF evaluated by the lookup evaluator itself at the pixel's exact direction (not the
//! interpolated profile the light uses), the beam's spread over the tilted sample, the spot's projected area
//! and the inverse-square law.

use iridis_render::material::Material;
use iridis_render::math::*;
use iridis_render::{parse_scene, render};

/// A sample at the origin facing `(1, 0, 1)`, the beam arriving along −x (45°), a white screen `dist` away
/// along the mirror direction +z, an orthographic camera looking at the screen from the sample's side.
fn scene(table: &str, dist: f64, power: f64) -> String {
    include_str!("scenes/laser_screen.toml")
        .replace("{table}", table)
        .replace("{power}", &power.to_string())
        .replace("{cam}", &(dist - 1.0).to_string())
        .replace("{dist}", &dist.to_string())
        .replace("{h}", &(dist * 1.2).to_string())
}

/// Over the screen, away from the mirror direction (the zero order is a spike no 512² map resolves), the
/// rendered luminance equals the closed form with the BRDF of builtin:gaussian (random roughness, rms 30 nm,
/// correlation 500 nm: a broad lobe with fine speckle): the median pixel within 1 %, nine in ten within 5 %
/// (the light reads its profile bilinearly from a 512² map, the closed form evaluates the table at the
/// pixel's exact direction), and the sum over the screen within 1 %. Moving the screen twice as far quarters
/// what arrives in a given direction.
#[test]
fn the_screen_shows_the_brdf_times_the_inverse_square_law() {
    let dir = std::path::Path::new(".");
    let (dist, power) = (10.0, 1e4);
    let s = parse_scene(&scene("builtin:gaussian", dist, power), "laser.toml", dir).unwrap();
    let Material::Diffraction(df) = &s.materials[0] else { panic!("the sample is a diffraction material") };
    let img = render(&s, 48, 48, 1, &|_| {});
    let n = normalize([1.0, 0.0, 1.0]);
    let t = [0.0, 1.0, 0.0];
    let b = cross(n, t);
    let wi = [1.0, 0.0, 0.0];
    let mirror = [0.0, 0.0, 1.0];
    let cos_in = dot(wi, n);
    let local = |v: V3| [dot(v, t), dot(v, b), dot(v, n)];
    let lum = |c: [f64; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    let (mut rel, mut sum_got, mut sum_expected) = (Vec::new(), 0.0, 0.0);
    for row in 0..48 {
        for col in 0..48 {
            // The screen point this pixel's centre sees (the camera looks along +z: its right is −x).
            let half = dist * 1.2 / 2.0;
            let (x, y) =
                (-half + (col as f64 + 0.5) / 48.0 * 2.0 * half, half - (row as f64 + 0.5) / 48.0 * 2.0 * half);
            let p = [-x, y, dist];
            let wo = normalize(p);
            if dot(wo, mirror) > 5f64.to_radians().cos() {
                continue;
            }
            let f = df.evaluator.xyz(local(wi), local(wo)).to_linear_srgb();
            let expected = lum(f) * power * dot(wo, n) / (cos_in * dot(p, p)) * wo[2];
            let g = img.data[row * 48 + col];
            let got = lum([g[0] as f64, g[1] as f64, g[2] as f64]);
            rel.push((got - expected).abs() / expected);
            sum_got += got;
            sum_expected += expected;
        }
    }
    rel.sort_by(f64::total_cmp);
    let (median, p90) = (rel[rel.len() / 2], rel[rel.len() * 9 / 10]);
    let total = (sum_got - sum_expected).abs() / sum_expected;
    eprintln!("{} pixels: median relative difference {median:.4}, 90th percentile {p90:.4}, sum {total:.5}", rel.len());
    assert!(rel.len() > 2000 && median < 0.005 && p90 < 0.02 && total < 0.005, "{median} {p90} {total}");

    // Twice as far, the same direction (the camera's view widens with the distance) gets ¼, up to the spot's
    // lift off the sample (10⁻⁴ of the scene's size: it shifts the directions a little, within 0.25 %).
    let near = img;
    let far_scene = parse_scene(&scene("builtin:gaussian", 2.0 * dist, power), "laser.toml", dir).unwrap();
    let far = render(&far_scene, 48, 48, 1, &|_| {});
    for k in [10 * 48 + 10, 36 * 48 + 30, 5 * 48 + 40] {
        for c in 0..3 {
            let ratio = near.data[k][c] as f64 / far.data[k][c] as f64;
            assert!((ratio - 4.0).abs() < 0.01, "pixel {k}: near/far {ratio}");
        }
    }
}

/// The beam must meet a diffraction sample; what it meets otherwise is named.
#[test]
fn a_laser_needs_a_diffraction_sample_in_its_path() {
    let dir = std::path::Path::new(".");
    let text = scene("builtin:gaussian", 10.0, 1.0);
    let e = parse_scene(&text.replace("direction = [-1, 0, 0]", "direction = [1, 0, 0]"), "laser.toml", dir)
        .unwrap_err()
        .to_string();
    assert!(e.contains("meets nothing") && e.contains("laser.toml:"), "{e}");
    let e = parse_scene(&text.replace("material = \"sample\"", "material = \"screen\""), "laser.toml", dir)
        .unwrap_err()
        .to_string();
    assert!(e.contains("`screen`") && e.contains("not a diffraction material"), "{e}");
    let e = parse_scene(&text.replace("direction = [-1, 0, 0]\n", ""), "laser.toml", dir).unwrap_err().to_string();
    assert!(e.contains("missing key `direction`"), "{e}");
}
