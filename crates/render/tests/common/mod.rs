//! What the renderer's test files share beyond the furnace scenes (`furnace/mod.rs`).
#![allow(dead_code)] // each test file uses its own subset

use iridis_render::material::{Material, ThinFilm};
use iridis_render::Scene;

/// The scene's thin-film materials, in the order of its material list.
pub fn thin_films(scene: &Scene) -> Vec<&ThinFilm> {
    scene
        .materials
        .iter()
        .filter_map(|m| match m {
            Material::ThinFilm(f) => Some(f.as_ref()),
            _ => None,
        })
        .collect()
}

/// The environment map the tests draw: 32 × 16 texels, radiance 2.0 in the upper half and 0.5 in the lower (both
/// exact in RGBE), so the mean is 1.25; with `red_column` the centre column (u = 0.5, towards −z) is red.
pub fn two_tone_sky(red_column: bool) -> image::Rgb32FImage {
    let (w, h) = (32u32, 16u32);
    image::Rgb32FImage::from_fn(w, h, |x, y| {
        let v = if y < h / 2 { 2.0 } else { 0.5 };
        if red_column && x == w / 2 {
            image::Rgb([v, 0.0, 0.0])
        } else {
            image::Rgb([v, v, v])
        }
    })
}

/// A scene of a camera and the environment map `file` (a path relative to the scene's folder) at intensity 1.
pub fn environment_map_scene(file: &str) -> String {
    format!("[camera]\nposition = [0, 0, 5]\n[environment]\nkind = \"map\"\nfile = \"{file}\"\nintensity = 1\n")
}
