//! `iridis.diffraction`: the paper's lookup tables (precompute, save, load) and BRDF maps as XYZ arrays from
//! a height field (reference or ground-truth evaluator) or a table (lookup), through `iridis_diffraction`.

use std::path::Path;
use std::sync::Arc;

use iridis_diffraction::geometry::direction;
use iridis_diffraction::map::brdf_map;
use iridis_diffraction::taylor::terms_for_bound;
use iridis_diffraction::{
    Evaluator, GroundTruth, Lookup, LookupTable, Patch, Reference, Shading, SpectralSetup, TableParams, TaylorTerms,
    DEFAULT_COHERENCE_NM,
};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;
use crate::color::{illuminant, observer};
use crate::surface::PyHeightField;

/// Terms bounded so that the series' remainder is below this (the CLI's `--terms auto`).
const TERM_EPSILON: f64 = 1e-6;

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

    /// The table's metadata (surface, grid, Taylor terms, coherence, spectral setup).
    #[getter]
    fn meta<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let m = &self.table.meta;
        let d = PyDict::new(py);
        d.set_item("surface", &m.surface)?;
        d.set_item("rows", m.rows)?;
        d.set_item("cols", m.cols)?;
        d.set_item("dx_nm", m.dx_nm)?;
        d.set_item("dy_nm", m.dy_nm)?;
        d.set_item("taylor_terms", m.taylor_terms)?;
        d.set_item("coherence_nm", m.coherence_nm)?;
        d.set_item("uv_resolution", m.uv_resolution)?;
        d.set_item("uv_power", m.uv_power)?;
        d.set_item("illuminant", &m.illuminant)?;
        d.set_item("observer", &m.observer)?;
        d.set_item("wavelength_step_nm", m.wavelength_step_nm)?;
        d.set_item("warnings", m.warnings.clone())?;
        Ok(d)
    }
}

fn patch_of(hf: &PyHeightField) -> PyResult<Patch> {
    let h = hf.field();
    Patch::from_row_major(h.rows, h.cols, h.dx_nm, h.dy_nm, &h.heights_nm).map_err(value_error)
}

fn terms_of(
    patch: &Patch,
    terms: Option<usize>,
    coherence_nm: f64,
) -> Result<TaylorTerms, iridis_diffraction::DiffractionError> {
    let n = terms.unwrap_or_else(|| terms_for_bound(patch.max_abs_height, 380.0, TERM_EPSILON));
    TaylorTerms::compute(patch, n, coherence_nm)
}

/// The paper's lookup tables `I_p(u, v)` of a height field, as `iridis precompute`.
#[pyfunction]
#[pyo3(signature = (surface, coherence_nm=None, terms=None, uv_resolution=501, uv_power=5.0, illuminant="D65", observer="1931", step_nm=5.0, name=""))]
fn precompute(
    py: Python<'_>,
    surface: &PyHeightField,
    coherence_nm: Option<f64>,
    terms: Option<usize>,
    uv_resolution: usize,
    uv_power: f64,
    illuminant: &str,
    observer: &str,
    step_nm: f64,
    name: &str,
) -> PyResult<PyTable> {
    let spectral =
        SpectralSetup::new(self::illuminant(illuminant)?, self::observer(observer)?, step_nm).map_err(value_error)?;
    let patch = patch_of(surface)?;
    let coherence = coherence_nm.unwrap_or(DEFAULT_COHERENCE_NM);
    let name = if name.is_empty() { surface.field().meta.source.clone() } else { name.to_string() };
    let table = py
        .allow_threads(|| {
            let t = terms_of(&patch, terms, coherence)?;
            LookupTable::build(&t, &spectral, TableParams { uv_resolution, uv_power }, &name, &|_| {})
        })
        .map_err(value_error)?;
    Ok(PyTable { table: Arc::new(table) })
}

/// A BRDF map (the paper's layout: view directions on the unit disk, row 0 at the top) as linear XYZ,
/// shape (size, size, 3), light from (θ_i, φ_i) in radians. `source` is a height field (methods
/// `reference`, `ground-truth`) or a table (method `lookup`).
#[pyfunction]
#[pyo3(signature = (source, method, theta_i, phi_i, size, coherence_nm=None, terms=None, illuminant="D65", observer="1931", step_nm=5.0))]
fn brdf_map_xyz<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    method: &str,
    theta_i: f64,
    phi_i: f64,
    size: usize,
    coherence_nm: Option<f64>,
    terms: Option<usize>,
    illuminant: &str,
    observer: &str,
    step_nm: f64,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    if !(1..=4096).contains(&size) {
        return Err(value_error(format!("size {size} must be between 1 and 4096 pixels")));
    }
    if !((0.0..std::f64::consts::FRAC_PI_2).contains(&theta_i) && phi_i.is_finite()) {
        return Err(value_error(format!("incidence θ = {theta_i} rad must be in [0, π/2), φ finite")));
    }
    let shading = Shading::default();
    let evaluator: Box<dyn Evaluator> = if let Ok(t) = source.downcast::<PyTable>() {
        if method != "lookup" {
            return Err(value_error(format!(
                "method {method} needs the height field, not a table: pass the Surface the table was made from"
            )));
        }
        Box::new(
            Lookup::new(t.get().table.clone(), shading, iridis_diffraction::table::Precision::F64)
                .map_err(value_error)?,
        )
    } else if let Ok(h) = source.downcast::<PyHeightField>() {
        let patch = patch_of(h.get())?;
        let spectral = SpectralSetup::new(self::illuminant(illuminant)?, self::observer(observer)?, step_nm)
            .map_err(value_error)?;
        let coherence = coherence_nm.unwrap_or(DEFAULT_COHERENCE_NM);
        match method {
            "reference" => {
                let t = py.allow_threads(|| terms_of(&patch, terms, coherence)).map_err(value_error)?;
                Box::new(Reference { terms: Arc::new(t), shading, spectral })
            }
            "ground-truth" => {
                let samples = 2 * spectral.wavelengths().len() - 1;
                Box::new(GroundTruth::new(&patch, coherence, shading, &spectral, samples).map_err(value_error)?)
            }
            "lookup" => {
                return Err(value_error("method lookup needs a Table: iridis.diffraction.precompute(surface) first"))
            }
            _ => {
                return Err(value_error(format!(
                    "unknown method '{method}'; expected reference, ground-truth or lookup"
                )))
            }
        }
    } else {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "source must be an iridis.surface.Surface or an iridis.diffraction.Table",
        ));
    };
    let wi = direction(theta_i, phi_i);
    let xyz = py.allow_threads(|| brdf_map(evaluator.as_ref(), wi, size, &|_| {}));
    let flat: Vec<f64> = xyz.iter().flat_map(|c| c.to_array()).collect();
    Ok(Array3::from_shape_vec((size, size, 3), flat).expect("shape").into_pyarray(py))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyTable>()?;
    m.add_function(wrap_pyfunction!(precompute, m)?)?;
    m.add_function(wrap_pyfunction!(brdf_map_xyz, m)?)?;
    Ok(())
}
