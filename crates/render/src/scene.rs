//! The scene a renderer draws: camera, lights, environment, meshes and analytic shapes, materials, textures,
//! output settings and how extended light is integrated. The loaders build it: [`crate::scene_toml`] from
//! the TOML format, [`crate::gltf_scene`] from a glTF file ([`crate::load`] picks by the file's extension).

use std::path::PathBuf;

use iridis_color::Encoding;

use crate::area::AreaLight;
use crate::bvh::Bvh;
use crate::camera::Camera;
use crate::geometry::{Mesh, Plane, Sphere};
use crate::light::{EnvSampler, Environment, Light, Rgb};
use crate::material::*;
use crate::math::*;
use crate::texture::Texture;

/// Image settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// Image size in pixels, 1 to [`MAX_IMAGE_SIDE`] a side.
    pub width: u32,
    pub height: u32,
    /// Samples per pixel, 1 to [`MAX_SPP`].
    pub spp: u32,
    /// Exposure in RU (PHYSICS.md): linear colours are multiplied by it before clipping and encoding.
    pub exposure: f64,
    pub encoding: Encoding,
    /// Linear sRGB shown where a primary ray leaves the scene and the environment is hidden.
    pub background: Rgb,
    /// Reflection/transmission bounces before the environment takes over.
    pub max_depth: u32,
    /// The random streams' seed (Monte Carlo): renders with different seeds are independent estimates.
    pub seed: u64,
}

/// The largest image side in pixels (a 16384² RGB f32 image is 3 GiB), for scenes, `--size` and the GPU's
/// frames alike.
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// The most samples per pixel a render takes (`spp`, `--spp`).
pub const MAX_SPP: u32 = 4096;

/// Whether an image of `width × height` pixels is one the renderers make; the error is the rule, for the caller
/// to put after the name of what gave the size (`--size`, `[output] size`, a frame).
pub fn check_image_size(width: u32, height: u32) -> Result<(), String> {
    let side = 1..=MAX_IMAGE_SIDE;
    if side.contains(&width) && side.contains(&height) {
        return Ok(());
    }
    Err(format!("width and height must be from 1 to {MAX_IMAGE_SIDE} pixels"))
}

/// Whether `spp` samples per pixel is a number the renderers take; the error is the rule, as above.
pub fn check_spp(spp: u32) -> Result<(), String> {
    if (1..=MAX_SPP).contains(&spp) {
        return Ok(());
    }
    Err(format!("use 1 to {MAX_SPP} samples per pixel"))
}

/// A scene ready to render.
#[derive(Debug, Clone)]
pub struct Scene {
    pub camera: Camera,
    pub lights: Vec<Light>,
    pub environment: Environment,
    /// Whether primary rays that miss show the environment (else `output.background`).
    pub environment_visible: bool,
    pub meshes: Vec<Mesh>,
    pub spheres: Vec<Sphere>,
    pub planes: Vec<Plane>,
    pub materials: Vec<Material>,
    pub material_names: Vec<String>,
    pub textures: Vec<Texture>,
    pub bvh: Bvh,
    pub output: Output,
    /// The environment's irradiance map ([`Environment::irradiance_map`]; `None` where it is uniform), made
    /// by the loaders; call [`Scene::update_irradiance`] after changing `environment`.
    pub irradiance: Option<Texture>,
    /// The environment as directional lights ([`Environment::as_lights`]) for diffraction,
    /// made with `irradiance`.
    pub environment_lights: Vec<([f64; 3], [f64; 3])>,
    /// Sphere, disk and rectangle lights.
    pub area_lights: Vec<AreaLight>,
    /// How extended light (the environment, area lights) is integrated.
    pub integration: Integration,
    /// The environment's importance sampler (Monte Carlo), made with `irradiance`.
    pub env_sampler: Option<EnvSampler>,
    /// Notes for the user (normals computed, tangents generated, …).
    pub notes: Vec<String>,
    /// What the user should know because the picture may not be what the file meant (a glTF film thickness
    /// that looks written in the wrong unit, …).
    pub warnings: Vec<String>,
    /// The sections a TOML scene was written with, for exporting it with its materials
    /// ([`crate::gltf_export::scene_glb`]); `None` for a glTF scene.
    pub source: Option<SceneSource>,
}

/// A TOML scene as written: its `[output]`, `[environment]`, `[textures]` and `[materials]` sections as JSON
/// (`{"output": …, "environment": …, "textures": {name: …}, "materials": {name: …}}`, absent sections left
/// out) and the folder its relative paths are resolved against. A GLB exported from the scene carries them in
/// its `extras`, and iridis rebuilds the materials from them when it reads the file back.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSource {
    pub sections: serde_json::Value,
    pub base: PathBuf,
}

