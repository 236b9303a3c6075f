//! `iridis view`: the interactive window on the GPU (`iridis_api::view`). The GPU's benchmark is
//! `iridis bench gpu` (cmd/bench.rs); `render --gpu` and `brdf-map --gpu` are library calls of their commands.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args as ClapArgs;

use crate::progress::Cli;

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Opens a window that renders on the GPU (the shaders of `iridis render --gpu` and `brdf-map --gpu`): a
scene (.toml, .gltf, .glb), reloaded when the file changes, or the BRDF map of a lookup table (.npz from
`iridis precompute`) or of a SURFACE (its table is built first). The panel sets the exposure (RU) and gamma,
the thin films' thickness, layer IOR and SVT strength, and shows each diffraction table's BRDF map at a
chosen incidence; the frame time is shown below. Drag to orbit, right-drag (or shift-drag) to move the
light, wheel to zoom, R resets, H toggles the help, Esc quits. On a BRDF map, drag to turn the light's
incidence and the wheel sets the exposure.

Needs a display and a Vulkan driver; on a headless machine: xvfb-run -a iridis view SCENE.
--check drives the window with synthetic input (a drag to orbit, a right-drag for the light, the wheel,
the H key), checks that each changed what is shown, saves a screenshot of the window and exits (non-zero
if an input did nothing): the scripted check that CI runs under Xvfb with lavapipe.

Examples:
  iridis view examples/snake_elaphe.toml
  iridis view examples/soap_bubble.toml
  iridis view elaphe.npz                       BRDF map of a precomputed table
  iridis view builtin:blazed                   builds a 201² table first
  xvfb-run -a iridis view examples/soap_bubble.toml --check viewer.png --json")]
pub struct ViewArgs {
    /// A scene (.toml, .gltf, .glb), a lookup table (.npz) or a SURFACE.
    pub input: String,
    /// u-v resolution of the table built when INPUT is a SURFACE [default: 201]; refused with a scene or a
    /// TABLE.
    #[arg(long, value_name = "N")]
    pub uv_resolution: Option<usize>,
    /// Scripted check: drive the window with synthetic input, save a screenshot (PNG) here, exit.
    #[arg(long)]
    pub check: Option<PathBuf>,
    /// With --check: print the check's report as JSON.
    #[arg(long, requires = "check")]
    pub json: bool,
    #[command(flatten)]
    pub surface_opts: iridis_api::SurfaceOptions,
}

pub fn run_view(a: ViewArgs) -> Result<()> {
    let Some(c) = iridis_api::view::view(&a.input, a.uv_resolution, &a.surface_opts, a.check.as_deref(), &Cli)? else {
        return Ok(());
    };
    crate::output::print_answer(a.json, || Ok(c.to_json()), || c.text())?;
    c.verdict()
}
