//! `iridis render --gpu` against the CPU renderer: every example scene in `examples/` rendered both ways must
//! agree as displayed colours (issue 8: mean CIEDE2000 < 1, 99th percentile < 3).
//!
//! Needs a Vulkan adapter (lavapipe on machines without a GPU); `IRIDIS_SKIP_GPU=1` skips.

mod common;

use std::path::PathBuf;

use common::gpu;
use iridis_color::integrate::white_point;
use iridis_color::lab::delta_e_2000;
use iridis_color::{Illuminant, Lab, Observer, Xyz};
use iridis_gpu::GpuScene;
use iridis_render::material::Material;
use iridis_render::{load_scene, render, Image};

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

/// Per-pixel CIEDE2000 between the displayed images (exposure, clipped to the sRGB cube), sorted.
fn delta_e(a: &Image, b: &Image, exposure: f64) -> Vec<f64> {
    let white = white_point(Illuminant::D65, Observer::Cie1931);
    let shown = |p: [f32; 3]| {
        let rgb = p.map(|c| {
            let c = c as f64 * exposure;
            if c.is_nan() {
                0.0
            } else {
                c.clamp(0.0, 1.0)
            }
        });
        Lab::from_xyz(Xyz::from_linear_srgb(rgb), white)
    };
    let mut d: Vec<f64> = a.data.iter().zip(&b.data).map(|(&p, &q)| delta_e_2000(shown(p), shown(q))).collect();
    d.sort_by(|x, y| x.total_cmp(y));
    d
}

#[test]
fn every_example_scene_matches_the_cpu() {
    let Some(gpu) = gpu() else { return };
    let scenes = examples();
    assert!(scenes.len() >= 8, "examples/ has {} scenes", scenes.len());
    let mut report = Vec::new();
    for path in scenes {
        let scene = load_scene(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let rough = scene.materials.iter().any(|m| matches!(m, Material::ThinFilm(f) if f.rough.is_some()));
        if rough {
            // Rough films (LSRS) are CPU-only: the GPU must say so, not render something else.
            let e = GpuScene::new(&gpu, &scene).unwrap_err().to_string();
            assert!(e.contains("rough substrate") && e.contains("CPU only"), "{name}: {e}");
            eprintln!("{name:<32} refused on the GPU (rough film, CPU only)");
            continue;
        }
        let (w, h) = (96, (96.0 * scene.output.height as f64 / scene.output.width as f64).round() as u32);
        let cpu = render(&scene, w, h, 1, &|_| {});
        let g = GpuScene::new(&gpu, &scene).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let img = g.render(w, h, 1, &|_| {}).unwrap();
        let d = delta_e(&cpu, &img, scene.output.exposure);
        let mean = d.iter().sum::<f64>() / d.len() as f64;
        let p99 = d[((d.len() as f64 * 0.99) as usize).min(d.len() - 1)];
        eprintln!("{name:<32} {w}×{h}: mean ΔE00 {mean:.3}, p99 {p99:.3}, max {:.2}", d[d.len() - 1]);
        // The image must show something (a black GPU image would agree with a black CPU image).
        let lit = cpu.data.iter().filter(|p| p.iter().any(|&c| c > 1e-3)).count();
        assert!(lit > cpu.data.len() / 10, "{name}: the CPU image is nearly black");
        report.push((name, mean, p99));
    }
    assert!(report.len() >= 8, "{} scenes compared", report.len());
    for (name, mean, p99) in &report {
        // Issue 14: measured on lavapipe at 96 px, mean ≤ 0.009 and p99 ≤ 0.007 on every example but the soap
        // bubble (0.061 / 1.68: rays refracted through two thin shells, where f32 and f64 intersections part),
        // with a few silhouette pixels apart (max ≈ 24) where one renderer's ray hits and the other's misses.
        let (mean_max, p99_max) = if name.starts_with("soap_bubble") { (0.2, 3.0) } else { (0.05, 0.05) };
        assert!(*mean < mean_max && *p99 < p99_max, "{name}: mean ΔE00 {mean:.3}, p99 {p99:.3}");
    }
}
