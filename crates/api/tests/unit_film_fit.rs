//! The unit tests of src/film_fit.rs (depth windows and absorption profiles), moved here so that `cargo test`
//! compiles the library once.

use iridis_api::film_fit::*;

#[test]
fn depth_windows_are_read_with_units_and_refused_when_empty() {
    assert_eq!(parse_depth("-20nm:0.2um").unwrap(), (-20.0, 200.0));
    assert!(parse_depth("200nm:0nm").unwrap_err().to_string().contains("is empty"));
    assert!(parse_depth("200nm").unwrap_err().to_string().contains("write FROM:TO"));
}

#[test]
fn a_gold_film_conserves_energy_and_absorbs_where_the_field_is() {
    let p = profile("air | Au 30nm | glass", 500.0, 0.0, "P", 41, None).unwrap();
    let d = &p.profile;
    assert!((d.r + d.t + d.layers.iter().sum::<f64>() + d.substrate - 1.0).abs() < 1e-12);
    assert_eq!(p.polarization, "p");
    assert!(p.text().contains("absorbed in layer 1 ("), "{}", p.text());
    assert_eq!(p.csv().lines().count(), 42);
    assert!(profile("air | Au 30nm | glass", 500.0, 0.0, "x", 41, None)
        .unwrap_err()
        .to_string()
        .contains("use avg, s or p"));
}
