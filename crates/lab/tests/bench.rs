//! The test bench against the grating equation (paper sec. 6.1, Table 1): known gratings must give back their
//! periods.

use crate::common;

use iridis_diffraction::{Patch, Reference};
use iridis_lab::bench::{self, BenchSetup};

/// A 1-D profile along x (or y), `periods` periods of `period_px` samples, `lines` lines across.
fn grating(
    profile: impl Fn(f64) -> f64,
    period_nm: f64,
    period_px: usize,
    periods: usize,
    lines: usize,
    along_y: bool,
) -> Patch {
    let n = period_px * periods;
    let d = period_nm / period_px as f64;
    let line: Vec<f64> = (0..n).map(|i| profile((i % period_px) as f64 / period_px as f64)).collect();
    if along_y {
        // Row 0 is the top (y largest); heights vary with the row.
        let h: Vec<f64> = (0..n * lines).map(|k| line[n - 1 - k / lines]).collect();
        Patch::from_row_major(n, lines, d, d, &h).unwrap()
    } else {
        let h: Vec<f64> = (0..n * lines).map(|k| line[k % n]).collect();
        Patch::from_row_major(lines, n, d, d, &h).unwrap()
    }
}

/// The reference evaluator, its Taylor remainder below 1e-7.
fn reference(patch: &Patch, coherence: f64) -> Reference {
    common::reference(patch, coherence, 1e-7)
}

#[test]
fn blazed_grating_2500nm_at_75deg_gives_its_period() {
    // Paper Table 1: blazed grating of 2500 nm, θ_i = 75°: 2500.34 nm, variance 0.16.
    let patch = grating(|t| 300.0 * t, 2500.0, 50, 8, 2, false);
    let e = reference(&patch, 65_000.0);
    let setup = BenchSetup::new(75f64.to_radians(), 0.0, 1, (380.0, 780.0, 20.0), (20.0, 70.0, 0.05)).unwrap();
    let (_, r) = bench::run(&e, &setup, &|_| {}).unwrap();
    assert_eq!(r.peaks.len(), 21, "a peak at every wavelength");
    let p = r.periodicity;
    assert!((p.mean - 2500.0).abs() < 1.0, "mean {} nm", p.mean);
    assert!(p.variance < 1.0, "variance {} nm²", p.variance);
    for pk in &r.peaks {
        let expected = setup.grating_angle(1.0, pk.wavelength_nm, 2500.0).unwrap();
        assert!((pk.angle_deg - expected).abs() < 0.01, "{pk:?} vs {expected}");
    }
}

#[test]
fn sinusoidal_gratings_500_to_3000nm_within_0_2_percent() {
    for (d, px) in [(500.0, 25), (1000.0, 25), (2000.0, 40), (3000.0, 50)] {
        let patch = grating(|t| 40.0 * (std::f64::consts::TAU * t).sin(), d, px, 8, 2, false);
        let e = reference(&patch, 65_000.0);
        let setup = BenchSetup::new(75f64.to_radians(), 0.0, 1, (380.0, 780.0, 40.0), (-80.0, 80.0, 0.05)).unwrap();
        let (_, r) = bench::run(&e, &setup, &|_| {}).unwrap();
        let rel = (r.periodicity.mean - d).abs() / d;
        assert!(rel < 0.002, "d = {d}: measured {} nm ({:.4} %)", r.periodicity.mean, 100.0 * rel);
        assert!(r.peaks.len() >= 9, "d = {d}: only {} peaks", r.peaks.len());
    }
}

#[test]
fn azimuth_rotates_the_surface_so_periods_along_y_are_measured() {
    let patch = grating(|t| 40.0 * (std::f64::consts::TAU * t).sin(), 1500.0, 30, 8, 2, true);
    let e = reference(&patch, 65_000.0);
    let along_y =
        BenchSetup::new(60f64.to_radians(), 90f64.to_radians(), 1, (400.0, 700.0, 50.0), (-60.0, 80.0, 0.05)).unwrap();
    let (_, r) = bench::run(&e, &along_y, &|_| {}).unwrap();
    assert!((r.periodicity.mean - 1500.0).abs() < 3.0, "{}", r.periodicity.mean);
    // Across the grooves' direction (azimuth 0) the surface is flat: there is no first order to find.
    let along_x = BenchSetup::new(60f64.to_radians(), 0.0, 1, (400.0, 700.0, 50.0), (-60.0, 80.0, 0.05)).unwrap();
    let m = bench::reflectance_matrix(&e, &along_x, &|_| {}).unwrap();
    let off_mirror: f64 = m
        .wavelengths_nm
        .iter()
        .enumerate()
        .flat_map(|(i, &l)| {
            let m = &m;
            let s = &along_x;
            m.angles_deg
                .iter()
                .enumerate()
                .filter(move |(_, &a)| s.frequency(l, a).abs() > 1e-4)
                .map(move |(j, _)| m.row(i)[j])
        })
        .fold(0.0, f64::max);
    assert!(off_mirror < 1e-8, "no diffraction across: {off_mirror}");
}

