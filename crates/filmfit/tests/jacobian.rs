//! The fit's exact Jacobian (`model_jacobian`: automatic differentiation through the template's Cauchy and
//! Sellmeier formulas, constant indices and thicknesses) against Richardson-extrapolated central differences
//! of `model`, for R, T (with an incoherent slide) and ψ/Δ.

use iridis_filmfit::{model, model_jacobian, FitOptions, Quantity, Template};

fn check(stack: &str, values: &[f64], quantity: Quantity, angle_deg: f64) {
    let t = Template::parse(stack).unwrap();
    let opt = FitOptions { angle_rad: angle_deg.to_radians(), quantity, ..FitOptions::default() };
    let wl = [420.0, 515.0, 633.0, 780.0];
    let jac = model_jacobian::<6>(&t, values, &wl, &opt).unwrap();
    let base = model(&t, values, &wl, &opt).unwrap();
    assert_eq!(jac.len(), base.len());
    for k in 0..values.len() {
        let central = |h: f64| {
            let (mut a, mut b) = (values.to_vec(), values.to_vec());
            a[k] -= h;
            b[k] += h;
            let (ma, mb) = (model(&t, &a, &wl, &opt).unwrap(), model(&t, &b, &wl, &opt).unwrap());
            ma.iter().zip(&mb).map(|(a, b)| (b - a) / (2.0 * h)).collect::<Vec<_>>()
        };
        let h = 1e-4 * values[k].abs().max(1e-2);
        let (c1, c2) = (central(h), central(h / 2.0));
        // Errors relative to the largest derivative of this parameter's column.
        let scale = jac.iter().map(|r| r[k].abs()).fold(0.0, f64::max);
        assert!(scale > 0.0);
        for i in 0..base.len() {
            let fd = (4.0 * c2[i] - c1[i]) / 3.0;
            let exact = jac[i][k];
            assert!(
                (exact - fd).abs() < 1e-7 * scale,
                "{stack}, {quantity:?}, parameter {k}, value {i}: exact {exact:e}, finite differences {fd:e}"
            );
        }
        for row in &jac {
            assert!(row[values.len()..].iter().all(|v| *v == 0.0), "unused directions stay zero");
        }
    }
}

#[test]
fn cauchy_film_thickness_on_silicon() {
    let s = "air | cauchy:{A=1.5:1.3..1.7},{B=0.004:0..0.02},{C=0.0001:0..0.001} {d=300nm:100nm..600nm} | Si";
    check(s, &[1.47, 0.0052, 0.0002, 312.0], Quantity::R, 0.0);
    check(s, &[1.47, 0.0052, 0.0002, 312.0], Quantity::PsiDelta, 70.0);
}

#[test]
fn sellmeier_substrate_and_constant_index_layer() {
    let s = "air | n={n=2.0:1.5..2.5} {d=100nm:10nm..300nm} | sellmeier:{B1=1.0:0.5..1.5},{C1=0.006:0..0.02},1.0,100";
    check(s, &[2.05, 140.0, 1.04, 0.006], Quantity::R, 30.0);
    check(s, &[2.05, 140.0, 1.04, 0.006], Quantity::T, 50.0);
    check(s, &[2.05, 140.0, 1.04, 0.006], Quantity::PsiDelta, 65.0);
}

#[test]
fn incident_medium_index_and_incoherent_slide() {
    // A fitted incident-medium index moves the Snell invariant n₀ sin θ₀ too.
    let s = "n={n0=1.33:1.2..1.5} | n=2.1 {d=150nm:50nm..400nm} | inc:cauchy:{A=1.52:1.4..1.6},0.004 1mm | air";
    check(s, &[1.33, 212.0, 1.52], Quantity::T, 0.0);
    check(s, &[1.33, 212.0, 1.52], Quantity::R, 40.0);
}

#[test]
fn a_layer_at_its_critical_angle_falls_back_to_finite_differences() {
    // An air gap between glass at exactly its critical angle: cos θ = 0 in the gap, where ∂R/∂n_gap is
    // infinite. The exact Jacobian says so (not a finite wrong number); the fit then uses finite
    // differences and still ends with finite values and uncertainties.
    let t = Template::parse("n=1.5 | n={n=1.0:0.9..1.1} {d=200nm:100nm..300nm} | n=1.5").unwrap();
    let th = (1.0f64 / 1.5).asin();
    assert_eq!(1.5 * th.sin(), 1.0, "the angle is exactly critical in floating point");
    let opt = FitOptions { angle_rad: th, quantity: Quantity::R, grid: 1, ..FitOptions::default() };
    let wl: Vec<f64> = (0..40).map(|i| 450.0 + 5.0 * i as f64).collect();
    let jac = model_jacobian::<2>(&t, &[1.0, 200.0], &wl, &opt).unwrap();
    assert!(jac.iter().any(|r| !r[0].is_finite()), "∂R/∂n is unbounded at the critical angle");
    let clean = model(&t, &[1.0, 200.0], &wl, &opt).unwrap();
    let data = iridis_filmfit::Measured {
        wavelength_nm: wl.clone(),
        values: clean.iter().enumerate().map(|(i, v)| v + 1e-3 * ((i * 7 % 5) as f64 - 2.0)).collect(),
        sigma: Some(vec![1e-3; wl.len()]),
    };
    let r = iridis_filmfit::fit(&t, &data, &FitOptions { grid: 1, ..opt }).unwrap();
    assert!(r.values.iter().chain(&r.sigma).all(|v| v.is_finite()), "{r:?}");
    assert_eq!(r.jacobian, "finite differences");
}
