//! A lookup table knows what it was made from, and refuses to serve anything else: every field of its
//! provenance is checked and a mismatch is named.

use iridis_color::{Illuminant, Observer};
use iridis_diffraction::table::{LookupTable, Provenance, TableParams};
use iridis_diffraction::{Patch, SpectralSetup, TaylorTerms};

fn patch(seed: f64) -> Patch {
    let h: Vec<f64> = (0..8 * 10).map(|k| 30.0 * ((k as f64 * 0.7 + seed).sin())).collect();
    Patch::from_row_major(8, 10, 50.0, 60.0, &h).unwrap()
}

#[test]
fn every_field_of_a_tables_provenance_is_checked_and_named() {
    let p = patch(0.0);
    let spectral = SpectralSetup::new(Illuminant::D65, Observer::Cie1931, 10.0).unwrap();
    let params = TableParams { uv_resolution: 21, uv_power: 3.0 };
    let terms = TaylorTerms::compute(&p, 6, 2000.0).unwrap();
    let table = LookupTable::build(&terms, &spectral, params, "test", &|_| {}).unwrap();
    // Written and read back: the provenance survives the file.
    let mut buf = std::io::Cursor::new(Vec::new());
    table.write_npz(&mut buf).unwrap();
    buf.set_position(0);
    let table = LookupTable::read_npz(buf, "t.npz").unwrap();
    let good = Provenance::of(&p, 2000.0, 6, &spectral, params);
    assert_eq!(table.mismatches(&good), Vec::<String>::new());
    assert!(table.check(&good, "t.npz").is_ok());
    assert_eq!(table.meta.surface_fingerprint.as_deref(), Some(p.fingerprint().as_str()));

    let other_spectral = |i: Illuminant, o: Observer, from: f64, to: f64, step: f64| {
        SpectralSetup::with_range(i, o, from, to, step).unwrap()
    };
    let mut shifted = patch(0.0);
    shifted.heights[17] += 1e-9; // one height changed in its last digits: another surface
    let cases: Vec<(&str, Provenance)> = vec![
        ("surface fingerprint", Provenance::of(&shifted, 2000.0, 6, &spectral, params)),
        ("size", Provenance { size: Some((10, 8)), ..good.clone() }),
        ("pixel size", Provenance { pixel_nm: Some((50.0, 50.0)), ..good.clone() }),
        ("coherence", Provenance::of(&p, 65_000.0, 6, &spectral, params)),
        (
            "illuminant",
            Provenance::of(
                &p,
                2000.0,
                6,
                &other_spectral(Illuminant::E, Observer::Cie1931, 380.0, 780.0, 10.0),
                params,
            ),
        ),
        (
            "observer",
            Provenance::of(
                &p,
                2000.0,
                6,
                &other_spectral(Illuminant::D65, Observer::Cie1964, 380.0, 780.0, 10.0),
                params,
            ),
        ),
        ("wavelength step", Provenance::of(&p, 2000.0, 6, &SpectralSetup::default(), params)),
        (
            "wavelength range",
            Provenance::of(
                &p,
                2000.0,
                6,
                &other_spectral(Illuminant::D65, Observer::Cie1931, 400.0, 700.0, 10.0),
                params,
            ),
        ),
        ("Taylor terms", Provenance::of(&p, 2000.0, 7, &spectral, params)),
        ("u-v grid", Provenance::of(&p, 2000.0, 6, &spectral, TableParams { uv_resolution: 21, uv_power: 5.0 })),
        ("u-v grid", Provenance::of(&p, 2000.0, 6, &spectral, TableParams { uv_resolution: 31, uv_power: 3.0 })),
    ];
    for (field, expected) in cases {
        let m = table.mismatches(&expected);
        assert_eq!(m.len(), 1, "{field}: {m:?}");
        assert!(m[0].starts_with(field), "{field}: {m:?}");
        let e = table.check(&expected, "t.npz").unwrap_err().to_string();
        assert!(e.contains("t.npz") && e.contains(field) && e.contains("iridis precompute"), "{e}");
    }
    // Several at once: each named.
    let e = table.check(&Provenance::of(&patch(1.0), 3000.0, 6, &spectral, params), "t.npz").unwrap_err().to_string();
    assert!(e.contains("surface fingerprint") && e.contains("coherence"), "{e}");
    // A table written before fingerprints were recorded cannot vouch for its surface.
    let mut old = table.clone();
    old.meta.surface_fingerprint = None;
    assert!(old.mismatches(&good)[0].contains("records none"), "{:?}", old.mismatches(&good));
    // Fields left out are not checked (brdf-map on a table alone checks only the options given).
    assert!(table.mismatches(&Provenance { coherence_nm: Some(2000.0), ..Provenance::default() }).is_empty());
}

#[test]
fn a_table_built_for_a_custom_light_records_that_light_not_an_illuminant() {
    let p = patch(0.0);
    let mut spectral = SpectralSetup::new(Illuminant::E, Observer::Cie1931, 20.0).unwrap();
    let laser: Vec<f64> = spectral.wavelengths().iter().map(|&l| (-((l - 532.0) / 3.0).powi(2)).exp()).collect();
    spectral.light = Some(laser.clone());
    let terms = TaylorTerms::compute(&p, 4, 2000.0).unwrap();
    let params = TableParams { uv_resolution: 11, uv_power: 2.0 };
    let table = LookupTable::build(&terms, &spectral, params, "laser", &|_| {}).unwrap();
    assert_eq!(table.meta.illuminant, "light");
    assert_eq!(table.meta.light_spectrum.as_deref(), Some(laser.as_slice()));
    assert!(table.mismatches(&Provenance::of(&p, 2000.0, 4, &spectral, params)).is_empty());
    // Another beam: refused by its spectrum; the plain illuminant E: refused by name.
    let mut other = spectral.clone();
    other.light = Some(laser.iter().rev().copied().collect());
    let m = table.mismatches(&Provenance::of(&p, 2000.0, 4, &other, params));
    assert!(m.len() == 1 && m[0].starts_with("light spectrum"), "{m:?}");
    let plain = SpectralSetup::new(Illuminant::E, Observer::Cie1931, 20.0).unwrap();
    let m = table.mismatches(&Provenance::of(&p, 2000.0, 4, &plain, params));
    assert!(m.iter().any(|s| s.starts_with("illuminant")), "{m:?}");
}
