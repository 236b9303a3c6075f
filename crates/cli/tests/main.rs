//! The integration tests of iridis: one module a file, one test binary (README, "Tests").

mod absurd_input_cli;
mod brdf_cli;
mod color_cli;
mod common;
mod consistency_cli;
mod demo_cli;
mod gpu_cli;
mod help_cli;
mod json_doc_cli;
mod lab_cli;
mod output_cli;
mod render_cli;
mod rough_cli;
mod surface_cli;
mod thinfilm_cli;
mod vision_cli;
