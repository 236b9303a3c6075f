//! The GPU paths the front ends share (`iridis render --gpu`, `brdf-map --gpu`, Python's `iridis.render` with
//! `gpu=True`): open the adapter, render a scene or a lookup BRDF map, and report the adapter.

use anyhow::Result;
use iridis_color::ToneMap;
use iridis_diffraction::encoding::TableEncoding;
use iridis_diffraction::{Fresnel, FresnelConvention, LookupTable};
use iridis_gpu::scene::SceneFilm;
use iridis_gpu::{Gpu, GpuLookup, GpuScene, MapOutput};

use crate::report::{with_progress, Report};

/// Opens the GPU (the library's error names the driver to install when there is none).
pub fn open() -> Result<Gpu> {
    Ok(Gpu::new()?)
}

/// A scene rendered on the GPU.
#[derive(Debug)]
pub struct GpuRender {
    pub image: iridis_render::Image,
    /// Upload, shader compilation, render and read-back.
    pub seconds: f64,
    pub adapter: String,
}

/// Renders a scene on the GPU with progress over bands of rows, its thin films shaded as `film` says (colour
/// tables by default); a shader stack that overflowed is a warning.
pub fn render_scene(
    scene: &iridis_render::Scene,
    w: u32,
    h: u32,
    spp: u32,
    film: SceneFilm,
    report: &dyn Report,
) -> Result<GpuRender> {
    let t = std::time::Instant::now();
    let gpu = open()?;
    let g = GpuScene::with_film(&gpu, scene, film)?;
    let img = with_progress(report, h as u64, "render (GPU)", |p| g.render(w, h, spp, p));
    if let Some(o) = g.stack_overflow() {
        report.warn(&o.to_string());
    }
    Ok(GpuRender { image: img?, seconds: t.elapsed().as_secs_f64(), adapter: gpu.adapter_name() })
}

/// A lookup BRDF map rendered on the GPU.
#[derive(Debug)]
pub struct GpuMap {
    /// The shader's XYZ per pixel and the tone-mapped image.
    pub output: MapOutput,
    /// Seconds of the map's dispatch (wall clock).
    pub map_seconds: f64,
    pub adapter: String,
}

/// The lookup method's BRDF map (paper eq. 10–12) of `table` on the GPU for light `wi`, the table stored as
/// `encoding` says: the shader's numbers, laid out as [`crate::brdf::render_map`]'s.
#[allow(clippy::too_many_arguments)]
pub fn lookup_map(
    gpu: &Gpu,
    table: &LookupTable,
    fresnel: Fresnel,
    shadowing: bool,
    convention: FresnelConvention,
    encoding: TableEncoding,
    wi: [f64; 3],
    size: usize,
    tone: ToneMap,
) -> Result<GpuMap> {
    let lookup = GpuLookup::encoded(gpu, table, fresnel, shadowing, encoding, u64::MAX)?.with_convention(convention);
    let frame = lookup.frame(size, tone)?;
    let map_seconds = frame.run(wi)?.wall.as_secs_f64();
    let output = frame.read()?;
    Ok(GpuMap { output, map_seconds, adapter: gpu.adapter_name() })
}
