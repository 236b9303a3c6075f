//! Writes a scene's triangle meshes as a binary glTF 2.0 file (`.glb`): positions, normals, UVs and the
//! orientation field as TANGENT, so that a procedural mesh (the scaled snake, whose nanostructure axis follows
//! each scale's long axis) renders the same in another scene with `orientation = "tangent"`, in iridis' GPU
//! path, or in any glTF tool. [`scene_glb`] adds the scene: every material as glTF PBR (metallic-roughness,
//! KHR_materials_iridescence for a one-layer film) for other tools, and as iridis' own definition in the
//! material's and the file's `extras`, which iridis reads back, so that `iridis render x.glb` looks like the
//! scene; the camera; the point and directional lights (KHR_lights_punctual).

use serde_json::json;

use crate::camera::Camera;
use crate::error::RenderError;
use crate::geometry::Mesh;
use crate::light::Light;
use crate::material::{ColorSource, Material};
use crate::math::*;
use crate::scene::Scene;

/// The TANGENT written for vertex `i` of `m`: its `along` field where it has one (the orientation rule of
/// the procedural snake), otherwise the tangent of the first triangle corner that uses it (MikkTSpace or the
/// file's own). `None` when the mesh has neither.
fn vertex_tangents(m: &Mesh) -> Option<Vec<[f32; 4]>> {
    if let Some(a) = &m.along {
        return Some(a.iter().map(|v| [v[0] as f32, v[1] as f32, v[2] as f32, 1.0]).collect());
    }
    let ts = m.corner_tangents.as_ref()?;
    let mut out = vec![[1.0, 0.0, 0.0, 1.0]; m.positions.len()];
    let mut seen = vec![false; m.positions.len()];
    for (k, t) in ts.iter().enumerate() {
        let v = m.triangles[k / 3][k % 3] as usize;
        if !seen[v] {
            seen[v] = true;
            out[v] = t.map(|x| x as f32);
        }
    }
    Some(out)
}

/// The GLB bytes of `meshes` (one glTF mesh and node each, in world space), without materials.
pub fn glb_bytes(meshes: &[Mesh]) -> Result<Vec<u8>, RenderError> {
    write_glb(meshes, None)
}

/// What [`scene_glb`] adds to the meshes: glTF materials (one per scene material, indexed as the scene's),
/// nodes and root extensions for the camera and lights, and the root's extras.
struct SceneParts {
    materials: Vec<serde_json::Value>,
    nodes: Vec<serde_json::Value>,
    cameras: Vec<serde_json::Value>,
    lights: Vec<serde_json::Value>,
    extras: Option<serde_json::Value>,
}

impl SceneParts {
    fn materials_use_iridescence(&self) -> bool {
        self.materials.iter().any(|m| m.pointer("/extensions/KHR_materials_iridescence").is_some())
    }
}

