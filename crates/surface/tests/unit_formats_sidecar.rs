//! The unit tests of src/formats/sidecar.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::sidecar::*;
use std::path::Path;

#[test]
fn parses_and_refuses() {
    let p = Path::new("x.json");
    let s = Sidecar::parse(r#"{"pixel_size_nm": [10, 20], "height_unit": "um", "max_height_nm": 5}"#, p).unwrap();
    assert_eq!(s.pixel_size_nm, Some((10.0, 20.0)));
    assert_eq!(s.height_scale(), Some(1000.0));
    assert_eq!((s.height_min_nm, s.height_max_nm), (Some(0.0), Some(5.0)));
    for bad in [r#"{"pixel_size_nm": 0}"#, r#"{"pixel_size_nm": -3}"#, r#"{"height_unit": "kg"}"#, "[1]", "{"] {
        assert!(Sidecar::parse(bad, p).is_err(), "{bad}");
    }
    let back = Sidecar::parse(&s.to_json(), p).unwrap();
    assert_eq!(back.pixel_size_nm, s.pixel_size_nm);
}
