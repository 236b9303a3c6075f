//! `iridis view`: an interactive window (winit through eframe) that renders a scene with [`GpuScene`] or a
//! lookup table's BRDF map with [`GpuLookup`], and an egui panel for the display (exposure in RU, gamma), the
//! thin films (thickness, the film layer's index, SVT strength), the diffraction tables (a BRDF-map view of each
//! at a chosen incidence) and the frame time. Dragging orbits the camera, right- or shift-dragging moves the
//! light, the wheel zooms; the scene file is reloaded when it changes on disk. On a BRDF map, dragging turns the
//! light's incidence and the wheel sets the exposure.
//!
//! Frames are rendered by the same compute shaders as `iridis render --gpu` into a storage buffer; a small
//! compute pass (`present.rs`) stores its displayed pixels into a texture registered with egui's wgpu
//! renderer, so a frame never travels to the CPU and back. The panel shows the render pass's own GPU
//! timestamps where the adapter has them. A frame is rendered only when something changed.
//!
//! [`ViewOptions::check`] runs the scripted check used under Xvfb: it drives the window through egui's own
//! input path (pointer drags, a key, the wheel), verifies that every input changed what is shown, takes a
//! screenshot of the whole window and closes it.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant, SystemTime};

use eframe::egui;
use iridis_color::{Encoding, ToneMap};
use iridis_diffraction::geometry::direction;
use iridis_diffraction::LookupTable;
use iridis_render::area::{AreaLight, Shape};
use iridis_render::camera::{frame as camera_frame, Camera};
use iridis_render::light::Light;
use iridis_render::material::Material;
use iridis_render::Scene;

use crate::present::{PresentTarget, Presenter};
use crate::scene::{FilmControls, GpuScene, SceneFrame};
use crate::{FrameTime, Gpu, GpuLookup};

/// What the window shows.
#[derive(Debug)]
pub enum ViewInput {
    /// A scene file (TOML or glTF), reloaded when it changes.
    Scene(PathBuf),
    /// A lookup table's BRDF map (`name` for the title).
    Table { table: Box<LookupTable>, name: String },
}

/// Window options.
#[derive(Debug, Clone, Default)]
pub struct ViewOptions {
    /// Run the scripted check and keep a screenshot of the window here.
    pub check: Option<PathBuf>,
}

/// What the scripted check saw.
#[derive(Debug, Clone)]
pub struct CheckReport {
    pub adapter: String,
    /// Frames rendered (GPU dispatches).
    pub frames: usize,
    /// Each input and how much it changed the shown image (mean absolute difference of 8-bit values).
    pub steps: Vec<(String, f64)>,
    /// Median frame time of the renders (ms): submission to completion of the render pass.
    pub frame_ms: f64,
    /// Median of the render pass's GPU timestamps (ms), where the adapter has timestamp queries.
    pub gpu_ms: Option<f64>,
    /// Median time to read a frame back to the CPU (ms), measured by the check on every frame as the peer of
    /// what the viewer no longer does.
    pub readback_ms: f64,
    /// Whether the texture egui drew held exactly the rendered frame's pixels, every frame.
    pub texture_equals_frame: bool,
    /// The window as RGBA8 (`width × height`).
    pub screenshot: Option<(usize, usize, Vec<u8>)>,
}

/// Samples per pixel a Monte Carlo image accumulates before the viewer stops rendering it.
const VIEW_MC_SAMPLES: u32 = 1024;
/// Camera sample offsets of a Monte Carlo frame (cycled through as samples accumulate).
const VIEW_MC_OFFSETS: u32 = 64;

/// Loads a scene for the viewer (the CLI prints notes; the viewer shows them).
pub type SceneLoader = fn(&Path) -> Result<Scene, String>;

/// Opens the window and runs until it is closed. Returns the check's report when [`ViewOptions::check`] is set.
pub fn run(input: ViewInput, opts: ViewOptions, load: SceneLoader) -> Result<Option<CheckReport>, String> {
    // Load the scene before opening a window: a broken file is an error message, not an empty window.
    let first = match &input {
        ViewInput::Scene(p) => Some(load(p)?),
        ViewInput::Table { .. } => None,
    };
    let mut wgpu_options = egui_wgpu_config()?;
    // The scripted check runs under a virtual X server: no display to wait for.
    wgpu_options.surface.present_mode =
        if opts.check.is_some() { wgpu::PresentMode::AutoNoVsync } else { wgpu::PresentMode::AutoVsync };
    let title = match &input {
        ViewInput::Scene(p) => format!("iridis view — {}", p.display()),
        ViewInput::Table { name, .. } => format!("iridis view — {name}"),
    };
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size([1180.0, 720.0]).with_title(title),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options,
        ..Default::default()
    };
    let report = Arc::new(Mutex::new(None));
    let out = report.clone();
    let mut failure: Option<String> = None;
    let failure_slot = Arc::new(Mutex::new(None::<String>));
    let fail = failure_slot.clone();
    let result = eframe::run_native(
        "iridis view",
        native,
        Box::new(move |cc| {
            let rs = cc.wgpu_render_state.as_ref().ok_or("eframe opened no wgpu renderer")?;
            let gpu: &'static Gpu =
                Box::leak(Box::new(Gpu::from_parts(rs.device.clone(), rs.queue.clone(), rs.adapter.get_info())));
            match Viewer::new(gpu, rs.clone(), input, first, opts, load, out) {
                Ok(v) => Ok(Box::new(v) as Box<dyn eframe::App>),
                Err(e) => {
                    *fail.lock().unwrap_or_else(|p| p.into_inner()) = Some(e.clone());
                    Err(e.into())
                }
            }
        }),
    );
    if let Some(e) = failure_slot.lock().unwrap_or_else(|p| p.into_inner()).take() {
        failure = Some(e);
    }
    if let Some(e) = failure {
        return Err(e);
    }
    result.map_err(|e| {
        // winit's OS errors begin "os error at /…/winit-…/src/…/mod.rs:765: ": the build's path, not the user's.
        let text = e.to_string();
        let text = text.find(".rs:").and_then(|i| text[i..].splitn(3, ':').nth(2)).map_or(text.as_str(), str::trim);
        let text = text.trim_end_matches('.');
        format!(
            "cannot open the viewer window: {text}. It needs a display (X11; under a headless server use \
             `xvfb-run -a iridis view …`) and a Vulkan driver (`apt-get install mesa-vulkan-drivers` without a GPU)"
        )
    })?;
    let r = report.lock().unwrap_or_else(|p| p.into_inner()).take();
    Ok(r)
}

