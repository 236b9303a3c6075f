//! Every integration test of this crate in one binary: one link instead of one per file, one process
//! (GPU tests share one device), the files' tests run side by side on libtest's threads. Each file is
//! a module and keeps its own doc comment; `cargo test -p CRATE --test integration FILE::` runs one.

mod aperture;
mod common;
mod energy;
mod f32_lookup;
mod lattice_encoding;
mod physics;
mod provenance;
mod table_io;
