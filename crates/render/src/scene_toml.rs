//! The TOML scene format (documented with examples in `docs/render.md`): [`parse_scene`] builds a
//! [`Scene`] from it.
//!
//! Every section is a flat table with a `kind` key; unknown keys are refused, and every error names the file,
//! the line and the key. Paths are relative to the scene file.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use iridis_color::units::{parse_angle_rad, parse_length_nm};
use iridis_color::{Encoding, Illuminant};
use iridis_diffraction::table::{Lookup, Precision, TableParams};
use iridis_diffraction::{Fresnel, Shading, Units};
use iridis_thinfilm::htsg::{Htsg, Roughness, Series};
use serde::Deserialize;
use toml::Spanned;

use crate::area::{AreaLight, Shape};
use crate::bvh::Bvh;
use crate::camera::{frame, Camera};
use crate::error::RenderError;
use crate::geometry::{Plane, Sphere};
use crate::light::{equirect_mean, illuminant_tint, EnvSampler, Environment, Light, Rgb};
use crate::material::*;
use crate::math::*;
use crate::scene::{Integration, Output, Scene, SceneSource};
use crate::snake::{snake_mesh, ScaleKind, SnakeParams};
use crate::texture::{TexKind, Texture};

// ---------------------------------------------------------------- the file format (serde)

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(default)]
    output: OutputDef,
    camera: Spanned<CameraDef>,
    #[serde(default)]
    light: Vec<Spanned<LightDef>>,
    environment: Option<Spanned<EnvDef>>,
    #[serde(default)]
    textures: BTreeMap<String, Spanned<TextureDef>>,
    #[serde(default)]
    materials: BTreeMap<String, Spanned<MaterialDef>>,
    #[serde(default)]
    object: Vec<Spanned<ObjectDef>>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct OutputDef {
    size: Option<[u32; 2]>,
    spp: Option<u32>,
    exposure: Option<f64>,
    encoding: Option<String>,
    background: Option<[f64; 3]>,
    max_depth: Option<u32>,
    integration: Option<String>,
    seed: Option<u64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDef {
    kind: Option<String>,
    position: Option<[f64; 3]>,
    look_at: Option<[f64; 3]>,
    up: Option<[f64; 3]>,
    fov: Option<String>,
    height: Option<f64>,
    target: Option<[f64; 3]>,
    normal: Option<[f64; 3]>,
    distance: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDef {
    kind: String,
    direction: Option<[f64; 3]>,
    position: Option<[f64; 3]>,
    intensity: Option<f64>,
    spectrum: Option<String>,
    color: Option<[f64; 3]>,
    radius: Option<f64>,
    normal: Option<[f64; 3]>,
    look_at: Option<[f64; 3]>,
    tangent: Option<[f64; 3]>,
    size: Option<[f64; 2]>,
    visible: Option<bool>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct EnvDef {
    kind: String,
    color: Option<[f64; 3]>,
    zenith: Option<[f64; 3]>,
    horizon: Option<[f64; 3]>,
    ground: Option<[f64; 3]>,
    file: Option<String>,
    intensity: Option<f64>,
    rotation: Option<String>,
    visible: Option<bool>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TextureDef {
    kind: String,
    file: Option<String>,
    scale: Option<f64>,
    octaves: Option<u32>,
    seed: Option<u32>,
    from: Option<f64>,
    to: Option<f64>,
    along: Option<String>,
    base: Option<[f64; 3]>,
    edge: Option<[f64; 3]>,
    a: Option<[f64; 3]>,
    b: Option<[f64; 3]>,
    n: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDef {
    kind: String,
    color: Option<[f64; 3]>,
    texture: Option<String>,
    /// microfacet: GGX roughness in [0, 1]; thinfilm: rms height of the rough substrate, a length ("25nm").
    roughness: Option<NumOrText>,
    /// thinfilm: autocorrelation length of the rough substrate ("300nm").
    correlation: Option<String>,
    metallic: Option<f64>,
    ior: Option<f64>,
    table: Option<String>,
    uv_resolution: Option<usize>,
    orientation: Option<String>,
    orientation_texture: Option<String>,
    direction: Option<[f64; 3]>,
    angle: Option<String>,
    scale_ru: Option<f64>,
    w_diffuse: Option<f64>,
    ambient: Option<f64>,
    fresnel_n: Option<f64>,
    units: Option<String>,
    blend: Option<String>,
    stack: Option<String>,
    svt: Option<String>,
    d_rel: Option<String>,
    transmission: Option<bool>,
    base: Option<String>,
    factor: Option<f64>,
}

/// A value that is a number for one material kind and a length with its unit for another (`roughness`).
#[derive(Debug, Clone, PartialEq)]
enum NumOrText {
    Num(f64),
    Text(String),
}

impl<'de> Deserialize<'de> for NumOrText {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = NumOrText;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number (microfacet roughness, 0–1) or a length with its unit (thin film, e.g. \"25nm\")")
            }
            fn visit_f64<E>(self, v: f64) -> Result<NumOrText, E> {
                Ok(NumOrText::Num(v))
            }
            fn visit_i64<E>(self, v: i64) -> Result<NumOrText, E> {
                Ok(NumOrText::Num(v as f64))
            }
            fn visit_u64<E>(self, v: u64) -> Result<NumOrText, E> {
                Ok(NumOrText::Num(v as f64))
            }
            fn visit_str<E>(self, v: &str) -> Result<NumOrText, E> {
                Ok(NumOrText::Text(v.to_string()))
            }
        }
        d.deserialize_any(V)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectDef {
    kind: String,
    material: Option<String>,
    center: Option<[f64; 3]>,
    radius: Option<f64>,
    normal: Option<[f64; 3]>,
    tangent: Option<[f64; 3]>,
    size: Option<[f64; 2]>,
    file: Option<String>,
    translate: Option<[f64; 3]>,
    scale: Option<f64>,
    rotate: Option<[f64; 3]>,
    length: Option<f64>,
    waves: Option<f64>,
    amplitude: Option<f64>,
    rings: Option<usize>,
    segments: Option<usize>,
    tiles: Option<[f64; 2]>,
    scales: Option<String>,
    scale_rows: Option<usize>,
    scale_length: Option<f64>,
    section: Option<[f64; 2]>,
    scale_grid: Option<[usize; 2]>,
    eye_material: Option<String>,
}

// ---------------------------------------------------------------- loading

/// The most triangles a scaled snake may have: 112 MB of triangle records on the GPU, within the 128 MiB
/// that lavapipe binds in one storage buffer.
const MAX_SNAKE_TRIANGLES: usize = 500_000;

/// The first number of a scene document that is not finite: where it is (`[output]`, `[[object]] #2`), the key
/// that holds it, and the number.
fn non_finite_number(doc: &toml::Table) -> Option<(String, String, f64)> {
    fn find(v: &toml::Value, key: &str) -> Option<(String, f64)> {
        match v {
            toml::Value::Float(x) if !x.is_finite() => Some((key.to_string(), *x)),
            toml::Value::Array(a) => a.iter().find_map(|x| find(x, key)),
            toml::Value::Table(t) => t.iter().find_map(|(k, x)| find(x, k)),
            _ => None,
        }
    }
    doc.iter().find_map(|(section, v)| match v {
        toml::Value::Array(items) if items.iter().all(toml::Value::is_table) => items
            .iter()
            .enumerate()
            .find_map(|(i, x)| find(x, section).map(|(k, n)| (format!("[[{section}]] #{}", i + 1), k, n))),
        toml::Value::Table(t) => t.iter().find_map(|(k, x)| {
            // [materials.NAME], [textures.NAME]: one level deeper.
            let place = if x.is_table() { format!("[{section}.{k}]") } else { format!("[{section}]") };
            find(x, k).map(|(key, n)| (place, key, n))
        }),
        _ => find(v, section).map(|(k, n)| ("the top level".to_string(), k, n)),
    })
}

/// 1-based line of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].bytes().filter(|&b| b == b'\n').count() + 1
}

struct Ctx<'a> {
    text: &'a str,
    name: &'a str,
    base: PathBuf,
    /// Notes made while building (what a material's height field was read and levelled as).
    notes: std::cell::RefCell<Vec<String>>,
}

impl Ctx<'_> {
    fn err(&self, span: std::ops::Range<usize>, msg: impl Into<String>) -> RenderError {
        RenderError::Scene { path: self.name.to_string(), line: line_of(self.text, span.start), message: msg.into() }
    }
    /// An error at the line where `key` is written in the table at `span`.
    fn err_key(&self, span: &std::ops::Range<usize>, key: &str, msg: impl Into<String>) -> RenderError {
        RenderError::Scene { path: self.name.to_string(), line: key_line(self.text, span, key), message: msg.into() }
    }
    fn path(&self, p: &str) -> PathBuf {
        self.base.join(p)
    }
}

fn need<T: Copy>(
    v: Option<T>,
    ctx: &Ctx,
    span: &std::ops::Range<usize>,
    what: &str,
    key: &str,
) -> Result<T, RenderError> {
    v.ok_or_else(|| ctx.err(span.clone(), format!("{what}: missing key `{key}`")))
}

fn angle(
    s: &Option<String>,
    ctx: &Ctx,
    span: &std::ops::Range<usize>,
    key: &str,
    default: f64,
) -> Result<f64, RenderError> {
    match s {
        None => Ok(default),
        Some(s) => parse_angle_rad(s).map_err(|e| ctx.err(span.clone(), format!("`{key}` = \"{s}\": {e}"))),
    }
}

/// Parses scene text. `name` is used in messages; relative paths are resolved against `base`.
pub fn parse_scene(text: &str, name: &str, base: &Path) -> Result<Scene, RenderError> {
    let file: SceneFile = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| line_of(text, s.start)).unwrap_or(1);
        let src = text.lines().nth(line - 1).unwrap_or("").trim();
        let message = if src.is_empty() { e.message().to_string() } else { format!("{} (in `{src}`)", e.message()) };
        RenderError::Scene { path: name.to_string(), line, message }
    })?;
    let ctx = Ctx { text, name, base: base.to_path_buf(), notes: Default::default() };
    // TOML writes `nan` and `inf` as numbers; no length, angle, colour or intensity is one (a sphere centred at
    // nan was drawn nowhere, without a word).
    if let Ok(doc) = toml::from_str::<toml::Table>(text) {
        if let Some((place, key, x)) = non_finite_number(&doc) {
            let line = text
                .lines()
                .position(|l| {
                    let code = l.split('#').next().unwrap_or("");
                    code.contains(&key)
                        && code.split(|c: char| !c.is_ascii_alphanumeric()).any(|w| w == "nan" || w == "inf")
                })
                .map_or(1, |i| i + 1);
            return Err(RenderError::Scene {
                path: name.to_string(),
                line,
                message: format!("{place}: `{key}` holds {x}: the numbers of a scene must be finite"),
            });
        }
    }
    let mut notes = Vec::new();
    let mut warnings = Vec::new();

    // Output
    let o = &file.output;
    let [width, height] = o.size.unwrap_or([512, 512]);
    let encoding = Encoding::parse(o.encoding.as_deref().unwrap_or("srgb"))
        .map_err(|e| ctx.err(0..0, format!("[output] encoding: {e}")))?;
    let output = Output {
        width,
        height,
        spp: o.spp.unwrap_or(1),
        exposure: o.exposure.unwrap_or(1.0),
        encoding,
        background: o.background.unwrap_or([0.0; 3]),
        max_depth: o.max_depth.unwrap_or(6),
        seed: o.seed.unwrap_or(0),
    };
    if !(output.exposure.is_finite() && output.exposure > 0.0) {
        return Err(ctx.err(0..0, "[output] `exposure` must be a positive number of RU"));
    }
    // The limits of --size and --spp, which replace these (a 0 × 0 image failed only at the PNG encoder, after the
    // render; 10⁵ × 10⁵ began a render of 120 GB; spp = 0 wrote a black image).
    crate::scene::check_image_size(width, height)
        .map_err(|e| ctx.err(0..0, format!("[output] `size` = [{width}, {height}]: {e}")))?;
    crate::scene::check_spp(output.spp).map_err(|e| ctx.err(0..0, format!("[output] `spp` = {}: {e}", output.spp)))?;
    if !output.background.iter().all(|c| c.is_finite() && *c >= 0.0) {
        return Err(ctx.err(0..0, "[output] `background` must be three finite linear sRGB values ≥ 0"));
    }

    let camera = build_camera(&file.camera, &ctx)?;

    // Textures
    let mut textures = Vec::new();
    let mut tex_index = BTreeMap::new();
    for (name, def) in &file.textures {
        let span = def.span();
        let t = build_texture(name, def.get_ref(), &span, &ctx)?;
        tex_index.insert(name.clone(), (textures.len(), span));
        textures.push(t);
    }
    let texture_ref = |tname: &str, kind: TexKind, span: &std::ops::Range<usize>, key: &str| {
        let (i, _) = tex_index.get(tname).ok_or_else(|| {
            ctx.err(span.clone(), format!("`{key}` = \"{tname}\": no texture of that name in [textures]"))
        })?;
        let k = textures[*i].kind();
        if k != kind {
            return Err(ctx.err(
                span.clone(),
                format!(
                    "`{key}` = \"{tname}\": a {} texture is needed here, but \"{tname}\" is a {} texture",
                    kind.name(),
                    k.name()
                ),
            ));
        }
        Ok(*i)
    };

    // Materials
    let mut materials = Vec::new();
    let mut material_names = Vec::new();
    let mut mat_index = BTreeMap::new();
    // Thin films may name a base material defined anywhere: build the others first.
    let mut order: Vec<_> = file.materials.iter().collect();
    order.sort_by_key(|(_, d)| d.get_ref().base.is_some());
    // The keys as written, to refuse those that belong to another kind of material (serde only knows the union).
    let raw: toml::Table = toml::from_str(text).unwrap_or_default();
    for (name, def) in order {
        let span = def.span();
        let written = raw.get("materials").and_then(|m| m.get(name)).and_then(|t| t.as_table());
        check_material_keys(name, &def.get_ref().kind, written, &span, &ctx)?;
        let m = build_material(name, def.get_ref(), &span, &ctx, &texture_ref, &mat_index, &materials)?;
        // Where the texture thins a layer by more than it holds, the layer is clamped at 0 nm (the stack's
        // evaluate_offset): a note, since those texels show the stack without that layer.
        if let Some((film, svt)) = match &m {
            Material::ThinFilm(film) => film.svt.as_ref().map(|svt| (film, svt)),
            _ => None,
        } {
            let thinnest = film.stack.thicknesses().into_iter().fold(f64::INFINITY, f64::min);
            let d_rel = svt.d_rel_nm;
            if d_rel.abs() > thinnest {
                // d = d_avg + d_rel (2α − 1) < 0 below α = (1 − d/d_rel)/2, or above (1 + d/|d_rel|)/2 for d_rel < 0.
                let (side, alpha) = if d_rel > 0.0 {
                    ("below", 0.5 * (1.0 - thinnest / d_rel))
                } else {
                    ("above", 0.5 * (1.0 + thinnest / -d_rel))
                };
                notes.push(format!(
                    "[materials.{name}]: |d_rel| = {} nm is more than its thinnest layer ({thinnest} nm): where the \
                     svt texture is {side} {alpha:.3}, that layer is clamped to 0 nm",
                    d_rel.abs()
                ));
            }
        }
        mat_index.insert(name.clone(), materials.len());
        materials.push(m);
        material_names.push(name.clone());
    }

    let integration = match o.integration.as_deref() {
        None | Some("fast") => Integration::Fast,
        Some("monte-carlo") => Integration::MonteCarlo(Default::default()),
        Some(other) => {
            return Err(ctx
                .err(0..0, format!("[output] integration = \"{other}\": use \"fast\" (real-time) or \"monte-carlo\"")))
        }
    };

    // Lights (a laser's spot is found once the objects are in place)
    let mut lights = Vec::new();
    let mut area_lights = Vec::new();
    let mut lasers = Vec::new();
    for l in &file.light {
        if l.get_ref().kind == "laser" {
            lasers.push(build_laser_beam(l.get_ref(), &l.span(), &ctx)?);
        } else {
            match build_light(l.get_ref(), &l.span(), &ctx)? {
                Built::Delta(d) => lights.push(d),
                Built::Area(a) => area_lights.push(a),
            }
        }
    }
    let (environment, environment_visible) = match &file.environment {
        None => (Environment::None, false),
        Some(e) => build_env(e.get_ref(), &e.span(), &ctx)?,
    };

    // Objects
    let mut meshes = Vec::new();
    let mut spheres = Vec::new();
    let mut planes = Vec::new();
    for (k, obj) in file.object.iter().enumerate() {
        let span = obj.span();
        let d = obj.get_ref();
        let what = format!("[[object]] #{} (kind \"{}\")", k + 1, d.kind);
        let mat = |required: bool| -> Result<Option<usize>, RenderError> {
            match &d.material {
                Some(m) => mat_index.get(m).copied().map(Some).ok_or_else(|| {
                    ctx.err(span.clone(), format!("{what}: `material` = \"{m}\" is not defined in [materials.*]"))
                }),
                None if required => Err(ctx.err(span.clone(), format!("{what}: missing key `material`"))),
                None => Ok(None),
            }
        };
        let transform = {
            let rot = d.rotate.unwrap_or([0.0; 3]).map(f64::to_radians);
            Transform {
                rotation: euler_xyz(rot),
                scale: d.scale.unwrap_or(1.0),
                translation: d.translate.unwrap_or([0.0; 3]),
            }
        };
        if !(transform.scale.is_finite() && transform.scale > 0.0) {
            return Err(ctx.err(span.clone(), format!("{what}: `scale` must be positive")));
        }
        match d.kind.as_str() {
            "sphere" => {
                let radius = need(d.radius, &ctx, &span, &what, "radius")?;
                if !(radius > 0.0 && radius.is_finite()) {
                    return Err(ctx.err(span.clone(), format!("{what}: `radius` must be positive")));
                }
                spheres.push(Sphere {
                    center: d.center.unwrap_or([0.0; 3]),
                    radius,
                    material: mat(true)?.unwrap_or(0),
                });
            }
            "plane" => {
                let normal = try_normalize(d.normal.unwrap_or([0.0, 1.0, 0.0]))
                    .ok_or_else(|| ctx.err(span.clone(), format!("{what}: `normal` must not be zero")))?;
                let tangent = orthogonalize(d.tangent.unwrap_or_else(|| any_perpendicular(normal)), normal)
                    .ok_or_else(|| {
                        ctx.err(span.clone(), format!("{what}: `tangent` must not be parallel to `normal`"))
                    })?;
                planes.push(Plane {
                    center: d.center.unwrap_or([0.0; 3]),
                    normal,
                    tangent,
                    size: d.size,
                    uv_unit: 1.0,
                    material: mat(true)?.unwrap_or(0),
                });
            }
            "snake" => {
                let def = SnakeParams::default();
                let p = SnakeParams {
                    length: d.length.unwrap_or(def.length),
                    radius: d.radius.unwrap_or(def.radius),
                    waves: d.waves.unwrap_or(def.waves),
                    amplitude: d.amplitude.unwrap_or(def.amplitude),
                    rings: d.rings.unwrap_or(def.rings).clamp(8, 20_000),
                    segments: d.segments.unwrap_or(def.segments).clamp(6, 2_000),
                    tiles: d.tiles.unwrap_or(def.tiles),
                    scales: match d.scales.as_deref() {
                        None => def.scales,
                        Some(k) => ScaleKind::parse(k).ok_or_else(|| {
                            ctx.err_key(
                                &span,
                                "scales",
                                format!("{what}: `scales` = \"{k}\": use none, smooth or keeled"),
                            )
                        })?,
                    },
                    scale_rows: d.scale_rows.unwrap_or(def.scale_rows),
                    scale_length: d.scale_length.unwrap_or(def.scale_length),
                    section: d.section.unwrap_or(def.section),
                    scale_grid: d.scale_grid.unwrap_or(def.scale_grid),
                };
                if !(3..=61).contains(&p.scale_rows) {
                    return Err(ctx.err_key(&span, "scale_rows", format!("{what}: `scale_rows` must be 3 to 61")));
                }
                if !(p.scale_length.is_finite() && p.scale_length >= 0.0) {
                    return Err(ctx.err_key(
                        &span,
                        "scale_length",
                        format!("{what}: `scale_length` must be ≥ 0 (0: automatic)"),
                    ));
                }
                if p.scale_grid.iter().any(|n| !(3..=64).contains(n)) {
                    return Err(ctx.err_key(
                        &span,
                        "scale_grid",
                        format!("{what}: `scale_grid` = {:?}: 3 to 64 vertices along and across a scale", p.scale_grid),
                    ));
                }
                let [s0, s1] = p.section;
                if !(0.0..=1.0).contains(&s0) || !(0.0..=1.0).contains(&s1) || s0 >= s1 {
                    return Err(ctx.err_key(
                        &span,
                        "section",
                        format!("{what}: `section` = [{s0}, {s1}]: two fractions of the body, tail (0) to head (1), the first smaller"),
                    ));
                }
                if p.scales != ScaleKind::None {
                    let n = crate::snake::triangle_count(&p);
                    if n > MAX_SNAKE_TRIANGLES {
                        return Err(ctx.err(
                            span.clone(),
                            format!(
                                "{what}: these scales make {n} triangles (at most {MAX_SNAKE_TRIANGLES}); use fewer \
                                 `scale_rows`, a longer `scale_length`, a smaller `scale_grid` or a `section` of the body"
                            ),
                        ));
                    }
                }
                let mut m = snake_mesh(&p, mat(true)?.unwrap_or(0));
                m.transform(&transform);
                meshes.push(m);
                if let Some(e) = &d.eye_material {
                    let material = mat_index.get(e).copied().ok_or_else(|| {
                        ctx.err_key(
                            &span,
                            "eye_material",
                            format!("{what}: `eye_material` = \"{e}\" is not defined in [materials.*]"),
                        )
                    })?;
                    for (c, r) in crate::snake::eyes(&p) {
                        spheres.push(Sphere { center: transform.point(c), radius: r * transform.scale, material });
                    }
                }
            }
            "obj" => {
                let f = d.file.as_ref().ok_or_else(|| ctx.err(span.clone(), format!("{what}: missing key `file`")))?;
                let m = mat(true)?.unwrap_or(0);
                let mut ms = crate::obj_io::load_obj(&ctx.path(f), m, &mut notes)?;
                for mesh in &mut ms {
                    mesh.transform(&transform);
                }
                meshes.extend(ms);
            }
            "gltf" => {
                let f = d.file.as_ref().ok_or_else(|| ctx.err(span.clone(), format!("{what}: missing key `file`")))?;
                let over = mat(false)?;
                let loaded = crate::gltf_io::load_gltf(
                    &ctx.path(f),
                    &mut materials,
                    &mut material_names,
                    &mut textures,
                    over,
                    &mut notes,
                    &mut warnings,
                )?;
                for mut mesh in loaded {
                    mesh.transform(&transform);
                    meshes.push(mesh);
                }
            }
            other => {
                return Err(ctx.err(
                    span.clone(),
                    format!("{what}: unknown kind \"{other}\"; use sphere, plane, obj, gltf or snake"),
                ))
            }
        }
    }
    notes.extend(ctx.notes.take());
    if spheres.is_empty() && planes.is_empty() && meshes.is_empty() {
        notes.push("the scene has no objects: the image shows only the background".into());
    }
    // Meshes whose material needs UVs must have them.
    for m in &meshes {
        if m.uvs.is_none() && materials[m.material].needs_uv() {
            return Err(RenderError::Input(format!(
                "mesh \"{}\" has no texture coordinates (UVs), but its material \"{}\" reads a texture; add UVs \
                 to the mesh (e.g. Blender: UV > Smart UV Project) or use a material without textures",
                m.name, material_names[m.material]
            )));
        }
    }
    let bvh = Bvh::build(&meshes);
    let irradiance = environment.irradiance_map();
    let environment_lights = environment.as_lights();
    let env_sampler = (integration != Integration::Fast).then(|| EnvSampler::new(&environment)).flatten();
    let sections: serde_json::Map<String, serde_json::Value> = ["output", "environment", "textures", "materials"]
        .into_iter()
        .filter_map(|k| Some((k.to_string(), serde_json::to_value(raw.get(k)?).ok()?)))
        .collect();
    let source = SceneSource {
        sections: serde_json::Value::Object(sections),
        base: std::fs::canonicalize(base).unwrap_or_else(|_| base.to_path_buf()),
    };
    let mut scene = Scene {
        camera,
        lights,
        area_lights,
        integration,
        env_sampler,
        irradiance,
        environment_lights,
        environment,
        environment_visible,
        meshes,
        spheres,
        planes,
        materials,
        material_names,
        textures,
        bvh,
        output,
        notes,
        warnings,
        source: Some(source),
    };
    for beam in lasers {
        let spot = laser_spot(&scene, &beam, &ctx)?;
        scene.lights.push(Light::Laser(Box::new(spot)));
    }
    Ok(scene)
}

