//! The integration tests of iridis-color: one module a file, one test binary (README, "Tests").

mod against_references;
mod lab_default_white;
mod tonemap_resample;
