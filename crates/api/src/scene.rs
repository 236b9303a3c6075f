//! Scenes (TOML or glTF) rendered to files: `iridis render` ([`render_file`]), the example scenes embedded so
//! that the demo and the benchmark run anywhere ([`EXAMPLES`], [`write_examples`]), and the demo's sections of
//! rendered scenes ([`figures_section`], [`demo_section`]).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use iridis_gpu::scene::SceneFilm;
use iridis_gpu::FilmPath;
use iridis_render::gltf_io::GltfOptions;
use iridis_render::scene::MAX_IMAGE_SIDE;
use iridis_render::{Image, Scene};

use crate::gallery::Gallery;
use crate::report::{with_progress, Report};

/// The demo's sections report through the gallery's log only (a [`Gallery`] carries no [`Report`]).
use crate::report::Quiet;

/// Parses an image size `WxH` (`1024x768`, `1024×768`), 1 to [`MAX_IMAGE_SIDE`] (16384) pixels a side.
pub fn parse_size(s: &str) -> Result<(u32, u32)> {
    let (w, h) =
        s.split_once(['x', 'X', '×']).with_context(|| format!("--size '{s}': write WIDTHxHEIGHT, e.g. 1024x768"))?;
    let p = |v: &str| v.trim().parse::<u32>().ok().filter(|n| (1..=MAX_IMAGE_SIDE).contains(n));
    match (p(w), p(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => bail!("--size '{s}': width and height must be whole numbers from 1 to {MAX_IMAGE_SIDE}"),
    }
}

/// Loads a scene (a glTF file's camera and lights chosen by `gltf`); its notes and warnings go to `report`.
pub fn load(path: &Path, gltf: &GltfOptions, report: &dyn Report) -> Result<Scene> {
    let scene = iridis_render::load_scene_with(path, gltf).map_err(anyhow::Error::new)?;
    for n in &scene.notes {
        report.note(n);
    }
    for w in &scene.warnings {
        report.warn(w);
    }
    Ok(scene)
}

/// Renders on the CPU (all cores) with progress over rows; returns the image and the seconds it took.
pub fn render_cpu(scene: &Scene, w: u32, h: u32, spp: u32, report: &dyn Report) -> (Image, f64) {
    let t = Instant::now();
    let img = with_progress(report, h as u64, "render", |p| iridis_render::render(scene, w, h, spp, p));
    (img, t.elapsed().as_secs_f64())
}

/// How `--spectral-samples N` shades films on the GPU: colour tables without it, else the direct evaluation at
/// N wavelength samples over 380–780 nm.
pub fn scene_film(spectral_samples: Option<usize>) -> Result<SceneFilm> {
    use iridis_thinfilm::spectral::{sampled_weights, FULL_BAND_NM};
    Ok(match spectral_samples {
        None => SceneFilm::default(),
        Some(n) => {
            sampled_weights(n, FULL_BAND_NM).with_context(|| format!("--spectral-samples {n}"))?;
            SceneFilm { path: FilmPath::Direct, spectral_samples: n }
        }
    })
}

/// What `iridis render` is asked for (with the feature `cli`, its arguments but the glTF options).
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
// The field docs are `--help` text too, where `[output]` names a scene table, not a link.
#[allow(rustdoc::broken_intra_doc_links)]
pub struct RenderRequest {
    /// Scene: TOML (.toml) or glTF 2.0 (.gltf, .glb).
    pub scene: PathBuf,
    /// Output image: .png (tone-mapped) or .exr (linear float).
    // `None` with `export_mesh` only.
    #[cfg_attr(feature = "cli", arg(short, long, required_unless_present = "export_mesh"))]
    pub output: Option<PathBuf>,
    /// Image size WxH (default: the scene's [output] size).
    #[cfg_attr(feature = "cli", arg(long))]
    pub size: Option<String>,
    /// Samples per pixel for anti-aliasing (default: the scene's).
    #[cfg_attr(feature = "cli", arg(long))]
    pub spp: Option<u32>,
    /// Exposure in RU (default: the scene's; 1 RU: a normal-incidence mirror under a 1 RU light is white).
    #[cfg_attr(feature = "cli", arg(long))]
    pub exposure: Option<f64>,
    /// Also write the linear image as OpenEXR here.
    #[cfg_attr(feature = "cli", arg(long))]
    pub exr: Option<PathBuf>,
    /// Render on the GPU (wgpu, Vulkan; Mesa's lavapipe on machines without one).
    #[cfg_attr(feature = "cli", arg(long))]
    pub gpu: bool,
    /// Also (or, without -o, only) write the scene's triangle meshes as binary glTF (.glb): positions,
    /// normals, UVs and the orientation field as TANGENT.
    #[cfg_attr(feature = "cli", arg(long))]
    pub export_mesh: Option<PathBuf>,
    /// With --gpu: evaluate smooth films directly at N wavelength samples (380-780 nm) per hit instead of
    /// from colour tables (81: the 5 nm reference).
    #[cfg_attr(feature = "cli", arg(long, value_name = "N"))]
    pub spectral_samples: Option<usize>,
    /// glTF: the camera and the lights (`iridis render --camera --ignore-gltf-lights`).
    #[cfg_attr(feature = "cli", arg(skip))]
    pub gltf: GltfOptions,
}

/// A render written to its files.
#[derive(Debug)]
pub struct Rendered {
    /// The image (linear sRGB, before exposure); `None` when only the meshes were exported.
    pub image: Option<Image>,
    /// What was written, a line each (`wrote …`).
    pub lines: Vec<String>,
}

/// A scene's image as [`render_image`] renders it.
#[derive(Debug)]
pub struct RenderedImage {
    /// Linear sRGB, before exposure.
    pub image: Image,
    /// The exposure (RU) the files take: the one given, or the scene's.
    pub exposure: f64,
    pub size: (u32, u32),
    pub spp: u32,
    /// The render's time (s) and where it ran ("2 threads", "the GPU" and its adapter).
    pub seconds: f64,
    pub device: String,
}

/// A PNG whose every pixel is black is said: no light reaches the camera, or the exposure is too low for what
/// does (with the exposure that would show it).
fn warn_if_black(img: &iridis_render::Image, exposure: f64, encoding: iridis_color::Encoding, report: &dyn Report) {
    // The encoding is monotone in each channel: the image is black when its brightest pixel is (one pixel tone
    // mapped, not the image a second time).
    let peak = |p: &[f32; 3]| p.iter().fold(0.0f32, |m, &c| m.max(c));
    let Some(brightest) = img.data.iter().filter(|p| peak(p).is_finite()).max_by(|a, b| peak(a).total_cmp(&peak(b)))
    else {
        return;
    };
    let one = iridis_render::Image { width: 1, height: 1, data: vec![*brightest] };
    if one.to_rgb8(exposure, encoding).iter().any(|&c| c > 0) {
        return;
    }
    let brightest = peak(brightest) as f64;
    if brightest > 0.0 {
        report.warn(&format!(
            "the image is black at exposure {} RU: its brightest channel is {brightest:.3e} (linear sRGB), white \
             at --exposure {:.4e} RU",
            iridis_color::spectrum::short_number(exposure),
            1.0 / brightest
        ));
    } else {
        report.warn("the image is black: no light reaches the camera (check the lights and the camera's view)");
    }
}

/// The other end, for an exposure given (`--exposure 1e30` wrote a white image without a word): most of the lit
/// pixels clipped (a channel at white) show where the light is more than its colours; said, with the exposure that puts the 99th
/// percentile of the lit pixels at white. A scene's own exposure is its author's choice and is not judged.
fn warn_if_clipped(img: &iridis_render::Image, exposure: f64, report: &dyn Report) {
    let mut lit: Vec<f64> = img
        .data
        .iter()
        .map(|p| p.iter().fold(0.0f32, |m, &c| m.max(c)) as f64)
        .filter(|&v| crate::lit::is_lit(v))
        .collect();
    let clipped = lit.iter().filter(|&&v| v * exposure >= 1.0).count() as f64 / lit.len().max(1) as f64;
    if clipped <= 0.5 {
        return;
    }
    lit.sort_by(f64::total_cmp);
    let p99 = lit[((lit.len() - 1) as f64 * 0.99).round() as usize];
    report.warn(&format!(
        "{:.0} % of the image's lit pixels are clipped at --exposure {} RU (a channel at white): the image shows where \
         the light is more than its colours; --exposure {} RU puts the 99th percentile of them at white",
        100.0 * clipped,
        iridis_color::spectrum::short_number(exposure),
        iridis_color::spectrum::short_number(1.0 / p99)
    ));
}

/// The checks of what shapes an image (size, samples, exposure, spectral samples), before the scene is read;
/// returns the size asked for.
fn check_image_options(a: &RenderRequest) -> Result<Option<(u32, u32)>> {
    let size = a.size.as_deref().map(parse_size).transpose()?;
    if let Some(s) = a.spp {
        iridis_render::scene::check_spp(s).map_err(|e| anyhow::anyhow!("--spp {s}: {e}"))?;
    }
    if let Some(x) = a.exposure {
        if !(x.is_finite() && x > 0.0) {
            bail!("--exposure {x}: must be a positive number of RU");
        }
    }
    if a.spectral_samples.is_some() && !a.gpu {
        bail!("--spectral-samples sets the GPU's direct film evaluation; add --gpu (the CPU evaluates films at 81 samples)");
    }
    Ok(size)
}

/// The image of `a`'s scene (its glTF camera and lights as `a.gltf` says), on the CPU or the GPU, at `a`'s size,
/// samples and exposure or the scene's: `iridis render` before the files, and Python's `iridis.render.render`.
pub fn render_image(a: &RenderRequest, report: &dyn Report) -> Result<RenderedImage> {
    let size = check_image_options(a)?;
    let film = scene_film(a.spectral_samples)?;
    let scene = load(&a.scene, &a.gltf, report)?;
    render_loaded(&scene, a, size, film, report)
}

/// [`render_image`] of a scene already loaded (`iridis render` exports its meshes from the same), at the checked
/// `size` or the scene's.
fn render_loaded(
    scene: &Scene,
    a: &RenderRequest,
    size: Option<(u32, u32)>,
    film: SceneFilm,
    report: &dyn Report,
) -> Result<RenderedImage> {
    let (w, h) = size.unwrap_or((scene.output.width, scene.output.height));
    let spp = a.spp.unwrap_or(scene.output.spp);
    let exposure = a.exposure.unwrap_or(scene.output.exposure);
    let (image, seconds, device) = if a.gpu {
        let smooth_film = |m: &iridis_render::material::Material| matches!(m, iridis_render::material::Material::ThinFilm(f) if f.rough.is_none());
        if let Some(n) = a.spectral_samples.filter(|_| !scene.materials.iter().any(smooth_film)) {
            report.note(&format!(
                "--spectral-samples {n} evaluates smooth thin films directly; {} has none (rough films and the \
                 other materials take their colour tables), so it changes nothing here",
                a.scene.display()
            ));
        }
        let r = crate::gpu::render_scene(scene, w, h, spp, film, report)?;
        (r.image, r.seconds, format!("the GPU {}", r.adapter))
    } else {
        let (img, secs) = render_cpu(scene, w, h, spp, report);
        (img, secs, format!("{} threads", rayon::current_num_threads()))
    };
    Ok(RenderedImage { image, exposure, size: (w, h), spp, seconds, device })
}

/// `iridis render`: checks every input before the (possibly long) render, then exports the meshes and renders
/// the image on the CPU or the GPU into the run's output set; nothing is written unless all succeeds.
pub fn render_file(a: &RenderRequest, report: &dyn Report) -> Result<Rendered> {
    let fmt = crate::output::declare_opt("-o", a.output.as_deref(), &["png", "exr"])?;
    crate::output::declare_opt("--exr", a.exr.as_deref(), &["exr"])?;
    crate::output::declare_opt("--export-mesh", a.export_mesh.as_deref(), &["glb"])?;
    let start = Instant::now();
    let size = check_image_options(a)?;
    if a.output.is_none() {
        // Only the meshes are exported: what shapes the image would change nothing.
        let given: Vec<&str> = [
            ("--size", a.size.is_some()),
            ("--spp", a.spp.is_some()),
            ("--exposure", a.exposure.is_some()),
            ("--exr", a.exr.is_some()),
            ("--gpu", a.gpu),
        ]
        .into_iter()
        .filter_map(|(flag, given)| given.then_some(flag))
        .collect();
        if !given.is_empty() {
            bail!(
                "{} would be ignored: without -o no image is rendered (--export-mesh alone writes the meshes); give \
                 -o IMAGE to render too",
                given.join(", ")
            );
        }
    }
    let film = scene_film(a.spectral_samples)?;
    let scene = load(&a.scene, &a.gltf, report)?;
    let mut lines = Vec::new();
    if let Some(path) = &a.export_mesh {
        let (glb, notes) = iridis_render::gltf_export::scene_glb(&scene).map_err(anyhow::Error::new)?;
        for n in notes {
            report.note(&format!("{}: {n}", path.display()));
        }
        crate::output::write_bytes(path, &glb)?;
        let tris: usize = scene.meshes.iter().map(|m| m.triangles.len()).sum();
        lines.push(format!(
            "wrote {} ({} meshes, {tris} triangles, {} materials, camera and lights)",
            path.display(),
            scene.meshes.len(),
            scene.materials.len()
        ));
    }
    let (Some(output), Some(fmt)) = (&a.output, fmt) else { return Ok(Rendered { image: None, lines }) };
    let RenderedImage { image: img, exposure, size: (w, h), spp, seconds: secs, device } =
        render_loaded(&scene, a, size, film, report)?;
    let bytes = match fmt.as_str() {
        "exr" => img.encode_exr(exposure)?,
        _ => {
            warn_if_black(&img, exposure, scene.output.encoding, report);
            if a.exposure.is_some() {
                warn_if_clipped(&img, exposure, report);
            }
            img.encode_png(exposure, scene.output.encoding)?
        }
    };
    crate::output::write_bytes(output, &bytes)?;
    if let Some(e) = &a.exr {
        crate::output::write_bytes(e, &img.encode_exr(exposure)?)?;
    }
    lines.push(format!(
        "wrote {} ({w}×{h}, {spp} spp, {:.2} s in all, of which the render {secs:.2} s on {device})",
        output.display(),
        start.elapsed().as_secs_f64()
    ));
    Ok(Rendered { image: Some(img), lines })
}

/// The example scenes, embedded so that the demo and the benchmark run anywhere.
pub const EXAMPLES: &[(&str, &str)] = &[
    ("fig1_elaphe_section.toml", include_str!("../../../examples/fig1_elaphe_section.toml")),
    ("fig1_elaphe_section_light_b.toml", include_str!("../../../examples/fig1_elaphe_section_light_b.toml")),
    ("fig1_elaphe_section_bare.toml", include_str!("../../../examples/fig1_elaphe_section_bare.toml")),
    ("fig1_elaphe_section_bare_light_b.toml", include_str!("../../../examples/fig1_elaphe_section_bare_light_b.toml")),
    ("fig18_xenopeltis_a.toml", include_str!("../../../examples/fig18_xenopeltis_a.toml")),
    ("fig18_xenopeltis_b.toml", include_str!("../../../examples/fig18_xenopeltis_b.toml")),
    ("fig18_xenopeltis_c.toml", include_str!("../../../examples/fig18_xenopeltis_c.toml")),
    ("snake_studio.toml", include_str!("../../../examples/snake_studio.toml")),
    ("laser_screen.toml", include_str!("../../../examples/laser_screen.toml")),
    ("snake_elaphe.toml", include_str!("../../../examples/snake_elaphe.toml")),
    ("snake_elaphe_backlit.toml", include_str!("../../../examples/snake_elaphe_backlit.toml")),
    ("snake_xenopeltis.toml", include_str!("../../../examples/snake_xenopeltis.toml")),
    ("snake_xenopeltis_backlit.toml", include_str!("../../../examples/snake_xenopeltis_backlit.toml")),
    ("soap_bubble.toml", include_str!("../../../examples/soap_bubble.toml")),
    ("oil_spill.toml", include_str!("../../../examples/oil_spill.toml")),
    ("gold_sphere.toml", include_str!("../../../examples/gold_sphere.toml")),
    ("gltf_iridescence.toml", include_str!("../../../examples/gltf_iridescence.toml")),
    ("rough_film.toml", include_str!("../../../examples/rough_film.toml")),
];
/// Files the example scenes refer to.
pub const EXAMPLE_FILES: &[(&str, &[u8])] = &[
    ("iridescent_spheres.gltf", include_bytes!("../../../examples/iridescent_spheres.gltf")),
    ("elaphe_skin.png", include_bytes!("../../../examples/elaphe_skin.png")),
    ("xenopeltis_skin.png", include_bytes!("../../../examples/xenopeltis_skin.png")),
    ("studio.hdr", include_bytes!("../../../examples/studio.hdr")),
    ("unit_box.obj", include_bytes!("../../../examples/unit_box.obj")),
];

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

/// The paper's figures as scenes (issue 19), in the gallery's first section: (scene, caption).
const FIGURES: &[(&str, &str)] = &[
    (
        "fig18_xenopeltis_a",
        "Figure 18(a), first view: a section of a sunbeam snake (Xenopeltis unicolor), 15 rows of smooth scale \
         plates with the Xenopeltis-like nanostructure along each scale's long axis, 800 RU, no texture, light \
         overhead",
    ),
    (
        "fig18_xenopeltis_b",
        "Figure 18(a), second view: along the body from the head's side, light from behind the tail",
    ),
    ("fig18_xenopeltis_c", "Figure 18(a), third view: from above the tail end, light low from the head's side"),
    (
        "fig1_elaphe_section",
        "Figure 1, with texture, light A: a corn snake's (Elaphe guttata) skin, 27 rows of keeled scale plates \
         with the Elaphe-like nanostructure, its colour pattern blended in by Algorithm 4",
    ),
    ("fig1_elaphe_section_light_b", "Figure 1, with texture, light B (above, from the head's side)"),
    ("fig1_elaphe_section_bare", "Figure 1, without texture (the diffraction colour alone), light A"),
    ("fig1_elaphe_section_bare_light_b", "Figure 1, without texture, light B"),
    (
        "snake_studio",
        "A sunbeam snake in a studio: lit only by a procedural studio HDR (softboxes), which the diffraction \
         material takes as 64 directional lights",
    ),
    (
        "laser_screen",
        "The laser experiment of sec. 6.2 in 3-D: a beam meets the Elaphe sample at 45° and its reflection lands \
         on a screen parallel to the beam",
    ),
];

/// The gallery's first section: the paper's figures as scenes at their own size (1024 px wide), each beside
/// the BRDF map its centre pixel comes from.
pub fn figures_section(g: &mut Gallery) -> Result<()> {
    g.section(
        "Snake skin as in the paper's figures",
        "Close-ups of snake skin whose scales are individually curved, overlapping plates (iridis-render's \
         procedural snake: keeled Elaphe scales, smooth Xenopeltis scales; the nanostructure's axis along each \
         scale's long axis), framed like the paper's Figures 1 and 18, a snake in a studio, and the laser \
         experiment. Next to each render is the BRDF map it comes from: the lookup table's colour for every view \
         direction under the light that lights the centre pixel, in that pixel's surface frame (θi, φi), the \
         circle marking the direction towards the camera — the centre pixel shows the map's colour there. Each \
         render: `iridis render scenes/NAME.toml -o NAME.png`.",
    );
    let dir = g.path("scenes");
    write_examples(&dir)?;
    for (name, caption) in FIGURES {
        let scene = load(&dir.join(format!("{name}.toml")), &Default::default(), &Quiet)?;
        let (w, h, spp) = (scene.output.width, scene.output.height, scene.output.spp);
        let (img, secs) = render_cpu(&scene, w, h, spp, &Quiet);
        let file = format!("render_{name}.png");
        crate::output::write_bytes(&g.path(&file), &img.encode_png(scene.output.exposure, scene.output.encoding)?)?;
        g.image(&file, &format!("{name}: {caption}. {w}×{h}, {spp} spp, {secs:.1} s on the CPU."));
        if let Some((map, title)) = figure_map(&scene) {
            let file = format!("brdf_{name}.png");
            crate::output::write_png_rgb8(&g.path(&file), map.width, map.height, &map.data)?;
            g.image(&file, &title);
        }
    }
    Ok(())
}

/// The BRDF map a figure's centre pixel comes from, drawn with the view direction marked: for a laser, the
/// spot's reflection profile (what the screen shows); otherwise the diffraction material nearest the image's
/// centre under the brightest light there.
fn figure_map(scene: &Scene) -> Option<(iridis_plot::RgbImage, String)> {
    use iridis_color::{ToneMap, Xyz};
    use iridis_plot::{ImagePlot, RgbImage, Series};
    use iridis_render::light::Light;
    use iridis_render::material::Material;
    let size = 320usize;
    let plot = |xyz: Vec<Xyz>, exposure: f64, title: String, marker: Option<[f64; 3]>| {
        let tone = ToneMap { exposure_ru: exposure, encoding: iridis_color::Encoding::Srgb };
        let pixels = RgbImage {
            width: size as u32,
            height: size as u32,
            data: xyz.iter().flat_map(|&p| tone.to_rgb8(p)).collect(),
        };
        let overlays = marker
            .map(|v| {
                let (xs, ys): (Vec<f64>, Vec<f64>) = (0..=32)
                    .map(|k| {
                        let a = std::f64::consts::TAU * k as f64 / 32.0;
                        (v[0] + 0.05 * a.cos(), v[1] + 0.05 * a.sin())
                    })
                    .unzip();
                let mut s = Series::new("view", &xs, &ys);
                s.color = Some([255, 255, 255]);
                vec![s]
            })
            .unwrap_or_default();
        ImagePlot { overlays, ..ImagePlot::view_directions(title, &pixels, (560, 600)) }.render().ok()
    };
    let angles = |v: [f64; 3]| (v[2].clamp(-1.0, 1.0).acos().to_degrees(), v[1].atan2(v[0]).to_degrees());
    if let Some(Light::Laser(spot)) = scene.lights.iter().find(|l| matches!(l, Light::Laser(_))) {
        let iridis_render::texture::Texture::Image { width, data, .. } = &spot.profile else { return None };
        // Resampled to the map's size (nearest texel).
        let xyz = (0..size * size)
            .map(|k| {
                let (c, r) = ((k % size) * width / size, (k / size) * width / size);
                let p = &data[(r * width + c) * 3..(r * width + c) * 3 + 3];
                Xyz::from_linear_srgb([p[0] as f64, p[1] as f64, p[2] as f64])
            })
            .collect();
        let (ti, _) = angles([0.0, 0.0, spot.cos_in]);
        let title = format!("the laser spot's reflection: θi = {ti:.0}°, 1500 RU");
        let m = plot(xyz, 1500.0, title.clone(), None)?;
        return Some((m, format!("What the screen shows: the sample's BRDF map at the beam's incidence ({title})")));
    }
    let aspect = scene.output.width as f64 / scene.output.height as f64;
    // The diffraction pixel nearest the image's centre that a light reaches, on a 41 × 41 grid.
    let mut grid: Vec<(f64, f64)> =
        (0..41 * 41).map(|k| ((k % 41) as f64 / 20.0 - 1.0, (k / 41) as f64 / 20.0 - 1.0)).collect();
    grid.sort_by(|a, b| (a.0 * a.0 + a.1 * a.1).total_cmp(&(b.0 * b.0 + b.1 * b.1)));
    let view = grid.into_iter().find_map(|(x, y)| scene.local_view(x, y, aspect).filter(|v| !v.lights.is_empty()))?;
    let Material::Diffraction(df) = &scene.materials[view.material] else { return None };
    let lum = |e: [f64; 3]| 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2];
    let (wi, e) = view.lights.iter().copied().max_by(|a, b| lum(a.1).total_cmp(&lum(b.1)))?;
    let xyz = iridis_diffraction::map::brdf_map(df.evaluator.as_ref(), wi, size, 1, &|_| {});
    let (ti, pi) = angles(wi);
    let exposure = df.scale_ru * lum(e);
    let title = format!("BRDF map: θi = {ti:.0}°, φi = {pi:.0}°, {exposure:.0} RU");
    let m = plot(xyz, exposure, title.clone(), Some(view.view))?;
    Some((
        m,
        format!(
            "The BRDF map ({}) that the centre pixel comes from: {title}; circle: towards the camera",
            df.description
        ),
    ))
}

