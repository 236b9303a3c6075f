//! The unit tests of src/snake.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::math::*;
use iridis_render::snake::*;
use std::f64::consts::{PI, TAU};

fn params(scales: ScaleKind) -> SnakeParams {
    SnakeParams { scales, scale_rows: 19, ..Default::default() }
}

/// The dorsal plate on the dorsal midline whose centre lies nearest `s = 2/3`, where the spine's sine
/// wave turns neither way (so the plate's own shape alone bends its long axis).
fn midline_plate(body: &Body) -> Plate {
    *plates(body)
        .iter()
        .filter(|p| p.dorsal && p.phi.abs() < 1e-9)
        .min_by(|a, b| {
            let c = |p: &Plate| (body.s_of_sigma(p.sigma_base - 0.5 * PLATE_LENGTH) - 2.0 / 3.0).abs();
            c(a).total_cmp(&c(b))
        })
        .expect("a midline plate")
}

fn angle(a: V3, b: V3) -> f64 {
    dot(normalize(a), normalize(b)).clamp(-1.0, 1.0).acos()
}

#[test]
fn sigma_inverts() {
    let b = Body::new(&params(ScaleKind::Smooth));
    for s in [0.01, 0.2, 0.5, 0.77, 0.95, 0.999] {
        assert!((b.s_of_sigma(b.sigma_of(s)) - s).abs() < 1e-9, "{s}");
    }
}

#[test]
fn plate_gradient_is_the_derivative_of_its_height() {
    for shape in [PlateShape::keeled(1.0), PlateShape::keeled(0.4), PlateShape::smooth(), PlateShape::ventral()] {
        for a in [0.05, 0.2, 0.37, 0.5, 0.8, 0.97] {
            for b in [-0.95, -0.8, -0.3, -0.05, 0.0, 0.12, 0.5, 0.78, 0.9] {
                let e = 1e-6;
                let fa = (shape.height(a + e, b) - shape.height(a - e, b)) / (2.0 * e);
                let fb = (shape.height(a, b + e) - shape.height(a, b - e)) / (2.0 * e);
                let (ga, gb) = shape.gradient(a, b);
                assert!((fa - ga).abs() < 1e-6 && (fb - gb).abs() < 1e-6, "{shape:?} {a} {b}: {fa} {ga} {fb} {gb}");
            }
        }
    }
}

/// The plate's normal is the body's normal tilted by the slopes of the plate's height, in closed form:
/// `n ∝ n_body − (w·∂h/∂a / |∂B/∂a|)·ê_a − (w·∂h/∂b / |∂B/∂b|)·ê_b`, where `B(a, b)` is the body surface
/// under the plate and `ê_a ⟂ ê_b` its directions (orthogonal on the midline `b = 0` and across the
/// widest part `a = 0.55`, where the outline's width does not change). Left out: the height `h` times
/// the body's curvature `1/R` (the displaced surface is `1 + h/R` as wide), so the bound is
/// `1.5·h/R` of the tilt plus 0.05°.
#[test]
fn normals_are_unit_and_tilt_as_the_plate_slopes_say() {
    for kind in [ScaleKind::Keeled, ScaleKind::Smooth] {
        let body = Body::new(&params(kind));
        let plate = midline_plate(&body);
        let mut largest_tilt = 0.0f64;
        let points: Vec<(f64, f64)> = [0.15, 0.3, 0.5, 0.7, 0.85, 0.95]
            .iter()
            .map(|&a| (a, 0.0))
            .chain([-0.9, -0.6, -0.3, -0.1, 0.1, 0.3, 0.6, 0.9].iter().map(|&b| (WIDEST, b)))
            .collect();
        for (a, b) in points {
            let n = plate.normal(&body, a, b);
            assert!((length(n) - 1.0).abs() < 1e-12);
            let under = |a: f64, b: f64| {
                let (s, phi) = plate.body_coords(&body, a, b);
                body.surface(s, phi)
            };
            let e = 1e-5;
            let ba = mul(sub(under(a + e, b), under(a - e, b)), 0.5 / e);
            let bb = mul(sub(under(a, b + e), under(a, b - e)), 0.5 / e);
            let ea = normalize(ba);
            let eb = normalize(sub(bb, mul(ea, dot(bb, ea))));
            let (s, phi) = plate.body_coords(&body, a, b);
            let nb = body.normal(s, phi);
            let (ha, hb) = plate.shape.gradient(a, b);
            let expected =
                normalize(sub(nb, add(mul(ea, plate.w * ha / length(ba)), mul(eb, plate.w * hb / dot(bb, eb)))));
            let tilt = angle(expected, nb);
            largest_tilt = largest_tilt.max(tilt);
            let err = angle(n, expected);
            let h = plate.w * plate.shape.height(a, b);
            let (rw, rh) = body.half_axes(s);
            assert!(
                err < 1.5 * h.abs() / rw.min(rh) * tilt + 0.05f64.to_radians(),
                "{kind:?} ({a}, {b}): normal {:.3}° from the closed form (tilt {:.2}°)",
                err.to_degrees(),
                tilt.to_degrees()
            );
        }
        // The plates do tilt: the tip lifts 6–10° and the dome or keel slopes as much across.
        assert!(largest_tilt.to_degrees() > 6.0, "{kind:?}: largest tilt {:.1}°", largest_tilt.to_degrees());
    }
}

