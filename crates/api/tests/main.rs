//! The integration tests of iridis-api: one module a file, one test binary (README, "Tests").

mod grating_fixtures;
mod table1;
mod unit_bench;
mod unit_brdf_map;
mod unit_film;
mod unit_film_fit;
mod unit_fresnel;
mod unit_grating;
mod unit_grating_bench;
mod unit_model;
mod unit_output;
mod unit_report;
mod unit_rigorous_brdf;
mod unit_scene;
mod unit_surface;
mod unit_unit_cell;
mod vision_directions;