/// A laser as written: its aperture, the beam's direction of travel, its power × tint, and where it is written.
struct LaserBeam {
    position: V3,
    direction: V3,
    rgb: Rgb,
    span: std::ops::Range<usize>,
}

/// Side of a laser's reflection profile in pixels (a BRDF map of the sample at the beam's incidence).
pub const LASER_PROFILE_SIZE: usize = 512;

fn build_laser_beam(d: &LightDef, span: &std::ops::Range<usize>, ctx: &Ctx) -> Result<LaserBeam, RenderError> {
    let what = "[[light]] (kind \"laser\")";
    let intensity = d.intensity.unwrap_or(1.0);
    if !(intensity.is_finite() && intensity >= 0.0) {
        return Err(ctx.err(span.clone(), format!("{what}: `intensity` (the beam's power, RU · unit²) must be ≥ 0")));
    }
    let rgb = mul(hadamard(spectrum_tint(&d.spectrum, ctx, span)?, d.color.unwrap_or([1.0; 3])), intensity);
    let position = need(d.position, ctx, span, what, "position")?;
    let direction = try_normalize(need(d.direction, ctx, span, what, "direction")?)
        .ok_or_else(|| ctx.err(span.clone(), format!("{what}: `direction` (where the beam goes) must not be zero")))?;
    Ok(LaserBeam { position, direction, rgb, span: span.clone() })
}

