//! Writes a scene's triangle meshes as a binary glTF 2.0 file (`.glb`): positions, normals, UVs and the
//! orientation field as TANGENT, so that a procedural mesh (the scaled snake, whose nanostructure axis follows
//! each scale's long axis) renders the same in another scene with `orientation = "tangent"`, in iridis' GPU
//! path, or in any glTF tool. No materials: a scene that loads the file names its own (`material = "…"`).

use serde_json::json;

use crate::error::RenderError;
use crate::geometry::Mesh;

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

/// The GLB bytes of `meshes` (one glTF mesh and node each, in world space).
pub fn glb_bytes(meshes: &[Mesh]) -> Result<Vec<u8>, RenderError> {
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
        gl_meshes.push(json!({"name": m.name, "primitives": [{"attributes": attributes, "indices": indices}]}));
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
    let node_ids: Vec<usize> = (0..nodes.len()).collect();
    let doc = json!({
        "asset": {"version": "2.0", "generator": concat!("iridis ", env!("CARGO_PKG_VERSION"))},
        "scene": 0,
        "scenes": [{"nodes": node_ids}],
        "nodes": nodes,
        "meshes": gl_meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len()}],
    });
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
