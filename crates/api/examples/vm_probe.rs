use iridis_api::unit_cell::averaged_profile;
use iridis_diffraction::geometry::direction;
use iridis_diffraction::grating::{Normalisation, UnitCell};
use iridis_diffraction::Patch;
use iridis_lab::laser::MetalFresnel;
use iridis_rigorous::{Options, Problem, Profile1d};
use num_complex::Complex64;
use std::f64::consts::TAU;
fn resample(v: &[f64], n: usize) -> Vec<f64> {
    let m = v.len();
    let half = m / 2;
    let coef: Vec<Complex64> = (0..=half).map(|k| {
        let c: Complex64 = v.iter().enumerate().map(|(j, &h)| h * Complex64::from_polar(1.0, -TAU * (k * j) as f64 / m as f64)).sum();
        let w = if k == 0 || (m % 2 == 0 && k == half) { 1.0 } else { 2.0 };
        c * w / m as f64 }).collect();
    (0..n).map(|i| { let t = i as f64 / n as f64; coef.iter().enumerate().map(|(k, c)| (c * Complex64::from_polar(1.0, TAU * k as f64 * t)).re).sum() }).collect()
}
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let spec = &a[1];
    let depth: f64 = a[2].parse().unwrap();
    let theta: f64 = a[3].parse().unwrap();
    let mat = &a[4];
    let patch = iridis_api::surface::load_patch(spec, &Default::default(), &iridis_api::Quiet).unwrap();
    let peak = iridis_api::surface::dominant_period(&patch).unwrap();
    let bins = ((peak.period_nm / patch.dx) as usize / 2 * 2).max(4);
    let h = resample(&averaged_profile(&patch, peak.period_nm, peak.orientation_deg, bins), 256);
    let (lo, hi) = h.iter().fold((1e9f64, -1e9f64), |(a, b), &x| (a.min(x), b.max(x)));
    let period = peak.period_nm;
    let heights: Vec<f64> = h.iter().map(|v| (v - 0.5 * (lo + hi)) / (0.5 * (hi - lo)) * depth * period).collect();
    let stack: iridis_thinfilm::Stack = format!("air | {mat}").parse().unwrap();
    let f = MetalFresnel::new(stack.substrate, 380.0, 780.0).unwrap();
    let rows: Vec<f64> = heights.iter().chain(&heights).copied().collect();
    let p2 = Patch::from_row_major(2, 256, period / 256.0, period / 256.0, &rows).unwrap();
    let cell = UnitCell::new(&p2, 380.0).unwrap();
    let prof = Profile1d { period_nm: period, heights_nm: heights };
    for l in (0..=40).map(|i| 380.0 + 10.0 * i as f64) {
        let rig = iridis_rigorous::solve_1d(&prof, &Problem::new(l, theta.to_radians(), 0.0, f.index(l)), &Options::default()).unwrap();
        let sc = cell.efficiencies(direction(theta.to_radians(), 0.0), l, &f, Normalisation::Energy).unwrap();
        print!("{l} M{} ", rig.convergence.orders[0]);
        for o in &rig.orders {
            let s = sc.orders.iter().find(|q| q.m == o.m as i64).map_or(0.0, |q| q.efficiency.unpolarized);
            print!(" m{}({:.0}°) {:.4}/{:.4}[te {:.4} tm {:.4}]", o.m, o.theta_deg, o.efficiency.unpolarized, s, o.efficiency.te, o.efficiency.tm);
        }
        println!();
    }
}