/// Follows a laser's beam to the first surface it meets, which must be a diffraction material (the paper's
/// sample), and makes the spot a light: its reflection of the beam into every direction, by Algorithm 4 for a
/// light of 1 RU from the beam (`Diffraction::shade_light`), as a hemisphere map in the sample's frame.
fn laser_spot(scene: &Scene, beam: &LaserBeam, ctx: &Ctx) -> Result<crate::light::LaserSpot, RenderError> {
    use rayon::prelude::*;
    let what = "[[light]] (kind \"laser\")";
    let hit = scene.intersect(beam.position, beam.direction, f64::INFINITY).ok_or_else(|| {
        ctx.err(
            beam.span.clone(),
            format!(
                "{what}: the beam from {:?} along {:?} meets nothing; aim `direction` at the diffraction sample",
                beam.position, beam.direction
            ),
        )
    })?;
    let Material::Diffraction(df) = &scene.materials[hit.material] else {
        return Err(ctx.err(
            beam.span.clone(),
            format!(
                "{what}: the beam first meets material `{}`, which is not a diffraction material; the laser's \
                 reflection is made for a diffraction sample in its path",
                scene.material_names.get(hit.material).map(String::as_str).unwrap_or("?")
            ),
        ));
    };
    let n = hit.n;
    let t = df.orientation.tangent(&hit, &scene.textures);
    let b = cross(n, t);
    let wi = mul(beam.direction, -1.0);
    let cos_in = dot(wi, n);
    if cos_in <= 1e-6 {
        return Err(ctx.err(beam.span.clone(), format!("{what}: the beam grazes the sample; tilt it or the sample")));
    }
    let tex = df.texture.at(hit.uv, &scene.textures);
    let size = LASER_PROFILE_SIZE;
    let data: Vec<f32> = (0..size * size)
        .into_par_iter()
        .flat_map_iter(|k| {
            let f = iridis_diffraction::map::view_direction(k % size, k / size, size)
                .map(|[x, y, z]| {
                    let wo = add(add(mul(t, x), mul(b, y)), mul(n, z));
                    df.shade_light(&hit, t, wi, wo, [1.0; 3], tex)
                })
                .unwrap_or([0.0; 3]);
            f.map(|c| c as f32)
        })
        .collect();
    let profile = Texture::Image {
        width: size,
        height: size,
        channels: 3,
        data,
        kind: TexKind::Data,
        name: "laser reflection profile".into(),
    };
    // Off the sample by a little more than the GPU's ray offsets, so that a shadow ray towards the spot does not
    // stop on the sample itself.
    let p = hit.p;
    let lift = 1e-4 * (p[0].abs().max(p[1].abs()).max(p[2].abs()) + hit.t);
    Ok(crate::light::LaserSpot { position: add(p, mul(n, lift)), rgb: beam.rgb, frame: [t, b, n], cos_in, profile })
}

