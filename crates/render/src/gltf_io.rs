//! glTF 2.0 input (`.gltf` with external or embedded buffers, `.glb`): triangle meshes with normals, UVs and
//! tangents (MikkTSpace when the file has none, as the glTF specification asks), PBR metallic-roughness
//! materials as a GGX base, and `KHR_materials_iridescence` as a thin-film stack over that base:
//! `air | n = iridescenceIor, d | n = 1.5`, with `d = mix(thicknessMinimum, thicknessMaximum, texture.g)`
//! (Sussenbach's SVT with `d_avg = (min + max)/2`, `d_rel = (max − min)/2`) or `d = thicknessMaximum`
//! without a texture, and the film's reflection weighted by `iridescenceFactor`.

use std::path::Path;

use crate::error::RenderError;
use crate::geometry::Mesh;
use crate::light::{Environment, Light};
use crate::material::{ColorSource, Material, Microfacet, Svt, ThinFilm};
use crate::math::*;
use crate::texture::{TexKind, Texture};

fn bad(path: &Path, msg: impl std::fmt::Display) -> RenderError {
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
/// every mesh uses that material instead of the file's.
pub fn load_gltf(
    path: &Path,
    materials: &mut Vec<Material>,
    material_names: &mut Vec<String>,
    textures: &mut Vec<Texture>,
    material_override: Option<usize>,
    notes: &mut Vec<String>,
) -> Result<Vec<Mesh>, RenderError> {
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
        image::load_from_memory(&data).map_err(|e| bad(path, format!("image {}: {e}", tex.source().index())))
    };

    // Materials
    let mut mat_map = Vec::new();
    for m in doc.materials() {
        let name = m.name().map(str::to_string).unwrap_or_else(|| format!("gltf material {}", m.index().unwrap_or(0)));
        let pbr = m.pbr_metallic_roughness();
        let bc = pbr.base_color_factor();
        let color = match pbr.base_color_texture() {
            Some(info) => {
                textures.push(Texture::from_image(image_of(info.texture())?, TexKind::Color, &name)?);
                ColorSource::Texture(textures.len() - 1)
            }
            None => ColorSource::Const([bc[0] as f64, bc[1] as f64, bc[2] as f64]),
        };
        let base = Microfacet {
            color,
            roughness: pbr.roughness_factor().clamp(0.0, 1.0) as f64,
            metallic: pbr.metallic_factor().clamp(0.0, 1.0) as f64,
            ior: 1.5,
        };
        let ext = m.extensions().and_then(|e| e.get("KHR_materials_iridescence"));
        let mat = match ext {
            Some(x) => {
                let num = |k: &str, d: f64| x.get(k).and_then(|v| v.as_f64()).unwrap_or(d);
                let factor = num("iridescenceFactor", 0.0).clamp(0.0, 1.0);
                let ior = num("iridescenceIor", 1.3);
                let (dmin, dmax) =
                    (num("iridescenceThicknessMinimum", 100.0), num("iridescenceThicknessMaximum", 400.0));
                if !(ior >= 1.0 && dmin >= 0.0 && dmax >= 0.0) {
                    return Err(bad(
                        path,
                        format!("material \"{name}\": iridescence IOR {ior} or thickness {dmin}–{dmax} nm is invalid"),
                    ));
                }
                let tex_index =
                    x.get("iridescenceThicknessTexture").and_then(|t| t.get("index")).and_then(|i| i.as_u64());
                let (d, svt) = match tex_index {
                    Some(i) => {
                        let tex = doc
                            .textures()
                            .nth(i as usize)
                            .ok_or_else(|| bad(path, format!("thickness texture {i} does not exist")))?;
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
                let stack: iridis_thinfilm::Stack = format!("air | n={ior} {d}nm | n=1.5")
                    .parse()
                    .map_err(|e| bad(path, format!("material \"{name}\": {e}")))?;
                let mut film = ThinFilm::new(stack, svt, false)?;
                film.base = Some(base);
                film.factor = factor;
                Material::ThinFilm(Box::new(film))
            }
            None => Material::Microfacet(base),
        };
        materials.push(mat);
        material_names.push(name);
        mat_map.push(materials.len() - 1);
    }
    let default_material = match material_override {
        Some(m) => m,
        None => {
            materials.push(Material::Microfacet(Microfacet {
                color: ColorSource::Const([0.8; 3]),
                roughness: 0.5,
                metallic: 0.0,
                ior: 1.5,
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
            let material = material_override
                .unwrap_or_else(|| prim.material().index().map(|i| mat_map[i]).unwrap_or(default_material));
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
            if let Some(uv) = reader.read_tex_coords(0) {
                m.uvs = Some(uv.into_f32().map(|t| [t[0] as f64, t[1] as f64]).collect());
            }
            match reader.read_tangents() {
                Some(ts) => {
                    let ts: Vec<[f32; 4]> = ts.collect();
                    m.corner_tangents =
                        Some(m.triangles.iter().flat_map(|t| t.map(|i| ts[i as usize].map(|x| x as f64))).collect());
                }
                None => {
                    m.compute_tangents();
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

fn identity4() -> [[f64; 4]; 4] {
    let mut m = [[0.0; 4]; 4];
    for (i, r) in m.iter_mut().enumerate() {
        r[i] = 1.0;
    }
    m
}

/// Product of column-major 4×4 matrices (glTF's layout: `m[column][row]`).
fn mat4_mul(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
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

/// A glTF file as a whole scene: its meshes and materials, a camera framing them from the front (+z) and a
/// little above, a directional D65 light from the upper left and a sky environment.
pub fn scene_from_gltf(path: &Path) -> Result<crate::scene::Scene, RenderError> {
    let mut materials = Vec::new();
    let mut names = Vec::new();
    let mut textures = Vec::new();
    let mut notes = Vec::new();
    let meshes = load_gltf(path, &mut materials, &mut names, &mut textures, None, &mut notes)?;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for m in &meshes {
        let (a, b) = m.bounds();
        for k in 0..3 {
            lo[k] = lo[k].min(a[k]);
            hi[k] = hi[k].max(b[k]);
        }
    }
    let center = mul(add(lo, hi), 0.5);
    let radius = (0.5 * length(sub(hi, lo))).max(1e-6);
    let fov = 35f64.to_radians();
    let dist = radius / (fov / 2.0).sin() * 1.1;
    let position = add(center, mul(normalize([0.0, 0.35, 1.0]), dist));
    let (forward, right, up) = crate::camera::frame(sub(center, position), [0.0, 1.0, 0.0]).expect("camera frame");
    notes.push("glTF scene: default camera (front, slightly above), a D65 light from the upper left and a sky".into());
    let bvh = crate::bvh::Bvh::build(&meshes);
    let environment =
        Environment::Sky { zenith: [0.25, 0.45, 0.9], horizon: [0.9, 0.92, 0.95], ground: [0.2, 0.18, 0.15] };
    Ok(crate::scene::Scene {
        camera: crate::camera::Camera::Perspective { position, forward, right, up, tan_half: (fov / 2.0).tan() },
        lights: vec![Light::Directional { direction: normalize([-0.5, 1.0, 0.7]), rgb: [1.0; 3] }],
        irradiance: environment.irradiance_map(),
        environment,
        environment_visible: true,
        meshes,
        spheres: Vec::new(),
        planes: Vec::new(),
        materials,
        material_names: names,
        textures,
        bvh,
        output: crate::scene::Output {
            width: 512,
            height: 512,
            spp: 4,
            exposure: 1.0,
            encoding: iridis_color::Encoding::Srgb,
            background: [0.0; 3],
            max_depth: 6,
        },
        notes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trip() {
        assert_eq!(base64_decode("aXJpZGlz").unwrap(), b"iridis");
        assert_eq!(base64_decode("aXJpZA==").unwrap(), b"irid");
        assert!(base64_decode("a*b").is_none());
    }
}
