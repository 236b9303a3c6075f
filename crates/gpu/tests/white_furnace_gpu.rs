//! The white furnace on the GPU: the CPU test's scenes (`crates/render/tests/furnace/mod.rs`) rendered by
//! `scene.wgsl`, at unit scale and shrunk or grown 1000×, must show radiance 1 over the whole sphere.
//!
//! Needs a Vulkan adapter (lavapipe on machines without a GPU); `IRIDIS_SKIP_GPU=1` skips.

mod common;
#[path = "../../render/tests/furnace/mod.rs"]
mod furnace;

use common::gpu;
use furnace::{deviation, furnace_scene, MATERIALS};
use iridis_gpu::GpuScene;

#[test]
fn every_material_passes_the_white_furnace_on_the_gpu_at_every_scale() {
    let Some(gpu) = gpu() else { return };
    let mut failures = Vec::new();
    for (name, mat) in MATERIALS {
        for scale in [1.0, 1e-3, 1e3] {
            let scene = furnace_scene(mat, scale);
            let g = GpuScene::new(&gpu, &scene).unwrap_or_else(|e| panic!("{name}: {e}"));
            let img = g.render(41, 41, 1, &|_| {}).unwrap();
            let (worst, n) = deviation(&img);
            eprintln!("{name:<32} ×{scale:<6} {n} pixels, largest |L − 1| = {worst:.2e}");
            assert!(n > 1000, "{name}: the sphere covers {n} pixels");
            // f32 arithmetic and the f32 energy table: a few 1e-4.
            if worst > 3e-3 {
                failures.push(format!("{name} ×{scale}: |L − 1| up to {worst:.4}"));
            }
            assert_eq!(g.stack_overflow(), None, "{name}");
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
