//! The unit tests of src/builtin.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::builtin::*;
use iridis_surface::generate::{Generator, Grid};
use iridis_surface::LoadOptions;

#[test]
fn query_and_options_override_defaults() {
    let hf = builtin_surface("sine?size=8um&pixel=50nm", &LoadOptions::default()).unwrap();
    assert_eq!((hf.rows, hf.cols, hf.dx_nm), (160, 160, 50.0));
    let o = LoadOptions { size_nm: Some(4000.0), pixel_size_nm: Some(40.0), ..Default::default() };
    let hf = builtin_surface("blazed", &o).unwrap();
    assert_eq!((hf.rows, hf.cols), (100, 100));
    // Blazed default: 6° blaze on 2500 nm → depth 2500·tan 6° = 262.7606 nm.
    let (g, _) = from_params("blazed", &[], &Grid::default()).unwrap();
    assert!(matches!(g, Generator::Blazed { depth_nm, .. } if (depth_nm - 262.7606).abs() < 1e-3));
    let p = |k: &str, v: &str| vec![(k.to_string(), v.to_string())];
    let (g, _) = from_params("blazed", &p("blaze", "45deg"), &Grid::default()).unwrap();
    assert!(matches!(g, Generator::Blazed { depth_nm, .. } if (depth_nm - 2500.0).abs() < 1e-9));
}

#[test]
fn query_and_flag_must_agree() {
    let o = LoadOptions { size_nm: Some(8000.0), pixel_size_nm: Some(50.0), seed: Some(2), ..Default::default() };
    let e = builtin_surface("sine?size=5um", &o).unwrap_err().to_string();
    assert!(e.contains("size 5um") && e.contains("--size says 8um"), "{e}");
    let e = builtin_surface("sine?pixel=40nm", &o).unwrap_err().to_string();
    assert!(e.contains("pixel 40nm") && e.contains("--pixel-size says 50nm"), "{e}");
    let e = builtin_surface("gaussian?seed=3", &o).unwrap_err().to_string();
    assert!(e.contains("seed 3") && e.contains("--seed says 2"), "{e}");
    // Saying the same thing twice is no conflict.
    let hf = builtin_surface("gaussian?size=8um&pixel=50nm&seed=2", &o).unwrap();
    assert_eq!((hf.rows, hf.cols), (160, 160));
}

#[test]
fn a_seed_for_a_structure_without_randomness_is_refused() {
    let random = "(a seed shapes cd, gaussian, elaphe, xenopeltis)";
    let e = builtin_surface("sine?seed=3", &LoadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("seed 3 would be ignored: sine has no randomness") && e.contains(random), "{e}");
    let o = LoadOptions { seed: Some(2), ..Default::default() };
    let e = builtin_surface("blazed", &o).unwrap_err().to_string();
    assert!(e.contains("--seed 2 would be ignored: blazed has no randomness"), "{e}");
    let p = vec![("seed".to_string(), "4".to_string())];
    let e = from_params("rect-bumps", &p, &Grid::default()).unwrap_err().to_string();
    assert!(e.contains("seed 4 would be ignored: rect-bumps"), "{e}");
    // A random structure takes it: two seeds, two surfaces; the same seed, the same surface.
    let h = |seed: u64| builtin_surface("gaussian?size=4um", &LoadOptions { seed: Some(seed), ..Default::default() });
    let (a, b, c) = (h(2).unwrap(), h(3).unwrap(), h(2).unwrap());
    assert!(a.heights_nm != b.heights_nm && a.heights_nm == c.heights_nm);
}

#[test]
fn the_note_reads_as_written() {
    let hf = builtin_surface("blazed?size=6.4um&pixel=50nm&angle=30deg", &LoadOptions::default()).unwrap();
    // Blazed default depth 2500 nm · tan 6° = 262.7606 nm, shown to 6 digits.
    assert_eq!(hf.meta.notes, ["blazed period=2500nm depth=262.761nm size=6.4um pixel=50nm angle=30deg"]);
}

#[test]
fn bad_specs_say_why() {
    let o = LoadOptions::default();
    for (spec, needle) in [
        ("marble", "unknown built-in"),
        ("sine?period=1100", "no unit"),
        ("sine?rms=3nm", "not a parameter"),
        ("sine?pixel=0nm", "positive"),
        ("sine?size=1mm&pixel=1nm", "too large"),
        ("sine?seed=-1", "whole number"),
        ("sine?period", "key=value"),
        ("sine?period=10nm&pixel=65nm", "two pixels"),
        // Over-size built-ins: the way out is a larger pixel or a smaller patch, not cropping.
        ("sine?size=4mm&pixel=65nm", "use a larger pixel or a smaller size"),
        ("sine?size=2mm&pixel=65nm", "use a larger pixel or a smaller size"),
    ] {
        let e = builtin_surface(spec, &o).unwrap_err().to_string();
        assert!(e.contains(needle), "{spec}: {e}");
    }
}
