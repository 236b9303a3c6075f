//! In-process benchmark: times the solver on a 1-D and a 2-D case and states the accuracy of what it timed.
//!
//! The accuracy of a timed answer is measured against the same problem solved with more Fourier orders (about 2M
//! in 1-D, M + 1 in 2-D; the C-method converges exponentially on smooth profiles, so that answer is exact to far
//! below the timed one's error); the peer timings of `iridis bench grating`
//! (`iridis_api::grating_bench`) use the reference efficiencies printed here.

use crate::{sample_1d, sample_2d, solve_1d, solve_2d, Options, Problem, Solution};
use num_complex::Complex64;
use serde::Serialize;
use std::time::Instant;

/// One benchmark case: a sine grating (1-D) or a crossed sine grating (2-D), `h = a sin(Kx)` or
/// `h = a/2 (sin Kx + sin Ky)`.
#[derive(Debug, Clone, Serialize)]
pub struct BenchCase {
    pub name: String,
    pub two_d: bool,
    pub period_nm: f64,
    pub amplitude_nm: f64,
    pub wavelength_nm: f64,
    pub theta_i_deg: f64,
    pub phi_i_deg: f64,
    /// Substrate permittivity `[Re ε, Im ε]`.
    pub eps: [f64; 2],
    pub tolerance: f64,
}

impl BenchCase {
    /// The cases: a sine, Λ = 1000 nm, a/Λ = 0.1, λ = 550 nm, θ = 30°, on metal (ε = −20 + 1i) and on
    /// glass (n = 1.5); and a crossed sine on glass (n = 1.5), Λ = 1000 nm both ways, a = 50 nm, λ = 550 nm, θ = 30°, φ = 20°.
    pub fn standard() -> Vec<BenchCase> {
        let metal = BenchCase {
            name: "1-D sine on metal".into(),
            two_d: false,
            period_nm: 1000.0,
            amplitude_nm: 100.0,
            wavelength_nm: 550.0,
            theta_i_deg: 30.0,
            phi_i_deg: 0.0,
            eps: [-20.0, 1.0],
            tolerance: 1e-3,
        };
        let glass = BenchCase { name: "1-D sine on glass".into(), eps: [2.25, 0.0], ..metal.clone() };
        let crossed = BenchCase {
            name: "2-D crossed sine on glass".into(),
            two_d: true,
            amplitude_nm: 50.0,
            phi_i_deg: 20.0,
            ..glass.clone()
        };
        vec![metal, glass, crossed]
    }

    /// The case's grating as the solver takes it: the 1-D sine at 256 samples, the crossed sine on 32 × 32.
    pub fn grating(&self) -> crate::Grating {
        let (p, a) = (self.period_nm, self.amplitude_nm);
        let k = 2.0 * std::f64::consts::PI / p;
        if self.two_d {
            crate::Grating::TwoD(sample_2d(p, p, 32, 32, |x, y| 0.5 * a * ((k * x).sin() + (k * y).sin())))
        } else {
            crate::Grating::OneD(sample_1d(p, 256, |x| a * (k * x).sin()))
        }
    }

    /// The case's light and substrate at `wavelength_nm` (the case's own wavelength, or another one).
    pub fn problem(&self, wavelength_nm: f64) -> Problem {
        Problem::new(
            wavelength_nm,
            self.theta_i_deg.to_radians(),
            self.phi_i_deg.to_radians(),
            Problem::index_from_permittivity(Complex64::new(self.eps[0], self.eps[1])),
        )
    }

    /// The solver's options for the case: the 2-D one may go up to M = 12 (the default cap is 8).
    pub fn options(&self) -> Options {
        if self.two_d {
            Options { max_orders: Some(12), ..Options::default() }
        } else {
            Options::default()
        }
    }

    fn solve(&self, tolerance: f64, fixed_orders: Option<usize>) -> Result<Solution, crate::RigorousError> {
        let problem = self.problem(self.wavelength_nm);
        let opts = Options { tolerance, fixed_orders, ..self.options() };
        match self.grating() {
            crate::Grating::TwoD(g) => solve_2d(&g, &problem, &opts),
            crate::Grating::OneD(g) => solve_1d(&g, &problem, &opts),
        }
    }
}

/// One reflected or transmitted order of the reference answer.
#[derive(Debug, Clone, Serialize)]
pub struct BenchOrder {
    pub m: i32,
    pub n: i32,
    pub transmitted: bool,
    pub te: f64,
    pub tm: f64,
}

/// What one case measured.
#[derive(Debug, Clone, Serialize)]
pub struct BenchReport {
    pub case: BenchCase,
    /// Truncation `[Mx, My]` of the timed answer, and its harmonics `(2Mx+1)(2My+1)`.
    pub orders: [usize; 2],
    pub harmonics: usize,
    /// Wall time of one solve (TE and TM together, the whole automatic order search), best of `repeats`, s.
    pub seconds: f64,
    pub repeats: usize,
    /// The solver's own error estimate of the timed answer.
    pub estimated_error: f64,
    /// Largest error of the timed answer's efficiencies against the reference (relative above η = 1e-3,
    /// absolute ×1e3 below, as the tolerance).
    pub measured_error: f64,
    /// The reference efficiencies (the same problem with more orders), for peers to compare with.
    pub reference: Vec<BenchOrder>,
}

fn orders_of(s: &Solution) -> Vec<BenchOrder> {
    let mk = |o: &crate::Order, transmitted| BenchOrder {
        m: o.m,
        n: o.n,
        transmitted,
        te: o.efficiency.te,
        tm: o.efficiency.tm,
    };
    s.orders.iter().map(|o| mk(o, false)).chain(s.transmitted_orders.iter().map(|o| mk(o, true))).collect()
}

/// Times each case (one thread: the solver does not parallelise a single problem), `repeats` times, and
/// measures the accuracy of the timed answer.
pub fn benchmark(cases: &[BenchCase], repeats: usize) -> Result<Vec<BenchReport>, crate::RigorousError> {
    let mut out = Vec::new();
    for case in cases {
        let mut best = f64::INFINITY;
        let mut sol = None;
        for _ in 0..repeats.max(1) {
            let t = Instant::now();
            let s = case.solve(case.tolerance, None)?;
            best = best.min(t.elapsed().as_secs_f64());
            sol = Some(s);
        }
        let sol = sol.expect("at least one repeat");
        // The reference: a larger truncation than the timed answer's (M + 1 in 2-D, from the pair M − 1, M + 1;
        // about 2M in 1-D).
        let m = sol.convergence.orders[0];
        let reference = orders_of(&case.solve(case.tolerance, Some(if case.two_d { m - 1 } else { 2 * m }))?);
        let timed = orders_of(&sol);
        let mut err: f64 = 0.0;
        for r in &reference {
            let t = timed.iter().find(|t| t.m == r.m && t.n == r.n && t.transmitted == r.transmitted);
            for (want, got) in [(r.te, t.map(|t| t.te)), (r.tm, t.map(|t| t.tm))] {
                err = err.max((got.unwrap_or(0.0) - want).abs() / want.max(1e-3));
            }
        }
        out.push(BenchReport {
            case: case.clone(),
            orders: sol.convergence.orders,
            harmonics: sol.convergence.harmonics,
            seconds: best,
            repeats: repeats.max(1),
            estimated_error: sol.convergence.estimated_error,
            measured_error: err,
            reference,
        });
    }
    Ok(out)
}
