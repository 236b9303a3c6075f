//! `iridis render`: offline rendering of a scene (TOML or glTF) with the CPU renderer of `iridis-render`
//! (issue 7); `iridis bench render`; the demo's rendering section.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use iridis_render::{load_scene, render, Scene};

use crate::progress::bar;

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Renders a scene: a TOML file (camera, lights, environment, textures, materials, objects; see docs/render.md)
or a glTF 2.0 file (.gltf/.glb, KHR_materials_iridescence as a thin film; default camera and light). The
output format follows the extension: .png is tone-mapped (exposure in RU, sRGB), .exr is linear sRGB float.
Nothing is written unless the whole render succeeds.

Examples:
  iridis render examples/soap_bubble.toml -o bubble.png
  iridis render examples/snake_elaphe.toml -o snake.png --size 1024x768 --spp 4
  iridis render examples/gold_sphere.toml -o gold.exr
  iridis render examples/rough_film.toml -o rough.png --size 480x320   # films on rough substrates (LSRS)
  iridis render examples/iridescent_spheres.gltf -o gltf.png --size 512x512
  iridis render examples/snake_elaphe.toml -o snake_gpu.png --gpu      on the GPU (lavapipe without one)
  iridis render examples/soap_bubble.toml -o bubble_81.png --size 96x96 --gpu --spectral-samples 81

--gpu renders the same scene with the WGSL port of the renderer (iridis-gpu) through Vulkan; its colours
match the CPU's (mean CIEDE2000 < 1 on every example scene, tested). Thin films shade there from colour
tables (XYZ over angle and thickness, filled by the 81-sample evaluation; rough films' LSRS tables are made
on the CPU); --spectral-samples N evaluates smooth films directly at N wavelengths (380-780 nm) per hit
instead, 81 being the reference. Without a GPU, Mesa's software driver works:
apt-get install mesa-vulkan-drivers.")]
pub struct RenderArgs {
    /// Scene: TOML (.toml) or glTF 2.0 (.gltf, .glb).
    pub scene: PathBuf,
    /// Output image: .png (tone-mapped) or .exr (linear float).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Image size WxH (default: the scene's [output] size).
    #[arg(long)]
    pub size: Option<String>,
    /// Samples per pixel for anti-aliasing (default: the scene's).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Exposure in RU (default: the scene's; 1 RU: a normal-incidence mirror under a 1 RU light is white).
    #[arg(long)]
    pub exposure: Option<f64>,
    /// Also write the linear image as OpenEXR here.
    #[arg(long)]
    pub exr: Option<PathBuf>,
    /// Render on the GPU (wgpu, Vulkan; Mesa's lavapipe on machines without one).
    #[arg(long)]
    pub gpu: bool,
    /// With --gpu: evaluate smooth films directly at N wavelength samples (380-780 nm) per hit instead of
    /// from colour tables (81: the 5 nm reference).
    #[arg(long, value_name = "N")]
    pub spectral_samples: Option<usize>,
}

