//! KHR_materials_iridescence → thin-film stack over the base (examples/iridescent_spheres.gltf, made by
//! tools/make_iridescence_gltf.py).

use iridis_render::material::Material;

#[test]
fn iridescence_maps_onto_thin_films() {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/iridescent_spheres.gltf"));
    let scene = iridis_render::load_scene(path).unwrap();
    assert_eq!(scene.meshes.len(), 4);
    let films: Vec<_> = scene
        .materials
        .iter()
        .filter_map(|m| match m {
            Material::ThinFilm(f) => Some(f),
            _ => None,
        })
        .collect();
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
