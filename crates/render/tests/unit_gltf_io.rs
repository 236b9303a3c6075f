//! The unit tests of src/gltf_io.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::gltf_io::*;

#[test]
fn base64_round_trip() {
    assert_eq!(base64_decode("aXJpZGlz").unwrap(), b"iridis");
    assert_eq!(base64_decode("aXJpZA==").unwrap(), b"irid");
    assert!(base64_decode("a*b").is_none());
}
