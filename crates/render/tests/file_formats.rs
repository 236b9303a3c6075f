//! Input formats beyond the examples: malformed glTF (the message names line and column), binary glTF
//! (`.glb`, geometry in the BIN chunk) and Radiance `.hdr` environment maps, all written by the test itself.

use std::path::Path;

use iridis_render::material::Material;
use iridis_render::{load_scene, parse_scene, render};

/// A glTF document with one triangle (z = 0, facing +z) whose positions live in buffer 0 (`uri` given or, for
/// GLB, the BIN chunk), with a KHR_materials_iridescence material: a 350 nm film of n = 1.33 over red.
fn triangle_json(uri: Option<&str>) -> String {
    let buffer = match uri {
        Some(u) => format!("{{\"byteLength\": 36, \"uri\": \"{u}\"}}"),
        None => "{\"byteLength\": 36}".to_string(),
    };
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_materials_iridescence"],
  "scene": 0,
  "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "material": 0}}]}}],
  "materials": [{{
    "name": "film",
    "pbrMetallicRoughness": {{"baseColorFactor": [1, 0, 0, 1], "metallicFactor": 0, "roughnessFactor": 0.5}},
    "extensions": {{"KHR_materials_iridescence": {{"iridescenceFactor": 1, "iridescenceIor": 1.33,
                                                  "iridescenceThicknessMaximum": 350}}}}
  }}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                  "min": [-1, -1, 0], "max": [1, 1, 0]}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
  "buffers": [{buffer}]
}}"#
    )
}

fn triangle_bytes() -> Vec<u8> {
    [-1.0f32, -1.0, 0.0, 1.0, -1.0, 0.0, 0.0, 1.0, 0.0].iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A GLB container (glTF 2.0 spec, "Binary glTF Layout"): 12-byte header, JSON chunk padded with spaces, BIN
/// chunk padded with zeros, every chunk 4-byte aligned.
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let pad = |mut v: Vec<u8>, fill: u8| {
        while !v.len().is_multiple_of(4) {
            v.push(fill);
        }
        v
    };
    let j = pad(json.as_bytes().to_vec(), b' ');
    let b = pad(bin.to_vec(), 0);
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x4E4F_534Au32.to_le_bytes()); // "JSON"
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x004E_4942u32.to_le_bytes()); // "BIN\0"
    out.extend_from_slice(&b);
    out
}

#[test]
fn malformed_gltf_names_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    // The JSON breaks on line 3, column 15 (a `}` where an array element is expected).
    let p = dir.path().join("broken.gltf");
    std::fs::write(&p, "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"meshes\": [ }\n}\n").unwrap();
    let e = load_scene(&p).unwrap_err().to_string();
    assert!(e.contains("broken.gltf") && e.contains("not a valid glTF"), "{e}");
    assert!(e.contains("line 3") && e.contains("column 15"), "{e}");
    // Through a scene file, the scene's line is named too.
    let scene = "[camera]\nposition = [0, 0, 5]\n[[object]]\nkind = \"gltf\"\nfile = \"broken.gltf\"\n";
    let e = parse_scene(scene, "s.toml", dir.path()).unwrap_err().to_string();
    assert!(e.contains("line 3") && e.contains("column 15"), "{e}");
}

#[test]
fn binary_gltf_loads_and_renders() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("tri.glb");
    std::fs::write(&p, glb(&triangle_json(None), &triangle_bytes())).unwrap();
    let scene = load_scene(&p).unwrap();
    assert_eq!(scene.meshes.len(), 1);
    assert_eq!(scene.meshes[0].triangles.len(), 1);
    let (lo, hi) = scene.meshes[0].bounds();
    assert_eq!((lo, hi), ([-1.0, -1.0, 0.0], [1.0, 1.0, 0.0]), "positions from the BIN chunk");
    let films: Vec<_> = scene
        .materials
        .iter()
        .filter_map(|m| match m {
            Material::ThinFilm(f) => Some(f),
            _ => None,
        })
        .collect();
    assert_eq!(films.len(), 1);
    assert_eq!(films[0].stack.thicknesses(), vec![350.0]);
    // The same document as .gltf with the buffer in a side file gives the same mesh.
    std::fs::write(dir.path().join("tri.bin"), triangle_bytes()).unwrap();
    let g = dir.path().join("tri.gltf");
    std::fs::write(&g, triangle_json(Some("tri.bin"))).unwrap();
    let twin = load_scene(&g).unwrap();
    assert_eq!(twin.meshes[0].bounds(), scene.meshes[0].bounds());
    // It renders: the default camera frames the triangle, whose centre pixel is not the sky behind it.
    let img = render(&scene, 16, 16, 1, &|_| {});
    let centre = img.data[8 * 16 + 8];
    let corner = img.data[0];
    assert!(centre.iter().zip(&corner).any(|(a, b)| (a - b).abs() > 1e-3), "{centre:?} vs {corner:?}");
    // A truncated GLB (BIN chunk cut short) is refused cleanly.
    let bytes = std::fs::read(&p).unwrap();
    let cut = dir.path().join("cut.glb");
    std::fs::write(&cut, &bytes[..bytes.len() - 20]).unwrap();
    let e = load_scene(&cut).unwrap_err().to_string();
    assert!(e.contains("cut.glb"), "{e}");
}

#[test]
fn hdr_environment_map() {
    let dir = tempfile::tempdir().unwrap();
    // Upper half 2.0, lower half 0.5 (both exact in RGBE), with a red column at the centre (−z).
    let (w, h) = (32u32, 16u32);
    let img = image::Rgb32FImage::from_fn(w, h, |x, y| {
        let v = if y < h / 2 { 2.0 } else { 0.5 };
        if x == w / 2 {
            image::Rgb([v, 0.0, 0.0])
        } else {
            image::Rgb([v, v, v])
        }
    });
    image::DynamicImage::ImageRgb32F(img).save(dir.path().join("sky.hdr")).unwrap();
    let text = "[camera]\nposition = [0, 0, 5]\n[environment]\nkind = \"map\"\nfile = \"sky.hdr\"\nintensity = 1\n";
    let scene = parse_scene(text, "env.toml", Path::new(dir.path())).unwrap();
    let up = scene.environment.radiance([0.0, 1.0, 0.0]);
    let down = scene.environment.radiance([0.0, -1.0, 0.0]);
    assert!(up.iter().all(|c| (c - 2.0).abs() < 1e-6), "{up:?}");
    assert!(down.iter().all(|c| (c - 0.5).abs() < 1e-6), "{down:?}");
    // Looking towards −z just above the horizon: the centre column's red (u = 0.5 is texel 16's left edge,
    // so aim at its centre, u = 16.5/32, i.e. φ = 2π·(0.5/32) to the +x side).
    let phi = std::f64::consts::TAU * 0.5 / 32.0;
    let toward = [phi.sin() * 0.99, 0.1411, -phi.cos() * 0.99];
    let red = scene.environment.radiance(toward);
    assert!(red[0] > 1.9 && red[1] < 0.1 && red[2] < 0.1, "{red:?}");
    let mean = scene.environment.mean();
    assert!((mean[0] - 1.25).abs() < 0.01, "{mean:?}");
}
