//! The scene renderer on the GPU (`shaders/scene.wgsl`): [`iridis_render`]'s ray caster — the same cameras,
//! geometry, BVH, materials, lights, environments and textures — one pixel per invocation, in `f32`.
//!
//! [`GpuScene::new`] flattens a loaded [`Scene`] into storage buffers (the layout is documented record by
//! record in the shader) and compiles the pipeline; [`GpuScene::frame`] allocates the output of one image size
//! and [`SceneFrame::run`] renders a frame (the viewer's path); [`GpuScene::render`] renders in bands of rows (so that
//! a progress bar moves and no dispatch runs for long), returning the same linear [`Image`] the CPU renders —
//! PNG and EXR encoding are shared.
//!
//! Thin films shade from colour tables by default (issue 17): a smooth film's reflected and transmitted XYZ
//! over `cos θ` × its SVT offset range, filled on the GPU by the direct evaluation ([`crate::film`]), and a rough
//! film's LSRS tables (`k_r`, `π k_d`, the diffuse albedo) made on the CPU
//! ([`iridis_thinfilm::rough_table`], [`iridis_render::material::ThinFilm::rough_env_table`]). A smooth film
//! that no table can follow (a critical angle inside its stack) and every smooth film under
//! [`FilmPath::Direct`] run the recurrence at every wavelength sample per hit.
//!
//! What the GPU does not evaluate, it refuses with a message at upload: diffraction materials whose evaluator
//! is not a lookup table (the scene format only makes lookup ones), incoherent film layers, and tables larger
//! than one storage binding.

use iridis_color::ToneMap;
use iridis_diffraction::geometry::{Fresnel, FresnelSource};
use iridis_render::area::{AreaLight, Shape};
use iridis_render::camera::Camera;
use iridis_render::integrate::{Integration, Strategy};
use iridis_render::light::{Environment, Light};
use iridis_render::material::{ColorSource, Material, Microfacet, OrientRule};
use iridis_render::render::sample_offset;
use iridis_render::sampling::Distribution2d;
use iridis_render::texture::Texture;
use iridis_render::{Image, Scene};
use iridis_thinfilm::spectral::FULL_BAND_NM;
use wgpu::util::DeviceExt;

use crate::film::{build_table, FilmPath};
use crate::lookup::{display_buffer, storage_out};
use crate::{
    dispatch, unpack_rgb8, xyz_to_srgb_words, FrameTime, Gpu, GpuError, Timer, COMMON_WGSL, FILM_WGSL, LOOKUP_WGSL,
    TURNS_WGSL,
};
use iridis_thinfilm::rough_table::RoughColorTable;
use iridis_thinfilm::table::{TableGrid, MAX_NODES, NODES_PER_PERIOD};
use iridis_thinfilm::Complex64;

/// The scene shader's source: the shared helpers, both models and the renderer.
pub(crate) fn scene_source() -> String {
    format!(
        "{COMMON_WGSL}\n{TURNS_WGSL}\n{LOOKUP_WGSL}\n{FILM_WGSL}\n{}\n{}\n{}",
        include_str!("shaders/film_rough.wgsl"),
        include_str!("shaders/scene.wgsl"),
        include_str!("shaders/extended.wgsl")
    )
}

// scene.wgsl's ALBEDO_COS and ALBEDO_AZ read the energy blend's albedo table with these sizes.
const _: () = assert!(iridis_render::lobe_albedo::COS_NODES == 10 && iridis_render::lobe_albedo::AZIMUTHS == 16);

/// Rows rendered per dispatch.
const BAND_ROWS: u32 = 32;
/// Samples per pixel of one pass of a Monte Carlo render (progressive accumulation).
pub const MC_PASS_SAMPLES: u32 = 8;
/// Largest samples per pixel, the renderers' limit (the sample offsets live in the scene buffer: space for
/// this many is reserved).
pub use iridis_render::scene::MAX_SPP;
use iridis_render::scene::{check_image_size, check_spp};

const NONE: u32 = u32::MAX;

/// `vec4<f32>` records with integer words bit-cast, as the shader reads them.
#[derive(Default)]
struct Records(Vec<[f32; 4]>);

impl Records {
    fn len(&self) -> u32 {
        self.0.len() as u32
    }
    fn push(&mut self, v: [f32; 4]) {
        self.0.push(v);
    }
    fn v3(&mut self, v: [f64; 3], w: f32) {
        self.0.push([v[0] as f32, v[1] as f32, v[2] as f32, w]);
    }
    fn v3w(&mut self, v: [f64; 3], w: u32) {
        self.v3(v, f32::from_bits(w));
    }
    fn words(&mut self, w: [u32; 4]) {
        self.0.push(w.map(f32::from_bits));
    }
    fn color(&mut self, c: &ColorSource) {
        match *c {
            ColorSource::Const(rgb) => self.v3w(rgb, NONE),
            ColorSource::Texture(i) => self.v3w([0.0; 3], i as u32),
        }
    }
    fn pad_to(&mut self, start: u32, n: u32) {
        while self.len() < start + n {
            self.0.push([0.0; 4]);
        }
    }
}

/// A scene uploaded to the GPU with its pipeline.
#[derive(Debug)]
pub struct GpuScene<'g> {
    gpu: &'g Gpu,
    pipeline: wgpu::ComputePipeline,
    scene: wgpu::Buffer,
    texels: wgpu::Buffer,
    media: wgpu::Buffer,
    weights: wgpu::Buffer,
    tables: wgpu::Buffer,
    /// The films' colour tables (binding 10).
    film_tables: wgpu::Buffer,
    grid_nm: Vec<f64>,
    /// The uniform words after the camera (environment, matrix, counts, offsets).
    layout: Layout,
    camera: Camera,
    lights: Vec<Light>,
    /// Texture number of the first laser spot's reflection profile (the profiles follow the scene's textures).
    first_profile: u32,
    area_lights: Vec<AreaLight>,
    output: iridis_render::scene::Output,
    /// The films' media as uploaded (the viewer's thickness, IOR and SVT controls rewrite copies of them).
    media_cpu: Vec<[f32; 2]>,
    films: Vec<FilmSlot>,
    last_overflow: std::sync::Mutex<Option<StackOverflow>>,
}

/// Where a thin-film material lives in the buffers.
#[derive(Debug, Clone)]
struct FilmSlot {
    /// vec4 index of its material record.
    record: u32,
    /// Its flags word (without the colour-table bit).
    flags: u32,
    /// vec4 index of its `[SVT texture, d_rel, factor]` record.
    svt_record: u32,
    svt: [f32; 4],
    media_base: usize,
    thick_base: usize,
    n_media: usize,
    /// The same film over a metallic base's metal ([`iridis_render::material::ThinFilm::metal_stack`]): its
    /// media block (same layers, the metal as substrate; thicknesses shared).
    metal_media_base: Option<usize>,
    /// A smooth film's room for a colour table in `film_tables`: first vec4 and nodes; `None`: evaluated
    /// directly (a rough film, or [`FilmPath::Direct`]).
    table: Option<(u32, usize)>,
}

