//! The two ground truths (finite aperture, periodic extension) against each other, against an explicitly
//! tiled patch, and the periodic one against the reference where the reference's only approximations (the
//! 4σ_f cut of eq. 8 and the Taylor remainder) have a bound we can compute.

use crate::common;

use std::sync::Arc;

use iridis_diffraction::evaluator::{Aperture, Evaluator, GroundTruth, Reference};
use iridis_diffraction::geometry::{direction, Shading};
use iridis_diffraction::{Patch, SpectralSetup, TaylorTerms};
use num_complex::Complex64;

fn gt(patch: &Patch, coherence: f64, aperture: Aperture) -> GroundTruth {
    GroundTruth::with_aperture(patch, coherence, Shading::default(), &SpectralSetup::default(), 41, aperture).unwrap()
}

#[test]
fn periodic_ground_truth_equals_the_reference_up_to_its_bounded_approximations() {
    // 12 × 12 samples at 100 nm: L = 1.2 µm. The window's σ_f is 1/(7 L), so a bin's Gaussian has fallen to
    // e^{−24.5} at the next bin, and σ_s = 7 L / 2π = 13 pixels (the lattice sum's aliasing of the window,
    // ~exp(−2π² σ_s²/dx²), is far below f64).
    let (n, dx) = (12usize, 100.0);
    let l = n as f64 * dx;
    let sigma_f = 1.0 / (7.0 * l);
    let sigma_s = 1.0 / (std::f64::consts::TAU * sigma_f);
    let coherence = 4.0 * sigma_s;
    let patch = Patch::from_row_major(n, n, dx, dx, &common::heights(n * n, 30.0, 7)).unwrap();
    let terms_n = 24;
    let terms = Arc::new(TaylorTerms::compute(&patch, terms_n, coherence).unwrap());
    let reference = Reference { terms, shading: Shading::default(), spectral: SpectralSetup::default() };
    let truth = gt(&patch, coherence, Aperture::Periodic);
    let mut scratch = vec![Complex64::new(0.0, 0.0); terms_n + 1];
    let g = |fx: f64, fy: f64| (-(fx * fx + fy * fy) / (2.0 * sigma_f * sigma_f)).exp();
    // Bound on |A_reference − A_periodic| at frequency f and wavelength λ (w = −(wi_z + wr_z), |w| ≤ 2):
    //  * bins the reference leaves out (beyond 4σ_f, or outside the DFT's index range): Σ G(f − f_s) · max|c_s|,
    //    |c_s| ≤ mean |p| = 1;
    //  * the Taylor remainder of p: |c_trunc − c| ≤ (2 k |h|max)^{N+1}/(N+1)!, times Σ G over the bins used.
    let bound = |fx: f64, fy: f64, lambda: f64| {
        let x = 2.0 * std::f64::consts::TAU / lambda * patch.max_abs_height;
        let taylor = (1..=terms_n + 1).fold(1.0, |acc, k| acc * x / k as f64);
        let (lo, hi) = (-(((n - 1) / 2) as i64), (n / 2) as i64);
        let (mut cut, mut used) = (0.0, 0.0);
        for t in -60i64..=60 {
            for s in -60i64..=60 {
                let (dfx, dfy) = (fx - s as f64 / l, fy - t as f64 / l);
                let inside = (lo..=hi).contains(&s) && (lo..=hi).contains(&t);
                if inside && dfx * dfx + dfy * dfy <= 16.0 * sigma_f * sigma_f {
                    used += g(dfx, dfy);
                } else {
                    cut += g(dfx, dfy);
                }
            }
        }
        cut + taylor * used
    };
    let wi = [0.0, 0.0, 1.0];
    let mut at_bins = 0;
    for lambda in [500.0, 640.0] {
        // Directions whose frequency f = (−u/λ, −v/λ) sits on DFT bins (s, t): u = −(wi_x + wr_x).
        for (s, t) in [(0i64, 0i64), (1, 0), (0, 1), (1, 1), (-1, 1), (1, -1), (-1, 0)] {
            let (ox, oy) = (s as f64 * lambda / l, t as f64 * lambda / l);
            let wr = [ox, oy, (1.0 - ox * ox - oy * oy).sqrt()];
            let a = reference.amplitude(lambda, wi, wr, &mut scratch);
            let b = truth.amplitude(lambda, wi, wr);
            let d = bound(s as f64 / l, t as f64 / l, lambda);
            assert!(d < 1e-9, "bound at bin ({s}, {t}) {d}");
            assert!(
                (a - b).norm() <= d,
                "bin ({s},{t}) at {lambda} nm: reference {a} vs periodic truth {b}, bound {d}"
            );
            if b.norm() > 1e-2 {
                let rel = (a.norm_sqr() - b.norm_sqr()).abs() / b.norm_sqr();
                assert!(rel <= 1e-6, "bin ({s},{t}) at {lambda} nm: |A|² differs by {rel:e} relative");
                at_bins += 1;
            }
        }
        // Between bins the reference's 4σ_f cut is the whole difference; it stays within its bound.
        for (tr, pr) in [(0.3, 1.0), (0.45, 2.5), (0.2, 4.0)] {
            let wr = direction(tr, pr);
            let a = reference.amplitude(lambda, wi, wr, &mut scratch);
            let b = truth.amplitude(lambda, wi, wr);
            let (fx, fy) = ((wi[0] + wr[0]) / lambda, (wi[1] + wr[1]) / lambda);
            let d = bound(fx, fy, lambda);
            assert!((a - b).norm() <= d, "({tr},{pr}) at {lambda} nm: reference {a} vs periodic truth {b}, bound {d}");
        }
    }
    assert!(at_bins >= 6, "only {at_bins} bins with |A| > 0.01 checked");
}

