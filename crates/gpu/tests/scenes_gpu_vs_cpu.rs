//! `iridis render --gpu` against the CPU renderer: every example scene in `examples/` rendered both ways must
//! agree as displayed colours (issue 8: mean CIEDE2000 < 1, 99th percentile < 3), at unit scale and shrunk
//! or grown 1000× (issue 21: ray offsets relative to the scene's scale), and so must scenes written here for
//! what the examples leave out: point lights, an environment map, orthographic and hemisphere cameras, every
//! orientation rule, image colour textures.
//!
//! Needs a Vulkan adapter (lavapipe on machines without a GPU); `IRIDIS_SKIP_GPU=1` skips.
//!
//! The scale test renders, by default, the fewest examples that together use every kind of object, material,
//! light, camera, environment and texture (and every value of `scales`, `orientation`, `transmission`) any
//! example uses — 8 of 19 examples today; a scale-dependent ray offset shows in a kind of geometry or material,
//! not in a second lighting of the same scene. `IRIDIS_EXHAUSTIVE=1` renders every example at both scales.

use crate::common;

use std::path::PathBuf;

use common::gpu;
use iridis_gpu::GpuScene;
use iridis_render::{load_scene, parse_scene, render, Scene};

fn examples() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    v.sort();
    v
}

/// The example scene at `path`, loaded once for this binary's tests (a snake scene takes ~1 s to build; the
/// scale test renders its examples at two scales, and the unit-scale test renders them all).
fn example_scene(path: &std::path::Path) -> Scene {
    static LOADED: std::sync::OnceLock<std::sync::Mutex<std::collections::HashMap<PathBuf, Scene>>> =
        std::sync::OnceLock::new();
    let mut loaded = LOADED.get_or_init(Default::default).lock().unwrap_or_else(|e| e.into_inner());
    let scene = loaded.entry(path.to_path_buf()).or_insert_with(|| {
        let scene = load_scene(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        // A rough film's tables are made on first use and travel with the scene's clones (Scene::scale leaves
        // materials alone): made here once, not once for every clone (each scale, each test), seconds each.
        for m in &scene.materials {
            if let iridis_render::material::Material::ThinFilm(f) = m {
                let _ = (f.rough_table(), f.rough_env_table());
            }
        }
        scene
    });
    scene.clone()
}

/// `IRIDIS_EXHAUSTIVE=1`: the full versions of the tests (README, "Tests").
fn exhaustive() -> bool {
    std::env::var("IRIDIS_EXHAUSTIVE").as_deref() == Ok("1")
}

/// What a scene file uses: (section, its `kind`, key, value) for every key of every section, the value kept
/// for the keys that choose a code path (`kind`, `scales`, `orientation`, `transmission`).
fn features(path: &std::path::Path) -> std::collections::BTreeSet<[String; 4]> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut sections: Vec<(String, Vec<(String, String)>)> = Vec::new();
    for line in text.lines() {
        let line = line.split('#').next().unwrap().trim();
        if line.starts_with('[') {
            let name = line.trim_matches(|c: char| c == '[' || c == ']');
            sections.push((name.split('.').next().unwrap().to_string(), Vec::new()));
        } else if let (Some((k, v)), Some(sec)) = (line.split_once('='), sections.last_mut()) {
            sec.1.push((k.trim().to_string(), v.trim().trim_matches('"').to_string()));
        }
    }
    let mut f = std::collections::BTreeSet::new();
    for (section, keys) in sections {
        let kind = keys.iter().find(|(k, _)| k == "kind").map_or(String::new(), |(_, v)| v.clone());
        for (k, v) in keys {
            let v =
                if ["kind", "scales", "orientation", "transmission"].contains(&k.as_str()) { v } else { String::new() };
            f.insert([section.clone(), kind.clone(), k, v]);
        }
    }
    f
}

/// The examples the scale test renders: all with `IRIDIS_EXHAUSTIVE=1`, else the fewest (greedily, in file
/// order on ties) that together have every feature any example has.
fn scale_test_examples() -> Vec<PathBuf> {
    let all = examples();
    if exhaustive() {
        return all;
    }
    let feats: Vec<_> = all.iter().map(|p| features(p)).collect();
    let wanted: std::collections::BTreeSet<_> = feats.iter().flatten().cloned().collect();
    let (mut covered, mut picked) = (std::collections::BTreeSet::new(), Vec::new());
    while covered != wanted {
        let gain = |k: usize| feats[k].difference(&covered).count();
        let best = (0..all.len()).rev().max_by_key(|&k| gain(k)).unwrap();
        covered.extend(feats[best].iter().cloned());
        picked.push(best);
    }
    picked.sort();
    picked.into_iter().map(|k| all[k].clone()).collect()
}

