//! One module per command group.
pub mod bench;
pub mod brdf;
pub mod color;
pub mod demo;
pub mod gpu;
pub mod grating;
pub mod lab;
pub mod render;
pub mod report;
pub mod surface;
pub mod thinfilm;
pub mod vision;
