//! The integration tests of iridis-lab: one module a file, one test binary (README, "Tests").

mod bench;
mod common;
mod models;
mod unit_analysis;
mod unit_compare;
mod unit_laser;
mod unit_stam;
mod variants;