/// The GLB bytes of a whole scene (module notes), and notes on what glTF could not carry (analytic spheres
/// and planes, area lights, lasers, the hemisphere camera).
pub fn scene_glb(scene: &Scene) -> Result<(Vec<u8>, Vec<String>), RenderError> {
    let mut notes = Vec::new();
    let materials = scene.materials.iter().zip(&scene.material_names).map(|(m, name)| pbr(m, name, scene)).collect();
    let mut nodes = Vec::new();
    let mut cameras = Vec::new();
    let aspect = scene.output.width as f64 / scene.output.height.max(1) as f64;
    let framed = |position: V3, forward: V3, right: V3, up: V3| {
        // glTF cameras look along −z with +y up: columns x = right, y = up, z = −forward.
        let z = mul(forward, -1.0);
        [
            right[0],
            right[1],
            right[2],
            0.0,
            up[0],
            up[1],
            up[2],
            0.0,
            z[0],
            z[1],
            z[2],
            0.0,
            position[0],
            position[1],
            position[2],
            1.0,
        ]
    };
    match scene.camera {
        Camera::Perspective { position, forward, right, up, tan_half } => {
            cameras.push(json!({"type": "perspective", "name": "iridis camera",
                "perspective": {"yfov": 2.0 * tan_half.atan(), "aspectRatio": aspect, "znear": 1e-3}}));
            nodes.push(json!({"name": "iridis camera", "camera": 0, "matrix": framed(position, forward, right, up)}));
        }
        Camera::Orthographic { position, forward, right, up, half_height } => {
            cameras.push(json!({"type": "orthographic", "name": "iridis camera",
                "orthographic": {"xmag": half_height * aspect, "ymag": half_height, "znear": 0.0, "zfar": 1e9}}));
            nodes.push(json!({"name": "iridis camera", "camera": 0, "matrix": framed(position, forward, right, up)}));
        }
        Camera::Hemisphere { .. } => {
            notes.push("the hemisphere (BRDF-map) camera has no glTF counterpart: not exported".into())
        }
    }
    let mut lights = Vec::new();
    let (mut lasers, areas) = (0, scene.area_lights.len());
    for l in &scene.lights {
        let (kind, rgb, matrix) = match l {
            Light::Directional { direction, rgb } => {
                // It shines along the node's −z: +z points towards the light.
                let z = normalize(*direction);
                let x = any_perpendicular(z);
                let y = cross(z, x);
                (
                    "directional",
                    *rgb,
                    [x[0], x[1], x[2], 0.0, y[0], y[1], y[2], 0.0, z[0], z[1], z[2], 0.0, 0.0, 0.0, 0.0, 1.0],
                )
            }
            Light::Point { position, rgb } => {
                let p = *position;
                ("point", *rgb, [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, p[0], p[1], p[2], 1.0])
            }
            Light::Laser(_) => {
                lasers += 1;
                continue;
            }
        };
        let intensity = rgb.iter().fold(0.0f64, |a, &b| a.max(b));
        let color = if intensity > 0.0 { rgb.map(|c| c / intensity) } else { [1.0; 3] };
        lights.push(json!({"type": kind, "color": color, "intensity": intensity}));
        nodes.push(json!({"name": format!("iridis {kind} light"), "matrix": matrix,
            "extensions": {"KHR_lights_punctual": {"light": lights.len() - 1}}}));
    }
    if lasers + areas > 0 {
        notes.push(format!(
            "{} area light(s) and {lasers} laser(s) have no KHR_lights_punctual counterpart: not exported",
            areas
        ));
    }
    if !scene.spheres.is_empty() || !scene.planes.is_empty() {
        notes.push(format!(
            "{} analytic sphere(s) and {} plane(s) are not meshes: not exported",
            scene.spheres.len(),
            scene.planes.len()
        ));
    }
    let extras = scene
        .source
        .as_ref()
        .map(|s| json!({"iridis": {"sections": s.sections, "base": s.base.display().to_string()}}));
    if extras.is_none() {
        notes.push("the scene has no TOML definitions (a glTF scene): materials exported as glTF PBR only".into());
    }
    let bytes = write_glb(&scene.meshes, Some(SceneParts { materials, nodes, cameras, lights, extras }))?;
    Ok((bytes, notes))
}

/// A material as glTF PBR (what another tool shows) plus its iridis name in `extras`.
fn pbr(m: &Material, name: &str, scene: &Scene) -> serde_json::Value {
    let colour = |c: &ColorSource| -> [f64; 3] {
        match c {
            ColorSource::Const(c) => *c,
            // The texture's mean over an 8 × 8 grid of samples: what a single PBR colour can say of it.
            ColorSource::Texture(i) => scene.textures.get(*i).map_or([0.8; 3], |t| {
                let mut acc = [0.0; 3];
                for k in 0..64 {
                    let c = t.sample([((k % 8) as f64 + 0.5) / 8.0, ((k / 8) as f64 + 0.5) / 8.0]);
                    for j in 0..3 {
                        acc[j] += c[j] / 64.0;
                    }
                }
                acc
            }),
        }
    };
    let rgba = |c: [f64; 3]| [c[0].clamp(0.0, 1.0), c[1].clamp(0.0, 1.0), c[2].clamp(0.0, 1.0), 1.0];
    let mut out = match m {
        Material::Lambert { color } => json!({"pbrMetallicRoughness": {"baseColorFactor": rgba(colour(color)),
            "metallicFactor": 0.0, "roughnessFactor": 1.0}}),
        Material::Microfacet(f) => json!({"pbrMetallicRoughness": {"baseColorFactor": rgba(colour(&f.color)),
            "metallicFactor": f.metallic, "roughnessFactor": f.roughness}}),
        Material::Diffraction(d) => json!({"pbrMetallicRoughness": {"baseColorFactor": rgba(colour(&d.texture)),
            "metallicFactor": 0.0, "roughnessFactor": 0.4}}),
        Material::ThinFilm(f) => {
            let (base, metallic, roughness) = match &f.base {
                Some(b) => (colour(&b.color), b.metallic, b.roughness),
                None => ([0.05; 3], 0.0, 0.0),
            };
            let mut v = json!({"pbrMetallicRoughness": {"baseColorFactor": rgba(base),
                "metallicFactor": metallic, "roughnessFactor": roughness}});
            if let [layer] = f.stack.layers.as_slice() {
                if let Ok(n) = layer.material.index_at(550.0) {
                    let d = layer.thickness_nm;
                    let (lo, hi) = f.svt.map_or((d, d), |s| ((d - s.d_rel_nm).max(0.0), d + s.d_rel_nm));
                    v["extensions"] = json!({"KHR_materials_iridescence": {"iridescenceFactor": f.factor,
                        "iridescenceIor": n.re, "iridescenceThicknessMinimum": lo, "iridescenceThicknessMaximum": hi}});
                }
            }
            v
        }
    };
    out["name"] = json!(name);
    out["extras"] = json!({"iridis": {"material": name}});
    out
}

