//! Light units and the equirectangular environment, through scene files.

use crate::common;

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
    common::two_tone_sky(false).save(dir.path().join("sky.exr")).unwrap();
    image::Rgb32FImage::from_fn(16, 16, |_, _| image::Rgb([1.0, 1.0, 1.0]))
        .save(dir.path().join("square.exr"))
        .unwrap();
    let load = |file: &str| parse_scene(&common::environment_map_scene(file), "env.toml", dir.path());
    let scene = load("sky.exr").unwrap();
    let up = scene.environment.radiance([0.0, 1.0, 0.0]);
    let down = scene.environment.radiance([0.0, -1.0, 0.0]);
    assert!((up[0] - 2.0).abs() < 1e-6 && (down[0] - 0.5).abs() < 1e-6, "{up:?} {down:?}");
    // Upper and lower hemispheres weigh the same: mean (2 + 0.5) / 2.
    let mean = scene.environment.mean();
    assert!((mean[1] - 1.25).abs() < 0.01, "{mean:?}");
    let e = load("square.exr").unwrap_err().to_string();
    assert!(e.contains("env.toml:3:") && e.contains("twice as wide"), "{e}");
    let e = load("sky.png").unwrap_err().to_string();
    assert!(e.contains("linear HDR"), "{e}");
}

/// The environment as directional lights (for diffraction and rough films), in the lights' unit `E/π`: they
/// add up to the environment's power `∫ L dω / π` (4 for a uniform radiance 1), and as a quadrature of a
/// Lambertian surface's reflected radiance `∫ L cos θ dω / π` they give the closed form 1 for a uniform
/// environment, and the irradiance map's value for a sky, at every normal.
#[test]
fn environment_lights_integrate_a_lambertian_surface() {
    use iridis_render::light::{Environment, ENVIRONMENT_LIGHTS};
    let uniform = Environment::Uniform([1.0, 1.0, 1.0]).as_lights();
    assert_eq!(uniform.len(), ENVIRONMENT_LIGHTS);
    let power: f64 = uniform.iter().map(|(_, e)| e[0]).sum();
    assert!((power - 4.0).abs() < 1e-9, "Σ e = {power}");
    assert!(Environment::None.as_lights().is_empty());
    let sky = Environment::Sky { zenith: [0.2, 0.4, 0.9], horizon: [0.9, 0.9, 0.9], ground: [0.1, 0.1, 0.1] };
    let (sky_lights, map) = (sky.as_lights(), sky.irradiance_map());
    let lambert = |lights: &[([f64; 3], [f64; 3])], n: [f64; 3], c: usize| -> f64 {
        lights.iter().map(|(d, e)| e[c] * (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]).max(0.0)).sum::<f64>()
    };
    let (mut worst_uniform, mut worst_sky) = (0.0f64, 0.0f64);
    for i in 0..40 {
        // Normals spread over the sphere (a spiral), none on a quadrature direction by construction.
        let y = 1.0 - (2 * i + 1) as f64 / 40.0;
        let (r, phi) = ((1.0 - y * y).sqrt(), 2.1 * i as f64 + 0.3);
        let n = [r * phi.cos(), y, r * phi.sin()];
        worst_uniform = worst_uniform.max((lambert(&uniform, n, 0) - 1.0).abs());
        let expect = sky.irradiance(map.as_ref(), n);
        for c in 0..3 {
            worst_sky = worst_sky.max((lambert(&sky_lights, n, c) - expect[c]).abs() / expect[c]);
        }
    }
    eprintln!("64-direction quadrature: uniform |err| ≤ {worst_uniform:.4}, sky relative ≤ {worst_sky:.4}");
    assert!(worst_uniform < 0.03, "uniform environment: Lambertian radiance off by {worst_uniform}");
    assert!(worst_sky < 0.05, "sky: off the irradiance map by {worst_sky}");
}

