//! glTF 2.0 input (`.gltf` with external or embedded buffers, `.glb`): triangle meshes with normals, UVs and
//! tangents (MikkTSpace when the file has none, as the glTF specification asks), PBR metallic-roughness
//! materials as a GGX base, and `KHR_materials_iridescence` as a thin-film stack over that base:
//! `air | n = iridescenceIor, d | n = ior` (`KHR_materials_ior`, default 1.5), and for a metallic base the same
//! film over the metal (its index from the base colour as `F_0`), with `d = mix(thicknessMinimum,
//! thicknessMaximum, texture.g)` (Sussenbach's SVT with `d_avg = (min + max)/2`, `d_rel = (max − min)/2`) or
//! `d = thicknessMaximum` without a texture. The film's reflectance replaces the base's specular Fresnel
//! (render.rs, `shade_film_over_base`) and `iridescenceFactor` mixes it with the base alone. Textures:
//! `baseColorTexture` × `baseColorFactor`, `texCoord` and `KHR_texture_transform` (applied to the mesh's
//! UVs), the thickness texture's G channel, the metallic-roughness (G, B) and normal textures; what is not read (occlusion and
//! emissive textures, samplers other than repeat/linear, `iridescenceTexture`) is named in a note.

use std::path::Path;

use crate::error::RenderError;
use crate::geometry::Mesh;
use crate::material::{ColorSource, Material, Microfacet, Svt, ThinFilm};
use crate::math::*;
use crate::texture::{TexKind, Texture};

pub(crate) fn bad(path: &Path, msg: impl std::fmt::Display) -> RenderError {
    RenderError::Input(format!("glTF {}: {msg}", path.display()))
}

/// Standard base64 (RFC 4648) as used in glTF data URIs.
pub fn base64_decode(s: &str) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0);
    for c in s.bytes() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            b'=' => break,
            b'\n' | b'\r' | b' ' => continue,
            _ => return None,
        };
        acc = (acc << 6) | v as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
        }
    }
    Some(out)
}

fn read_uri(path: &Path, uri: &str) -> Result<Vec<u8>, RenderError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, data) = rest.split_once(";base64,").ok_or_else(|| bad(path, "a data URI must be base64-encoded"))?;
        return base64_decode(data).ok_or_else(|| bad(path, "a data URI holds invalid base64"));
    }
    let file = path.parent().unwrap_or(Path::new(".")).join(uri.replace("%20", " "));
    std::fs::read(&file).map_err(|e| bad(path, format!("cannot read {}: {e}", file.display())))
}

