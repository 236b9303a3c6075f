//! The white furnace on the GPU: the CPU test's materials (`crates/render/tests/furnace/mod.rs`), each on its
//! own sphere of one grid scene, rendered by `scene.wgsl` at unit scale and shrunk or grown 1000×, must show
//! radiance 1 over every sphere.
//!
//! Needs a Vulkan adapter (lavapipe on machines without a GPU); `IRIDIS_SKIP_GPU=1` skips.

mod common;
#[path = "../../render/tests/furnace/mod.rs"]
mod furnace;

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
        let g = GpuScene::new(&gpu, &scene).unwrap();
        let img = g.render(GRID_COLS as u32 * k, rows * k, 1, &|_| {}).unwrap();
        assert_eq!(g.stack_overflow(), None);
        for ((name, _), (worst, n)) in MATERIALS.iter().zip(grid_deviation(&img)) {
            eprintln!("{name:<32} ×{scale:<6} {n} pixels, largest |L − 1| = {worst:.2e}");
            assert!(n > 200, "{name}: the sphere covers {n} pixels");
            // f32 arithmetic and the f32 energy table: a few 1e-4.
            if worst > 3e-3 {
                failures.push(format!("{name} ×{scale}: |L − 1| up to {worst:.4}"));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