/// egui draws on the device every other GPU path opens ([`crate::open_vulkan`]), handed over whole.
fn egui_wgpu_config() -> Result<eframe::egui_wgpu::WgpuConfiguration, String> {
    let (instance, adapter, device, queue, _) = crate::open_vulkan().map_err(|e| e.to_string())?;
    let setup = eframe::egui_wgpu::WgpuSetupExisting { instance, adapter, device, queue };
    Ok(eframe::egui_wgpu::WgpuConfiguration {
        wgpu_setup: eframe::egui_wgpu::WgpuSetup::Existing(setup),
        ..Default::default()
    })
}

/// An orbit around a target point, y up (the camera of perspective and orthographic scenes).
#[derive(Debug, Clone, Copy)]
struct Orbit {
    target: [f64; 3],
    dist: f64,
    yaw: f64,
    pitch: f64,
    /// tan(fov/2) (perspective) or half the view height (orthographic).
    lens: f64,
    ortho: bool,
}

impl Orbit {
    fn from_camera(cam: &Camera, scene: &Scene) -> Option<Self> {
        let (position, forward, lens, ortho) = match *cam {
            Camera::Perspective { position, forward, tan_half, .. } => (position, forward, tan_half, false),
            Camera::Orthographic { position, forward, half_height, .. } => (position, forward, half_height, true),
            Camera::Hemisphere { .. } => return None,
        };
        let target = scene.intersect(position, forward, f64::INFINITY).map(|h| h.p).unwrap_or([
            position[0] + 10.0 * forward[0],
            position[1] + 10.0 * forward[1],
            position[2] + 10.0 * forward[2],
        ]);
        let d = [position[0] - target[0], position[1] - target[1], position[2] - target[2]];
        let dist = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-6);
        Some(Self { target, dist, yaw: d[0].atan2(d[2]), pitch: (d[1] / dist).clamp(-1.0, 1.0).asin(), lens, ortho })
    }

    fn camera(&self) -> Option<Camera> {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        let dir = [cp * sy, sp, cp * cy];
        let position = [0, 1, 2].map(|k| self.target[k] + dir[k] * self.dist);
        let (forward, right, up) = camera_frame([-dir[0], -dir[1], -dir[2]], [0.0, 1.0, 0.0])?;
        Some(if self.ortho {
            Camera::Orthographic { position, forward, right, up, half_height: self.lens }
        } else {
            Camera::Perspective { position, forward, right, up, tan_half: self.lens }
        })
    }
}

/// A diffraction material's table for the BRDF-map view.
struct MapView {
    name: String,
    lookup: GpuLookup<'static>,
    scale_ru: f64,
    info: String,
}

struct SceneView {
    path: PathBuf,
    modified: Option<SystemTime>,
    cpu: Scene,
    gpu: GpuScene<'static>,
    frame: Option<SceneFrame>,
    orbit: Option<Orbit>,
    home: Option<Orbit>,
    lights0: Vec<Light>,
    area0: Vec<AreaLight>,
    /// Rotation of the lights about the vertical and the horizontal axis (rad).
    light_yaw: f64,
    light_pitch: f64,
    maps: Vec<MapView>,
    films: usize,
    /// What was last uploaded: lights and film controls are rewritten only when they change.
    uploaded_lights: Vec<Light>,
    uploaded_area: Vec<AreaLight>,
    /// Monte Carlo: samples accumulated in the frame so far (0: start a new image).
    samples: u32,
    uploaded_film: FilmControls,
}

enum Mode {
    Scene(Box<SceneView>),
    Table(Box<MapView>),
}

/// The scripted check's state machine.
struct Check {
    step: usize,
    /// Frame counter inside the current step.
    tick: usize,
    before: Option<Vec<u8>>,
    steps: Vec<(String, f64)>,
    screenshot: Arc<Mutex<Option<Arc<egui::ColorImage>>>>,
    requested: bool,
}

/// The texture the main image is presented in, and its egui id.
struct FrameTexture {
    target: PresentTarget,
    id: egui::TextureId,
}