/// A rough film shades from the LSRS colour tables the GPU uploads (`ThinFilm::rough_table`), not from the HTSG
/// series at 81 wavelengths for every light at every hit (issue 32: `rough_film.toml` at 320 × 240 took 53 s of
/// CPU that way, 10 s with the tables). Head-on view, light at 40° (between the 39° and 42° nodes): the pixel is
/// the table's interpolated `π k_d cos θ_l` (to the XYZ → RGB round trip, 1e-7), which differs measurably from
/// the direct evaluation.
#[test]
fn rough_films_shade_from_the_colour_tables_the_gpu_uses() {
    use iridis_render::material::Material;
    let (tl, az) = (40f64.to_radians(), 25f64.to_radians());
    let text = format!(
        "[camera]\nkind = \"orthographic\"\nposition = [0, 0, 10]\nlook_at = [0, 0, 0]\nup = [0, 1, 0]\nheight = 2\n\
         [[light]]\nkind = \"directional\"\ndirection = [{}, {}, {}]\nintensity = 1\n\
         [materials.film]\nkind = \"thinfilm\"\nstack = \"air | water 348nm | Si\"\nroughness = \"25nm\"\n\
         correlation = \"300nm\"\n[[object]]\nkind = \"plane\"\nnormal = [0, 0, 1]\ntangent = [1, 0, 0]\n\
         material = \"film\"\n",
        tl.sin() * az.cos(),
        tl.sin() * az.sin(),
        tl.cos()
    );
    let scene = parse_scene(&text, "rough.toml", std::path::Path::new(".")).unwrap();
    let Material::ThinFilm(f) = &scene.materials[0] else { panic!("not a film") };
    let got = render(&scene, 3, 3, 1, &|_| {}).xyz(1, 1);
    // Seen head-on the azimuth of the light relative to the view is immaterial (π by convention).
    let tables = f.rough_table().expect("a rough film has tables").expect("its tables can be made");
    let table = tables.diffuse_at(1.0, tl.cos(), std::f64::consts::PI, 0.0);
    let (_, direct) = f.rough_colors(1.0, 0.0, &[(tl.cos(), std::f64::consts::PI)]).unwrap();
    let k = tl.cos();
    for (g, (t, d)) in got.to_array().iter().zip(table.to_array().iter().zip(direct[0].to_array())) {
        assert!((g - t * k).abs() < 1e-7 * (t * k), "pixel {g} vs table {}", t * k);
        assert!((g - d * k).abs() > 1e-5 * (d * k), "the table and the direct evaluation should differ at 40°");
    }
}

/// A diffraction sphere under a smooth sky, lit by the environment alone. The fast path takes the sky as 64
/// directional lights, each the lobe averaged over a square of solid angle around it; with squares the size of
/// the light's own cell (before issue 32) a narrow lobe reflected each cell as a flat patch with hard edges —
/// the "blocky" sphere — while the true image (Monte Carlo, sampling the sky) is smooth. Measured as the mean
/// jump between neighbouring pixels across the sphere relative to its mean luminance, against the same on the
/// Monte Carlo image blurred to take out its noise.
#[test]
fn a_diffraction_sphere_under_a_sky_is_not_blocky() {
    let text = |integration: &str| {
        format!(
            "[output]\nintegration = \"{integration}\"\n[camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\n\
             fov = \"32deg\"\n[environment]\nkind = \"sky\"\nzenith = [0.2, 0.35, 0.8]\nhorizon = [0.9, 0.9, 0.95]\n\
             ground = [0.15, 0.12, 0.1]\n[materials.skin]\nkind = \"diffraction\"\ntable = \"builtin:elaphe\"\n\
             uv_resolution = 101\nscale_ru = 3000\nw_diffuse = 0\n[[object]]\nkind = \"sphere\"\n\
             center = [0, 0, 0]\nradius = 1\nmaterial = \"skin\"\n"
        )
    };
    let n = 64u32;
    let lum = |integration: &str, spp: u32| -> Vec<f64> {
        let scene = parse_scene(&text(integration), "sky.toml", std::path::Path::new(".")).unwrap();
        let img = render(&scene, n, n, spp, &|_| {});
        (0..n * n).map(|k| img.xyz(k % n, k / n).y).collect()
    };
    // Pixels well inside the sphere's disk (radius ≈ 0.89 of the half image at fov 32°, distance 4).
    let inside = |c: u32, r: u32| {
        let (x, y) = (c as f64 + 0.5 - n as f64 / 2.0, r as f64 + 0.5 - n as f64 / 2.0);
        x.hypot(y) < 0.7 * n as f64 / 2.0
    };
    // Mean |neighbour difference| (right and down), over the mean luminance.
    let jumps = |l: &[f64]| {
        let (mut s, mut m) = (0.0, 0.0);
        for r in 0..n - 1 {
            for c in 0..n - 1 {
                if inside(c, r) && inside(c + 1, r + 1) {
                    let v = l[(r * n + c) as usize];
                    s += (l[(r * n + c + 1) as usize] - v).abs() + (l[((r + 1) * n + c) as usize] - v).abs();
                    m += v;
                }
            }
        }
        s / 2.0 / m
    };
    let fast = jumps(&lum("fast", 1));
    // The Monte Carlo image at 64 spp, box-blurred 3 × 3 to take out most of its noise.
    let mc = lum("monte-carlo", 64);
    let blurred: Vec<f64> = (0..n * n)
        .map(|k| {
            let (c, r) = ((k % n) as i64, (k / n) as i64);
            let mut s = 0.0;
            for dr in -1..=1 {
                for dc in -1..=1 {
                    let (cc, rr) = ((c + dc).clamp(0, n as i64 - 1), (r + dr).clamp(0, n as i64 - 1));
                    s += mc[(rr * n as i64 + cc) as usize];
                }
            }
            s / 9.0
        })
        .collect();
    let smooth = jumps(&blurred);
    eprintln!("neighbour jumps over the mean: fast {fast:.4}, Monte Carlo (blurred) {smooth:.4}");
    // Measured: fast 0.082 (0.163 with one cell per light, before issue 32), Monte Carlo 0.051.
    assert!(fast < 2.0 * smooth.max(0.002), "fast {fast} vs Monte Carlo {smooth}");
}
