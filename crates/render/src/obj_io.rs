//! Wavefront OBJ meshes (through `tobj`): triangulated, one index per vertex; normals computed when missing,
//! MikkTSpace tangents when the mesh has UVs. OBJ's `v` texture axis points up, so `v` is flipped to the
//! top-left origin used everywhere else (glTF's).

use std::path::Path;

use crate::error::RenderError;
use crate::geometry::Mesh;

pub fn load_obj(path: &Path, material: usize, notes: &mut Vec<String>) -> Result<Vec<Mesh>, RenderError> {
    let opts = tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };
    let (models, _materials) = tobj::load_obj(path, &opts).map_err(|e| {
        RenderError::Input(format!(
            "cannot load OBJ mesh {}: {e} (check the path and that it is a Wavefront .obj)",
            path.display()
        ))
    })?;
    if models.is_empty() {
        return Err(RenderError::Input(format!("OBJ file {} holds no faces", path.display())));
    }
    let mut out = Vec::new();
    for model in models {
        let m = &model.mesh;
        let nv = m.positions.len() / 3;
        if m.indices.is_empty() {
            continue;
        }
        if let Some(bad) = m.indices.iter().find(|&&i| i as usize >= nv) {
            return Err(RenderError::Input(format!(
                "OBJ {}: face index {bad} beyond the {nv} vertices",
                path.display()
            )));
        }
        let positions: Vec<[f64; 3]> =
            m.positions.chunks_exact(3).map(|p| [p[0] as f64, p[1] as f64, p[2] as f64]).collect();
        if positions.iter().flatten().any(|x| !x.is_finite()) {
            return Err(RenderError::Input(format!(
                "OBJ {}: a vertex position is not a finite number",
                path.display()
            )));
        }
        let mut mesh = Mesh {
            name: if model.name.is_empty() { path.display().to_string() } else { model.name.clone() },
            positions,
            triangles: m.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
            material,
            ..Default::default()
        };
        if m.normals.len() == m.positions.len() {
            mesh.normals = m
                .normals
                .chunks_exact(3)
                .map(|n| crate::math::try_normalize([n[0] as f64, n[1] as f64, n[2] as f64]).unwrap_or([0.0, 0.0, 1.0]))
                .collect();
        } else {
            mesh.compute_normals();
            notes.push(format!("mesh \"{}\" has no normals: computed smooth vertex normals from the faces", mesh.name));
        }
        if m.texcoords.len() / 2 == nv {
            mesh.uvs = Some(m.texcoords.chunks_exact(2).map(|t| [t[0] as f64, 1.0 - t[1] as f64]).collect());
            if !mesh.compute_tangents() {
                notes.push(format!("mesh \"{}\": MikkTSpace could not build tangents", mesh.name));
            }
        }
        out.push(mesh);
    }
    if out.is_empty() {
        return Err(RenderError::Input(format!("OBJ file {} holds no triangles", path.display())));
    }
    Ok(out)
}
