//! The unit tests of src/compare.rs (CIELAB error maps and their statistics), moved here so that `cargo test`
//! compiles the library once.

use iridis_color::Xyz;
use iridis_lab::compare::{clipped_white, clipping_warning, delta_e_map, stats};

#[test]
fn identical_images_have_zero_error_and_percentile_is_nearest_rank() {
    let img = vec![Some(Xyz::new(0.2, 0.3, 0.1)), None, Some(Xyz::new(0.0, 0.0, 0.0))];
    let s = stats(&delta_e_map(&img, &img, 100.0));
    assert_eq!((s.mean, s.p95, s.count), (0.0, 0.0, 2));
    let values: Vec<Option<f64>> = (1..=20).map(|k| Some(k as f64)).collect();
    let s = stats(&values);
    assert_eq!((s.mean, s.p95, s.max), (10.5, 19.0, 20.0));
}

/// The share of a map a display clips to white: a pixel counts where every linear sRGB channel reaches 1, so
/// display white (1, 1, 1) counts from exactly 1 RU and a pure red (0.5, 0, 0) never; pixels without a value
/// are not in the count. Warned of above one half, naming the share.
#[test]
fn clipped_white_counts_pixels_every_channel_of_which_clips() {
    let white = Xyz::from_linear_srgb([1.0, 1.0, 1.0]);
    let grey = Xyz::from_linear_srgb([0.25, 0.25, 0.25]);
    let red = Xyz::from_linear_srgb([0.5, 0.0, 0.0]);
    let img = vec![Some(white), Some(grey), Some(red), None];
    let share = |e: f64| clipped_white(&img, e);
    assert_eq!(share(0.999), 0.0);
    assert_eq!(share(1.0 + 1e-9), 1.0 / 3.0);
    assert_eq!(share(4.0 + 1e-9), 2.0 / 3.0);
    assert_eq!(share(1e9), 2.0 / 3.0, "the red pixel's green and blue stay at 0 however bright");
    assert_eq!(clipped_white(&[None, None], 10.0), 0.0);
    assert_eq!(clipping_warning(0.5, "the truth", 1000.0), None);
    let w = clipping_warning(2.0 / 3.0, "the ground-truth image", 1000.0).unwrap();
    assert!(w.starts_with("at 1000 RU the ground-truth image shows as white (clipped) on 67 % of the map"), "{w}");
}
