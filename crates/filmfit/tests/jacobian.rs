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
