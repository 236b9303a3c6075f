//! `cargo run --release -p iridis-rigorous --example convergence`: the convergence tables of docs/rigorous.md
//! (efficiency of every propagating order against the truncation M, metal ε = −20 + 1i, TE and TM).
use iridis_rigorous::*;
use num_complex::Complex64 as C;
use std::f64::consts::PI;

fn table_1d(ratio: f64, lam: f64, theta: f64) {
    let period = 1000.0;
    let g = sample_1d(period, 256, |x| ratio * period * (2.0 * PI * x / period).sin());
    let p = Problem::new(lam, theta.to_radians(), 0.0, Problem::index_from_permittivity(C::new(-20.0, 1.0)));
    println!("\n1-D sine, metal, a/Λ = {ratio}, λ = {lam} nm, θ_i = {theta}°");
    let mut header = false;
    for m in [3usize, 4, 6, 8, 12, 16, 24, 32, 48] {
        let s = solve_1d(&g, &p, &Options { fixed_orders: Some(m), ..Options::default() }).unwrap();
        if !header {
            let cols: Vec<String> = s.orders.iter().map(|o| format!("m = {} TE / TM", o.m)).collect();
            println!("| M (compared with) | {} | estimated error |", cols.join(" | "));
            println!("|---|{}---|", "---|".repeat(cols.len()));
            header = true;
        }
        let cols: Vec<String> =
            s.orders.iter().map(|o| format!("{:.6} / {:.6}", o.efficiency.te, o.efficiency.tm)).collect();
        println!(
            "| {} ({}) | {} | {:.1e} |",
            s.convergence.orders[0],
            s.convergence.compared_with[0],
            cols.join(" | "),
            s.convergence.estimated_error
        );
    }
}

fn table_2d() {
    let period = 1000.0;
    let k = 2.0 * PI / period;
    let g = sample_2d(period, period, 32, 32, |x, y| 50.0 * ((k * x).sin() + (k * y).sin()));
    let p = Problem::new(
        550.0,
        30f64.to_radians(),
        20f64.to_radians(),
        Problem::index_from_permittivity(C::new(-20.0, 1.0)),
    );
    println!("\n2-D crossed sine h = 50 nm (sin Kx + sin Ky), metal, Λ = 1000 nm, λ = 550 nm, θ_i = 30°, φ_i = 20°");
    println!("| M | (0,0) TE / TM | (1,0) TE / TM | (1,1) TE / TM | R TE / TM | estimated error | seconds |");
    println!("|---|---|---|---|---|---|---|");
    for m in [2usize, 3, 4, 5] {
        let t = std::time::Instant::now();
        let s = solve_2d(&g, &p, &Options { fixed_orders: Some(m), ..Options::default() }).unwrap();
        let dt = t.elapsed().as_secs_f64();
        let e = |a: i32, b: i32| {
            s.orders
                .iter()
                .find(|o| o.m == a && o.n == b)
                .map(|o| format!("{:.5} / {:.5}", o.efficiency.te, o.efficiency.tm))
                .unwrap_or_default()
        };
        println!(
            "| {} ({}) | {} | {} | {} | {:.5} / {:.5} | {:.1e} | {:.1} |",
            s.convergence.orders[0],
            s.convergence.compared_with[0],
            e(0, 0),
            e(1, 0),
            e(1, 1),
            s.reflected_total.te,
            s.reflected_total.tm,
            s.convergence.estimated_error,
            dt
        );
    }
}

fn main() {
    table_1d(0.15, 450.0, 30.0);
    table_1d(0.15, 650.0, 0.0);
    table_1d(0.05, 550.0, 30.0);
    if std::env::args().any(|a| a == "--2d") {
        table_2d();
    }
}
