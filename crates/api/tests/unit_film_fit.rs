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
    let p = profile("air | Au 30nm | glass", 500.0, 0.0, "P", 41, None, &iridis_api::report::Quiet).unwrap();
    let d = &p.profile;
    assert!((d.r + d.t + d.layers.iter().sum::<f64>() + d.substrate - 1.0).abs() < 1e-12);
    assert_eq!(p.polarization, "p");
    assert!(p.text().contains("absorbed in layer 1 ("), "{}", p.text());
    assert_eq!(p.csv().lines().count(), 42);
    assert!(profile("air | Au 30nm | glass", 500.0, 0.0, "x", 41, None, &iridis_api::report::Quiet)
        .unwrap_err()
        .to_string()
        .contains("use avg, s or p"));
}

/// `--grid` spaces the multi-start search over the fitted thicknesses: with none fitted it was dropped without a
/// word (one local fit ran), and above the most points a range takes it was capped silently (100 asked, 63 run
/// with two thicknesses: ⌊4000^(1/2)⌋). Now refused and warned.
#[test]
fn a_grid_that_cannot_be_used_is_refused_and_one_capped_says_so() {
    let wl: Vec<f64> = (0..61).map(|i| 400.0 + 5.0 * i as f64).collect();
    let truth = iridis_thinfilm::Stack::parse("air | n=1.45 120nm | n=2.0 80nm | n=3.9").unwrap();
    let r: Vec<f64> = wl.iter().map(|&w| truth.evaluate(w, 0.0).unwrap().r()).collect();
    let request = |stack: &str, grid: usize| FitRequest {
        stack: stack.into(),
        quantity: "R".into(),
        grid,
        ..FitRequest::default()
    };
    let said = iridis_api::report::Collect::default();
    let no_thickness = request("air | n={n=1.5:1.3..1.7} 120nm | n=2.0 80nm | n=3.9", 7);
    let e = fit_arrays(wl.clone(), r.clone(), None, &no_thickness, &said).unwrap_err().to_string();
    assert!(e.contains("--grid 7 would be ignored") && e.contains("fits none"), "{e}");
    let two = request("air | n=1.45 {d1=100nm:50nm..300nm} | n=2.0 {d2=100nm:50nm..300nm} | n=3.9", 100);
    let fit = fit_arrays(wl, r, None, &two, &said).unwrap();
    assert_eq!(iridis_filmfit::fit::max_grid_points(2), 63);
    let warned: Vec<String> = said.take().into_iter().map(|(_, t)| t).collect();
    assert!(warned.iter().any(|w| w.contains("--grid 100: at most 63 points")), "{warned:?}");
    assert!(
        (fit.result.values[0] - 120.0).abs() < 0.5 && (fit.result.values[1] - 80.0).abs() < 0.5,
        "{:?}",
        fit.result
    );
}
