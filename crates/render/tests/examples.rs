//! Every scene in `examples/` (`*.toml`, and glTF files rendered on their own) loads and renders at a tiny
//! size: the picture has light in it and is not one flat colour. New examples are picked up by themselves.

use std::path::PathBuf;

use iridis_render::{load_scene, render};

#[test]
fn every_example_renders() {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"));
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| matches!(p.extension().and_then(|e| e.to_str()), Some("toml" | "gltf" | "glb")))
        .collect();
    scenes.sort();
    assert!(scenes.iter().filter(|p| p.extension().is_some_and(|e| e == "toml")).count() >= 9, "{scenes:?}");
    for p in &scenes {
        let scene = load_scene(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        let img = render(&scene, 24, 16, 1, &|_| {});
        assert_eq!(img.data.len(), 24 * 16);
        // Luminance of each pixel at the scene's exposure (what the PNG would show before clipping).
        let lum: Vec<f64> = img
            .data
            .iter()
            .map(|c| scene.output.exposure * (0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64))
            .collect();
        assert!(lum.iter().all(|l| l.is_finite() && *l >= 0.0), "{}: negative or non-finite pixels", p.display());
        let mean = lum.iter().sum::<f64>() / lum.len() as f64;
        let sd = (lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lum.len() as f64).sqrt();
        let lit = lum.iter().filter(|&&l| l > 0.02).count();
        eprintln!("{}: mean luminance {mean:.3}, sd {sd:.3}, {lit} of 384 pixels lit", p.display());
        assert!(lit >= 24, "{}: the picture is (nearly) black ({lit} lit pixels)", p.display());
        assert!(sd > 0.01, "{}: the picture is uniform (sd {sd})", p.display());
    }
}
