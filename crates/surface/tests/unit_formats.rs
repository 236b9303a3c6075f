//! The unit tests of src/formats/mod.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::*;
use iridis_surface::HeightField;

/// Shared test helpers.
pub fn sample_field() -> HeightField {
    let (rows, cols) = (7, 9);
    let h = (0..rows * cols).map(|i| ((i as f64) * 0.37).sin() * 40.0 + i as f64 * 0.01).collect();
    HeightField::new(rows, cols, 12.5, 13.25, h).unwrap()
}

#[test]
fn detection_by_content() {
    assert_eq!(detect_format(b"GWYP\0\0"), Some(Format::Gwy));
    assert_eq!(detect_format(b"\x93NUMPY\x01\x00"), Some(Format::Npy));
    assert_eq!(detect_format(b"\x89PNG\r\n\x1a\nxxxx"), Some(Format::Png));
    assert_eq!(detect_format(b"II*\0...."), Some(Format::Tiff));
    assert_eq!(detect_format(b"1 2 3\n4 5 6\n"), Some(Format::Text));
    assert_eq!(detect_format(b"\xff\xd8\xff\xe0JFIF"), None);
    let e = read_bytes(b"\xff\xd8\xff\xe0JFIF", "x.jpg", None, &LoadOptions::default()).unwrap_err();
    assert!(e.to_string().contains("JPEG"), "{e}");
}

/// A pixel size the file states wins over a contradicting --pixel-size (issue 32: 50 nm turned a 0.506 µm
/// scan into 51 µm without a word), with a warning naming the file's value; --override-units uses the
/// user's, naming the file's too. A flag that agrees, or a file without a pixel size, says nothing.
#[test]
fn the_files_pixel_size_wins_unless_overridden() {
    let file = Some((0.494, 0.494));
    let given = LoadOptions { pixel_size_nm: Some(50.0), ..Default::default() };
    let (p, w) = pick_pixel(file, None, &given, "x").unwrap();
    assert_eq!(p, (0.494, 0.494));
    let w = w.unwrap();
    assert!(w.contains("--pixel-size 50 nm ignored") && w.contains("0.4940 × 0.4940 nm"), "{w}");
    let forced = LoadOptions { override_units: true, ..given.clone() };
    let (p, w) = pick_pixel(file, None, &forced, "x").unwrap();
    assert_eq!(p, (50.0, 50.0));
    assert!(w.unwrap().contains("replaces the file's own 0.4940 × 0.4940 nm"));
    assert_eq!(pick_pixel(None, None, &given, "x").unwrap(), ((50.0, 50.0), None));
    assert_eq!(
        (pixel_text(9.999_999_999_9), pixel_text(65.0), pixel_text(1563.2)),
        ("10.00".into(), "65.00".into(), "1563".into())
    );
    let same = LoadOptions { pixel_size_nm: Some(0.494), ..Default::default() };
    assert_eq!(pick_pixel(file, None, &same, "x").unwrap().1, None);
}

#[test]
fn units() {
    assert_eq!(unit_to_nm("m"), Some(1e9));
    assert_eq!(unit_to_nm("µm"), Some(1e3));
    assert_eq!(unit_to_nm("furlong"), None);
}

/// Options a kind of SURFACE has no use for are refused by name, not ignored: a file's reading options for a
/// built-in, the built-ins' `--size`/`--seed` for a file, `--max-height` (the height of white) for a file that
/// is not a grey image.
#[test]
fn options_a_surface_would_ignore_are_refused() {
    let refused = |spec: &str, o: LoadOptions, words: &[&str]| {
        let e = load_surface(spec, &o).unwrap_err().to_string();
        for w in words {
            assert!(e.contains(w), "{spec}: '{e}' lacks '{w}'");
        }
    };
    let b = "builtin:sine?size=1um&pixel=100nm";
    let channel = Some(channel::ChannelSel::Index(1));
    refused(
        b,
        LoadOptions { channel, as_height: true, ..Default::default() },
        &["--channel, --as-height would be ignored: they are for"],
    );
    refused(
        b,
        LoadOptions { max_height_nm: Some(9.0), ..Default::default() },
        &["--max-height would be ignored: it is for", "builtin:sine"],
    );
    let dir = tempfile::tempdir().unwrap();
    let npy = dir.path().join("h.npy");
    std::fs::write(&npy, write_bytes(&sample_field(), Format::Npy).unwrap().0).unwrap();
    let f = npy.to_str().unwrap();
    let with_pixel = LoadOptions { pixel_size_nm: Some(10.0), ..Default::default() };
    assert!(load_surface(f, &with_pixel).is_ok());
    refused(
        f,
        LoadOptions { size_nm: Some(1e3), seed: Some(2), ..with_pixel.clone() },
        &["--size, --seed would be ignored: they shape"],
    );
    refused(f, LoadOptions { seed: Some(2), ..with_pixel.clone() }, &["--seed would be ignored: it shapes"]);
    refused(f, LoadOptions { max_height_nm: Some(9.0), ..with_pixel.clone() }, &["--max-height would be", "npy"]);
    // --as-height reads an instrument's other signal as heights: an array of numbers is read as heights anyway.
    refused(f, LoadOptions { as_height: true, ..with_pixel.clone() }, &["--as-height would be ignored", "npy"]);
    // --override-units with nothing to override it with; with a pixel size it applies that one.
    refused(f, LoadOptions { override_units: true, ..Default::default() }, &["--override-units would be", "none"]);
    assert!(load_surface(f, &LoadOptions { override_units: true, ..with_pixel }).is_ok());
}
