//! The unit tests of src/cie.rs, moved here so that `cargo test` compiles the library once.

use iridis_color::cie::*;

#[test]
fn tables_have_the_published_shape() {
    for o in Observer::ALL {
        let c = o.cmfs();
        assert_eq!(c.wavelengths_nm.len(), 471);
        assert_eq!(c.wavelengths_nm[0], 360.0);
        assert_eq!(c.wavelengths_nm[470], 830.0);
    }
    // CIE 1931 ȳ(555 nm) = 1.0 (the photopic peak) and x̄(600 nm) = 1.0622 (CIE 015 Table 1).
    let c = Observer::Cie1931.cmfs();
    assert!((c.at(555.0)[1] - 1.0).abs() < 1e-4);
    assert!((c.at(600.0)[0] - 1.0622).abs() < 1e-4);
    for i in Illuminant::ALL {
        let (lo, hi) = i.spd().range_nm();
        assert!(lo <= 360.0 && hi >= 830.0, "{i}");
    }
    // D65 is normalised to 100 at 560 nm.
    assert!((Illuminant::D65.spd().value_at(560.0) - 100.0).abs() < 1e-9);
}

#[test]
fn names_parse() {
    assert_eq!("D65".parse::<Illuminant>().unwrap(), Illuminant::D65);
    assert_eq!("1964".parse::<Observer>().unwrap(), Observer::Cie1964);
    let e = "f2".parse::<Illuminant>().unwrap_err().to_string();
    assert!(e.contains("f2") && e.contains("d65"), "{e}");
}
