//! `iridis.thinfilm.fit` and `iridis.thinfilm.profile`: the library functions `iridis thinfilm fit` and
//! `iridis thinfilm profile` call (`iridis_filmfit::read`, `iridis_filmfit::fit`,
//! `iridis_thinfilm::depth::depth_profile`), with the CLI's messages as `ValueError` (`OSError` for a file that
//! cannot be read).

use std::path::Path;

use iridis_filmfit::{fit, FitOptions, FitResult, Measured, Quantity, Template};
use iridis_thinfilm::color::Polarization;
use iridis_thinfilm::depth::depth_profile;
use numpy::{PyArray1, PyArray2, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;

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
    Ok(out)
}

/// The fit (as `iridis thinfilm fit --json`): from a file (`path`, read like the CLI reads it) or from arrays.
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
) -> PyResult<Bound<'py, PyDict>> {
    // The file-reading keywords (`columns`, `percent`, `from_nm`, `to_nm`, `sigma`, `weights`) as the CLI's.
    let request = crate::film_commands::fit_request(stack, angle_rad, quantity, grid, options)?;
    let q: Quantity = quantity.parse().map_err(value_error)?;
    // A file: read and fitted by the library call of `iridis thinfilm fit` (its warnings as Python warnings).
    if let (Some(p), None, None) = (&path, &wavelengths, &values) {
        let f = crate::facade::run(py, |report| iridis_api::film_fit::fit_file(Path::new(p), &request, report))?;
        let read = (f.reading.notes, f.reading.columns, f.reading.percent);
        return fit_dict(py, stack, angle_rad, &f.template, q, f.reading.data, f.result, f.seconds, read);
    }
    let template = Template::parse(stack).map_err(value_error)?;
    let data = match (&path, &wavelengths, &values) {
        (None, Some(w), Some(v)) => {
            let s = sigma_values.map(|s| s.as_array().to_vec());
            Measured::from_arrays(w.as_array().to_vec(), v.as_array().to_vec(), s, q).map_err(value_error)?
        }
        _ => return Err(value_error("give the measured spectrum as a file path, or as wavelengths and values")),
    };
    let opt = FitOptions { angle_rad, quantity: q, grid, ..FitOptions::default() };
    let t0 = std::time::Instant::now();
    let r = py.allow_threads(|| fit(&template, &data, &opt)).map_err(value_error)?;
    let seconds = t0.elapsed().as_secs_f64();
    let read = (vec!["arrays given: wavelengths in nm, values as fractions".to_string()], vec![], false);
    fit_dict(py, stack, angle_rad, &template, q, data, r, seconds, read)
}

/// The fit as the dict of `iridis thinfilm fit --json` (arrays as NumPy arrays).
#[allow(clippy::too_many_arguments)]
fn fit_dict<'py>(
    py: Python<'py>,
    stack: &str,
    angle_rad: f64,
    template: &Template,
    q: Quantity,
    data: Measured,
    r: FitResult,
    seconds: f64,
    (notes, columns_used, was_percent): (Vec<String>, Vec<String>, bool),
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("stack", stack)?;
    out.set_item("quantity", q.name())?;
    out.set_item("angle_deg", angle_rad.to_degrees())?;
    out.set_item("names", r.names.clone())?;
    out.set_item("units", template.params.iter().map(|p| p.unit()).collect::<Vec<_>>())?;
    out.set_item("values", PyArray1::from_vec(py, r.values.clone()))?;
    out.set_item("sigma", PyArray1::from_vec(py, r.sigma.clone()))?;
    out.set_item("correlation", PyArray2::from_vec2(py, &r.correlation)?)?;
    out.set_item("chi2", r.chi2)?;
    out.set_item("dof", r.dof)?;
    out.set_item("reduced_chi2", r.reduced_chi2)?;
    out.set_item("sigma_given", r.sigma_given)?;
    out.set_item("at_bound", r.at_bound.clone())?;
    out.set_item("starts", r.starts_tried)?;
    out.set_item("evaluations", r.evaluations)?;
    out.set_item("jacobian", r.jacobian)?;
    out.set_item("seconds", seconds)?;
    out.set_item("fitted", PyArray1::from_vec(py, r.fitted))?;
    out.set_item("wavelength_nm", PyArray1::from_vec(py, data.wavelength_nm))?;
    out.set_item("measured", PyArray1::from_vec(py, data.values))?;
    let read = PyDict::new(py);
    read.set_item("columns", columns_used)?;
    read.set_item("percent", was_percent)?;
    read.set_item("notes", notes)?;
    out.set_item("read", read)?;
    Ok(out)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(m, [_profile, _fit]);
    Ok(())
}
