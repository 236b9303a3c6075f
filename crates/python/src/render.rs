//! `iridis.render`: a scene (TOML or glTF) rendered on the CPU into an array, through `iridis_render` (what
//! `iridis render` does before it encodes the file).

use std::path::Path;

use iridis_render::{load_scene, render, RenderError};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;

/// Renders the scene at `path`; `width`, `height`, `spp` default to the scene's own. Returns a dict with
/// `linear_srgb` (float32, shape (height, width, 3), before exposure), the scene's `exposure`, `notes`.
#[pyfunction]
#[pyo3(signature = (path, width=None, height=None, spp=None))]
fn render_scene<'py>(
    py: Python<'py>,
    path: &str,
    width: Option<u32>,
    height: Option<u32>,
    spp: Option<u32>,
) -> PyResult<Bound<'py, PyDict>> {
    if !Path::new(path).exists() {
        return Err(PyOSError::new_err(format!("scene {path}: no such file")));
    }
    let scene = py.allow_threads(|| load_scene(Path::new(path))).map_err(|e| match e {
        RenderError::Io(e) => PyOSError::new_err(format!("scene {path}: {e}")),
        e => value_error(e),
    })?;
    let (w, h) = (width.unwrap_or(scene.output.width), height.unwrap_or(scene.output.height));
    let spp = spp.unwrap_or(scene.output.spp);
    if !(1..=16384).contains(&w) || !(1..=16384).contains(&h) {
        return Err(value_error(format!("size {w}×{h}: use 1 to 16384 pixels a side")));
    }
    if !(1..=4096).contains(&spp) {
        return Err(value_error(format!("spp {spp}: use 1 to 4096 samples per pixel")));
    }
    let img = py.allow_threads(|| render(&scene, w, h, spp, &|_| {}));
    let flat: Vec<f32> = img.data.iter().flatten().copied().collect();
    let arr = Array3::from_shape_vec((h as usize, w as usize, 3), flat).expect("shape");
    let out = PyDict::new(py);
    let a: Bound<'py, PyArray3<f32>> = arr.into_pyarray(py);
    out.set_item("linear_srgb", a)?;
    out.set_item("exposure", scene.output.exposure)?;
    out.set_item("spp", spp)?;
    out.set_item("notes", scene.notes.clone())?;
    Ok(out)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(render_scene, m)?)?;
    Ok(())
}
