//! The unit tests of src/formats/gwy.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::gwy::*;
use iridis_surface::formats::LoadOptions;

#[test]
fn round_trip_keeps_units_and_heights() {
    let hf = crate::unit_formats::sample_field();
    let bytes = write(&hf);
    let back = read(&bytes, None, &LoadOptions::default()).unwrap();
    assert_eq!((back.rows, back.cols), (hf.rows, hf.cols));
    assert!((back.dx_nm - hf.dx_nm).abs() < 1e-9 && (back.dy_nm - hf.dy_nm).abs() < 1e-9);
    for (a, b) in back.heights_nm.iter().zip(&hf.heights_nm) {
        assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{a} vs {b}");
    }
    assert_eq!(back.meta.z_unit, "m");
}

#[test]
fn truncations_are_errors() {
    let bytes = write(&crate::unit_formats::sample_field());
    for n in [0, 3, 4, 10, 30, 60, 100, bytes.len() / 2, bytes.len() - 1] {
        assert!(read(&bytes[..n], None, &LoadOptions::default()).is_err(), "{n}");
    }
}