fn build_camera(c: &Spanned<CameraDef>, ctx: &Ctx) -> Result<Camera, RenderError> {
    let span = c.span();
    let d = c.get_ref();
    let kind = d.kind.as_deref().unwrap_or("perspective");
    let up = d.up.unwrap_or([0.0, 1.0, 0.0]);
    match kind {
        "perspective" | "orthographic" => {
            let position = need(d.position, ctx, &span, "[camera]", "position")?;
            let look_at = d.look_at.unwrap_or([0.0; 3]);
            let (forward, right, up) = frame(sub(look_at, position), up).ok_or_else(|| {
                ctx.err(span.clone(), "[camera]: `look_at` must differ from `position` and not lie along `up`")
            })?;
            if kind == "perspective" {
                let fov = angle(&d.fov, ctx, &span, "fov", 40f64.to_radians())?;
                if !(fov > 0.0 && fov < std::f64::consts::PI) {
                    return Err(ctx.err(span, "[camera]: `fov` must be between 0deg and 180deg"));
                }
                Ok(Camera::Perspective { position, forward, right, up, tan_half: (fov / 2.0).tan() })
            } else {
                let h = d.height.unwrap_or(2.0);
                if !(h.is_finite() && h > 0.0) {
                    return Err(ctx.err(span, "[camera]: `height` must be positive"));
                }
                Ok(Camera::Orthographic { position, forward, right, up, half_height: h / 2.0 })
            }
        }
        "hemisphere" => {
            let normal = try_normalize(d.normal.unwrap_or([0.0, 0.0, 1.0]))
                .ok_or_else(|| ctx.err(span.clone(), "[camera]: `normal` must not be zero"))?;
            let up = orthogonalize(d.up.unwrap_or([0.0, 1.0, 0.0]), normal)
                .ok_or_else(|| ctx.err(span.clone(), "[camera]: `up` must not be parallel to `normal`"))?;
            Ok(Camera::Hemisphere {
                target: d.target.unwrap_or([0.0; 3]),
                normal,
                right: cross(up, normal),
                up,
                distance: d.distance.unwrap_or(10.0),
            })
        }
        other => {
            Err(ctx
                .err(span, format!("[camera]: unknown kind \"{other}\"; use perspective, orthographic or hemisphere")))
        }
    }
}

