//! Colour tables against the direct evaluation (issue 17: the fast film path must stay within mean ΔE00 0.1
//! and 99th percentile 0.5 of the 81-sample colour): every case is evaluated directly on a grid of angles and
//! offsets that falls between the table's nodes, over the whole domain (0°–89.5°, the stated offsets), and
//! compared as displayed (the brightest reflected colour at Y = 1; the transmitted colour likewise).

use iridis_color::Xyz;
use iridis_thinfilm::accuracy::DeltaEStats;
use iridis_thinfilm::spectral::{dense_weights, exposure_for};
use iridis_thinfilm::table::{FilmTable, TableGrid};
use iridis_thinfilm::Stack;
use rayon::prelude::*;

/// (stack, lowest and highest offset): the GPU tests' films, soap films up to 5 µm, absorbing stacks.
const CASES: &[(&str, f64, f64)] = &[
    ("air | water 500nm | air", -400.0, 400.0), // the benchmark's frame: 100–900 nm
    ("air | water 750nm | air", -750.0, 750.0), // 0–1500 nm
    ("air | water 2000nm | air", -100.0, 100.0),
    ("air | water 5000nm | air", -100.0, 100.0), // fringes dense in angle
    ("air | gasoline 216nm | water 220nm | asphalt", -100.0, 100.0),
    ("air | Si 108nm | glass", -50.0, 50.0),
    ("air | Au 30nm | glass", -20.0, 20.0),
    ("air | n=1.38 100nm | n=0.2+3.4i", -100.0, 300.0),
];

/// The 20-layer quarter-wave mirror of the GPU tests.
fn mirror() -> String {
    let mut s = "air".to_string();
    for _ in 0..10 {
        s += " | n=2.35 58.5nm | n=1.38 99.6nm";
    }
    s + " | glass"
}

/// The direct (81-sample) colours over `angles × offsets` points placed between any table's nodes.
struct Direct {
    points: Vec<(f64, f64)>,
    r: Vec<Xyz>,
    t: Vec<Xyz>,
}

fn direct(stack: &Stack, lo: f64, hi: f64) -> Direct {
    let w = dense_weights();
    let (na, no) = (180, if hi > lo { 41 } else { 1 });
    let points: Vec<(f64, f64)> = (0..no)
        .flat_map(|j| {
            (0..na).map(move |i| {
                // 0°–89.5° and the offsets, off the node positions (an irrational fraction of a step).
                let theta = (89.5 * (i as f64 + 0.3137) / na as f64).to_radians();
                let o = if no > 1 { lo + (hi - lo) * (j as f64 + 0.271) / no as f64 } else { lo };
                (theta, o)
            })
        })
        .collect();
    let (r, t): (Vec<Xyz>, Vec<Xyz>) = points
        .par_iter()
        .map(|&(theta, o)| {
            let (r, t): (Vec<f64>, Vec<f64>) = w
                .wavelengths_nm()
                .iter()
                .map(|&l| {
                    let x = stack.evaluate_offset(l, theta, o).unwrap();
                    (x.r(), x.t())
                })
                .unzip();
            (w.integrate(&r), w.integrate(&t))
        })
        .unzip();
    Direct { points, r, t }
}

/// A table of `density` nodes per period against the direct colours: (grid, reflected stats, transmitted stats).
fn compare_with(stack: &Stack, lo: f64, hi: f64, density: f64, d: &Direct) -> (TableGrid, DeltaEStats, DeltaEStats) {
    let w = dense_weights();
    let grid = TableGrid::with_density(stack, w.wavelengths_nm(), (lo, hi), density).unwrap();
    let table = FilmTable::build(stack, &w, grid).unwrap();
    let (r_table, t_table): (Vec<Xyz>, Vec<Xyz>) =
        d.points.iter().map(|&(theta, o)| table.lookup(theta.cos(), o)).unzip();
    let r = DeltaEStats::between(&r_table, &d.r, exposure_for(&d.r));
    let t = if d.t.iter().any(|x| x.y > 1e-6) {
        DeltaEStats::between(&t_table, &d.t, exposure_for(&d.t))
    } else {
        DeltaEStats::of(vec![])
    };
    (grid, r, t)
}

/// Table against direct over `angles × offsets` points placed between nodes: (reflected, transmitted) stats.
fn compare(stack: &Stack, lo: f64, hi: f64, density: f64) -> (TableGrid, DeltaEStats, DeltaEStats) {
    compare_with(stack, lo, hi, density, &direct(stack, lo, hi))
}

#[test]
fn tables_meet_the_colour_bound() {
    let mirror = mirror();
    let mut cases: Vec<(&str, f64, f64)> = CASES.to_vec();
    // The mirror's offset moves 20 interfaces, so its fringes are dense in offset: ±40 nm is 755 offset nodes
    // and 14 s of table build (2-core VM), ±10 nm a quarter of both. The bound is one of interpolation between
    // neighbouring nodes, the same at any offset: the full range with `IRIDIS_EXHAUSTIVE=1` (README, "Tests").
    let mirror_offset = if std::env::var("IRIDIS_EXHAUSTIVE").as_deref() == Ok("1") { 40.0 } else { 10.0 };
    cases.push((&mirror, -mirror_offset, mirror_offset));
    let mut worst = (0.0f64, 0.0f64);
    for (s, lo, hi) in cases {
        let stack = Stack::parse(s).unwrap();
        let (g, r, t) = compare(&stack, lo, hi, iridis_thinfilm::table::NODES_PER_PERIOD);
        eprintln!("{s:48} {lo:+5}…{hi:+5} nm: {:4} × {:3} nodes; R {r}; T {t}", g.cos_nodes, g.offset_nodes);
        for x in [r, t] {
            worst = (worst.0.max(x.mean), worst.1.max(x.p99));
        }
    }
    eprintln!("worst mean {:.4}, worst p99 {:.4}", worst.0, worst.1);
    // Issue 17's bound is mean 0.1, p99 0.5; measured with 48 nodes per period (2026-11-24): worst mean 0.014
    // (gold's transmission), worst p99 0.28 (a 5 µm soap film's transmission at grazing incidence).
    assert!(worst.0 < 0.02 && worst.1 < 0.35, "worst mean {}, p99 {}", worst.0, worst.1);
}

#[test]
fn the_error_falls_with_the_node_density() {
    // Bilinear interpolation: the error of a smooth function falls as the square of the step. From 4 to 16
    // nodes per period the mean ΔE00 must fall by well over 4 (16 for a pure quadratic law).
    let stack = Stack::parse("air | water 750nm | air").unwrap();
    // The direct colours do not depend on the table: evaluated once for the three densities.
    let direct = direct(&stack, -750.0, 750.0);
    let m: Vec<f64> = [4.0, 8.0, 16.0]
        .iter()
        .map(|&d| {
            let (g, r, _) = compare_with(&stack, -750.0, 750.0, d, &direct);
            eprintln!("{d:4} nodes per period: {} × {} nodes, R {r}", g.cos_nodes, g.offset_nodes);
            r.mean
        })
        .collect();
    assert!(m[0] > m[1] && m[1] > m[2] && m[0] / m[2] > 4.0, "{m:?}");
}
