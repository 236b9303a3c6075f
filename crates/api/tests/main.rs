//! The integration tests of iridis-api: one module a file, one test binary (README, "Tests").

mod grating_fixtures;
mod table1;
mod vision_directions;
