use iridis_rigorous::*;
use num_complex::Complex64 as C;
use std::time::Instant;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ratio: f64 = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(0.1);
    let metal = args.get(2).map(|s| s == "metal").unwrap_or(true);
    let lam: f64 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(550.0);
    let th: f64 = args.get(4).map(|s| s.parse().unwrap()).unwrap_or(30.0);
    let ph: f64 = args.get(5).map(|s| s.parse().unwrap()).unwrap_or(20.0);
    let crossed = args.get(6).map(|s| s == "crossed").unwrap_or(false);
    let period = 1000.0;
    let a = ratio * period;
    let w = 2.0 * std::f64::consts::PI / period;
    let prof1 = sample_1d(period, 64, |x| a * (w * x).sin());
    let prof2 = sample_2d(period, period, if crossed { 32 } else { 1 }, 64, |x, y| {
        if crossed {
            0.5 * a * ((w * x).sin() + (w * y).sin())
        } else {
            a * (w * x).sin()
        }
    });
    let n2 = if metal { Problem::index_from_permittivity(C::new(-20.0, 1.0)) } else { C::new(1.5, 0.0) };
    let p = Problem::new(lam, th.to_radians(), ph.to_radians(), n2);
    if !crossed {
        let s = solve_1d(&prof1, &p, &Options::default()).unwrap();
        let effs: Vec<String> =
            s.orders.iter().map(|o| format!("{}:{:.6}/{:.6}", o.m, o.efficiency.te, o.efficiency.tm)).collect();
        println!(
            "1D R={:.6}/{:.6} T={:.6}/{:.6} {}",
            s.reflected_total.te,
            s.reflected_total.tm,
            s.transmitted_total.te,
            s.transmitted_total.tm,
            effs.join(" ")
        );
    }
    for m in [2usize, 3, 4, 5, 6, 7] {
        let t = Instant::now();
        let opts = Options { fixed_orders: Some(m), ..Options::default_2d() };
        let s = solve_2d(&prof2, &p, &opts).unwrap();
        let dt = t.elapsed().as_secs_f64();
        let effs: Vec<String> = s
            .orders
            .iter()
            .filter(|o| o.n != 0 || o.efficiency.unpolarized > 1e-3)
            .map(|o| format!("({},{}):{:.3e}/{:.3e}", o.m, o.n, o.efficiency.te, o.efficiency.tm))
            .collect();
        let tr: Vec<String> = s
            .transmitted_orders
            .iter()
            .map(|o| format!("({},{}):{:.4e}/{:.4e}", o.m, o.n, o.efficiency.te, o.efficiency.tm))
            .collect();
        println!("  T {}", tr.join(" "));
        println!(
            "M={:?} err={:.2e} R={:.6}/{:.6} T={:.6}/{:.6} t={:.3}s {}",
            s.convergence.orders,
            s.convergence.estimated_error,
            s.reflected_total.te,
            s.reflected_total.tm,
            s.transmitted_total.te,
            s.transmitted_total.tm,
            dt,
            effs.join(" ")
        );
    }
}