/// Loads the meshes of the default scene, appending their materials and textures. With `material_override`,
/// every mesh uses that material instead of the file's. A glTF material whose `extras` name an iridis material
/// (`{"iridis": {"material": NAME}}`, as `iridis render --export-mesh` writes them) takes the one of that name
/// already in `material_names` (a TOML scene's, or the file's own iridis extras) instead of its PBR
/// approximation. What the file asks for that cannot look as meant (a film thickness apparently in the wrong
/// unit) goes to `warnings`.
pub fn load_gltf(
    path: &Path,
    materials: &mut Vec<Material>,
    material_names: &mut Vec<String>,
    textures: &mut Vec<Texture>,
    material_override: Option<usize>,
    notes: &mut Vec<String>,
    warnings: &mut Vec<String>,
) -> Result<Vec<Mesh>, RenderError> {
    let known = material_names.len();
    let bytes = std::fs::read(path).map_err(|e| bad(path, format!("cannot read the file: {e}")))?;
    let g = gltf::Gltf::from_slice(&bytes).map_err(|e| bad(path, format!("not a valid glTF 2.0 file: {e}")))?;
    let doc = &g.document;
    let mut buffers = Vec::new();
    for b in doc.buffers() {
        let data = match b.source() {
            gltf::buffer::Source::Bin => g.blob.clone().ok_or_else(|| bad(path, "the GLB binary chunk is missing"))?,
            gltf::buffer::Source::Uri(u) => read_uri(path, u)?,
        };
        if data.len() < b.length() {
            return Err(bad(
                path,
                format!("buffer {} has {} bytes, the file declares {}", b.index(), data.len(), b.length()),
            ));
        }
        buffers.push(data);
    }
    // Images are decoded lazily, per use (colour, or the G channel of a thickness map).
    let image_of = |tex: gltf::Texture| -> Result<image::DynamicImage, RenderError> {
        let data = match tex.source().source() {
            gltf::image::Source::View { view, .. } => {
                let b = &buffers[view.buffer().index()];
                b.get(view.offset()..view.offset() + view.length())
                    .ok_or_else(|| bad(path, "an image view lies outside its buffer"))?
                    .to_vec()
            }
            gltf::image::Source::Uri { uri, .. } => read_uri(path, uri)?,
        };
        // As `image::load_from_memory` reads it: the format from the content.
        image::ImageReader::new(std::io::Cursor::new(data.as_slice()))
            .with_guessed_format()
            .map_err(image::ImageError::IoError)
            .and_then(iridis_surface::formats::raster::decode)
            .map_err(|e| bad(path, format!("image {}: {e}", tex.source().index())))
    };

    // Materials
    let mut mat_map = Vec::new();
    // Per glTF material: which UV set its textures read, and their KHR_texture_transform.
    let mut mat_uv: Vec<UvMap> = Vec::new();
    for m in doc.materials() {
        let name = m.name().map(str::to_string).unwrap_or_else(|| format!("gltf material {}", m.index().unwrap_or(0)));
        // An iridis material by name (the export's extras): the scene's own, not the PBR stand-in.
        let named = extras_of(m.extras())
            .and_then(|x| x.get("iridis")?.get("material")?.as_str().map(str::to_string))
            .and_then(|n| material_names[..known].iter().position(|k| *k == n));
        if let Some(i) = named {
            mat_map.push(i);
            mat_uv.push(UvMap::default());
            continue;
        }
        let pbr = m.pbr_metallic_roughness();
        let bc = pbr.base_color_factor();
        let factor3 = [bc[0] as f64, bc[1] as f64, bc[2] as f64];
        let mut uv_map: Option<UvMap> = None;
        let color = match pbr.base_color_texture() {
            Some(info) => {
                let mut t = Texture::from_image(image_of(info.texture())?, TexKind::Color, &name)?;
                // baseColorFactor multiplies the texture (glTF 2.0, 3.9.2).
                if let Texture::Image { channels, data, .. } = &mut t {
                    let c = *channels;
                    for (i, v) in data.iter_mut().enumerate() {
                        if i % c < 3 {
                            *v *= factor3[i % c] as f32;
                        }
                    }
                }
                textures.push(t);
                check_sampler(&name, "baseColorTexture", &info.texture(), notes);
                uv_map = Some(UvMap::of(info.tex_coord(), info.extensions()));
                ColorSource::Texture(textures.len() - 1)
            }
            None => ColorSource::Const(factor3),
        };
        let ext = |k: &str| m.extensions().and_then(|e| e.get(k));
        // KHR_materials_ior: the dielectric's index (default 1.5), the film's substrate under iridescence.
        let ior = ext("KHR_materials_ior").and_then(|x| x.get("ior")).and_then(|v| v.as_f64()).unwrap_or(1.5);
        if !(ior >= 1.0 && ior.is_finite()) {
            return Err(bad(path, format!("material \"{name}\": KHR_materials_ior ior = {ior}; it must be ≥ 1")));
        }
        // The data textures below are read linearly and share the material's texture coordinates.
        let mut data_texture = |tex: gltf::Texture, uv: UvMap, slot: &str, label: &str| {
            textures.push(Texture::from_image(image_of(tex.clone())?, TexKind::Data, &format!("{name} {label}"))?);
            check_sampler(&name, slot, &tex, notes);
            share_uv_map(&mut uv_map, uv, &name, slot, notes);
            Ok::<usize, RenderError>(textures.len() - 1)
        };
        // metallicRoughnessTexture: G scales the roughness, B the metallic factor (glTF 2.0, sec. 3.9.2).
        let metallic_roughness = match pbr.metallic_roughness_texture() {
            Some(info) => Some(data_texture(
                info.texture(),
                UvMap::of(info.tex_coord(), info.extensions()),
                "metallicRoughnessTexture",
                "metallic-roughness",
            )?),
            None => None,
        };
        // normalTexture: a tangent-space normal (2·rgb − 1, x and y × scale) (sec. 3.9.3).
        let normal_texture = match m.normal_texture() {
            Some(info) => Some((
                data_texture(
                    info.texture(),
                    UvMap::of(info.tex_coord(), info.extensions()),
                    "normalTexture",
                    "normal",
                )?,
                info.scale() as f64,
            )),
            None => None,
        };
        let base = Microfacet {
            color,
            roughness: pbr.roughness_factor().clamp(0.0, 1.0) as f64,
            metallic: pbr.metallic_factor().clamp(0.0, 1.0) as f64,
            ior,
            metallic_roughness,
            normal_texture,
        };
        // What the renderer does not read, named once per material.
        let mut ignored = Vec::new();
        if m.occlusion_texture().is_some() {
            ignored.push("occlusionTexture");
        }
        if m.emissive_texture().is_some() || m.emissive_factor() != [0.0; 3] {
            ignored.push("emission");
        }
        for k in m.extensions().into_iter().flat_map(|e| e.keys()) {
            if k != "KHR_materials_ior" && k != "KHR_materials_iridescence" {
                notes.push(format!("material \"{name}\": extension {k} is not supported (ignored)"));
            }
        }
        if !ignored.is_empty() {
            notes.push(format!("material \"{name}\": not supported, ignored: {}", ignored.join(", ")));
        }
        let mat = match ext("KHR_materials_iridescence") {
            Some(x) => {
                let num = |k: &str, d: f64| x.get(k).and_then(|v| v.as_f64()).unwrap_or(d);
                let factor = num("iridescenceFactor", 0.0).clamp(0.0, 1.0);
                let film_ior = num("iridescenceIor", 1.3);
                let (dmin, dmax) =
                    (num("iridescenceThicknessMinimum", 100.0), num("iridescenceThicknessMaximum", 400.0));
                if !(film_ior >= 1.0 && dmin >= 0.0 && dmax >= 0.0) {
                    return Err(bad(
                        path,
                        format!(
                            "material \"{name}\": iridescence IOR {film_ior} or thickness {dmin}–{dmax} nm is invalid"
                        ),
                    ));
                }
                if let Some(w) =
                    implausible_thickness(&name, dmin, dmax, x.get("iridescenceThicknessTexture").is_some())
                {
                    warnings.push(w);
                }
                let tex_info = x.get("iridescenceThicknessTexture");
                let tex_index = tex_info.and_then(|t| t.get("index")).and_then(|i| i.as_u64());
                let (d, svt) = match tex_index {
                    Some(i) => {
                        let tex = doc
                            .textures()
                            .nth(i as usize)
                            .ok_or_else(|| bad(path, format!("thickness texture {i} does not exist")))?;
                        check_sampler(&name, "iridescenceThicknessTexture", &tex, notes);
                        let info = tex_info.expect("has an index");
                        let set = info.get("texCoord").and_then(|v| v.as_u64()).unwrap_or(0) as u32;
                        let own = UvMap::of(set, info.get("extensions").and_then(|e| e.as_object()));
                        share_uv_map(&mut uv_map, own, &name, "iridescenceThicknessTexture", notes);
                        let rgb = image_of(tex)?.to_rgb32f();
                        let (w, h) = (rgb.width() as usize, rgb.height() as usize);
                        // The G channel, linear (glTF: thickness textures hold data, not colours).
                        let data = rgb.pixels().map(|p| p[1]).collect();
                        textures.push(Texture::Image {
                            width: w,
                            height: h,
                            channels: 1,
                            data,
                            kind: TexKind::Grey,
                            name: format!("{name} thickness"),
                        });
                        ((dmin + dmax) / 2.0, Some(Svt { texture: textures.len() - 1, d_rel_nm: (dmax - dmin) / 2.0 }))
                    }
                    None => (dmax, None),
                };
                if x.get("iridescenceTexture").is_some() {
                    notes.push(format!("material \"{name}\": iridescenceTexture is not supported; the factor {factor} applies everywhere"));
                }
                // The film over the dielectric base (substrate: its KHR_materials_ior index) and, for a metallic
                // base, over the metal (substrate: the index whose F_0 is the base colour).
                let stack: iridis_thinfilm::Stack = format!("air | n={film_ior} {d}nm | n={ior}")
                    .parse()
                    .map_err(|e| bad(path, format!("material \"{name}\": {e}")))?;
                let mut film = ThinFilm::new(stack.clone(), svt, false)?;
                if base.metallic > 0.0 {
                    let f0 = match base.color {
                        ColorSource::Const(c) => c,
                        ColorSource::Texture(_) => {
                            notes.push(format!(
                                "material \"{name}\": the metal under the iridescent film takes baseColorFactor as \
                                 its F_0 (a base colour texture still colours its Schlick reflection)"
                            ));
                            factor3
                        }
                    };
                    let mut metal = stack;
                    metal.substrate = metal_from_f0(f0).map_err(|e| bad(path, format!("material \"{name}\": {e}")))?;
                    film.metal_stack = Some(metal);
                }
                film.base = Some(base);
                film.factor = factor;
                Material::ThinFilm(Box::new(film))
            }
            None => Material::Microfacet(base),
        };
        materials.push(mat);
        material_names.push(name);
        mat_map.push(materials.len() - 1);
        mat_uv.push(uv_map.unwrap_or_default());
    }
    let default_material = match material_override {
        Some(m) => m,
        None => {
            materials.push(Material::Microfacet(Microfacet {
                color: ColorSource::Const([0.8; 3]),
                roughness: 0.5,
                metallic: 0.0,
                ior: 1.5,
                metallic_roughness: None,
                normal_texture: None,
            }));
            material_names.push("gltf default".into());
            materials.len() - 1
        }
    };

    // Meshes of the default scene, with node transforms.
    let scene =
        doc.default_scene().or_else(|| doc.scenes().next()).ok_or_else(|| bad(path, "the file has no scene"))?;
    let mut out = Vec::new();
    let mut stack: Vec<(gltf::Node, [[f64; 4]; 4])> = scene.nodes().map(|n| (n, identity4())).collect();
    while let Some((node, parent)) = stack.pop() {
        let local = node.transform().matrix().map(|c| c.map(|x| x as f64));
        let world = mat4_mul(&parent, &local);
        for child in node.children() {
            stack.push((child, world));
        }
        let Some(mesh) = node.mesh() else { continue };
        for prim in mesh.primitives() {
            let label = format!("{} primitive {}", mesh.name().unwrap_or("mesh"), prim.index());
            if prim.mode() != gltf::mesh::Mode::Triangles {
                notes.push(format!("{label}: mode {:?} skipped (only triangles are rendered)", prim.mode()));
                continue;
            }
            let reader = prim.reader(|b| buffers.get(b.index()).map(|v| v.as_slice()));
            let positions: Vec<V3> = reader
                .read_positions()
                .ok_or_else(|| bad(path, format!("{label} has no POSITION attribute")))?
                .map(|p| p.map(|x| x as f64))
                .collect();
            let n = positions.len();
            let triangles: Vec<[u32; 3]> = match reader.read_indices() {
                Some(ix) => ix.into_u32().collect::<Vec<_>>().chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
                None => (0..n as u32 / 3).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect(),
            };
            if triangles.iter().flatten().any(|&i| i as usize >= n) {
                return Err(bad(path, format!("{label}: an index points beyond the {n} vertices")));
            }
            let gltf_mat = prim.material().index();
            let material =
                material_override.unwrap_or_else(|| gltf_mat.map(|i| mat_map[i]).unwrap_or(default_material));
            let uv_map = gltf_mat.filter(|_| material_override.is_none()).map(|i| mat_uv[i]).unwrap_or_default();
            let mut m = Mesh { name: label.clone(), positions, triangles, material, ..Default::default() };
            match reader.read_normals() {
                Some(ns) => m.normals = ns.map(|v| normalize(v.map(|x| x as f64))).collect(),
                None => {
                    m.compute_normals();
                    notes.push(format!("{label} has no normals: computed smooth vertex normals from the faces"));
                }
            }
            if m.normals.len() != n {
                return Err(bad(path, format!("{label}: {} normals for {n} positions", m.normals.len())));
            }
            if let Some(uv) = reader.read_tex_coords(uv_map.set) {
                m.uvs = Some(uv.into_f32().map(|t| uv_map.apply([t[0] as f64, t[1] as f64])).collect());
            } else if uv_map.set != 0 {
                notes.push(format!("{label}: its material reads TEXCOORD_{}, which the primitive lacks", uv_map.set));
            }
            match reader.read_tangents() {
                Some(ts) => {
                    let ts: Vec<[f32; 4]> = ts.collect();
                    m.corner_tangents =
                        Some(m.triangles.iter().flat_map(|t| t.map(|i| ts[i as usize].map(|x| x as f64))).collect());
                }
                None => {
                    // MikkTSpace assumes v grows upwards in the image (OpenGL); glTF's v grows downwards (row 0
                    // at v = 0), so its bitangent sign is the mirror of MikkTSpace's on glTF UVs: flipping v
                    // leaves the tangent dP/du alone and negates w. Then a normal texture's green points up the
                    // image (+y of glTF's tangent space), as glTF's exporters and sample viewer have it.
                    if m.compute_tangents() {
                        for t in m.corner_tangents.iter_mut().flatten() {
                            t[3] = -t[3];
                        }
                    }
                }
            }
            transform_mesh(&mut m, &world);
            out.push(m);
        }
    }
    if out.is_empty() {
        return Err(bad(path, "the default scene holds no triangle meshes"));
    }
    Ok(out)
}

