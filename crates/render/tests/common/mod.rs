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
