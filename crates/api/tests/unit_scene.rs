//! The unit tests of src/scene.rs (sizes and the embedded example scenes), moved here so that `cargo test` compiles
//! the library once.

use iridis_api::scene::*;

#[test]
fn sizes_parse() {
    assert_eq!(parse_size("1024x768").unwrap(), (1024, 768));
    assert!(parse_size("1024").is_err());
    assert!(parse_size("0x5").is_err());
}

#[test]
fn every_embedded_example_parses() {
    let dir = tempfile::tempdir().unwrap();
    for p in write_examples(dir.path()).unwrap() {
        // Tables are built on first use; cheap after that (cached).
        load(&p, &Default::default(), &iridis_api::Quiet).unwrap_or_else(|e| panic!("{}: {e:#}", p.display()));
    }
}
