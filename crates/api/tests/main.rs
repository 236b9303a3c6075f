//! Every integration test of this crate in one binary: one link instead of one per file, one process
//! (GPU tests share one device), the files' tests run side by side on libtest's threads. Each file is
//! a module and keeps its own doc comment; `cargo test -p CRATE --test integration FILE::` runs one.

mod grating_fixtures;
mod table1;
mod vision_directions;