fn spectrum_tint(s: &Option<String>, ctx: &Ctx, span: &std::ops::Range<usize>) -> Result<Rgb, RenderError> {
    let name = s.as_deref().unwrap_or("d65");
    let ill: Illuminant = name.parse().map_err(|e| ctx.err(span.clone(), format!("`spectrum` = \"{name}\": {e}")))?;
    Ok(illuminant_tint(ill))
}

/// A light of the scene file: a delta light (directional, point) or an area light.
enum Built {
    Delta(Light),
    Area(AreaLight),
}

fn build_light(d: &LightDef, span: &std::ops::Range<usize>, ctx: &Ctx) -> Result<Built, RenderError> {
    let what = format!("[[light]] (kind \"{}\")", d.kind);
    let intensity = d.intensity.unwrap_or(1.0);
    if !(intensity.is_finite() && intensity >= 0.0) {
        return Err(ctx.err(span.clone(), format!("{what}: `intensity` must be ≥ 0 (RU)")));
    }
    let rgb = mul(hadamard(spectrum_tint(&d.spectrum, ctx, span)?, d.color.unwrap_or([1.0; 3])), intensity);
    // Keys that belong to another kind of light are refused, with the kinds they belong to.
    let keys: [(&str, bool, &str); 7] = [
        ("direction", d.direction.is_some(), "directional"),
        ("radius", d.radius.is_some(), "sphere, disk"),
        ("normal", d.normal.is_some(), "disk, rectangle"),
        ("look_at", d.look_at.is_some(), "disk, rectangle"),
        ("tangent", d.tangent.is_some(), "rectangle"),
        ("size", d.size.is_some(), "rectangle"),
        ("visible", d.visible.is_some(), "sphere, disk, rectangle"),
    ];
    for (key, given, kinds) in keys {
        if given
            && !kinds.split(", ").any(|k| k == d.kind)
            && ["directional", "point", "sphere", "disk", "rectangle"].contains(&d.kind.as_str())
        {
            return Err(ctx.err(
                span.clone(),
                format!("{what}: `{key}` is not a key of this kind of light (it belongs to {kinds})"),
            ));
        }
    }
    let positive = |v: Option<f64>, key: &str| -> Result<f64, RenderError> {
        let x = v.ok_or_else(|| ctx.err(span.clone(), format!("{what}: missing key `{key}`")))?;
        if !(x.is_finite() && x > 0.0) {
            return Err(ctx.err(span.clone(), format!("{what}: `{key}` must be a positive length")));
        }
        Ok(x)
    };
    // The way a disk's or rectangle's emitting face looks: `normal`, or from `position` towards `look_at`.
    let facing = |center: V3| -> Result<V3, RenderError> {
        let n = match (d.normal, d.look_at) {
            (Some(n), None) => n,
            (None, Some(t)) => sub(t, center),
            (Some(_), Some(_)) => {
                return Err(ctx.err(span.clone(), format!("{what}: give `normal` or `look_at`, not both")))
            }
            (None, None) => {
                return Err(ctx.err(
                    span.clone(),
                    format!("{what}: missing key `normal` (the way its emitting face looks) or `look_at`"),
                ))
            }
        };
        try_normalize(n).ok_or_else(|| ctx.err(span.clone(), format!("{what}: its facing direction must not be zero")))
    };
    let area = |shape: Shape| Built::Area(AreaLight { shape, radiance: rgb, visible: d.visible.unwrap_or(true) });
    match d.kind.as_str() {
        "directional" => {
            let dir = try_normalize(need(d.direction, ctx, span, &what, "direction")?)
                .ok_or_else(|| ctx.err(span.clone(), format!("{what}: `direction` must not be zero")))?;
            Ok(Built::Delta(Light::Directional { direction: dir, rgb }))
        }
        "point" => Ok(Built::Delta(Light::Point { position: need(d.position, ctx, span, &what, "position")?, rgb })),
        "sphere" => Ok(area(Shape::Sphere {
            center: need(d.position, ctx, span, &what, "position")?,
            radius: positive(d.radius, "radius")?,
        })),
        "disk" => {
            let center = need(d.position, ctx, span, &what, "position")?;
            Ok(area(Shape::Disk { center, normal: facing(center)?, radius: positive(d.radius, "radius")? }))
        }
        "rectangle" => {
            let center = need(d.position, ctx, span, &what, "position")?;
            let normal = facing(center)?;
            let size = need(d.size, ctx, span, &what, "size")?;
            if !size.iter().all(|x| x.is_finite() && *x > 0.0) {
                return Err(ctx.err(span.clone(), format!("{what}: `size` = [w, h] must be positive lengths")));
            }
            let tangent =
                orthogonalize(d.tangent.unwrap_or_else(|| any_perpendicular(normal)), normal).ok_or_else(|| {
                    ctx.err(span.clone(), format!("{what}: `tangent` must not be parallel to its normal"))
                })?;
            Ok(area(Shape::Rectangle { center, normal, tangent, size }))
        }
        other => Err(ctx.err(
            span.clone(),
            format!("[[light]]: unknown kind \"{other}\"; use directional, point, sphere, disk, rectangle or laser"),
        )),
    }
}