/// GPU against CPU for one scene at `w` pixels wide: (mean ΔE00, 99th percentile, share of pixels where a
/// displayed 8-bit channel differs by more than 8 levels), and whether the CPU image is lit.
fn compare(gpu: &iridis_gpu::Gpu, scene: &Scene, name: &str, w: u32) -> (f64, f64, f64, bool) {
    let h = ((w as f64 * scene.output.height as f64 / scene.output.width as f64).round() as u32).max(1);
    let cpu = render(scene, w, h, 1, &|_| {});
    let g = GpuScene::new(gpu, scene).unwrap_or_else(|e| panic!("{name}: {e}"));
    let img = g.render(w, h, 1, &|_| {}).unwrap();
    if let Some(o) = g.stack_overflow() {
        panic!("{name}: {o}");
    }
    let d = common::image_delta_e(&cpu, &img, scene.output.exposure);
    let (a, b) = (
        cpu.to_rgb8(scene.output.exposure, scene.output.encoding),
        img.to_rgb8(scene.output.exposure, scene.output.encoding),
    );
    let off = a.chunks(3).zip(b.chunks(3)).filter(|(p, q)| p.iter().zip(*q).any(|(x, y)| x.abs_diff(*y) > 8)).count();
    let lit = cpu.data.iter().filter(|p| p.iter().any(|&c| c > 1e-3)).count() > cpu.data.len() / 10;
    (d.mean, d.p99, off as f64 / d.count as f64, lit)
}

#[test]
fn every_example_scene_matches_the_cpu_at_1e_3_and_1e3_scale() {
    let _serial = common::one_scene_at_a_time();
    let Some(gpu) = gpu() else { return };
    let mut report = Vec::new();
    for path in scale_test_examples() {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        for scale in [1e-3, 1e3] {
            let mut scene = example_scene(&path);
            scene.scale(scale);
            let (mean, p99, off, lit) = compare(gpu, &scene, &name, 64);
            eprintln!("{name:<32} ×{scale:<6} mean ΔE00 {mean:.3}, p99 {p99:.3}, > 8 levels {:.3} %", off * 100.0);
            assert!(lit, "{name} ×{scale}: the CPU image is nearly black");
            report.push((format!("{name} ×{scale}"), mean, p99, off));
        }
    }
    assert!(report.len() >= 16, "{} renders compared", report.len());
    for (name, mean, p99, off) in &report {
        assert!(*mean < 1.0 && *p99 < 3.0 && *off < 0.01, "{name}: mean ΔE00 {mean:.3}, p99 {p99:.3}, {off:.4}");
    }
}

/// Writes the test inputs: an EXR sky map with a warm sun, a PNG colour texture and a PNG vector field.
fn write_inputs(dir: &std::path::Path) {
    let env = image::Rgb32FImage::from_fn(64, 32, |x, y| {
        let v = y as f32 / 31.0;
        let sun = if (x as i32 - 40).abs() <= 2 && (y as i32 - 9).abs() <= 2 { 30.0 } else { 0.0 };
        image::Rgb([0.3 + 0.6 * (1.0 - v) + sun, 0.35 + 0.5 * (1.0 - v) + sun * 0.8, 0.5 * (1.0 - v) + 0.2 + sun * 0.5])
    });
    env.save(dir.join("env.exr")).unwrap();
    let color = image::RgbImage::from_fn(8, 8, |x, y| image::Rgb([(x * 30 + 20) as u8, (y * 30 + 20) as u8, 200]));
    color.save(dir.join("color.png")).unwrap();
    // A field turning by 90° across u: (cos, sin) of u·π/2 mapped to 2·rg − 1.
    let vec = image::RgbImage::from_fn(16, 4, |x, _| {
        let a = x as f32 / 15.0 * std::f32::consts::FRAC_PI_2;
        image::Rgb([((a.cos() + 1.0) * 127.5) as u8, ((a.sin() + 1.0) * 127.5) as u8, 255])
    });
    vec.save(dir.join("vector.png")).unwrap();
}