/// The JSON of a glTF object's `extras`, where it has some.
pub(crate) fn extras_of(e: &gltf::json::Extras) -> Option<serde_json::Value> {
    e.as_ref().and_then(|raw| serde_json::from_str(raw.get()).ok())
}

/// Thinnest film whose interference colours show: below 10 nm a film's reflectance differs from its
/// substrate's by at most a few per cent, evenly over the spectrum.
pub const THINNEST_COLOURED_FILM_NM: f64 = 10.0;

/// A warning for a KHR_materials_iridescence thickness range that cannot be what the author meant: glTF gives
/// it in nanometres, and a range below [`THINNEST_COLOURED_FILM_NM`] (e.g. 0.2–0.6, written in µm) renders as no
/// film at all. The range used is `dmax` alone without a thickness texture, `dmin`–`dmax` with one.
pub fn implausible_thickness(material: &str, dmin: f64, dmax: f64, textured: bool) -> Option<String> {
    let (lo, hi) = if textured { (dmin.min(dmax), dmin.max(dmax)) } else { (dmax, dmax) };
    (hi > 0.0 && hi < THINNEST_COLOURED_FILM_NM).then(|| {
        let range = |k: f64| if lo == hi { format!("{}", hi * k) } else { format!("{}–{}", lo * k, hi * k) };
        format!(
            "material \"{material}\": iridescence thickness {} nm is below {THINNEST_COLOURED_FILM_NM} nm, too thin to \
             show interference colours, so it renders as (almost) no film; KHR_materials_iridescence gives \
             thicknesses in nanometres — if these were micrometres, the film is {} nm: fix \
             iridescenceThicknessMinimum/Maximum in the file",
            range(1.0),
            range(1000.0)
        )
    })
}

