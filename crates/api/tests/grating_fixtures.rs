//! `iridis grating` against an independent rigorous solution: the Rayleigh–Fourier method (numpy,
//! tools/gen_rayleigh_fixtures.py, committed in crates/rigorous/tests/fixtures/rayleigh_sine.json) for sine
//! gratings of period 1000 nm on glass (ε = 2.25) and a metal (ε = −20 + 1i), λ 450–650 nm, θ_i 0° and 30°,
//! where the Rayleigh hypothesis holds. Issue 27: the scalar (Kirchhoff) model's unpolarised efficiencies of
//! shallow gratings (a/Λ = 0.01) within 5 %; the rigorous method through the facade equal to it.

use iridis_api::grating::{grating, GratingMethod, GratingOptions};
use iridis_api::surface::Source;
use iridis_api::Quiet;
use iridis_diffraction::geometry::direction;
use iridis_diffraction::Patch;
use num_complex::Complex64;

fn fixture() -> serde_json::Value {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../rigorous/tests/fixtures/rayleigh_sine.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn sine(period: f64, amplitude: f64) -> Source {
    let n = 200;
    let h: Vec<f64> =
        (0..2 * n).map(|i| amplitude * (std::f64::consts::TAU * (i % n) as f64 / n as f64).sin()).collect();
    Source::Patch { patch: Patch::from_row_major(2, n, period / n as f64, 50.0, &h).unwrap(), name: "sine".into() }
}

/// `n + ik = √ε` with `k ≥ 0`, written as a stack's medium.
fn medium(eps: [f64; 2]) -> String {
    let n = Complex64::new(eps[0], eps[1]).sqrt();
    let n = if n.im < 0.0 { -n } else { n };
    if n.im == 0.0 {
        format!("n={:.17}", n.re)
    } else {
        format!("n={:.17}+{:.17}i", n.re, n.im)
    }
}

/// The fixture's converged efficiency (its last run) of reflected order `m` for `pol` in one configuration.
fn reference(cases: &[serde_json::Value], like: &serde_json::Value, pol: &str, m: i64) -> Option<f64> {
    let same = |c: &serde_json::Value| {
        ["material", "amplitude_nm", "wavelength_nm", "theta_deg"].iter().all(|k| c[k] == like[k]) && c["pol"] == pol
    };
    let c = cases.iter().find(|c| same(c))?;
    c["runs"].as_array()?.last()?["reflected"][m.to_string()].as_f64()
}

#[test]
fn kirchhoff_is_within_5_percent_of_rayleigh_fourier_on_shallow_gratings_and_rigorous_equals_it() {
    let f = fixture();
    let cases = f["cases"].as_array().unwrap();
    let (mut worst_k, mut worst_r, mut compared) = (0.0f64, 0.0f64, 0);
    // The scalar model's worst unpolarised error by depth (a/Λ), for the record (the bar is only on shallow ones).
    let mut by_depth = std::collections::BTreeMap::<u64, f64>::new();
    for case in cases.iter().filter(|c| c["pol"] == "te") {
        let (a, lambda, theta) = (
            case["amplitude_nm"].as_f64().unwrap(),
            case["wavelength_nm"].as_f64().unwrap(),
            case["theta_deg"].as_f64().unwrap(),
        );
        let eps = [case["eps"][0].as_f64().unwrap(), case["eps"][1].as_f64().unwrap()];
        let opts = |method| GratingOptions {
            method,
            light: direction(theta.to_radians(), 0.0),
            wavelengths_nm: vec![lambda],
            material: Some(medium(eps)),
            ..GratingOptions::default()
        };
        let source = sine(case["period_nm"].as_f64().unwrap(), a);
        let none = Default::default();
        let k = grating(&source, &none, &opts(GratingMethod::Kirchhoff), &Quiet).unwrap();
        let r = grating(&source, &none, &opts(GratingMethod::Rigorous), &Quiet).unwrap();
        for (method, g) in [("kirchhoff", &k), ("rigorous", &r)] {
            for o in &g.answers[0].orders {
                let (Some(te), Some(tm)) = (reference(cases, case, "te", o.m), reference(cases, case, "tm", o.m))
                else {
                    panic!("{method}: order {} at {lambda} nm has no reference", o.m)
                };
                let want = 0.5 * (te + tm);
                if want < 1e-3 {
                    continue;
                }
                let rel = (o.efficiency.unpolarized - want).abs() / want;
                if method == "rigorous" {
                    // The same physics, another method: to the solver's tolerance.
                    for (got, w) in [(o.efficiency.te, te), (o.efficiency.tm, tm)] {
                        assert!((got - w).abs() <= 2e-3 * w.max(1e-3), "rigorous {case}: m {} {got} vs {w}", o.m);
                    }
                    worst_r = worst_r.max(rel);
                } else if o.theta_deg <= 60.0 {
                    let w = by_depth.entry(a as u64).or_insert(0.0);
                    *w = w.max(rel);
                }
                if method == "kirchhoff" && a / 1000.0 <= 0.02 && o.theta_deg <= 60.0 {
                    assert!(
                        rel < 0.05,
                        "kirchhoff, {} a {a} λ {lambda} θ {theta}: m {} {} vs {want}",
                        case["material"],
                        o.m,
                        o.efficiency.unpolarized
                    );
                    worst_k = worst_k.max(rel);
                    compared += 1;
                }
            }
        }
    }
    eprintln!(
        "shallow (a/Λ = 0.01): {compared} orders, worst Kirchhoff error {:.2} %; rigorous {:.2e}",
        100.0 * worst_k,
        worst_r
    );
    eprintln!("Kirchhoff's worst unpolarised error by amplitude (nm, period 1000 nm): {by_depth:?}");
    assert!(compared >= 20, "{compared}");
}

#[test]
fn kirchhoffs_orders_sum_to_at_most_the_light_at_every_incidence() {
    // A perfect-ish reflector (n = 0.0001 + 30i reflects > 99.9 %) and a deep sine: the printed obliquity
    // returned up to 2× the light; normalised, never more than 1.
    let source = sine(1100.0, 150.0);
    for deg in [0.0, 30.0, 60.0, 75.0, 85.0, 89.0] {
        let opts = GratingOptions {
            light: direction(f64::to_radians(deg), 0.0),
            wavelengths_nm: vec![400.0, 550.0, 700.0],
            material: Some("n=0.0001+30i".into()),
            ..GratingOptions::default()
        };
        let g = grating(&source, &Default::default(), &opts, &Quiet).unwrap();
        for a in &g.answers {
            let t = a.reflected_total;
            assert!(t.te <= 1.0 + 1e-12 && t.tm <= 1.0 + 1e-12, "{deg}° {} nm: {t:?}", a.wavelength_nm);
            assert!(t.unpolarized > 0.99, "{deg}°: {t:?}");
        }
    }
}
