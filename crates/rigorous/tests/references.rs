//! The C-method against independent references, from committed fixtures:
//! - tests/fixtures/rayleigh_sine.json: the Rayleigh–Fourier method (numpy, tools/gen_rayleigh_fixtures.py),
//!   shallow sine gratings (a/Λ ≤ 0.05, inside the Rayleigh hypothesis' validity), metal and glass, TE and TM;
//! - tests/fixtures/grcwa_sine.json: grcwa 0.1.2, staircase RCWA (tools/gen_rigorous_fixtures.py), a/Λ up to
//!   0.15, used where grcwa itself converges (its change between 41 orders/40 slices and 81/80 below 0.5 % on
//!   every order above 1e-3): glass TE and TM, metal TE.
//!
//! The bar (issue 28): every propagating order with η > 1e-3 within 1 % of the reference, relative.

use iridis_rigorous::{sample_1d, solve_1d, Options, Problem, Solution};
use num_complex::Complex64;
use serde_json::Value;
use std::collections::BTreeMap;

fn load(name: &str) -> Value {
    let path = format!("{}/tests/fixtures/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

fn efficiencies(runs: &Value, side: &str) -> BTreeMap<i32, f64> {
    runs[side].as_object().unwrap().iter().map(|(k, v)| (k.parse().unwrap(), v.as_f64().unwrap())).collect()
}

fn solve_case(case: &Value) -> Solution {
    let f = |k: &str| case[k].as_f64().unwrap();
    let eps = Complex64::new(case["eps"][0].as_f64().unwrap(), case["eps"][1].as_f64().unwrap());
    let (period, amp) = (f("period_nm"), f("amplitude_nm"));
    let profile = sample_1d(period, 128, |x| amp * (2.0 * std::f64::consts::PI * x / period).sin());
    let problem = Problem::new(
        f("wavelength_nm"),
        f("theta_deg").to_radians(),
        f("phi_deg").to_radians(),
        Problem::index_from_permittivity(eps),
    );
    let sol = solve_1d(&profile, &problem, &Options::default()).unwrap();
    assert!(sol.convergence.met, "{:?}", sol.convergence);
    sol
}

/// Worst relative error over the orders with reference η > 1e-3 (reflected and transmitted), and the number
/// of orders compared; the smaller orders must agree within `small` in absolute terms (the reference's own
/// accuracy).
fn compare(case: &Value, reference: &Value, sol: &Solution, small: f64) -> (f64, usize) {
    let te = case["pol"] == "te";
    let mut worst: f64 = 0.0;
    let mut count = 0;
    for (side, ours) in [("reflected", &sol.orders), ("transmitted", &sol.transmitted_orders)] {
        for (m, want) in efficiencies(reference, side) {
            let got = ours.iter().find(|o| o.m == m).map(|o| if te { o.efficiency.te } else { o.efficiency.tm });
            let got = got.unwrap_or_else(|| panic!("order {m} ({side}) missing: {case}"));
            if want > 1e-3 {
                worst = worst.max((got - want).abs() / want);
                count += 1;
            } else {
                assert!((got - want).abs() < small, "small order {m}: {got} vs {want} in {case}");
            }
        }
    }
    (worst, count)
}

#[test]
fn c_method_agrees_with_rayleigh_fourier_on_shallow_sines() {
    let doc = load("rayleigh_sine.json");
    let mut table: BTreeMap<String, (f64, usize)> = BTreeMap::new();
    for case in doc["cases"].as_array().unwrap() {
        let runs = case["runs"].as_array().unwrap();
        let sol = solve_case(case);
        let (worst, n) = compare(case, &runs[1], &sol, 2e-5);
        let key = format!("{} {}", case["material"].as_str().unwrap(), case["pol"].as_str().unwrap());
        let e = table.entry(key).or_insert((0.0, 0));
        e.0 = e.0.max(worst);
        e.1 += n;
    }
    for (k, (w, n)) in &table {
        println!("Rayleigh–Fourier {k}: worst relative error {w:.2e} over {n} orders");
        // The Rayleigh–Fourier reference is converged to ~1e-14 (its two truncations) and the C-method's
        // automatic truncation lands far below its 1e-3 tolerance on these shallow sines: measured 1e-14 (glass)
        // to 1e-12 (metal TM), so 1e-6 leaves room for rounding and still catches any physics error.
        assert!(*w < 1e-6, "{k}: {w}");
    }
}

#[test]
fn c_method_agrees_with_grcwa_where_grcwa_converges() {
    let doc = load("grcwa_sine.json");
    let mut table: BTreeMap<String, (f64, usize, usize)> = BTreeMap::new();
    let mut skipped: BTreeMap<String, usize> = BTreeMap::new();
    for case in doc["cases"].as_array().unwrap() {
        let runs = case["runs"].as_array().unwrap();
        let (coarse, fine) = (efficiencies(&runs[0], "reflected"), efficiencies(&runs[1], "reflected"));
        let key = format!(
            "{} {}{}",
            case["material"].as_str().unwrap(),
            case["pol"].as_str().unwrap(),
            if case["phi_deg"].as_f64().unwrap() != 0.0 { " conical" } else { "" }
        );
        let grcwa_change =
            fine.iter().filter(|(_, v)| **v > 1e-3).map(|(m, v)| (v - coarse[m]).abs() / v).fold(0.0, f64::max);
        // Metal TM: staircase RCWA does not converge (Popov et al. 2002); a small change between two
        // resolutions there is a coincidence, not convergence (docs/rigorous.md), so it is never a reference.
        if grcwa_change > 5e-3 || key.starts_with("metal tm") {
            *skipped.entry(key).or_default() += 1;
            continue;
        }
        let sol = solve_case(case);
        // Orders below 1e-3 are compared with grcwa's own accuracy, 1e-4.
        let (worst, n) = compare(case, &runs[1], &sol, 1e-4);
        println!(
            "  {key} a={} λ={} θ={}: worst {worst:.2e}, grcwa's own change {grcwa_change:.2e}",
            case["amplitude_nm"], case["wavelength_nm"], case["theta_deg"]
        );
        let e = table.entry(key).or_insert((0.0, 0, 0));
        e.0 = e.0.max(worst);
        e.1 += n;
        e.2 += 1;
    }
    for (k, (w, n, cases)) in &table {
        println!("grcwa {k}: worst relative error {w:.2e} over {n} orders in {cases} cases");
        assert!(*w < 1e-2, "{k}: {w}");
    }
    for (k, n) in &skipped {
        println!("grcwa {k}: {n} cases where grcwa itself changes by more than 0.5 % or metal TM (not compared)");
    }
    // Glass (TE, TM) and metal TE must be covered; metal TM is where staircase RCWA does not converge.
    for k in ["glass te", "glass tm", "metal te"] {
        assert!(table.get(k).is_some_and(|t| t.2 >= 6), "too few converged grcwa cases for {k}: {table:?}");
    }
}
