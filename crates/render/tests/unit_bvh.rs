//! The unit tests of src/bvh.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::bvh::*;
use iridis_render::geometry::intersect_triangle;
use iridis_render::snake::{snake_mesh, SnakeParams};

/// The BVH finds exactly the nearest hit that testing every triangle finds.
#[test]
fn bvh_agrees_with_brute_force() {
    let meshes = vec![snake_mesh(&SnakeParams { rings: 80, segments: 16, ..Default::default() }, 0)];
    let bvh = Bvh::build(&meshes);
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut hits = 0;
    for _ in 0..2000 {
        let o = [rnd() * 12.0 - 6.0, 2.0 + rnd(), rnd() * 4.0 - 2.0];
        let target = [rnd() * 10.0 - 5.0, 0.3, rnd() * 2.0 - 1.0];
        let d = iridis_render::math::normalize(iridis_render::math::sub(target, o));
        let fast = bvh.intersect(&meshes, o, d, f64::INFINITY).map(|h| h.0);
        let m = &meshes[0];
        let slow = m
            .triangles
            .iter()
            .filter_map(|t| {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                intersect_triangle(o, d, a, b, c, f64::INFINITY).map(|h| h.0)
            })
            .min_by(|a, b| a.total_cmp(b));
        assert_eq!(fast.is_some(), slow.is_some());
        if let (Some(a), Some(b)) = (fast, slow) {
            assert!((a - b).abs() < 1e-12);
            hits += 1;
        }
    }
    assert!(hits > 200, "the test must exercise hits ({hits})");
}
