//! The integration tests of iridis-plot: one module a file, one test binary (README, "Tests").

mod unit_lib;
