//! `iridis.vision`: colours as animals see them (`iridis-vision`), spectra as NumPy arrays in, the analysis of
//! `iridis vision --json` out (as JSON text the Python module turns into a dict). The options are read by the
//! library's `Spec`, as on the command line, so the words and messages are the CLI's.

use iridis_vision::{analyse, Light, Spec, VisualSystem};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::args::value_error;

/// The analysis of spectra (one per row of `values`, on `wavelengths`) as JSON text.
#[pyfunction]
#[pyo3(signature = (wavelengths, values, names, visual=None, lambda_max=None, chromophore=None, oil_droplets=None,
    ocular_media=None, illuminant=None, illuminant_units=None, illuminant_scale=None, background=None, weber=None,
    weber_ref=None, densities=None, receptor_noise=None, noise=None, achromatic=None, achromatic_weber=None, space=None))]
fn _analyse(
    py: Python<'_>,
    wavelengths: PyReadonlyArray1<'_, f64>,
    values: PyReadonlyArray2<'_, f64>,
    names: Vec<String>,
    visual: Option<String>,
    lambda_max: Option<String>,
    chromophore: Option<String>,
    oil_droplets: Option<String>,
    ocular_media: Option<String>,
    illuminant: Option<String>,
    illuminant_units: Option<String>,
    illuminant_scale: Option<f64>,
    background: Option<String>,
    weber: Option<f64>,
    weber_ref: Option<String>,
    densities: Option<String>,
    receptor_noise: Option<String>,
    noise: Option<String>,
    achromatic: Option<String>,
    achromatic_weber: Option<f64>,
    space: Option<String>,
) -> PyResult<String> {
    let spec = Spec {
        visual,
        lambda_max,
        chromophore,
        oil_droplets,
        ocular_media,
        illuminant,
        illuminant_units,
        illuminant_scale,
        background,
        weber,
        weber_ref,
        densities,
        receptor_noise,
        noise,
        achromatic,
        achromatic_weber,
        space,
    };
    let (wl, rows) = crate::args::spectra_rows(&wavelengths, &values)?;
    if names.len() != rows.len() {
        return Err(value_error(format!("{} names for {} spectra", names.len(), rows.len())));
    }
    let spectra: Vec<(String, Vec<f64>)> = names.into_iter().zip(rows).collect();
    py.allow_threads(|| -> Result<String, String> {
        let system = spec.system().map_err(|e| e.to_string())?;
        let options = spec.options(&system).map_err(|e| e.to_string())?;
        let a = analyse(&spectra, &wl, &system, &options).map_err(|e| e.to_string())?;
        serde_json::to_string(&a).map_err(|e| e.to_string())
    })
    .map_err(value_error)
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
    m.add_function(wrap_pyfunction!(_analyse, m)?)?;
    m.add_function(wrap_pyfunction!(_sensitivities, m)?)?;
    m.add_function(wrap_pyfunction!(_vision_names, m)?)?;
    Ok(())
}
