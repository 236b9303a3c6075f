//! What the GPU paths are built on, checked on the CPU in f64: the ground truth's separable description
//! ([`Lattice`], what the GPU sums) against the ground truth's own sums, its colour from powers against its
//! `xyz`, and the table encodings of the lookup shader against the f64 lookup they stand for.

use crate::common;

use std::sync::Arc;

use iridis_diffraction::encoding::{EncodedTable, TableEncoding};
use iridis_diffraction::evaluator::{Aperture, Evaluator, GroundTruth};
use iridis_diffraction::geometry::{direction, uvw, Shading};
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::taylor::terms_for_bound;
use iridis_diffraction::{Patch, SpectralSetup, TaylorTerms};
use num_complex::Complex64;

/// `A` at wavenumber `s` summed term by term over the lattice's description (no recurrences, no separation).
fn lattice_amplitude(gt: &GroundTruth, wi: [f64; 3], wr: [f64; 3], s: f64) -> Complex64 {
    let l = gt.lattice();
    let [u, v, w] = uvw(wi, wr);
    let mut a = Complex64::new(0.0, 0.0);
    for t in 0..l.rows {
        for i in 0..l.cols {
            for &(m, gx) in &l.column_images[i] {
                for &(n, gy) in &l.row_images[t] {
                    let x = (i as f64 + (m * l.cols as i64) as f64) * l.dx;
                    let y = (t as f64 + (n * l.rows as i64) as f64) * l.dy;
                    let phase = std::f64::consts::TAU * s * (w * l.heights[t * l.cols + i] + u * x + v * y);
                    a += Complex64::from_polar(gx * gy, phase);
                }
            }
        }
    }
    a
}

#[test]
fn the_lattice_describes_the_same_sum_as_the_ground_truth() {
    // 20 × 24 samples at 40 × 45 nm (0.96 × 0.9 µm); coherence 1.5 µm (the periodic sum reaches neighbouring
    // images) and 0.25 µm (the finite window falls below its 1e-12 cut inside the patch, so columns drop out;
    // σ_s = 62.5 nm spans a pixel, as the model needs).
    let (rows, cols) = (20, 24);
    let patch = Patch::from_row_major(rows, cols, 40.0, 45.0, &common::heights(rows * cols, 60.0, 3)).unwrap();
    for (aperture, coherence) in [
        (Aperture::Finite, 1500.0),
        (Aperture::Finite, 250.0),
        (Aperture::Periodic, 1500.0),
        (Aperture::Periodic, 250.0),
    ] {
        let gt =
            GroundTruth::with_aperture(&patch, coherence, Shading::default(), &SpectralSetup::default(), 21, aperture)
                .unwrap();
        let total: f64 = gt.lattice().column_images.iter().flatten().map(|c| c.1).sum::<f64>()
            * gt.lattice().row_images.iter().flatten().map(|r| r.1).sum::<f64>();
        // The window is normalised over the whole lattice; the 1e-12 cut leaves out a negligible rest.
        assert!((total - 1.0).abs() < 1e-9, "{aperture:?} {coherence}: Σ g = {total}");
        let mut worst = 0.0f64;
        for (ti, tr, pr) in [(0.0, 0.0, 0.0), (30.0, 25.0, 200.0), (55.0, 70.0, 10.0)] {
            let (wi, wr) = (direction(f64::to_radians(ti), 0.0), direction(f64::to_radians(tr), f64::to_radians(pr)));
            for lambda in [400.0, 555.0, 700.0] {
                let cpu = gt.amplitude(lambda, wi, wr).norm_sqr();
                let lat = lattice_amplitude(&gt, wi, wr, 1.0 / lambda).norm_sqr();
                worst = worst.max((cpu - lat).abs() / cpu.max(1e-3));
            }
        }
        eprintln!("{aperture:?}, coherence {coherence} nm: |A|² lattice vs ground truth, worst {worst:.1e}");
        // The finite lattice adds the square's corners beyond the disk the CPU keeps (each < 1e-12 of the peak).
        assert!(worst < 1e-9, "{aperture:?} {coherence}: {worst}");
    }
}

