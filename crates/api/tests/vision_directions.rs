//! How an animal sees a diffracting surface from several directions (`iridis brdf vision`): the spectra are the
//! BRDF's reflectance factor, so a sine grating sends the same spectrum to ±θ at normal incidence (symmetry of
//! its orders), and a blazed one far more light to its facets' side.

use iridis_api::surface::Source;
use iridis_api::vision::{along_plane, PlaneViews};
use iridis_api::Quiet;

fn seen(spec: &str, views: &[f64]) -> iridis_api::vision::DirectionalVision {
    // The light's 65 µm: the cell's orders do not overlap (a 2 µm window on a 1100 nm sine lets neighbouring
    // orders interfere, and the window's place then breaks the ±θ symmetry).
    let model = iridis_api::ModelOptions::default();
    let visual = iridis_vision::Spec { visual: Some("bluetit".into()), ..Default::default() };
    let source = Source::Spec(spec.into());
    let shading = iridis_diffraction::Shading::default();
    let plane = PlaneViews { light_theta: 0.0, azimuth: Some(0.0), views_deg: views, spec: &visual };
    along_plane(&source, &Default::default(), &model, shading, plane, &Quiet).unwrap()
}

#[test]
fn a_sine_grating_looks_the_same_from_plus_and_minus_theta_and_a_blazed_one_brighter_on_its_facets_side() {
    let sine = seen("builtin:sine?size=4.4um&pixel=50nm&period=1100nm&depth=100nm", &[-25.0, 25.0]);
    // |c_m| = |c_−m| for a sine (Jacobi–Anger: J_−m = (−1)^m J_m): the same spectrum from both sides, to the
    // far tails of the window (whose phase is the only asymmetry: 1e-9 of the peak).
    let (a, b) = (&sine.views[0].2, &sine.views[1].2);
    let peak = a.iter().fold(0.0f64, |m, &x| m.max(x));
    assert!(peak > 0.0 && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-9 * peak), "{a:?} vs {b:?}");
    let d = sine.analysis.distance("-25°", "+25°").unwrap();
    assert!(d.delta_l.unwrap() < 1e-9, "{d:?}");
    let blazed = seen("builtin:blazed?size=5um&pixel=50nm", &[-25.0, 25.0]);
    let d = blazed.analysis.distance("-25°", "+25°").unwrap();
    eprintln!("blazed ±25°: ΔS {:?}, ΔL {:?} JND", d.delta_s, d.delta_l);
    // The same orders on both sides (the grating equation), far brighter on the facets' side (−x): the bird
    // sees the same hues and a plain difference in brightness.
    assert!(d.delta_l.unwrap() > 5.0, "{d:?}");
    // +25° looks from −x (positive angles are the specular side of light from +x: ω_r,x = −sin θ_r).
    let (minus, plus) = (&blazed.views[0].2, &blazed.views[1].2);
    assert!(plus.iter().sum::<f64>() > 3.0 * minus.iter().sum::<f64>());
    // The spectra are π f_r on 300–700 nm, the birds' range.
    assert_eq!(sine.wavelengths_nm.first(), Some(&300.0));
    assert_eq!(sine.wavelengths_nm.last(), Some(&700.0));
}

#[test]
fn the_model_options_are_used_or_refused() {
    let sine = "builtin:sine?size=4.4um&pixel=50nm&period=1100nm&depth=100nm";
    let visual = iridis_vision::Spec { visual: Some("bluetit".into()), ..Default::default() };
    let run = |model: iridis_api::ModelOptions| {
        let plane = PlaneViews { light_theta: 0.0, azimuth: Some(0.0), views_deg: &[25.0], spec: &visual };
        let shading = iridis_diffraction::Shading::default();
        along_plane(&Source::Spec(sine.into()), &Default::default(), &model, shading, plane, &Quiet)
    };
    let auto = run(Default::default()).unwrap();
    // --step: the same pointwise BRDF on a coarser grid (f_r at a wavelength does not depend on the others).
    let coarse = run(iridis_api::ModelOptions { step_nm: Some(10.0), ..Default::default() }).unwrap();
    assert_eq!(coarse.wavelengths_nm.len(), 41);
    for (k, l) in coarse.wavelengths_nm.iter().enumerate() {
        assert_eq!(auto.wavelengths_nm[2 * k], *l);
        let (a, c) = (auto.views[0].2[2 * k], coarse.views[0].2[k]);
        assert!((a - c).abs() <= 1e-12 * a.abs().max(1e-30), "{l} nm: {a} vs {c}");
    }
    // --terms: a 100 nm deep sine at 300 nm has k·2h ≈ 4.2, so three terms leave a visible remainder.
    let three = run(iridis_api::ModelOptions { terms: "3".into(), ..Default::default() }).unwrap();
    assert_eq!(three.taylor_terms, 3);
    assert!(auto.taylor_terms > 3, "auto took {}", auto.taylor_terms);
    let rel = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f64>() / a.iter().sum::<f64>();
    assert!(rel(&auto.views[0].2, &three.views[0].2) > 0.01);
    // What it would not use is refused, not ignored; a step that does not divide 300–700 nm too.
    let refused = |m: iridis_api::ModelOptions, words: &str| {
        let e = run(m).unwrap_err().to_string();
        assert!(e.contains(words), "{e}");
    };
    refused(iridis_api::ModelOptions { conserve_energy: true, ..Default::default() }, "--conserve-energy would be");
    refused(iridis_api::ModelOptions { observer: Some("1964".into()), ..Default::default() }, "--observer 1964");
    refused(iridis_api::ModelOptions { illuminant: Some("a".into()), ..Default::default() }, "illuminant (a)");
    refused(iridis_api::ModelOptions { step_nm: Some(7.0), ..Default::default() }, "whole number of 7 nm steps");
}
