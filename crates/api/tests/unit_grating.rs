//! The unit tests of src/grating.rs: how a patch taken as one unit cell holds its period, against the orders the
//! scalar model computes for it.

use iridis_api::grating::{grating, period_fit, GratingOptions, PeriodFit};
use iridis_api::report::{Collect, Kind};
use iridis_api::surface::Source;

/// The unpolarised efficiencies of the positive orders (n = 0) of a 1 nm deep sine of period 1100 nm on a patch
/// `size` wide, at normal incidence and 500 nm, with what the run noted and found of the period's fit.
fn orders(size: &str) -> (Vec<(i64, f64)>, Vec<String>, PeriodFit) {
    let spec = format!("builtin:sine?size={size}&pixel=50nm&depth=1nm");
    let opts = GratingOptions { wavelengths_nm: vec![500.0], ..Default::default() };
    let said = Collect::default();
    let g = grating(&Source::Spec(spec), &Default::default(), &opts, &said).unwrap();
    let notes = said.take().into_iter().filter(|(k, _)| *k == Kind::Note).map(|(_, t)| t).collect();
    let positive = g.answers[0].orders.iter().filter(|o| o.n == 0 && o.m > 0).map(|o| (o.m, o.efficiency.unpolarized));
    (positive.collect(), notes, g.period_fit.expect("a sine has a dominant period"))
}

/// A shallow grating's orders are the cell's Fourier coefficients of the sine: its +1 order spreads over the
/// cell's orders as `sinc²(L/d − m)` (a plane wave cut at the cell's edges), so the nearest takes
/// `sinc²(δ)` of it — 77.8 % for 8 µm / 1100 nm = 7.27 periods — and a run says so; 7.7 µm (7 periods) tiles.
#[test]
fn a_period_that_does_not_tile_the_cell_spreads_its_orders_by_sinc_squared() {
    let (_, _, share) = period_fit((8000.0, 8000.0), 1100.0, 0.0);
    let delta = 8000.0f64 / 1100.0 - 7.0;
    let closed = ((std::f64::consts::PI * delta).sin() / (std::f64::consts::PI * delta)).powi(2);
    assert!((share - closed).abs() < 1e-12 && (share - 0.778).abs() < 1e-3, "{share}");
    let (spread, notes, fit) = orders("8um");
    let total: f64 = spread.iter().map(|o| o.1).sum();
    let nearest = spread.iter().find(|o| o.0 == 7).unwrap().1;
    assert!((nearest / total - share).abs() < 0.005, "order 7 takes {} of the +1 light", nearest / total);
    assert!(notes.iter().any(|n| n.contains("7.27 times along x") && n.contains("about 78 %")), "{notes:?}");
    // The same figures in --json: the orders' measured share, the period found, the cycles across the cell.
    let json = fit.to_json();
    assert!((json["nearest_order_share"].as_f64().unwrap() - nearest / total).abs() < 0.005, "{json}");
    assert!((json["period_nm"].as_f64().unwrap() - 1100.0).abs() < 1.0 && json["tiles"] == false, "{json}");
    assert!((json["cycles_x"].as_f64().unwrap() - 8000.0 / 1100.0).abs() < 0.01, "{json}");
    let (tiled, notes, fit) = orders("7.7um");
    let total: f64 = tiled.iter().map(|o| o.1).sum();
    assert!(tiled.iter().find(|o| o.0 == 7).unwrap().1 / total > 0.9999);
    assert!(!notes.iter().any(|n| n.contains("not a whole number")), "{notes:?}");
    assert!(fit.to_json()["tiles"] == true && (fit.cycles.0 - 7.0).abs() < 0.01, "{fit:?}");
    // Tiled, the listing still numbers the cell's orders: the note says the period's first orders are ±(7, 0),
    // the order that carries the light above.
    assert!(notes.iter().any(|n| n.contains("7.00 times") && n.contains("its first orders ±(7, 0)")), "{notes:?}");
    // Along a diagonal both directions count: 1.5 periods along x and along y, sinc²(½) = 4/π² each, 0.164 in all.
    let (_, _, diagonal) = period_fit((3000.0, 3000.0), 1000.0 * 2f64.sqrt(), 45.0);
    assert!((diagonal - (4.0 / std::f64::consts::PI.powi(2)).powi(2)).abs() < 1e-9, "{diagonal}");
}

/// The report's map coherence: half the scan's shorter side, at least four of its strongest periods and at least
/// what its pixels carry (4 × the coarser pixel) — a 3 × 3-sample scan of 100 nm pixels had 150 nm chosen and then
/// refused ("shorter than this scan's 100 nm pixels carry"); none for a scan larger than twice the light's 65 µm.
#[test]
fn the_reports_map_coherence_respects_the_pixels() {
    use iridis_api::grating::map_coherence_nm;
    assert_eq!(map_coherence_nm([300.0, 300.0], 0.0, [100.0, 100.0]), Some(400.0));
    assert_eq!(map_coherence_nm([10_000.0, 8_000.0], 1100.0, [50.0, 50.0]), Some(4_400.0));
    assert_eq!(map_coherence_nm([20_000.0, 20_000.0], 1100.0, [50.0, 50.0]), Some(10_000.0));
    assert_eq!(map_coherence_nm([200_000.0, 200_000.0], 1100.0, [50.0, 50.0]), None);
}

/// `--unit-cell auto` gives a sine back as itself: on 100 nm pixels its 1100 nm period is 11 samples, which 32
/// interpolated bins bent (order 2 of Maxwell's equations 34 % low at 30°); the cell now equals one period of
/// the same samples taken whole. A period of 2 pixels, or a peak holding 0.02 % of the height variance (a patch
/// shorter than its period), is refused, not taken as a grating.
#[test]
fn the_auto_unit_cell_of_a_sine_is_the_sine() {
    use iridis_api::grating::GratingMethod;
    let light = 30f64.to_radians();
    let opts = GratingOptions {
        method: GratingMethod::Rigorous,
        light: [light.sin(), 0.0, light.cos()],
        wavelengths_nm: vec![550.0],
        ..Default::default()
    };
    let run = |spec: &str, auto: bool| {
        let o = GratingOptions { unit_cell_auto: auto, ..opts.clone() };
        grating(&Source::Spec(spec.into()), &Default::default(), &o, &Collect::default())
    };
    let efficiencies = |g: &iridis_api::grating::Grating| -> Vec<f64> {
        g.answers[0].orders.iter().map(|o| o.efficiency.unpolarized).collect()
    };
    let whole = run("builtin:sine?size=1100nm&pixel=100nm", false).unwrap();
    let auto = run("builtin:sine?size=10um&pixel=100nm", true).unwrap();
    let (w, a) = (efficiencies(&whole), efficiencies(&auto));
    assert_eq!(w.len(), a.len());
    for (x, y) in w.iter().zip(&a) {
        // The period found is 1100 nm to ± 0.12 nm (1e-4), the efficiencies to as much.
        assert!((x - y).abs() < 1e-4 * x.max(1e-3), "whole cell {w:?}, auto {a:?}");
    }
    let e = run("builtin:sine?size=10um&pixel=500nm", true).unwrap_err().to_string();
    assert!(e.contains("spans 2.0 pixels of 500 nm: too few to take its profile from (at least 4)"), "{e}");
    let e = run("builtin:sine?period=1500nm&size=1000nm&pixel=10nm", true).unwrap_err().to_string();
    assert!(e.contains("holds 0.02 % of the height variance, too little for a period"), "{e}");
}
