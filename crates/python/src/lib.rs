//! # iridis-python
//!
//! The native part of the Python package `iridis` (built with maturin, imported as `iridis._native`): thin
//! bindings of the library crates and of the facade the CLI calls (`iridis-api`) — NumPy arrays in and out,
//! the GIL released while Rust computes, library errors raised as `ValueError` (`OSError` for files) with the
//! library's (and so the CLI's) messages, the facade's warnings as Python warnings. The Python modules in
//! `python/iridis/` give the public names, docstrings and type stubs.

use pyo3::prelude::*;

mod args;
mod bench;
mod brdf;
mod color;
mod diffraction;
mod facade;
mod film;
mod film_commands;
mod lab;
mod render;
mod scan_report;
mod surface;
mod thinfilm;
mod tmm;
mod vision;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    tmm::register(m)?;
    color::register(m)?;
    thinfilm::register(m)?;
    film::register(m)?;
    film_commands::register(m)?;
    surface::register(m)?;
    diffraction::register(m)?;
    render::register(m)?;
    lab::register(m)?;
    scan_report::register(m)?;
    vision::register(m)?;
    bench::register(m)?;
    brdf::register(m)?;
    Ok(())
}
