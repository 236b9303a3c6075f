use iridis_rigorous::*;
use num_complex::Complex64 as C;
use std::time::Instant;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ratio: f64 = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(0.1);
    let metal = args.get(2).map(|s| s == "metal").unwrap_or(true);
    let lam: f64 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(550.0);
    let th: f64 = args.get(4).map(|s| s.parse().unwrap()).unwrap_or(30.0);
    let period = 1000.0;
    let a = ratio * period;
    let prof = sample_1d(period, 256, |x| a * (2.0 * std::f64::consts::PI * x / period).sin());
    let n2 = if metal { Problem::index_from_permittivity(C::new(-20.0, 1.0)) } else { C::new(1.5, 0.0) };
    let p = Problem::new(lam, th.to_radians(), 0.0, n2);
    for m in [5usize, 8, 12, 16, 24, 32, 48, 64] {
        let t = Instant::now();
        let opts = Options { fixed_orders: Some(m), ..Options::default() };
        let s = solve_1d(&prof, &p, &opts).unwrap();
        let dt = t.elapsed().as_secs_f64();
        let effs: Vec<String> =
            s.orders.iter().map(|o| format!("{}:{:.6}/{:.6}", o.m, o.efficiency.te, o.efficiency.tm)).collect();
        println!(
            "M={} err={:.2e} R={:.6}/{:.6} T={:.6}/{:.6} t={:.3}s {}",
            s.convergence.orders[0],
            s.convergence.estimated_error,
            s.reflected_total.te,
            s.reflected_total.tm,
            s.transmitted_total.te,
            s.transmitted_total.tm,
            dt,
            effs.join(" ")
        );
    }
    let t = Instant::now();
    let s = solve_1d(&prof, &p, &Options::default()).unwrap();
    println!("auto: {:?} {:.3}s", s.convergence, t.elapsed().as_secs_f64());
}
