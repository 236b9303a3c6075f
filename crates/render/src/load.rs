//! Reading a scene file of either format: TOML ([`crate::scene_toml`]) or glTF 2.0 ([`crate::gltf_scene`]).

use std::path::Path;

use crate::error::RenderError;
use crate::gltf_io::GltfOptions;
use crate::gltf_scene::scene_from_gltf_with;
use crate::scene::Scene;
use crate::scene_toml::parse_scene;

/// Reads a scene file (TOML, or a glTF 2.0 file `.gltf`/`.glb` with its own cameras and lights, or a default
/// camera and light where it has none).
pub fn load_scene(path: &Path) -> Result<Scene, RenderError> {
    load_scene_with(path, &GltfOptions::default())
}

/// [`load_scene`] with the choices a glTF scene leaves open (which of its cameras, whether its lights).
pub fn load_scene_with(path: &Path, gltf: &GltfOptions) -> Result<Scene, RenderError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if ext == "gltf" || ext == "glb" {
        return scene_from_gltf_with(path, gltf);
    }
    if ext == "obj" {
        // A mesh is one object of a scene; read as TOML it failed on its first vertex line.
        let name = path.file_name().map_or_else(|| path.display().to_string(), |f| f.to_string_lossy().into_owned());
        return Err(RenderError::Input(format!(
            "{}: an OBJ file is a mesh, not a scene; put it in a TOML scene as an object — [[object]] kind = \"obj\", \
             file = \"{name}\", material = … — with a [camera] and a [[light]] (docs/render.md; \
             examples/laser_screen.toml places unit_box.obj), or give a glTF file (.gltf, .glb), which holds its own",
            path.display()
        )));
    }
    if gltf.camera.is_some() || gltf.ignore_lights {
        return Err(RenderError::Input(format!(
            "{}: --camera and --ignore-gltf-lights choose among a glTF file's own cameras and lights; a TOML scene \
             has its [camera] and [[light]]",
            path.display()
        )));
    }
    let text = std::fs::read_to_string(path).map_err(|e| {
        RenderError::Input(format!("cannot read scene {}: {e} (check the path; scenes are TOML files)", path.display()))
    })?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    parse_scene(&text, &path.display().to_string(), &base).map_err(|e| match e {
        // Another kind of file read as TOML fails on its first lines: say what a scene file is.
        RenderError::Scene { path: p, line, message } if !matches!(ext.as_str(), "toml" | "") => RenderError::Scene {
            message: format!("{message} (a scene is a TOML file, .toml, or a glTF file, .gltf or .glb; not .{ext})"),
            path: p,
            line,
        },
        e => e,
    })
}
