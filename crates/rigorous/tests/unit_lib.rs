//! The unit tests of src/lib.rs (the solvers' physics checks and input validation), moved here so that
//! `cargo test` compiles the library once.

use iridis_rigorous::*;
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

/// A small fixed 2-D truncation for fast tests: the smallest M that holds the propagating orders, and M + 2.
fn small_2d() -> Options {
    Options { fixed_orders: Some(1), ..Options::default() }
}

#[test]
fn a_flat_surface_reflects_as_fresnel_says_at_conical_incidence() {
    let flat = sample_1d(700.0, 8, |_| 0.0);
    let flat2 = sample_2d(250.0, 220.0, 4, 4, |_, _| 0.0);
    for (n2, theta, phi) in [
        (C::new(1.5, 0.0), 0.0, 0.0),
        (C::new(1.5, 0.0), 0.5, 0.7),
        (Problem::index_from_permittivity(C::new(-20.0, 1.0)), 0.6, 1.2),
        (C::new(0.2, 3.4), 1.1, 2.5),
    ] {
        let p = Problem { incident_index: 1.2, ..Problem::new(550.0, theta, phi, n2) };
        let (rs, rp) = fresnel(1.2, n2, theta);
        for sol in [solve_1d(&flat, &p, &Options::default()).unwrap(), solve_2d(&flat2, &p, &small_2d()).unwrap()] {
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

fn sine(period: f64, amp: f64) -> Profile1d {
    sample_1d(period, 64, |x| amp * (2.0 * PI * x / period).sin())
}

fn tight() -> Options {
    Options { tolerance: 1e-7, ..Options::default() }
}

#[test]
fn a_lossless_dielectric_grating_conserves_energy() {
    // Deep sine (a/Λ = 0.15) on glass, classical and conical incidence: R + T = 1.
    let g = sine(1000.0, 150.0);
    for (lam, th, ph) in [(450.0, 0.0, 0.0), (550.0, 30.0, 0.0), (650.0, 45.0, 60.0), (500.0, 10.0, 90.0)] {
        let p = Problem::new(lam, f64::to_radians(th), f64::to_radians(ph), C::new(1.5, 0.0));
        let s = solve_1d(&g, &p, &Options::default()).unwrap();
        let e = s.convergence.energy_error.unwrap();
        assert!(e < 1e-9, "R + T − 1 = {e} at {lam} nm {th}° {ph}°");
        assert!(s.transmitted_orders.len() > s.orders.len());
    }
}

#[test]
fn a_lossless_metal_grating_reflects_everything() {
    // ε = −20 exactly (n = 0, k = √20): no loss, no transmitted wave, R = 1 for TE and TM.
    let g = sine(1000.0, 150.0);
    for (lam, th, ph) in [(450.0, 0.0, 0.0), (600.0, 30.0, 0.0), (550.0, 40.0, 30.0)] {
        let p = Problem::new(lam, f64::to_radians(th), f64::to_radians(ph), C::new(0.0, 20f64.sqrt()));
        let s = solve_1d(&g, &p, &Options::default()).unwrap();
        assert!(s.transmitted_orders.is_empty());
        assert!((s.reflected_total.te - 1.0).abs() < 1e-9, "{}", s.reflected_total.te);
        assert!((s.reflected_total.tm - 1.0).abs() < 1e-9, "{}", s.reflected_total.tm);
    }
}

/// The reciprocal configuration of reflected order `o` of a solution: light from `ω_r` of that order.
fn reciprocal(p: &Problem, o: &Order) -> Problem {
    Problem { theta_i_rad: o.theta_deg.to_radians(), phi_i_rad: o.phi_deg.to_radians(), ..p.clone() }
}

/// Reciprocity (Petit 1980, ch. 1; Maystre 1984): the power in order (m, n) with polarisation b, lit from
/// `ω_i` with polarisation a, equals the power in the same order (m, n) with polarisation a, lit from that
/// order's `ω_r` with polarisation b: η^{a→b}_{mn}(ω_i) = η^{b→a}_{mn}(ω_r), s and p of each wave's own plane.
fn check_reciprocity(a: &Solution, solve: impl Fn(&Problem) -> Solution, p: &Problem, tol: f64) -> f64 {
    let mut worst: f64 = 0.0;
    for o in a.orders.iter().filter(|o| o.efficiency.unpolarized > 1e-4) {
        let b = solve(&reciprocal(p, o));
        let back = b.orders.iter().find(|q| q.m == o.m && q.n == o.n).unwrap();
        assert!((back.theta_deg - a.theta_i_deg).abs() < 1e-6);
        let pairs = [
            (o.into_s.te, back.into_s.te),
            (o.into_p.te, back.into_s.tm),
            (o.into_s.tm, back.into_p.te),
            (o.into_p.tm, back.into_p.tm),
        ];
        for (x, y) in pairs {
            let rel = (x - y).abs() / x.max(1e-4);
            worst = worst.max(rel);
            assert!(rel < tol, "order ({}, {}): {x} vs {y}", o.m, o.n);
        }
    }
    worst
}

#[test]
fn order_efficiencies_are_reciprocal_on_an_asymmetric_profile() {
    // Two harmonics with a phase: no mirror symmetry, so η_m(ω_i) ≠ η_{−m}(ω_i) and the test has teeth.
    let period = 800.0;
    let g =
        sample_1d(period, 96, |x| 110.0 * (2.0 * PI * x / period).sin() + 50.0 * (4.0 * PI * x / period + 1.0).sin());
    let metal = Problem::index_from_permittivity(C::new(-20.0, 1.0));
    for (n2, ph) in [(metal, 0.0), (metal, 35.0), (C::new(1.5, 0.0), 20.0)] {
        let p = Problem::new(600.0, 20f64.to_radians(), f64::to_radians(ph), n2);
        let a = solve_1d(&g, &p, &tight()).unwrap();
        // Light from the mirrored azimuth: a symmetric profile would give order −m what order m gets here.
        let mirror = solve_1d(&g, &Problem { phi_i_rad: p.phi_i_rad + PI, ..p.clone() }, &tight()).unwrap();
        let asym = a
            .orders
            .iter()
            .filter_map(|o| {
                mirror.orders.iter().find(|q| q.m == -o.m).map(|q| (o.efficiency.te - q.efficiency.te).abs())
            })
            .fold(0.0, f64::max);
        assert!(asym > 1e-3, "the profile must break the mirror symmetry: {asym}");
        check_reciprocity(&a, |q| solve_1d(&g, q, &tight()).unwrap(), &p, 1e-6);
    }
}

#[test]
fn shallow_perfect_conductor_matches_the_first_order_perturbation() {
    // h = a sin(Kx) on a near-perfect conductor (n + ik = 1000i). First-order perturbation of the Rayleigh
    // expansion (Petit 1980 ch. 1; derivation in docs/rigorous.md, eq. P1–P2):
    //   TE: η_±1 = (k a)² cos θ_i cos θ_±1,   TM: η_±1 = (k a)² (1 − α₀ α_±1)² / (cos θ_i cos θ_±1),
    // α the signed tangential wavevectors over k (α₀ = −sin θ_i). Corrections: O((ka)²) ≈ 1e-4 relative from
    // the next order in a, O(1/|n|) = 1e-3 from the finite conductivity.
    let (period, amp, lam) = (1000.0, 1.0, 550.0);
    let g = sine(period, amp);
    let ka = 2.0 * PI / lam * amp;
    for th in [0.0f64, 30.0] {
        let p = Problem::new(lam, th.to_radians(), 0.0, C::new(0.0, 1000.0));
        let s = solve_1d(&g, &p, &tight()).unwrap();
        let a0 = -th.to_radians().sin();
        for o in s.orders.iter().filter(|o| o.m.abs() == 1) {
            let an = a0 + o.m as f64 * lam / period;
            let (ci, cr) = (th.to_radians().cos(), (1.0 - an * an).sqrt());
            let te = ka * ka * ci * cr;
            let tm = ka * ka * (1.0 - a0 * an).powi(2) / (ci * cr);
            assert!((o.efficiency.te / te - 1.0).abs() < 3e-3, "TE m={} θ={th}: {} vs {te}", o.m, o.efficiency.te);
            assert!((o.efficiency.tm / tm - 1.0).abs() < 3e-3, "TM m={} θ={th}: {} vs {tm}", o.m, o.efficiency.tm);
        }
    }
}

#[test]
fn the_2d_solver_on_a_ridge_profile_agrees_with_the_1d_solver_at_conical_incidence() {
    // Two formulations: the covariant 4N eigenproblem of a(x, y) and the scalar E_y/H_y one of a(x).
    let (period, amp) = (700.0, 30.0);
    let g1 = sine(period, amp);
    let g2 = sample_2d(period, 500.0, 1, 64, |x, _| amp * (2.0 * PI * x / period).sin());
    let metal = Problem::index_from_permittivity(C::new(-20.0, 1.0));
    for n2 in [metal, C::new(1.5, 0.0)] {
        let p = Problem::new(600.0, 25f64.to_radians(), 40f64.to_radians(), n2);
        let a = solve_1d(&g1, &p, &tight()).unwrap();
        let b = solve_2d(&g2, &p, &Options { fixed_orders: Some(2), ..Options::default() }).unwrap();
        for o in &a.orders {
            let q = b.orders.iter().find(|q| q.m == o.m && q.n == 0).unwrap();
            assert!((q.theta_deg - o.theta_deg).abs() < 1e-9 && (q.phi_deg - o.phi_deg).abs() < 1e-9);
            for (x, y) in [(o.efficiency.te, q.efficiency.te), (o.efficiency.tm, q.efficiency.tm)] {
                assert!((x - y).abs() < 1e-3 * x.max(1e-3), "order {}: {x} vs {y}", o.m);
            }
        }
        // A profile without y dependence sends nothing into orders n ≠ 0.
        assert!(b.orders.iter().filter(|q| q.n != 0).all(|q| q.efficiency.unpolarized < 1e-20));
    }
}

#[test]
fn a_crossed_grating_conserves_energy_and_is_reciprocal() {
    // h = a (sin Kx + sin Ky) + a/2 sin(Kx + Ky + 1): no symmetry; glass (lossless) and metal.
    let (px, py) = (900.0, 1000.0);
    let g = sample_2d(px, py, 16, 16, |x, y| {
        let (u, v) = (2.0 * PI * x / px, 2.0 * PI * y / py);
        40.0 * (u.sin() + v.sin()) + 20.0 * (u + v + 1.0).sin()
    });
    let opts = Options { fixed_orders: Some(2), ..Options::default() };
    let glass = Problem::new(650.0, 20f64.to_radians(), 30f64.to_radians(), C::new(1.5, 0.0));
    let s = solve_2d(&g, &glass, &opts).unwrap();
    assert!(s.transmitted_orders.iter().any(|o| o.n != 0 && o.m != 0 && o.efficiency.unpolarized > 1e-3));
    let e = s.convergence.energy_error.unwrap();
    assert!(e < 1e-6, "R + T − 1 = {e}");
    let metal = Problem { substrate_index: Problem::index_from_permittivity(C::new(-20.0, 1.0)), ..glass.clone() };
    let a = solve_2d(&g, &metal, &opts).unwrap();
    // At a fixed truncation the reciprocal problem's order window is shifted, so reciprocity holds to the
    // truncation error (the record's estimate), not to rounding.
    let tol = 10.0 * a.convergence.estimated_error.max(1e-4);
    // The three brightest orders with both m and n non-zero among them (each reciprocal solve is a 2-D solve).
    let mut a = a;
    a.orders.sort_by(|x, y| y.efficiency.unpolarized.total_cmp(&x.efficiency.unpolarized));
    let diagonal = a.orders.iter().position(|o| o.m != 0 && o.n != 0).unwrap();
    let keep = [a.orders[0].clone(), a.orders[1].clone(), a.orders[diagonal].clone()];
    assert!(keep[2].efficiency.unpolarized > 1e-3);
    a.orders = keep.to_vec();
    check_reciprocity(&a, |q| solve_2d(&g, q, &opts).unwrap(), &metal, tol);
}

#[test]
fn bad_input_gets_a_specific_error() {
    let g = sine(1000.0, 10.0);
    let p = Problem::new(550.0, 0.0, 0.0, C::new(1.5, 0.0));
    let o = Options::default();
    let err = |g: &Profile1d, p: &Problem, o: &Options| solve_1d(g, p, o).unwrap_err();
    assert_eq!(err(&Profile1d { period_nm: 0.0, ..g.clone() }, &p, &o), RigorousError::InvalidPeriod(0.0));
    assert_eq!(err(&g, &Problem { wavelength_nm: -1.0, ..p.clone() }, &o), RigorousError::InvalidWavelength(-1.0));
    let mut nan = g.clone();
    nan.heights_nm[5] = f64::NAN;
    assert!(matches!(err(&nan, &p, &o), RigorousError::NonFiniteHeight { index: 5, .. }));
    assert_eq!(err(&Profile1d { heights_nm: vec![0.0, 1.0], ..g.clone() }, &p, &o), RigorousError::TooFewSamples(2));
    assert_eq!(
        err(&g, &Problem { substrate_index: C::new(1.5, -0.1), ..p.clone() }, &o),
        RigorousError::NegativeExtinction(-0.1)
    );
    assert!(matches!(err(&g, &Problem { theta_i_rad: 1.6, ..p.clone() }, &o), RigorousError::InvalidPolarAngle(_)));
    assert!(matches!(
        err(&g, &Problem { incident_index: 0.0, ..p.clone() }, &o),
        RigorousError::InvalidIncidentIndex(_)
    ));
    assert!(matches!(err(&g, &p, &Options { tolerance: 0.0, ..o }), RigorousError::InvalidTolerance(_)));
    let bad2 = Profile2d { period_x_nm: 500.0, period_y_nm: 500.0, rows: 4, cols: 4, heights_nm: vec![0.0; 15] };
    assert_eq!(solve_2d(&bad2, &p, &o).unwrap_err(), RigorousError::GridSize { rows: 4, cols: 4, len: 15 });
    // Messages name the quantity and the unit.
    assert!(RigorousError::InvalidPeriod(0.0).to_string().contains("nanometres"));
}

#[test]
fn an_unmet_tolerance_is_reported_not_hidden() {
    // A deep metal grating with a cap of M = 6: the search stops at the cap and says so.
    let g = sine(1000.0, 150.0);
    let p = Problem::new(450.0, 0.0, 0.0, Problem::index_from_permittivity(C::new(-20.0, 1.0)));
    let s =
        solve_1d(&g, &p, &Options { tolerance: 1e-12, min_orders: Some(4), max_orders: Some(6), ..Options::default() })
            .unwrap();
    assert!(s.convergence.capped && !s.convergence.met);
    assert!(s.convergence.estimated_error > 1e-12);
    assert_eq!(s.convergence.orders, [6, 0]);
    // The default search meets its tolerance on the same grating, with a smaller error estimate than asked.
    let s = solve_1d(&g, &p, &Options::default()).unwrap();
    assert!(s.convergence.met && s.convergence.estimated_error <= 1e-3 && !s.convergence.capped);
}

#[test]
fn the_batch_gives_the_answers_of_single_solves_in_order() {
    let g = sine(1000.0, 80.0);
    let metal = Problem::index_from_permittivity(C::new(-20.0, 1.0));
    let problems: Vec<Problem> =
        (0..6).map(|i| Problem::new(450.0 + 40.0 * i as f64, (5.0 * i as f64).to_radians(), 0.0, metal)).collect();
    let batch = solve_batch(&Grating::OneD(g.clone()), &problems, &Options::default());
    for (p, b) in problems.iter().zip(batch) {
        let b = b.unwrap();
        let s = solve_1d(&g, p, &Options::default()).unwrap();
        assert_eq!(b.wavelength_nm, p.wavelength_nm);
        assert_eq!(b.reflected_total, s.reflected_total);
    }
}

#[test]
fn a_diagonal_ridge_in_a_square_cell_agrees_with_the_rotated_1d_grating() {
    // h = a sin(2π(x + y)/Λ) in a Λ × Λ cell is a 1-D sine of period Λ/√2 along (1, 1)/√2: the 2-D solver
    // (both slopes non-zero, every Toeplitz block coupled) against the 1-D solver in the rotated frame, where
    // the light's azimuth is φ − 45° and order p is the cell's order (p, p).
    let (period, amp) = (1000.0, 30.0);
    let g2 = sample_2d(period, period, 16, 16, |x, y| amp * (2.0 * PI * (x + y) / period).sin());
    let d = period / 2f64.sqrt();
    let g1 = sine(d, amp);
    let metal = Problem::index_from_permittivity(C::new(-20.0, 1.0));
    for (n2, th, ph) in [(metal, 20.0f64, 10.0f64), (C::new(1.5, 0.0), 35.0, 70.0)] {
        let p2 = Problem::new(600.0, th.to_radians(), ph.to_radians(), n2);
        let p1 = Problem { phi_i_rad: (ph - 45.0).to_radians(), ..p2.clone() };
        let a = solve_1d(&g1, &p1, &tight()).unwrap();
        let b = solve_2d(&g2, &p2, &Options { fixed_orders: Some(2), ..Options::default() }).unwrap();
        assert!(a.orders.len() >= 2);
        for (ours, theirs) in [(&a.orders, &b.orders), (&a.transmitted_orders, &b.transmitted_orders)] {
            for o in ours.iter() {
                let q = theirs.iter().find(|q| q.m == o.m && q.n == o.m).unwrap();
                assert!((q.theta_deg - o.theta_deg).abs() < 1e-9);
                let dphi = (q.phi_deg - o.phi_deg - 45.0).rem_euclid(360.0);
                assert!(dphi.min(360.0 - dphi) < 1e-9 || o.theta_deg < 1e-9);
                for (x, y) in [(o.efficiency.te, q.efficiency.te), (o.efficiency.tm, q.efficiency.tm)] {
                    // Measured: 3e-9 at M = 2 … 4; the two formulations share no matrix.
                    assert!((x - y).abs() < 1e-6 * x.max(1e-3), "order {}: 1-D {x} vs 2-D {y}", o.m);
                }
            }
        }
        // Nothing goes into orders off the diagonal.
        assert!(b.orders.iter().filter(|q| q.m != q.n).all(|q| q.efficiency.unpolarized < 1e-20));
    }
}

fn q(n: C, s: f64) -> C {
    let v = (n * n - s * s).sqrt();
    if v.im < 0.0 {
        -v
    } else {
        v
    }
}

/// Reflectance of a single film on a substrate (Airy's sum; Born & Wolf §1.6.4), TE and TM.
fn airy(n0: f64, n1: C, d_nm: f64, n2: C, lam: f64, theta: f64) -> (f64, f64) {
    let s = n0 * theta.sin();
    let (q0, q1, q2) = (q(C::new(n0, 0.0), s), q(n1, s), q(n2, s));
    let ph = (C::new(0.0, 2.0) * q1 * (2.0 * PI / lam * d_nm)).exp();
    let te = |qa: C, qb: C| (qa - qb) / (qa + qb);
    let tm = |na: C, qa: C, nb: C, qb: C| (nb * nb * qa - na * na * qb) / (nb * nb * qa + na * na * qb);
    let n0c = C::new(n0, 0.0);
    let (a, b) = (te(q0, q1), te(q1, q2));
    let rs = (a + b * ph) / (1.0 + a * b * ph);
    let (a, b) = (tm(n0c, q0, n1, q1), tm(n1, q1, n2, q2));
    let rp = (a + b * ph) / (1.0 + a * b * ph);
    (rs.norm_sqr(), rp.norm_sqr())
}

#[test]
fn a_coated_flat_substrate_reflects_as_airy_says() {
    let flat = sample_1d(700.0, 8, |_| 0.0);
    let flat2 = sample_2d(250.0, 220.0, 4, 4, |_, _| 0.0);
    let metal = Problem::index_from_permittivity(C::new(-20.0, 1.0));
    for (n1, d, n2, theta, phi) in [
        (C::new(2.0, 0.0), 80.0, metal, 0.4, 0.3),
        (C::new(0.2, 3.4), 20.0, C::new(1.5, 0.0), 0.9, 1.9),
        (C::new(1.33, 0.0), 635.0, C::new(1.0, 0.0), 0.0, 0.0),
    ] {
        let p =
            Problem { coatings: vec![Coating { thickness_nm: d, index: n1 }], ..Problem::new(550.0, theta, phi, n2) };
        let (rs, rp) = airy(1.0, n1, d, n2, 550.0, theta);
        for sol in [solve_1d(&flat, &p, &Options::default()).unwrap(), solve_2d(&flat2, &p, &small_2d()).unwrap()] {
            let o = &sol.orders[sol.orders.iter().position(|o| o.m == 0 && o.n == 0).unwrap()];
            assert!((o.efficiency.te - rs).abs() < 1e-12, "TE {} vs {rs}", o.efficiency.te);
            assert!((o.efficiency.tm - rp).abs() < 1e-12, "TM {} vs {rp}", o.efficiency.tm);
        }
    }
}

#[test]
fn coatings_of_the_substrate_itself_or_of_zero_thickness_change_nothing() {
    // A layer of the substrate's own index (any thickness) or of zero thickness is no layer at all: the
    // interfaces it adds carry no jump, the layer's up- and down-going modes must cancel exactly.
    let g = sine(1000.0, 120.0);
    let metal = Problem::index_from_permittivity(C::new(-20.0, 1.0));
    for n2 in [metal, C::new(1.5, 0.0)] {
        let bare = Problem::new(500.0, 0.5, 0.4, n2);
        let a = solve_1d(&g, &bare, &Options { fixed_orders: Some(12), ..Options::default() }).unwrap();
        for coating in
            [Coating { thickness_nm: 60.0, index: n2 }, Coating { thickness_nm: 0.0, index: C::new(2.0, 0.1) }]
        {
            let p = Problem { coatings: vec![coating], ..bare.clone() };
            let b = solve_1d(&g, &p, &Options { fixed_orders: Some(12), ..Options::default() }).unwrap();
            for (x, y) in a.orders.iter().zip(&b.orders) {
                assert!((x.efficiency.te - y.efficiency.te).abs() < 1e-9, "{:?} {:?}", x, y);
                assert!((x.efficiency.tm - y.efficiency.tm).abs() < 1e-9, "{:?} {:?}", x, y);
            }
        }
    }
}

#[test]
fn a_coated_lossless_grating_conserves_energy() {
    // Two dielectric coatings (80 nm n = 2.0, 150 nm n = 1.38) on a deep sine on glass, conical incidence.
    let g = sine(1000.0, 120.0);
    let p = Problem {
        coatings: vec![
            Coating { thickness_nm: 80.0, index: C::new(2.0, 0.0) },
            Coating { thickness_nm: 150.0, index: C::new(1.38, 0.0) },
        ],
        ..Problem::new(550.0, 0.6, 0.7, C::new(1.5, 0.0))
    };
    let s = solve_1d(&g, &p, &Options::default()).unwrap();
    assert!(s.convergence.met);
    let e = s.convergence.energy_error.unwrap();
    assert!(e < 1e-9, "R + T − 1 = {e}");
}

#[test]
fn rayleigh_anomalies_and_a_weakly_absorbing_substrate_are_handled() {
    // λ = Λ at normal incidence: orders ±1 leave at grazing (k_z = 0), left to the eigenmodes; the answer stays
    // continuous and conserves energy. A substrate with k = 1e-9 reflects as the lossless one (to 1e-9) and,
    // by the convention of PHYSICS.md, transmits nothing: what the lossless one transmits is absorbed.
    let g = sine(1000.0, 80.0);
    for lam in [999.999, 1000.0, 1000.001] {
        let lossless = solve_1d(&g, &Problem::new(lam, 0.0, 0.0, C::new(1.5, 0.0)), &Options::default()).unwrap();
        assert!(lossless.convergence.energy_error.unwrap() < 1e-8, "{lam}: {:?}", lossless.convergence);
        let lossy = solve_1d(&g, &Problem::new(lam, 0.0, 0.0, C::new(1.5, 1e-9)), &Options::default()).unwrap();
        assert!(lossy.transmitted_orders.is_empty());
        assert!((lossy.reflected_total.te - lossless.reflected_total.te).abs() < 1e-9);
        assert!((lossy.reflected_total.tm - lossless.reflected_total.tm).abs() < 1e-9);
        assert!((lossy.absorbed.te - lossless.transmitted_total.te).abs() < 1e-8);
    }
    let near = |lam: f64| {
        solve_1d(&g, &Problem::new(lam, 0.0, 0.0, C::new(1.5, 0.0)), &Options::default()).unwrap().reflected_total
    };
    assert!((near(1000.0).te - near(1000.001).te).abs() < 1e-5);
}

/// A cell that repeats a period k times couples only every k-th order: solved whole, the truncation search saw
/// no change between ±8 and ±12 (the true period's ±1) and stopped there with R + T = 104.9 % (an audit's
/// 8 × 160 nm sine). It is solved on one repeat: the same efficiencies as the period alone, orders numbered in
/// the cell's (m = k·m'), `cell_repeats` saying so; along both axes for a crossed grid.
#[test]
fn a_cell_of_repeats_is_solved_on_one_and_numbered_in_the_cells_orders() {
    let one = sine(500.0, 60.0);
    let tiled = Profile1d { period_nm: 2000.0, heights_nm: one.heights_nm.repeat(4) };
    let p = Problem::new(550.0, 20f64.to_radians(), 0.0, C::new(1.5, 0.0));
    let (a, b) = (solve_1d(&one, &p, &Options::default()).unwrap(), solve_1d(&tiled, &p, &Options::default()).unwrap());
    assert_eq!((a.convergence.cell_repeats, b.convergence.cell_repeats), ([1, 1], [4, 1]));
    assert_eq!(a.orders.len(), b.orders.len());
    for (x, y) in a.orders.iter().zip(&b.orders) {
        assert_eq!(4 * x.m, y.m);
        assert!((x.efficiency.te - y.efficiency.te).abs() < 1e-12 && (x.theta_deg - y.theta_deg).abs() < 1e-9);
    }
    let cell = |rows: usize, cols: usize, tile: usize| {
        sample_2d(600.0 * tile as f64, 700.0 * tile as f64, rows * tile, cols * tile, |x, y| {
            30.0 * (2.0 * PI * x / 600.0).sin() * (2.0 * PI * y / 700.0).cos()
        })
    };
    let q = Problem::new(600.0, 10f64.to_radians(), 0.3, C::new(1.5, 0.0));
    let (a, b) =
        (solve_2d(&cell(8, 8, 1), &q, &small_2d()).unwrap(), solve_2d(&cell(8, 8, 2), &q, &small_2d()).unwrap());
    assert_eq!(b.convergence.cell_repeats, [2, 2]);
    for x in &a.orders {
        let y = b.orders.iter().find(|y| (y.m, y.n) == (2 * x.m, 2 * x.n)).unwrap();
        assert!((x.efficiency.unpolarized - y.efficiency.unpolarized).abs() < 1e-12);
    }
}

/// A lossless answer that loses or makes light is not converged, whatever the change between truncations says:
/// the same 8-period cell with one sample moved by 1 pm (no longer an exact repeat, solved whole) searches on
/// until R + T = 1 within the tolerance, and then agrees with the period alone.
#[test]
fn a_truncation_that_loses_light_is_not_accepted() {
    let one = sample_1d(160.0, 16, |x| 50.0 * (2.0 * PI * x / 160.0).sin());
    let mut heights = one.heights_nm.repeat(8);
    heights[3] += 1e-3;
    let nearly = Profile1d { period_nm: 1280.0, heights_nm: heights };
    let p = Problem::new(550.0, 0.0, 0.0, C::new(1.5, 0.0));
    let (a, b) =
        (solve_1d(&one, &p, &Options::default()).unwrap(), solve_1d(&nearly, &p, &Options::default()).unwrap());
    assert_eq!(b.convergence.cell_repeats, [1, 1]);
    assert!(b.convergence.met && b.convergence.energy_error.unwrap() <= 1e-3, "{:?}", b.convergence);
    let r = |s: &Solution| s.reflected_total.te;
    assert!((r(&a) - r(&b)).abs() < 1e-3 * r(&a).max(1e-3), "{} vs {}", r(&a), r(&b));
}

/// A crossed cell of three 1000 nm periods with 1 pm of noise: its x truncation is pinned at the 2-D cap from the
/// start, so the search raised y alone and compared (8, 7) with (8, 8), a change of 1e-12 that tests nothing of x
/// (TM 1 % off the exact tile, "met"). Not met, and the stated error is at least |R + T − 1|.
#[test]
fn a_comparison_that_leaves_an_axis_untested_is_not_convergence() {
    let (rows, cols) = (4, 300);
    let mut h = Vec::with_capacity(rows * cols);
    for j in 0..rows {
        for i in 0..cols {
            let noise = 1e-3 * (((i * 7 + j * 13) % 11) as f64 / 5.0 - 1.0);
            h.push(80.0 * (2.0 * PI * (i % 100) as f64 / 100.0).sin() + noise);
        }
    }
    let cell = Profile2d { period_x_nm: 3000.0, period_y_nm: 40.0, rows, cols, heights_nm: h };
    let p = Problem::new(550.0, 0.0, 0.0, C::new(1.5, 0.0));
    let s = solve_2d(&cell, &p, &Options::default()).unwrap();
    let c = &s.convergence;
    assert_eq!(c.orders[0], c.compared_with[0], "{c:?}");
    assert!(!c.met && c.estimated_error >= c.energy_error.unwrap(), "{c:?}");
}