fn build_env(d: &EnvDef, span: &std::ops::Range<usize>, ctx: &Ctx) -> Result<(Environment, bool), RenderError> {
    let intensity = d.intensity.unwrap_or(1.0);
    // A radiance below 0 has no meaning; it was clipped to 0 without a word.
    let colours = [("color", d.color), ("zenith", d.zenith), ("horizon", d.horizon), ("ground", d.ground)];
    for (key, c) in colours.iter().filter_map(|(k, c)| c.map(|c| (k, c))) {
        if c.iter().any(|v| *v < 0.0) {
            return Err(
                ctx.err(span.clone(), format!("[environment] `{key}` = {c:?}: a radiance must be ≥ 0 (linear sRGB)"))
            );
        }
    }
    if intensity < 0.0 {
        return Err(ctx.err(span.clone(), format!("[environment] `intensity` = {intensity}: must be ≥ 0")));
    }
    let visible = d.visible.unwrap_or(true);
    let env = match d.kind.as_str() {
        "uniform" => Environment::Uniform(mul(d.color.unwrap_or([1.0; 3]), intensity)),
        "sky" => Environment::Sky {
            zenith: mul(d.zenith.unwrap_or([0.25, 0.45, 0.9]), intensity),
            horizon: mul(d.horizon.unwrap_or([0.9, 0.92, 0.95]), intensity),
            ground: mul(d.ground.unwrap_or([0.2, 0.18, 0.15]), intensity),
        },
        "map" => {
            let f = d
                .file
                .as_ref()
                .ok_or_else(|| ctx.err(span.clone(), "[environment] kind \"map\": missing key `file`"))?;
            let path = ctx.path(f);
            let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
            if ext != "exr" && ext != "hdr" {
                return Err(ctx.err(
                    span.clone(),
                    format!("[environment] `file` = \"{f}\": an environment map must be a linear HDR image (.exr or .hdr, equirectangular), not .{ext}"),
                ));
            }
            let tex = Texture::load(&path, TexKind::Color)?;
            if let Texture::Image { width, height, .. } = &tex {
                if width != &(2 * height) {
                    return Err(ctx.err(
                        span.clone(),
                        format!("[environment] `file` = \"{f}\" is {width}×{height}; an equirectangular map is twice as wide as high"),
                    ));
                }
            }
            let mean = equirect_mean(&tex, intensity);
            Environment::Map {
                texture: Box::new(tex),
                rotation: angle(&d.rotation, ctx, span, "rotation", 0.0)?,
                intensity,
                mean,
            }
        }
        other => {
            return Err(
                ctx.err(span.clone(), format!("[environment]: unknown kind \"{other}\"; use uniform, sky or map"))
            )
        }
    };
    Ok((env, visible))
}

fn build_texture(name: &str, d: &TextureDef, span: &std::ops::Range<usize>, ctx: &Ctx) -> Result<Texture, RenderError> {
    let what = format!("[textures.{name}]");
    if let Some(kind) = TexKind::parse(&d.kind) {
        let f = d.file.as_ref().ok_or_else(|| ctx.err(span.clone(), format!("{what}: missing key `file`")))?;
        return Texture::load(&ctx.path(f), kind).map_err(|e| ctx.err(span.clone(), format!("{what}: {e}")));
    }
    Ok(match d.kind.as_str() {
        "noise" => Texture::Noise { scale: d.scale.unwrap_or(4.0), octaves: d.octaves.unwrap_or(4), seed: d.seed.unwrap_or(1) },
        "gradient" => Texture::Gradient {
            from: d.from.unwrap_or(0.0),
            to: d.to.unwrap_or(1.0),
            along_u: match d.along.as_deref().unwrap_or("v") {
                "u" => true,
                "v" => false,
                o => return Err(ctx.err(span.clone(), format!("{what}: `along` = \"{o}\": use \"u\" or \"v\""))),
            },
        },
        "scales" => Texture::Scales {
            base: reflectance(d.base.unwrap_or([0.05, 0.04, 0.03]), &what, "base", span, ctx)?,
            edge: reflectance(d.edge.unwrap_or([0.01, 0.01, 0.01]), &what, "edge", span, ctx)?,
        },
        "checker" => Texture::Checker {
            a: reflectance(d.a.unwrap_or([0.8; 3]), &what, "a", span, ctx)?,
            b: reflectance(d.b.unwrap_or([0.2; 3]), &what, "b", span, ctx)?,
            n: match d.n.unwrap_or(8.0) {
                n if n > 0.0 => n,
                n => return Err(ctx.err_key(span, "n", format!("{what}: `n` = {n}: squares per unit of u and v must be > 0"))),
            },
        },
        other => {
            return Err(ctx.err(
                span.clone(),
                format!("{what}: unknown kind \"{other}\"; use color, grey or vector (with `file`), or noise, gradient, scales, checker"),
            ))
        }
    })
}

type TexRef<'a> = dyn Fn(&str, TexKind, &std::ops::Range<usize>, &str) -> Result<usize, RenderError> + 'a;

fn color_source(
    d: &MaterialDef,
    what: &str,
    span: &std::ops::Range<usize>,
    ctx: &Ctx,
    tex: &TexRef,
    default: Rgb,
) -> Result<ColorSource, RenderError> {
    Ok(match &d.texture {
        Some(t) => ColorSource::Texture(tex(t, TexKind::Color, span, "texture")?),
        None => ColorSource::Const(reflectance(d.color.unwrap_or(default), what, "color", span, ctx)?),
    })
}

/// A colour that is a reflectance (a surface's albedo, a texture's colour): each channel in [0, 1]. Above 1 the
/// surface returns more light than it receives (`color = [3, 3, 3]` on a Lambertian floor was rendered so).
fn reflectance(c: Rgb, what: &str, key: &str, span: &std::ops::Range<usize>, ctx: &Ctx) -> Result<Rgb, RenderError> {
    if c.iter().all(|x| (0.0..=1.0).contains(x)) {
        return Ok(c);
    }
    Err(ctx.err_key(
        span,
        key,
        format!(
            "{what}: `{key}` = {c:?}: a reflectance has each channel in [0, 1] (above 1 a surface returns more light than \
             it receives); for a brighter image raise the lights or the exposure"
        ),
    ))
}

