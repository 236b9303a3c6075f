//! The integration tests of iridis-vision: one module a file, one test binary (README, "Tests").

mod against_numpy;
mod unit_light;
mod unit_model;
mod unit_space;
mod unit_spec;
mod unit_system;
mod unit_table;
mod unit_template;