/// How a scene's thin films are shaded on the GPU.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SceneFilm {
    /// Colour tables (the default) or the recurrence per hit for smooth films; rough films always use tables.
    pub path: FilmPath,
    /// Wavelength samples of the direct evaluation, evenly over 380–780 nm (81: 5 nm steps, the reference).
    pub spectral_samples: usize,
}

impl Default for SceneFilm {
    fn default() -> Self {
        Self { path: FilmPath::Table, spectral_samples: 81 }
    }
}

/// Interactive changes to every thin-film material of a scene (the viewer's panel).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmControls {
    /// Every layer's thickness is multiplied by this.
    pub thickness_scale: f64,
    /// A real refractive index for the first film layer at every wavelength, instead of its material.
    pub layer_ior: Option<f64>,
    /// The SVT amplitude `d_rel` is multiplied by this.
    pub svt_scale: f64,
}

impl Default for FilmControls {
    fn default() -> Self {
        Self { thickness_scale: 1.0, layer_ior: None, svt_scale: 1.0 }
    }
}

/// Where a list of records starts in the scene buffer (in vec4) and how many records it holds.
#[derive(Debug, Clone, Copy, Default)]
struct Span {
    base: u32,
    n: u32,
}

#[derive(Debug, Clone, Copy, Default)]
struct Layout {
    env: [[f32; 4]; 4],
    background: [f32; 4],
    env_kind: u32,
    env_tex: u32,
    env_visible: u32,
    spheres: Span,
    planes: Span,
    lights: Span,
    nodes: Span,
    tri_base: u32,
    mat_base: u32,
    tex_base: u32,
    sample_base: u32,
    n_lambda: u32,
    energy_base: u32,
    irr_tex: u32,
    /// The environment's directional lights in `tables` (6 floats each: direction, irradiance), NONE: none.
    env_light_base: u32,
    /// 0 fast, 1 Monte Carlo.
    integration: u32,
    seed: u32,
    area_lights: Span,
    /// The environment's importance sampler in `tables` (`[columns, rows]` then the distribution), NONE: none.
    env_cdf_base: u32,
}

/// Output buffers for one image size (the benchmark's and the viewer's frame loop), used with the
/// [`GpuScene`] that made it.
#[derive(Debug)]
pub struct SceneFrame {
    width: u32,
    height: u32,
    spp: u32,
    params: wgpu::Buffer,
    display: wgpu::Buffer,
    bind: wgpu::BindGroup,
    out_rgb: wgpu::Buffer,
    out_rgba: wgpu::Buffer,
    /// `[count, deepest depth]` of secondary rays that found the shader's ray stack full.
    overflow: wgpu::Buffer,
    timer: Option<Timer>,
}

/// Secondary rays that found the shader's ray stack (24 rays) full during a render: they took the
/// environment's radiance instead of being traced, so the image may lack some inter-reflections there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StackOverflow {
    /// How many rays were dropped.
    pub rays: u32,
    /// The deepest bounce at which one was.
    pub depth: u32,
}

impl std::fmt::Display for StackOverflow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the GPU's ray stack ({STACK} rays) overflowed: {} secondary rays, the deepest at bounce {}, took the \
             environment's light instead of being traced; lower [output] max_depth or render on the CPU for the \
             exact image",
            self.rays, self.depth
        )
    }
}

/// The largest coordinate (scene units) the GPU renderer takes. It works in f32: the triangle test multiplies a
/// ray's distance to a vertex by two edges, which passes f32's 3.4e38 for a mesh of 1e13 units seen from its own
/// size away (measured on lavapipe: black from 1e13, right at 1e12). The CPU renders in f64.
pub const MAX_GPU_COORDINATE: f64 = 1e11;

/// The largest absolute coordinate of what `scene` places: mesh vertices, spheres and planes (with their radius or
/// size), the camera, point lights, laser spots and area lights.
pub fn largest_coordinate(scene: &Scene) -> f64 {
    let norm = |v: &[f64; 3]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let vertices = scene.meshes.iter().flat_map(|m| m.positions.iter()).map(norm);
    let spheres = scene.spheres.iter().map(|s| norm(&s.center) + s.radius.abs());
    let planes = scene.planes.iter().map(|p| norm(&p.center) + p.size.map_or(0.0, |[w, h]| w.abs() + h.abs()));
    let camera = match &scene.camera {
        Camera::Perspective { position, .. } | Camera::Orthographic { position, .. } => norm(position),
        Camera::Hemisphere { target, distance, .. } => norm(target) + distance.abs(),
    };
    let lights = scene.lights.iter().map(|l| match l {
        Light::Directional { .. } => 0.0,
        Light::Point { position, .. } => norm(position),
        Light::Laser(spot) => norm(&spot.position),
    });
    let areas = scene.area_lights.iter().map(|a| match &a.shape {
        Shape::Sphere { center, radius } | Shape::Disk { center, radius, .. } => norm(center) + radius.abs(),
        Shape::Rectangle { center, size, .. } => norm(center) + size[0].abs() + size[1].abs(),
    });
    vertices.chain(spheres).chain(planes).chain(lights).chain(areas).fold(camera, f64::max)
}

/// Refuses a scene beyond [`MAX_GPU_COORDINATE`], which the GPU would render black or wrong.
fn check_f32_range(scene: &Scene) -> Result<(), GpuError> {
    let largest = largest_coordinate(scene);
    if largest > MAX_GPU_COORDINATE {
        return Err(GpuError::Invalid(format!(
            "the scene places something at {largest:.3e} units from the origin; the GPU renderer works in f32 and \
             takes coordinates up to {MAX_GPU_COORDINATE:.0e}: scale the scene down (a scene's unit is free) or \
             render it on the CPU (without --gpu), which works in f64"
        )));
    }
    Ok(())
}

/// Rays the shader's stack holds (`STACK` in scene.wgsl).
pub const STACK: u32 = 24;

impl<'g> GpuScene<'g> {
    /// Flattens `scene` into GPU buffers and compiles the renderer. Fails with a clear message for what the
    /// GPU path does not evaluate.
    pub fn new(gpu: &'g Gpu, scene: &Scene) -> Result<Self, GpuError> {
        Self::with_film(gpu, scene, SceneFilm::default())
    }

