//! `iridis.diffraction.brdf_map(…, gpu=True | f32=True | table_precision=…)` and
//! `iridis.diffraction.brdf_eval`: the very library calls of `iridis brdf-map` (`iridis_api::brdf_map::compute`,
//! on the CPU or the GPU) and `iridis brdf eval --json` (`iridis_api::brdf_eval`), on a SURFACE or TABLE argument.

use iridis_api::brdf_eval::{brdf_eval as eval, EvalRequest};
use iridis_api::brdf_map::{compute, MapRequest};
use iridis_api::model::TableGrid;
use iridis_color::Encoding;
use iridis_diffraction::geometry::direction;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::above;
use crate::diffraction::xyz_array;
use crate::facade::{json_to_py, run, Options};

/// `iridis brdf-map`'s map as the CLI computes it: a dict with `xyz` (linear XYZ of ρ, (size, size, 3)),
/// `per_sr` (f_r in sr⁻¹ as XYZ, with `per_sr=True`), `exposure_ru` (the one `auto_exposure` chose), `method`,
/// `coherence_nm`. Options: the model, surface and shading options of the module, `uv_resolution`,
/// `uv_power`, `exposure_ru`, `auto_exposure`, `per_sr`, `subsamples`, `f32`, `gpu`, `table_precision`, `material`,
/// `unit_cell`.
#[pyfunction]
#[pyo3(signature = (source, method, theta_i, phi_i, size, options=None))]
fn brdf_map_run<'py>(
    py: Python<'py>,
    source: String,
    method: Option<String>,
    theta_i: f64,
    phi_i: f64,
    size: usize,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (t, p) = above("incidence", (theta_i, phi_i))?;
    let mut o = Options::new(options);
    let (fresnel, convention, shadowing) = o.shading_text()?;
    let method = method.unwrap_or_else(|| "lookup".into());
    let (exposure_ru, auto_exposure) = (o.positive("exposure_ru")?, o.bool("auto_exposure")?.unwrap_or(false));
    let r = MapRequest {
        model: o.model()?,
        surface: o.surface()?,
        fresnel,
        convention,
        shadowing,
        wi: direction(t, p),
        size,
        exposure_ru: exposure_ru.unwrap_or(iridis_api::brdf_map::DEFAULT_EXPOSURE_RU),
        auto_exposure,
        encoding: Encoding::Srgb,
        grid: TableGrid { uv_resolution: o.usize("uv_resolution")?, uv_power: o.positive("uv_power")? },
        f32: o.bool("f32")?.unwrap_or(false),
        gpu: o.bool("gpu")?.unwrap_or(false),
        table_precision: o.string("table_precision")?,
        per_sr: o.bool("per_sr")?.unwrap_or(false),
        subsamples: o.usize("subsamples")?.unwrap_or(1),
        ..MapRequest::new(&source, &method)
    };
    o.finish()?;
    let m = run(py, |rep| compute(&r, None, rep))?;
    let d = PyDict::new(py);
    d.set_item("xyz", xyz_array(py, &m.xyz, m.size))?;
    d.set_item("per_sr", m.per_sr.as_ref().map(|f| xyz_array(py, f, m.size)))?;
    d.set_item("exposure_ru", m.tone.exposure_ru)?;
    d.set_item("method", &m.method)?;
    d.set_item("coherence_nm", m.coherence_nm)?;
    Ok(d)
}

/// `iridis brdf eval --json` as a dict (the same keys and numbers). Options as [`brdf_map_run`]'s, plus
/// `visual` (`--relative` changes only the CLI's text: the dict holds both ρ and f_r).
#[pyfunction]
#[pyo3(signature = (source, method, light, view, options=None))]
fn brdf_eval<'py>(
    py: Python<'py>,
    source: String,
    method: Option<String>,
    light: (f64, f64),
    view: (f64, f64),
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let (light, view) = (above("light", light)?, above("view", view)?);
    let mut o = Options::new(options);
    let (fresnel, convention, shadowing) = o.shading_text()?;
    let r = EvalRequest {
        input: source,
        method,
        model: o.model()?,
        surface: o.surface()?,
        fresnel,
        convention,
        shadowing,
        grid: TableGrid { uv_resolution: o.usize("uv_resolution")?, uv_power: o.positive("uv_power")? },
        light,
        view,
        visual: o.string("visual")?,
        relative: false,
    };
    o.finish()?;
    let (value, text) = run(py, |rep| {
        let e = eval(&r, None, rep)?;
        Ok((e.to_json()?, e.text()))
    })?;
    Ok((json_to_py(py, &value)?, text))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(m, [brdf_map_run, brdf_eval]);
    Ok(())
}