/// The texture coordinates a material's textures read: the UV set (`texCoord`) and `KHR_texture_transform`
/// (offset, rotation, scale; its `texCoord` overrides the set), applied to the mesh's UVs at load.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct UvMap {
    set: u32,
    /// `[offset_u, offset_v, rotation, scale_u, scale_v]`; `None`: identity.
    transform: Option<[f64; 5]>,
}

impl UvMap {
    fn of(tex_coord: u32, extensions: Option<&serde_json::Map<String, serde_json::Value>>) -> Self {
        let Some(t) = extensions.and_then(|e| e.get("KHR_texture_transform")) else {
            return UvMap { set: tex_coord, transform: None };
        };
        let pair = |k: &str, d: [f64; 2]| {
            t.get(k)
                .and_then(|v| v.as_array())
                .map(|a| [0, 1].map(|i| a.get(i).and_then(|x| x.as_f64()).unwrap_or(d[i])))
                .unwrap_or(d)
        };
        let (o, s) = (pair("offset", [0.0, 0.0]), pair("scale", [1.0, 1.0]));
        let r = t.get("rotation").and_then(|v| v.as_f64()).unwrap_or(0.0);
        let set = t.get("texCoord").and_then(|v| v.as_u64()).map(|v| v as u32).unwrap_or(tex_coord);
        UvMap { set, transform: Some([o[0], o[1], r, s[0], s[1]]) }
    }

