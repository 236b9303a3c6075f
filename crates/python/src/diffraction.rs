//! `iridis.diffraction`: the paper's lookup tables (precompute, save, load), BRDF maps as XYZ arrays and point
//! queries (ρ(λ) and XYZ for one pair of directions), for every method the CLI has, through the facade
//! (`iridis_api::brdf`, `iridis_api::model`: the functions `iridis precompute`, `iridis brdf-map` and
//! `iridis brdf eval` call).

use std::path::Path;
use std::sync::Arc;

use iridis_api::brdf::{
    default_method, evaluator_for, make_evaluator, point, render_map, scalar_error_said, table_evaluator,
    EvaluatorSetup, RIGOROUS,
};
use iridis_api::model::{is_table, refuse_build_options, refuse_build_options_for_table, TableGrid};
use iridis_api::report::Report;
use iridis_api::surface::Source;
use iridis_api::{ModelOptions, SurfaceOptions};
use iridis_diffraction::geometry::direction;
use iridis_diffraction::table::Precision;
use iridis_diffraction::{Evaluator, LookupTable, Patch, Shading, TableParams};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray1, PyArray3};
use pyo3::exceptions::{PyOSError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;
use crate::facade::{api_error, json_to_py, run, serialized, Options};
use crate::surface::PyHeightField;

/// A lookup table (the native half of `iridis.diffraction.Table`).
#[pyclass(frozen, module = "iridis._native", name = "_Table")]
#[derive(Debug)]
pub struct PyTable {
    table: Arc<LookupTable>,
}

#[pymethods]
impl PyTable {
    /// Reads a table written by `iridis precompute` or `Table.save`.
    #[staticmethod]
    fn load(py: Python<'_>, path: &str) -> PyResult<Self> {
        if !Path::new(path).exists() {
            return Err(PyOSError::new_err(format!("table {path}: no such file")));
        }
        let t = py.allow_threads(|| LookupTable::load(Path::new(path))).map_err(value_error)?;
        Ok(Self { table: Arc::new(t) })
    }

    /// Writes the table as `.npz` (what `iridis precompute -o` writes).
    fn save(&self, py: Python<'_>, path: &str) -> PyResult<()> {
        py.allow_threads(|| self.table.save(Path::new(path))).map_err(|e| PyOSError::new_err(e.to_string()))
    }

    /// The table's metadata as stored in its `.npz` (surface, grid, Taylor terms, coherence, spectral setup,
    /// units, warnings, …; the keys of [`iridis_diffraction::table::TableMeta`]).
    #[getter]
    fn meta<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        serialized(py, &self.table.meta)
    }
}

/// A height field in memory as the facade's [`Source`], named after where it came from.
pub fn source_of_field(h: &PyHeightField) -> PyResult<Source> {
    let f = h.field();
    let patch = Patch::from_row_major(f.rows, f.cols, f.dx_nm, f.dy_nm, &f.heights_nm).map_err(value_error)?;
    let name = if f.meta.source.is_empty() { "surface".to_string() } else { f.meta.source.clone() };
    Ok(Source::Patch { patch, name })
}

/// A Surface in memory is already read: the options that say how to read a file would be ignored, so they are
/// refused (`pixel_size_nm=10` on a Surface of 50 nm pixels changed nothing, in silence).
pub fn refuse_reading_options(s: &iridis_api::SurfaceOptions) -> anyhow::Result<()> {
    let given: Vec<&str> = [
        ("pixel_size_nm", s.pixel_size_nm.is_some()),
        ("max_height_nm", s.max_height_nm.is_some()),
        ("channel", s.channel.is_some()),
        ("height_unit", s.height_unit.is_some()),
        ("level", s.level.is_some()),
        ("override_units", s.units.override_units),
        ("as_height", s.units.as_height),
    ]
    .into_iter()
    .filter_map(|(name, set)| set.then_some(name))
    .collect();
    if given.is_empty() {
        return Ok(());
    }
    let (they, them) = if given.len() == 1 { ("it says", "it") } else { ("they say", "them") };
    anyhow::bail!(
        "{} would be ignored: {they} how to read a file, and this Surface is already read; give {them} to \
         surface.load (Surface.level levels it)",
        given.join(", ")
    )
}

/// What an evaluator is made from: a table, a height field in memory, or an argument as the CLI takes it
/// (a SURFACE, or a TABLE file told apart by content).
enum Input {
    Table(Arc<LookupTable>),
    Field(Source),
    Arg(String),
}