#[test]
fn colour_from_powers_is_the_ground_truths_colour() {
    let patch = Patch::from_row_major(8, 8, 100.0, 100.0, &common::heights(64, 40.0, 11)).unwrap();
    let gt = GroundTruth::with_aperture(
        &patch,
        800.0,
        Shading::default(),
        &SpectralSetup::default(),
        31,
        Aperture::Periodic,
    )
    .unwrap();
    let s = gt.wavenumbers().to_vec();
    // Grazing view: some wavenumbers lie beyond Nyquist (u/λ > 1/(2·100 nm)) and must be left out.
    for (wi, wr) in [(direction(0.3, 0.0), direction(0.5, 2.0)), (direction(1.4, 0.0), direction(1.45, 0.0))] {
        let power: Vec<f64> = s.iter().map(|&k| gt.amplitude(1.0 / k, wi, wr).norm_sqr()).collect();
        let (a, b) = (gt.xyz(wi, wr), gt.xyz_from_power(wi, wr, &power));
        for (x, y) in [(a.x, b.x), (a.y, b.y), (a.z, b.z)] {
            assert!((x - y).abs() <= 1e-9 * x.abs().max(1e-12), "{a:?} vs {b:?}");
        }
    }
}

/// A table of a built-in (6 µm at 62.5 nm, coherence 3 µm) on a 61² grid.
fn table(name: &str) -> Arc<LookupTable> {
    let hf = iridis_surface::builtin::builtin_surface(&format!("{name}?size=6um&pixel=62.5nm"), &Default::default())
        .unwrap();
    let patch = Patch::from_row_major(hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, &hf.heights_nm).unwrap();
    let n = terms_for_bound(patch.max_abs_height, 380.0, 1e-6).unwrap();
    let terms = TaylorTerms::compute(&patch, n, 3000.0).unwrap();
    let params = TableParams { uv_resolution: 61, uv_power: 5.0 };
    Arc::new(LookupTable::build(&terms, &SpectralSetup::default(), params, name, &|_| {}).unwrap())
}

#[test]
fn encodings_stand_for_the_f64_lookup() {
    for name in ["elaphe", "blazed"] {
        let t = table(name);
        let np = t.powers();
        let f64_lookup = Lookup::new(t.clone(), Shading::default(), Precision::F64).unwrap();
        let f32_lookup = Lookup::new(t.clone(), Shading::default(), Precision::F32).unwrap();
        let f32 = EncodedTable::encode(&t, TableEncoding::F32).unwrap();
        let exact = EncodedTable::encode(&t, TableEncoding::Chebyshev { terms: np, half: false }).unwrap();
        let f16 = EncodedTable::encode(&t, TableEncoding::F16).unwrap();
        assert_eq!(f32.bytes(), t.data.len() * 4);
        assert_eq!(f16.bytes(), t.meta.uv_resolution.pow(2) * 3 * np.div_ceil(2) * 4);
        let (mut e32, mut echeb, mut e16, mut peak) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for ti in [0.0, 35.0] {
            for k in 0..400 {
                let wi = direction(f64::to_radians(ti), 0.0);
                let wr = direction(f64::to_radians((k % 20) as f64 * 4.4), (k / 20) as f64 * 0.33);
                let [u, v, w] = uvw(wi, wr);
                let r = f64_lookup.sum(u, v, w);
                let (a, b, c, d) = (f32_lookup.sum(u, v, w), f32.sum(u, v, w), exact.sum(u, v, w), f16.sum(u, v, w));
                for ch in 0..3 {
                    peak = peak.max(r[ch].abs());
                    // The f32 encoding is Lookup's f32 table, summed in f64 here.
                    e32 = e32.max((a[ch] - b[ch]).abs());
                    echeb = echeb.max((c[ch] - r[ch]).abs());
                    e16 = e16.max((d[ch] - r[ch]).abs());
                }
            }
        }
        let (e32, echeb, e16) = (e32 / peak, echeb / peak, e16 / peak);
        eprintln!("{name} (2N+1 = {np}): relative to the peak, f32 {e32:.1e}, cheb{np} {echeb:.1e}, f16 {e16:.1e}");
        // Measured: f32 5.5e-7 (elaphe), 1.6e-6 (blazed) — the powers' f32 rounding, summed in f32 vs f64.
        assert!(e32 < 5e-6, "{name}: f32 {e32}");
        // 2N+1 Chebyshev coefficients are the degree-2N polynomial itself, in a better-conditioned basis than
        // the powers: measured 4.4e-8 and 2.5e-8, ten times below the f32 powers.
        assert!(echeb < 2e-7, "{name}: cheb {echeb}");
        // Half precision, 2^-11 per stored power, amplified by the sum's cancellation: measured 2.2e-3, 7.6e-3.
        assert!(e16 < 3e-2, "{name}: f16 {e16}");
    }
}
