//! The unit tests of src/template.rs, moved here so that `cargo test` compiles the library once.

use iridis_vision::template::*;

#[test]
fn templates_peak_near_lambda_max() {
    // The α band is built to be 1 at λ = λmax (x = 1) to within the fit of its constants.
    for &l in &[360.0, 420.0, 500.0, 560.0, 620.0] {
        for c in [Chromophore::A1, Chromophore::A2] {
            let v = alpha_band(l, l, c);
            assert!((v - 1.0).abs() < 0.01, "{c} {l}: {v}");
            // and the maximum on a 0.1 nm grid lies within 3 nm of λmax.
            let peak = (0..=2000)
                .map(|i| l - 100.0 + 0.1 * i as f64)
                .max_by(|a, b| alpha_band(l, *a, c).total_cmp(&alpha_band(l, *b, c)));
            assert!((peak.unwrap() - l).abs() < 3.0, "{c} {l}: peak at {peak:?}");
        }
    }
}

#[test]
fn droplet_is_half_transparent_at_lambda_mid() {
    // exp(−exp(−2.89·0.5 + 1.08)) = 0.4995: the model's half-transmission point is λmid.
    let d = Droplet::from_type(DropletType::C, 413.0).unwrap().unwrap();
    assert!((d.lambda_mid_nm() - (0.99 * 413.0 + 24.38)).abs() < 1e-9);
    assert!((d.transmittance(d.lambda_mid_nm()) - (-(-1.445f64 + 1.08).exp()).exp()).abs() < 1e-12);
    assert!(d.transmittance(350.0) < 1e-6 && d.transmittance(600.0) > 0.999);
    assert!(Droplet::from_type(DropletType::T, 330.0).unwrap().is_none());
}
