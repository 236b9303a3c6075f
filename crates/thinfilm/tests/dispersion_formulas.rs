//! The refractiveindex.info dispersion formulas 3 (polynomial), 7 (Herzberger), 8 (retro) and 9 (exotic), read
//! from YAML as the database writes them and checked against the published formulas evaluated independently in
//! 50-digit decimal arithmetic (`tools/gen_dispersion_fixtures.py` → `fixtures/dispersion_formulas.json`), and
//! formula 3 against SCHOTT's catalogue value of n_d for BK7.

use iridis_thinfilm::nkfile::parse_yaml;
use serde_json::Value;

fn fixture() -> Value {
    crate::common::fixture("dispersion_formulas.json")
}

fn yaml(formula: u64, range_um: &[Value], coefficients: &[Value]) -> String {
    let c: Vec<String> = coefficients.iter().map(|v| format!("{}", v.as_f64().unwrap())).collect();
    format!(
        "REFERENCES: test\nDATA:\n  - type: formula {formula}\n    wavelength_range: {} {}\n    coefficients: {}\nSPECS:\n    temperature: 20\n",
        range_um[0].as_f64().unwrap(),
        range_um[1].as_f64().unwrap(),
        c.join(" ")
    )
}

#[test]
fn formulas_3_7_8_9_match_the_published_definitions() {
    let doc = fixture();
    let cases = doc["cases"].as_array().unwrap();
    let mut seen = Vec::new();
    for case in cases {
        let formula = case["formula"].as_u64().unwrap();
        seen.push(formula);
        let text = yaml(formula, case["range_um"].as_array().unwrap(), case["coefficients"].as_array().unwrap());
        let m = parse_yaml(&text, &format!("formula{formula}.yml")).unwrap_or_else(|e| panic!("{text}\n{e}"));
        let r = case["range_um"].as_array().unwrap();
        assert_eq!(m.range_nm(), (r[0].as_f64().unwrap() * 1000.0, r[1].as_f64().unwrap() * 1000.0));
        for row in case["values"].as_array().unwrap() {
            let (w, want) = (row["wavelength_nm"].as_f64().unwrap(), row["n"].as_f64().unwrap());
            let got = m.index_at(w).unwrap();
            assert_eq!(got.im, 0.0, "formula {formula}: no k table, so κ = 0");
            assert!(
                ((got.re - want) / want).abs() < 1e-13,
                "formula {formula} at {w} nm: {} vs {want} ({})",
                got.re,
                case["what"]
            );
        }
        // Outside the declared range the formula is not extrapolated.
        assert!(m.index_at(r[0].as_f64().unwrap() * 1000.0 * 0.9).is_err());
    }
    seen.sort_unstable();
    assert_eq!(seen, [3, 7, 8, 9]);
}

/// SCHOTT's former catalogue formula for BK7 (formula 3 with even powers) gives the catalogue's
/// n_d = 1.51680, n_F = 1.52238 and n_C = 1.51432 (d, F, C lines: 587.56, 486.13, 656.27 nm).
#[test]
fn formula_3_reproduces_bk7_catalogue_indices() {
    let doc = fixture();
    let case = doc["cases"].as_array().unwrap().iter().find(|c| c["formula"] == 3).unwrap();
    let text = yaml(3, case["range_um"].as_array().unwrap(), case["coefficients"].as_array().unwrap());
    let m = parse_yaml(&text, "bk7_old.yml").unwrap();
    for (w, n) in [(587.5618, 1.51680), (486.13, 1.52238), (656.27, 1.51432)] {
        let got = m.index_at(w).unwrap().re;
        assert!((got - n).abs() < 1e-5, "{w} nm: {got} vs catalogue {n}");
    }
}