fn input_of(obj: &Bound<'_, PyAny>) -> PyResult<Input> {
    if let Ok(t) = obj.downcast::<PyTable>() {
        return Ok(Input::Table(t.get().table.clone()));
    }
    if let Ok(h) = obj.downcast::<PyHeightField>() {
        return Ok(Input::Field(source_of_field(h.get())?));
    }
    if let Ok(s) = obj.extract::<String>() {
        return Ok(Input::Arg(s));
    }
    Err(PyTypeError::new_err(format!(
        "source must be an iridis.surface.Surface, an iridis.diffraction.Table or a SURFACE or TABLE argument as \
         the CLI takes it (str), got {}",
        obj.get_type().name()?
    )))
}

/// Everything an evaluator needs besides its input.
struct EvalOptions {
    model: ModelOptions,
    surface: SurfaceOptions,
    fresnel: (String, iridis_diffraction::FresnelConvention, bool),
    /// The u-v grid as given (refused where no table is built from it) and as used.
    grid: TableGrid,
    params: TableParams,
}

impl EvalOptions {
    fn read(o: &mut Options<'_>) -> PyResult<Self> {
        let model = o.model()?;
        let surface = o.surface()?;
        let fresnel = o.shading_text()?;
        let grid = TableGrid { uv_resolution: o.usize("uv_resolution")?, uv_power: o.positive("uv_power")? };
        let params = grid.params().map_err(api_error)?;
        Ok(Self { model, surface, fresnel, grid, params })
    }

    fn shading(&self) -> anyhow::Result<Shading> {
        let (f, c, s) = &self.fresnel;
        iridis_api::fresnel::shading(f, *c, *s)
    }

    /// The evaluator setup of `method` with these options (the CPU's f64 precision).
    fn setup<'a>(&'a self, method: &'a str, shading: Shading) -> EvaluatorSetup<'a> {
        let (model, surface, params) = (&self.model, &self.surface, self.params);
        EvaluatorSetup { method, model, shading, params, precision: Precision::F64, surface }
    }
}

/// The evaluator of `method` (default: lookup for a table, reference for a height field) on an input.
fn evaluator(
    input: &Input,
    method: Option<&str>,
    o: &EvalOptions,
    report: &dyn Report,
) -> anyhow::Result<Box<dyn Evaluator>> {
    let shading = o.shading()?;
    // A u-v grid shapes a table built here from a height field by the lookup method, and nothing else: given
    // anywhere else it would be ignored, so it is refused as `brdf-map` refuses it (a table first, then a method
    // that builds none).
    match input {
        Input::Table(t) => {
            refuse_build_options("this Table", o.grid, &o.surface, "the call")?;
            table_evaluator(t.clone(), method.unwrap_or("lookup"), &o.model, shading, Precision::F64, report)
        }
        Input::Field(s) => {
            refuse_reading_options(&o.surface)?;
            let m = method.unwrap_or("reference");
            o.grid.refuse_unless_lookup(m)?;
            evaluator_for(s, o.setup(m, shading), report)
        }
        Input::Arg(a) => {
            let m = method.unwrap_or_else(|| default_method(a));
            refuse_build_options_for_table(a, o.grid, &o.surface, "the call")?;
            o.grid.refuse_unless_lookup(m)?;
            make_evaluator(a, o.setup(m, shading), report)
        }
    }
}

/// A direction `(θ, φ)` in radians above the surface.
fn direction_of(what: &str, angles: (f64, f64)) -> PyResult<[f64; 3]> {
    let (theta, phi) = crate::args::above(what, angles)?;
    Ok(direction(theta, phi))
}

