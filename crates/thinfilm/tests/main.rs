//! The integration tests of iridis-thinfilm: one module a file, one test binary (README, "Tests").

mod against_references;
mod common;
mod derivatives;
mod dispersion_formulas;
mod film_path_study;
mod film_tables;
mod incoherent_and_fields;
mod rough_tables;
mod spectral_sampling;
mod tmm_convention;
