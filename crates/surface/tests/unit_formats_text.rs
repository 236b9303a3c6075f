//! The unit tests of src/formats/text.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::text::*;
use iridis_surface::formats::LoadOptions;

#[test]
fn round_trip_is_exact() {
    let hf = crate::unit_formats::sample_field();
    let back = read(write(&hf).as_bytes(), None, &LoadOptions::default()).unwrap();
    assert_eq!(back.heights_nm, hf.heights_nm);
    assert!((back.dx_nm - hf.dx_nm).abs() < 1e-12 && (back.dy_nm - hf.dy_nm).abs() < 1e-12);
}

/// The header's own units win over contradicting flags unless --override-units (issue 32).
#[test]
fn the_headers_units_win_over_flags() {
    let hf = crate::unit_formats::sample_field();
    let text = write(&hf);
    let flags = LoadOptions { pixel_size_nm: Some(50.0), height_unit: Some("um".into()), ..Default::default() };
    let kept = read(text.as_bytes(), None, &flags).unwrap();
    assert_eq!(kept.heights_nm, hf.heights_nm);
    assert!((kept.dx_nm - hf.dx_nm).abs() < 1e-12);
    let w = kept.meta.warnings.join("\n");
    assert!(
        w.contains("ignored: the header gives the values in nm") && w.contains("--pixel-size 50 nm ignored"),
        "{w}"
    );
    let forced = read(text.as_bytes(), None, &LoadOptions { override_units: true, ..flags }).unwrap();
    assert_eq!((forced.dx_nm, forced.heights_nm[1]), (50.0, 1000.0 * hf.heights_nm[1]));
}

#[test]
fn gwyddion_export_header_in_metres() {
    let t = "# Channel: Height\n# Width: 2.000 µm\n# Height: 1.000 µm\n# Value units: m\n\
             1e-9 2e-9 3e-9 4e-9\n5e-9 6e-9 7e-9 8e-9\n";
    let hf = read(t.as_bytes(), None, &LoadOptions::default()).unwrap();
    assert_eq!((hf.rows, hf.cols), (2, 4));
    assert!((hf.dx_nm - 500.0).abs() < 1e-9 && (hf.dy_nm - 500.0).abs() < 1e-9);
    assert!((hf.get(1, 3) - 8.0).abs() < 1e-9);
}

#[test]
fn ragged_and_non_finite_refused() {
    let o = LoadOptions { pixel_size_nm: Some(1.0), ..Default::default() };
    assert!(read(b"1 2 3\n4 5\n", None, &o).unwrap_err().to_string().contains("equal rows"));
    assert!(read(b"1 2\nnan 5\n", None, &o).unwrap_err().to_string().contains("finite"));
    assert!(read(b"1 2 3 4\n", None, &o).unwrap_err().to_string().contains("2×2"));
}

/// One line of column names is a header; a second line without numbers is refused where it stands (an OBJ
/// mesh's `v x y z` lines were all taken as headers, leaving "0 × 0 samples").
#[test]
fn one_header_line_and_no_more() {
    let o = LoadOptions { pixel_size_nm: Some(1.0), ..Default::default() };
    assert_eq!(read(b"a b\n1 2\n3 4\n", None, &o).unwrap().heights_nm, vec![1.0, 2.0, 3.0, 4.0]);
    let e = read(b"# a cube\nv -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\n", None, &o).unwrap_err().to_string();
    assert!(e.contains("line 3: 'v' is not a number") && e.contains("at most one line of column names"), "{e}");
}
