//! The integration tests of iridis-lab: one module a file, one test binary (README, "Tests").

mod bench;
mod common;
mod models;
mod variants;