struct Viewer {
    gpu: &'static Gpu,
    render_state: eframe::egui_wgpu::RenderState,
    presenter: Presenter,
    mode: Mode,
    load: SceneLoader,
    frame_tex: Option<FrameTexture>,
    map_tex: Option<egui::TextureHandle>,
    shown: Vec<u8>,
    exposure: f64,
    srgb: bool,
    gamma: f64,
    film: FilmControls,
    ior_on: bool,
    ior: f64,
    map_theta: f64,
    map_phi: f64,
    map_index: usize,
    res_scale: f32,
    help: bool,
    dirty: bool,
    map_dirty: bool,
    times: Vec<FrameTime>,
    /// The check's readback times (ms) and whether every presented texture equalled its frame.
    readback_ms: Vec<f64>,
    texture_equals_frame: bool,
    status: Vec<String>,
    last_poll: Instant,
    image_rect: Option<egui::Rect>,
    check: Option<Check>,
    report: Arc<Mutex<Option<CheckReport>>>,
}

fn modified(p: &Path) -> Option<SystemTime> {
    std::fs::metadata(p).and_then(|m| m.modified()).ok()
}

fn map_views(gpu: &'static Gpu, scene: &Scene) -> Result<Vec<MapView>, String> {
    let mut out = Vec::new();
    for (i, m) in scene.materials.iter().enumerate() {
        if let Material::Diffraction(d) = m {
            let Some(l) = d.evaluator.as_lookup() else { continue };
            let Some(f) = l.shading.fresnel.as_builtin() else { continue };
            let t = &l.table;
            out.push(MapView {
                name: scene.material_names.get(i).cloned().unwrap_or_else(|| format!("material {i}")),
                lookup: GpuLookup::new(gpu, t, f.clone(), l.shading.shadowing)
                    .map_err(|e| e.to_string())?
                    .with_convention(l.shading.convention),
                scale_ru: d.scale_ru,
                info: table_info(t),
            });
        }
    }
    Ok(out)
}

fn table_info(t: &LookupTable) -> String {
    format!(
        "{}: {}² u-v grid (power {}), N = {} Taylor terms, coherence {:.0} µm",
        t.meta.surface,
        t.meta.uv_resolution,
        t.meta.uv_power,
        t.meta.taylor_terms,
        t.meta.coherence_nm / 1000.0
    )
}

impl SceneView {
    fn new(gpu: &'static Gpu, path: PathBuf, cpu: Scene) -> Result<Self, String> {
        let g = GpuScene::new(gpu, &cpu).map_err(|e| e.to_string())?;
        let orbit = Orbit::from_camera(&cpu.camera, &cpu);
        let films = cpu.materials.iter().filter(|m| matches!(m, Material::ThinFilm(_))).count();
        Ok(Self {
            modified: modified(&path),
            path,
            maps: map_views(gpu, &cpu)?,
            lights0: cpu.lights.clone(),
            area0: cpu.area_lights.clone(),
            uploaded_area: cpu.area_lights.clone(),
            samples: 0,
            gpu: g,
            frame: None,
            home: orbit,
            orbit,
            light_yaw: 0.0,
            light_pitch: 0.0,
            films,
            uploaded_lights: cpu.lights.clone(),
            uploaded_film: FilmControls::default(),
            cpu,
        })
    }

    /// The light rotation of the viewer's light drag: about +y by the yaw, then about the horizontal axis.
    fn light_rotation(&self) -> impl Fn([f64; 3]) -> [f64; 3] + '_ {
        move |v: [f64; 3]| {
            // Yaw about +y, then pitch about the horizontal axis perpendicular to the yawed vector.
            let (s, c) = self.light_yaw.sin_cos();
            let v = [c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2]];
            let h = (v[0] * v[0] + v[2] * v[2]).sqrt();
            if h < 1e-9 {
                return v;
            }
            let r = (h * h + v[1] * v[1]).sqrt();
            let pitch = (v[1] / r).asin() + self.light_pitch;
            let pitch = pitch.clamp(-1.55, 1.55);
            let (sp, cp) = pitch.sin_cos();
            [v[0] / h * cp * r, sp * r, v[2] / h * cp * r]
        }
    }

    /// A position turned about the orbit's target.
    fn turn_point(&self, p: [f64; 3]) -> [f64; 3] {
        let target = self.orbit.map(|o| o.target).unwrap_or([0.0; 3]);
        let q = (self.light_rotation())([p[0] - target[0], p[1] - target[1], p[2] - target[2]]);
        [q[0] + target[0], q[1] + target[1], q[2] + target[2]]
    }

    /// The area lights moved with the light drag about the orbit's target; a disk's or rectangle's facing turns
    /// by the rotation that takes its centre's old direction from the target to the new one.
    fn area_lights(&self) -> Vec<AreaLight> {
        use iridis_render::math::{cross, dot, normalize, rotate_about, sub, try_normalize};
        let target = self.orbit.map(|o| o.target).unwrap_or([0.0; 3]);
        self.area0
            .iter()
            .map(|l| {
                let center = match l.shape {
                    Shape::Sphere { center, .. } | Shape::Disk { center, .. } | Shape::Rectangle { center, .. } => {
                        center
                    }
                };
                let moved = self.turn_point(center);
                let turn = |v: [f64; 3]| -> [f64; 3] {
                    let (Some(a), Some(b)) = (try_normalize(sub(center, target)), try_normalize(sub(moved, target)))
                    else {
                        return v;
                    };
                    match try_normalize(cross(a, b)) {
                        Some(k) => normalize(rotate_about(v, k, dot(a, b).clamp(-1.0, 1.0).acos())),
                        None => v,
                    }
                };
                let shape = match l.shape {
                    Shape::Sphere { radius, .. } => Shape::Sphere { center: moved, radius },
                    Shape::Disk { normal, radius, .. } => Shape::Disk { center: moved, normal: turn(normal), radius },
                    Shape::Rectangle { normal, tangent, size, .. } => {
                        Shape::Rectangle { center: moved, normal: turn(normal), tangent: turn(tangent), size }
                    }
                };
                AreaLight { shape, ..*l }
            })
            .collect()
    }

    fn lights(&self) -> Vec<Light> {
        let target = self.orbit.map(|o| o.target).unwrap_or([0.0; 3]);
        let rot = self.light_rotation();
        self.lights0
            .iter()
            .map(|l| match l {
                &Light::Directional { direction, rgb } => Light::Directional { direction: rot(direction), rgb },
                &Light::Point { position, rgb } => {
                    let p = rot([position[0] - target[0], position[1] - target[1], position[2] - target[2]]);
                    Light::Point { position: [p[0] + target[0], p[1] + target[1], p[2] + target[2]], rgb }
                }
                // A laser's spot stays where the beam meets the sample.
                Light::Laser(_) => l.clone(),
            })
            .collect()
    }
}

