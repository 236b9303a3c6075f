//! `iridis view` (the `viewer` feature): the interactive window on a scene, a lookup table or a SURFACE's table,
//! and its scripted check (`--check`: synthetic input, a screenshot, the report as text and JSON).

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use iridis_diffraction::table::TableParams;
use iridis_gpu::viewer::{run, CheckReport, ViewInput, ViewOptions};
use serde_json::{json, Value};

use crate::report::Report;
use crate::{ModelOptions, SurfaceOptions};

fn load_for_view(p: &Path) -> std::result::Result<iridis_render::Scene, String> {
    iridis_render::load_scene(p).map_err(|e| e.to_string())
}

/// u-v samples per axis of the table `view` builds from a SURFACE when not told (smaller than
/// [`TableParams::default`]'s 501: the window opens in seconds).
pub const VIEW_UV_RESOLUTION: usize = 201;

/// Opens the window on INPUT (a scene .toml/.gltf/.glb, a TABLE or a SURFACE whose table is built at
/// `uv_resolution`, default [`VIEW_UV_RESOLUTION`], first) until it is closed; with `check`, drives it with
/// synthetic input, writes the screenshot there (PNG, declared first) and returns what the check saw. Options
/// that only shape a SURFACE's table, given with a scene or a finished TABLE, are refused: they would be ignored.
pub fn view(
    input: &str,
    uv_resolution: Option<usize>,
    surface: &SurfaceOptions,
    check: Option<&Path>,
    report: &dyn Report,
) -> Result<Option<ViewCheck>> {
    crate::output::declare_opt("--check", check, &["png"])?;
    let path = Path::new(input);
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let what = if matches!(ext.as_deref(), Some("toml" | "gltf" | "glb")) {
        if !path.exists() {
            bail!("scene {} does not exist", path.display());
        }
        let given: Vec<String> =
            uv_resolution.map(|n| format!("--uv-resolution {n}")).into_iter().chain(surface.flags()).collect();
        if !given.is_empty() {
            bail!(
                "{input} is a scene, so {} would be ignored: these options shape the table `iridis view` builds \
                 from a SURFACE; a scene's materials name their own tables and surfaces",
                given.join(" ")
            );
        }
        ViewInput::Scene(path.to_path_buf())
    } else {
        let grid = crate::model::TableGrid { uv_resolution, uv_power: None };
        crate::model::refuse_build_options_for_table(input, grid, surface, "`iridis view`")?;
        let params = grid.params_or(TableParams { uv_resolution: VIEW_UV_RESOLUTION, ..TableParams::default() })?;
        let table = crate::model::lookup_table(None, input, &ModelOptions::default(), params, surface, report)?;
        ViewInput::Table { table: Box::new(table), name: input.to_string() }
    };
    let opts = ViewOptions { check: check.map(Path::to_path_buf) };
    let seen = run(what, opts, load_for_view).map_err(anyhow::Error::msg)?;
    let (Some(r), Some(shot)) = (seen, check) else { return Ok(None) };
    if let Some((w, h, rgba)) = &r.screenshot {
        let rgb: Vec<u8> = rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
        crate::output::write_png_rgb8(shot, *w as u32, *h as u32, &rgb)?;
    }
    Ok(Some(ViewCheck { report: r, screenshot: shot.to_path_buf() }))
}

/// What the scripted check saw, and where its screenshot went.
#[derive(Debug)]
pub struct ViewCheck {
    pub report: CheckReport,
    pub screenshot: PathBuf,
}

impl ViewCheck {
    /// Whether every input changed what is shown and the window drew exactly the rendered frame.
    pub fn ok(&self) -> bool {
        let r = &self.report;
        r.steps.len() == 4 && r.steps.iter().all(|(_, d)| *d > 0.0) && r.texture_equals_frame
    }

    /// The check as an error when it failed (after its report is shown).
    pub fn verdict(&self) -> Result<()> {
        if !self.report.texture_equals_frame {
            bail!("the texture the window drew differs from the rendered frame (a present-pass defect)");
        }
        if !self.ok() {
            bail!("the viewer did not answer every input (a change of 0 above)");
        }
        Ok(())
    }

    pub fn to_json(&self) -> Value {
        let r = &self.report;
        json!({
            "adapter": r.adapter,
            "frames": r.frames,
            "frame_ms_median": r.frame_ms,
            "gpu_ms_median": r.gpu_ms,
            "readback_ms_median": r.readback_ms,
            "texture_equals_frame": r.texture_equals_frame,
            "steps": r.steps.iter().map(|(n, d)| json!({"input": n, "change": d})).collect::<Vec<_>>(),
            "screenshot": self.screenshot.display().to_string(),
            "ok": self.ok(),
        })
    }

    pub fn text(&self) -> String {
        let r = &self.report;
        let mut t = vec![format!("viewer check on {}: {} frames, median {:.1} ms", r.adapter, r.frames, r.frame_ms)];
        if let Some(g) = r.gpu_ms {
            t.push(format!("  render pass (GPU timestamps): median {g:.2} ms"));
        }
        t.push(format!(
            "  frames shown without a readback: the texture {} the frame; a readback would add a median {:.2} ms",
            if r.texture_equals_frame { "equals" } else { "DIFFERS FROM" },
            r.readback_ms
        ));
        t.extend(r.steps.iter().map(|(n, d)| format!("  {n}: change {d:.3}")));
        t.push(format!("wrote {}", self.screenshot.display()));
        t.join("\n")
    }
}
