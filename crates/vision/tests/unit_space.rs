//! The unit tests of src/space.rs, moved here so that `cargo test` compiles the library once.

use iridis_vision::space::*;

#[test]
fn simplex_vertices_and_edges() {
    // pavo's coldist tests: the largest distances in each space are the edges of the simplex.
    let d = |a: &Coordinates, b: &Coordinates| {
        a.position.iter().zip(&b.position).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt()
    };
    let line = |r: &[f64]| simplex(Space::Line, r).unwrap();
    assert!((d(&line(&[0.0, 1.0]), &line(&[1.0, 0.0])) - 2.0 / 2f64.sqrt()).abs() < 1e-15);
    let tri = |r: &[f64]| simplex(Space::Triangle, r).unwrap();
    assert!((d(&tri(&[0.0, 0.0, 1.0]), &tri(&[0.0, 1.0, 0.0])) - 2.0 / 2f64.sqrt()).abs() < 1e-15);
    let tet = |r: &[f64]| simplex(Space::Tetrahedron, r).unwrap();
    assert!((d(&tet(&[0.0, 0.0, 0.0, 1.0]), &tet(&[1.0, 0.0, 0.0, 0.0])) - 3f64.sqrt() / 2f64.sqrt()).abs() < 1e-15);
    // The achromatic point is the origin, each vertex 0.75 from it, the UV vertex straight up.
    assert!(tet(&[0.25; 4]).chroma < 1e-15 && tet(&[0.25; 4]).hue_deg.is_none());
    for k in 0..4 {
        let mut r = [0.0; 4];
        r[k] = 1.0;
        assert!((tet(&r).chroma - 0.75).abs() < 1e-15);
    }
    assert!((tet(&[1.0, 0.0, 0.0, 0.0]).elevation_deg.unwrap() - 90.0).abs() < 1e-12);
}

#[test]
fn hexagon_background_at_centre_and_unit_corners() {
    // The background itself (q = 1 for every receptor) sits at the centre; a receptor at full excitation
    // with the others dark sits at a corner, 1 from the centre.
    assert!(hexagon(&[1.0, 1.0, 1.0]).unwrap().chroma < 1e-15);
    let g = hexagon(&[0.0, 0.0, 1e12]).unwrap();
    assert!((g.chroma - 1.0).abs() < 1e-9 && (g.hue_deg.unwrap() - 330.0).abs() < 1e-6, "{g:?}");
}
