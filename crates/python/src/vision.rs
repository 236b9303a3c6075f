//! `iridis.vision`: colours as animals see them (`iridis-vision`), spectra as NumPy arrays in, the analysis of
//! `iridis vision --json` out (as JSON text the Python module turns into a dict). The options are read by the
//! library's `Spec`, as on the command line, so the words and messages are the CLI's.

use iridis_vision::{analyse, Light, Spec, VisualSystem};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;
use crate::facade::{run, Options};
use crate::film_commands::Answer;

/// The analysis options as typed (the CLI's words), from a wrapper's keyword options; `None` leaves a default.
fn spec(options: Option<Bound<'_, PyDict>>) -> PyResult<Spec> {
    Options::read(options, |o| {
        Ok(Spec {
            visual: o.string("visual")?,
            lambda_max: o.string("lambda_max")?,
            chromophore: o.string("chromophore")?,
            oil_droplets: o.string("oil_droplets")?,
            ocular_media: o.string("ocular_media")?,
            illuminant: o.string("illuminant")?,
            illuminant_units: o.string("illuminant_units")?,
            illuminant_scale: o.f64("illuminant_scale")?,
            background: o.string("background")?,
            weber: o.f64("weber")?,
            weber_ref: o.string("weber_ref")?,
            densities: o.string("densities")?,
            receptor_noise: o.string("receptor_noise")?,
            noise: o.string("noise")?,
            achromatic: o.string("achromatic")?,
            achromatic_weber: o.f64("weber_achromatic")?,
            space: o.string("space")?,
        })
    })
}

/// The analysis of spectra (one per row of `values`, on `wavelengths`) as JSON text.
#[pyfunction]
#[pyo3(signature = (wavelengths, values, names, **options))]
fn _analyse(
    py: Python<'_>,
    wavelengths: PyReadonlyArray1<'_, f64>,
    values: PyReadonlyArray2<'_, f64>,
    names: Vec<String>,
    options: Option<Bound<'_, PyDict>>,
) -> PyResult<String> {
    let spec = spec(options)?;
    let (wl, rows) = crate::args::spectra_rows(&wavelengths, &values)?;
    if names.len() != rows.len() {
        return Err(value_error(format!("{} names for {} spectra", names.len(), rows.len())));
    }
    let spectra: Vec<(String, Vec<f64>)> = names.into_iter().zip(rows).collect();
    py.allow_threads(|| -> Result<String, String> {
        let system = spec.system().map_err(|e| e.to_string())?;
        let options = spec.options(&system).map_err(|e| e.to_string())?;
        let mut a = analyse(&spectra, &wl, &system, &options).map_err(|e| e.to_string())?;
        a.notes.extend(iridis_vision::table::percent_note(
            &spectra,
            "divide them by 100",
            options.noise_model == iridis_vision::model::NoiseModel::Quantum,
        ));
        serde_json::to_string(&a).map_err(|e| e.to_string())
    })
    .map_err(value_error)
}

/// `iridis vision`: the spectra CSV at `path` (`percent` divides by 100) analysed with `options`; the answer
/// has the CLI's `--json` and its text.
#[pyfunction]
#[pyo3(signature = (path, percent, **options))]
fn _vision_file<'py>(
    py: Python<'py>,
    path: &str,
    percent: bool,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let spec = spec(options)?;
    let a = run(py, |report| {
        let v = iridis_api::vision::analyse_file(std::path::Path::new(path), &spec, percent)?;
        v.analysis.notes.iter().for_each(|n| iridis_api::Report::note(report, n));
        Ok(Answer { json: Some(v.to_json()?), text: Some(v.text()), ..Default::default() })
    })?;
    a.into_py(py)
}

/// Each receptor's sensitivity (unit sum over the 1 nm samples of 300–700 nm, times the ocular media) at
/// `wavelengths`: shape (receptors, wavelengths), with the receptor names.
#[pyfunction]
#[pyo3(signature = (wavelengths, visual=None, lambda_max=None, chromophore=None, oil_droplets=None))]
fn _sensitivities<'py>(
    py: Python<'py>,
    wavelengths: PyReadonlyArray1<'py, f64>,
    visual: Option<String>,
    lambda_max: Option<String>,
    chromophore: Option<String>,
    oil_droplets: Option<String>,
) -> PyResult<(Vec<String>, Bound<'py, PyArray2<f64>>)> {
    let spec = Spec { visual, lambda_max, chromophore, oil_droplets, ..Spec::default() };
    let system = spec.system().map_err(value_error)?;
    let wl = wavelengths.as_array().to_vec();
    let n = system.receptors.len();
    let out: Vec<f64> =
        system.receptors.iter().flat_map(|r| wl.iter().map(|&l| r.sensitivity(l) * system.media(l))).collect();
    let arr = Array2::from_shape_vec((n, wl.len()), out).expect("n × wavelengths");
    Ok((system.receptor_names(), arr.into_pyarray(py)))
}

/// (name, description) pairs.
type Named = Vec<(String, String)>;

/// The built-in visual systems and illuminants: ([(id, description)], [(name, description)]).
#[pyfunction]
fn _vision_names() -> (Named, Named) {
    let f = |v: &[(&str, &str)]| v.iter().map(|(a, b)| (a.to_string(), b.to_string())).collect();
    (f(VisualSystem::builtin_names()), f(Light::builtin_names()))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(m, [_analyse, _vision_file, _sensitivities, _vision_names]);
    Ok(())
}
