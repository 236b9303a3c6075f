//! The unit tests of src/light.rs, moved here so that `cargo test` compiles the library once.

use iridis_color::Illuminant;
use iridis_render::light::*;
use iridis_render::math::*;
use iridis_render::texture::{TexKind, Texture};

#[test]
fn the_environment_sampler_is_a_density_and_follows_the_sky() {
    use iridis_render::sampling::{next2, seed};
    let sky = Environment::Sky { zenith: [2.0, 2.0, 2.0], horizon: [1.0; 3], ground: [0.1; 3] };
    let s = EnvSampler::new(&sky).unwrap();
    // ∫ pdf dω = 1 on a fine grid, independent of the cells.
    let acc = crate::unit_sampling::sphere_integral(800, 400, |d| s.pdf(d));
    assert!((acc - 1.0).abs() < 1e-3, "∫ pdf = {acc}");
    // Sampled directions report the pdf of pdf(); E[L/pdf] = ∫ L dω (closed form from the mean radiance).
    seed(9, 0);
    let n = 100_000;
    let (mut m, mut m2) = (0.0, 0.0);
    for _ in 0..n {
        let (d, p) = s.sample(next2());
        assert!((p - s.pdf(d)).abs() < 1e-9 * p, "{p} vs {}", s.pdf(d));
        let x = sky.radiance(d)[0] / p;
        m += x;
        m2 += x * x;
    }
    let mean = m / n as f64;
    let se = ((m2 / n as f64 - mean * mean) / n as f64).sqrt();
    let want = 4.0 * std::f64::consts::PI * sky.mean()[0];
    assert!((mean - want).abs() < 4.0 * se + 1e-3 * want, "{mean} ± {se} vs {want}");
    // Importance sampling pays: the relative error is far below uniform sampling's for this sky.
    assert!(se / mean < 0.3 / (n as f64).sqrt(), "relative standard deviation {}", se / mean * (n as f64).sqrt());
}

#[test]
fn d65_tint_is_white_and_a_is_warm() {
    let t = illuminant_tint(Illuminant::D65);
    assert!(t.iter().all(|c| (c - 1.0).abs() < 1e-12));
    let a = illuminant_tint(Illuminant::A);
    assert!(a[0] > 1.0 && a[2] < 0.5, "{a:?}");
}

#[test]
fn equirect_poles_and_centre() {
    assert!(equirect_uv([0.0, 1.0, 0.0], 0.0).1 < 1e-12);
    let (u, v) = equirect_uv([0.0, 0.0, -1.0], 0.0);
    assert!((u - 0.5).abs() < 1e-12 && (v - 0.5).abs() < 1e-12);
    for (u, v) in [(0.1, 0.3), (0.7, 0.8), (0.5, 0.5)] {
        let (a, b) = equirect_uv(equirect_dir(u, v, 0.4), 0.4);
        assert!((a - u).abs() < 1e-12 && (b - v).abs() < 1e-12);
    }
    let uni = Environment::Uniform([0.2, 0.3, 0.4]);
    assert_eq!(uni.mean(), [0.2, 0.3, 0.4]);
}

/// `E(n)/π = ∫ L(ω) max(n·ω, 0) dω / π` (red channel) on an `nt × np` (θ, φ) grid, directly from the
/// environment's radiance — not through the map's cells.
fn brute_force_irradiance(env: &Environment, n: V3, nt: usize, np: usize) -> f64 {
    let mut sum = 0.0;
    for i in 0..nt {
        let th = std::f64::consts::PI * (i as f64 + 0.5) / nt as f64;
        for j in 0..np {
            let ph = std::f64::consts::TAU * (j as f64 + 0.5) / np as f64;
            let d = [th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()];
            let dw = th.sin() * std::f64::consts::PI / nt as f64 * std::f64::consts::TAU / np as f64;
            sum += env.radiance(d)[0] * dot(n, d).max(0.0) * dw / std::f64::consts::PI;
        }
    }
    sum
}

#[test]
fn a_vertical_normal_reads_one_irradiance_whatever_its_azimuth() {
    // An environment bright on one side (+x half of the sphere 1, the other 0.1): the irradiance straight up
    // is the brute-force integral, and normals a hair off vertical (any azimuth, and −0 in z, whose
    // atan2 gives the opposite column) read the same value. Before the map's rows held the poles, these
    // read the first row's texels at the azimuth's column: 1.6 % apart on examples/studio.hdr.
    let (w, h) = (64, 32);
    let data: Vec<f32> = (0..w * h)
        .flat_map(|k| {
            let d = equirect_dir(((k % w) as f64 + 0.5) / w as f64, ((k / w) as f64 + 0.5) / h as f64, 0.0);
            let l = if d[0] > 0.0 { 1.0 } else { 0.1 };
            [l as f32; 3]
        })
        .collect();
    let texture = Texture::Image { width: w, height: h, channels: 3, data, kind: TexKind::Color, name: "half".into() };
    let env = Environment::Map {
        mean: equirect_mean(&texture, 1.0),
        texture: Box::new(texture),
        rotation: 0.0,
        intensity: 1.0,
    };
    let map = env.irradiance_map().unwrap();
    let want = brute_force_irradiance(&env, [0.0, 1.0, 0.0], 600, 600);
    let up = env.irradiance(Some(&map), [0.0, 1.0, 0.0])[0];
    assert!((up - want).abs() < 0.01 * want, "straight up: {up} vs the integral {want}");
    for n in [[0.0, 1.0, -0.0], [1e-4, 1.0, 0.0], [-1e-4, 1.0, 0.0], [0.0, 1.0, 1e-4], [0.0, 1.0, -1e-4]] {
        let got = env.irradiance(Some(&map), n)[0];
        assert!((got - up).abs() < 1e-4 * up, "{n:?}: {got} vs {up} straight up");
    }
}

#[test]
fn irradiance_of_a_sky_matches_a_brute_force_integral() {
    // E(n)/π = ∫ L(ω) max(n·ω, 0) dω / π on a fine (θ, φ) grid, directly from the sky's radiance — not
    // through the map's cells. Two tones: radiance 1 above the horizon, 0.2 below (blended over 7°).
    let sky = Environment::Sky { zenith: [1.0; 3], horizon: [1.0; 3], ground: [0.2; 3] };
    let map = sky.irradiance_map().unwrap();
    for deg in [0.0f64, 30.0, 60.0, 90.0, 120.0, 180.0] {
        let t = deg.to_radians();
        let n = [t.sin(), t.cos(), 0.0];
        let want = brute_force_irradiance(&sky, n, 1000, 400);
        let got = sky.irradiance(Some(&map), n)[0];
        assert!((got - want).abs() < 0.01, "{deg}°: {got} vs {want}");
    }
    // A uniform environment: exactly its radiance, with or without a map.
    let uni = Environment::Sky { zenith: [0.7; 3], horizon: [0.7; 3], ground: [0.7; 3] };
    let m = uni.irradiance_map().unwrap();
    for n in [[0.0, 1.0, 0.0], [0.6, 0.0, 0.8], [0.0, -1.0, 0.0]] {
        assert!((uni.irradiance(Some(&m), n)[1] - 0.7).abs() < 1e-6);
    }
}
