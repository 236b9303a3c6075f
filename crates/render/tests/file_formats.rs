//! Input formats beyond the examples: malformed glTF (the message names line and column), binary glTF
//! (`.glb`, geometry in the BIN chunk) and Radiance `.hdr` environment maps, all written by the test itself.

use std::path::Path;

use crate::common;

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

/// A mesh or an image given where a scene goes: the message says what a scene file is, and for an OBJ how it
/// enters one (it was the TOML parser's "expected `.`, `=`" at the first vertex).
#[test]
fn a_file_that_is_not_a_scene_is_named_for_what_it_is() {
    let obj = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/unit_box.obj");
    let e = load_scene(&obj).unwrap_err().to_string();
    assert!(e.contains("an OBJ file is a mesh, not a scene") && e.contains("kind = \"obj\""), "{e}");
    assert!(e.contains("file = \"unit_box.obj\""), "{e}");
    let dir = tempfile::tempdir().unwrap();
    let txt = dir.path().join("notes.txt");
    std::fs::write(&txt, "v 1 2 3\n").unwrap();
    let e = load_scene(&txt).unwrap_err().to_string();
    assert!(e.contains("notes.txt:1") && e.contains("a scene is a TOML file") && e.contains("not .txt"), "{e}");
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
    let films = common::thin_films(&scene);
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
    let img = common::two_tone_sky(true);
    image::DynamicImage::ImageRgb32F(img).save(dir.path().join("sky.hdr")).unwrap();
    let scene = parse_scene(&common::environment_map_scene("sky.hdr"), "env.toml", Path::new(dir.path())).unwrap();
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

/// A diffraction material's `table` takes any SURFACE, as every command does (issue 32: `table =
/// "../snake.gwy"` failed with "not an npz (zip) file … Could not find EOCD"): the height field is read,
/// plane-levelled as the model commands level files, taken as one unit cell under the light's coherence, and
/// made into a table, with notes saying so. A `.npz` holding heights (numpy's savez), not a table, too.
#[test]
fn a_materials_table_may_be_any_surface() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("scenes");
    std::fs::create_dir(&sub).unwrap();
    let hf =
        iridis_surface::load_surface("builtin:sine?size=1600nm&pixel=50nm&period=400nm", &Default::default()).unwrap();
    for ext in ["gwy", "npz"] {
        let fmt = iridis_surface::Format::from_extension(Path::new(&format!("x.{ext}"))).unwrap();
        let (bytes, side) = iridis_surface::formats::write_bytes(&hf, fmt).unwrap();
        std::fs::write(dir.path().join(format!("sine.{ext}")), bytes).unwrap();
        if let Some(s) = side {
            std::fs::write(dir.path().join(format!("sine.{ext}.json")), s).unwrap();
        }
        let text = format!(
            "[camera]\nposition = [0, 0, 3]\n[[light]]\nkind = \"directional\"\ndirection = [0, 0, 1]\n\
             [materials.skin]\nkind = \"diffraction\"\ntable = \"../sine.{ext}\"\nuv_resolution = 31\n\
             [[object]]\nkind = \"sphere\"\nradius = 1\nmaterial = \"skin\"\n"
        );
        let scene = parse_scene(&text, "s.toml", &sub).unwrap_or_else(|e| panic!("{ext}: {e}"));
        let Material::Diffraction(d) = &scene.materials[0] else { panic!("not diffraction") };
        let meta = &d.evaluator.as_lookup().unwrap().table.meta;
        assert_eq!((meta.rows, meta.cols, meta.uv_resolution), (32, 32, 31), "{ext}");
        // The light's 65 µm, as `iridis precompute` takes it: the 1.6 µm patch is one unit cell of a periodic
        // surface, and the notes say so.
        assert!((meta.coherence_nm - 65_000.0).abs() < 1e-9, "{ext}: {}", meta.coherence_nm);
        let notes = scene.notes.join("\n");
        assert!(notes.contains("levelling: plane") && notes.contains("taken as one unit cell"), "{ext}: {notes}");
        let img = render(&scene, 8, 8, 1, &|_| {});
        assert!(img.xyz(4, 4).y.is_finite());
    }
}