impl Viewer {
    fn new(
        gpu: &'static Gpu,
        render_state: eframe::egui_wgpu::RenderState,
        input: ViewInput,
        first: Option<Scene>,
        opts: ViewOptions,
        load: SceneLoader,
        report: Arc<Mutex<Option<CheckReport>>>,
    ) -> Result<Self, String> {
        let (mode, exposure, srgb, gamma) = match input {
            ViewInput::Scene(path) => {
                let cpu = first.ok_or("no scene")?;
                let (srgb, gamma) = match cpu.output.encoding {
                    Encoding::Gamma(g) => (false, g),
                    _ => (true, 2.2),
                };
                let exposure = cpu.output.exposure;
                (Mode::Scene(Box::new(SceneView::new(gpu, path, cpu)?)), exposure, srgb, gamma)
            }
            ViewInput::Table { table, name } => {
                let lookup = GpuLookup::new(gpu, &table, Default::default(), true).map_err(|e| e.to_string())?;
                let info = table_info(&table);
                (Mode::Table(Box::new(MapView { name, lookup, scale_ru: 1.0, info })), 1500.0, true, 2.2)
            }
        };
        let software = gpu.is_software();
        Ok(Self {
            gpu,
            render_state,
            presenter: Presenter::new(gpu).map_err(|e| e.to_string())?,
            mode,
            load,
            frame_tex: None,
            map_tex: None,
            shown: Vec::new(),
            exposure,
            srgb,
            gamma,
            film: FilmControls::default(),
            ior_on: false,
            ior: 1.33,
            map_theta: 30.0,
            map_phi: 0.0,
            map_index: 0,
            // A software adapter renders on the CPU: start small so that the window stays responsive. The
            // scripted check tests the path from the renderer to the window (each input changes the frame, the
            // texture holds the frame's pixels), not the picture: it renders at the slider's smallest scale.
            res_scale: if opts.check.is_some() {
                0.1
            } else if software {
                0.35
            } else {
                1.0
            },
            help: true,
            dirty: true,
            map_dirty: true,
            times: Vec::new(),
            readback_ms: Vec::new(),
            texture_equals_frame: true,
            status: Vec::new(),
            last_poll: Instant::now(),
            image_rect: None,
            check: opts.check.map(|_| Check {
                step: 0,
                tick: 0,
                before: None,
                steps: Vec::new(),
                screenshot: Arc::new(Mutex::new(None)),
                requested: false,
            }),
            report,
        })
    }

    fn tone(&self) -> ToneMap {
        ToneMap {
            exposure_ru: self.exposure,
            encoding: if self.srgb { Encoding::Srgb } else { Encoding::Gamma(self.gamma) },
        }
    }

    fn reload_if_changed(&mut self) {
        if self.last_poll.elapsed() < Duration::from_millis(500) {
            return;
        }
        self.last_poll = Instant::now();
        let Mode::Scene(sv) = &mut self.mode else { return };
        let m = modified(&sv.path);
        if m == sv.modified {
            return;
        }
        sv.modified = m;
        let path = sv.path.clone();
        match (self.load)(&path).and_then(|cpu| SceneView::new(self.gpu, path.clone(), cpu)) {
            Ok(mut new) => {
                // Keep the user's view where the scene's camera did not change.
                if new.cpu.camera == sv.cpu.camera {
                    new.orbit = sv.orbit;
                }
                new.light_yaw = sv.light_yaw;
                new.light_pitch = sv.light_pitch;
                **sv = new;
                self.status = vec![format!("reloaded {}", path.display())];
                self.dirty = true;
                self.map_dirty = true;
            }
            Err(e) => self.status = vec![format!("reload failed, still showing the previous version: {e}")],
        }
    }

    /// Whether a Monte Carlo image is still accumulating samples (then frames keep coming while nothing moves).
    fn accumulating(&self) -> bool {
        matches!(&self.mode, Mode::Scene(sv) if sv.gpu.monte_carlo() && sv.samples < VIEW_MC_SAMPLES)
    }

