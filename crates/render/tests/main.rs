//! The integration tests of iridis-render: one module a file, one test binary (README, "Tests").

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
