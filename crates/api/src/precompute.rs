//! `iridis precompute` (and the table Python's `iridis.diffraction.precompute(…, gpu=…)` could build): the Taylor
//! terms and lookup tables of a height field on the CPU or the GPU, written as one .npz.

use std::path::Path;

use anyhow::Result;
use iridis_diffraction::table::TableParams;

use crate::model::{build_table, spectral_setup, taylor_terms, ModelOptions};
use crate::report::Report;
use crate::surface::{Source, SurfaceOptions};
use iridis_diffraction::table::LookupTable;

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

/// The Taylor terms and lookup tables of `source` as `r` asks (its `surface` aside: `source` is the height field),
/// on the CPU or the GPU, named `name` in the table's metadata; the size is said first, as `target` will hold it
/// (`iridis precompute`'s file, Python's Table). Refuses what a table cannot carry
/// ([`crate::brdf::refuse_for_lookup_table`]).
pub fn table_of(
    source: &Source,
    r: &PrecomputeRequest,
    name: &str,
    target: &str,
    report: &dyn Report,
) -> Result<LookupTable> {
    crate::brdf::refuse_for_lookup_table(&r.model)?;
    let patch = source.patch(&r.surface_opts, report)?;
    let mut spectral = spectral_setup(&r.model, report)?;
    let terms = taylor_terms(&patch, &r.model, report)?;
    if r.units == iridis_diffraction::Units::Radiometric {
        spectral = spectral.radiometric(terms.coherence_nm)?;
    }
    let res = r.params.uv_resolution;
    // The size is known once N is: say it before the long build and the write.
    let values = res * res * 3 * (2 * terms.n_max + 1);
    report.info(&format!(
        "{target} will hold {res}² × 3 × {} values in f64: {:.1} MB",
        2 * terms.n_max + 1,
        (values * 8) as f64 / 1e6
    ));
    if let Some(available) = available_memory_bytes().filter(|&a| (values as u64).saturating_mul(8) > a) {
        report.warn(&format!(
            "the table needs {:.1} GB in memory and this machine has {:.1} GB available: the build may be killed \
             or swap; lower --uv-resolution (memory grows with its square) or --terms",
            (values * 8) as f64 / 1e9,
            available as f64 / 1e9
        ));
    }
    let gpu = if r.gpu { Some(crate::gpu::open()?) } else { None };
    build_table(gpu.as_ref(), &terms, &spectral, r.params, name, report)
}

/// `iridis precompute`: [`table_of`] the SURFACE argument written to `output` (.npz, declared first) through the
/// run's output set; returns the line saying what was written.
pub fn precompute(r: &PrecomputeRequest, output: &Path, report: &dyn Report) -> Result<String> {
    crate::brdf::refuse_for_lookup_table(&r.model)?;
    crate::output::declare("-o", output, &["npz"])?;
    let start = std::time::Instant::now();
    let source = Source::Spec(r.surface.clone());
    let table = table_of(&source, r, &r.surface, &output.display().to_string(), report)?;
    let res = r.params.uv_resolution;
    let mut bytes = 0;
    crate::output::write_atomic(output, |w| {
        table.write_npz(&mut *w)?;
        bytes = w.stream_position()?;
        Ok(())
    })?;
    Ok(format!(
        "wrote {} ({} tables of {res}², N = {}, {:.1} MB, {:.1} s)",
        output.display(),
        table.powers(),
        table.meta.taylor_terms,
        bytes as f64 / 1e6,
        start.elapsed().as_secs_f64()
    ))
}

/// The memory the system says is available to a new allocation (Linux's `MemAvailable`); `None` elsewhere or when
/// it cannot be read, where no warning is given.
fn available_memory_bytes() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
