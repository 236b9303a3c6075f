//! The integration tests of iridis-diffraction: one module a file, one test binary (README, "Tests").

mod aperture;
mod common;
mod energy;
mod f32_lookup;
mod lattice_encoding;
mod physics;
mod provenance;
mod table_io;
mod unit_encoding;
mod unit_evaluator;
mod unit_geometry;
mod unit_grating;
mod unit_point;
mod unit_taylor;
