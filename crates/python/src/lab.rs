//! `iridis.lab`: the virtual test bench (paper sec. 6.1) and method comparisons in CIELAB (paper sec. 6.3,
//! Table 2), through the facade (`iridis_api::lab`: the functions `iridis testbench` and `iridis compare`
//! call). Results come back as the CLI's `--json` (the same keys, docs/json.md) plus the arrays behind them.

use iridis_api::lab::{comparison, parse_against, spectral, testbench, workbench_from, LabOptions};
use iridis_api::surface::Source;
use iridis_diffraction::TableParams;
use iridis_lab::bench::BenchSetup;
use iridis_lab::image::Pixels;
use iridis_lab::methods::Method;
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;
use crate::facade::{run, Options};
use crate::surface::PyHeightField;

/// A SURFACE argument (str) or an `iridis.surface.Surface`.
fn source_of(obj: &Bound<'_, PyAny>) -> PyResult<Source> {
    if let Ok(h) = obj.downcast::<PyHeightField>() {
        return crate::diffraction::source_of_field(h.get());
    }
    if let Ok(s) = obj.extract::<String>() {
        return Ok(Source::Spec(s));
    }
    Err(PyTypeError::new_err(format!(
        "surface must be an iridis.surface.Surface or a SURFACE argument as the CLI takes it (str), got {}",
        obj.get_type().name()?
    )))
}

/// The lab's options: the surface's, `coherence_nm`, `terms`, `fresnel`, `fresnel_convention`, `shadowing`,
/// `stam_epsilon`.
fn lab_options(o: &mut Options<'_>) -> PyResult<LabOptions> {
    let surface = o.surface()?;
    let coherence_nm = o.positive("coherence_nm")?;
    let terms = match o.usize("terms")? {
        Some(n) => n.to_string(),
        None => "auto".into(),
    };
    let (fresnel, convention, shadowing) = o.shading_text()?;
    let stam_epsilon = o.positive("stam_epsilon")?.unwrap_or(0.01);
    Ok(LabOptions { surface, coherence_nm, terms, fresnel, convention, shadowing, stam_epsilon })
}

fn method(s: &str) -> PyResult<Method> {
    s.parse().map_err(value_error)
}

/// What `_testbench` returns: the `--json` text, the reflectance matrix, its wavelengths and angles.
type BenchArrays<'py> =
    (String, Bound<'py, numpy::PyArray2<f64>>, Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// The test bench: returns `(json, matrix, wavelengths_nm, angles_deg)` — `json` as `iridis testbench --json`
/// prints it, `matrix` the reflectance over (λ, θ_r).
#[pyfunction]
#[pyo3(signature = (surface, method_name, incidence, azimuth, order, wavelengths, angles_deg, period_nm=None, max_period_nm=None, options=None))]
fn _testbench<'py>(
    py: Python<'py>,
    surface: &Bound<'py, PyAny>,
    method_name: &str,
    incidence: f64,
    azimuth: Option<f64>,
    order: i32,
    wavelengths: (f64, f64, f64),
    angles_deg: (f64, f64, f64),
    period_nm: Option<f64>,
    max_period_nm: Option<f64>,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<BenchArrays<'py>> {
    let method = method(method_name)?;
    let mut o = Options::new(options);
    let lab = lab_options(&mut o)?;
    o.finish()?;
    let source = source_of(surface)?;
    let mut setup =
        BenchSetup::new(incidence, azimuth.unwrap_or(0.0), order, wavelengths, angles_deg).map_err(value_error)?;
    setup.period_hint_nm = period_nm;
    let t = run(py, |r| testbench(&source, &lab, method, setup, azimuth.is_none(), max_period_nm, r))?;
    let mut j = t.result.to_json();
    j["method"] = serde_json::json!(method.name());
    j["surface"] = serde_json::json!(source.name());
    let m = &t.matrix;
    let matrix = Array2::from_shape_vec((m.wavelengths_nm.len(), m.angles_deg.len()), m.values.clone())
        .map_err(|e| value_error(format!("reflectance matrix: {e}")))?;
    Ok((
        j.to_string(),
        matrix.into_pyarray(py),
        PyArray1::from_vec(py, m.wavelengths_nm.clone()),
        PyArray1::from_vec(py, m.angles_deg.clone()),
    ))
}

/// Method comparisons: returns `(json, maps)` — `json` as `iridis compare --json` prints it, `maps` a dict of
/// each method's and each truth's BRDF map as XYZ of shape (size, size, 3), NaN outside the unit disk.
#[pyfunction]
#[pyo3(signature = (surface, methods, against, exposures, theta_i, phi_i, size, step_nm, illuminant, uv_resolution, uv_power, table=None, options=None))]
fn _compare<'py>(
    py: Python<'py>,
    surface: &Bound<'py, PyAny>,
    methods: Vec<String>,
    against: &str,
    exposures: Vec<f64>,
    theta_i: f64,
    phi_i: f64,
    size: usize,
    step_nm: f64,
    illuminant: &str,
    uv_resolution: usize,
    uv_power: f64,
    table: Option<String>,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<(String, Bound<'py, PyDict>)> {
    let methods = methods.iter().map(|m| method(m)).collect::<PyResult<Vec<_>>>()?;
    if methods.is_empty() {
        return Err(value_error("methods: give at least one method"));
    }
    let against = parse_against(against).map_err(value_error)?;
    if exposures.is_empty() || exposures.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
        return Err(value_error(format!("exposures {exposures:?}: give positive exposures in RU")));
    }
    if !(8..=2048).contains(&size) {
        return Err(value_error(format!("size {size} must be 8–2048 pixels")));
    }
    if !((0.0..std::f64::consts::FRAC_PI_2).contains(&theta_i) && phi_i.is_finite()) {
        return Err(value_error(format!("incidence θ = {theta_i} rad must be in [0, π/2), φ finite")));
    }
    let mut o = Options::new(options);
    let lab = lab_options(&mut o)?;
    o.finish()?;
    let source = source_of(surface)?;
    let (json, images) = run(py, |r| {
        let mut config = lab.config()?;
        config.spectral = spectral(illuminant, step_nm, r)?;
        config.table = TableParams { uv_resolution, uv_power };
        config.table_path = table.map(Into::into);
        let b = workbench_from(&source, &lab, config, r)?;
        let pixels = Pixels::brdf_map(theta_i, phi_i, size);
        let c = comparison(&b, &methods, against, &pixels, &exposures, r)?;
        let j = c.to_json(source.name(), against, size, iridis_color::units::degrees(theta_i), b.config.coherence_nm);
        let mut images: Vec<(String, Vec<Option<iridis_color::Xyz>>)> = c.images;
        images.extend(c.truths.into_iter().map(|(m, img)| (m.name().to_string(), img)));
        Ok((j.to_string(), images))
    })?;
    let maps = PyDict::new(py);
    for (name, img) in images {
        let flat: Vec<f64> = img.iter().flat_map(|p| p.map(|x| x.to_array()).unwrap_or([f64::NAN; 3])).collect();
        let a = Array3::from_shape_vec((size, size, 3), flat).map_err(|e| value_error(format!("map {name}: {e}")))?;
        maps.set_item(name, a.into_pyarray(py))?;
    }
    Ok((json, maps))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_testbench, m)?)?;
    m.add_function(wrap_pyfunction!(_compare, m)?)?;
    Ok(())
}
