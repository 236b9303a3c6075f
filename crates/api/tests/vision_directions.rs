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
