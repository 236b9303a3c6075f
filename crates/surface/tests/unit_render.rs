//! The unit tests of src/render.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::render::*;
use iridis_surface::HeightField;

#[test]
fn lengths() {
    assert_eq!(round_length(13_000.0), 10_000.0);
    assert_eq!(round_length(2_600.0), 2_000.0);
    assert_eq!(round_length(0.7), 0.5);
    assert_eq!(format_length(10_000.0), "10 µm");
    assert_eq!(format_length(500.0), "500 nm");
}

#[test]
fn downsamples_and_lights_slopes_facing_the_light_brighter() {
    // A ramp rising to the right (slope facing −x, towards the light on the left) is brighter than one
    // rising to the left, for the same grey map.
    let grey = |_t: f64| [200u8, 200, 200];
    let mk = |s: f64| {
        let h = (0..300 * 300).map(|i| s * (i % 300) as f64).collect();
        HeightField::new(300, 300, 10.0, 10.0, h).unwrap()
    };
    let a = shaded_relief(&mk(1.0), 100, grey);
    let b = shaded_relief(&mk(-1.0), 100, grey);
    assert_eq!((a.width, a.height), (100, 100));
    assert!(a.rgb[(10 * 100 + 50) * 3] > b.rgb[(10 * 100 + 50) * 3]);
}
