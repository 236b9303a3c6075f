//! The unit tests of src/energy.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::energy::*;

#[test]
fn a_smooth_mirror_reflects_everything_and_schlick_averages_to_1_21() {
    // α → 0: the lobe is a mirror, G = 1: E_0 = 1 at every angle, E_1 = (1 − μ)^5.
    for mu in [0.2, 0.5, 1.0] {
        let (e0, e1) = albedo(0.0, mu);
        assert!((e0 - 1.0).abs() < 1e-3, "E_0({mu}) = {e0}");
        assert!((e1 - (1.0 - mu).powi(5)).abs() < 1e-3, "E_1({mu}) = {e1}");
    }
    // 2∫(1 − μ)^5 μ dμ = 1/21 on the table's trapezoid rule.
    let ([_, _], [a0, a1]) = lookup(0.0, 0.5);
    assert!((a0 - 1.0).abs() < 2e-3 && (a1 - 1.0 / 21.0).abs() < 2e-3, "{a0} {a1}");
}

#[test]
fn rough_ggx_albedo_matches_a_brute_force_integral() {
    // Single-scattering GGX albedo at α = 1, normal incidence (where single scattering loses most): the
    // half-vector quadrature against a brute-force integral over ω_i on a (μ_i, φ) grid.
    let (e0, _) = albedo(1.0, 1.0);
    let a2 = alpha2(1.0);
    let (mut s, n) = (0.0, 400);
    for i in 0..n {
        let mu_i = (i as f64 + 0.5) / n as f64;
        for j in 0..n {
            let phi = std::f64::consts::TAU * (j as f64 + 0.5) / n as f64;
            let si = (1.0 - mu_i * mu_i).sqrt();
            let wi = [si * phi.cos(), si * phi.sin(), mu_i];
            let h = [wi[0] / 2.0, wi[1] / 2.0, (wi[2] + 1.0) / 2.0];
            let l = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
            let nh = h[2] / l;
            let f = ggx_d(a2, nh) * smith_g1(a2, mu_i) * smith_g1(a2, 1.0) / (4.0 * mu_i);
            s += f * mu_i * (1.0 / n as f64) * (std::f64::consts::TAU / n as f64);
        }
    }
    assert!((e0 - s).abs() < 5e-3, "table {e0}, brute force {s}");
}