/// The paper's lookup tables `I_p(u, v)` of a height field, as `iridis precompute`, through the same library
/// call (`iridis_api::precompute::table_of`): coherence, terms and the spectral setup from `options`, the u-v grid
/// `uv_resolution`, `uv_power`, `units` (relative or radiometric) and `gpu`; what a table cannot carry is refused
/// there, any other keyword here.
#[pyfunction]
#[pyo3(signature = (source, name=None, options=None))]
fn precompute(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    name: Option<String>,
    options: Option<Bound<'_, PyDict>>,
) -> PyResult<PyTable> {
    let request = Options::read(options, |o| {
        let model = o.model()?;
        let surface_opts = o.surface()?;
        let grid = TableGrid { uv_resolution: o.usize("uv_resolution")?, uv_power: o.positive("uv_power")? };
        let units = match o.string("units")? {
            None => iridis_diffraction::Units::Relative,
            Some(u) => u.parse().map_err(value_error)?,
        };
        Ok(iridis_api::precompute::PrecomputeRequest {
            surface: String::new(),
            surface_opts,
            model,
            params: grid.params().map_err(api_error)?,
            units,
            gpu: o.bool("gpu")?.unwrap_or(false),
        })
    })?;
    let source = match input_of(source)? {
        Input::Field(s) => {
            refuse_reading_options(&request.surface_opts).map_err(value_error)?;
            s
        }
        Input::Arg(a) if !iridis_api::model::is_table(&a) => Source::Spec(a),
        _ => return Err(value_error("precompute needs a height field (a Surface or a SURFACE argument), not a table")),
    };
    let name = name.unwrap_or_else(|| source.name().to_string());
    let table = run(py, |r| iridis_api::precompute::table_of(&source, &request, &name, "the table", r))?;
    Ok(PyTable { table: Arc::new(table) })
}

/// A BRDF map (the paper's layout: view directions on the unit disk, row 0 at the top) as linear XYZ,
/// shape (size, size, 3), light from (θ_i, φ_i) in radians, as `iridis brdf-map --raw`; with `per_sr`, the
/// BRDF f_r in sr⁻¹ as XYZ instead, as `iridis brdf-map --brdf`; each pixel the mean of `subsamples²` view
/// samples, as `--subsamples`.
#[pyfunction]
#[pyo3(signature = (source, method, theta_i, phi_i, size, options=None, per_sr=false, subsamples=1))]
#[allow(clippy::too_many_arguments)]
fn brdf_map_xyz<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    method: Option<String>,
    theta_i: f64,
    phi_i: f64,
    size: usize,
    options: Option<Bound<'py, PyDict>>,
    per_sr: bool,
    subsamples: usize,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    if !(1..=4096).contains(&size) {
        return Err(value_error(format!("size {size} must be between 1 and 4096 pixels")));
    }
    iridis_api::brdf_map::check_subsamples(subsamples).map_err(value_error)?;
    let wi = direction_of("incidence", (theta_i, phi_i))?;
    let eo = Options::read(options, EvalOptions::read)?;
    let input = input_of(source)?;
    let xyz = run(py, |r| {
        let e = evaluator(&input, method.as_deref(), &eo, r)?;
        iridis_api::brdf_map::warn_lobes_between_pixels(e.as_ref(), size, subsamples, per_sr, r);
        let xyz = if per_sr {
            iridis_api::brdf::render_map_per_sr(e.as_ref(), &eo.model, wi, size, subsamples, r)?
        } else {
            render_map(e.as_ref(), wi, size, subsamples, r)
        };
        // As `iridis brdf-map` says of a map with no light (lost here, where no exposure follows).
        iridis_api::brdf_map::warn_if_black(&xyz, e.name(), size * subsamples, r);
        Ok(xyz)
    })?;
    Ok(xyz_array(py, &xyz, size))
}

/// A BRDF map of `size`² colours as linear XYZ of shape (size, size, 3).
pub(crate) fn xyz_array<'py>(py: Python<'py>, xyz: &[iridis_color::Xyz], size: usize) -> Bound<'py, PyArray3<f64>> {
    let flat: Vec<f64> = xyz.iter().flat_map(|c| c.to_array()).collect();
    Array3::from_shape_vec((size, size, 3), flat).expect("shape").into_pyarray(py)
}