    /// As [`GpuScene::new`] with the thin films shaded as `film` says.
    pub fn with_film(gpu: &'g Gpu, scene: &Scene, film: SceneFilm) -> Result<Self, GpuError> {
        check_f32_range(scene)?;
        let mut rec = Records::default();
        let mut lay = Layout { sample_base: rec.len(), ..Default::default() };

        // Samples per pixel: the CPU's offsets, computed once in f64 (up to MAX_SPP, each spp its own set).
        // The shader reads sample s of an spp-sample pixel at sample_base + s; the sets differ per spp, so
        // the frame writes its own set (see SceneFrame::render); here only the room is reserved.
        rec.pad_to(lay.sample_base, MAX_SPP);

        lay.spheres.base = rec.len();
        for s in &scene.spheres {
            rec.v3(s.center, s.radius as f32);
            rec.words([s.material as u32, 0, 0, 0]);
        }
        lay.spheres.n = scene.spheres.len() as u32;

        lay.planes.base = rec.len();
        for p in &scene.planes {
            let [w, h] = p.size.unwrap_or([0.0, 0.0]);
            rec.v3w(p.center, u32::from(p.size.is_some()));
            rec.v3(p.normal, w as f32);
            rec.v3(p.tangent, h as f32);
            rec.push([f32::from_bits(p.material as u32), p.uv_unit as f32, 0.0, 0.0]);
        }
        lay.planes.n = scene.planes.len() as u32;

        lay.lights.base = rec.len();
        let first_profile = scene.textures.len() as u32;
        push_lights(&mut rec, &scene.lights, lay.lights.base, first_profile);
        lay.lights.n = scene.lights.len() as u32;

        lay.area_lights.base = rec.len();
        push_area_lights(&mut rec, &scene.area_lights);
        lay.area_lights.n = scene.area_lights.len() as u32;
        lay.integration = match scene.integration {
            Integration::Fast => 0,
            Integration::MonteCarlo(Strategy::Mis) => 1,
            Integration::MonteCarlo(other) => {
                return Err(GpuError::Invalid(format!(
                    "the GPU integrates extended light by multiple importance sampling only ({other:?} sampling is \
                     a check of the CPU renderer)"
                )))
            }
        };
        lay.seed = scene.output.seed as u32;
        // What extended light needs of a diffraction table (its lobe's sampler, its prefiltered tables):
        // uploaded where extended light exists.
        let extended = !matches!(scene.environment, Environment::None) || !scene.area_lights.is_empty();

        lay.nodes.base = rec.len();
        for n in scene.bvh.nodes() {
            rec.v3w(n.lo, n.start);
            rec.v3w(n.hi, n.count);
        }
        lay.nodes.n = scene.bvh.nodes().len() as u32;

        // Triangles in the BVH's primitive order, so a leaf's range indexes them directly.
        lay.tri_base = rec.len();
        for p in &scene.bvh.prims {
            let m = &scene.meshes[p.mesh as usize];
            let tri = p.tri as usize;
            let idx = m.triangles[tri].map(|i| i as usize);
            let flags = u32::from(m.uvs.is_some())
                | (u32::from(m.corner_tangents.is_some()) << 1)
                | (u32::from(m.along.is_some()) << 2);
            rec.v3w(m.positions[idx[0]], m.material as u32);
            rec.v3w(m.positions[idx[1]], flags);
            rec.v3(m.positions[idx[2]], 0.0);
            for &i in &idx {
                rec.v3(m.normals[i], 0.0);
            }
            let uv = |k: usize| m.uvs.as_ref().map(|u| u[idx[k]].map(|x| x as f32)).unwrap_or([0.0; 2]);
            let (a, b, c) = (uv(0), uv(1), uv(2));
            rec.push([a[0], a[1], b[0], b[1]]);
            rec.push([c[0], c[1], 0.0, 0.0]);
            for k in 0..3 {
                let t = m.corner_tangents.as_ref().map(|t| t[tri * 3 + k]).unwrap_or([0.0; 4]);
                rec.push(t.map(|x| x as f32));
            }
            for &i in &idx {
                rec.v3(m.along.as_ref().map(|a| a[i]).unwrap_or([0.0; 3]), 0.0);
            }
        }

        // Materials, their tables and films.
        let sw = iridis_thinfilm::spectral::sampled_weights(film.spectral_samples, FULL_BAND_NM)
            .map_err(|e| GpuError::Invalid(format!("--spectral-samples: {e}")))?;
        let grid = sw.wavelengths_nm().to_vec();
        lay.n_lambda = grid.len() as u32;
        let mut film_data: Vec<[f32; 4]> = Vec::new();
        let mut tables: Vec<f32> = Vec::new();
        let mut media: Vec<[f32; 2]> = Vec::new();
        let mut films = Vec::new();
        lay.mat_base = rec.len();
        for (mi, m) in scene.materials.iter().enumerate() {
            let start = rec.len();
            let name = scene.material_names.get(mi).map(String::as_str).unwrap_or("?");
            match m {
                Material::Lambert { color } => {
                    rec.words([0, 0, 0, 0]);
                    rec.color(color);
                }
                Material::Microfacet(mf) => {
                    rec.words([1, 0, 0, 0]);
                    push_microfacet(&mut rec, mf);
                }
                Material::Diffraction(df) => {
                    let lookup = df.evaluator.as_lookup().ok_or_else(|| {
                        GpuError::Invalid(format!(
                            "material `{name}`: the GPU renders diffraction from lookup tables only ({})",
                            df.description
                        ))
                    })?;
                    let fresnel = lookup.shading.fresnel.as_builtin().cloned().ok_or_else(|| {
                        GpuError::Invalid(format!(
                            "material `{name}`: its Fresnel factor ({}) has no GPU version",
                            lookup.shading.fresnel.describe()
                        ))
                    })?;
                    let t = &lookup.table;
                    let base = tables.len() as u32;
                    tables.extend(t.data.iter().map(|&v| v as f32));
                    let (flag_f, n_re, n_im) = match fresnel {
                        Fresnel::Schlick { n } => (0u32, n as f32, 0.0f32),
                        Fresnel::Index { n } => (2u32, n.re as f32, n.im as f32),
                    };
                    let f0 = fresnel.reflectance(500.0, 1.0) as f32;
                    let (rule, dir, otex) = match df.orientation.rule {
                        OrientRule::Tangent => (0u32, [0.0; 3], NONE),
                        OrientRule::Along => (1, [0.0; 3], NONE),
                        OrientRule::Direction(d) => (2, d, NONE),
                        OrientRule::Texture(i) => (3, [0.0; 3], i as u32),
                    };
                    rec.words([2, 0, 0, 0]);
                    rec.color(&df.texture);
                    rec.push([df.scale_ru as f32, df.w_diffuse as f32, df.ambient as f32, df.fresnel_n as f32]);
                    rec.v3w(dir, rule);
                    rec.push([df.orientation.angle as f32, f32::from_bits(otex), 0.0, 0.0]);
                    rec.words([
                        t.meta.uv_resolution as u32,
                        t.powers() as u32,
                        u32::from(lookup.shading.shadowing)
                            | flag_f
                            | crate::lookup::convention_flag(lookup.shading.convention),
                        base,
                    ]);
                    rec.push([(1.0 / t.meta.uv_power) as f32, f0, n_re, n_im]);
                    // [lobe distributions, prefiltered tables] (extended.wgsl).
                    let (mut lobe, mut pref) = (NONE, NONE);
                    if extended {
                        if let Some(ls) = df.lobe_sampler() {
                            lobe = tables.len() as u32;
                            push_lobe(&mut tables, ls, t.meta.uv_resolution);
                        }
                        if let Some(p) = df.prefiltered() {
                            pref = tables.len() as u32;
                            for v in [&p.f, &p.c, &p.r] {
                                tables.extend(v.iter().map(|&x| x as f32));
                            }
                        }
                    }
                    // The energy blend's lobe albedo (render::lobe_albedo: the nodes, then A_avg), NONE under
                    // Algorithm 4.
                    let mut albedo = NONE;
                    if let iridis_render::material::Blend::Energy(a) = &df.blend {
                        albedo = tables.len() as u32;
                        tables.extend(a.nodes().iter().flatten().map(|&v| v as f32));
                        tables.extend(a.average().map(|v| v as f32));
                    }
                    rec.words([lobe, pref, albedo, 0]);
                }
                Material::ThinFilm(f) => {
                    if f.stack.has_incoherent() {
                        return Err(GpuError::Invalid(format!(
                            "material `{name}`: incoherent (inc:) layers render on the CPU only; render this \
                             scene without --gpu"
                        )));
                    }
                    let n_media = f.stack.layers.len() + 2;
                    let media_base = media.len() as u32;
                    for &l in &grid {
                        for m in f.stack.materials() {
                            let n = m
                                .index_at(l)
                                .map_err(|e| GpuError::Invalid(format!("material `{name}`: stack {}: {e}", f.stack)))?;
                            media.push([n.re as f32, n.im as f32]);
                        }
                    }
                    let thick_base = media.len() as u32;
                    media.extend(f.stack.thicknesses().iter().map(|&d| [d as f32, 0.0]));
                    let flags = u32::from(f.svt.is_some())
                        | (u32::from(f.transmission) << 1)
                        | (u32::from(f.base.is_some()) << 2)
                        | (u32::from(f.rough.is_some()) << 4);
                    rec.words([3, 0, 0, 0]);
                    rec.words([n_media as u32, media_base, thick_base, flags]);
                    // A metallic base's film: the same layers over the metal, per wavelength after the thicknesses.
                    let metal_media_base = match &f.metal_stack {
                        Some(ms) => {
                            let b = media.len();
                            for &l in &grid {
                                for m in ms.materials() {
                                    let n = m.index_at(l).map_err(|e| {
                                        GpuError::Invalid(format!("material `{name}`: metal under the film: {e}"))
                                    })?;
                                    media.push([n.re as f32, n.im as f32]);
                                }
                            }
                            Some(b)
                        }
                        None => None,
                    };
                    let (svt_tex, d_rel) = f.svt.map(|s| (s.texture as u32, s.d_rel_nm as f32)).unwrap_or((NONE, 0.0));
                    let metal_word = metal_media_base.map_or(NONE, |b| b as u32);
                    let svt = [f32::from_bits(svt_tex), d_rel, f.factor as f32, f32::from_bits(metal_word)];
                    let svt_range = f.svt_range_nm();
                    // Room for a smooth film's colour table: enough for the viewer's controls at their
                    // extremes (thickness and SVT ×3, a layer index up to 2.6), at least 64 Ki nodes.
                    let table = match (f.rough, film.path) {
                        (None, FilmPath::Table) => TableGrid::for_stack(&f.stack, &grid, svt_range).ok().map(|g| {
                            let room = (g.len() * 18).clamp(1 << 16, MAX_NODES);
                            let base = film_data.len() as u32;
                            film_data.resize(film_data.len() + 2 * room, [0.0; 4]);
                            (base, room)
                        }),
                        _ => None,
                    };
                    films.push(FilmSlot {
                        record: start,
                        flags,
                        svt_record: rec.len(),
                        svt,
                        media_base: media_base as usize,
                        thick_base: thick_base as usize,
                        n_media,
                        metal_media_base,
                        table,
                    });
                    rec.push(svt);
                    if let Some(b) = &f.base {
                        push_microfacet(&mut rec, b);
                    }
                    if let Some(table) = f.rough_table() {
                        let table =
                            table.map_err(|e| GpuError::Invalid(format!("material `{name}`: rough film: {e}")))?;
                        push_rough_tables(&mut rec, &mut film_data, f, table);
                    }
                }
            }
            rec.pad_to(start, 8);
        }

        // The GGX energy table (render::energy), shared by every microfacet: E_0, E_1, then their averages.
        let energy = iridis_render::energy::table();
        lay.energy_base = tables.len() as u32;
        for v in [&energy.e0, &energy.e1, &energy.avg0, &energy.avg1] {
            tables.extend(v.iter().map(|&x| x as f32));
        }

        // The environment as directional lights (render::light::Environment::as_lights), for diffraction.
        lay.env_light_base = NONE;
        if !scene.environment_lights.is_empty() {
            assert_eq!(
                scene.environment_lights.len(),
                iridis_render::light::ENVIRONMENT_LIGHTS,
                "ENV_LIGHTS of scene.wgsl"
            );
            lay.env_light_base = tables.len() as u32;
            for (d, e) in &scene.environment_lights {
                tables.extend(d.iter().chain(e).map(|&x| x as f32));
            }
        }

        // The environment's importance sampler (Monte Carlo).
        // Uploaded whatever the integration, so that the viewer can switch to Monte Carlo.
        lay.env_cdf_base = NONE;
        let built;
        let sampler = match &scene.env_sampler {
            Some(s) => Some(s),
            None => {
                built = iridis_render::light::EnvSampler::new(&scene.environment);
                built.as_ref()
            }
        };
        if let Some(es) = sampler {
            lay.env_cdf_base = tables.len() as u32;
            tables.extend([es.dist.cols as f32, es.dist.rows as f32]);
            push_distribution(&mut tables, &es.dist);
        }

        // Textures (the environment map and its irradiance map last).
        lay.tex_base = rec.len();
        let mut textures: Vec<&Texture> = scene.textures.iter().collect();
        textures.extend(scene.lights.iter().filter_map(|l| match l {
            Light::Laser(spot) => Some(&spot.profile),
            _ => None,
        }));
        let mut texels: Vec<f32> = Vec::new();
        lay.env_visible = u32::from(scene.environment_visible);
        let m = scene.environment.mean();
        lay.env[3] = [m[0] as f32, m[1] as f32, m[2] as f32, 0.0];
        let c = |v: [f64; 3], w: f64| [v[0] as f32, v[1] as f32, v[2] as f32, w as f32];
        match &scene.environment {
            Environment::None => lay.env_kind = 0,
            Environment::Uniform(rgb) => {
                lay.env_kind = 1;
                lay.env[0] = c(*rgb, 0.0);
            }
            Environment::Sky { zenith, horizon, ground } => {
                lay.env_kind = 2;
                lay.env[0] = c(*zenith, 0.0);
                lay.env[1] = c(*horizon, 0.0);
                lay.env[2] = c(*ground, 0.0);
            }
            Environment::Map { texture, rotation, intensity, .. } => {
                lay.env_kind = 3;
                lay.env_tex = textures.len() as u32;
                textures.push(texture);
                lay.env[0] = c([0.0; 3], *intensity);
                lay.env[1] = c([*rotation, 0.0, 0.0], 0.0);
            }
        }
        lay.irr_tex = NONE;
        if let Some(irr) = &scene.irradiance {
            lay.irr_tex = textures.len() as u32;
            textures.push(irr);
        }
        for t in textures {
            let start = rec.len();
            match t {
                Texture::Image { width, height, channels, data, .. } => {
                    rec.words([0, *width as u32, *height as u32, *channels as u32]);
                    rec.words([texels.len() as u32, 0, 0, 0]);
                    texels.extend_from_slice(data);
                }
                Texture::Noise { scale, octaves, seed } => {
                    rec.words([1, 0, 0, 0]);
                    rec.push([*scale as f32, f32::from_bits(*octaves), f32::from_bits(*seed), 0.0]);
                }
                Texture::Gradient { from, to, along_u } => {
                    rec.words([2, 0, 0, 0]);
                    rec.push([*from as f32, *to as f32, f32::from_bits(u32::from(*along_u)), 0.0]);
                }
                Texture::Scales { base, edge } => {
                    rec.words([3, 0, 0, 0]);
                    rec.v3(*base, 0.0);
                    rec.v3(*edge, 0.0);
                }
                Texture::Checker { a, b, n } => {
                    rec.words([4, 0, 0, 0]);
                    rec.v3(*a, *n as f32);
                    rec.v3(*b, 0.0);
                }
            }
            rec.pad_to(start, 3);
        }
        let bg = scene.output.background;
        lay.background = [bg[0] as f32, bg[1] as f32, bg[2] as f32, 0.0];

        let weights: Vec<[f32; 4]> = grid
            .iter()
            .zip(sw.weights())
            .map(|(&l, w)| [w[0] as f32, w[1] as f32, w[2] as f32, (std::f64::consts::TAU / l) as f32])
            .collect();

        for (what, bytes) in [
            ("the scene (geometry, materials, textures)", rec.0.len() as u64 * 16),
            ("the scene's image textures", texels.len() as u64 * 4),
            ("the scene's lookup tables", tables.len() as u64 * 4),
            ("the scene's film colour tables", film_data.len() as u64 * 16),
        ] {
            gpu.check_storage(
                what,
                bytes,
                "use fewer or smaller meshes and textures, or tables with a smaller uv_resolution",
            )?;
        }
        let nonempty = |v: &mut Vec<f32>| {
            if v.is_empty() {
                v.push(0.0);
            }
        };
        nonempty(&mut texels);
        nonempty(&mut tables);
        if media.is_empty() {
            media.push([0.0; 2]);
        }
        if film_data.is_empty() {
            film_data.push([0.0; 4]);
        }
        let source = scene_source();
        let (scene_buf, texels_buf, media_buf, weights_buf, tables_buf, film_buf, pipeline) =
            gpu.checked("uploading the scene and compiling the renderer", || {
                let init = |label: &str, data: &[u8], usage: wgpu::BufferUsages| {
                    gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(label),
                        contents: data,
                        usage,
                    })
                };
                let storage = wgpu::BufferUsages::STORAGE;
                let pipeline = gpu
                    .scene_pipeline
                    .get_or_init(|| {
                        let module = gpu.shader("scene.wgsl", &source);
                        gpu.compute_pipeline(&module, "iridis scene", "render_scene")
                    })
                    .clone();
                (
                    init("scene records", bytemuck::cast_slice(&rec.0), storage | wgpu::BufferUsages::COPY_DST),
                    init("scene texels", bytemuck::cast_slice(&texels), storage),
                    init("scene film media", bytemuck::cast_slice(&media), storage | wgpu::BufferUsages::COPY_DST),
                    init("scene film weights", bytemuck::cast_slice(&weights), storage),
                    init("scene tables", bytemuck::cast_slice(&tables), storage),
                    init("scene film tables", bytemuck::cast_slice(&film_data), storage | wgpu::BufferUsages::COPY_DST),
                    pipeline,
                )
            })?;
        let s = Self {
            gpu,
            pipeline,
            scene: scene_buf,
            texels: texels_buf,
            media: media_buf,
            weights: weights_buf,
            tables: tables_buf,
            film_tables: film_buf,
            grid_nm: grid,
            layout: lay,
            camera: scene.camera.clone(),
            lights: scene.lights.clone(),
            first_profile,
            area_lights: scene.area_lights.clone(),
            output: scene.output.clone(),
            media_cpu: media,
            films,
            last_overflow: std::sync::Mutex::new(None),
        };
        s.build_film_tables(&s.media_cpu, 1.0);
        Ok(s)
    }

    /// Fills every smooth film's colour table on the GPU from `media` (the uploaded media, or the viewer's
    /// changed copy) for its SVT range × `svt_scale`, and points its record at it; a film whose table does not
    /// fit its room, or that no table can follow, is marked for direct evaluation instead.
    fn build_film_tables(&self, media: &[[f32; 2]], svt_scale: f64) {
        let q = &self.gpu.queue;
        for f in &self.films {
            let Some((base, room)) = f.table else { continue };
            let built = self.build_film_table(f, media, svt_scale, base, room);
            let mut words = [f.flags, 0, 0, 0];
            if let Some(g) = built {
                words[0] |= 8;
                let t = [
                    [
                        f32::from_bits(base),
                        f32::from_bits(g.cos_nodes as u32),
                        f32::from_bits(g.offset_nodes as u32),
                        0.0,
                    ],
                    [g.offset_nm.0 as f32, g.offset_nm.1 as f32, 0.0, 0.0],
                ];
                q.write_buffer(&self.scene, (f.record as u64 + 6) * 16, bytemuck::cast_slice(&t));
            }
            // Word 3 of record 1: the flags.
            q.write_buffer(&self.scene, (f.record as u64 + 1) * 16 + 12, bytemuck::cast_slice(&words[..1]));
        }
    }

    /// One film's table (see [`GpuScene::build_film_tables`]); `None` where it falls back to direct evaluation.
    fn build_film_table(
        &self,
        f: &FilmSlot,
        media: &[[f32; 2]],
        svt_scale: f64,
        base: u32,
        room: usize,
    ) -> Option<TableGrid> {
        let n_lambda = self.grid_nm.len();
        let indices: Vec<Vec<Complex64>> = (0..n_lambda)
            .map(|l| {
                (0..f.n_media)
                    .map(|j| {
                        let [re, im] = media[f.media_base + l * f.n_media + j];
                        Complex64::new(re as f64, im as f64)
                    })
                    .collect()
            })
            .collect();
        let layers = f.n_media - 2;
        let thick: Vec<f32> =
            (0..layers.max(1)).map(|j| if j < layers { media[f.thick_base + j][0] } else { 0.0 }).collect();
        let d: Vec<f64> = thick[..layers].iter().map(|&x| x as f64).collect();
        let r = (f.svt[1] as f64 * svt_scale).abs();
        let grid = TableGrid::for_indices(&indices, &d, &self.grid_nm, (-r, r), NODES_PER_PERIOD).ok()?;
        if grid.len() > room {
            return None;
        }
        let gpu = self.gpu;
        let flat: Vec<[f32; 2]> = media[f.media_base..f.media_base + n_lambda * f.n_media].to_vec();
        let (m, t) = gpu
            .checked("uploading a film for its colour table", || {
                let init = |label: &str, data: &[u8]| gpu.storage_init(label, data);
                (
                    init("film table media", bytemuck::cast_slice(&flat)),
                    init("film table thickness", bytemuck::cast_slice(&thick)),
                )
            })
            .ok()?;
        let (table, _) = build_table(gpu, &m, &t, &self.weights, f.n_media as u32, n_lambda as u32, &grid).ok()?;
        let mut enc =
            gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("film table copy") });
        enc.copy_buffer_to_buffer(&table, 0, &self.film_tables, base as u64 * 16, grid.len() as u64 * 32);
        gpu.submit_and_wait(enc.finish()).ok()?;
        Some(grid)
    }

    /// Whether the scene has thin-film materials (for which [`GpuScene::set_film_controls`] does something).
    pub fn has_films(&self) -> bool {
        !self.films.is_empty()
    }

    /// Applies the viewer's thin-film controls to every thin-film material (from the scene's own values).
    pub fn set_film_controls(&self, c: FilmControls) {
        let mut media = self.media_cpu.clone();
        let q = &self.gpu.queue;
        for f in &self.films {
            let layers = f.n_media - 2;
            for j in 0..layers {
                media[f.thick_base + j][0] = (self.media_cpu[f.thick_base + j][0] as f64 * c.thickness_scale) as f32;
            }
            if let (Some(n), true) = (c.layer_ior, layers > 0) {
                let n_lambda = (f.thick_base - f.media_base) / f.n_media;
                for l in 0..n_lambda {
                    media[f.media_base + l * f.n_media + 1] = [n as f32, 0.0];
                    if let Some(m) = f.metal_media_base {
                        media[m + l * f.n_media + 1] = [n as f32, 0.0];
                    }
                }
            }
            let mut svt = f.svt;
            svt[1] = (svt[1] as f64 * c.svt_scale) as f32;
            q.write_buffer(&self.scene, f.svt_record as u64 * 16, bytemuck::cast_slice(&[svt]));
        }
        q.write_buffer(&self.media, 0, bytemuck::cast_slice(&media));
        self.build_film_tables(&media, c.svt_scale);
    }

    /// The adapter the scene lives on.
    pub fn gpu(&self) -> &Gpu {
        self.gpu
    }

    /// The camera the next frames use.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// Moves the camera (the viewer's orbit).
    pub fn set_camera(&mut self, camera: Camera) {
        self.camera = camera;
    }

    /// The scene's lights.
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// Replaces the lights (same number as the scene has: the viewer drags them).
    pub fn set_lights(&mut self, lights: &[Light]) -> Result<(), GpuError> {
        same_count("lights", self.lights.len(), lights.len())?;
        let old: Vec<_> = self.lights.iter().filter(|l| matches!(l, Light::Laser(_))).collect();
        let new: Vec<_> = lights.iter().filter(|l| matches!(l, Light::Laser(_))).collect();
        if old != new {
            return Err(GpuError::Invalid(
                "a laser spot's reflection is fixed by the scene; it cannot be moved".into(),
            ));
        }
        let mut rec = Records::default();
        push_lights(&mut rec, lights, self.layout.lights.base, self.first_profile);
        self.gpu.queue.write_buffer(&self.scene, self.layout.lights.base as u64 * 16, bytemuck::cast_slice(&rec.0));
        self.lights = lights.to_vec();
        Ok(())
    }

    /// The scene's area lights.
    pub fn area_lights(&self) -> &[AreaLight] {
        &self.area_lights
    }

    /// Replaces the area lights (same number as the scene has: the viewer turns them with its light drag).
    pub fn set_area_lights(&mut self, lights: &[AreaLight]) -> Result<(), GpuError> {
        same_count("area lights", self.area_lights.len(), lights.len())?;
        let mut rec = Records::default();
        push_area_lights(&mut rec, lights);
        self.gpu.queue.write_buffer(
            &self.scene,
            self.layout.area_lights.base as u64 * 16,
            bytemuck::cast_slice(&rec.0),
        );
        self.area_lights = lights.to_vec();
        Ok(())
    }

    /// Whether the scene has extended light (an environment or area lights), which Monte Carlo integrates.
    pub fn has_extended_light(&self) -> bool {
        self.layout.area_lights.n > 0 || self.layout.env_kind != 0
    }

    /// Whether the next frames integrate extended light by Monte Carlo.
    pub fn monte_carlo(&self) -> bool {
        self.layout.integration == 1
    }

    /// Switches between the fast path and Monte Carlo (the viewer's toggle; the scene file's `integration`
    /// is the start). Monte Carlo frames are meant to accumulate ([`SceneFrame::run_samples`]).
    pub fn set_monte_carlo(&mut self, on: bool) {
        self.layout.integration = u32::from(on);
    }

    /// The scene's output settings (size, spp, exposure, encoding).
    pub fn output(&self) -> &iridis_render::scene::Output {
        &self.output
    }

    /// Allocates the output of `width × height` images with `spp` samples per pixel, displayed with `tone`.
    pub fn frame(&self, width: u32, height: u32, spp: u32, tone: ToneMap) -> Result<SceneFrame, GpuError> {
        check_image_size(width, height).map_err(|e| GpuError::Invalid(format!("image {width}×{height}: {e}")))?;
        check_spp(spp).map_err(|e| GpuError::Invalid(format!("{spp} samples per pixel: {e}")))?;
        let pixels = width as u64 * height as u64;
        self.gpu.check_storage("the image", pixels * 16, "render a smaller image")?;
        // This frame's sample offsets (the CPU's R2 set for spp samples).
        let offsets: Vec<[f32; 4]> = (0..spp)
            .map(|s| {
                let (x, y) = sample_offset(s, spp);
                [x as f32, y as f32, 0.0, 0.0]
            })
            .collect();
        self.gpu.queue.write_buffer(&self.scene, self.layout.sample_base as u64 * 16, bytemuck::cast_slice(&offsets));
        let gpu = self.gpu;
        gpu.checked("allocating the image", || {
            let params = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("scene params"),
                size: (PARAM_WORDS * 4) as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let display = display_buffer(gpu, tone);
            let out_rgb = storage_out(gpu, "scene rgb", pixels * 16);
            let out_rgba = storage_out(gpu, "scene rgba", pixels * 4);
            let overflow = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("scene stack overflow"),
                contents: bytemuck::cast_slice(&[0u32; 2]),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            });
            let bind = gpu.bind_in_order(
                "scene bindings",
                &self.pipeline,
                &[
                    &params,
                    &display,
                    &self.scene,
                    &self.texels,
                    &self.media,
                    &self.weights,
                    &self.tables,
                    &out_rgb,
                    &out_rgba,
                    &overflow,
                    &self.film_tables,
                ],
            );
            SceneFrame { width, height, spp, params, display, bind, out_rgb, out_rgba, overflow, timer: gpu.timer() }
        })
    }

    /// Renders `width × height` with `spp` samples per pixel and reads the linear image back;
    /// `progress(rows_done)` is called after each band of rows (of each pass, scaled to the image's rows).
    /// Monte Carlo accumulates progressively, [`MC_PASS_SAMPLES`] samples per pass: every pass adds its samples
    /// to the running mean of each pixel, so the image converges pass by pass as the CPU's does with `spp`.
    pub fn render(&self, width: u32, height: u32, spp: u32, progress: &dyn Fn(usize)) -> Result<Image, GpuError> {
        let tone = ToneMap { exposure_ru: self.output.exposure, encoding: self.output.encoding };
        let frame = self.frame(width, height, spp, tone)?;
        let per_pass = if self.layout.integration == 0 { spp } else { MC_PASS_SAMPLES.min(spp) };
        let passes = spp.div_ceil(per_pass);
        for k in 0..passes {
            let sample0 = k * per_pass;
            let n = per_pass.min(spp - sample0);
            let mut row = 0;
            while row < height {
                let rows = BAND_ROWS.min(height - row);
                frame.run_rows(self, row, rows, (sample0, n))?;
                row += rows;
                progress(((k * height + row) / passes) as usize);
            }
        }
        *self.last_overflow.lock().unwrap_or_else(|e| e.into_inner()) = frame.stack_overflow(self)?;
        frame.read_image(self)
    }

    /// Whether the last [`GpuScene::render`] dropped rays because the shader's ray stack was full (the CLI
    /// prints it once as a warning).
    pub fn stack_overflow(&self) -> Option<StackOverflow> {
        *self.last_overflow.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn param_words(&self, width: u32, height: u32, spp: u32, row0: u32, pass: (u32, u32)) -> [u32; PARAM_WORDS] {
        let f = |v: f64| (v as f32).to_bits();
        let v4 = |v: [f64; 3], w: u32| [f(v[0]), f(v[1]), f(v[2]), w];
        let (kind, pos, fwd, right, up, s) = match self.camera {
            Camera::Perspective { position, forward, right, up, tan_half } => {
                (0, position, forward, right, up, tan_half)
            }
            Camera::Orthographic { position, forward, right, up, half_height } => {
                (1, position, forward, right, up, half_height)
            }
            Camera::Hemisphere { target, normal, right, up, distance } => (2, target, normal, right, up, distance),
        };
        let l = &self.layout;
        let mut w = Vec::with_capacity(PARAM_WORDS);
        w.extend(v4(pos, kind));
        w.extend(v4(fwd, f(s)));
        w.extend(v4(right, 0));
        w.extend(v4(up, 0));
        for e in &l.env {
            w.extend(e.map(f32::to_bits));
        }
        w.extend(l.background.map(f32::to_bits));
        let m = xyz_to_srgb_words();
        w.extend(m.map(f32::to_bits));
        w.extend([width, height, spp, row0]);
        w.extend([l.env_kind, l.env_tex, l.env_visible, self.output.max_depth]);
        w.extend([l.spheres.n, l.spheres.base, l.planes.n, l.planes.base]);
        w.extend([l.lights.n, l.lights.base, l.nodes.n, l.nodes.base]);
        w.extend([l.tri_base, l.mat_base, l.tex_base, l.sample_base]);
        w.extend([l.n_lambda, l.energy_base, l.irr_tex, l.env_light_base]);
        w.extend([pass.0, pass.1, l.integration, l.seed]);
        w.extend([l.area_lights.n, l.area_lights.base, l.env_cdf_base, 0]);
        w.try_into().expect("the Params struct of scene.wgsl")
    }
}