impl SceneSource {
    /// The sections as TOML text with a stand-in camera: a scene [`crate::scene_toml::parse_scene`] reads back into the same
    /// materials, textures, environment and output.
    pub fn to_toml(&self) -> String {
        let mut out = String::from("[camera]\nposition = [0, 0, 1]\n");
        let table = |out: &mut String, header: &str, v: &serde_json::Value| {
            out.push_str(&format!("[{header}]\n"));
            for (k, x) in v.as_object().into_iter().flatten() {
                out.push_str(&format!("{} = {}\n", toml_key(k), toml_value(x)));
            }
        };
        for section in ["output", "environment"] {
            if let Some(v) = self.sections.get(section) {
                table(&mut out, section, v);
            }
        }
        for section in ["textures", "materials"] {
            for (name, v) in self.sections.get(section).and_then(|t| t.as_object()).into_iter().flatten() {
                table(&mut out, &format!("{section}.{}", toml_key(name)), v);
            }
        }
        out
    }
}

/// A TOML key: bare where it may be, quoted otherwise.
fn toml_key(k: &str) -> String {
    if !k.is_empty() && k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
        k.to_string()
    } else {
        toml_string(k)
    }
}

fn toml_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 || c == '\u{7f}' => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A JSON value (as [`SceneSource`] keeps a TOML value) written back as TOML; objects become inline tables.
fn toml_value(v: &serde_json::Value) -> String {
    match v {
        serde_json::Value::Null => "\"\"".into(),
        serde_json::Value::Bool(b) => b.to_string(),
        serde_json::Value::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => i.to_string(),
            (None, Some(f)) => format!("{f:?}"),
            _ => n.to_string(),
        },
        serde_json::Value::String(s) => toml_string(s),
        serde_json::Value::Array(a) => format!("[{}]", a.iter().map(toml_value).collect::<Vec<_>>().join(", ")),
        serde_json::Value::Object(o) => format!(
            "{{ {} }}",
            o.iter().map(|(k, x)| format!("{} = {}", toml_key(k), toml_value(x))).collect::<Vec<_>>().join(", ")
        ),
    }
}

impl Scene {
    /// Recomputes [`Scene::irradiance`] and [`Scene::environment_lights`] from `environment`.
    pub fn update_irradiance(&mut self) {
        self.irradiance = self.environment.irradiance_map();
        self.environment_lights = self.environment.as_lights();
        self.env_sampler = EnvSampler::new(&self.environment);
    }

    /// Multiplies every length by `s` about the origin: objects, camera, point lights (whose irradiance at
    /// distance 1 is multiplied by `s²`, so that what arrives at the scaled objects is unchanged) and laser
    /// spots (their beam power likewise). Infinite
    /// planes' UV unit scales too, so their textures stay put. Materials keep their nanometre scales. The image
    /// is the same at any `s` (the renderers' tests check this at 10⁻³ and 10³).
    pub fn scale(&mut self, s: f64) {
        for sp in &mut self.spheres {
            sp.center = mul(sp.center, s);
            sp.radius *= s;
        }
        for p in &mut self.planes {
            p.center = mul(p.center, s);
            p.size = p.size.map(|[w, h]| [w * s, h * s]);
            p.uv_unit *= s;
        }
        for m in &mut self.meshes {
            for p in &mut m.positions {
                *p = mul(*p, s);
            }
        }
        for l in &mut self.lights {
            match l {
                Light::Point { position, rgb } => {
                    *position = mul(*position, s);
                    *rgb = mul(*rgb, s * s);
                }
                // A beam's power is irradiance × area: the same image needs `s²` of it.
                Light::Laser(spot) => {
                    spot.position = mul(spot.position, s);
                    spot.rgb = mul(spot.rgb, s * s);
                }
                Light::Directional { .. } => {}
            }
        }
        for l in &mut self.area_lights {
            *l = l.scaled(s);
        }
        self.camera = match self.camera.clone() {
            Camera::Perspective { position, forward, right, up, tan_half } => {
                Camera::Perspective { position: mul(position, s), forward, right, up, tan_half }
            }
            Camera::Orthographic { position, forward, right, up, half_height } => {
                Camera::Orthographic { position: mul(position, s), forward, right, up, half_height: half_height * s }
            }
            Camera::Hemisphere { target, normal, right, up, distance } => {
                Camera::Hemisphere { target: mul(target, s), normal, right, up, distance: distance * s }
            }
        };
        self.bvh = Bvh::build(&self.meshes);
    }
}

/// How the environment (and area lights) reach surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Integration {
    /// Deterministic and real-time: the environment's irradiance map and mirror ray, its 64 directional lights
    /// for diffraction (each a prefiltered area light); an area light as one directional light from its centre
    /// with its irradiance (diffraction: the lobe averaged over its solid angle). Secondary rays do not see
    /// area lights.
    #[default]
    Fast,
    /// Monte Carlo; converges with the samples per pixel. The strategy is multiple importance sampling; the
    /// two single-technique estimators exist to check it (they converge to the same image, with more noise).
    MonteCarlo(Strategy),
}

/// Which samples of extended light count (the weights of the two techniques).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Strategy {
    /// Light and BRDF samples, weighted by the power heuristic.
    #[default]
    Mis,
    /// Light samples only (the BRDF's samples still carry the path to other surfaces).
    Light,
    /// BRDF samples only.
    Brdf,
}
