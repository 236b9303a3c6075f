//! The same fit as scipy.optimize.least_squares with a tmm model (tools/fit_scipy_compare.py wrote the
//! measurement and scipy's answer): same optimum, same uncertainties.

use iridis_filmfit::{fit, Derivatives, FitOptions, Measured, Quantity, Template};
use serde_json::Value;

#[test]
fn same_optimum_as_scipy_least_squares() {
    let doc: Value = serde_json::from_str(include_str!("fixtures/scipy_fit.json")).unwrap();
    let csv = include_str!("fixtures/scipy_fit.csv");
    let t = Template::parse(doc["stack"].as_str().unwrap()).unwrap();
    let mut data = Measured::from_csv(csv, "scipy_fit.csv", Quantity::R, None).unwrap();
    assert_eq!(data.values.len(), 401);
    data.sigma = Some(vec![0.002; data.values.len()]);
    let want: Vec<f64> = doc["x"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    let want_sigma: Vec<f64> = doc["sigma"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    let chi2 = doc["chi2"].as_f64().unwrap();
    // One local fit from scipy's start, and the default multi-start search, with exact derivatives and with
    // finite differences: all land on scipy's optimum.
    for (grid, derivatives) in
        [1, 0].into_iter().flat_map(|g| [(g, Derivatives::Exact), (g, Derivatives::FiniteDifferences)])
    {
        let opt = FitOptions { angle_rad: 0.0, quantity: Quantity::R, grid, refine: 4, derivatives };
        let r = fit(&t, &data, &opt).unwrap();
        eprintln!(
            "grid {grid}, {derivatives:?}: {:?} ± {:?}, χ² {} (scipy {want:?} ± {want_sigma:?}, χ² {chi2})",
            r.values, r.sigma, r.chi2
        );
        for k in 0..3 {
            // Within 1e-4 of a standard deviation: the same minimum, not merely a nearby one.
            assert!((r.values[k] - want[k]).abs() < 1e-4 * want_sigma[k], "param {k}: {} vs {}", r.values[k], want[k]);
            assert!((r.sigma[k] / want_sigma[k] - 1.0).abs() < 1e-4, "σ {k}: {} vs {}", r.sigma[k], want_sigma[k]);
        }
        assert!((r.chi2 - chi2).abs() < 1e-7 * chi2, "χ² {} vs {chi2}", r.chi2);
    }
}