/// The keys each material kind reads, besides `kind`: the one list the scene loader checks against (the
/// material tables of `docs/render.md` describe the same keys).
pub const MATERIAL_KEYS: &[(&str, &[&str])] = &[
    ("lambert", &["color", "texture"]),
    ("microfacet", &["color", "texture", "roughness", "metallic", "ior"]),
    (
        "diffraction",
        &[
            "table",
            "uv_resolution",
            "orientation",
            "orientation_texture",
            "direction",
            "angle",
            "scale_ru",
            "w_diffuse",
            "color",
            "texture",
            "ambient",
            "fresnel_n",
            "units",
            "blend",
        ],
    ),
    ("thinfilm", &["stack", "svt", "d_rel", "transmission", "base", "factor", "roughness", "correlation"]),
];

/// The 1-based line where `key` is written in the table that starts at `span` (the table's first line when
/// it cannot be found, e.g. a quoted key).
fn key_line(text: &str, span: &std::ops::Range<usize>, key: &str) -> usize {
    let first = line_of(text, span.start);
    let start = text[..span.start.min(text.len())].rfind('\n').map_or(0, |i| i + 1);
    for (k, line) in text[start..].lines().enumerate() {
        let t = line.trim_start();
        if k > 0 && t.starts_with('[') {
            break;
        }
        // `key = …`, also inside an inline table `{ kind = "lambert", key = … }`.
        for (i, _) in t.match_indices(key) {
            let before = t[..i].chars().next_back();
            let after = t[i + key.len()..].trim_start();
            if before.is_none_or(|c| c == ' ' || c == '{' || c == ',') && after.starts_with('=') {
                return first + k;
            }
        }
    }
    first
}

/// Refuses keys that the material's kind does not read (`stack` on a lambert material, say), naming the key,
/// the kind and the line.
fn check_material_keys(
    name: &str,
    kind: &str,
    written: Option<&toml::Table>,
    span: &std::ops::Range<usize>,
    ctx: &Ctx,
) -> Result<(), RenderError> {
    let (Some(keys), Some((_, allowed))) = (written, MATERIAL_KEYS.iter().find(|(k, _)| *k == kind)) else {
        return Ok(());
    };
    for key in keys.keys() {
        if key != "kind" && !allowed.contains(&key.as_str()) {
            let owners: Vec<&str> =
                MATERIAL_KEYS.iter().filter(|(_, ks)| ks.contains(&key.as_str())).map(|(k, _)| *k).collect();
            return Err(RenderError::Scene {
                path: ctx.name.to_string(),
                line: key_line(ctx.text, span, key),
                message: format!(
                    "[materials.{name}]: `{key}` is not a key of a {kind} material (it belongs to {}); a {kind} \
                     material takes {}",
                    owners.join(" and "),
                    allowed.join(", ")
                ),
            });
        }
    }
    Ok(())
}

