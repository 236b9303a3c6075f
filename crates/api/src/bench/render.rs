//! `iridis bench render`: load and render time of each example scene on the CPU.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;
use serde_json::json;

use super::Bench;
use crate::report::Report;
use crate::scene::{load, render_cpu, write_examples};

/// `iridis bench render`'s options (with the feature `cli`, its flags).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct RenderOptions {
    /// Image side (square images).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 1024))]
    pub size: u32,
    /// Samples per pixel.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 1))]
    pub spp: u32,
    /// Scenes to time (default: every example, embedded in the binary).
    #[cfg_attr(feature = "cli", arg(long = "scene", value_name = "SCENE"))]
    pub scenes: Vec<PathBuf>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self { size: 1024, spp: 1, scenes: Vec::new() }
    }
}

/// Load and render seconds, Mpixel/s and triangles of each scene.
pub fn render(a: &RenderOptions, report: &dyn Report) -> Result<Bench> {
    iridis_render::scene::check_image_size(a.size, a.size).map_err(|e| anyhow::anyhow!("--size {}: {e}", a.size))?;
    iridis_render::scene::check_spp(a.spp).map_err(|e| anyhow::anyhow!("--spp {}: {e}", a.spp))?;
    let tmp = tempfile::tempdir()?;
    let scenes = if a.scenes.is_empty() { write_examples(tmp.path())? } else { a.scenes.clone() };
    let threads = rayon::current_num_threads();
    let mut rows = Vec::new();
    let mut t = vec![format!("render benchmark: {0}×{0}, {1} spp, {threads} threads", a.size, a.spp)];
    let names: Vec<String> =
        scenes.iter().map(|p| p.file_name().and_then(|n| n.to_str()).unwrap_or("?").to_string()).collect();
    let width = super::name_column_width("", names.iter().map(String::as_str));
    for (p, name) in scenes.iter().zip(names) {
        let start = Instant::now();
        let scene = load(p, &Default::default(), report)?;
        let load_s = start.elapsed().as_secs_f64();
        let (_, secs) = render_cpu(&scene, a.size, a.size, a.spp, report);
        let tris: usize = scene.meshes.iter().map(|m| m.triangles.len()).sum();
        t.push(format!(
            "  {name:<width$} load {load_s:6.2} s   render {secs:7.2} s   {:6.2} Mpixel/s   {tris} triangles",
            (a.size as f64).powi(2) / secs / 1e6
        ));
        rows.push(json!({"scene": name, "load_s": load_s, "render_s": secs, "triangles": tris}));
    }
    Ok(Bench::new(t, json!({"size": a.size, "spp": a.spp, "threads": threads, "scenes": rows})))
}
