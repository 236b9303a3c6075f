//! KHR_materials_iridescence → thin-film stack over the base (examples/iridescent_spheres.gltf, made by
//! tools/make_iridescence_gltf.py).

use crate::common;

use iridis_render::material::Material;

#[test]
fn iridescence_maps_onto_thin_films() {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/iridescent_spheres.gltf"));
    let scene = iridis_render::load_scene(path).unwrap();
    assert_eq!(scene.meshes.len(), 4);
    let films = common::thin_films(&scene);
    assert_eq!(films.len(), 3, "three iridescent materials");
    // No texture: thickness = maximum (400 nm); texture: d_avg 500 nm ± 300 nm from the G channel.
    assert_eq!(films[0].stack.thicknesses(), vec![400.0]);
    assert!(films[0].svt.is_none() && films[0].factor == 1.0);
    assert_eq!(films[1].stack.thicknesses(), vec![500.0]);
    let svt = films[1].svt.expect("thickness texture → SVT");
    assert_eq!(svt.d_rel_nm, 300.0);
    // The texture's G runs from 0 (top row) to 1 (bottom row) of its 64 rows (sampled at texel centres:
    // the glTF default sampler repeats, so the edges blend with the opposite row).
    let top = scene.textures[svt.texture].sample([0.5, 0.5 / 64.0])[0];
    let bottom = scene.textures[svt.texture].sample([0.5, 63.5 / 64.0])[0];
    assert!(top < 0.02 && bottom > 0.98, "{top} {bottom}");
    assert_eq!(films[2].factor, 0.5);
    assert!(films.iter().all(|f| f.base.is_some()));
    // The sphere meshes have UVs, normals and MikkTSpace tangents; the floor has neither UVs nor tangents.
    assert!(scene.meshes.iter().filter(|m| m.uvs.is_some() && m.corner_tangents.is_some()).count() == 3);
    // The film colour at normal incidence differs between 400 nm and 200 nm films (the model is live).
    let (a, _) = films[0].colors(1.0, 0.0);
    let (b, _) = films[1].colors(1.0, -300.0);
    assert!((a.x - b.x).abs() + (a.y - b.y).abs() + (a.z - b.z).abs() > 0.01);
}

/// A one-triangle glTF written to a temporary directory: a metallic base with a base-colour texture read
/// through TEXCOORD_1 and KHR_texture_transform, KHR_materials_ior, iridescence, and a normal map.
fn write_spec_gltf(dir: &std::path::Path) -> std::path::PathBuf {
    let mut bin: Vec<u8> = Vec::new();
    let f = |v: &[f32], bin: &mut Vec<u8>| v.iter().for_each(|x| bin.extend(x.to_le_bytes()));
    f(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], &mut bin); // positions @0
    f(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0], &mut bin); // normals @36
    f(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0], &mut bin); // TEXCOORD_0 @72
    f(&[0.1, 0.2, 0.3, 0.2, 0.1, 0.4], &mut bin); // TEXCOORD_1 @96
    std::fs::write(dir.join("tri.bin"), &bin).unwrap();
    image::RgbImage::from_pixel(2, 2, image::Rgb([255, 255, 255])).save(dir.join("white.png")).unwrap();
    let json = r#"{
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_ior", "KHR_materials_iridescence", "KHR_texture_transform"],
  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TEXCOORD_1": 3},
                               "material": 0}]}],
  "buffers": [{"uri": "tri.bin", "byteLength": 120}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 72, "byteLength": 24}, {"buffer": 0, "byteOffset": 96, "byteLength": 24}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC2"}],
  "images": [{"uri": "white.png"}], "textures": [{"source": 0}],
  "materials": [{
    "name": "gold film",
    "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.78, 0.34, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.3,
      "baseColorTexture": {"index": 0, "texCoord": 0,
        "extensions": {"KHR_texture_transform": {"texCoord": 1, "offset": [0.5, 0.0], "scale": [2.0, 2.0]}}}},
    "normalTexture": {"index": 0},
    "extensions": {"KHR_materials_ior": {"ior": 1.7},
                   "KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.0,
                                                 "iridescenceThicknessMaximum": 300}}}]
}"#;
    let path = dir.join("spec.gltf");
    std::fs::write(&path, json).unwrap();
    path
}

