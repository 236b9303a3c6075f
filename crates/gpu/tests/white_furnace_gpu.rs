//! The white furnace on the GPU: the CPU test's materials (`crates/render/tests/furnace/mod.rs`), each on its
//! own sphere of one grid scene, rendered by `scene.wgsl` at unit scale and shrunk or grown 1000×, must show
//! radiance 1 over every sphere.
//!
//! Needs a Vulkan adapter (lavapipe on machines without a GPU); `IRIDIS_SKIP_GPU=1` skips.

use crate::common;
use crate::furnace;

use common::gpu;
use furnace::{furnace_grid, grid_deviation, GRID_COLS, MATERIALS};
use iridis_gpu::GpuScene;

#[test]
fn every_material_passes_the_white_furnace_on_the_gpu_at_every_scale() {
    let Some(gpu) = gpu() else { return };
    let rows = MATERIALS.len().div_ceil(GRID_COLS) as u32;
    let k = 24;
    let mut failures = Vec::new();
    for scale in [1.0, 1e-3, 1e3] {
        let scene = furnace_grid(scale);
        let g = GpuScene::new(gpu, &scene).unwrap();
        let img = g.render(GRID_COLS as u32 * k, rows * k, 1, &|_| {}).unwrap();
        assert_eq!(g.stack_overflow(), None);
        for ((name, _), result) in MATERIALS.iter().zip(grid_deviation(&img)) {
            // f32 arithmetic and the f32 energy table: a few 1e-4.
            furnace::tally(&mut failures, &format!("{name} ×{scale}"), result, 200, 3e-3);
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Rough films in the GPU's furnace (the CPU test `rough_films_in_the_furnace_reflect_their_albedo`): at the
/// centre of the sphere (normal view) the luminance must be the film's reflected fraction `k_r + ∫ k_d cos θ dω`,
/// the directional albedo at normal incidence that `RoughStack::albedo` integrates on a dense 60 × 120 grid —
/// here from the LSRS colour tables (`k_r`) and the diffuse albedo table; and no pixel may exceed radiance 1.
#[test]
fn rough_films_in_the_gpu_furnace_reflect_their_albedo() {
    let Some(gpu) = gpu() else { return };
    for (stack, sigma, tau) in furnace::ROUGH_FILMS {
        let scene = furnace::rough_film_furnace(stack, sigma, tau);
        let img = GpuScene::new(gpu, &scene).unwrap().render(21, 21, 1, &|_| {}).unwrap();
        furnace::assert_rough_film_reflects_its_albedo(&scene, &img, stack, "GPU");
    }
}

/// The energy-blend diffraction material (issue 21; the CPU test `diffraction_with_the_energy_blend_passes_the_
/// scene_furnace`) in the GPU's furnace: the fast path within the CPU's bounds (the environment's 64-cell
/// quadrature of the lobe) and within f32 of the CPU's image, and Monte Carlo at radiance 1 on average over the
/// sphere within its noise.
#[test]
fn diffraction_with_the_energy_blend_in_the_gpu_furnace() {
    use furnace::{
        deviation, energy_diffraction, energy_diffraction_furnace, mean_and_se, monte_carlo, sphere_pixels,
        worst_within, FAST_DIFFRACTION_FURNACE, FAST_DIFFRACTION_FURNACE_RIM,
    };
    use iridis_render::integrate::Strategy;
    let Some(gpu) = gpu() else { return };
    let size = 41;
    let (material, _) = energy_diffraction();
    let scene = energy_diffraction_furnace(&material, 1.0);
    let img = GpuScene::new(gpu, &scene).unwrap().render(size, size, 1, &|_| {}).unwrap();
    let cpu = iridis_render::render(&scene, size, size, 1, &|_| {});
    let (worst, n) = deviation(&img);
    let within_45 = worst_within(&img, 45.0);
    let apart = img
        .data
        .iter()
        .zip(&cpu.data)
        .flat_map(|(g, c)| (0..3).map(move |k| (g[k] - c[k]).abs()))
        .fold(0.0f32, f32::max);
    eprintln!("GPU fast path: {n} pixels, |L − 1| ≤ {worst:.2e} ({within_45:.2e} within 45°), GPU − CPU ≤ {apart:.2e}");
    assert!(within_45 < FAST_DIFFRACTION_FURNACE && worst < FAST_DIFFRACTION_FURNACE_RIM, "{within_45} / {worst}");
    assert!(apart < 2e-3, "GPU and CPU images up to {apart} apart");

    let spp = 64;
    let mc = monte_carlo(energy_diffraction_furnace(&material, 1.0), Strategy::Mis);
    let img = GpuScene::new(gpu, &mc).unwrap().render(size, size, spp, &|_| {}).unwrap();
    let on_sphere: Vec<f64> = sphere_pixels(&img).map(|c| (c[0] + c[1] + c[2]) as f64 / 3.0).collect();
    let (mean, se) = mean_and_se(&on_sphere);
    eprintln!("GPU Monte Carlo ({spp} spp): mean {mean:.5} ± {se:.5} over {} pixels", on_sphere.len());
    assert!((mean - 1.0).abs() < 4.0 * se + 1e-3, "Monte Carlo: mean {mean} ± {se}");
}
