//! The white furnace on the CPU: every material kind that absorbs nothing, alone inside a uniform environment
//! of radiance 1, must show radiance 1 everywhere on the sphere (issue 21: the dielectric microfacet reached
//! 1.61 at the rim, its diffuse lobe ignoring the Fresnel that the specular took).

use crate::furnace;

use furnace::{
    deviation, furnace_grid, furnace_scene, grid_deviation, sphere_pixels, worst_within, FAST_DIFFRACTION_FURNACE,
    FAST_DIFFRACTION_FURNACE_RIM, GRID_COLS, MATERIALS,
};
use iridis_render::render;

#[test]
fn every_material_passes_the_white_furnace_on_the_cpu() {
    let mut failures = Vec::new();
    for (name, mat) in MATERIALS {
        let scene = furnace_scene(mat, 1.0);
        let img = render(&scene, 41, 41, 1, &|_| {});
        furnace::tally(&mut failures, name, deviation(&img), 1000, 2e-3);
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn the_furnace_grid_holds_on_the_cpu_too() {
    // The GPU test's one-scene grid (spheres that see each other), on the CPU at 10⁻³ scale.
    let rows = MATERIALS.len().div_ceil(GRID_COLS) as u32;
    let img = render(&furnace_grid(1e-3), GRID_COLS as u32 * 24, rows * 24, 1, &|_| {});
    for ((name, _), (worst, n)) in MATERIALS.iter().zip(grid_deviation(&img)) {
        assert!(n > 200 && worst < 2e-3, "{name}: {n} pixels, |L − 1| up to {worst}");
    }
}

/// Rough films in the furnace: their diffuse lobe is lit by the environment (as directional lights) as well
/// as by lights, and their specular part follows the mirror ray. At the centre of the sphere (normal view) the
/// luminance must be the film's reflected fraction `k_r + ∫ k_d cos θ dω` — by reciprocity the directional
/// albedo at normal incidence, which `RoughStack::albedo` integrates on a dense 60 × 120 grid, weighted by
/// D65 × ȳ — to the 64-direction quadrature's accuracy; and no pixel may exceed radiance 1 beyond it.
#[test]
fn rough_films_in_the_furnace_reflect_their_albedo() {
    for (stack, sigma, tau) in furnace::ROUGH_FILMS {
        let scene = furnace::rough_film_furnace(stack, sigma, tau);
        let img = render(&scene, 21, 21, 1, &|_| {});
        furnace::assert_rough_film_reflects_its_albedo(&scene, &img, stack, "CPU");
    }
}

/// Diffraction under the energy-conserving blend (issue 21): a radiometric table of a rough nanostructure with a
/// wide lobe (3.2 µm coherence, so a direction grid resolves it), a white texture under it. In a uniform white
/// environment the light reflected into ω_o — the lobe plus the texture's share, integrated over ω_i on a dense
/// (θ, φ) grid, independently of the u-v quadrature behind the albedo table — must be 1; and the lobe alone
/// (no texture) must reflect at most 1.
#[test]
fn diffraction_with_the_energy_blend_passes_the_furnace() {
    use iridis_render::material::Diffraction;

    let (material, albedo) = furnace::energy_diffraction();
    let hit = furnace::flat_hit();
    // ∫ L cos θ_i dω_i for radiance 1: each cell a directional light of irradiance dω/π (the lights' unit E/π).
    let furnace = |m: &Diffraction, wo: [f64; 3], tex: f64| {
        let (nt, np) = (300, 600);
        let mut acc = [0.0; 3];
        for i in 0..nt {
            let theta = (i as f64 + 0.5) / nt as f64 * std::f64::consts::FRAC_PI_2;
            let d_omega = theta.sin() * (std::f64::consts::FRAC_PI_2 / nt as f64) * (std::f64::consts::TAU / np as f64);
            for j in 0..np {
                let phi = (j as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
                let wi = [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()];
                let e = d_omega / std::f64::consts::PI;
                let c = m.shade_light(&hit, [1.0, 0.0, 0.0], wi, wo, [e; 3], [tex; 3]);
                for k in 0..3 {
                    acc[k] += c[k];
                }
            }
        }
        acc
    };
    let mut worst = 0.0f64;
    for (theta, phi) in [(0.0f64, 0.0f64), (25.0, 0.4), (50.0, 2.0), (70.0, 4.0)] {
        let (t, p) = (theta.to_radians(), phi);
        let wo = [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()];
        let (l, lobe) = (furnace(&material, wo, 1.0), furnace(&material, wo, 0.0));
        eprintln!(
            "θ_o = {theta}°: lobe alone {lobe:.4?}, lobe + white texture {l:.4?}, A_avg {:.4?}",
            albedo.average()
        );
        for k in 0..3 {
            assert!(lobe[k] <= 1.0 && lobe[k] > 0.01, "θ_o = {theta}°: the lobe reflects {lobe:?}");
            worst = worst.max((l[k] - 1.0).abs());
        }
    }
    // The albedo table's interpolation (10 × 16 nodes) against the dense grid's integral of the same lobe.
    assert!(worst < 0.01, "|L − 1| up to {worst}");
}

/// The same material on the furnace's sphere, as a scene (issue 21): the fast path lights the lobe through the
/// environment's 64 cells (each the lobe averaged over its solid angle) and the texture through the irradiance
/// around the normal, `(1 − A(ω_o))` of it; Monte Carlo samples the lobe and the cosine lobe. Both must give
/// radiance 1 over the sphere: the fast path to its quadrature's accuracy at every pixel, Monte Carlo on average
/// over the sphere within its noise.
#[test]
fn diffraction_with_the_energy_blend_passes_the_scene_furnace() {
    use iridis_render::integrate::Strategy;
    let size = 41;
    let (material, _) = furnace::energy_diffraction();
    let fast = render(&furnace::energy_diffraction_furnace(&material, 1.0), size, size, 1, &|_| {});
    let (worst, n) = deviation(&fast);
    let within_45 = worst_within(&fast, 45.0);
    eprintln!("fast path: {n} pixels, largest |L − 1| = {worst:.2e}, within 45° of the view {within_45:.2e}");
    assert!(n > 1000, "{n} pixels on the sphere");
    assert!(within_45 < FAST_DIFFRACTION_FURNACE, "fast path: |L − 1| up to {within_45} within 45°");
    assert!(worst < FAST_DIFFRACTION_FURNACE_RIM, "fast path: |L − 1| up to {worst} at the rim");

    let spp = 64;
    let scene = furnace::monte_carlo(furnace::energy_diffraction_furnace(&material, 1.0), Strategy::Mis);
    let mc = render(&scene, size, size, spp, &|_| {});
    let on_sphere: Vec<f64> = sphere_pixels(&mc).map(|c| (c[0] + c[1] + c[2]) as f64 / 3.0).collect();
    let (mean, se) = furnace::mean_and_se(&on_sphere);
    eprintln!("Monte Carlo ({spp} spp): mean {mean:.5} ± {se:.5} over {} pixels", on_sphere.len());
    assert!((mean - 1.0).abs() < 4.0 * se + 1e-3, "Monte Carlo: mean {mean} ± {se}");
}

/// The energy blend keeps the BRDF reciprocal: the lobe is (radiometric table), and the texture's share
/// `(1 − A(ω_i))(1 − A(ω_o))/(1 − A_avg)` is symmetric in its two directions, so `f(ω_i, ω_o) = f(ω_o, ω_i)` for the
/// whole material (`π f cos θ_i` is what `shade_light` returns for a light of unit irradiance).
#[test]
fn the_energy_blend_is_reciprocal() {
    let (material, _) = furnace::energy_diffraction();
    let hit = furnace::flat_hit();
    let dir = |t: f64, p: f64| [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()];
    let f = |wi: [f64; 3], wo: [f64; 3]| {
        material.shade_light(&hit, [1.0, 0.0, 0.0], wi, wo, [1.0; 3], [1.0; 3]).map(|c| c / wi[2])
    };
    let mut worst = 0.0f64;
    for (ti, pi, to, po) in [(0.2, 0.0, 0.3, 2.8), (0.5, 0.5, 0.4, 3.5), (0.9, 1.0, 0.75, 4.2), (1.2, 2.0, 0.1, 0.3)] {
        let (wi, wo) = (dir(ti, pi), dir(to, po));
        let (a, b) = (f(wi, wo), f(wo, wi));
        for k in 0..3 {
            worst = worst.max((a[k] - b[k]).abs() / a[k].abs().max(1e-12));
        }
    }
    eprintln!("energy blend: largest relative |f(ω_i, ω_o) − f(ω_o, ω_i)| = {worst:.1e}");
    assert!(worst < 1e-6, "relative {worst}");
}