#[test]
fn periodic_ground_truth_is_the_finite_ground_truth_of_the_tiled_patch() {
    // A 10 × 12 patch (80 × 100 nm pixels) tiled 5 × 5: the tiled patch's centre is the middle tile's, and the
    // window (σ_s = 300 nm, cut at 7.43 σ_s = 2.23 µm) stays inside the ±2.5 tiles, so the finite aperture over
    // the tiles and the periodic extension of one tile sum the same lattice points.
    let (rows, cols, dx, dy) = (10usize, 12usize, 80.0, 100.0);
    let h = common::heights(rows * cols, 45.0, 11);
    let patch = Patch::from_row_major(rows, cols, dx, dy, &h).unwrap();
    let k = 5;
    let mut tiled = Vec::with_capacity(rows * cols * k * k);
    for r in 0..rows * k {
        for c in 0..cols * k {
            tiled.push(h[(r % rows) * cols + c % cols]);
        }
    }
    let big = Patch::from_row_major(rows * k, cols * k, dx, dy, &tiled).unwrap();
    let coherence = 1200.0;
    let periodic = gt(&patch, coherence, Aperture::Periodic);
    let finite = gt(&big, coherence, Aperture::Finite);
    assert_eq!((periodic.name(), finite.name()), ("ground-truth-periodic", "ground-truth"));
    for (ti, pi, tr, pr) in [(0.0, 0.0, 0.0, 0.0), (0.3, 0.2, 0.5, 2.0), (0.9, 1.0, 0.4, 4.0), (0.5, 3.0, 1.2, 0.7)] {
        let (wi, wr) = (direction(ti, pi), direction(tr, pr));
        for lambda in [420.0, 555.0, 700.0] {
            let a = periodic.amplitude(lambda, wi, wr);
            let b = finite.amplitude(lambda, wi, wr);
            assert!((a - b).norm() <= 1e-10 * b.norm().max(1e-3), "{lambda} nm: periodic {a} vs tiled {b}");
        }
        let (x, y) = (periodic.xyz(wi, wr), finite.xyz(wi, wr));
        assert!((x.y - y.y).abs() <= 1e-9 * y.y.max(1e-6), "Y: periodic {} vs tiled {}", x.y, y.y);
    }
}