/// On a known scale the nanostructure's axis is the scale's long axis — the chord from the middle of its
/// base to its tip, in the local tangent plane — within the plate's arch along the midline (2.3°: the
/// arch `0.03 w·π` over a plate 2.3 w long) and, across the plate, within that plus the convergence of
/// the field lines towards the tip (`CONVERGE` 0.3 of a half-width 0.7 w over 2.3 w: 5.2°); it is unit,
/// in the tangent plane, points from base to tip, and turns across the plate.
#[test]
fn orientation_follows_the_long_axis_of_a_known_scale() {
    for kind in [ScaleKind::Keeled, ScaleKind::Smooth] {
        let body = Body::new(&params(kind));
        let plate = midline_plate(&body);
        let axis = sub(plate.point(&body, 1.0, 0.0), plate.point(&body, 0.0, 0.0));
        for a in [0.1, 0.3, 0.5, 0.7, 0.9] {
            for b in [-0.9, -0.5, 0.0, 0.5, 0.9] {
                let t = plate.orientation(&body, a, b);
                let n = plate.normal(&body, a, b);
                assert!((length(t) - 1.0).abs() < 1e-12 && dot(t, n).abs() < 1e-12);
                assert!(dot(t, axis) > 0.0, "{kind:?} ({a}, {b}): the axis points from tip to base");
                let local_axis = orthogonalize(axis, n).unwrap();
                let dev = angle(t, local_axis).to_degrees();
                let bound = if b == 0.0 { 2.5 } else { 8.0 };
                assert!(dev < bound, "{kind:?} ({a}, {b}): {dev:.2}° off the long axis (bound {bound}°)");
                // Towards the tip the field leans towards the midline (converges), by up to the closed
                // form's atan(|b|·hw·CONVERGE·0.7 w / ((1 − CONVERGE·a)·2.32 w)) ≈ 4.7° at (0.9, ±0.9).
                if a >= 0.7 && b != 0.0 {
                    let to_mid = orthogonalize(sub(plate.point(&body, a, 0.0), plate.point(&body, a, b)), n).unwrap();
                    let lean = dot(t, to_mid).asin().to_degrees();
                    assert!(lean > 0.3 && lean < 8.0, "{kind:?} ({a}, {b}): leans {lean:.2}° towards the midline");
                }
            }
        }
    }
}

