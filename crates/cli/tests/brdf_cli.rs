//! `iridis precompute` and `iridis brdf-map` as a user runs them, including their refusals.

mod common;
use common::{assert_fails, iridis};

const SURFACE: &str = "builtin:sine?size=8um&pixel=50nm";

#[test]
fn precompute_then_map_and_refusals() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("t.npz");
    let t = table.to_str().unwrap();
    let out =
        iridis(&["precompute", SURFACE, "-o", t, "--uv-resolution", "41", "--coherence", "4um", "--step", "10nm"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let png = dir.path().join("m.png");
    let raw = dir.path().join("m.npy");
    let out = iridis(&["brdf-map", t, "-o", png.to_str().unwrap(), "--size", "32", "--raw", raw.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (32, 32));
    assert_eq!(img.get_pixel(0, 0).0, [0, 0, 0], "outside the unit disk is black");
    // .npy header: magic and the [32, 32, 3] shape.
    let bytes = std::fs::read(&raw).unwrap();
    assert_eq!(&bytes[..6], b"\x93NUMPY");
    assert!(String::from_utf8_lossy(&bytes[..128]).contains("(32, 32, 3"));

    // The table and options that contradict it.
    assert_fails(&["brdf-map", t, "-o", "x.png", "--coherence", "65um"], &["other parameters"]);
    assert_fails(&["brdf-map", t, "-o", "x.png", "--method", "reference"], &["needs the height field"]);
    assert_fails(&["brdf-map", t, "-o", "x.png", "--exposure", "0"], &["exposure"]);
    assert_fails(&["brdf-map", t, "-o", "x.png", "--incidence", "90deg"], &["[0°, 90°)"]);
    assert_fails(&["brdf-map", t, "-o", "x.png", "--incidence", "20"], &["no unit"]);
    let junk = dir.path().join("junk.npz");
    std::fs::write(&junk, b"PK\x03\x04 garbage").unwrap();
    assert_fails(&["brdf-map", junk.to_str().unwrap(), "-o", "x.png"], &["junk.npz"]);
    // A failed run leaves no output behind.
    let never = dir.path().join("never.png");
    assert_fails(&["brdf-map", junk.to_str().unwrap(), "-o", never.to_str().unwrap()], &["junk.npz"]);
    assert!(!never.exists());
    assert_fails(&["precompute", "no/such/surface.npy", "-o", t], &["no/such/surface.npy"]);
    assert_fails(&["precompute", SURFACE, "-o", t, "--terms", "many"], &["--terms"]);
}

#[test]
fn all_three_methods_agree_on_a_mirror_like_surface() {
    // A very shallow grating is nearly a mirror: at normal incidence the centre pixel is white for all methods.
    let dir = tempfile::tempdir().unwrap();
    for method in ["ground-truth", "reference", "lookup"] {
        let png = dir.path().join(format!("{method}.png"));
        let out = iridis(&[
            "brdf-map",
            "builtin:sine?size=6um&pixel=60nm&depth=2nm",
            "--method",
            method,
            "--coherence",
            "3um",
            "--size",
            "9",
            "--exposure",
            "1",
            "--uv-resolution",
            "61",
            "-o",
            png.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{method}: {}", String::from_utf8_lossy(&out.stderr));
        let img = image::open(&png).unwrap().to_rgb8();
        let c = img.get_pixel(4, 4).0;
        assert!(c.iter().all(|&v| v >= 245), "{method}: centre {c:?}");
    }
}