#[test]
fn both_ground_truths_agree_when_the_window_is_well_inside_the_patch() {
    // 64 × 64 at 50 nm (3.2 µm) with σ_s = 250 nm: the lattice's window mass outside the patch bounds how much
    // the images can add, |A_periodic − A_finite| ≤ 2 · (mass outside) / (mass in total).
    let (n, dx, coherence) = (64usize, 50.0, 1000.0);
    let patch = Patch::from_row_major(n, n, dx, dx, &common::heights(n * n, 60.0, 3)).unwrap();
    let sigma = coherence / 4.0;
    let centre = (n - 1) as f64 * dx / 2.0;
    let axis = |m_range: i64| -> f64 {
        (-m_range * n as i64..(m_range + 1) * n as i64)
            .map(|i| {
                let x = i as f64 * dx - centre;
                (-(x * x) / (2.0 * sigma * sigma)).exp()
            })
            .sum()
    };
    let (inside, all) = (axis(0).powi(2), axis(20).powi(2));
    let outside = 1.0 - inside / all;
    assert!(outside > 1e-12 && outside < 1e-6, "window mass outside the patch {outside:e}");
    let periodic = gt(&patch, coherence, Aperture::Periodic);
    let finite = gt(&patch, coherence, Aperture::Finite);
    for (ti, pi, tr, pr) in [(0.0, 0.0, 0.0, 0.0), (0.5, 0.3, 0.2, 2.0), (0.9, 0.0, 0.6, 3.0), (0.2, 1.0, 1.2, 4.0)] {
        let (wi, wr) = (direction(ti, pi), direction(tr, pr));
        for lambda in [400.0, 550.0, 700.0] {
            let a = periodic.amplitude(lambda, wi, wr);
            let b = finite.amplitude(lambda, wi, wr);
            assert!((a - b).norm() <= 2.0 * outside + 1e-13, "{lambda} nm: periodic {a} vs finite {b}");
        }
    }
}

#[test]
fn a_window_thousands_of_patches_wide_is_refused_with_what_to_lower() {
    let patch = Patch::from_row_major(4, 4, 10.0, 10.0, &common::heights(16, 5.0, 1)).unwrap();
    let e =
        GroundTruth::with_aperture(&patch, 1e9, Shading::default(), &SpectralSetup::default(), 3, Aperture::Periodic)
            .unwrap_err()
            .to_string();
    assert!(e.contains("lower --coherence") && e.contains("images"), "{e}");
    // The finite aperture has no such limit.
    assert!(GroundTruth::with_aperture(
        &patch,
        1e9,
        Shading::default(),
        &SpectralSetup::default(),
        3,
        Aperture::Finite
    )
    .is_ok());
    assert_eq!("periodic".parse::<Aperture>().unwrap(), Aperture::Periodic);
    assert!("infinite".parse::<Aperture>().unwrap_err().to_string().contains("expected finite"));
}

/// A window narrower than a pixel (σ_s = coherence/4 below max(dx, dy)) is refused by every evaluator that
/// samples it, with the shortest length the sampling carries, 4·max(dx, dy); that length itself is accepted.
#[test]
fn a_window_narrower_than_a_pixel_is_refused_with_the_shortest_the_sampling_carries() {
    let patch = Patch::from_row_major(8, 8, 60.0, 40.0, &common::heights(64, 20.0, 3)).unwrap();
    assert_eq!(patch.min_coherence_nm(), 240.0);
    let short = 239.5;
    let refusals = [
        patch.check_coherence(short).unwrap_err().to_string(),
        TaylorTerms::compute(&patch, 4, short).unwrap_err().to_string(),
        GroundTruth::with_aperture(&patch, short, Shading::default(), &SpectralSetup::default(), 3, Aperture::Finite)
            .unwrap_err()
            .to_string(),
    ];
    for e in refusals {
        assert!(
            e.contains("a coherence length of 239.5 nm is shorter than this scan's 60 nm pixels carry")
                && e.contains("σ_s = coherence/4 = 59.88 nm")
                && e.contains("give at least 240 nm"),
            "{e}"
        );
    }
    assert!(patch.check_coherence(0.0).unwrap_err().to_string().contains("must be positive"));
    assert!(patch.check_coherence(240.0).is_ok() && TaylorTerms::compute(&patch, 4, 240.0).is_ok());
}
