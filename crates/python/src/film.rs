//! `iridis.thinfilm.fit` and `iridis.thinfilm.profile`: the library functions `iridis thinfilm fit` and
//! `iridis thinfilm profile` call (`iridis_api::film_fit::fit_file` and `fit_arrays`,
//! `iridis_thinfilm::depth::depth_profile`), with the CLI's messages as `ValueError` (`OSError` for a file that
//! cannot be read).

use std::path::Path;

use iridis_api::film::GridGiven;
use iridis_api::film_fit;
use iridis_thinfilm::color::Polarization;
use iridis_thinfilm::depth::depth_profile;
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;
use crate::facade::{json_to_py, run};

/// The depth profile (as `iridis thinfilm profile --json`).
#[pyfunction]
#[pyo3(signature = (stack, wavelength_nm, angle_rad, polarization, points, window=None))]
fn _profile<'py>(
    py: Python<'py>,
    stack: PyRef<'py, crate::thinfilm::PyStack>,
    wavelength_nm: f64,
    angle_rad: f64,
    polarization: &str,
    points: usize,
    window: Option<(f64, f64)>,
) -> PyResult<Bound<'py, PyDict>> {
    let pol: Polarization = polarization.parse().map_err(value_error)?;
    let s = stack.stack.clone();
    let d =
        py.allow_threads(|| depth_profile(&s, wavelength_nm, angle_rad, pol, points, window)).map_err(value_error)?;
    let out = PyDict::new(py);
    out.set_item("stack", s.to_string())?;
    out.set_item("R", d.r)?;
    out.set_item("T", d.t)?;
    out.set_item("layers", d.layer_names)?;
    out.set_item("A_layers", PyArray1::from_vec(py, d.layers))?;
    out.set_item("A_substrate", d.substrate)?;
    out.set_item("balance", d.balance)?;
    out.set_item("depth_nm", d.depth_nm)?;
    out.set_item("z_nm", PyArray1::from_vec(py, d.z_nm))?;
    out.set_item("medium", PyArray1::from_vec(py, d.medium.iter().map(|&m| m as i64).collect()))?;
    out.set_item("E2", PyArray1::from_vec(py, d.e2))?;
    out.set_item("absorption_per_nm", PyArray1::from_vec(py, d.absorption_per_nm))?;
    out.set_item("flux", PyArray1::from_vec(py, d.flux))?;
    out.set_item("notes", d.notes)?;
    out.set_item("warnings", d.warnings)?;
    Ok(out)
}

/// The fit (as `iridis thinfilm fit --json`, arrays as NumPy arrays): of a file (`path`, read as the CLI reads it)
/// or of arrays (`wavelengths`, `values`, `sigma_values`), by the library calls `fit_file` and `fit_arrays`; their
/// warnings as Python warnings.
#[pyfunction]
#[pyo3(signature = (stack, angle_rad, quantity, grid, path=None, wavelengths=None, values=None, sigma_values=None,
    **options))]
fn _fit<'py>(
    py: Python<'py>,
    stack: &str,
    angle_rad: f64,
    quantity: &str,
    grid: usize,
    path: Option<String>,
    wavelengths: Option<PyReadonlyArray1<'py, f64>>,
    values: Option<PyReadonlyArray1<'py, f64>>,
    sigma_values: Option<PyReadonlyArray1<'py, f64>>,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    // The reading keywords (`columns`, `percent`, `from_nm`, `to_nm`, `sigma`, `weights`) as the CLI's.
    let request = crate::film_commands::fit_request(stack, angle_rad, quantity, grid, options)?;
    let f = match (path, wavelengths, values) {
        (Some(p), None, None) if sigma_values.is_none() => {
            run(py, |report| film_fit::fit_file(Path::new(&p), &request, report))?
        }
        (None, Some(w), Some(v)) => {
            let (w, v) = (w.as_array().to_vec(), v.as_array().to_vec());
            let s = sigma_values.map(|s| s.as_array().to_vec());
            run(py, |report| film_fit::fit_arrays(w, v, s, &request, report))?
        }
        _ => return Err(value_error("give the measured spectrum as a file path, or as wavelengths and values")),
    };
    let d = json_to_py(py, &f.to_json())?;
    // The arrays as NumPy arrays (a null, a σ the covariance could not give, as NaN).
    let numpy = py.import("numpy")?;
    for key in ["values", "sigma", "correlation", "fitted", "wavelength_nm", "measured"] {
        d.set_item(key, numpy.call_method1("asarray", (d.get_item(key)?, "float64"))?)?;
    }
    Ok(d)
}

/// Refuses a colour grid that would give a colour of nothing and warns of a partial band, as `thinfilm color`
/// does (`iridis_api::film::check_colour_grid`): `Stack.color` took 300–380 nm and printed a* 485.
#[pyfunction]
fn _check_colour_grid(py: Python<'_>, grid_nm: Vec<f64>) -> PyResult<()> {
    run(py, |r| iridis_api::film::check_colour_grid(&grid_nm, GridGiven::List("grid_nm"), r))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(m, [_profile, _fit, _check_colour_grid]);
    Ok(())
}
