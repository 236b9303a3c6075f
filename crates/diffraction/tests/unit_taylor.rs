//! The unit tests of src/taylor.rs (the Taylor terms, whole and banded), moved here so that `cargo test` compiles
//! the library once.

use iridis_diffraction::taylor::*;
use iridis_diffraction::Patch;
use num_complex::Complex64;

/// In-place 2D forward DFT (the whole grid at once, as the terms were computed before bands) of a row-major `rows × cols` array (`Σ x e^{−2πi(...)}`).
fn fft2(
    data: &mut [Complex64],
    rows: usize,
    cols: usize,
    fft_x: &dyn iridis_fft::Fft<f64>,
    fft_y: &dyn iridis_fft::Fft<f64>,
) {
    fft_x.process(data); // rustfft processes consecutive chunks of its length: every row
    let mut t = vec![Complex64::new(0.0, 0.0); rows * cols];
    transpose(data, &mut t, rows, cols);
    fft_y.process(&mut t);
    transpose(&t, data, cols, rows);
}

/// The coefficients as computed before bands: every term's full 2-D DFT times the centring, unsigned
/// layout `(t · cols + s)` per term.
fn full_grid(patch: &Patch, n_max: usize) -> Vec<Vec<Complex64>> {
    let (rows, cols) = (patch.rows, patch.cols);
    let (fft_x, fft_y) = (iridis_fft::plan(cols, false), iridis_fft::plan(rows, false));
    let norm = 1.0 / (rows * cols) as f64;
    let phase_x: Vec<f64> = (0..cols).map(|s| signed(s, cols) as f64 * (cols - 1) as f64 / (2 * cols) as f64).collect();
    (0..=n_max)
        .map(|n| {
            let i_n = [
                Complex64::new(1.0, 0.0),
                Complex64::new(0.0, 1.0),
                Complex64::new(-1.0, 0.0),
                Complex64::new(0.0, -1.0),
            ][n % 4];
            let mut data: Vec<Complex64> = patch.heights.iter().map(|&h| i_n * h.powi(n as i32)).collect();
            fft2(&mut data, rows, cols, fft_x.as_ref(), fft_y.as_ref());
            for (k, c) in data.iter_mut().enumerate() {
                let (s, t) = (k % cols, k / cols);
                let ty = signed(t, rows) as f64 * (rows - 1) as f64 / (2 * rows) as f64;
                let (sin, cos) = (std::f64::consts::TAU * (phase_x[s] + ty)).sin_cos();
                *c *= Complex64::new(cos * norm, sin * norm);
            }
            data
        })
        .collect()
}

fn rough_patch(rows: usize, cols: usize, dx: f64) -> Patch {
    let h: Vec<f64> = (0..rows * cols)
        .map(|k| {
            let (x, y) = ((k % cols) as f64, (k / cols) as f64);
            60.0 * (0.37 * x + 0.11 * y).sin() + 25.0 * (0.05 * x * y).cos() + 3.0 * ((k * 7919) % 13) as f64
        })
        .collect();
    Patch::from_row_major(rows, cols, dx, dx * 1.3, &h).unwrap()
}

#[test]
fn banded_terms_are_the_full_grids_bits_inside_and_zero_outside() {
    // Odd and even sizes (the DFT's signed ranges differ), every bin and a band off the origin.
    for (rows, cols) in [(48, 60), (37, 53)] {
        let patch = rough_patch(rows, cols, 40.0);
        let want = full_grid(&patch, 5);
        for band in [Band::ALL, Band::light([0.5, -0.3, 0.81], 380.0, 1e-4), Band::directions(500.0, 0.0)] {
            let t = TaylorTerms::compute_in_band(&patch, 5, 9000.0, band, &|_| {}).unwrap();
            let mut inside = 0;
            for tt in 0..rows {
                for s in 0..cols {
                    let f =
                        [signed(s, cols) as f64 / (cols as f64 * 40.0), signed(tt, rows) as f64 / (rows as f64 * 52.0)];
                    let d = ((f[0] - band.centre[0]).powi(2) + (f[1] - band.centre[1]).powi(2)).sqrt();
                    for n in 0..=5 {
                        let got = t.bin(s, tt)[n];
                        if d <= band.radius {
                            assert_eq!(got, want[n][tt * cols + s], "{rows}×{cols} {band:?} bin ({s}, {tt}) term {n}");
                        } else {
                            assert_eq!(got, Complex64::new(0.0, 0.0));
                        }
                    }
                    inside += usize::from(d <= band.radius);
                }
            }
            assert_eq!(t.memory_bytes(), inside * 6 * 16);
            if band == Band::ALL {
                assert_eq!(inside, rows * cols);
            } else {
                assert!(inside < rows * cols / 2, "{band:?} keeps {inside}");
            }
        }
    }
}

