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
    refused(iridis_api::ModelOptions { observer: Some("1964".into()), ..Default::default() }, "--observer 1964");
    refused(iridis_api::ModelOptions { illuminant: Some("a".into()), ..Default::default() }, "illuminant (a)");
    refused(iridis_api::ModelOptions { step_nm: Some(7.0), ..Default::default() }, "whole number of 7 nm steps");
}

/// `--conserve-energy`: the views' lobes are scaled as `brdf eval --conserve-energy` scales them on 380–700 nm,
/// and in the ultraviolet, below the colour grid, each lobe by its order's factor of the energy-normalised
/// channel matrix: the ratio of the order's efficiency under `iridis grating`'s energy normalisation to its
/// Kirchhoff efficiency (the same matrix; its energy and reciprocity are tested in iridis-diffraction).
#[test]
fn conserve_energy_scales_the_views_as_brdf_eval_and_the_grating_orders_say() {
    use iridis_diffraction::geometry::direction;
    let sine = "builtin:sine?size=4.4um&pixel=50nm&period=1100nm&depth=400nm";
    let visual = iridis_vision::Spec { visual: Some("bluetit".into()), ..Default::default() };
    // Light at 50° (Kirchhoff's factor as printed is well off energy conservation there); at 300 nm the order
    // m = +1 leaves at sin θ_r = sin 50° − 300/1100 (θ_r ≈ 29.6° on the specular side), and the view at 20°
    // sees m = +1 at about 466 nm. At 300 nm orders up to 2/λ apart in frequency couple, seven of the sine's;
    // a unit cell set up for 380 nm keeps five (|c_±6|² of this 400 nm deep sine is a few %).
    let light = 50f64.to_radians();
    let grating = |normalisation| {
        let opts = iridis_api::grating::GratingOptions {
            light: direction(light, 0.0),
            wavelengths_nm: vec![300.0],
            normalisation: Some(normalisation),
            ..Default::default()
        };
        let g = iridis_api::grating::grating(&Source::Spec(sine.into()), &Default::default(), &opts, &Quiet).unwrap();
        // The 4.4 µm patch is the unit cell: the sine's first order is the cell's fourth.
        g.answers[0].orders.iter().find(|o| o.m == 4 && o.n == 0).unwrap().clone()
    };
    let energy = grating(iridis_diffraction::grating::Normalisation::Energy);
    let kirchhoff = grating(iridis_diffraction::grating::Normalisation::Kirchhoff);
    let uv_view = energy.theta_deg;
    assert!((energy.phi_deg - 180.0).abs() < 1e-9 && (uv_view - 29.56).abs() < 0.01, "{energy:?}");
    let views = [20.0, uv_view];
    let run = |conserve_energy: bool| {
        let model = iridis_api::ModelOptions { conserve_energy, ..Default::default() };
        let plane = PlaneViews { light_theta: light, azimuth: Some(0.0), views_deg: &views, spec: &visual };
        along_plane(&Source::Spec(sine.into()), &Default::default(), &model, Default::default(), plane, &Quiet).unwrap()
    };
    let (plain, scaled) = (run(false), run(true));
    assert!(scaled.energy_normalised && !plain.energy_normalised);
    assert!(scaled.quantity().contains("energy-normalised") && scaled.to_json()["quantity"] == scaled.quantity());
    let w = &scaled.wavelengths_nm;
    let at = |l: f64| w.iter().position(|x| *x == l).unwrap();
    // The ultraviolet: the lobe of the sine's m = +1 at 300 nm, scaled by the order's factor.
    let (s, p) = (scaled.views[1].2[at(300.0)], plain.views[1].2[at(300.0)]);
    let want = energy.efficiency.unpolarized / kirchhoff.efficiency.unpolarized;
    eprintln!("300 nm, m = +1: lobe factor {:.6}, grating's energy/Kirchhoff {want:.6}", s / p);
    assert!(p > 0.0 && (s / p - want).abs() < 1e-5 * want, "{} vs {want}", s / p);
    assert!((want - 1.0).abs() > 0.01, "the scaling is not the identity here: {want}");
    // 380–700 nm: brdf eval at the same directions (the view at +20° in the plane: ω_r,x = −sin θ_r).
    let model = iridis_api::ModelOptions { conserve_energy: true, ..Default::default() };
    let eval = iridis_api::brdf::eval_point(
        sine,
        Some("reference"),
        &model,
        Default::default(),
        Default::default(),
        &Default::default(),
        direction(light, 0.0),
        direction(20f64.to_radians(), std::f64::consts::PI),
        &Quiet,
    )
    .unwrap();
    let eval_fr = &eval.query.brdf.as_ref().unwrap().unpolarized;
    let seen = &scaled.views[0].2;
    let peak = seen.iter().fold(0.0f64, |m, &x| m.max(x));
    let mut compared = 0;
    for (k, l) in eval.query.wavelengths_nm.iter().enumerate().filter(|(_, l)| **l <= 700.0) {
        let want = std::f64::consts::PI * eval_fr[k];
        // Both sum the Taylor series to a remainder of 1e-6 (vision's terms bounded at 300 nm, eval's at 380).
        assert!((seen[at(*l)] - want).abs() <= 1e-5 * peak, "{l} nm: vision {} vs brdf eval {want}", seen[at(*l)]);
        compared += 1;
    }
    assert_eq!(compared, 65, "380–700 nm in 5 nm steps");
}