/// Parses `WxH`.
pub fn parse_size(s: &str) -> Result<(u32, u32)> {
    let (w, h) =
        s.split_once(['x', 'X', '×']).with_context(|| format!("--size '{s}': write WIDTHxHEIGHT, e.g. 1024x768"))?;
    let p = |v: &str| v.trim().parse::<u32>().ok().filter(|n| (1..=16384).contains(n));
    match (p(w), p(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => bail!("--size '{s}': width and height must be whole numbers from 1 to 16384"),
    }
}

/// Loads a scene, printing its notes.
pub fn load(path: &Path) -> Result<Scene> {
    let scene = load_scene(path).map_err(anyhow::Error::new)?;
    for n in &scene.notes {
        eprintln!("note: {n}");
    }
    Ok(scene)
}

/// Renders with a progress bar; returns the image and the seconds it took.
pub fn render_with_bar(scene: &Scene, w: u32, h: u32, spp: u32) -> (iridis_render::Image, f64) {
    let pb = bar(h as u64, "render");
    let t = Instant::now();
    let img = render(scene, w, h, spp, &|d| pb.set_position(d as u64));
    pb.finish_and_clear();
    (img, t.elapsed().as_secs_f64())
}

pub fn run(a: RenderArgs) -> Result<()> {
    // Check everything the user typed before the (possibly long) render.
    let fmt = crate::output::declare("-o", &a.output, &["png", "exr"])?;
    crate::output::declare_opt("--exr", a.exr.as_deref(), &["exr"])?;
    let start = Instant::now();
    let size = a.size.as_deref().map(parse_size).transpose()?;
    if let Some(s) = a.spp {
        if !(1..=4096).contains(&s) {
            bail!("--spp {s}: use 1 to 4096 samples per pixel");
        }
    }
    if let Some(x) = a.exposure {
        if !(x.is_finite() && x > 0.0) {
            bail!("--exposure {x}: must be a positive number of RU");
        }
    }
    if a.spectral_samples.is_some() && !a.gpu {
        bail!("--spectral-samples sets the GPU's direct film evaluation; add --gpu (the CPU evaluates films at 81 samples)");
    }
    let film = crate::cmd::gpu::scene_film(a.spectral_samples)?;
    let scene = load(&a.scene)?;
    let (w, h) = size.unwrap_or((scene.output.width, scene.output.height));
    let spp = a.spp.unwrap_or(scene.output.spp);
    let exposure = a.exposure.unwrap_or(scene.output.exposure);
    let (img, secs, device) = if a.gpu {
        let (img, secs, adapter) = crate::cmd::gpu::render_scene(&scene, w, h, spp, film)?;
        (img, secs, format!("the GPU {adapter}"))
    } else {
        let (img, secs) = render_with_bar(&scene, w, h, spp);
        (img, secs, format!("{} threads", rayon::current_num_threads()))
    };
    let bytes = match fmt.as_str() {
        "exr" => img.encode_exr(exposure)?,
        _ => img.encode_png(exposure, scene.output.encoding)?,
    };
    crate::output::write_bytes(&a.output, &bytes)?;
    if let Some(e) = &a.exr {
        crate::output::write_bytes(e, &img.encode_exr(exposure)?)?;
    }
    crate::outln!(
        "wrote {} ({w}×{h}, {spp} spp, {:.2} s in all, of which the render {secs:.2} s on {device})",
        a.output.display(),
        start.elapsed().as_secs_f64()
    )?;
    Ok(())
}

/// The example scenes, embedded so that the demo and the benchmark run anywhere.
pub const EXAMPLES: &[(&str, &str)] = &[
    ("snake_elaphe.toml", include_str!("../../../../examples/snake_elaphe.toml")),
    ("snake_elaphe_backlit.toml", include_str!("../../../../examples/snake_elaphe_backlit.toml")),
    ("snake_xenopeltis.toml", include_str!("../../../../examples/snake_xenopeltis.toml")),
    ("snake_xenopeltis_backlit.toml", include_str!("../../../../examples/snake_xenopeltis_backlit.toml")),
    ("soap_bubble.toml", include_str!("../../../../examples/soap_bubble.toml")),
    ("oil_spill.toml", include_str!("../../../../examples/oil_spill.toml")),
    ("gold_sphere.toml", include_str!("../../../../examples/gold_sphere.toml")),
    ("gltf_iridescence.toml", include_str!("../../../../examples/gltf_iridescence.toml")),
    ("rough_film.toml", include_str!("../../../../examples/rough_film.toml")),
];
/// Files the example scenes refer to.
pub const EXAMPLE_FILES: &[(&str, &[u8])] =
    &[("iridescent_spheres.gltf", include_bytes!("../../../../examples/iridescent_spheres.gltf"))];

/// Writes the embedded examples into `dir` and returns their paths.
pub fn write_examples(dir: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    for (name, bytes) in EXAMPLE_FILES {
        crate::output::write_now(&dir.join(name), bytes)?;
    }
    let mut out = Vec::new();
    for (name, text) in EXAMPLES {
        let p = dir.join(name);
        crate::output::write_now(&p, text.as_bytes())?;
        out.push(p);
    }
    Ok(out)
}

#[derive(Debug, ClapArgs)]
pub struct RenderBench {
    /// Image side (square images).
    #[arg(long, default_value_t = 1024)]
    pub size: u32,
    /// Samples per pixel.
    #[arg(long, default_value_t = 1)]
    pub spp: u32,
    /// Scenes to time (default: every example, embedded in the binary).
    #[arg(long)]
    pub scene: Vec<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// `iridis bench render`: load and render time of each example scene.
pub fn bench(a: RenderBench) -> Result<()> {
    let tmp = tempfile::tempdir()?;
    let scenes = if a.scene.is_empty() { write_examples(tmp.path())? } else { a.scene.clone() };
    let threads = rayon::current_num_threads();
    let mut rows = Vec::new();
    if !a.json {
        crate::outln!("render benchmark: {0}×{0}, {1} spp, {threads} threads", a.size, a.spp)?;
    }
    for p in &scenes {
        let t = Instant::now();
        let scene = load(p)?;
        let load_s = t.elapsed().as_secs_f64();
        let (_, secs) = render_with_bar(&scene, a.size, a.size, a.spp);
        let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("?").to_string();
        let tris: usize = scene.meshes.iter().map(|m| m.triangles.len()).sum();
        if !a.json {
            crate::outln!(
                "  {name:<28} load {load_s:6.2} s   render {secs:7.2} s   {:6.2} Mpixel/s   {tris} triangles",
                (a.size as f64).powi(2) / secs / 1e6
            )?;
        }
        rows.push(serde_json::json!({"scene": name, "load_s": load_s, "render_s": secs, "triangles": tris}));
    }
    if a.json {
        crate::output::print_json(&serde_json::json!({
            "size": a.size, "spp": a.spp, "threads": threads, "scenes": rows
        }))?;
    }
    Ok(())
}

/// The demo's rendering section: every example scene at a modest size.
pub fn demo(g: &mut crate::cmd::demo::Gallery) -> Result<()> {
    g.section(
        "Rendered scenes",
        "The example scenes of examples/ rendered on the CPU (iridis-render): snakes whose scales carry the \
         Elaphe-like and Xenopeltis-like nanostructures (lookup tables of builtin:elaphe / builtin:xenopeltis, \
         nanostructure x axis along the body, the thesis' texture blending) under two light directions, a soap \
         bubble draining (thin at the top, thick at the bottom), an oil film on wet asphalt, a gold sphere, and \
         a glTF file with KHR_materials_iridescence, and a thin film on a smooth and on a rough substrate \
         (the LSRS model: a dimmer mirror image and a coloured glossy lobe). The scene files are written next to the images: \
         `iridis render scenes/NAME.toml -o NAME.png --size 1024x768`.",
    );
    let scenes = write_examples(&g.path("scenes"))?;
    for p in scenes {
        let name = p.file_stem().and_then(|n| n.to_str()).unwrap_or("scene").to_string();
        let scene = load(&p)?;
        let (w, h) = (320, (320.0 * scene.output.height as f64 / scene.output.width as f64).round() as u32);
        let (img, secs) = render_with_bar(&scene, w, h, 2);
        let file = format!("render_{name}.png");
        crate::output::write_bytes(&g.path(&file), &img.encode_png(scene.output.exposure, scene.output.encoding)?)?;
        g.image(
            &file,
            &format!("{name}: {w}×{h}, 2 spp, {secs:.1} s (iridis render scenes/{name}.toml -o {name}.png)"),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse() {
        assert_eq!(parse_size("1024x768").unwrap(), (1024, 768));
        assert!(parse_size("1024").is_err());
        assert!(parse_size("0x5").is_err());
    }

    #[test]
    fn every_embedded_example_parses() {
        let dir = tempfile::tempdir().unwrap();
        for p in write_examples(dir.path()).unwrap() {
            // Tables are built on first use; cheap after that (cached).
            load(&p).unwrap_or_else(|e| panic!("{}: {e:#}", p.display()));
        }
    }
}
