//! Light units and the equirectangular environment, through scene files.

use iridis_render::{parse_scene, render};

/// A white Lambertian plane under a point light of 1 RU at distance 2 straight above: the pixel below the light
/// shows albedo · cos θ / r² = 0.5 · 1 / 4 (Y, D65 white), and a pixel further out falls off as cos θ / r².
#[test]
fn point_light_on_lambert_follows_inverse_square_and_cosine() {
    let scene = parse_scene(
        r#"
[camera]
kind = "orthographic"
position = [0, 5, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
height = 4
[[light]]
kind = "point"
position = [0, 2, 0]
intensity = 1
[materials.white]
kind = "lambert"
color = [0.5, 0.5, 0.5]
[[object]]
kind = "plane"
normal = [0, 1, 0]
material = "white"
"#,
        "point.toml",
        std::path::Path::new("."),
    )
    .unwrap();
    let img = render(&scene, 5, 5, 1, &|_| {});
    let centre = img.xyz(2, 2).y;
    assert!((centre - 0.125).abs() < 1e-6, "{centre}");
    // Pixel (4, 2) sits 1.6 units to the side: r² = 4 + 2.56, cos θ = 2 / r.
    let r2: f64 = 4.0 + 1.6 * 1.6;
    let want = 0.5 * (2.0 / r2.sqrt()) / r2;
    let side = img.xyz(4, 2).y;
    assert!((side - want).abs() < 1e-6, "{side} vs {want}");
}

/// An equirectangular EXR: row 0 is straight up, the last row straight down, and the map's mean lights a
/// Lambertian surface; an image that is not twice as wide as high, or not HDR, is refused.
#[test]
fn equirect_environment_orientation_and_refusals() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (32u32, 16u32);
    let img = image::Rgb32FImage::from_fn(w, h, |_, y| {
        let v = if y < h / 2 { 2.0 } else { 0.5 };
        image::Rgb([v, v, v])
    });
    img.save(dir.path().join("sky.exr")).unwrap();
    image::Rgb32FImage::from_fn(16, 16, |_, _| image::Rgb([1.0, 1.0, 1.0]))
        .save(dir.path().join("square.exr"))
        .unwrap();
    let text = |file: &str| {
        format!("[camera]\nposition = [0, 0, 5]\n[environment]\nkind = \"map\"\nfile = \"{file}\"\nintensity = 1\n")
    };
    let scene = parse_scene(&text("sky.exr"), "env.toml", dir.path()).unwrap();
    let up = scene.environment.radiance([0.0, 1.0, 0.0]);
    let down = scene.environment.radiance([0.0, -1.0, 0.0]);
    assert!((up[0] - 2.0).abs() < 1e-6 && (down[0] - 0.5).abs() < 1e-6, "{up:?} {down:?}");
    // Upper and lower hemispheres weigh the same: mean (2 + 0.5) / 2.
    let mean = scene.environment.mean();
    assert!((mean[1] - 1.25).abs() < 0.01, "{mean:?}");
    let e = parse_scene(&text("square.exr"), "env.toml", dir.path()).unwrap_err().to_string();
    assert!(e.contains("env.toml:3:") && e.contains("twice as wide"), "{e}");
    let e = parse_scene(&text("sky.png"), "env.toml", dir.path()).unwrap_err().to_string();
    assert!(e.contains("linear HDR"), "{e}");
}
