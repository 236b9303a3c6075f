//! `iridis.render`: a scene (TOML or glTF) rendered into an array on the CPU (`iridis_render`) or on the GPU
//! (the facade's `iridis_api::gpu::render_scene`, what `iridis render --gpu` calls), before the CLI would
//! encode the file.

use std::path::Path;

use iridis_render::scene::{check_image_size, check_spp};
use iridis_render::{load_scene, render, RenderError};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;

/// Renders the scene at `path`; `width`, `height`, `spp` default to the scene's own; `gpu`: on the GPU (a
/// `ValueError` naming the driver to install when there is no adapter; the renderer's warnings as Python
/// warnings). Returns a dict with `linear_srgb` (float32, shape (height, width, 3), before exposure), the
/// scene's `exposure`, `notes` and `device` (`cpu` or the adapter's name).
#[pyfunction]
#[pyo3(signature = (path, width=None, height=None, spp=None, gpu=false))]
fn render_scene<'py>(
    py: Python<'py>,
    path: &str,
    width: Option<u32>,
    height: Option<u32>,
    spp: Option<u32>,
    gpu: bool,
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
    check_image_size(w, h).map_err(|e| value_error(format!("size {w}×{h}: {e}")))?;
    check_spp(spp).map_err(|e| value_error(format!("spp {spp}: {e}")))?;
    let (img, device) = if gpu {
        let r = crate::facade::run(py, |report| {
            iridis_api::gpu::render_scene(&scene, w, h, spp, Default::default(), report)
        })?;
        (r.image, r.adapter)
    } else {
        (py.allow_threads(|| render(&scene, w, h, spp, &|_| {})), "cpu".to_string())
    };
    let flat: Vec<f32> = img.data.iter().flatten().copied().collect();
    let arr = Array3::from_shape_vec((h as usize, w as usize, 3), flat).expect("shape");
    let out = PyDict::new(py);
    let a: Bound<'py, PyArray3<f32>> = arr.into_pyarray(py);
    out.set_item("linear_srgb", a)?;
    out.set_item("exposure", scene.output.exposure)?;
    out.set_item("spp", spp)?;
    out.set_item("notes", scene.notes.clone())?;
    out.set_item("device", device)?;
    Ok(out)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(m, [render_scene]);
    Ok(())
}
