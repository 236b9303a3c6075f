//! `iridis.surface`: height fields from any supported file or a built-in generator (the CLI's SURFACE
//! argument, `iridis_surface::load_surface`), levelling, roughness statistics.

use iridis_surface::formats::channel::ChannelSel;
use iridis_surface::{load_surface, prep, stats, HeightField, LoadOptions};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;

use crate::args::value_error;
use crate::facade::{run, serialized};
use crate::scan_report::with_outputs;

/// Heights in nm, row-major, with the pixel size and where they came from (the native half of
/// `iridis.surface.Surface`).
#[pyclass(frozen, module = "iridis._native", name = "_HeightField")]
#[derive(Debug)]
pub struct PyHeightField {
    hf: HeightField,
}

/// Missing files are `OSError` (as Python's own `open`), everything else about the input `ValueError`.
fn surface_error(spec: &str, e: iridis_surface::SurfaceError) -> PyErr {
    let msg = crate::args::in_python_terms(&format!("cannot load surface {spec}: {e}"));
    let missing = !spec.starts_with("builtin:") && !std::path::Path::new(spec).exists();
    if missing {
        PyOSError::new_err(msg)
    } else {
        value_error(msg)
    }
}

impl PyHeightField {
    pub fn field(&self) -> &HeightField {
        &self.hf
    }
}

#[pymethods]
impl PyHeightField {
    #[new]
    fn new(heights_nm: PyReadonlyArray2<'_, f64>, dx_nm: f64, dy_nm: f64) -> PyResult<Self> {
        let a = heights_nm.as_array();
        let (rows, cols) = a.dim();
        let hf = HeightField::new(rows, cols, dx_nm, dy_nm, a.iter().copied().collect()).map_err(value_error)?;
        Ok(Self { hf })
    }

    #[getter]
    fn heights_nm<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        Array2::from_shape_vec((self.hf.rows, self.hf.cols), self.hf.heights_nm.clone())
            .expect("shape")
            .into_pyarray(py)
    }
    #[getter]
    fn dx_nm(&self) -> f64 {
        self.hf.dx_nm
    }
    #[getter]
    fn dy_nm(&self) -> f64 {
        self.hf.dy_nm
    }
    /// Source, format, the unit heights were stored in, notes, warnings and the channel read (the keys of
    /// [`iridis_surface::Metadata`]).
    #[getter]
    fn meta<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        // The reader's notes and warnings in a Python caller's words, as its errors are.
        let mut meta = self.hf.meta.clone();
        for line in meta.notes.iter_mut().chain(meta.warnings.iter_mut()) {
            *line = crate::args::in_python_terms(line);
        }
        serialized(py, &meta)
    }

    /// A levelled copy: `none`, `mean`, `plane`, `rows`, `lines-median` or `poly` (the CLI's `--level`).
    fn level(&self, how: &str) -> PyResult<Self> {
        Ok(Self { hf: prep::level_by_name(&self.hf, how).map_err(value_error)? })
    }

    /// `iridis surface info --json` of this field (the facade's `iridis_api::surface::info`), as JSON text:
    /// the dominant periods (at most `peaks`), roughness and radial PSDF/ACF of the plane-levelled field, and
    /// the physics warnings for a window of `coherence_nm`.
    fn info_json(&self, py: Python<'_>, peaks: usize, coherence_nm: f64) -> PyResult<String> {
        if !(coherence_nm.is_finite() && coherence_nm > 0.0) {
            return Err(value_error(format!("coherence_nm = {coherence_nm}: must be a positive, finite number")));
        }
        Ok(py.allow_threads(|| iridis_api::surface::info(&self.hf, peaks, coherence_nm).to_string()))
    }

    /// The table `iridis surface info` prints (warnings apart) for the report `json` of [`Self::info_json`].
    #[staticmethod]
    fn info_text_of(json: &str) -> PyResult<String> {
        let r: serde_json::Value = serde_json::from_str(json).map_err(value_error)?;
        Ok(iridis_api::surface_info::info_text(&r))
    }

    /// Writes `surface info`'s figures (`--image`, `--psdf`, `--acf`: PNG paths, or None), titled `name`.
    #[pyo3(signature = (name, image=None, psdf=None, acf=None))]
    fn figures(
        &self,
        py: Python<'_>,
        name: &str,
        image: Option<std::path::PathBuf>,
        psdf: Option<std::path::PathBuf>,
        acf: Option<std::path::PathBuf>,
    ) -> PyResult<()> {
        let figures = iridis_api::surface_info::InfoFigures {
            image: image.as_deref(),
            psdf: psdf.as_deref(),
            acf: acf.as_deref(),
        };
        run(py, |r| {
            with_outputs(|| {
                for (flag, p) in [("image", figures.image), ("psdf", figures.psdf), ("acf", figures.acf)] {
                    iridis_api::output::declare_opt(flag, p, &["png"])?;
                }
                iridis_api::surface_info::write_figures(&self.hf, name, figures, r)
            })
        })
    }

    /// Writes the field as `iridis surface convert`/`generate` do: the format from the extension (.gwy, .gsf,
    /// .npy, .npz, .png, .txt), with a sidecar where the format has no units.
    fn write(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        run(py, |_| {
            with_outputs(|| {
                iridis_api::surface_info::declare_surface("", &path)?;
                iridis_api::surface_info::write_surface(&self.hf, &path)
            })
        })
    }

    /// `surface convert`'s steps after levelling: crop (`"ROW,COL,ROWS,COLS"`), resample (pixel size, nm), tile
    /// (`"NYxNX"`), pad (`"ROWSxCOLS"`).
    #[pyo3(signature = (crop=None, resample_nm=None, tile=None, pad=None))]
    fn reshape(
        &self,
        py: Python<'_>,
        crop: Option<String>,
        resample_nm: Option<f64>,
        tile: Option<String>,
        pad: Option<String>,
    ) -> PyResult<Self> {
        let steps = iridis_api::surface_info::Reshape { crop, resample_nm, tile, pad };
        let hf = run(py, |_| steps.apply(self.hf.clone()))?;
        Ok(Self { hf })
    }

    /// Roughness of the field as it is (level it first): `sq_nm`, `sa_nm`, `skewness`, `excess_kurtosis`,
    /// `sz_nm`, `correlation_length_nm`, the keys of `iridis surface info --json`'s `roughness`.
    fn roughness<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let r = py.allow_threads(|| stats::roughness(&self.hf));
        serialized(py, &r)
    }
}

