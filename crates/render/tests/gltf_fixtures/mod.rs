//! glTF files written by tests (shared with `crates/gpu/tests/scenes_gpu_vs_cpu.rs`, which includes this file
//! by path).

#![allow(dead_code)]

/// A quad facing +z (two triangles, corners (±1, ±1, 0), UVs 0–1) whose material has a metallic-roughness
/// texture `mr` (`width × 1` texels of `[R, G, B]`, 8-bit) over `roughnessFactor` 0.8 and `metallicFactor` 1,
/// base colour [0.9, 0.6, 0.3]; written with its PNG into `dir`.
pub fn write_metallic_roughness_quad(dir: &std::path::Path, mr: &[[u8; 3]]) -> std::path::PathBuf {
    write_quad(dir, mr, None)
}

/// The same quad with a normal texture as well (`width × 1` texels, its `scale`).
pub fn write_normal_mapped_quad(dir: &std::path::Path, normal: &[[u8; 3]], scale: f64) -> std::path::PathBuf {
    write_quad(dir, &[[0, 255, 255]], Some((normal, scale)))
}

fn write_quad(dir: &std::path::Path, mr: &[[u8; 3]], normal: Option<(&[[u8; 3]], f64)>) -> std::path::PathBuf {
    let mut bin: Vec<u8> = Vec::new();
    let f = |v: &[f32], bin: &mut Vec<u8>| v.iter().for_each(|x| bin.extend(x.to_le_bytes()));
    #[rustfmt::skip]
    f(&[-1.0, -1.0, 0.0, 1.0, -1.0, 0.0, 1.0, 1.0, 0.0, -1.0, -1.0, 0.0, 1.0, 1.0, 0.0, -1.0, 1.0, 0.0], &mut bin); // @0
    f(&[0.0, 0.0, 1.0].repeat(6), &mut bin); // normals @72
    f(&[0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0], &mut bin); // TEXCOORD_0 @144
    std::fs::write(dir.join("quad.bin"), &bin).unwrap();
    let save = |texels: &[[u8; 3]], name: &str| {
        let mut img = image::RgbImage::new(texels.len() as u32, 1);
        for (i, p) in texels.iter().enumerate() {
            img.put_pixel(i as u32, 0, image::Rgb(*p));
        }
        img.save(dir.join(name)).unwrap();
    };
    save(mr, "mr.png");
    let normal_json = match normal {
        Some((texels, scale)) => {
            save(texels, "normal.png");
            format!(r#", "normalTexture": {{"index": 1, "scale": {scale}}}"#)
        }
        None => {
            // Listed in "images" either way: a flat normal, unused.
            save(&[[128, 128, 255]], "normal.png");
            String::new()
        }
    };
    let json = r#"{
  "asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "material": 0}]}],
  "buffers": [{"uri": "quad.bin", "byteLength": 192}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72}, {"buffer": 0, "byteOffset": 72, "byteLength": 72},
                  {"buffer": 0, "byteOffset": 144, "byteLength": 48}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 6, "type": "VEC2"}],
  "images": [{"uri": "mr.png"}, {"uri": "normal.png"}], "textures": [{"source": 0}, {"source": 1}],
  "materials": [{
    "name": "textured metal",
    "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.8,
      "metallicRoughnessTexture": {"index": 0}}@NORMAL_TEXTURE@}]
}"#
    .replace("@NORMAL_TEXTURE@", &normal_json);
    let path = dir.join("quad.gltf");
    std::fs::write(&path, json).unwrap();
    path
}
