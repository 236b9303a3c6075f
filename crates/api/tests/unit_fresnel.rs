//! The unit tests of src/fresnel.rs (parsing Fresnel options), moved here so that `cargo test` compiles the library
//! once.

use iridis_api::fresnel::*;
use iridis_diffraction::Fresnel;
use num_complex::Complex64;

#[test]
fn fresnel_parses() {
    assert!(matches!(parse_fresnel("schlick").unwrap(), Fresnel::Schlick { n } if n == 1.5));
    match parse_fresnel("index:0.2+3.4i").unwrap() {
        Fresnel::Index { n } => assert_eq!(n, Complex64::new(0.2, 3.4)),
        f => panic!("{f:?}"),
    }
    assert!(parse_fresnel("index:abc").is_err());
    assert!(parse_fresnel("schlick:1").is_err());
    assert!(parse_fresnel_source("gold").unwrap().depends_on_wavelength());
    assert!(parse_fresnel_source("stack:air | n=1.5 100nm | n=1.3").unwrap().depends_on_wavelength());
}