#[test]
fn two_sub_structures_give_two_ridges() {
    // Xenopeltis-like (paper Figure 7d, Table 1: 605.89 and 536.13 nm across the fingers): half the rows with
    // period 600 nm, half with 540 nm; both fit the 16.2 µm patch a whole number of times.
    let (dx, cols, rows) = (20.0, 810usize, 8usize);
    let h: Vec<f64> = (0..rows * cols)
        .map(|k| {
            let (r, c) = (k / cols, k % cols);
            let d = if r < rows / 2 { 600.0 } else { 540.0 };
            30.0 * (std::f64::consts::TAU * c as f64 * dx / d).sin()
        })
        .collect();
    let patch = Patch::from_row_major(rows, cols, dx, dx, &h).unwrap();
    let e = reference(&patch, 65_000.0);
    let setup = BenchSetup::new(75f64.to_radians(), 0.0, 1, (380.0, 780.0, 20.0), (-80.0, 80.0, 0.05)).unwrap();
    let (_, r) = bench::run(&e, &setup, &|_| {}).unwrap();
    assert_eq!(r.ridges.len(), 2, "{:?}", r.ridges.iter().map(|x| x.period_nm).collect::<Vec<_>>());
    let mut ps: Vec<f64> = r.ridges.iter().map(|x| x.period_nm).collect();
    ps.sort_by(|a, b| a.total_cmp(b));
    assert!((ps[0] - 540.0).abs() < 1.5 && (ps[1] - 600.0).abs() < 1.5, "{ps:?}");
    assert!(r.to_json()["ridges"].as_array().unwrap().len() == 2);
}

#[test]
fn bad_setups_are_refused_with_reasons() {
    let r = |e: iridis_lab::LabError| e.to_string();
    assert!(r(BenchSetup::new(1.0, 0.0, 0, (380.0, 780.0, 5.0), (-80.0, 80.0, 0.1)).unwrap_err()).contains("order 0"));
    assert!(r(BenchSetup::new(1.6, 0.0, 1, (380.0, 780.0, 5.0), (-80.0, 80.0, 0.1)).unwrap_err()).contains("incidence"));
    assert!(
        r(BenchSetup::new(1.0, 0.0, 1, (780.0, 380.0, 5.0), (-80.0, 80.0, 0.1)).unwrap_err()).contains("wavelength")
    );
    assert!(r(BenchSetup::new(1.0, 0.0, 1, (380.0, 780.0, 5.0), (-95.0, 80.0, 0.1)).unwrap_err()).contains("90°"));
}

/// The bench's period along one direction of a built-in surface against the surface analysis' strongest
/// period within 20° of that direction (issue 6: "agrees with `iridis surface info`"), projected onto the
/// plane of incidence.
fn bench_vs_analysis(spec: &str, azimuth_deg: f64, orientation_deg: f64) -> (f64, f64) {
    let hf = iridis_surface::load_surface(spec, &iridis_surface::LoadOptions::default()).unwrap();
    let peaks = iridis_surface::find_peaks(&hf, &iridis_surface::PeakOptions::default());
    // The bench sees a grating vector tilted by Δ from its plane through its projection: period P / cos Δ.
    let tilt = |p: &iridis_surface::Peak| {
        let d = (p.orientation_deg - orientation_deg).rem_euclid(180.0);
        d.min(180.0 - d)
    };
    let strongest = peaks
        .iter()
        .filter(|p| tilt(p) < 20.0)
        .max_by(|a, b| a.power.total_cmp(&b.power))
        .unwrap_or_else(|| panic!("{spec}: no period near {orientation_deg}° in {peaks:?}"));
    let geometric = strongest.period_nm / tilt(strongest).to_radians().cos();
    let patch = Patch::from_row_major(hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, &hf.heights_nm).unwrap();
    let e = reference(&patch, 8000.0);
    let mut setup =
        BenchSetup::new(75f64.to_radians(), azimuth_deg.to_radians(), 1, (400.0, 700.0, 25.0), (-60.0, 74.0, 0.05))
            .unwrap();
    setup.max_period_nm = 8000.0 / 2.55;
    let (_, r) = bench::run(&e, &setup, &|_| {}).unwrap();
    (r.periodicity.mean, geometric)
}

#[test]
fn bench_agrees_with_the_surface_analysis_on_elaphe_and_xenopeltis() {
    for (spec, azimuth, orientation) in [
        ("builtin:elaphe?size=20um&pixel=50nm", 90.0, 90.0),
        ("builtin:xenopeltis?size=20um&pixel=50nm", 0.0, 0.0),
        ("builtin:xenopeltis?size=20um&pixel=50nm", 90.0, 90.0),
    ] {
        let (optical, geometric) = bench_vs_analysis(spec, azimuth, orientation);
        eprintln!("{spec} azimuth {azimuth}°: bench {optical:.1} nm, surface analysis {geometric:.1} nm");
        assert!(
            (optical - geometric).abs() < 0.02 * geometric,
            "{spec} at {azimuth}°: bench {optical} vs analysis {geometric}"
        );
    }
}
