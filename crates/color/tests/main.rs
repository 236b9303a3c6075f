//! The integration tests of iridis-color: one module a file, one test binary (README, "Tests").

mod against_references;
mod common;
mod lab_default_white;
mod tonemap_resample;
mod unit_cie;
mod unit_convert;
mod unit_integrate;
mod unit_names;
mod unit_spectrum;
mod unit_units;