/// Scenes for what the examples leave out; each names the features it covers.
const COVERAGE: &[(&str, &str)] = &[
    (
        "orthographic, point lights, environment map, image colour texture, direction orientation",
        r#"
[output]
size = [96, 64]
[camera]
kind = "orthographic"
position = [0, 2, 6]
look_at = [0, 0.6, 0]
height = 3.2
[[light]]
kind = "point"
position = [-1.5, 2.5, 2]
intensity = 4
[[light]]
kind = "point"
position = [2, 1, 1.5]
intensity = 2
color = [1.0, 0.7, 0.4]
[environment]
kind = "map"
file = "env.exr"
rotation = "30deg"
[textures.photo]
kind = "color"
file = "color.png"
[materials.painted]
kind = "microfacet"
texture = "photo"
roughness = 0.35
[materials.metal]
kind = "microfacet"
color = [0.95, 0.64, 0.54]
metallic = 1.0
roughness = 0.25
[materials.grating]
kind = "diffraction"
table = "builtin:blazed"
uv_resolution = 41
orientation = "direction"
direction = [1, 0, 0.3]
scale_ru = 1500
w_diffuse = 0.2
texture = "photo"
ambient = 0.3
[materials.floor]
kind = "lambert"
texture = "photo"
[[object]]
kind = "sphere"
center = [-1.1, 0.7, 0]
radius = 0.7
material = "painted"
[[object]]
kind = "sphere"
center = [0.4, 0.6, -0.3]
radius = 0.6
material = "metal"
[[object]]
kind = "plane"
center = [1.4, 0.7, 0.5]
normal = [-0.3, 0.2, 1]
tangent = [1, 0, 0.3]
size = [1.0, 1.0]
material = "grating"
[[object]]
kind = "plane"
normal = [0, 1, 0]
tangent = [1, 0, 0]
size = [8, 8]
material = "floor"
"#,
    ),
    (
        "hemisphere camera, tangent orientation",
        r#"
[camera]
kind = "hemisphere"
target = [0, 0, 0]
normal = [0, 0, 1]
[[light]]
kind = "directional"
direction = [0.3, 0.2, 1]
[materials.grating]
kind = "diffraction"
table = "builtin:elaphe"
uv_resolution = 41
orientation = "tangent"
angle = "20deg"
scale_ru = 3000
[[object]]
kind = "plane"
normal = [0, 0, 1]
tangent = [1, 0, 0]
material = "grating"
"#,
    ),
    (
        "perspective, vector-texture orientation, point light, sky",
        r#"
[output]
size = [96, 64]
[camera]
kind = "perspective"
position = [0, 0.5, 3.2]
look_at = [0, 0, 0]
[[light]]
kind = "point"
position = [1, 2, 2.5]
intensity = 6
[environment]
kind = "sky"
[textures.field]
kind = "vector"
file = "vector.png"
[materials.grating]
kind = "diffraction"
table = "builtin:elaphe"
uv_resolution = 41
orientation = "texture"
orientation_texture = "field"
scale_ru = 3000
w_diffuse = 0.1
ambient = 0.2
[[object]]
kind = "sphere"
center = [0, 0, 0]
radius = 1.0
material = "grating"
"#,
    ),
];

#[test]
fn coverage_scenes_match_the_cpu_at_every_scale() {
    let _serial = common::one_scene_at_a_time();
    let Some(gpu) = gpu() else { return };
    let dir = tempfile::tempdir().unwrap();
    write_inputs(dir.path());
    let mut report = Vec::new();
    for (what, text) in COVERAGE {
        for scale in [1.0, 1e-3, 1e3] {
            let mut scene = parse_scene(text, what, dir.path()).unwrap_or_else(|e| panic!("{what}: {e}"));
            scene.scale(scale);
            let (mean, p99, off, lit) = compare(gpu, &scene, what, 72);
            eprintln!("{what:<88} ×{scale:<6} mean ΔE00 {mean:.3}, p99 {p99:.3}, > 8 levels {:.3} %", off * 100.0);
            assert!(lit, "{what} ×{scale}: the CPU image is nearly black");
            report.push((format!("{what} ×{scale}"), mean, p99, off));
        }
    }
    for (name, mean, p99, off) in &report {
        assert!(*mean < 1.0 && *p99 < 3.0 && *off < 0.01, "{name}: mean ΔE00 {mean:.3}, p99 {p99:.3}, {off:.4}");
    }
}

