//! The integration tests of iridis-surface: one module a file, one test binary (README, "Tests").

mod afm_instruments;
mod common;
mod robustness;
mod surface;