/// Refuses a replacement list of `what` (the viewer's drags) whose length is not the scene's.
fn same_count(what: &str, have: usize, given: usize) -> Result<(), GpuError> {
    if given != have {
        return Err(GpuError::Invalid(format!("the scene has {have} {what}; {given} given")));
    }
    Ok(())
}

/// `Params` of scene.wgsl: 12 vec4 and 32 u32.
// Public but hidden: not API, reachable only for the crate's tests in tests/ (Cargo.toml, `[lib] test = false`).
#[doc(hidden)]
pub const PARAM_WORDS: usize = 12 * 4 + 32;

/// Area light records (extended.wgsl): `[centre, kind]`, `[normal, radius | width]`, `[tangent, height]`,
/// `[radiance, visible]`.
fn push_area_lights(rec: &mut Records, lights: &[AreaLight]) {
    for l in lights {
        match l.shape {
            Shape::Sphere { center, radius } => {
                rec.v3w(center, 0);
                rec.v3([0.0; 3], radius as f32);
                rec.v3([0.0; 3], 0.0);
            }
            Shape::Disk { center, normal, radius } => {
                rec.v3w(center, 1);
                rec.v3(normal, radius as f32);
                rec.v3([0.0; 3], 0.0);
            }
            Shape::Rectangle { center, normal, tangent, size } => {
                rec.v3w(center, 2);
                rec.v3(normal, size[0] as f32);
                rec.v3(tangent, size[1] as f32);
            }
        }
        rec.v3w(l.radiance, u32::from(l.visible));
    }
}