#[test]
fn the_gltf_texture_set_ior_and_metallic_base_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let scene = iridis_render::load_scene(&write_spec_gltf(dir.path())).unwrap();
    let Material::ThinFilm(film) = &scene.materials[0] else { panic!("{:?}", scene.materials[0]) };
    let base = film.base.expect("the PBR base");
    // KHR_materials_ior: the base's index and the film's dielectric substrate.
    assert_eq!(base.ior, 1.7);
    assert_eq!(film.stack.substrate.index_at(550.0).unwrap().re, 1.7);
    // baseColorFactor multiplies the texture (white texels).
    let c = base.color.at([0.3, 0.3], &scene.textures);
    assert!((c[0] - 1.0).abs() < 1e-6 && (c[1] - 0.78).abs() < 1e-6 && (c[2] - 0.34).abs() < 1e-6, "{c:?}");
    // KHR_texture_transform's texCoord (1) and T·R·S: uv' = 2·uv + (0.5, 0).
    let uv = scene.meshes[0].uvs.as_ref().unwrap();
    assert!((uv[0][0] - 0.7).abs() < 1e-6 && (uv[0][1] - 0.4).abs() < 1e-6, "{uv:?}");
    // A metallic base: the film over the metal, whose index gives back F_0 = baseColorFactor at normal
    // incidence (film IOR 1: no film; Fresnel ((n − 1)/(n + 1))² of n = (1 + √F_0)/(1 − √F_0)).
    // The spectrum F_0(λ) is interpolated between the channels' wavelengths, so the sRGB of its colour comes
    // back within 0.1 (gold's red: 1.09).
    let rgb = film.metal_color(1.0, 0.0).unwrap().to_linear_srgb();
    for (k, want) in [1.0, 0.78, 0.34].into_iter().enumerate() {
        assert!((rgb[k] - want).abs() < 0.1, "channel {k}: {rgb:?} vs [1.0, 0.78, 0.34]");
    }
    // What is not read is named.
    assert!(scene.notes.iter().any(|n| n.contains("normalTexture")), "{:?}", scene.notes);
}

use crate::gltf_fixtures;

/// glTF's metallicRoughnessTexture: G scales the roughness and B the metallic factor, read linearly (an 8-bit
/// 51 is 0.2, not the sRGB-decoded 0.033); a uniform texture renders exactly as the constant material with
/// those products.
#[test]
fn the_metallic_roughness_texture_scales_roughness_and_metallic() {
    let dir = tempfile::tempdir().unwrap();
    let path = gltf_fixtures::write_metallic_roughness_quad(dir.path(), &[[0, 51, 255], [0, 255, 128]]);
    let scene = iridis_render::load_scene(&path).unwrap();
    let Material::Microfacet(m) = &scene.materials[0] else { panic!("{:?}", scene.materials[0]) };
    assert!(m.metallic_roughness.is_some());
    assert!(!scene.notes.iter().any(|n| n.contains("metallicRoughnessTexture")), "{:?}", scene.notes);
    // Texel centres of a 2 × 1 texture: u = 0.25 and 0.75.
    let left = m.at([0.25, 0.5], &scene.textures);
    let right = m.at([0.75, 0.5], &scene.textures);
    assert!((left.roughness - 0.8 * 0.2).abs() < 1e-6 && (left.metallic - 1.0).abs() < 1e-6, "{left:?}");
    assert!((right.roughness - 0.8).abs() < 1e-6 && (right.metallic - 128.0 / 255.0).abs() < 1e-6, "{right:?}");

    let uniform = gltf_fixtures::write_metallic_roughness_quad(dir.path(), &[[0, 51, 128]]);
    let textured = iridis_render::load_scene(&uniform).unwrap();
    let mut constant = iridis_render::load_scene(&uniform).unwrap();
    let Material::Microfacet(c) = &mut constant.materials[0] else { unreachable!() };
    c.roughness = 0.8 * 0.2;
    c.metallic = 128.0 / 255.0;
    c.metallic_roughness = None;
    let (a, b) =
        (iridis_render::render(&textured, 24, 24, 1, &|_| {}), iridis_render::render(&constant, 24, 24, 1, &|_| {}));
    let worst =
        a.data.iter().zip(&b.data).flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs())).fold(0.0f32, f32::max);
    assert!(worst < 1e-6, "textured vs constant: {worst}");
    // And the texture matters: the untextured factors (roughness 0.8, metallic 1) render otherwise.
    let mut factors = iridis_render::load_scene(&uniform).unwrap();
    let Material::Microfacet(c) = &mut factors.materials[0] else { unreachable!() };
    c.metallic_roughness = None;
    let f = iridis_render::render(&factors, 24, 24, 1, &|_| {});
    let diff =
        a.data.iter().zip(&f.data).flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs())).fold(0.0f32, f32::max);
    assert!(diff > 0.05, "the texture changed nothing: {diff}");
}

