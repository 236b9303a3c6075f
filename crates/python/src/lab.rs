//! `iridis.lab`: the virtual test bench (paper sec. 6.1) and method comparisons in CIELAB (paper sec. 6.3,
//! Table 2), through the facade (`iridis_api::lab`: the functions `iridis testbench` and `iridis compare`
//! call). Results come back as the CLI's `--json` (the same keys, docs/json.md) plus the arrays behind them.

use iridis_api::lab::{parse_against, LabOptions};
use iridis_api::lab_run as run;
use iridis_api::model::TableGrid;
use iridis_api::surface::Source;
use iridis_lab::bench::BenchSetup;
use iridis_lab::methods::Method;
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;
use crate::facade::{run as facade_run, Options};
use crate::scan_report::with_outputs;
use crate::surface::PyHeightField;

/// A SURFACE argument (str), read with `reading`, or an `iridis.surface.Surface`, for which any of `reading` is
/// refused (it is already read).
fn source_of(obj: &Bound<'_, PyAny>, reading: &iridis_api::SurfaceOptions) -> PyResult<Source> {
    if let Ok(h) = obj.downcast::<PyHeightField>() {
        crate::diffraction::refuse_reading_options(reading).map_err(value_error)?;
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

/// The surface (a `Surface` or SURFACE argument) and the lab's options from the keyword `options`: the
/// surface's, `coherence_nm`, `terms`, `fresnel`, `fresnel_convention`, `shadowing`, `epsilon` (any other
/// keyword is a `TypeError`).
fn source_and_lab(surface: &Bound<'_, PyAny>, options: Option<Bound<'_, PyDict>>) -> PyResult<(Source, LabOptions)> {
    let lab = Options::read(options, lab_options)?;
    Ok((source_of(surface, &lab.surface)?, lab))
}

fn lab_options(o: &mut Options<'_>) -> PyResult<LabOptions> {
    let surface = o.surface()?;
    let coherence_nm = o.positive("coherence_nm")?;
    let terms = match o.usize("terms")? {
        Some(n) => n.to_string(),
        None => "auto".into(),
    };
    let (fresnel, convention, shadowing) = o.shading_text()?;
    o.former_name("stam_epsilon", "epsilon")?;
    let stam_epsilon = o.positive("epsilon")?;
    Ok(LabOptions { surface, coherence_nm, terms, fresnel, convention, shadowing, stam_epsilon })
}

fn method(s: &str) -> PyResult<Method> {
    s.parse().map_err(value_error)
}

/// What `_testbench` returns: the `--json` text, the reflectance matrix, its wavelengths and angles.
type BenchArrays<'py> =
    (String, String, Bound<'py, numpy::PyArray2<f64>>, Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// The test bench: returns `(json, text, matrix, wavelengths_nm, angles_deg)` — `json` as `iridis testbench
/// --json` prints it, `text` as it prints without, `matrix` the reflectance over (λ, θ_r).
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
    // The lab's methods or rigorous (the library refuses any other), with the rigorous method's material and
    // unit cell (it refuses them with the others).
    let (lab, rigorous) = Options::read(options, |o| {
        let lab = lab_options(o)?;
        let rigorous = iridis_api::ModelOptions {
            material: o.string("material")?,
            unit_cell_auto: o.unit_cell_auto()?,
            ..Default::default()
        };
        Ok((lab, rigorous))
    })?;
    let source = source_of(surface, &lab.surface)?;
    let mut setup =
        BenchSetup::new(incidence, azimuth.unwrap_or(0.0), order, wavelengths, angles_deg).map_err(value_error)?;
    setup.period_hint_nm = period_nm;
    let req = run::TestbenchRequest {
        method: method_name.to_string(),
        rigorous,
        setup,
        along_dominant: azimuth.is_none(),
        max_period_nm,
        plot: None,
    };
    let tb = facade_run(py, |r| run::testbench_run(&source, &lab, &req, r))?;
    let (j, t, text) = (tb.to_json(), &tb.bench, tb.text());
    let m = &t.matrix;
    let matrix = Array2::from_shape_vec((m.wavelengths_nm.len(), m.angles_deg.len()), m.values.clone())
        .map_err(|e| value_error(format!("reflectance matrix: {e}")))?;
    Ok((
        j.to_string(),
        text,
        matrix.into_pyarray(py),
        PyArray1::from_vec(py, m.wavelengths_nm.clone()),
        PyArray1::from_vec(py, m.angles_deg.clone()),
    ))
}

/// Method comparisons: returns `(json, maps)` — `json` as `iridis compare --json` prints it, `maps` a dict of
/// each method's and each truth's BRDF map as XYZ of shape (size, size, 3), NaN outside the unit disk.
#[pyfunction]
#[pyo3(signature = (surface, methods, against, exposures, theta_i, phi_i, size, step_nm, illuminant, uv_resolution, uv_power, table=None, options=None, gpu=false))]
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
    uv_resolution: Option<usize>,
    uv_power: Option<f64>,
    table: Option<String>,
    options: Option<Bound<'py, PyDict>>,
    gpu: bool,
) -> PyResult<(String, String, Bound<'py, PyDict>)> {
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
    let (source, lab) = source_and_lab(surface, options)?;
    let req = run::CompareRequest {
        methods,
        against,
        exposures,
        incidence: (theta_i, crate::args::check_azimuth("incidence", phi_i)?),
        size,
        illuminant: illuminant.to_string(),
        dlambda_nm: step_nm,
        table: TableGrid { uv_resolution, uv_power },
        table_path: table.map(Into::into),
        gpu,
        maps: None,
    };
    let (json, text, images) = facade_run(py, |r| {
        let c = run::compare_run(&source, &lab, &req, r)?;
        let (j, text) = (c.to_json(), c.text());
        let mut images: Vec<(String, Vec<Option<iridis_color::Xyz>>)> = c.comparison.images;
        images.extend(c.comparison.truths.into_iter().map(|(m, img)| (m.name().to_string(), img)));
        Ok((j.to_string(), text, images))
    })?;
    let maps = PyDict::new(py);
    for (name, img) in images {
        maps.set_item(&name, xyz_array(py, &img, size, &format!("map {name}"))?)?;
    }
    Ok((json, text, maps))
}

/// A convergence sweep (`iridis sweep`): writes the contact sheet to `output` (and the error plot to `plot`,
/// default `output`'s name with `_error`) and returns `iridis sweep --json`'s text.
#[pyfunction]
#[pyo3(signature = (surface, param, values, output, method="reference", against="model", exposures=vec![1000.0], theta_i=0.0, phi_i=0.0, size=64, step_nm=None, uv_resolution=None, uv_power=None, plot=None, options=None, gpu=false))]
fn _sweep<'py>(
    py: Python<'py>,
    surface: &Bound<'py, PyAny>,
    param: &str,
    values: Vec<f64>,
    output: std::path::PathBuf,
    method: &str,
    against: &str,
    exposures: Vec<f64>,
    theta_i: f64,
    phi_i: f64,
    size: usize,
    step_nm: Option<f64>,
    uv_resolution: Option<usize>,
    uv_power: Option<f64>,
    plot: Option<std::path::PathBuf>,
    options: Option<Bound<'py, PyDict>>,
    gpu: bool,
) -> PyResult<(String, String)> {
    let req = run::SweepRequest {
        method: self::method(method)?,
        param: param.parse().map_err(value_error)?,
        values,
        against: against.to_string(),
        exposures,
        incidence: (theta_i, crate::args::check_azimuth("incidence", phi_i)?),
        size,
        dlambda_nm: step_nm,
        table: TableGrid { uv_resolution, uv_power },
        gpu,
        output,
        plot,
    };
    let (source, lab) = source_and_lab(surface, options)?;
    facade_run(py, |r| {
        with_outputs(|| {
            let w = run::sweep_run(&source, &lab, &req, r)?;
            Ok((w.to_json().to_string(), w.text()))
        })
    })
}