/// Loads a SURFACE as the CLI does: a file (AFM instrument formats, `.npy`, `.npz`, PNG/TIFF, text) or
/// `builtin:NAME[?size=…&pixel=…&seed=…]`.
#[pyfunction]
#[pyo3(signature = (spec, channel=None, pixel_size_nm=None, max_height_nm=None, height_unit=None,
                     override_units=false, as_height=false))]
#[allow(clippy::too_many_arguments)] // Python's keyword arguments, one a CLI flag.
fn load_height_field(
    py: Python<'_>,
    spec: &str,
    channel: Option<&str>,
    pixel_size_nm: Option<f64>,
    max_height_nm: Option<f64>,
    height_unit: Option<String>,
    override_units: bool,
    as_height: bool,
) -> PyResult<PyHeightField> {
    let channel = channel.map(|c| c.parse::<ChannelSel>()).transpose().map_err(value_error)?;
    let opts = LoadOptions {
        pixel_size_nm,
        max_height_nm,
        channel,
        height_unit,
        override_units,
        as_height,
        ..Default::default()
    };
    let hf = py.allow_threads(|| load_surface(spec, &opts)).map_err(|e| surface_error(spec, e))?;
    Ok(PyHeightField { hf })
}

/// A built-in nanostructure as `iridis surface generate KIND --PARAM VALUE …` makes it (the same library call,
/// `iridis_api::surface_info::generate`, every kind the CLI has): `params` as (name, value) texts.
#[pyfunction]
fn generate_height_field(py: Python<'_>, kind: &str, params: Vec<(String, String)>) -> PyResult<PyHeightField> {
    let hf = run(py, |_| iridis_api::surface_info::generate(kind, &params))?;
    Ok(PyHeightField { hf })
}

/// The channels of an instrument file: `(json, text)` as `iridis surface channels [--json]` prints them.
#[pyfunction]
fn surface_channels(py: Python<'_>, path: std::path::PathBuf) -> PyResult<(String, String)> {
    let c = run(py, |_| iridis_api::surface_info::channels(&path))?;
    Ok((c.to_json().to_string(), c.text()))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyHeightField>()?;
    add_functions!(m, [load_height_field, generate_height_field, surface_channels]);
    Ok(())
}