/// A [`Distribution2d`] as extended.wgsl reads it: row CDF, the rows' column CDFs, the cells' probabilities.
fn push_distribution(tables: &mut Vec<f32>, d: &Distribution2d) {
    for v in [&d.marginal, &d.conditional, &d.prob] {
        tables.extend(v.iter().map(|&x| x as f32));
    }
}

/// The lobe's distributions, one block per level of the same size (an empty level has a row CDF ending at 0).
fn push_lobe(tables: &mut Vec<f32>, ls: &iridis_render::lobe::LobeSampler, res: usize) {
    let n = res - 1;
    for level in &ls.levels {
        match level {
            Some(d) => push_distribution(tables, d),
            None => tables.extend(std::iter::repeat_n(0.0, (n + 1) + n * (n + 1) + n * n)),
        }
    }
}

/// Two records per light from record `base` on — `[direction | position, kind (0 directional, 1 point,
/// 2 laser spot)]`, `[irradiance rgb, laser: record of its frame]` — then three per laser spot:
/// `[t, profile texture]`, `[b, cos θ_i]`, `[n, 0]` (render::light::LaserSpot), whose profiles are textures
/// `first_profile`, `first_profile + 1`, … in the order of the lights.
fn push_lights(rec: &mut Records, lights: &[Light], base: u32, first_profile: u32) {
    let frames = base + 2 * lights.len() as u32;
    let mut spots = Vec::new();
    for l in lights {
        match l {
            Light::Directional { direction, rgb } => {
                rec.v3w(*direction, 0);
                rec.v3(*rgb, 0.0);
            }
            Light::Point { position, rgb } => {
                rec.v3w(*position, 1);
                rec.v3(*rgb, 0.0);
            }
            Light::Laser(spot) => {
                rec.v3w(spot.position, 2);
                rec.v3w(spot.rgb, frames + 3 * spots.len() as u32);
                spots.push(spot);
            }
        }
    }
    for (k, spot) in spots.iter().enumerate() {
        let [t, b, n] = spot.frame;
        rec.v3w(t, first_profile + k as u32);
        rec.v3(b, spot.cos_in as f32);
        rec.v3(n, 0.0);
    }
}

