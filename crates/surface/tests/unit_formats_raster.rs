//! The unit tests of src/formats/raster.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::raster::*;
use iridis_surface::formats::{Format, LoadOptions, Sidecar};

#[test]
fn png16_round_trip_to_its_precision() {
    let hf = crate::unit_formats::sample_field();
    let bytes = write_png16(&hf).unwrap();
    let side = Sidecar::for_field(&hf, true);
    let back = read(&bytes, Format::Png, Some(&side), &LoadOptions::default()).unwrap();
    let (lo, hi) = hf.min_max();
    let tol = (hi - lo) / 65535.0 / 2.0 + 1e-9;
    for (a, b) in back.heights_nm.iter().zip(&hf.heights_nm) {
        assert!((a - b).abs() <= tol, "{a} vs {b}");
    }
    assert_eq!((back.dx_nm, back.dy_nm), (hf.dx_nm, hf.dy_nm));
}

#[test]
fn needs_a_height_scale() {
    let bytes = write_png16(&crate::unit_formats::sample_field()).unwrap();
    let e = read(&bytes, Format::Png, None, &LoadOptions { pixel_size_nm: Some(10.0), ..Default::default() })
        .unwrap_err()
        .to_string();
    assert!(e.contains("--max-height"), "{e}");
}
