//! The unit tests of src/model.rs: how many Taylor terms a model takes, and what it says about a given count.

use iridis_api::model::{term_count, ModelOptions, TERMS_WARN_REMAINDER};
use iridis_api::report::{Collect, Kind};
use iridis_diffraction::Patch;

/// A sine of `amplitude` nm along x, 64 samples of 20 nm a period, four rows.
fn sine(amplitude: f64) -> Patch {
    let h: Vec<f64> = (0..4 * 64).map(|i| amplitude * (std::f64::consts::TAU * (i % 64) as f64 / 64.0).sin()).collect();
    Patch::from_row_major(4, 64, 20.0, 20.0, &h).unwrap()
}

fn terms(t: &str) -> ModelOptions {
    ModelOptions { terms: t.into(), ..ModelOptions::default() }
}

#[test]
fn a_given_term_count_is_warned_about_where_its_remainder_is_large_and_a_deep_relief_refused() {
    let patch = sine(300.0);
    // The remainder bound (k_max · 2|h|max)^{N+1}/(N+1)! at 380 nm (docs/PHYSICS.md), written out.
    let x = 2.0 * std::f64::consts::TAU / 380.0 * 300.0;
    let bound = |n: usize| (1..=n + 1).fold(1.0, |b, k| b * x / k as f64);
    let first_quiet = (0..200).find(|&n| bound(n) <= TERMS_WARN_REMAINDER).unwrap();
    let said = Collect::default();
    let auto = term_count(&patch, &terms("auto"), 380.0, &said).unwrap();
    assert!(bound(auto) <= 1e-6 && bound(auto - 1) > 1e-6, "auto N = {auto}");
    assert!(said.take().is_empty());
    assert_eq!(term_count(&patch, &terms(&first_quiet.to_string()), 380.0, &said).unwrap(), first_quiet);
    assert!(said.take().is_empty(), "N = {first_quiet} meets the bound");
    let fewer = first_quiet - 1;
    assert_eq!(term_count(&patch, &terms(&fewer.to_string()), 380.0, &said).unwrap(), fewer);
    let w = said.take();
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].0, Kind::Warning);
    assert!(w[0].1.contains(&format!("--terms {fewer}")) && w[0].1.contains(&format!("N = {auto}")), "{}", w[0].1);
    // A relief too deep for the expansion is refused whatever the count (a few terms hid it in noise before).
    let e = term_count(&sine(900.0), &terms("5"), 380.0, &said).unwrap_err().to_string();
    assert!(e.contains("too deep for the Taylor expansion"), "{e}");
}
