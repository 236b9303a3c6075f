//! Every integration test of this crate in one binary: one link instead of one per file, one process
//! (GPU tests share one device), the files' tests run side by side on libtest's threads. Each file is
//! a module and keeps its own doc comment; `cargo test -p CRATE --test integration FILE::` runs one.

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