#[test]
fn every_example_scene_matches_the_cpu() {
    let _serial = common::one_scene_at_a_time();
    let Some(gpu) = gpu() else { return };
    let scenes = examples();
    assert!(scenes.len() >= 8, "examples/ has {} scenes", scenes.len());
    let mut report = Vec::new();
    for path in scenes {
        let scene = example_scene(&path);
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let (w, h) = (96, (96.0 * scene.output.height as f64 / scene.output.width as f64).round() as u32);
        let cpu = render(&scene, w, h, 1, &|_| {});
        let g = GpuScene::new(gpu, &scene).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let img = g.render(w, h, 1, &|_| {}).unwrap();
        let d = common::image_delta_e(&cpu, &img, scene.output.exposure);
        let (mean, p99) = (d.mean, d.p99);
        eprintln!("{name:<32} {w}×{h}: mean ΔE00 {mean:.3}, p99 {p99:.3}, max {:.2}", d.max);
        // The image must show something (a black GPU image would agree with a black CPU image).
        let lit = cpu.data.iter().filter(|p| p.iter().any(|&c| c > 1e-3)).count();
        assert!(lit > cpu.data.len() / 10, "{name}: the CPU image is nearly black");
        report.push((name, mean, p99));
    }
    assert!(report.len() >= 9, "{} scenes compared", report.len());
    for (name, mean, p99) in &report {
        // Issue 14: bounds at the measured level (lavapipe, 96 px, 2026-11-23): mean ≤ 0.009 and p99 ≤ 0.007 on
        // the snakes and the gold sphere (a few silhouette pixels apart, max ≈ 24, where one renderer's ray hits
        // and the other's misses); films over a base since the GGX film lobe (issue 21): gltf_iridescence
        // 0.036 / 0.117, oil_spill 0.042 / 1.72 (at 1× only: 0.000 / 0.001 at 10⁻³ and 10³ — not yet
        // explained); the soap bubble 0.050 / 0.71 (rays refracted through two thin shells). Issue 17 (films
        // from colour tables on the GPU; the CPU evaluates them directly): gltf_iridescence 0.001 / 0.009,
        // soap_bubble 0.051 / 0.71, oil_spill 0.044 / 1.72 as before; rough_film (the LSRS tables against the
        // CPU's direct model at 81 wavelengths per hit and light) 0.059 / 0.38.
        let (mean_max, p99_max) = match name.as_str() {
            "soap_bubble.toml" | "oil_spill.toml" => (0.2, 3.0),
            "gltf_iridescence.toml" => (0.1, 0.3),
            "rough_film.toml" => (0.1, 0.6),
            _ => (0.05, 0.05),
        };
        assert!(*mean < mean_max && *p99 < p99_max, "{name}: mean ΔE00 {mean:.3}, p99 {p99:.3}");
    }
}

#[test]
fn a_full_ray_stack_is_reported_with_its_depth() {
    // 30 parallel soap films in front of the camera: every film splits a ray into a reflected and a
    // transmitted one, so the stack of pending rays grows by one per film and overflows its 24 places.
    let _serial = common::one_scene_at_a_time();
    let Some(gpu) = gpu() else { return };
    let mut text = String::from(
        "[output]\nmax_depth = 40\n[camera]\nkind = \"orthographic\"\nposition = [0, 0, 5]\nheight = 1\n\
         [environment]\nkind = \"sky\"\n[materials.film]\nkind = \"thinfilm\"\nstack = \"air | water 300nm | air\"\n\
         transmission = true\n",
    );
    for k in 0..30 {
        text.push_str(&format!(
            "[[object]]\nkind = \"plane\"\ncenter = [0, 0, {}]\nnormal = [0.05, 0, 1]\nmaterial = \"film\"\n",
            -0.1 * k as f64
        ));
    }
    let scene = parse_scene(&text, "films.toml", std::path::Path::new(".")).unwrap();
    let g = GpuScene::new(gpu, &scene).unwrap();
    g.render(4, 4, 1, &|_| {}).unwrap();
    let o = g.stack_overflow().expect("the stack overflows");
    eprintln!("{o}");
    assert!(o.rays >= 16 && o.depth >= 20 && o.depth <= 40, "{o:?}");
    assert!(o.to_string().contains("overflowed") && o.to_string().contains(&format!("bounce {}", o.depth)));
    // Fewer films fit: no report.
    let few = parse_scene(&text.replace("max_depth = 40", "max_depth = 10"), "films.toml", std::path::Path::new("."))
        .unwrap();
    let g = GpuScene::new(gpu, &few).unwrap();
    g.render(4, 4, 1, &|_| {}).unwrap();
    assert_eq!(g.stack_overflow(), None);
}

