//! The unit tests of src/light.rs, moved here so that `cargo test` compiles the library once.

use iridis_color::Illuminant;
use iridis_vision::light::*;

#[test]
fn d65_in_photons_from_300nm() {
    let d = Light::builtin("d65").unwrap();
    let (lo, _) = d.range_nm().unwrap();
    assert_eq!(lo, 300.0);
    // CIE D65 at 300 nm is 0.0341 and at 560 nm 100 (relative energy); in photons × λ, max 1 over 300–700.
    let spd = Illuminant::D65.spd();
    let ratio = d.at(300.0) / d.at(560.0);
    assert!((ratio - 0.0341 * 300.0 / (100.0 * 560.0)).abs() < 1e-12, "{ratio}");
    let m = (300..=700).map(|l| d.at(l as f64)).fold(0.0, f64::max);
    assert!((m - 1.0).abs() < 1e-12);
    assert_eq!(spd.value_at(300.0), 0.0341);
}

#[test]
fn names_and_backgrounds_parse() {
    for (n, _) in Light::builtin_names() {
        assert!(Light::builtin(n).is_ok(), "{n}");
    }
    assert!(Light::builtin("moonlight").unwrap_err().to_string().contains("forestshade"));
    assert_eq!(Background::parse("grey:0.2").unwrap(), Background::Grey(0.2));
    assert_eq!(Background::parse("none").unwrap(), Background::None);
    assert!(Background::parse("grey:-1").is_err());
    assert!(Background::parse("purple").is_err());
}
