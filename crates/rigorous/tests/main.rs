//! The integration tests of iridis-rigorous: one module a file, one test binary (README, "Tests").

mod references;
mod unit_lib;
mod unit_surface;
