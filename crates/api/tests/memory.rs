//! Memory scales with what is asked (issue 32, "Cost"): the steps of `iridis report` on a scan sampled
//! finer than light resolves hold a few copies of the scan, not a complex DFT of every Taylor term (twice)
//! and every order of every wavelength. The process' peak resident memory (Linux's `VmHWM`, reset through
//! `/proc/self/clear_refs` before each call: what `/usr/bin/time -v` reports) is read while each library
//! call runs, on a 512² scan at 50 nm (2 MiB of heights). One test in this binary: nothing else runs beside it.
//!
//! Before: `grating` (the scan as one unit cell) held ~27 terms × 512² × 16 B twice ≈ 230 MiB (≈ 110× the
//! heights) and the reference evaluator's terms ≈ 95×. The bound, 12× the heights, is what the kept bins need
//! (a twentieth of the grid for one light, a fifth for every direction pair, × the terms) with the
//! transforms' working rows and the scan's own copy.

use iridis_api::grating::{grating, GratingOptions};
use iridis_api::report::Quiet;
use iridis_api::surface::{load_patch, Source};

/// `VmRSS` or `VmHWM` of this process (bytes).
fn status(key: &str) -> usize {
    let s = std::fs::read_to_string("/proc/self/status").expect("/proc/self/status (Linux)");
    let line = s.lines().find(|l| l.starts_with(key)).unwrap_or_else(|| panic!("no {key} in /proc/self/status"));
    1024 * line.split_whitespace().nth(1).and_then(|v| v.parse::<usize>().ok()).expect("kB")
}

/// The peak resident bytes above those resident before, while `f` runs.
fn peak_during<T>(f: impl FnOnce() -> T) -> (T, usize) {
    // "5" resets the peak to the current resident size (proc(5), /proc/pid/clear_refs).
    std::fs::write("/proc/self/clear_refs", "5").expect("resetting the peak through /proc/self/clear_refs");
    let before = status("VmRSS:");
    let out = f();
    (out, status("VmHWM:").saturating_sub(before))
}

#[test]
fn the_reports_model_steps_hold_a_few_copies_of_the_scan() {
    let patch = load_patch("builtin:elaphe?size=25.6um&pixel=50nm", &Default::default(), &Quiet).unwrap();
    assert_eq!((patch.rows, patch.cols), (512, 512));
    let heights = patch.heights.len() * std::mem::size_of::<f64>();
    let source = Source::Patch { patch, name: "elaphe".into() };
    let bound = 12 * heights;

    // `iridis grating SCAN --light 0deg --from 380nm --to 780nm --step 10nm --orders-above 1%` (the report's).
    let opts = GratingOptions {
        wavelengths_nm: (0..=40).map(|i| 380.0 + 10.0 * i as f64).collect(),
        orders_above: 0.01,
        ..Default::default()
    };
    let (g, peak) = peak_during(|| grating(&source, &Default::default(), &opts, &Quiet).unwrap());
    eprintln!("grating: peak {:.1} MiB, {:.1}× the heights", peak as f64 / 1048576.0, peak as f64 / heights as f64);
    assert!(
        peak <= bound,
        "grating peaked at {peak} B, {:.1}× the {heights} B of heights",
        peak as f64 / heights as f64
    );
    // Every order counted, at most 1/1 % of them listed a wavelength (with the mirror order).
    assert!(g.answers.iter().all(|a| a.orders.len() <= 101 && a.unlisted > 1000), "{:?}", g.answers[0].unlisted);

    // The reference evaluator of `iridis brdf-map SCAN --method reference --incidence 0deg`: its Taylor terms.
    let shading = iridis_diffraction::geometry::Shading::default();
    // A map asks about one light (`brdf-map` sets it): the terms keep that light's bins.
    let model =
        iridis_api::ModelOptions { coherence_nm: Some(12_800.0), light: Some([0.0, 0.0, 1.0]), ..Default::default() };
    let (e, peak) = peak_during(|| {
        let setup = iridis_api::brdf::EvaluatorSetup {
            method: "reference",
            model: &model,
            shading,
            params: Default::default(),
            precision: iridis_diffraction::table::Precision::F64,
            surface: &Default::default(),
        };
        iridis_api::brdf::evaluator_for(&source, setup, &Quiet).unwrap()
    });
    eprintln!("reference: peak {:.1} MiB, {:.1}× the heights", peak as f64 / 1048576.0, peak as f64 / heights as f64);
    assert!(peak <= bound, "the reference evaluator peaked at {:.1}× the heights", peak as f64 / heights as f64);
    assert_eq!(e.name(), "reference");
}