    /// `T · R · S · uv` of the KHR_texture_transform specification.
    fn apply(&self, uv: [f64; 2]) -> [f64; 2] {
        let Some([ou, ov, r, su, sv]) = self.transform else { return uv };
        let (sn, cs) = r.sin_cos();
        let (x, y) = (uv[0] * su, uv[1] * sv);
        [cs * x + sn * y + ou, -sn * x + cs * y + ov]
    }
}

/// Notes the sampler settings the renderer does not follow (it repeats and filters bilinearly).
/// A material has one set of texture coordinates (the first texture's); a later texture that reads other
/// coordinates is named in a note and reads the material's.
fn share_uv_map(uv_map: &mut Option<UvMap>, own: UvMap, material: &str, slot: &str, notes: &mut Vec<String>) {
    match uv_map {
        None => *uv_map = Some(own),
        Some(u) if *u != own => notes.push(format!(
            "material \"{material}\": {slot} reads other texture coordinates (texCoord / KHR_texture_transform) \
             than baseColorTexture; both use the base colour's"
        )),
        Some(_) => {}
    }
}

fn check_sampler(material: &str, slot: &str, tex: &gltf::Texture, notes: &mut Vec<String>) {
    use gltf::texture::{MagFilter, WrappingMode};
    let s = tex.sampler();
    let mut odd = Vec::new();
    if s.wrap_s() != WrappingMode::Repeat || s.wrap_t() != WrappingMode::Repeat {
        odd.push(format!("wrap {:?}/{:?} (textures repeat)", s.wrap_s(), s.wrap_t()));
    }
    if s.mag_filter() == Some(MagFilter::Nearest) {
        odd.push("nearest filtering (textures are filtered bilinearly)".to_string());
    }
    if !odd.is_empty() {
        notes.push(format!("material \"{material}\": {slot}'s sampler is not supported: {}", odd.join(", ")));
    }
}

