use super::*;
use num_complex::Complex64 as C;
use std::f64::consts::PI;

fn fresnel(n1: f64, n2: C, theta: f64) -> (f64, f64) {
    let c1 = theta.cos();
    let s1 = n1 * theta.sin();
    let c2 = (C::new(1.0, 0.0) - (s1 / n2) * (s1 / n2)).sqrt();
    let rs = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2);
    let rp = (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2);
    (rs.norm_sqr(), rp.norm_sqr())
}

#[test]
fn a_flat_surface_reflects_as_fresnel_says_at_conical_incidence() {
    let flat = sample_1d(700.0, 8, |_| 0.0);
    let flat2 = sample_2d(700.0, 600.0, 4, 4, |_, _| 0.0);
    for (n2, theta, phi) in [
        (C::new(1.5, 0.0), 0.0, 0.0),
        (C::new(1.5, 0.0), 0.5, 0.7),
        (Problem::index_from_permittivity(C::new(-20.0, 1.0)), 0.6, 1.2),
        (C::new(0.2, 3.4), 1.1, 2.5),
    ] {
        let p = Problem { incident_index: 1.2, ..Problem::new(550.0, theta, phi, n2) };
        let (rs, rp) = fresnel(1.2, n2, theta);
        for sol in
            [solve_1d(&flat, &p, &Options::default()).unwrap(), solve_2d(&flat2, &p, &Options::default_2d()).unwrap()]
        {
            let o = sol.orders.iter().find(|o| o.m == 0 && o.n == 0).unwrap();
            assert!((o.efficiency.te - rs).abs() < 1e-12, "{} {}", o.efficiency.te, rs);
            assert!((o.efficiency.tm - rp).abs() < 1e-12, "{} {}", o.efficiency.tm, rp);
            assert!(o.into_p.te < 1e-20 && o.into_s.tm < 1e-20);
            assert!((o.theta_deg - theta.to_degrees()).abs() < 1e-9);
            if n2.im == 0.0 {
                assert!((sol.reflected_total.te + sol.transmitted_total.te - 1.0).abs() < 1e-12);
                assert!((sol.reflected_total.tm + sol.transmitted_total.tm - 1.0).abs() < 1e-12);
            }
        }
    }
}
