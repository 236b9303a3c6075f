//! The integration tests of iridis-gpu: one module a file, one test binary (README, "Tests").
//! The files share one device (`common::gpu`) and take turns with scenes (`common::one_scene_at_a_time`).

mod common;
mod diffraction_gpu;
mod extended_gpu;
#[path = "../../render/tests/furnace/mod.rs"]
mod furnace;
#[path = "../../render/tests/gltf_fixtures/mod.rs"]
mod gltf_fixtures;
mod gpu_vs_cpu;
mod scenes_gpu_vs_cpu;
mod unit_scene;
mod white_furnace_gpu;