/// The triangle document with a camera node (perspective, 40°, at z = 3 looking down −z, named "Closeup"), a
/// second camera ("Side", at x = 3 looking along −x), and a red KHR_lights_punctual point light of 5 cd at
/// (0, 0, 2); `thickness` the iridescence range [min, max] (nm).
fn lit_triangle_json(thickness: [f64; 2]) -> String {
    triangle_json(None)
        .replace(
            r#""extensionsUsed": ["KHR_materials_iridescence"],"#,
            r#""extensionsUsed": ["KHR_materials_iridescence", "KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0, 0], "intensity": 5}]}},
  "cameras": [{"type": "perspective", "name": "cam", "perspective": {"yfov": 0.6981317, "znear": 0.01, "aspectRatio": 2.0}},
              {"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.01}}],"#,
        )
        .replace(
            r#""scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],"#,
            r#""scenes": [{"nodes": [0, 1, 2, 3]}],
  "nodes": [{"mesh": 0}, {"name": "Closeup", "camera": 0, "translation": [0, 0, 3]},
            {"name": "Side", "camera": 1, "translation": [3, 0, 0], "rotation": [0, 0.7071068, 0, 0.7071068]},
            {"name": "Lamp", "translation": [0, 0, 2], "extensions": {"KHR_lights_punctual": {"light": 0}}}],"#,
        )
        .replace(
            r#""iridescenceThicknessMaximum": 350"#,
            &format!(r#""iridescenceThicknessMinimum": {}, "iridescenceThicknessMaximum": {}"#, thickness[0], thickness[1]),
        )
}

/// A glTF file's own camera and red KHR_lights_punctual light are what it renders with (issue 32: the default
/// camera and a D65 light were used, and the notes did not say the file's were dropped); `--camera NAME`
/// picks another of its cameras and `--ignore-gltf-lights` the default light, each saying so.
#[test]
fn gltf_cameras_and_punctual_lights_are_honoured() {
    use iridis_render::camera::Camera;
    use iridis_render::gltf_io::GltfOptions;
    use iridis_render::light::Light;
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("lit.gltf");
    std::fs::write(dir.path().join("tri.bin"), triangle_bytes()).unwrap();
    std::fs::write(
        &p,
        lit_triangle_json([100.0, 350.0]).replace(
            "\"buffers\": [{\"byteLength\": 36}]",
            "\"buffers\": [{\"byteLength\": 36, \"uri\": \"tri.bin\"}]",
        ),
    )
    .unwrap();
    let scene = load_scene(&p).unwrap();
    let Camera::Perspective { position, forward, tan_half, .. } = scene.camera else { panic!("{:?}", scene.camera) };
    assert!(position == [0.0, 0.0, 3.0] && forward == [0.0, 0.0, -1.0], "{position:?} {forward:?}");
    assert!((tan_half - (0.6981317f64 / 2.0).tan()).abs() < 1e-6);
    assert_eq!((scene.output.width, scene.output.height), (1024, 512), "the camera's aspect ratio 2");
    assert_eq!(scene.lights.len(), 1);
    let Light::Point { position, rgb } = &scene.lights[0] else { panic!("{:?}", scene.lights[0]) };
    assert_eq!((*position, *rgb), ([0.0, 0.0, 2.0], [5.0, 0.0, 0.0]));
    let notes = scene.notes.join("\n");
    assert!(
        notes.contains("glTF camera 'Closeup' (camera 'cam') from the file") && notes.contains("--camera NAME"),
        "{notes}"
    );
    assert!(notes.contains("1 KHR_lights_punctual light(s)") && notes.contains("--ignore-gltf-lights"), "{notes}");
    // The red light makes the lit triangle red: the centre pixel has no green or blue but the sky's.
    let img = render(&scene, 32, 16, 1, &|_| {});
    let c = img.data[8 * 32 + 16];
    assert!(c[0] > 2.0 * c[1].max(c[2]), "{c:?}");
    // Another camera by name: "Side" at x = 3, turned +90° about y, looks along −x.
    let side =
        iridis_render::load_scene_with(&p, &GltfOptions { camera: Some("Side".into()), ..Default::default() }).unwrap();
    let Camera::Perspective { position, forward, .. } = side.camera else { panic!() };
    assert!(position == [3.0, 0.0, 0.0] && (forward[0] + 1.0).abs() < 1e-6, "{position:?} {forward:?}");
    let e = iridis_render::load_scene_with(&p, &GltfOptions { camera: Some("Top".into()), ..Default::default() })
        .unwrap_err()
        .to_string();
    assert!(e.contains("--camera Top") && e.contains("'Closeup' (camera 'cam'), 'Side'"), "{e}");
    let plain =
        iridis_render::load_scene_with(&p, &GltfOptions { camera: Some("default".into()), ignore_lights: true })
            .unwrap();
    assert!(matches!(plain.lights[0], Light::Directional { rgb: [1.0, 1.0, 1.0], .. }));
    let notes = plain.notes.join("\n");
    assert!(notes.contains("ignored (--ignore-gltf-lights)") && notes.contains("default camera"), "{notes}");
}

/// KHR_materials_iridescence gives thicknesses in nm; 0.2–0.6 (micrometres by mistake) renders as no film, so
/// the scene warns and says what the numbers would be in µm (issue 32: silently no film).
#[test]
fn implausible_iridescence_thicknesses_are_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("thin.glb");
    std::fs::write(&p, glb(&lit_triangle_json([0.2, 0.6]), &triangle_bytes())).unwrap();
    let w = load_scene(&p).unwrap().warnings.join("\n");
    assert!(w.contains("iridescence thickness 0.6 nm is below 10 nm") && w.contains("600 nm"), "{w}");
    std::fs::write(&p, glb(&lit_triangle_json([100.0, 350.0]), &triangle_bytes())).unwrap();
    assert!(load_scene(&p).unwrap().warnings.is_empty());
}

/// `render --export-mesh x.glb` keeps the scene's materials (issue 32: re-rendered, the snake was white),
/// camera and lights: the GLB renders like the scene, and other tools see the materials as glTF PBR.
#[test]
fn an_exported_glb_renders_like_its_scene() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/unit_box.obj"), dir.path().join("box.obj"))
        .unwrap();
    let text = r#"
[output]
exposure = 1.5
[camera]
position = [1.6, 1.2, 2.4]
look_at = [0, 0, 0]
fov = "40deg"
[[light]]
kind = "directional"
direction = [0.4, 1, 0.6]
color = [1, 0.8, 0.6]
[environment]
kind = "sky"
zenith = [0.1, 0.2, 0.5]
[materials.red]
kind = "microfacet"
color = [0.8, 0.1, 0.05]
roughness = 0.4
[materials.film]
kind = "thinfilm"
stack = "air | water 320nm | n=1.5"
[[object]]
kind = "obj"
file = "box.obj"
material = "red"
[[object]]
kind = "obj"
file = "box.obj"
material = "film"
translate = [0, 1.1, 0]
"#;
    let scene = parse_scene(text, "box.toml", dir.path()).unwrap();
    let (bytes, _) = iridis_render::gltf_export::scene_glb(&scene).unwrap();
    let p = dir.path().join("box.glb");
    std::fs::write(&p, &bytes).unwrap();
    let back = load_scene(&p).unwrap();
    assert_eq!(back.output.exposure, 1.5);
    let (a, b) = (render(&scene, 40, 30, 1, &|_| {}), render(&back, 40, 30, 1, &|_| {}));
    let worst = a
        .data
        .iter()
        .zip(&b.data)
        .flat_map(|(p, q)| (0..3).map(move |k| f64::from((p[k] - q[k]).abs())))
        .fold(0.0f64, f64::max);
    assert!(worst < 1e-5, "largest difference {worst}");
    // What another viewer reads: PBR colours and the film as KHR_materials_iridescence.
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let doc: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let named = |n: &str| doc["materials"].as_array().unwrap().iter().find(|m| m["name"] == n).unwrap().clone();
    assert_eq!(named("red")["pbrMetallicRoughness"]["baseColorFactor"], serde_json::json!([0.8, 0.1, 0.05, 1.0]));
    let film = &named("film")["extensions"]["KHR_materials_iridescence"];
    assert_eq!(
        (film["iridescenceThicknessMaximum"].as_f64(), film["iridescenceIor"].as_f64()),
        (Some(320.0), Some(1.33))
    );
}
