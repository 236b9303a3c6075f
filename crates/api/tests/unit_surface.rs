//! The unit tests of src/surface.rs: what `iridis surface info` says of a patch too small for its period.

use iridis_surface::formats::{load_surface, LoadOptions};

/// A blazed (sawtooth) grating of period d has harmonics at d/m. On an 8 µm patch its 2500 nm fundamental
/// holds 3.2 cycles, fewer than the 4 a period needs to be listed, so the strongest period listed is the
/// second harmonic, d/2 — and a note says that more of the variance lies in structure too long to read; on a
/// 20 µm patch (8 cycles) the fundamental is listed and there is no such note.
#[test]
fn a_patch_too_small_for_its_period_says_the_listed_ones_may_be_harmonics() {
    let info = |size: &str| {
        let hf = load_surface(&format!("builtin:blazed?size={size}&pixel=50nm"), &LoadOptions::default()).unwrap();
        let v = iridis_api::surface::info(&hf, 5, 65_000.0);
        let notes: Vec<String> = v["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap().into()).collect();
        (v["peaks"][0]["period_nm"].as_f64().unwrap(), v["peaks"][0]["power"].as_f64().unwrap(), notes)
    };
    let (small, power, notes) = info("8um");
    assert!((small - 1250.0).abs() < 50.0, "the listed period {small} nm is not d/2");
    let note = notes.iter().find(|n| n.contains("may be its harmonics")).unwrap_or_else(|| panic!("{notes:?}"));
    assert!(
        note.contains(&format!("carries ({:.0} %)", 100.0 * power)) && note.contains("fewer than 4 cycles"),
        "{note}"
    );
    let (large, _, notes) = info("20um");
    assert!((large - 2500.0).abs() < 50.0, "the listed period {large} nm is not d");
    assert!(!notes.iter().any(|n| n.contains("too few repeats")), "{notes:?}");
}
