//! The unit tests of src/brdf_map.rs: the warning for a map whose pixels are further apart than the light's
//! lobes (and the laser screen's whose samples are), checked against the window's closed form and against the
//! maps themselves.

use iridis_api::brdf::{MEASURE_SAMPLES_PER_LOBE_SIGMA, SAMPLES_PER_LOBE_SIGMA};
use iridis_api::brdf_map::{compute, lobes_between_pixels, MapRequest};
use iridis_api::report::{Collect, Kind};

/// σ of the window's `|G(u/λ)|²` in direction cosines, `λ/(2√2 π σ_s)` with `σ_s` a quarter of the coherence
/// length (docs/PHYSICS.md), written out.
fn sigma_uv(lambda: f64, coherence: f64) -> f64 {
    lambda / (2.0 * 2f64.sqrt() * std::f64::consts::PI * coherence / 4.0)
}

#[test]
fn the_warning_starts_where_the_pixels_are_six_lobe_widths_apart() {
    let coherence = 65_000.0;
    // 2/size > 6σ at 380 nm: the largest quiet size is the first with 2/size ≤ 6σ.
    let quiet = (2.0 / (SAMPLES_PER_LOBE_SIGMA * sigma_uv(380.0, coherence))).ceil() as usize;
    assert_eq!(quiet, 127, "65 µm: 6σ = {}", SAMPLES_PER_LOBE_SIGMA * sigma_uv(380.0, coherence));
    assert!(lobes_between_pixels(quiet, 1, coherence, None, false).is_none());
    let w = lobes_between_pixels(quiet - 1, 1, coherence, Some(coherence), false).expect("one pixel fewer warns");
    assert!(
        w.contains("coherence 65.0 µm") && w.contains("--subsamples 2 (each pixel") && w.contains("shows every lobe")
    );
    // Measuring a lobe's light takes samples within 1.5σ (the sum's error 2e-4 per axis there, by Poisson
    // summation; 45 % over the disk at 3σ): 2/126 over 1.5σ is 4.02, so 5 a pixel side.
    let measure = (2.0 / 126.0 / (MEASURE_SAMPLES_PER_LOBE_SIGMA * sigma_uv(380.0, coherence))).ceil();
    assert_eq!(measure, 5.0);
    assert!(w.contains("to measure their light (the sum of f_r in sr⁻¹ over the disk) the samples must lie within 1.5σ: --subsamples 5"), "{w}");
    // 32² needs 127/32 → 4 view samples a pixel side, and with them is quiet.
    assert!(lobes_between_pixels(32, 1, coherence, None, false).unwrap().contains("--subsamples 4 "));
    assert!(lobes_between_pixels(32, 4, coherence, None, false).is_none());
    // Where f_r is written (--brdf), 4 a side still sums part of the light (samples 5.9σ apart): warned, naming
    // the 2/(32·1.5σ) = 16 a side within 1.5σ; at 16 it is quiet.
    let w = lobes_between_pixels(32, 4, coherence, None, true).expect("the sum is short");
    assert!(w.contains("every lobe shows, but the sum of f_r in sr⁻¹ over the disk takes only part of their light"));
    let needed = (2.0 / 32.0 / (MEASURE_SAMPLES_PER_LOBE_SIGMA * sigma_uv(380.0, coherence))).ceil();
    assert!(w.contains(&format!("--subsamples {needed}")) && needed == 16.0, "{w}");
    assert!(lobes_between_pixels(32, 16, coherence, None, true).is_none());
    // A shorter coherence widens the lobes: 8 µm is quiet at 16² (2/16 = 0.125 ≤ 6σ = 0.128).
    assert!(lobes_between_pixels(16, 1, 8_000.0, None, false).is_none());
    // The finite aperture's window, cut by the patch's edge, is named as such beside the light's.
    let w = lobes_between_pixels(32, 1, 59_500.0, Some(coherence), false).unwrap();
    assert!(w.contains("effective coherence 59.5 µm: the light's 65.0 µm window cut by the patch's edge"), "{w}");
}

/// Light at 30° on an 8 µm patch of a 1.1 µm sine (one unit cell: discrete orders, each a lobe of the 65 µm
/// window): a 32² map, whose pixels are 12 lobe widths apart, misses every lobe — mirror and orders — and says
/// so; a 128² map, quiet, catches them within a few widths of their peaks.
#[test]
fn a_map_that_misses_the_lobes_is_black_and_says_why() {
    let map = |size: usize| {
        let mut r = MapRequest::new("builtin:sine?size=8um&pixel=100nm", "reference");
        r.size = size;
        r.wi = [0.5, 0.0, 0.75f64.sqrt()];
        let said = Collect::default();
        let m = compute(&r, None, &said).unwrap();
        let brightest = m.xyz.iter().map(|p| p.y).fold(0.0, f64::max);
        let warned: Vec<String> = said
            .take()
            .into_iter()
            .filter(|(k, t)| *k == Kind::Warning && t.contains("pixels are"))
            .map(|x| x.1)
            .collect();
        (brightest, warned)
    };
    let (coarse, warned_coarse) = map(32);
    let (fine, warned_fine) = map(128);
    assert_eq!(warned_coarse.len(), 1, "{warned_coarse:?}");
    assert!(warned_fine.is_empty(), "{warned_fine:?}");
    // The mirror lobe at u = −0.5 lies 1/32 (8σ at 550 nm) from the 32² map's nearest pixel centres and 1/128
    // (2σ) from the 128² map's: e^(−32) against e^(−2) of its peak.
    assert!(fine > 1e-3, "128² brightest Y {fine}");
    assert!(coarse < 1e-9 * fine, "32² brightest Y {coarse} against {fine}");
}