/// The substrate of a film over a metal whose normal-incidence reflectance is `f0` (linear RGB): the real
/// index `n = (1 + √F_0)/(1 − √F_0)` (glTF iridescence's `Fresnel0ToIor`, √F_0 ≤ 0.9999), with `F_0(λ)`
/// piecewise linear through the channels at 610 (R), 550 (G) and 465 nm (B), constant beyond, on a 5 nm grid.
pub fn metal_from_f0(f0: [f64; 3]) -> Result<iridis_thinfilm::Material, RenderError> {
    let nodes = [(465.0, f0[2]), (550.0, f0[1]), (610.0, f0[0])];
    let mut csv = String::from("wavelength_nm,n\n");
    for i in 0..=80 {
        let l = 380.0 + 5.0 * i as f64;
        let f = if l <= nodes[0].0 {
            nodes[0].1
        } else if l >= nodes[2].0 {
            nodes[2].1
        } else {
            let k = if l < nodes[1].0 { 0 } else { 1 };
            let (a, b) = (nodes[k], nodes[k + 1]);
            a.1 + (b.1 - a.1) * (l - a.0) / (b.0 - a.0)
        };
        let r = f.clamp(0.0, 1.0).sqrt().min(0.9999);
        csv.push_str(&format!("{l},{}\n", (1.0 + r) / (1.0 - r)));
    }
    iridis_thinfilm::nkfile::parse_csv(&csv, "metal base (from baseColorFactor)")
        .map_err(|e| RenderError::Input(format!("metal base index: {e}")))
}

