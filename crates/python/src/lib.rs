//! # iridis-python
//!
//! The native part of the Python package `iridis` (built with maturin, imported as `iridis._native`): thin
//! bindings of the library crates and of the facade the CLI calls (`iridis-api`) — NumPy arrays in and out,
//! the GIL released while Rust computes, library errors raised as `ValueError` (`OSError` for files) with the
//! library's (and so the CLI's) messages, the facade's warnings as Python warnings. The Python modules in
//! `python/iridis/` give the public names, docstrings and type stubs.

use pyo3::prelude::*;

/// Adds `#[pyfunction]`s to the module `m` (a `register`'s work): `add_functions!(m, [f, g]);`.
macro_rules! add_functions {
    ($m:expr, [$($f:ident),+ $(,)?]) => {
        $($m.add_function(pyo3::wrap_pyfunction!($f, $m)?)?;)+
    };
}

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
    // Each binding module adds its functions and classes.
    let registers = [
        facade::register,
        tmm::register,
        color::register,
        thinfilm::register,
        film::register,
        film_commands::register,
        surface::register,
        diffraction::register,
        render::register,
        lab::register,
        scan_report::register,
        vision::register,
        bench::register,
        brdf::register,
    ];
    for register in registers {
        register(m)?;
    }
    Ok(())
}
