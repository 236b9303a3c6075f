//! `iridis.render`: a scene (TOML or glTF) rendered into an array on the CPU (`iridis_render`) or on the GPU
//! (the facade's `iridis_api::gpu::render_scene`, what `iridis render --gpu` calls), before the CLI would
//! encode the file.

use std::path::Path;

use iridis_api::scene::RenderRequest;
use iridis_render::gltf_io::GltfOptions;
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;

/// Renders the scene at `path` through the library's `iridis_api::scene::render_image` (what `iridis render`
/// renders before it writes the files): `width`, `height`, `spp`, `exposure` default to the scene's own; `gpu`
/// on the GPU (a `ValueError` naming the driver to install when there is no adapter), `spectral_samples` its
/// direct film evaluation; a glTF scene's `camera` (by name) and its lights (`ignore_gltf_lights`). The
/// renderer's notes and warnings as Python's. Returns a dict with `linear_srgb` (float32, shape (height, width,
/// 3), before exposure), the `exposure` (RU), `spp` and `device` (where it ran).
#[pyfunction]
#[pyo3(signature = (path, width=None, height=None, spp=None, gpu=false, exposure=None, spectral_samples=None, camera=None, ignore_gltf_lights=false))]
#[allow(clippy::too_many_arguments)]
fn render_scene<'py>(
    py: Python<'py>,
    path: &str,
    width: Option<u32>,
    height: Option<u32>,
    spp: Option<u32>,
    gpu: bool,
    exposure: Option<f64>,
    spectral_samples: Option<usize>,
    camera: Option<String>,
    ignore_gltf_lights: bool,
) -> PyResult<Bound<'py, PyDict>> {
    if !Path::new(path).exists() {
        return Err(PyOSError::new_err(format!("scene {path}: no such file")));
    }
    let size = match (width, height) {
        (Some(w), Some(h)) => Some(format!("{w}x{h}")),
        (None, None) => None,
        _ => return Err(value_error("give both width and height, or neither")),
    };
    let request = RenderRequest {
        scene: path.into(),
        size,
        spp,
        exposure,
        gpu,
        spectral_samples,
        gltf: GltfOptions { camera, ignore_lights: ignore_gltf_lights },
        ..RenderRequest::default()
    };
    let r = crate::facade::run(py, |report| iridis_api::scene::render_image(&request, report))?;
    let (w, h) = r.size;
    let flat: Vec<f32> = r.image.data.iter().flatten().copied().collect();
    let arr = Array3::from_shape_vec((h as usize, w as usize, 3), flat).expect("shape");
    let out = PyDict::new(py);
    let a: Bound<'py, PyArray3<f32>> = arr.into_pyarray(py);
    out.set_item("linear_srgb", a)?;
    out.set_item("exposure", r.exposure)?;
    out.set_item("spp", r.spp)?;
    out.set_item("device", r.device)?;
    Ok(out)
}

/// `iridis render SCENE --export-mesh GLB`: the scene's triangle meshes (positions, normals, UVs, the orientation
/// field as TANGENT), camera and lights written as binary glTF, through the same library call; returns the line
/// that says what was written.
#[pyfunction]
#[pyo3(signature = (path, glb, camera=None, ignore_gltf_lights=false))]
fn export_mesh(
    py: Python<'_>,
    path: &str,
    glb: std::path::PathBuf,
    camera: Option<String>,
    ignore_gltf_lights: bool,
) -> PyResult<String> {
    if !Path::new(path).exists() {
        return Err(PyOSError::new_err(format!("scene {path}: no such file")));
    }
    let request = RenderRequest {
        scene: path.into(),
        export_mesh: Some(glb),
        gltf: GltfOptions { camera, ignore_lights: ignore_gltf_lights },
        ..RenderRequest::default()
    };
    let r = crate::facade::run(py, |report| {
        crate::scan_report::with_outputs(|| iridis_api::scene::render_file(&request, report))
    })?;
    Ok(r.lines.join("\n"))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(m, [render_scene, export_mesh]);
    Ok(())
}