/// A microfacet's three records: colour, `[roughness, metallic, ior, metallic-roughness texture]`, and
/// `[normal texture, scale]` (NONE: none).
fn push_microfacet(rec: &mut Records, m: &Microfacet) {
    rec.color(&m.color);
    let mr = m.metallic_roughness.map_or(NONE, |i| i as u32);
    rec.push([m.roughness as f32, m.metallic as f32, m.ior as f32, f32::from_bits(mr)]);
    let (nt, scale) = m.normal_texture.map_or((NONE, 1.0), |(i, s)| (i as u32, s as f32));
    rec.push([f32::from_bits(nt), scale, 0.0, 0.0]);
}

/// A rough film's records (after its SVT record: four, where a base would go) and its tables in `film_data`:
/// `[k_r, π k_d, albedo first entries, angles | azimuths << 16]`, `[offset nodes, albedo cos nodes, albedo offset
/// nodes]`, `[first, last offset, albedo's first, last offset]`, `[albedo's first, last cos]` (film_rough.wgsl's
/// RoughTab). The tables are the material's own (`ThinFilm::rough_table`, `rough_env_table`), the ones the CPU
/// renderer shades with: made once for both.
fn push_rough_tables(
    rec: &mut Records,
    film_data: &mut Vec<[f32; 4]>,
    f: &iridis_render::material::ThinFilm,
    t: &RoughColorTable,
) {
    let (cos, env_offsets, env) = f.rough_env_table().expect("a rough film has its albedo table");
    let xyz = |x: &iridis_color::Xyz| [x.x as f32, x.y as f32, x.z as f32, 0.0];
    let spec = film_data.len() as u32;
    film_data.extend(t.specular.iter().map(xyz));
    let diffuse = film_data.len() as u32;
    film_data.extend(t.diffuse.iter().map(xyz));
    let env_base = film_data.len() as u32;
    film_data.extend(env.iter().map(xyz));
    let last = |v: &[f64]| v[v.len() - 1] as f32;
    rec.words([spec, diffuse, env_base, t.angles as u32 | ((t.azimuths as u32) << 16)]);
    rec.words([t.offsets as u32, cos.len() as u32, env_offsets.len() as u32, 0]);
    rec.push([t.offset_nm.0 as f32, t.offset_nm.1 as f32, env_offsets[0] as f32, last(env_offsets)]);
    rec.push([cos[0] as f32, last(cos), 0.0, 0.0]);
}