/// ρ(λ) and XYZ of one method for one pair of directions, as `iridis brdf eval --json`: a dict with `method`,
/// `wavelength_nm`, `reflectance` (None for lookup) and `xyz`.
#[pyfunction]
#[pyo3(signature = (source, method, light, view, options=None))]
fn eval_point<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    method: Option<String>,
    light: (f64, f64),
    view: (f64, f64),
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (wi, wr) = (direction_of("light", light)?, direction_of("view", view)?);
    let eo = Options::read(options, EvalOptions::read)?;
    let input = input_of(source)?;
    let (p, scalar_error, fresnel_factor) = run(py, |r| {
        let e = evaluator(&input, method.as_deref(), &eo, r)?;
        let mut p = point(e.as_ref(), &eo.model, wi, wr, r)?;
        p.rigorous = iridis_api::rigorous_brdf::RigorousBrdf::summary_of(e.as_ref());
        // The Fresnel factor's normal reflectance and whether it tells s from p, as `brdf eval --json` gives them.
        let (name, convention, shadowing) = &eo.fresnel;
        let shading = iridis_api::fresnel::shading(name, *convention, *shadowing)?;
        let fresnel = (shading.fresnel.normal_reflectance(), shading.fresnel.polarised());
        // The scalar model's error on the scan's own period, warned as `brdf eval` warns it (issue 28).
        let source = match &input {
            Input::Field(s) => Some(s.clone()),
            Input::Arg(a) if !is_table(a) => Some(Source::Spec(a.clone())),
            _ => None,
        };
        let error = match source {
            Some(s) if p.method != RIGOROUS => scalar_error_said(&s, &eo.surface, wi, eo.model.material.as_deref(), r),
            _ => None,
        };
        Ok((p, error, fresnel))
    })?;
    let d = PyDict::new(py);
    d.set_item("method", &p.method)?;
    d.set_item("light_direction", wi.to_vec())?;
    d.set_item("view_direction", wr.to_vec())?;
    d.set_item("wavelength_nm", PyArray1::from_vec(py, p.query.wavelengths_nm.clone()))?;
    match p.query.reflectance {
        Some(rho) => d.set_item("reflectance", PyArray1::from_vec(py, rho))?,
        None => d.set_item("reflectance", py.None())?,
    }
    match &p.query.brdf {
        Some(b) => {
            let f = PyDict::new(py);
            f.set_item("s", PyArray1::from_vec(py, b.s.clone()))?;
            f.set_item("p", PyArray1::from_vec(py, b.p.clone()))?;
            f.set_item("unpolarized", PyArray1::from_vec(py, b.unpolarized.clone()))?;
            d.set_item("brdf_per_sr", f)?;
        }
        None => d.set_item("brdf_per_sr", py.None())?,
    }
    d.set_item("coherence_nm", p.coherence_nm)?;
    d.set_item("window_effective_area_um2", p.effective_area_nm2.map(|a| a / 1e6))?;
    // What the numbers rest on, as brdf_eval's keys: the light and observer of the XYZ (a table's own, fixed
    // when it was built), the Fresnel factor and shadowing.
    let (illuminant, observer) = match &p.table {
        Some(t) => (t.illuminant.clone(), t.observer.clone()),
        None => (
            eo.model.illuminant.clone().unwrap_or_else(|| "d65".into()),
            eo.model.observer.clone().unwrap_or_else(|| "1931".into()),
        ),
    };
    d.set_item("illuminant", illuminant)?;
    d.set_item("observer", observer)?;
    let (fresnel, convention, shadowing) = &eo.fresnel;
    let rigorous = p.method == RIGOROUS;
    d.set_item("fresnel", (!rigorous).then_some(fresnel.as_str()))?;
    d.set_item("fresnel_convention", convention.name())?;
    d.set_item("shadowing", (!rigorous).then_some(*shadowing))?;
    d.set_item("xyz", PyArray1::from_vec(py, p.query.xyz.to_array().to_vec()))?;
    match scalar_error {
        Some(e) => d.set_item("scalar_error", json_to_py(py, &e.to_json())?)?,
        None => d.set_item("scalar_error", py.None())?,
    }
    d.set_item("fresnel_r0", fresnel_factor.0)?;
    d.set_item("polarised", rigorous || fresnel_factor.1)?;
    // `null` where there is none, as in `brdf eval --json`.
    let rigorous_json = p.rigorous.as_ref().map(|r| r.to_json()).unwrap_or_default();
    d.set_item("rigorous", json_to_py(py, &rigorous_json)?)?;
    d.set_item("table", json_to_py(py, &p.table.as_ref().map(iridis_api::brdf_eval::table_json).unwrap_or_default())?)?;
    Ok(d)
}

