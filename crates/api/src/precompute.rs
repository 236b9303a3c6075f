//! `iridis precompute` (and the table Python's `iridis.diffraction.precompute(…, gpu=…)` could build): the Taylor
//! terms and lookup tables of a height field on the CPU or the GPU, written as one .npz.

use std::path::Path;

use anyhow::{bail, Result};
use iridis_diffraction::table::TableParams;

use crate::model::{build_table, spectral_setup, taylor_terms, ModelOptions};
use crate::report::Report;
use crate::surface::{load_patch, SurfaceOptions};

/// What `iridis precompute` is asked for.
#[derive(Debug, Clone)]
pub struct PrecomputeRequest {
    /// The height field (a file or `builtin:NAME`).
    pub surface: String,
    pub surface_opts: SurfaceOptions,
    pub model: ModelOptions,
    pub params: TableParams,
    /// What the colours measure (relative: the paper's; radiometric: the BRDF).
    pub units: iridis_diffraction::Units,
    /// Build the tables on the GPU (values in f32).
    pub gpu: bool,
}

/// `iridis precompute`: the Taylor terms and lookup tables of a height field (on the CPU or the GPU) written
/// to `output` (.npz, declared first) through the run's output set; returns the line saying what was written.
pub fn precompute(r: &PrecomputeRequest, output: &Path, report: &dyn Report) -> Result<String> {
    if r.model.conserve_energy {
        bail!(
            "--conserve-energy would be ignored: it scales each wavelength's lobes, and a lookup table integrates \
             over wavelength in advance; brdf-map and brdf eval take it with --method reference or ground-truth"
        );
    }
    crate::output::declare("-o", output, &["npz"])?;
    let start = std::time::Instant::now();
    let patch = load_patch(&r.surface, &r.surface_opts, report)?;
    let mut spectral = spectral_setup(&r.model, report)?;
    let terms = taylor_terms(&patch, &r.model, report)?;
    if r.units == iridis_diffraction::Units::Radiometric {
        spectral = spectral.radiometric(terms.coherence_nm)?;
    }
    let res = r.params.uv_resolution;
    // The size is known once N is: say it before the long build and the write.
    let values = res * res * 3 * (2 * terms.n_max + 1);
    report.info(&format!(
        "{} will hold {res}² × 3 × {} values in f64: {:.1} MB",
        output.display(),
        2 * terms.n_max + 1,
        (values * 8) as f64 / 1e6
    ));
    let gpu = if r.gpu { Some(crate::gpu::open()?) } else { None };
    let table = build_table(gpu.as_ref(), &terms, &spectral, r.params, &r.surface, report)?;
    let mut buf = std::io::Cursor::new(Vec::new());
    table.write_npz(&mut buf)?;
    crate::output::write_bytes(output, buf.get_ref())?;
    Ok(format!(
        "wrote {} ({} tables of {res}², N = {}, {:.1} MB, {:.1} s)",
        output.display(),
        table.powers(),
        table.meta.taylor_terms,
        buf.get_ref().len() as f64 / 1e6,
        start.elapsed().as_secs_f64()
    ))
}
