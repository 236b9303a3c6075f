//! The unit tests of src/formats/npy.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::npy::*;
use iridis_surface::formats::{LoadOptions, Sidecar};

#[test]
fn round_trip_with_sidecar() {
    let hf = crate::unit_formats::sample_field();
    let bytes = write(&hf).unwrap();
    let side = Sidecar::for_field(&hf, false);
    let back = read(&bytes, Some(&side), &LoadOptions::default()).unwrap();
    assert_eq!(back.heights_nm, hf.heights_nm);
    assert_eq!((back.dx_nm, back.dy_nm), (hf.dx_nm, hf.dy_nm));
    assert!(back.meta.warnings.is_empty());
    // Without units it refuses, saying how to give them.
    let e = read(&bytes, None, &LoadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("--pixel-size"), "{e}");
}
