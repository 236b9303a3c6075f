//! `iridis.report`: the report of a scan (`iridis report`, `iridis_api::scan_report::write_report`),
//! `iridis.demo`: the gallery on built-in data (`iridis demo`, `iridis_api::demo::demo`), and the run's output set that the library's file-writing calls write through (committed when the call succeeds,
//! discarded when it fails, as the CLI does).

use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::facade::{run, Options};

/// Runs a facade call that writes files through the run's output set: the files appear together when it
/// succeeds, none when it fails.
pub fn with_outputs<T>(f: impl FnOnce() -> anyhow::Result<T>) -> anyhow::Result<T> {
    match f() {
        Ok(v) => {
            iridis_api::output::commit()?;
            Ok(v)
        }
        Err(e) => {
            iridis_api::output::discard();
            Err(e)
        }
    }
}

/// The report of `surface` written into `output`: returns `(report_json, text)` — `report.json`'s content and
/// what `iridis report` prints.
#[pyfunction]
#[pyo3(signature = (surface, output, options=None))]
fn _report(
    py: Python<'_>,
    surface: &str,
    output: &str,
    options: Option<Bound<'_, PyDict>>,
) -> PyResult<(String, String)> {
    let mut o = Options::new(options);
    let mut r = iridis_api::scan_report::ReportOptions::new(surface, std::path::Path::new(output));
    // Lengths as the CLI takes them ("5nm"), as the Python function documents.
    let s = &mut r.surface_options;
    s.channel = o.channel()?;
    s.pixel_size_nm = o.length_text_nm("pixel_size")?;
    s.max_height_nm = o.length_text_nm("max_height")?;
    s.height_unit = o.string("height_unit")?;
    s.level = o.string("level")?;
    s.units.override_units = o.bool("override_units")?.unwrap_or(false);
    s.units.as_height = o.bool("as_height")?.unwrap_or(false);
    r.size = o.usize("size")?.unwrap_or(r.size);
    r.coherence = o.string("coherence")?;
    r.visual = o.string("visual")?.unwrap_or(r.visual);
    r.no_testbench = !o.bool("testbench")?.unwrap_or(true);
    o.finish()?;
    run(py, |said| {
        with_outputs(|| {
            let rep = iridis_api::scan_report::write_report(&r, None, said)?;
            for w in &rep.warnings {
                iridis_api::Report::warn(said, w);
            }
            Ok((serde_json::to_string(&rep.json)?, rep.text()))
        })
    })
}

/// The demo gallery written into `out` (every section, or those in `only`): returns `(index, written)`, the
/// path of `index.html` and of every figure written, each also logged as `iridis demo` prints it.
#[pyfunction]
#[pyo3(signature = (out, only))]
fn _demo(py: Python<'_>, out: &str, only: Vec<String>) -> PyResult<(String, Vec<String>)> {
    let text = |p: &std::path::Path| p.to_string_lossy().into_owned();
    run(py, |said| {
        // The gallery names its figures; each is logged as `iridis demo` prints it.
        let (index, figures) = with_outputs(|| iridis_api::demo::demo(std::path::Path::new(out), &only, |_| {}))?;
        figures.iter().for_each(|f| iridis_api::Report::info(said, &format!("wrote {}", f.display())));
        Ok((text(&index), figures.iter().map(|f| text(f)).collect()))
    })
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(m, [_report, _demo]);
    m.add("DEMO_SECTIONS", iridis_api::demo::SECTIONS.map(|s| s.0).to_vec())?;
    Ok(())
}
