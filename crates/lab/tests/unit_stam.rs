//! The unit tests of src/stam.rs (Stam's analytic lattice models), moved here so that `cargo test` compiles the
//! library once.

use iridis_lab::stam::{Bump, Lattice};

#[test]
fn born_form_is_the_small_height_limit_of_the_kirchhoff_coefficient() {
    for bump in [Bump::Rectangular, Bump::Triangular] {
        let l = Lattice { period_x: 1000.0, period_y: Some(700.0), width: 400.0, length: 300.0, height: 1.0, bump };
        for (n, m) in [(1, 0), (2, 1), (-3, 2), (0, 1)] {
            let alpha = 1e-4;
            let exact = l.coefficient(n, m, alpha);
            let born = l.born_coefficient(n, m, alpha);
            assert!((exact - born).norm() < 1e-3 * born.norm(), "{bump:?} ({n},{m}): {exact} vs {born}");
        }
    }
}

#[test]
fn energy_is_conserved_over_all_orders() {
    // Parseval: Σ |c_nm|² = mean |p|² = 1 for p = exp(iα h/H) with |p| = 1.
    for bump in [Bump::Rectangular, Bump::Triangular] {
        let l = Lattice { period_x: 1000.0, period_y: None, width: 500.0, length: 0.0, height: 1.0, bump };
        let alpha = 2.3;
        let total: f64 = (-4000..=4000).map(|n| l.coefficient(n, 0, alpha).norm_sqr()).sum();
        assert!((total - 1.0).abs() < 2e-3, "{bump:?}: Σ|c|² = {total}");
    }
}
