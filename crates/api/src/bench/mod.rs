//! The benchmarks (`iridis bench …`, `iridis bench gpu`, Python's `python -m iridis.bench NAME`): speed measured
//! against a peer in the same run (numpy for FFT work, the slower methods for the lookup path, the CPU for the
//! GPU, grcwa for the rigorous solver) and accuracy against the ground truth. Nothing here is a test: tests
//! never depend on wall-clock time.
//!
//! Each harness is one function returning a [`Bench`]: the text a person reads and the JSON a script reads,
//! made from the same numbers. Progress goes to the caller's [`Report`](crate::Report); files (the saved
//! frames, the convergence plot) through the run's output set ([`crate::output`]).

pub mod diffraction;
pub mod gpu;
pub mod render;

use std::time::Duration;

use serde_json::{json, Value};

pub use crate::grating_bench::{bench_grating, GratingBenchOptions};

/// A benchmark's result: the human report (lines, no trailing newline) and the same numbers as JSON.
#[derive(Debug, Clone)]
pub struct Bench {
    text: String,
    json: Value,
}

impl Bench {
    pub(crate) fn new(text: Vec<String>, json: Value) -> Self {
        Self { text: text.join("\n"), json }
    }

    /// The report as `iridis bench …` prints it.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The report as `iridis bench … --json` prints it.
    pub fn to_json(&self) -> Value {
        self.json.clone()
    }
}

/// The rigorous solver against grcwa (`iridis bench grating`): [`bench_grating`]'s JSON and its text.
pub fn grating(o: &GratingBenchOptions, report: &dyn crate::Report) -> anyhow::Result<Bench> {
    let v = bench_grating(o, report)?;
    Ok(Bench { text: crate::grating_bench::text(&v), json: v })
}

/// The benches by the names `iridis bench NAME` and `python -m iridis.bench NAME` give them.
pub const NAMES: &[&str] = &["diffraction", "diffraction-accuracy", "diffraction-methods", "gpu", "render", "grating"];

/// The one ΔE statistics of every bench: displayed CIEDE2000 between matching colours (after one exposure,
/// clipped to the sRGB cube as a display shows them), `DeltaEStats::between`.
pub use iridis_thinfilm::accuracy::DeltaEStats;

/// Width of a text table's name column: its header's or the longest name's, whichever is wider (a scan's path,
/// a built-in with parameters and the figure scenes' names are longer than a fixed column).
pub(crate) fn name_column_width<'a>(header: &str, names: impl IntoIterator<Item = &'a str>) -> usize {
    names.into_iter().map(|n| n.chars().count()).fold(header.chars().count(), usize::max)
}

/// The pixels of a `size²` BRDF map that are view directions (inside the unit disk).
pub fn disk_pixels(size: usize) -> Vec<usize> {
    (0..size * size).filter(|&i| iridis_diffraction::map::view_direction(i % size, i / size, size).is_some()).collect()
}

/// The view direction of pixel `i` of a `size²` map (the normal outside the disk).
pub(crate) fn view_of(i: usize, size: usize) -> [f64; 3] {
    iridis_diffraction::map::view_direction(i % size, i / size, size).unwrap_or([0.0, 0.0, 1.0])
}

/// Up to `n` indices spread over `0..total`.
pub fn sample(total: usize, n: usize) -> Vec<usize> {
    let step = total.div_ceil(n).max(1);
    (0..total).step_by(step).collect()
}

/// min, median, p99 (nearest rank) and mean of frame times, in ms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameStats {
    pub min: f64,
    pub median: f64,
    pub p99: f64,
    pub mean: f64,
}

impl FrameStats {
    pub fn of(times: &[Duration]) -> Self {
        let mut ms: Vec<f64> = times.iter().map(|d| d.as_secs_f64() * 1e3).collect();
        ms.sort_by(f64::total_cmp);
        let rank = |q: f64| iridis_thinfilm::accuracy::nearest_rank(&ms, q);
        Self { min: ms[0], median: rank(0.5), p99: rank(0.99), mean: ms.iter().sum::<f64>() / ms.len() as f64 }
    }

    pub(crate) fn to_json(self) -> Value {
        json!({"min": self.min, "median": self.median, "p99": self.p99, "mean": self.mean})
    }
}
