//! The unit tests of src/geometry.rs (shading and Fresnel factors), moved here so that `cargo test` compiles the
//! library once.

use iridis_diffraction::geometry::*;
use num_complex::Complex64;

#[test]
fn mirror_at_normal_incidence_has_unit_factor() {
    let n = [0.0, 0.0, 1.0];
    for fresnel in [Fresnel::Schlick { n: 1.5 }, Fresnel::Index { n: Complex64::new(0.2, 3.4) }] {
        let s = Shading { fresnel: std::sync::Arc::new(fresnel), ..Shading::default() };
        assert!((s.factor(500.0, n, n) - 1.0).abs() < 1e-15);
    }
}

#[test]
fn a_bare_substrate_stack_matches_the_single_interface() {
    let stack: iridis_thinfilm::Stack = "air | n=1.5".parse().unwrap();
    let film = FilmFresnel::new(stack).unwrap();
    for c in [1.0, 0.8, 0.3] {
        let exact = fresnel_unpolarised(Complex64::new(1.5, 0.0), c);
        assert!((film.reflectance(550.0, c) - exact).abs() < 1e-12);
    }
}

#[test]
fn exact_fresnel_matches_textbook_values() {
    // Glass n = 1.5 at normal incidence: ((n-1)/(n+1))² = 0.04; Brewster's angle: Rp = 0 so R = Rs/2.
    assert!((fresnel_unpolarised(Complex64::new(1.5, 0.0), 1.0) - 0.04).abs() < 1e-15);
    let tb = 1.5f64.atan();
    let (ci, ct) = (tb.cos(), (1.0 - (tb.sin() / 1.5).powi(2)).sqrt());
    let rs = ((ci - 1.5 * ct) / (ci + 1.5 * ct)).powi(2);
    assert!((fresnel_unpolarised(Complex64::new(1.5, 0.0), ci) - rs / 2.0).abs() < 1e-14);
    // Grazing incidence reflects everything.
    assert!((fresnel_unpolarised(Complex64::new(1.5, 0.0), 0.0) - 1.0).abs() < 1e-12);
}