fn write_glb(meshes: &[Mesh], parts: Option<SceneParts>) -> Result<Vec<u8>, RenderError> {
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut gl_meshes = Vec::new();
    let mut nodes = Vec::new();
    // Appends one accessor over `data` (4-byte aligned, as glTF asks) and returns its index.
    let mut push = |bytes: Vec<u8>, count: usize, kind: &str, component: u32, target: u32, extra: serde_json::Value| {
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len(), "target": target}));
        bin.extend_from_slice(&bytes);
        let mut a = json!({"bufferView": views.len() - 1, "componentType": component, "count": count, "type": kind});
        if let (Some(o), Some(e)) = (a.as_object_mut(), extra.as_object()) {
            o.extend(e.clone());
        }
        accessors.push(a);
        accessors.len() - 1
    };
    const FLOAT: u32 = 5126;
    const UINT: u32 = 5125;
    const ARRAY: u32 = 34962;
    const ELEMENTS: u32 = 34963;
    let f32s = |v: &mut dyn Iterator<Item = f32>| v.flat_map(f32::to_le_bytes).collect::<Vec<u8>>();
    for m in meshes {
        if m.triangles.is_empty() {
            continue;
        }
        let n = m.positions.len();
        let (lo, hi) = m.bounds();
        let pos = push(
            f32s(&mut m.positions.iter().flat_map(|p| p.map(|x| x as f32))),
            n,
            "VEC3",
            FLOAT,
            ARRAY,
            json!({"min": lo.map(|x| x as f32), "max": hi.map(|x| x as f32)}),
        );
        let mut attributes = json!({"POSITION": pos});
        if m.normals.len() == n {
            let nrm =
                push(f32s(&mut m.normals.iter().flat_map(|p| p.map(|x| x as f32))), n, "VEC3", FLOAT, ARRAY, json!({}));
            attributes["NORMAL"] = json!(nrm);
        }
        if let Some(uvs) = &m.uvs {
            let uv = push(f32s(&mut uvs.iter().flat_map(|p| p.map(|x| x as f32))), n, "VEC2", FLOAT, ARRAY, json!({}));
            attributes["TEXCOORD_0"] = json!(uv);
        }
        if let Some(ts) = vertex_tangents(m) {
            let t = push(f32s(&mut ts.into_iter().flatten()), n, "VEC4", FLOAT, ARRAY, json!({}));
            attributes["TANGENT"] = json!(t);
        }
        let idx: Vec<u8> = m.triangles.iter().flatten().flat_map(|i| i.to_le_bytes()).collect();
        let indices = push(idx, m.triangles.len() * 3, "SCALAR", UINT, ELEMENTS, json!({}));
        let mut primitive = json!({"attributes": attributes, "indices": indices});
        if parts.is_some() {
            primitive["material"] = json!(m.material);
        }
        gl_meshes.push(json!({"name": m.name, "primitives": [primitive]}));
        nodes.push(json!({"mesh": gl_meshes.len() - 1, "name": m.name}));
    }
    if gl_meshes.is_empty() {
        return Err(RenderError::Input(
            "the scene has no triangle meshes to export (spheres and planes are analytic)".into(),
        ));
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let mut doc = json!({
        "asset": {"version": "2.0", "generator": concat!("iridis ", env!("CARGO_PKG_VERSION"))},
        "scene": 0,
        "meshes": gl_meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len()}],
    });
    if let Some(p) = parts {
        let mut used = Vec::new();
        if p.materials_use_iridescence() {
            used.push("KHR_materials_iridescence");
        }
        doc["materials"] = json!(p.materials);
        nodes.extend(p.nodes);
        if !p.cameras.is_empty() {
            doc["cameras"] = json!(p.cameras);
        }
        if !p.lights.is_empty() {
            doc["extensions"] = json!({"KHR_lights_punctual": {"lights": p.lights}});
            used.push("KHR_lights_punctual");
        }
        if !used.is_empty() {
            doc["extensionsUsed"] = json!(used);
        }
        if let Some(x) = p.extras {
            doc["extras"] = x;
        }
    }
    let node_ids: Vec<usize> = (0..nodes.len()).collect();
    doc["scenes"] = json!([{"nodes": node_ids}]);
    doc["nodes"] = json!(nodes);
    let mut text = serde_json::to_vec(&doc).map_err(|e| RenderError::Input(format!("glTF JSON: {e}")))?;
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let total = u32::try_from(total).map_err(|_| {
        RenderError::Input(format!("the meshes need {total} bytes, more than a GLB file holds (4 GiB)"))
    })?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    Ok(out)
}