fn build_material(
    name: &str,
    d: &MaterialDef,
    span: &std::ops::Range<usize>,
    ctx: &Ctx,
    tex: &TexRef,
    mat_index: &BTreeMap<String, usize>,
    built: &[Material],
) -> Result<Material, RenderError> {
    let what = format!("[materials.{name}]");
    let unit = |v: Option<f64>, key: &str, default: f64| -> Result<f64, RenderError> {
        let x = v.unwrap_or(default);
        if !(0.0..=1.0).contains(&x) {
            return Err(ctx.err(span.clone(), format!("{what}: `{key}` = {x} must lie in [0, 1]")));
        }
        Ok(x)
    };
    match d.kind.as_str() {
        "lambert" => Ok(Material::Lambert { color: color_source(d, &what, span, ctx, tex, [0.5; 3])? }),
        "microfacet" => Ok(Material::Microfacet(Microfacet {
            color: color_source(d, &what, span, ctx, tex, [0.5; 3])?,
            roughness: unit(
                match &d.roughness {
                    None => None,
                    Some(NumOrText::Num(x)) => Some(*x),
                    Some(NumOrText::Text(t)) => {
                        return Err(ctx.err(
                            span.clone(),
                            format!(
                                "{what}: `roughness` = \"{t}\": a microfacet roughness is a number in [0, 1] (GGX α = \
                                 roughness²); lengths such as \"25nm\" are for a thinfilm's rough substrate"
                            ),
                        ))
                    }
                },
                "roughness",
                0.3,
            )?,
            metallic: unit(d.metallic, "metallic", 0.0)?,
            ior: d.ior.unwrap_or(1.5),
            metallic_roughness: None,
            normal_texture: None,
        })),
        "diffraction" => {
            let table = d.table.as_ref().ok_or_else(|| {
                ctx.err(
                    span.clone(),
                    format!("{what}: missing key `table` (a .npz from `iridis precompute`, or \"builtin:elaphe\")"),
                )
            })?;
            let params = TableParams { uv_resolution: d.uv_resolution.unwrap_or(101), uv_power: 5.0 };
            if !(16..=2001).contains(&params.uv_resolution) {
                return Err(ctx.err(span.clone(), format!("{what}: `uv_resolution` must be between 16 and 2001")));
            }
            let units: Units = match d.units.as_deref() {
                None => Units::Relative,
                Some(u) => u.parse().map_err(|e| ctx.err_key(span, "units", format!("{what}: {e}")))?,
            };
            let mut table_notes = Vec::new();
            let t = crate::tables::load_table(table, &ctx.base, params, units, &mut table_notes)
                .map_err(|e| ctx.err(span.clone(), format!("{what}: {e}")))?;
            ctx.notes.borrow_mut().extend(table_notes.into_iter().map(|n| format!("{what}: {n}")));
            let fresnel_n = d.fresnel_n.unwrap_or(1.5);
            if !(fresnel_n.is_finite() && fresnel_n >= 1.0) {
                return Err(ctx.err_key(span, "fresnel_n", format!("{what}: `fresnel_n` = {fresnel_n} must be ≥ 1")));
            }
            let shading = Shading { fresnel: Arc::new(Fresnel::Schlick { n: fresnel_n }), ..Shading::default() };
            let lookup =
                Lookup::new(t, shading, Precision::F64).map_err(|e| ctx.err(span.clone(), format!("{what}: {e}")))?;
            let rule = match d.orientation.as_deref().unwrap_or("tangent") {
                "tangent" => OrientRule::Tangent,
                "along" => OrientRule::Along,
                "direction" => OrientRule::Direction(need(d.direction, ctx, span, &what, "direction")?),
                "texture" => {
                    let t = d.orientation_texture.as_ref().ok_or_else(|| {
                        ctx.err(span.clone(), format!("{what}: orientation \"texture\" needs `orientation_texture`"))
                    })?;
                    OrientRule::Texture(tex(t, TexKind::Vector, span, "orientation_texture")?)
                }
                o => {
                    return Err(ctx.err(
                        span.clone(),
                        format!("{what}: `orientation` = \"{o}\": use tangent, along, direction or texture"),
                    ))
                }
            };
            let scale_ru = match units {
                Units::Relative => d.scale_ru.unwrap_or(1.0),
                // The BRDF itself: R₀ for the surface's reflectance, π for the lights' unit E/π (a 1 RU light
                // gives a white Lambertian surface radiance cos θ_i).
                Units::Radiometric if d.scale_ru.is_some() => {
                    return Err(ctx.err_key(
                        span,
                        "scale_ru",
                        format!(
                            "{what}: `scale_ru` is the exposure of the paper's relative units; with units = \
                             \"radiometric\" the lobe is the BRDF itself (scaled by R₀ of `fresnel_n`): leave it out"
                        ),
                    ))
                }
                Units::Radiometric => std::f64::consts::PI * ((fresnel_n - 1.0) / (fresnel_n + 1.0)).powi(2),
            };
            if !(scale_ru.is_finite() && scale_ru >= 0.0) {
                return Err(ctx.err(span.clone(), format!("{what}: `scale_ru` must be ≥ 0")));
            }
            let ambient = d.ambient.unwrap_or(0.0).max(0.0);
            let blend = match d.blend.as_deref().unwrap_or("algorithm4") {
                "algorithm4" => Blend::Algorithm4,
                "energy" if units != Units::Radiometric => {
                    return Err(ctx.err_key(
                        span,
                        "blend",
                        format!(
                            "{what}: blend = \"energy\" needs units = \"radiometric\" (in the paper's relative \
                             units the lobe's brightness is an exposure, so there is no energy to conserve)"
                        ),
                    ))
                }
                "energy" if ambient > 0.0 => {
                    return Err(ctx.err_key(
                        span,
                        "ambient",
                        format!("{what}: `ambient` adds light from nowhere; blend = \"energy\" takes none"),
                    ))
                }
                "energy" => {
                    // The lobe's albedo: the radiometric colour times R₀ is the reflected fraction.
                    let r0 = scale_ru / std::f64::consts::PI;
                    Blend::Energy(Arc::new(
                        crate::lobe_albedo::LobeAlbedo::compute(&lookup, r0)
                            .map_err(|e| ctx.err(span.clone(), format!("{what}: {e}")))?,
                    ))
                }
                b => {
                    return Err(ctx.err_key(
                        span,
                        "blend",
                        format!("{what}: `blend` = \"{b}\": use algorithm4 (the thesis') or energy"),
                    ))
                }
            };
            Ok(Material::Diffraction(Box::new(Diffraction {
                evaluator: Arc::new(lookup),
                orientation: Orientation { rule, angle: angle(&d.angle, ctx, span, "angle", 0.0)? },
                scale_ru,
                w_diffuse: unit(d.w_diffuse, "w_diffuse", 0.0)?,
                texture: color_source(d, &what, span, ctx, tex, [0.0; 3])?,
                ambient,
                fresnel_n,
                description: table.clone(),
                blend,
                extended: Default::default(),
            })))
        }
        "thinfilm" => {
            let s = d.stack.as_ref().ok_or_else(|| {
                ctx.err(span.clone(), format!("{what}: missing key `stack`, e.g. \"air | water 400nm | air\""))
            })?;
            let stack: iridis_thinfilm::Stack =
                s.parse().map_err(|e| ctx.err(span.clone(), format!("{what}: `stack` = \"{s}\": {e}")))?;
            let svt = match &d.svt {
                None => None,
                Some(t) => {
                    let d_rel = match &d.d_rel {
                        Some(x) => parse_length_nm(x)
                            .map_err(|e| ctx.err(span.clone(), format!("{what}: `d_rel` = \"{x}\": {e}")))?,
                        None => {
                            return Err(ctx.err(
                                span.clone(),
                                format!("{what}: `svt` needs `d_rel`, the thickness variation, e.g. \"150nm\""),
                            ))
                        }
                    };
                    Some(Svt { texture: tex(t, TexKind::Grey, span, "svt")?, d_rel_nm: d_rel })
                }
            };
            let base = match &d.base {
                None => None,
                Some(b) => match mat_index.get(b).map(|&i| &built[i]) {
                    Some(Material::Lambert { color }) => Some(Microfacet {
                        color: *color,
                        roughness: 1.0,
                        metallic: 0.0,
                        ior: 1.0,
                        metallic_roughness: None,
                        normal_texture: None,
                    }),
                    Some(Material::Microfacet(m)) => Some(*m),
                    _ => {
                        return Err(ctx.err(
                            span.clone(),
                            format!("{what}: `base` = \"{b}\" must name a lambert or microfacet material"),
                        ))
                    }
                },
            };
            let mut film = ThinFilm::new(stack.clone(), svt, d.transmission.unwrap_or(false))
                .map_err(|e| ctx.err(span.clone(), format!("{what}: {e}")))?;
            // Over a metallic base the film's substrate is the metal, as in glTF iridescence: the index whose
            // F_0 is the base colour (crate::gltf_io::metal_from_f0).
            if let Some(b) = base.filter(|b| b.metallic > 0.0) {
                let ColorSource::Const(f0) = b.color else {
                    return Err(ctx.err(
                        span.clone(),
                        format!(
                            "{what}: the metallic base under the film takes its constant `color` as the metal's F_0; \
                             give the base a `color`, not a texture"
                        ),
                    ));
                };
                let mut metal = stack;
                metal.substrate =
                    crate::gltf_io::metal_from_f0(f0).map_err(|e| ctx.err(span.clone(), format!("{what}: {e}")))?;
                film.metal_stack = Some(metal);
            }
            film.base = base;
            film.factor = unit(d.factor, "factor", 1.0)?;
            let length = |key: &str, v: &str| {
                parse_length_nm(v).map_err(|e| ctx.err_key(span, key, format!("{what}: `{key}` = \"{v}\": {e}")))
            };
            match (&d.roughness, &d.correlation) {
                (None, None) => {}
                (Some(NumOrText::Num(x)), _) => {
                    return Err(ctx.err_key(
                        span,
                        "roughness",
                        format!(
                            "{what}: `roughness` = {x}: a thin film's roughness is the rms height of its substrate, \
                             a length with its unit, e.g. \"25nm\""
                        ),
                    ))
                }
                (Some(NumOrText::Text(s)), Some(c)) => {
                    let r = Roughness::new(length("roughness", s)?, length("correlation", c)?)
                        .map_err(|e| ctx.err_key(span, "roughness", format!("{what}: `roughness`/`correlation`: {e}")))?;
                    film.set_rough(Htsg::new(r, Series::default()))
                        .map_err(|e| ctx.err_key(span, "roughness", format!("{what}: {e}")))?;
                }
                (Some(_), None) => {
                    return Err(ctx.err_key(
                        span,
                        "roughness",
                        format!("{what}: `roughness` needs `correlation`, the substrate's autocorrelation length, e.g. \"300nm\""),
                    ))
                }
                (None, Some(_)) => {
                    return Err(ctx.err_key(
                        span,
                        "correlation",
                        format!("{what}: `correlation` needs `roughness`, the substrate's rms height, e.g. \"25nm\""),
                    ))
                }
            }
            Ok(Material::ThinFilm(Box::new(film)))
        }
        other => Err(ctx.err(
            span.clone(),
            format!("{what}: unknown kind \"{other}\"; use lambert, microfacet, diffraction or thinfilm"),
        )),
    }
}