#[test]
fn terms_whose_coefficients_overflow_are_refused() {
    // c_n = DFT((i h)^n)/samples with h in nm: |h|max^N must stay below f64's 1.8e308 (here 150^N · 48²).
    let patch = rough_patch(48, 48, 20.0);
    let h = patch.max_abs_height;
    let last_finite = ((f64::MAX.ln() - (48.0f64 * 48.0).ln()) / h.ln()).floor() as usize;
    let ok = TaylorTerms::compute(&patch, last_finite, 2000.0).unwrap();
    assert!(ok.bin(1, 0).iter().all(|c| c.re.is_finite() && c.im.is_finite()));
    let e = TaylorTerms::compute(&patch, last_finite + 1, 2000.0).unwrap_err().to_string();
    assert!(e.contains("overflows double precision"), "{e}");
}

#[test]
fn term_count_meets_its_bound() {
    let n = terms_for_bound(150.0, 380.0, 1e-6).unwrap();
    let x = 2.0 * std::f64::consts::TAU / 380.0 * 150.0;
    let bound = |n: usize| (1..=n + 1).fold(1.0, |acc, k| acc * x / k as f64);
    assert!(bound(n) <= 1e-6 && bound(n - 1) > 1e-6, "N = {n}");
}

#[test]
fn bands_hold_every_bin_the_windowed_sum_reads() {
    // The reference method reads eq. 8 at f = (ω_i + ω_r)_xy/λ: over the hemisphere of ω_r, at λ from the
    // band's shortest up, the banded terms give the full terms' sums bit for bit (a missing bin would not).
    let patch = rough_patch(64, 64, 30.0);
    let coherence = 3000.0;
    let full = TaylorTerms::compute(&patch, 4, coherence).unwrap();
    let r = 1.001 * window_radius(coherence);
    let wi = [0.6 * 0.3f64.cos(), 0.6 * 0.3f64.sin(), 0.8];
    let (mut a, mut b) = (vec![Complex64::new(0.0, 0.0); 5], vec![Complex64::new(0.0, 0.0); 5]);
    for (band, light) in [(Band::light(wi, 400.0, r), Some(wi)), (Band::directions(400.0, r), None)] {
        let t = TaylorTerms::compute_in_band(&patch, 4, coherence, band, &|_| {}).unwrap();
        assert!(t.memory_bytes() < full.memory_bytes() / 2);
        let mut nonzero = 0;
        for k in 0..400 {
            let (theta, phi) = (1.55 * (k % 20) as f64 / 19.0, std::f64::consts::TAU * (k / 20) as f64 / 20.0);
            let wr = [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()];
            // Any light (the directions band) or the band's own.
            let wi = light.unwrap_or([-wr[1], wr[0], wr[2]]);
            for lambda in [400.0, 550.0, 780.0] {
                let (fx, fy) = ((wi[0] + wr[0]) / lambda, (wi[1] + wr[1]) / lambda);
                full.windowed(fx, fy, &mut a);
                t.windowed(fx, fy, &mut b);
                assert_eq!(a, b, "{band:?} at f = ({fx}, {fy})");
                nonzero += usize::from(a[1].norm() > 0.0);
            }
        }
        assert!(nonzero > 1000, "{nonzero}");
    }
}

#[test]
fn flat_patch_has_unit_specular_amplitude() {
    let patch = Patch::from_row_major(8, 8, 50.0, 50.0, &[3.0; 64]).unwrap();
    let t = TaylorTerms::compute(&patch, 3, 65_000.0).unwrap();
    let mut out = vec![Complex64::new(0.0, 0.0); 4];
    t.windowed(0.0, 0.0, &mut out);
    assert!((out[0] - Complex64::new(1.0, 0.0)).norm() < 1e-15);
    assert!(out[1].norm() < 1e-15);
}

#[test]
fn single_cosine_has_its_bins_at_its_frequency() {
    // h = cos(2π x / P): c_1 = DFT{i h}/N has magnitude 1/2 at s = ±cols/P and nothing elsewhere.
    let (rows, cols, dx) = (4, 64, 10.0);
    let period_px = 16.0;
    let h: Vec<f64> = (0..rows * cols).map(|k| (std::f64::consts::TAU * (k % cols) as f64 / period_px).cos()).collect();
    let patch = Patch::from_row_major(rows, cols, dx, dx, &h).unwrap();
    let t = TaylorTerms::compute(&patch, 1, 1e9).unwrap();
    let bin = (cols as f64 / period_px) as usize;
    // |c_1| = 1/2 at ±(cols/P); the window-centring phase only rotates them.
    assert!((t.bin(bin, 0)[1].norm() - 0.5).abs() < 1e-12);
    assert!((t.bin(cols - bin, 0)[1].norm() - 0.5).abs() < 1e-12);
    assert!(t.bin(bin + 1, 0)[1].norm() < 1e-12);
}