    /// Renders the main image at `size` (pixels) and presents it in the frame texture; `restart`: something
    /// changed, so a Monte Carlo image starts over (otherwise it adds a sample per pixel). Returns an error
    /// message on failure.
    fn render(&mut self, size: [u32; 2], restart: bool) -> Result<(), String> {
        let tone = self.tone();
        let gpu = self.gpu;
        let (w, h) = match &self.mode {
            Mode::Scene(_) => (size[0], size[1]),
            Mode::Table(_) => (size[0].min(size[1]), size[0].min(size[1])),
        };
        if self.frame_tex.as_ref().map(|t| (t.target.width, t.target.height)) != Some((w, h)) {
            let target = self.presenter.target(gpu, w, h).map_err(|e| e.to_string())?;
            let mut renderer = self.render_state.renderer.write();
            let filter = wgpu::FilterMode::Linear;
            let id = match self.frame_tex.take() {
                Some(old) => {
                    renderer.update_egui_texture_from_wgpu_texture(&gpu.device, &target.sample_view, filter, old.id);
                    old.id
                }
                None => renderer.register_native_texture(&gpu.device, &target.sample_view, filter),
            };
            self.frame_tex = Some(FrameTexture { target, id });
        }
        let target = &self.frame_tex.as_ref().ok_or("no frame texture")?.target;
        // Only the scripted check reads frames back: to verify the texture and to time the copy it saves.
        let check = self.check.is_some();
        let timed_read = |read: &dyn Fn() -> Result<Vec<u8>, crate::GpuError>| {
            let t = Instant::now();
            read().map(|rgb| (rgb, t.elapsed().as_secs_f64() * 1e3)).map_err(|e| e.to_string())
        };
        let (ft, readback) = match &mut self.mode {
            Mode::Scene(sv) => {
                let mc = sv.gpu.monte_carlo();
                let offsets = if mc { VIEW_MC_OFFSETS } else { 1 };
                if sv.frame.as_ref().map(|f| (f.size(), f.spp())) != Some(((w, h), offsets)) {
                    sv.frame = Some(sv.gpu.frame(w, h, offsets, tone).map_err(|e| e.to_string())?);
                    sv.samples = 0;
                }
                if restart {
                    sv.samples = 0;
                }
                if let Some(cam) = sv.orbit.and_then(|o| o.camera()) {
                    sv.gpu.set_camera(cam);
                }
                let lights = sv.lights();
                if lights != sv.uploaded_lights {
                    sv.gpu.set_lights(&lights).map_err(|e| e.to_string())?;
                    sv.uploaded_lights = lights;
                }
                let area = sv.area_lights();
                if area != sv.uploaded_area {
                    sv.gpu.set_area_lights(&area).map_err(|e| e.to_string())?;
                    sv.uploaded_area = area;
                }
                let mut film = self.film;
                film.layer_ior = self.ior_on.then_some(self.ior);
                if film != sv.uploaded_film {
                    sv.gpu.set_film_controls(film);
                    sv.uploaded_film = film;
                }
                let frame = sv.frame.as_ref().ok_or("no frame")?;
                frame.set_tone(&sv.gpu, tone);
                let ft = if mc {
                    let ft = frame.run_samples(&sv.gpu, sv.samples, 1).map_err(|e| e.to_string())?;
                    sv.samples += 1;
                    ft
                } else {
                    frame.run(&sv.gpu).map_err(|e| e.to_string())?
                };
                self.presenter.present(gpu, frame.packed(), target).map_err(|e| e.to_string())?;
                let rb = if check { Some(timed_read(&|| frame.read_rgb8(&sv.gpu))?) } else { None };
                (ft, rb)
            }
            Mode::Table(mv) => {
                let wi = direction(self.map_theta.to_radians(), self.map_phi.to_radians());
                let frame = mv.lookup.frame(w as usize, tone).map_err(|e| e.to_string())?;
                let ft = frame.run(wi).map_err(|e| e.to_string())?;
                self.presenter.present(gpu, frame.packed(), target).map_err(|e| e.to_string())?;
                let rb = if check { Some(timed_read(&|| frame.read().map(|o| o.rgb8))?) } else { None };
                (ft, rb)
            }
        };
        if let Some((rgb, ms)) = readback {
            let shown = target.read_rgb8(gpu).map_err(|e| e.to_string())?;
            self.texture_equals_frame &= shown == rgb;
            self.readback_ms.push(ms);
            self.shown = rgb;
        }
        self.times.push(ft);
        Ok(())
    }

    fn render_map_view(&mut self, ctx: &egui::Context) {
        let Mode::Scene(sv) = &self.mode else { return };
        let Some(mv) = sv.maps.get(self.map_index) else { return };
        let tone = ToneMap { exposure_ru: self.exposure * mv.scale_ru, ..self.tone() };
        let wi = direction(self.map_theta.to_radians(), self.map_phi.to_radians());
        match mv.lookup.render_map(wi, 200, tone) {
            Ok(out) => {
                let img = egui::ColorImage::from_rgb([200, 200], &out.rgb8);
                match &mut self.map_tex {
                    Some(t) => t.set(img, egui::TextureOptions::LINEAR),
                    None => self.map_tex = Some(ctx.load_texture("iridis-map", img, egui::TextureOptions::LINEAR)),
                }
            }
            Err(e) => self.status = vec![format!("BRDF map: {e}")],
        }
    }