pub(crate) fn identity4() -> [[f64; 4]; 4] {
    let mut m = [[0.0; 4]; 4];
    for (i, r) in m.iter_mut().enumerate() {
        r[i] = 1.0;
    }
    m
}

/// Product of column-major 4×4 matrices (glTF's layout: `m[column][row]`).
pub(crate) fn mat4_mul(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let mut r = [[0.0; 4]; 4];
    for c in 0..4 {
        for row in 0..4 {
            r[c][row] = (0..4).map(|k| a[k][row] * b[c][k]).sum();
        }
    }
    r
}

/// Applies a column-major affine matrix: positions by the matrix, normals by its inverse transpose.
fn transform_mesh(m: &mut Mesh, w: &[[f64; 4]; 4]) {
    let lin: M3 = [[w[0][0], w[1][0], w[2][0]], [w[0][1], w[1][1], w[2][1]], [w[0][2], w[1][2], w[2][2]]];
    let t = [w[3][0], w[3][1], w[3][2]];
    let cof = [cross(col(&lin, 1), col(&lin, 2)), cross(col(&lin, 2), col(&lin, 0)), cross(col(&lin, 0), col(&lin, 1))];
    for p in &mut m.positions {
        *p = add(mat_vec(&lin, *p), t);
    }
    // The cofactor matrix (rows = columns' cross products) is the inverse transpose up to a positive factor
    // times det: normalising removes the scale, the sign of det flips mirrored nodes back.
    let det = dot(col(&lin, 0), cof[0]);
    for n in &mut m.normals {
        let v = [dot(cof[0], *n), dot(cof[1], *n), dot(cof[2], *n)];
        *n = normalize(mul(v, det.signum()));
    }
    if let Some(ts) = &mut m.corner_tangents {
        for c in ts.iter_mut() {
            let v = normalize(mat_vec(&lin, [c[0], c[1], c[2]]));
            *c = [v[0], v[1], v[2], c[3]];
        }
    }
}

fn col(m: &M3, j: usize) -> V3 {
    [m[0][j], m[1][j], m[2][j]]
}

/// The choices a glTF scene leaves open: which of its cameras (by node or camera name, or index; `default`
/// for iridis' own framing), and whether its KHR_lights_punctual lights are used.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GltfOptions {
    pub camera: Option<String>,
    pub ignore_lights: bool,
}
