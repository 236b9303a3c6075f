//! `Spectrum::resample`, `ToneMap` and `Encoding::parse` against laws written out here (linear interpolation,
//! the IEC 61966-2-1 sRGB curve, the definition of exposure) and against colour-science's linear sRGB values
//! (fixture from tools/gen_color_fixtures.py).

use iridis_color::convert::Xyz;
use iridis_color::tonemap::hex;
use iridis_color::{Encoding, Spectrum, ToneMap};
use serde_json::Value;

/// IEC 61966-2-1 sRGB encoding, written out independently of `convert::srgb_encode`.
fn iec_srgb(v: f64) -> f64 {
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

#[test]
fn resample_is_linear_interpolation_with_held_ends() {
    // A straight line is reproduced exactly by linear interpolation, on any grid inside the data.
    let s = Spectrum::from_fn(400.0, 700.0, 10.0, |w| 0.002 * w - 0.3).unwrap();
    let grid: Vec<f64> = (0..=120).map(|i| 401.3 + 2.47 * i as f64).collect();
    let r = s.resample(&grid).unwrap();
    assert_eq!(r.wavelengths_nm(), &grid[..]);
    for (&w, &v) in grid.iter().zip(r.values()) {
        assert!((v - (0.002 * w - 0.3)).abs() < 1e-14, "{w} nm: {v}");
    }
    // Between two samples of a curve the value is the chord's, not the curve's: (400, 1), (410, 4) → 2.5 at 405.
    let q = Spectrum::new(vec![400.0, 410.0, 420.0], vec![1.0, 4.0, 9.0]).unwrap();
    let r = q.resample(&[395.0, 400.0, 405.0, 412.5, 420.0, 430.0]).unwrap();
    assert_eq!(r.values(), &[1.0, 1.0, 2.5, 5.25, 9.0, 9.0]);
    // Onto its own grid, or a coarser grid of its own samples, nothing changes.
    assert_eq!(q.resample(q.wavelengths_nm()).unwrap(), q);
    let d65 = iridis_color::Illuminant::D65.spd();
    let five: Vec<f64> = (0..=80).map(|i| 380.0 + 5.0 * i as f64).collect();
    let r = d65.resample(&five).unwrap();
    for (&w, &v) in five.iter().zip(r.values()) {
        assert_eq!(v, d65.value_at(w));
    }
    // A grid that does not increase is refused.
    assert!(q.resample(&[400.0, 400.0, 410.0]).is_err());
    assert!(q.resample(&[410.0, 400.0]).is_err());
    assert!(q.resample(&[400.0]).is_err());
}

#[test]
fn encoding_parse_accepts_the_documented_forms() {
    assert_eq!(Encoding::parse("srgb"), Ok(Encoding::Srgb));
    assert_eq!(Encoding::parse(" sRGB "), Ok(Encoding::Srgb));
    assert_eq!(Encoding::parse("LINEAR"), Ok(Encoding::Linear));
    assert_eq!(Encoding::parse("1"), Ok(Encoding::Linear));
    assert_eq!(Encoding::parse("2.2"), Ok(Encoding::Gamma(2.2)));
    assert_eq!(Encoding::parse("1.8"), Ok(Encoding::Gamma(1.8)));
    for bad in ["0", "-2.2", "nan", "inf", "", "gamma", "2.2.2"] {
        let e = Encoding::parse(bad).unwrap_err();
        assert!(e.contains(&format!("'{bad}'")) && e.contains("srgb, linear or a gamma"), "{bad}: {e}");
    }
}

#[test]
fn encodings_follow_their_laws() {
    for v in [0.0, 0.001, 0.003_130_8, 0.01, 0.18, 0.5, 0.9, 1.0] {
        assert!((Encoding::Srgb.encode(v) - iec_srgb(v)).abs() < 1e-15, "{v}");
        assert!((Encoding::Gamma(2.2).encode(v) - v.powf(1.0 / 2.2)).abs() < 1e-15, "{v}");
        assert_eq!(Encoding::Linear.encode(v), v);
    }
    // Published points of the sRGB curve: 18 % grey encodes to 0.4614, 50 % to 0.7354.
    assert!((Encoding::Srgb.encode(0.18) - 0.461_356).abs() < 1e-6);
    assert!((Encoding::Srgb.encode(0.5) - 0.735_357).abs() < 1e-6);
}

#[test]
fn tonemap_matches_colour_science_linear_srgb() {
    let data: Value = serde_json::from_str(include_str!("fixtures/colour_science.json")).unwrap();
    let mut checked = 0;
    for entry in data["spectra"].as_array().unwrap() {
        let xyz: Vec<f64> = entry["XYZ"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let lin: Vec<f64> = entry["linear_srgb"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let xyz = Xyz::new(xyz[0], xyz[1], xyz[2]);
        let got = ToneMap::default().to_display(xyz);
        let own = xyz.to_linear_srgb();
        for c in 0..3 {
            // The pipeline: matrix, clip to [0, 1], IEC curve.
            assert_eq!(got[c], iec_srgb(own[c].clamp(0.0, 1.0)), "{}", entry["name"]);
            // And colour-science's linear sRGB, after clipping: colour-science derives its matrix from the
            // primaries, iridis uses the IEC's printed 4-digit one, so they differ by up to ~1e-4 (as in
            // against_references.rs).
            let back = if got[c] <= 0.04045 { got[c] / 12.92 } else { ((got[c] + 0.055) / 1.055).powf(2.4) };
            let want = lin[c].clamp(0.0, 1.0);
            assert!((back - want).abs() < 1e-4, "{}: {back} vs colour-science {want} (channel {c})", entry["name"]);
        }
        checked += 1;
    }
    assert!(checked > 50);
}

#[test]
fn tonemap_exposure_clip_and_pixels() {
    let white = Xyz::new(0.950_470_764_945_246, 1.0, 1.088_828_422_436_494_6); // D65, colour-science
    let grey = |y: f64| white.scale(y);
    // Exposure scales XYZ before anything else: 0.25 at 2 RU is 0.5 at 1 RU.
    let a = ToneMap { exposure_ru: 2.0, encoding: Encoding::Srgb }.to_display(grey(0.25));
    let b = ToneMap::default().to_display(grey(0.5));
    for c in 0..3 {
        assert!((a[c] - b[c]).abs() < 1e-12);
        assert!((b[c] - iec_srgb(0.5)).abs() < 1e-4, "{b:?}"); // the IEC matrix's 4 digits, as above
    }
    // 1 RU: a perfect mirror (Y = 1) is just white; brighter clips to white, negative and NaN to black.
    assert_eq!(ToneMap::default().to_rgb8(white), [255, 255, 255]);
    assert!(ToneMap::default().to_display(grey(3.0)).iter().all(|&c| (c - 1.0).abs() < 1e-15)); // 1.055 − 0.055
    assert_eq!(ToneMap::default().to_display(Xyz::new(-1.0, -1.0, -1.0)), [0.0, 0.0, 0.0]);
    assert_eq!(ToneMap::default().to_display(Xyz::new(f64::NAN, f64::NAN, f64::NAN)), [0.0, 0.0, 0.0]);
    // Linear output at 0.31 RU of white: 0.31 × 255 = 79.05 → 79; 0.33 × 255 = 84.15 → 84 (nearest).
    let lin = ToneMap { exposure_ru: 0.31, encoding: Encoding::Linear };
    assert_eq!(lin.to_rgb8(white), [79, 79, 79]);
    assert_eq!(hex(lin.to_rgb8(white)), "#4f4f4f");
    assert_eq!(ToneMap { exposure_ru: 0.33, encoding: Encoding::Linear }.to_rgb8(white), [84, 84, 84]);
    // Gamma 2.2 of 18 % grey: 0.18^(1/2.2) = 0.45865 → 117.
    let g = ToneMap { exposure_ru: 1.0, encoding: Encoding::Gamma(2.2) }.to_rgb8(grey(0.18));
    assert_eq!(g, [117, 117, 117]);
    assert_eq!(hex([255, 0, 16]), "#ff0010");
}