impl SceneFrame {
    /// Image size.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The samples per pixel of the frame's camera offsets.
    pub fn spp(&self) -> u32 {
        self.spp
    }

    /// Changes the display (exposure in RU, encoding) of the next frames.
    pub fn set_tone(&self, s: &GpuScene, tone: ToneMap) {
        s.gpu.queue.write_buffer(&self.display, 0, bytemuck::cast_slice(&crate::lookup::display_words(tone)));
    }

    /// Renders rows `row0 .. row0 + rows`, samples `pass.0 .. pass.0 + pass.1` of each pixel (added to the
    /// running mean of the samples before them), and waits for the GPU.
    fn run_rows(&self, s: &GpuScene, row0: u32, rows: u32, pass: (u32, u32)) -> Result<FrameTime, GpuError> {
        let words = s.param_words(self.width, self.height, self.spp, row0, pass);
        s.gpu.queue.write_buffer(&self.params, 0, bytemuck::cast_slice(&words));
        dispatch(
            s.gpu,
            self.timer.as_ref(),
            &s.pipeline,
            &self.bind,
            (self.width.div_ceil(8), rows.div_ceil(8)),
            "rendering the scene",
        )
    }

    /// Renders the whole image in one dispatch (the benchmark's and the viewer's frames) with the scene's
    /// current camera and lights, and waits for the GPU.
    pub fn run(&self, s: &GpuScene) -> Result<FrameTime, GpuError> {
        self.run_rows(s, 0, self.height, (0, self.spp))
    }