/// The demo's rendering section: every other example scene at a modest size.
pub fn demo_section(g: &mut Gallery) -> Result<()> {
    g.section(
        "Rendered scenes",
        "The other example scenes of examples/ rendered on the CPU (iridis-render): whole snakes whose scale \
         plates carry the Elaphe-like and Xenopeltis-like nanostructures (lookup tables of builtin:elaphe / \
         builtin:xenopeltis, nanostructure x axis along each scale, the thesis' texture blending) under two light \
         directions, a soap bubble draining (thin at the top, thick at the bottom), an oil film on wet asphalt, a \
         gold sphere, and a glTF file with KHR_materials_iridescence, and a thin film on a smooth and on a rough \
         substrate (the LSRS model: a dimmer mirror image and a coloured glossy lobe). The scene files are \
         written next to the images: `iridis render scenes/NAME.toml -o NAME.png --size 1024x768`.",
    );
    let scenes = write_examples(&g.path("scenes"))?;
    for p in scenes {
        let name = p.file_stem().and_then(|n| n.to_str()).unwrap_or("scene").to_string();
        if FIGURES.iter().any(|(f, _)| *f == name) {
            continue;
        }
        let scene = load(&p, &Default::default(), &Quiet)?;
        let (w, h) = (320, (320.0 * scene.output.height as f64 / scene.output.width as f64).round() as u32);
        let (img, secs) = render_cpu(&scene, w, h, 2, &Quiet);
        let file = format!("render_{name}.png");
        crate::output::write_bytes(&g.path(&file), &img.encode_png(scene.output.exposure, scene.output.encoding)?)?;
        g.image(
            &file,
            &format!("{name}: {w}×{h}, 2 spp, {secs:.1} s (iridis render scenes/{name}.toml -o {name}.png)"),
        );
    }
    Ok(())
}