/// The laser experiment (`iridis experiment laser`): writes the screen image(s) and returns `(json, xyz)` —
/// `iridis experiment laser --json`'s text and the screen as XYZ of shape (size, size, 3).
#[pyfunction]
#[pyo3(signature = (surface, output, method="reference", incidence=std::f64::consts::FRAC_PI_4, azimuth=0.0, aperture_nm=65_000.0, distance_nm=1e8, screen_nm=3e8, size=101, subsamples=3, spectrum=None, coating="gold", exposures=vec![1.0, 1000.0, 7500.0], step_nm=5.0, uv_resolution=None, uv_power=None, table=None, save_table=None, options=None))]
fn _laser<'py>(
    py: Python<'py>,
    surface: &Bound<'py, PyAny>,
    output: std::path::PathBuf,
    method: &str,
    incidence: f64,
    azimuth: f64,
    aperture_nm: f64,
    distance_nm: f64,
    screen_nm: f64,
    size: usize,
    subsamples: usize,
    spectrum: Option<std::path::PathBuf>,
    coating: &str,
    exposures: Vec<f64>,
    step_nm: f64,
    uv_resolution: Option<usize>,
    uv_power: Option<f64>,
    table: Option<std::path::PathBuf>,
    save_table: Option<std::path::PathBuf>,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<(String, String, Bound<'py, numpy::PyArray3<f64>>)> {
    let req = run::LaserRequest {
        method: self::method(method)?,
        setup: iridis_lab::laser::LaserSetup {
            incidence,
            azimuth: crate::args::check_azimuth("azimuth", azimuth)?,
            distance_nm,
            screen_width_nm: screen_nm,
            screen_height_nm: screen_nm,
            width_px: size,
            height_px: size,
            subsamples,
        },
        aperture_nm,
        spectrum,
        coating: coating.to_string(),
        exposures,
        dlambda_nm: step_nm,
        table: TableGrid { uv_resolution, uv_power },
        output,
        table_path: table,
        save_table,
    };
    let (source, lab) = source_and_lab(surface, options)?;
    let l = facade_run(py, |r| with_outputs(|| run::laser_run(&source, &lab, &req, r)))?;
    Ok((l.to_json().to_string(), l.text(), xyz_array(py, &l.image, size, "screen")?))
}

/// A square picture of `size`² colours as XYZ of shape (size, size, 3), NaN where there is none.
fn xyz_array<'py>(
    py: Python<'py>,
    img: &[Option<iridis_color::Xyz>],
    size: usize,
    what: &str,
) -> PyResult<Bound<'py, numpy::PyArray3<f64>>> {
    let flat: Vec<f64> = img.iter().flat_map(|p| p.map(|x| x.to_array()).unwrap_or([f64::NAN; 3])).collect();
    let a = Array3::from_shape_vec((size, size, 3), flat).map_err(|e| value_error(format!("{what}: {e}")))?;
    Ok(a.into_pyarray(py))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(m, [_sweep, _laser, _testbench, _compare]);
    Ok(())
}