/// Rays shot at the body from outside, over a patch of mid-body all the way around, meet a scale plate
/// first, never the inner tube under the plates: the plates cover the body without gaps.
#[test]
fn the_plates_cover_the_body() {
    for kind in [ScaleKind::Keeled, ScaleKind::Smooth] {
        let p = SnakeParams { section: [0.45, 0.6], scale_grid: [9, 7], ..params(kind) };
        let mesh = scaled_snake_mesh(&p, 0);
        let tube_tris = 2 * tube_rings(0.45, 0.6) * TUBE_SEGMENTS;
        let first_tube = mesh.triangles.len() - tube_tris;
        let meshes = [mesh];
        let bvh = iridis_render::bvh::Bvh::build(&meshes);
        let body = Body::new(&p);
        let mut shot = 0;
        for i in 0..60 {
            let s = 0.5 + 0.05 * i as f64 / 59.0;
            for j in 0..72 {
                let phi = -PI + TAU * (j as f64 + 0.37) / 72.0;
                let n = body.normal(s, phi);
                let o = add(body.surface(s, phi), mul(n, 0.3));
                let (_, _, _, hit) = bvh.intersect(&meshes, o, mul(n, -1.0), 1.0).expect("the ray meets the body");
                assert!((hit.tri as usize) < first_tube, "{kind:?}: a gap between the plates at s {s:.4}, φ {phi:.3}");
                shot += 1;
            }
        }
        assert_eq!(shot, 60 * 72);
    }
}

#[test]
fn keels_only_on_keeled_scales_and_only_on_the_upper_rows() {
    let keeled = plates(&Body::new(&params(ScaleKind::Keeled)));
    let smooth = plates(&Body::new(&params(ScaleKind::Smooth)));
    assert!(smooth.iter().all(|p| p.shape.keel == 0.0));
    assert!(keeled.iter().any(|p| p.shape.keel > 0.0));
    // Keels fade out down the flanks: none below the side midline (|φ| > π/2).
    assert!(keeled.iter().filter(|p| p.phi.abs() > PI / 2.0).all(|p| p.shape.keel == 0.0));
    // Ventral plates: one per scale spacing, on the belly.
    assert!(keeled.iter().filter(|p| !p.dorsal).all(|p| (p.phi - PI).abs() < 1e-12));
}

#[test]
fn the_triangle_count_is_what_the_mesh_has() {
    let p = SnakeParams { section: [0.3, 0.5], scale_grid: [7, 5], ..params(ScaleKind::Keeled) };
    assert_eq!(triangle_count(&p), scaled_snake_mesh(&p, 0).triangles.len());
}

#[test]
fn the_eyes_sit_on_the_head_one_each_side() {
    let p = params(ScaleKind::Smooth);
    let [(l, rl), (r, rr)] = eyes(&p);
    assert!(rl == rr && rl > 0.0);
    // Mirror images across the spine's vertical plane, on the upper half of the head.
    let body = Body::new(&p);
    let (_, side, up) = body.frame(EYE_S);
    let c = body.spine(EYE_S);
    assert!(dot(sub(l, c), side) < 0.0 && dot(sub(r, c), side) > 0.0);
    assert!((dot(sub(l, c), side) + dot(sub(r, c), side)).abs() < 0.05 * rl);
    assert!(dot(sub(l, c), up) > 0.0);
}

#[test]
fn snake_mesh_is_closed_around_and_tangents_follow_the_body() {
    let m = snake_mesh(&SnakeParams { rings: 60, segments: 12, ..Default::default() }, 0);
    assert_eq!(m.positions.len(), 60 * 13);
    let ts = m.corner_tangents.as_ref().expect("UVs give MikkTSpace tangents");
    // u runs along the body, so the MikkTSpace tangent (dP/du) agrees with the spine direction.
    let mut agree = 0;
    for (k, t) in ts.iter().enumerate() {
        let vtx = m.triangles[k / 3][k % 3] as usize;
        if dot([t[0], t[1], t[2]], m.along.as_ref().unwrap()[vtx]) > 0.9 {
            agree += 1;
        }
    }
    assert!(agree as f64 > 0.95 * ts.len() as f64, "{agree} of {}", ts.len());
}
