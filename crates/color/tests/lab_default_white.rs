//! CIELAB with the default white (D65, CIE 1931): `Lab::from_xyz_d65` / `to_xyz_d65` against colour-science
//! (fixture from tools/gen_color_fixtures.py) and the definition of CIELAB.

use iridis_color::integrate::{reflectance_to_xyz, white_point};
use iridis_color::lab::{d65_white, delta_e_2000, delta_e_displayed, displayed_lab};
use iridis_color::{Illuminant, Lab, Observer, Xyz};

use crate::common::{arr3, fixture, spectra};

#[test]
fn default_white_is_colour_science_d65() {
    let doc = fixture("colour_science.json");
    let d65 = doc["illuminants"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["illuminant"] == "D65" && e["observer"] == "1931")
        .unwrap();
    let want = arr3(&d65["XYZ"]);
    let w = d65_white();
    assert!((w.y - 1.0).abs() < 1e-12);
    for (got, want) in w.to_array().iter().zip(want) {
        assert!((got - want).abs() < 2e-5, "{w:?} vs colour-science {want}");
    }
    assert_eq!(w, white_point(Illuminant::D65, Observer::Cie1931));
    // The white itself is L* = 100, a* = b* = 0; half its luminance is L* = 116·0.5^(1/3) − 16 = 76.0693.
    let l = Lab::from_xyz_d65(w);
    assert!((l.l - 100.0).abs() < 1e-12 && l.a.abs() < 1e-12 && l.b.abs() < 1e-12, "{l:?}");
    let half = Lab::from_xyz_d65(w.scale(0.5));
    assert!((half.l - (116.0 * 0.5f64.cbrt() - 16.0)).abs() < 1e-12 && half.a.abs() < 1e-12);
}

#[test]
fn d65_lab_matches_colour_science_and_round_trips() {
    let doc = fixture("colour_science.json");
    let mut checked = 0;
    for (e, spectrum) in spectra(&doc) {
        if e["illuminant"] != "D65" || e["observer"] != "1931" {
            continue;
        }
        let name = e["name"].as_str().unwrap();
        let xyz = reflectance_to_xyz(&spectrum, Illuminant::D65, Observer::Cie1931);
        let lab = Lab::from_xyz_d65(xyz);
        // Same as naming the white explicitly, and as colour-science (tolerance as in against_references.rs:
        // rectangle against trapezoid rule on the 1 nm grid).
        assert_eq!(lab, Lab::from_xyz(xyz, white_point(Illuminant::D65, Observer::Cie1931)));
        let want = arr3(&e["Lab"]);
        for c in 0..3 {
            assert!((lab.to_array()[c] - want[c]).abs() < 2e-3, "{name}: {lab:?} vs colour-science {want:?}");
        }
        let back = lab.to_xyz_d65();
        for c in 0..3 {
            assert!((back.to_array()[c] - xyz.to_array()[c]).abs() < 1e-12, "{name}: {back:?} vs {xyz:?}");
        }
        checked += 1;
    }
    assert!(checked >= 9, "{checked} D65 spectra");
    // Dark colours take the linear branch of CIELAB (Y/Yw ≤ (6/29)³): L* = (29/3)³ Y.
    let dark = Xyz::new(0.001, 0.001, 0.001);
    assert!((Lab::from_xyz_d65(dark).l - 24389.0 / 27.0 * 0.001).abs() < 1e-12);
}

#[test]
fn displayed_colours_are_clipped_to_the_display_and_its_white_is_lightness_100() {
    // A perfect white reflector (display white, Y = 1) at 1 RU: L* = 100, a* = b* = 0.
    let white = Xyz::from_linear_srgb([1.0, 1.0, 1.0]);
    let lab = displayed_lab(white, 1.0);
    assert!((lab.l - 100.0).abs() < 1e-9 && lab.a.abs() < 1e-9 && lab.b.abs() < 1e-9, "{lab:?}");
    // Far brighter light clips to the same white; two colours both far above white are both shown white.
    assert!(delta_e_2000(lab, displayed_lab(white, 1000.0)) < 1e-9);
    assert!(delta_e_displayed(white.scale(3.0), white.scale(5.0), 1.0) < 1e-9);
    // Below white the exposure matters: 0.3 and 0.5 of white are greys of L* 61.654 and 76.069, a pure
    // lightness difference: ΔE00 = ΔL*/S_L with S_L = 1 + 0.015 (L̄ − 50)²/√(20 + (L̄ − 50)²) = 11.3033.
    let (l1, l2) = (116.0 * 0.3f64.cbrt() - 16.0, 116.0 * 0.5f64.cbrt() - 16.0);
    let m = 0.5 * (l1 + l2) - 50.0;
    let want = (l2 - l1) / (1.0 + 0.015 * m * m / (20.0 + m * m).sqrt());
    let got = delta_e_displayed(white.scale(0.3), white.scale(0.5), 1.0);
    assert!((got - want).abs() < 1e-9 && (want - 11.3033).abs() < 1e-4, "{got} vs {want}");
    // A channel that is not a number is shown black, as the darkest the display has.
    let nan = displayed_lab(Xyz::new(f64::NAN, 0.0, 0.0), 1.0);
    assert_eq!(nan.to_array(), displayed_lab(Xyz::new(0.0, 0.0, 0.0), 1.0).to_array());
    assert_eq!(nan.l, 0.0);
}
