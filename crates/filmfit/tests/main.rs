//! The integration tests of iridis-filmfit: one module a file, one test binary (README, "Tests").

mod against_scipy;
mod jacobian;
mod synthetic;
mod unit_data;
mod unit_template;