/// glTF's normalTexture: a uniform texel `(0.5 + 0.5 sin a, 0.5, 0.5 + 0.5 cos a)` tilts the quad's shading
/// normal to `(sin a, 0, cos a)` in the frame (T, B, N) = (+x, +y, +z) of its MikkTSpace tangents (u along +x);
/// `scale` stretches x and y before normalising (glTF 2.0, sec. 3.9.3). Checked on the hit the renderer sees.
#[test]
fn the_normal_texture_tilts_the_shading_normal() {
    let dir = tempfile::tempdir().unwrap();
    let a = 30f64.to_radians();
    let texel = [(127.5 + 127.5 * a.sin()).round() as u8, 128, (127.5 + 127.5 * a.cos()).round() as u8];
    for scale in [1.0, 0.5] {
        let path = gltf_fixtures::write_normal_mapped_quad(dir.path(), &[texel], scale);
        let scene = iridis_render::load_scene(&path).unwrap();
        assert!(!scene.notes.iter().any(|n| n.contains("normalTexture")), "{:?}", scene.notes);
        let Material::Microfacet(m) = &scene.materials[0] else { panic!("{:?}", scene.materials[0]) };
        let hit = scene.intersect([0.2, 0.3, 5.0], [0.0, 0.0, -1.0], f64::INFINITY).expect("the quad");
        let n = m.normal_at(&hit, &scene.textures).n;
        // The 8-bit texel, decoded as the renderer decodes it.
        let c = |v: u8| 2.0 * v as f64 / 255.0 - 1.0;
        let (x, y, z) = (c(texel[0]) * scale, c(texel[1]) * scale, c(texel[2]));
        let len = (x * x + y * y + z * z).sqrt();
        let want = [x / len, y / len, z / len];
        for k in 0..3 {
            assert!((n[k] - want[k]).abs() < 1e-6, "scale {scale}: normal {n:?}, want {want:?}");
        }
        // Against the closed form (sin a, 0, cos a) at scale 1, to the texel's 8-bit quantisation.
        if scale == 1.0 {
            assert!((n[0] - a.sin()).abs() < 0.01 && n[1].abs() < 0.01 && (n[2] - a.cos()).abs() < 0.01, "{n:?}");
        }
    }
    // Green points up the image: row 0 (v = 0) is the quad's top edge (+y), so a texel tilted by b towards
    // green tilts the normal towards +y — the glTF sample viewer's B = N × T for unmirrored UVs.
    let b = 25f64.to_radians();
    let up = [128, (127.5 + 127.5 * b.sin()).round() as u8, (127.5 + 127.5 * b.cos()).round() as u8];
    let scene = iridis_render::load_scene(&gltf_fixtures::write_normal_mapped_quad(dir.path(), &[up], 1.0)).unwrap();
    let Material::Microfacet(m) = &scene.materials[0] else { unreachable!() };
    let hit = scene.intersect([0.2, 0.3, 5.0], [0.0, 0.0, -1.0], f64::INFINITY).expect("the quad");
    let n = m.normal_at(&hit, &scene.textures).n;
    assert!(n[0].abs() < 0.01 && (n[1] - b.sin()).abs() < 0.01 && (n[2] - b.cos()).abs() < 0.01, "{n:?}");
}