    /// Progressive accumulation (the viewer's Monte Carlo frames): adds samples `sample0 .. sample0 + n` of
    /// every pixel to the running mean of the samples before them (`sample0 = 0` starts a new image). The
    /// camera offsets cycle through the frame's `spp` set; the random numbers differ for every sample index.
    pub fn run_samples(&self, s: &GpuScene, sample0: u32, n: u32) -> Result<FrameTime, GpuError> {
        self.run_rows(s, 0, self.height, (sample0, n.max(1)))
    }

    /// The stack overflows since this frame was made (see [`StackOverflow`]); `None` if there were none.
    pub fn stack_overflow(&self, s: &GpuScene) -> Result<Option<StackOverflow>, GpuError> {
        let w: Vec<u32> = bytemuck::pod_collect_to_vec(&s.gpu.read_buffer(&self.overflow, 8)?);
        Ok((w[0] > 0).then_some(StackOverflow { rays: w[0], depth: w[1] }))
    }

    /// Reads the last image back as linear sRGB.
    pub fn read_image(&self, s: &GpuScene) -> Result<Image, GpuError> {
        let gpu = s.gpu;
        let data: Vec<f32> = bytemuck::pod_collect_to_vec(&gpu.read_buffer(&self.out_rgb, self.out_rgb.size())?);
        let pixels = (self.width * self.height) as usize;
        Ok(Image {
            width: self.width,
            height: self.height,
            data: data.chunks_exact(4).take(pixels).map(|p| [p[0], p[1], p[2]]).collect(),
        })
    }

    /// The displayed pixels as the shader packed them (`pack4x8unorm`, row-major), for the viewer's present pass.
    #[cfg(feature = "viewer")]
    pub(crate) fn packed(&self) -> &wgpu::Buffer {
        &self.out_rgba
    }

    /// Reads the last image back as displayed 8-bit sRGB (exposure and encoding of [`GpuScene::frame`]).
    pub fn read_rgb8(&self, s: &GpuScene) -> Result<Vec<u8>, GpuError> {
        let gpu = s.gpu;
        let words: Vec<u32> = bytemuck::pod_collect_to_vec(&gpu.read_buffer(&self.out_rgba, self.out_rgba.size())?);
        Ok(unpack_rgb8(&words))
    }
}