/// The laser screen (paper Figure 8): its view samples against the aperture's lobes, and what to ask for.
#[test]
fn the_laser_screen_says_how_many_samples_its_lobes_need() {
    use iridis_api::lab_run::screen_misses_lobes;
    let setup = iridis_lab::laser::LaserSetup::default();
    // 300 mm over 101 × 3 samples at 100 mm: 9.9 mrad; a 65 µm aperture's lobes: 6σ = 15.8 mrad at 380 nm.
    assert!(screen_misses_lobes(&setup, 65_000.0).is_none());
    // 32 px: 31.25 mrad against 6σ = 5.13 mrad at 200 µm — 18.3 samples a pixel, so 16 of them on 37 pixels.
    let small = iridis_lab::laser::LaserSetup { width_px: 32, height_px: 32, ..setup.clone() };
    let spacing = 300.0 / (32.0 * 3.0) / 100.0;
    let needed = 32.0 * 3.0 * spacing / (SAMPLES_PER_LOBE_SIGMA * sigma_uv(380.0, 200_000.0)) / 16.0;
    assert_eq!(needed.ceil(), 37.0);
    let w = screen_misses_lobes(&small, 200_000.0).expect("32 px at 200 µm misses lobes");
    assert!(
        w.contains("31.25 mrad") && w.contains("aperture 200.0 µm") && w.contains("--subsamples 16 with --size 37"),
        "{w}"
    );
    // At 100 µm, 6σ = 10.3 mrad: 9.1 samples a pixel, so 10.
    let w = screen_misses_lobes(&small, 100_000.0).unwrap();
    assert!(w.contains("--subsamples 10 or more"), "{w}");
    // The same figures in --json (`sampling`): the spacing, σ, and how many times finer (18.3 / 3 = 6.09).
    let s = iridis_api::lab_run::ScreenSampling::of(&small, Some(200_000.0));
    let finer = spacing / (SAMPLES_PER_LOBE_SIGMA * sigma_uv(380.0, 200_000.0));
    assert!((s.spacing_rad - spacing).abs() < 1e-15 && (s.finer_by.unwrap() - finer).abs() < 1e-12, "{s:?}");
    assert!((s.to_json()["lobe_sigma_mrad"].as_f64().unwrap() - 1e3 * sigma_uv(380.0, 200_000.0)).abs() < 1e-12);
    assert_eq!(iridis_api::lab_run::ScreenSampling::of(&setup, Some(65_000.0)).finer_by, None);
    assert_eq!(
        iridis_api::lab_run::ScreenSampling::of(&setup, None).to_json()["lobe_sigma_mrad"],
        serde_json::Value::Null
    );
}

/// `--subsamples k`: each pixel the mean of its k² view samples, i.e. the `size·k` map averaged over k × k
/// blocks (the samples are that map's pixel centres), to the bit; so the 32² map of the 8 µm sine, black at one
/// sample a pixel, holds the 128² map's light.
#[test]
fn a_subsampled_map_is_the_finer_map_averaged_over_blocks() {
    let map = |size: usize, subsamples: usize| {
        let mut r = MapRequest::new("builtin:sine?size=8um&pixel=100nm", "reference");
        (r.size, r.subsamples, r.wi) = (size, subsamples, [0.5, 0.0, 0.75f64.sqrt()]);
        let said = Collect::default();
        let m = compute(&r, None, &said).unwrap();
        assert!(!said.take().iter().any(|(_, t)| t.contains("apart in view direction")), "{size}/{subsamples}");
        m.xyz
    };
    let (coarse, fine) = (map(32, 4), map(128, 1));
    let mut worst = 0.0f64;
    for (k, c) in coarse.iter().enumerate() {
        let (row, col) = (k / 32, k % 32);
        let block: f64 = (0..16).map(|q| fine[(row * 4 + q / 4) * 128 + col * 4 + q % 4].y).sum::<f64>() / 16.0;
        worst = worst.max((c.y - block).abs());
    }
    let brightest = fine.iter().map(|p| p.y).fold(0.0, f64::max);
    assert!(worst <= 1e-12 * brightest, "worst {worst} of {brightest}");
    assert!(coarse.iter().map(|p| p.y).fold(0.0, f64::max) > 0.05 * brightest);
    // The GPU's subsampled maps are its finer map through `block_mean`: the same numbers as the CPU's own sums.
    assert!(coarse == iridis_diffraction::map::block_mean(&fine, 128, 4));
}