/// Order efficiencies of a unit cell, as `iridis grating --json` (a dict with the same keys).
#[pyfunction]
#[pyo3(signature = (source, light, wavelengths_nm, options=None))]
fn grating<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    light: (f64, f64),
    wavelengths_nm: Vec<f64>,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    use iridis_api::grating::{Detector, GratingOptions};
    let wi = direction_of("light", light)?;
    let mut o = Options::new(options);
    let surface = o.surface()?;
    let method_given = o.string("method")?;
    let material = o.string("material")?;
    let fresnel = o.string("fresnel")?;
    let normalisation = o.string("normalisation")?;
    let detector = match (o.f64("detector_theta")?, o.f64("detector_phi")?, o.positive("acceptance")?) {
        (Some(t), p, a) => Some(Detector {
            direction: direction_of("detector", (t, p.unwrap_or(0.0)))?,
            acceptance_rad: a.unwrap_or(Detector::DEFAULT_ACCEPTANCE_DEG.to_radians()),
        }),
        (None, None, None) => None,
        _ => return Err(value_error("detector_phi and acceptance need detector_theta (radians)")),
    };
    let compare = o.bool("compare")?.unwrap_or(false);
    let method = method_given.unwrap_or_else(|| "kirchhoff".into());
    // --orders-above as a fraction (1e-3; the library checks its range).
    let orders_above = o.f64("orders_above")?.unwrap_or(0.0);
    let unit_cell_auto = o.unit_cell_auto()?;
    o.finish()?;
    let source = match input_of(source)? {
        Input::Field(s) => {
            refuse_reading_options(&surface).map_err(value_error)?;
            s
        }
        Input::Arg(a) => Source::Spec(a),
        Input::Table(_) => return Err(value_error("grating needs the height field (the unit cell), not a table")),
    };
    let value = run(py, |r| {
        let opts = GratingOptions {
            method: method.parse()?,
            light: wi,
            wavelengths_nm,
            material,
            fresnel,
            normalisation: normalisation.as_deref().map(str::parse).transpose()?,
            detector,
            unit_cell_auto,
            orders_above,
        };
        if !compare {
            let g = iridis_api::grating_run::grating_checked(&source, &surface, &opts, r)?;
            // The detector as the CLI's --detector writes it, for the text's line that names it.
            let named = detector.map(|d| {
                let deg = |x: f64| iridis_color::spectrum::short_number(x.to_degrees());
                let (t, p) = (d.direction[2].clamp(-1.0, 1.0).acos(), d.direction[1].atan2(d.direction[0]));
                format!("{}deg,{}deg", deg(t), deg(p.rem_euclid(std::f64::consts::TAU)))
            });
            let acceptance = detector.map_or(0.0, |d| d.acceptance_rad);
            let text = iridis_api::grating_run::grating_text(&g, light, named.as_deref(), acceptance);
            return Ok((g.to_json(), text));
        }
        let c = iridis_api::grating_run::compare(&source, &surface, &opts, r)?;
        Ok((c.to_json(), c.text()))
    })?;
    Ok((json_to_py(py, &value.0)?, value.1))
}

/// How an animal sees a surface from several directions, as `iridis brdf vision --json` (a dict).
#[pyfunction]
#[pyo3(signature = (source, visual, light_theta, views_deg, azimuth=None, illuminant=None, options=None))]
#[allow(clippy::too_many_arguments)]
fn brdf_vision<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    visual: String,
    light_theta: f64,
    views_deg: Vec<f64>,
    azimuth: Option<f64>,
    illuminant: Option<String>,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let eo = Options::read(options, EvalOptions::read)?;
    let azimuth = azimuth.map(|a| crate::args::check_azimuth("azimuth", a)).transpose()?;
    let source = match input_of(source)? {
        Input::Field(s) => {
            refuse_reading_options(&eo.surface).map_err(value_error)?;
            s
        }
        Input::Arg(a) => Source::Spec(a),
        Input::Table(_) => return Err(value_error("vision needs the height field, not a table")),
    };
    // The reference method along the plane, as `iridis brdf vision` (which has no u-v grid option).
    eo.grid.refuse_unless_lookup("reference").map_err(api_error)?;
    let spec = iridis_vision::Spec { visual: Some(visual), illuminant, ..Default::default() };
    let v = run(py, |r| {
        let plane = iridis_api::vision::PlaneViews { light_theta, azimuth, views_deg: &views_deg, spec: &spec };
        iridis_api::brdf_vision::brdf_vision(&source, &eo.surface, &eo.model, eo.shading()?, plane, None, r)
    })?;
    Ok((json_to_py(py, &v.to_json())?, iridis_api::brdf_vision::vision_text(&v)))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyTable>()?;
    add_functions!(m, [precompute, brdf_map_xyz, eval_point, grating, brdf_vision]);
    Ok(())
}
