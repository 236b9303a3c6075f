//! Every integration test of this crate in one binary: one link instead of one per file, one process
//! (GPU tests share one device), the files' tests run side by side on libtest's threads. Each file is
//! a module and keeps its own doc comment; `cargo test -p CRATE --test integration FILE::` runs one.

mod common;
mod diffraction_gpu;
mod extended_gpu;
#[path = "../../render/tests/furnace/mod.rs"]
mod furnace;
#[path = "../../render/tests/gltf_fixtures/mod.rs"]
mod gltf_fixtures;
mod gpu_vs_cpu;
mod scenes_gpu_vs_cpu;
mod white_furnace_gpu;
