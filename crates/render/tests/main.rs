//! Every integration test of this crate in one binary: one link instead of one per file, one process
//! (GPU tests share one device), the files' tests run side by side on libtest's threads. Each file is
//! a module and keeps its own doc comment; `cargo test -p CRATE --test integration FILE::` runs one.

mod algorithm4;
mod common;
mod examples;
mod extended_light;
mod file_formats;
mod furnace;
mod gltf_fixtures;
mod gltf_iridescence;
mod iridescence_spec;
mod laser;
mod lights_and_environment;
mod snake_scenes;
mod white_furnace;
