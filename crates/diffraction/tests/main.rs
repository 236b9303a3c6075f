//! The integration tests of iridis-diffraction: one module a file, one test binary (README, "Tests").

mod aperture;
mod common;
mod energy;
mod f32_lookup;
mod lattice_encoding;
mod physics;
mod provenance;
mod table_io;
