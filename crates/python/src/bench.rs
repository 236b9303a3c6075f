//! `iridis.bench.run(NAME, **options)` and `python -m iridis.bench NAME`: the library's benches
//! (`iridis_api::bench`), the same harnesses `iridis bench NAME` runs, with the CLI's defaults. Files a bench
//! writes (`save`, `convergence_plot`) appear only when it succeeds, as from the CLI.

use std::path::PathBuf;

use iridis_api::bench::{self, diffraction, gpu, render, Bench};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;
use crate::facade::{run, Options};

/// Takes a list option out of the dict (the facade's `Options` reads scalars), `None` when absent or None.
fn take_list<'py, T: FromPyObject<'py>>(d: &Option<Bound<'py, PyDict>>, key: &str) -> PyResult<Option<Vec<T>>> {
    let Some(d) = d else { return Ok(None) };
    let Some(v) = d.get_item(key)? else { return Ok(None) };
    d.del_item(key)?;
    if v.is_none() {
        return Ok(None);
    }
    v.extract::<Vec<T>>().map(Some).map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!("{key} must be a list, got {}", v.get_type().name().unwrap()))
    })
}

fn path(o: &mut Options<'_>, key: &'static str) -> PyResult<Option<PathBuf>> {
    Ok(o.string(key)?.map(PathBuf::from))
}

/// A bench with its options read, run later without the GIL.
type PreparedBench = Box<dyn FnOnce(&dyn iridis_api::Report) -> anyhow::Result<Bench> + Send>;

/// Runs the bench `name` (`iridis_api::bench::NAMES`) with `options` (the CLI's option names with `_`, lengths
/// in nm); returns its text and its JSON as text.
#[pyfunction]
#[pyo3(signature = (name, options=None))]
fn bench_run(py: Python<'_>, name: &str, options: Option<Bound<'_, PyDict>>) -> PyResult<(String, String)> {
    let options = options.map(|d| d.copy()).transpose()?;
    let b: PreparedBench = match name {
        "diffraction" => {
            let d = diffraction::SpeedOptions::default();
            let map_sizes = take_list(&options, "map_sizes")?.unwrap_or(d.map_sizes);
            let mut o = Options::new(options);
            let a = diffraction::SpeedOptions {
                size: o.usize("size")?.unwrap_or(d.size),
                terms: o.usize("terms")?.unwrap_or(d.terms),
                map_sizes,
                uv_resolution: o.usize("uv_resolution")?.unwrap_or(d.uv_resolution),
            };
            o.finish()?;
            Box::new(move |r| diffraction::speed(&a, r))
        }
        "diffraction-accuracy" => {
            let d = diffraction::AccuracyOptions::default();
            let surfaces = take_list(&options, "surfaces")?.unwrap_or(d.surfaces);
            let exposures = take_list(&options, "exposures")?.unwrap_or(d.exposures);
            let mut o = Options::new(options);
            let a = diffraction::AccuracyOptions {
                surfaces,
                map_size: o.usize("map_size")?.unwrap_or(d.map_size),
                coherence_nm: o.positive("coherence_nm")?,
                aperture: o.string("aperture")?.unwrap_or(d.aperture),
                exposures,
                uv_resolution: o.usize("uv_resolution")?.unwrap_or(d.uv_resolution),
                convergence_plot: path(&mut o, "convergence_plot")?,
                surface_options: o.surface()?,
            };
            o.finish()?;
            Box::new(move |r| diffraction::accuracy(&a, r))
        }
        "diffraction-methods" => {
            let d = diffraction::MethodsOptions::default();
            let patch_sizes = take_list(&options, "patch_sizes")?.unwrap_or(d.patch_sizes);
            let mut o = Options::new(options);
            let a = diffraction::MethodsOptions { patch_sizes, map_size: o.usize("map_size")?.unwrap_or(d.map_size) };
            o.finish()?;
            Box::new(move |r| diffraction::methods(&a, r))
        }
        "gpu" => {
            let d = gpu::GpuBenchOptions::default();
            let mut o = Options::new(options);
            let a = gpu::GpuBenchOptions {
                scene: path(&mut o, "scene")?,
                size: o.string("size")?.unwrap_or(d.size),
                frames: o.usize("frames")?.unwrap_or(d.frames),
                max_seconds: o.f64("max_seconds")?.unwrap_or(d.max_seconds),
                table: path(&mut o, "table")?,
                film_size: o.string("film_size")?.unwrap_or(d.film_size),
                stack: o.string("stack")?.unwrap_or(d.stack),
                spectral_samples: o.usize("spectral_samples")?.unwrap_or(d.spectral_samples),
                save: path(&mut o, "save")?,
                table_precision: o.string("table_precision")?.unwrap_or(d.table_precision),
                build_surface: o.string("build_surface")?.unwrap_or(d.build_surface),
                build_uv_resolution: o.usize("build_uv_resolution")?.unwrap_or(d.build_uv_resolution),
                gt_surface: o.string("gt_surface")?.unwrap_or(d.gt_surface),
                gt_size: o.usize("gt_size")?.unwrap_or(d.gt_size),
                gt_cpu_pixels: o.usize("gt_cpu_pixels")?.unwrap_or(d.gt_cpu_pixels),
                surface_options: o.surface()?,
            };
            o.finish()?;
            Box::new(move |r| gpu::gpu(&a, r))
        }
        "render" => {
            let d = render::RenderOptions::default();
            let scenes = take_list::<String>(&options, "scenes")?.map(|v| v.into_iter().map(PathBuf::from).collect());
            let mut o = Options::new(options);
            let size = o.usize("size")?.map_or(Ok(d.size), u32::try_from).map_err(value_error)?;
            let spp = o.usize("spp")?.map_or(Ok(d.spp), u32::try_from).map_err(value_error)?;
            let a = render::RenderOptions { size, spp, scenes: scenes.unwrap_or(d.scenes) };
            o.finish()?;
            Box::new(move |r| render::render(&a, r))
        }
        "grating" => {
            let mut o = Options::new(options);
            let d = bench::GratingBenchOptions::default();
            let (python, peer_seconds) = (o.string("python")?, o.positive("peer_seconds")?);
            let no_python = o.bool("no_python")?.unwrap_or(false);
            if no_python && (python.is_some() || peer_seconds.is_some()) {
                return Err(value_error("python and peer_seconds would be ignored: no_python times no peer"));
            }
            let a = bench::GratingBenchOptions {
                repeats: o.usize("repeats")?.unwrap_or(d.repeats),
                python: if no_python { None } else { python.or(d.python) },
                peer_seconds: peer_seconds.unwrap_or(d.peer_seconds),
                batch: o.usize("batch")?.unwrap_or(d.batch),
                quick: o.bool("quick")?.unwrap_or(d.quick),
            };
            o.finish()?;
            Box::new(move |r| bench::grating(&a, r))
        }
        other => return Err(value_error(format!("no bench '{other}': the benches are {}", bench::NAMES.join(", ")))),
    };
    let b = run(py, |r| {
        let out = b(r);
        match &out {
            Ok(_) => iridis_api::output::commit()?,
            Err(_) => iridis_api::output::discard(),
        }
        out
    })?;
    Ok((b.text().to_string(), iridis_api::output::json_string(&b.to_json())))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(m, [bench_run]);
    Ok(())
}
