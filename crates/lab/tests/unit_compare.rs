//! The unit tests of src/compare.rs (CIELAB error maps and their statistics), moved here so that `cargo test`
//! compiles the library once.

use iridis_color::lab::delta_e_2000;
use iridis_color::Xyz;
use iridis_lab::compare::{delta_e_map, displayed_lab, stats};

#[test]
fn identical_images_have_zero_error_and_percentile_is_nearest_rank() {
    let img = vec![Some(Xyz::new(0.2, 0.3, 0.1)), None, Some(Xyz::new(0.0, 0.0, 0.0))];
    let s = stats(&delta_e_map(&img, &img, 100.0));
    assert_eq!((s.mean, s.p95, s.pixels), (0.0, 0.0, 2));
    let values: Vec<Option<f64>> = (1..=20).map(|k| Some(k as f64)).collect();
    let s = stats(&values);
    assert_eq!((s.mean, s.p95, s.max), (10.5, 19.0, 20.0));
}

#[test]
fn saturated_white_has_lightness_100() {
    // A perfect white reflector (D65 white, Y = 1) at 1 RU is display white: L* = 100, a* = b* = 0.
    let lab = displayed_lab(Xyz::from_linear_srgb([1.0, 1.0, 1.0]), 1.0);
    assert!((lab.l - 100.0).abs() < 1e-9 && lab.a.abs() < 1e-9 && lab.b.abs() < 1e-9, "{lab:?}");
    // Far brighter light clips to the same white.
    let lab2 = displayed_lab(Xyz::from_linear_srgb([1.0, 1.0, 1.0]), 1000.0);
    assert!(delta_e_2000(lab, lab2) < 1e-9);
}