/// A mesh far larger than a unit: its edges' cross product has a squared length beyond f32's range at 5e9 units,
/// and the GPU drew the box black there (session 25); it matches the CPU at 1e10 now, and a scene beyond
/// `MAX_GPU_COORDINATE` is refused with a sentence rather than drawn black.
#[test]
fn a_mesh_of_1e10_units_matches_the_cpu_and_beyond_f32s_range_is_refused() {
    let _serial = common::one_scene_at_a_time();
    let Some(gpu) = gpu() else { return };
    let text = "[output]\nsize = [48, 32]\n[camera]\nkind = \"perspective\"\nposition = [1, 1.2, 1.6]\n\
                look_at = [0, 0, 0]\nfov = \"38deg\"\n[[light]]\nkind = \"directional\"\ndirection = [0.5, 1, 0.6]\n\
                [materials.grey]\nkind = \"lambert\"\n[[object]]\nkind = \"obj\"\nfile = \"unit_box.obj\"\n\
                material = \"grey\"\ntranslate = [-0.5, -0.5, -0.5]\n";
    let examples = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut scene = parse_scene(text, "box.toml", &examples).unwrap();
    scene.scale(1e10);
    let (mean, p99, off, lit) = compare(gpu, &scene, "box ×1e10", 48);
    eprintln!("box ×1e10: mean ΔE00 {mean:.3}, p99 {p99:.3}, > 8 levels {:.3} %", off * 100.0);
    assert!(lit, "the CPU image is nearly black");
    assert!(mean < 1.0 && p99 < 3.0 && off < 0.01, "mean ΔE00 {mean:.3}, p99 {p99:.3}, {off:.4}");
    scene.scale(100.0);
    // The camera at (1, 1.2, 1.6) × 1e12 is the farthest thing placed.
    assert_eq!(iridis_gpu::scene::largest_coordinate(&scene), 1.6e12);
    let e = GpuScene::new(gpu, &scene).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("1.600e12") && e.contains("1e11") && e.contains("without --gpu"), "{e}");
}

use crate::gltf_fixtures;

/// glTF's metallicRoughnessTexture on the GPU: a quad whose left half is a smooth metal and right half a rough
/// half-metal (two texels), under the glTF default light and sky, as on the CPU. (A uniform rough metal here
/// found the GPU's light highlights a factor cos θ_i too dark: mean ΔE00 1.37 before the fix.)
#[test]
fn a_metallic_roughness_texture_matches_the_cpu() {
    let _serial = common::one_scene_at_a_time();
    let Some(gpu) = gpu() else { return };
    let dir = tempfile::tempdir().unwrap();
    let path = gltf_fixtures::write_metallic_roughness_quad(dir.path(), &[[0, 40, 255], [0, 255, 128]]);
    let scene = load_scene(&path).unwrap();
    let (mean, p99, off, lit) = compare(gpu, &scene, "metallic-roughness quad", 72);
    eprintln!("metallic-roughness quad: mean ΔE00 {mean:.3}, p99 {p99:.3}, > 8 levels {:.3} %", off * 100.0);
    assert!(lit, "the CPU image is nearly black");
    assert!(mean < 1.0 && p99 < 3.0 && off < 0.01, "mean ΔE00 {mean:.3}, p99 {p99:.3}, {off:.4}");
}

/// glTF's normalTexture on the GPU: the quad's two halves tilted 35° left and 20° up by their texels, under
/// the glTF default light and sky, as on the CPU.
#[test]
fn a_normal_texture_matches_the_cpu() {
    let _serial = common::one_scene_at_a_time();
    let Some(gpu) = gpu() else { return };
    let dir = tempfile::tempdir().unwrap();
    let path = gltf_fixtures::write_normal_mapped_quad(dir.path(), &[[55, 128, 232], [128, 171, 248]], 1.0);
    let scene = load_scene(&path).unwrap();
    let (mean, p99, off, lit) = compare(gpu, &scene, "normal-mapped quad", 72);
    eprintln!("normal-mapped quad: mean ΔE00 {mean:.3}, p99 {p99:.3}, > 8 levels {:.3} %", off * 100.0);
    assert!(lit, "the CPU image is nearly black");
    assert!(mean < 1.0 && p99 < 3.0 && off < 0.01, "mean ΔE00 {mean:.3}, p99 {p99:.3}, {off:.4}");
}