    fn panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("iridis view");
        ui.label(egui::RichText::new(self.gpu.adapter_name()).small());
        if self.gpu.is_software() {
            ui.label(egui::RichText::new("software adapter: frame times measure the CPU").small().italics());
        }
        ui.separator();
        let mut changed = false;
        ui.label("Display");
        changed |= ui
            .add(egui::Slider::new(&mut self.exposure, 0.01..=20000.0).logarithmic(true).text("exposure (RU)"))
            .changed();
        ui.horizontal(|ui| {
            changed |= ui.radio_value(&mut self.srgb, true, "sRGB curve").changed();
            changed |= ui.radio_value(&mut self.srgb, false, "gamma").changed();
        });
        if !self.srgb {
            changed |= ui.add(egui::Slider::new(&mut self.gamma, 1.0..=3.0).text("gamma")).changed();
        }
        changed |= ui.add(egui::Slider::new(&mut self.res_scale, 0.1..=1.0).text("resolution")).changed();
        if let Mode::Scene(sv) = &mut self.mode {
            if sv.gpu.has_extended_light() {
                ui.separator();
                ui.label("Extended light (environment, area lights)");
                let mut mc = sv.gpu.monte_carlo();
                if ui.checkbox(&mut mc, "Monte Carlo (accumulates while still)").changed() {
                    sv.gpu.set_monte_carlo(mc);
                    changed = true;
                }
                let text = if mc {
                    format!("{} of {VIEW_MC_SAMPLES} samples per pixel", sv.samples)
                } else {
                    "fast: prefiltered lights, real time".to_string()
                };
                ui.label(egui::RichText::new(text).small());
            }
        }
        let (films, maps) = match &self.mode {
            Mode::Scene(sv) => (sv.films, sv.maps.len()),
            Mode::Table(_) => (0, 1),
        };
        if films > 0 {
            ui.separator();
            ui.label(format!("Thin films ({films} material{})", if films == 1 { "" } else { "s" }));
            changed |=
                ui.add(egui::Slider::new(&mut self.film.thickness_scale, 0.0..=3.0).text("thickness ×")).changed();
            ui.horizontal(|ui| {
                changed |= ui.checkbox(&mut self.ior_on, "film IOR").changed();
                changed |= ui.add_enabled(self.ior_on, egui::Slider::new(&mut self.ior, 1.0..=2.6)).changed();
            });
            changed |= ui.add(egui::Slider::new(&mut self.film.svt_scale, 0.0..=3.0).text("SVT strength ×")).changed();
        }
        let mut map_changed = false;
        if maps > 0 {
            ui.separator();
            ui.label("Diffraction");
            ui.horizontal(|ui| {
                ui.label("method");
                egui::ComboBox::from_id_salt("method").selected_text("lookup (GPU)").show_ui(ui, |ui| {
                    let _ = ui.selectable_label(true, "lookup (GPU)");
                });
            });
            ui.label(
                egui::RichText::new(
                    "reference and ground truth run on the CPU: iridis brdf-map --method reference|ground-truth",
                )
                .small(),
            );
            if let Mode::Scene(sv) = &self.mode {
                let names: Vec<String> = sv.maps.iter().map(|m| m.name.clone()).collect();
                let current = names.get(self.map_index).cloned().unwrap_or_default();
                egui::ComboBox::from_id_salt("table").selected_text(format!("table of {current}")).show_ui(ui, |ui| {
                    for (i, n) in names.iter().enumerate() {
                        map_changed |= ui.selectable_value(&mut self.map_index, i, n).changed();
                    }
                });
                if let Some(m) = sv.maps.get(self.map_index) {
                    ui.label(egui::RichText::new(&m.info).small());
                }
            } else if let Mode::Table(mv) = &self.mode {
                ui.label(egui::RichText::new(&mv.info).small());
            }
            ui.label("BRDF-map incidence");
            map_changed |= ui.add(egui::Slider::new(&mut self.map_theta, 0.0..=89.0).text("θi (°)")).changed();
            map_changed |= ui.add(egui::Slider::new(&mut self.map_phi, -180.0..=180.0).text("φi (°)")).changed();
            if matches!(self.mode, Mode::Scene(_)) {
                if let Some(t) = &self.map_tex {
                    ui.image((t.id(), egui::vec2(200.0, 200.0)));
                }
            }
        }
        ui.separator();
        if let Some(t) = self.times.last() {
            let ms = t.wall.as_secs_f64() * 1e3;
            ui.label(format!("frame {ms:.1} ms ({:.1} fps)", 1e3 / ms.max(1e-6)));
            // The render pass's own timestamps (a query set around our compute pass): the shading alone,
            // without submission and waiting.
            if let Some(g) = t.gpu {
                ui.label(format!("render pass {:.2} ms (GPU timestamps)", g.as_secs_f64() * 1e3));
            }
            ui.label(format!("{} frames rendered", self.times.len()));
        }
        for s in &self.status {
            ui.colored_label(egui::Color32::from_rgb(230, 170, 60), s);
        }
        if changed {
            self.dirty = true;
            self.map_dirty = true;
        }
        if map_changed {
            self.map_dirty = true;
            if matches!(self.mode, Mode::Table(_)) {
                self.dirty = true;
            }
        }
    }

    fn handle_input(&mut self, ctx: &egui::Context, resp: &egui::Response) {
        let shift = ctx.input(|i| i.modifiers.shift);
        let d = resp.drag_delta();
        if d != egui::Vec2::ZERO {
            let light = resp.dragged_by(egui::PointerButton::Secondary) || shift;
            match &mut self.mode {
                Mode::Scene(sv) => {
                    if light {
                        sv.light_yaw -= d.x as f64 * 0.01;
                        sv.light_pitch -= d.y as f64 * 0.01;
                    } else if let Some(o) = &mut sv.orbit {
                        o.yaw -= d.x as f64 * 0.01;
                        o.pitch = (o.pitch + d.y as f64 * 0.01).clamp(-1.5, 1.5);
                    }
                }
                Mode::Table(_) => {
                    self.map_phi = (self.map_phi + d.x as f64 * 0.5 + 180.0).rem_euclid(360.0) - 180.0;
                    self.map_theta = (self.map_theta + d.y as f64 * 0.3).clamp(0.0, 89.0);
                }
            }
            self.dirty = true;
        }
        if resp.hovered() {
            let scroll = ctx.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                match &mut self.mode {
                    Mode::Scene(sv) => {
                        if let Some(o) = &mut sv.orbit {
                            let f = (-scroll as f64 * 0.002).exp();
                            if o.ortho {
                                o.lens *= f;
                            } else {
                                o.dist *= f;
                            }
                            self.dirty = true;
                        }
                    }
                    // A BRDF map spans decades of radiance: the wheel brightens (up) or darkens it, within the
                    // exposure slider's range.
                    Mode::Table(_) => {
                        self.exposure = (self.exposure * (scroll as f64 * 0.004).exp()).clamp(0.01, 20000.0);
                        self.dirty = true;
                    }
                }
            }
        }
        ctx.input(|i| {
            if i.key_pressed(egui::Key::H) {
                self.help = !self.help;
            }
            if i.key_pressed(egui::Key::R) {
                if let Mode::Scene(sv) = &mut self.mode {
                    sv.orbit = sv.home;
                    sv.light_yaw = 0.0;
                    sv.light_pitch = 0.0;
                }
                self.dirty = true;
            }
            if i.key_pressed(egui::Key::Escape) {
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        });
    }

    /// Injects the check's inputs (pointer drags over the image, a key, the wheel) before egui sees the frame.
    fn script(&mut self, raw: &mut egui::RawInput) {
        let Some(rect) = self.image_rect else { return };
        let rendered = self.times.len();
        let Some(c) = &mut self.check else { return };
        let centre = rect.center();
        let m = egui::Modifiers::NONE;
        let drag = |button: egui::PointerButton, tick: usize, raw: &mut egui::RawInput| match tick {
            0 => {
                raw.events.push(egui::Event::PointerMoved(centre));
                raw.events.push(egui::Event::PointerButton { pos: centre, button, pressed: true, modifiers: m });
            }
            1..=3 => raw.events.push(egui::Event::PointerMoved(centre + egui::vec2(25.0 * tick as f32, 12.0))),
            4 => raw.events.push(egui::Event::PointerButton {
                pos: centre + egui::vec2(75.0, 12.0),
                button,
                pressed: false,
                modifiers: m,
            }),
            _ => {}
        };
        // Steps: 0 wait for the first image; 1 orbit (primary drag); 2 light (secondary drag); 3 wheel;
        // 4 the H key; 5 screenshot.
        match c.step {
            0 if rendered >= 1 => {
                // Hover the image first, as a hand on a mouse would; the drags start next frame.
                raw.events.push(egui::Event::PointerMoved(centre));
                c.tick = 1;
            }
            1 | 2 => {
                let button = if c.step == 1 { egui::PointerButton::Primary } else { egui::PointerButton::Secondary };
                drag(button, c.tick, raw);
            }
            3 if c.tick == 0 => {
                raw.events.push(egui::Event::PointerMoved(centre));
                raw.events.push(egui::Event::MouseWheel {
                    unit: egui::MouseWheelUnit::Point,
                    delta: egui::vec2(0.0, 120.0),
                    phase: egui::TouchPhase::Move,
                    source: egui::MouseWheelSource::Wheel,
                    modifiers: m,
                });
            }
            4 if c.tick == 0 => {
                for pressed in [true, false] {
                    raw.events.push(egui::Event::Key {
                        key: egui::Key::H,
                        physical_key: Some(egui::Key::H),
                        pressed,
                        repeat: false,
                        modifiers: m,
                    });
                }
            }
            _ => {}
        }
    }

    /// Advances the check after a frame: measures what the step's input changed.
    fn check_after_frame(&mut self, ctx: &egui::Context, help_before: bool) {
        let shown = self.shown.clone();
        let help = self.help;
        let map = matches!(self.mode, Mode::Table(_));
        let Some(c) = &mut self.check else { return };
        ctx.request_repaint();
        if c.step == 0 {
            if c.tick == 1 {
                c.step = 1;
                c.tick = 0;
            }
            return;
        }
        if c.tick == 0 && c.step <= 3 {
            c.before = Some(shown.clone());
        }
        c.tick += 1;
        let done = match c.step {
            1 | 2 => c.tick >= 7,
            3 => c.tick >= 3,
            4 => {
                if c.tick == 1 {
                    c.steps.push(("H key toggles the on-screen help".into(), f64::from(u8::from(help != help_before))));
                }
                c.tick >= 2
            }
            _ => false,
        };
        if done && c.step <= 3 {
            let before = c.before.take().unwrap_or_default();
            let diff = if before.len() == shown.len() && !before.is_empty() {
                before.iter().zip(&shown).map(|(a, b)| (*a as f64 - *b as f64).abs()).sum::<f64>() / before.len() as f64
            } else {
                f64::NAN
            };
            let name = if map {
                ["", "left drag turns the incidence", "right drag turns the incidence", "wheel changes the exposure"]
            } else {
                ["", "left drag orbits the camera", "right drag moves the light", "wheel zooms"]
            }[c.step];
            c.steps.push((name.into(), diff));
        }
        if done {
            c.step += 1;
            c.tick = 0;
        }
        if c.step == 5 && !c.requested {
            c.requested = true;
            let slot = c.screenshot.clone();
            ctx.request_screenshot(move |img| {
                *slot.lock().unwrap_or_else(|p| p.into_inner()) = Some(img);
            });
        }
        if c.requested {
            let shot = c.screenshot.lock().unwrap_or_else(|p| p.into_inner()).take();
            if let Some(img) = shot {
                let ms: Vec<f64> = self.times.iter().map(|t| t.wall.as_secs_f64() * 1e3).collect();
                let gpu_ms: Vec<f64> = self.times.iter().filter_map(|t| t.gpu).map(|g| g.as_secs_f64() * 1e3).collect();
                let rgba: Vec<u8> = img.pixels.iter().flat_map(|p| p.to_array()).collect();
                *self.report.lock().unwrap_or_else(|p| p.into_inner()) = Some(CheckReport {
                    adapter: self.gpu.adapter_name(),
                    frames: self.times.len(),
                    steps: c.steps.clone(),
                    frame_ms: median(ms),
                    gpu_ms: (!gpu_ms.is_empty()).then(|| median(gpu_ms)),
                    readback_ms: median(self.readback_ms.clone()),
                    texture_equals_frame: self.texture_equals_frame && !self.readback_ms.is_empty(),
                    screenshot: Some((img.size[0], img.size[1], rgba)),
                });
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
    }
}

/// The median of some times (NaN for none).
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

const HELP: &str = "drag: orbit the camera · right-drag or shift-drag: move the light · wheel: zoom\n\
R: reset view and light · H: hide/show this help · Esc: quit\n\
The scene file is reloaded when it changes on disk.";

const HELP_MAP: &str = "drag: turn the light's incidence (θ up-down, φ left-right) · wheel: exposure\n\
H: hide/show this help · Esc: quit";

impl eframe::App for Viewer {
    fn raw_input_hook(&mut self, _ctx: &egui::Context, raw: &mut egui::RawInput) {
        if self.check.is_some() {
            self.script(raw);
        }
    }

    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.reload_if_changed();
        let help_before = self.help;
        egui::Panel::left("controls").resizable(false).exact_size(300.0).show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| self.panel(ui));
        });
        egui::CentralPanel::default().show(ui, |ui| {
            let avail = ui.available_size();
            let ppp = ctx.pixels_per_point();
            let px = [
                ((avail.x * ppp * self.res_scale).round() as u32).clamp(16, 4096),
                ((avail.y * ppp * self.res_scale).round() as u32).clamp(16, 4096),
            ];
            let size_changed = match &self.mode {
                Mode::Scene(sv) => sv.frame.as_ref().map(|f| f.size()) != Some((px[0], px[1])),
                Mode::Table(_) => self.frame_tex.as_ref().map(|t| t.target.width) != Some(px[0].min(px[1])),
            };
            if self.dirty || size_changed || self.accumulating() {
                let restart = self.dirty || size_changed;
                self.dirty = false;
                if let Err(e) = self.render(px, restart) {
                    if self.check.is_some() {
                        // The scripted check waits for frames: a frame that fails would leave it waiting.
                        eprintln!("error: view --check: the frame failed: {e}");
                        std::process::exit(1);
                    }
                    self.status = vec![e];
                }
            }
            if self.map_dirty {
                self.map_dirty = false;
                self.render_map_view(&ctx);
            }
            if let Some(t) = &self.frame_tex {
                let size = match &self.mode {
                    Mode::Scene(_) => avail,
                    Mode::Table(_) => egui::vec2(avail.x.min(avail.y), avail.x.min(avail.y)),
                };
                let resp = ui.add(egui::Image::new((t.id, size)).sense(egui::Sense::click_and_drag()));
                self.image_rect = Some(resp.rect);
                self.handle_input(&ctx, &resp);
                if self.help {
                    let pos = resp.rect.left_top() + egui::vec2(8.0, 8.0);
                    egui::Area::new(egui::Id::unique("iridis-help")).fixed_pos(pos).show(&ctx, |ui| {
                        egui::Frame::popup(ui.style())
                            .show(ui, |ui| ui.label(if matches!(self.mode, Mode::Table(_)) { HELP_MAP } else { HELP }));
                    });
                }
            }
        });
        if self.dirty || self.accumulating() {
            ctx.request_repaint();
        }
        if self.check.is_some() {
            self.check_after_frame(&ctx, help_before);
        } else if matches!(self.mode, Mode::Scene(_)) {
            // Poll the scene file for changes.
            ctx.request_repaint_after(Duration::from_millis(500));
        }
    }
}
