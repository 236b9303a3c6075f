//! The study behind the GPU's fast film path (issue 17; docs/gpu.md, "Choosing the fast path"): four ways to
//! get a film's colour with less work than the recurrence at 81 wavelengths, measured against that dense
//! evaluation on the sparse-sampling experiment's domain (angles 0°–80°, SVT offsets ±95 nm; the same points
//! with angles to 89.5°), in CIEDE2000 as displayed:
//!
//! * the colour table over `√cos θ` × offset (`iridis_thinfilm::table`, 48 nodes per fringe period);
//! * Sussenbach's sparse sampling: N samples evenly over 400–700 nm (section 5.2.2);
//! * a quadrature fitted to the colour matching functions: N nodes evenly over 400–700 nm whose XYZ weights are
//!   fitted (least squares) to reproduce the dense XYZ of soap-film spectra, 0–1500 nm at 0°–80°;
//! * Belcour & Barla's (2017) spectral integration of one layer: the Airy reflectance as a Fourier series in
//!   the phase, `R = 1 − K (1 + 2 Σ_m (−x)^m cos mΦ)` with `x = r₁₂ r₂₃`, `K = (1 − r₁₂²)(1 − r₂₃²)/(1 − x²)`,
//!   `Φ = 2π·OPD/λ`, so that `XYZ = Σ_λ w(λ) R(λ)` needs only the transform `W(t) = Σ_λ w(λ) cos(2π t/λ)` of
//!   the sensitivities at `t = m·OPD` — here tabulated at 1 nm steps (their Gaussian fits of the sensitivities
//!   replaced by the exact transform), truncated after M harmonics. One dielectric, non-dispersive layer only.
//!
//! The printed table is docs/gpu.md's; the assertions are the conclusions drawn there.

use iridis_color::{SpectralWeights, Xyz};
use iridis_thinfilm::accuracy::DeltaEStats;
use iridis_thinfilm::spectral::{
    dense_weights, experiment_points, exposure_for, reflected_colors, sampled_weights, THESIS_BAND_NM, THESIS_D_REL_NM,
};
use iridis_thinfilm::table::{FilmTable, TableGrid};
use iridis_thinfilm::Stack;

const SOAP: &str = "air | water 500nm | air";
const OIL: &str = "air | gasoline 216nm | water 230nm | asphalt";

/// The experiment's points with angles up to `max_deg`.
fn points(max_deg: f64) -> Vec<(f64, f64)> {
    experiment_points(48, 48, THESIS_D_REL_NM)
        .into_iter()
        .map(|(t, o)| (t / 80f64.to_radians() * max_deg.to_radians(), o))
        .collect()
}

fn table_colors(stack: &Stack, pts: &[(f64, f64)]) -> Vec<Xyz> {
    let w = dense_weights();
    let grid = TableGrid::for_stack(stack, w.wavelengths_nm(), (-THESIS_D_REL_NM, THESIS_D_REL_NM)).unwrap();
    let t = FilmTable::build(stack, &w, grid).unwrap();
    pts.iter().map(|&(th, o)| t.lookup(th.cos(), o).0).collect()
}

/// Solves the symmetric positive definite system `a x = b` (Gaussian elimination, partial pivoting).
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs())).unwrap();
        a.swap(k, p);
        b.swap(k, p);
        for i in k + 1..n {
            let f = a[i][k] / a[k][k];
            for j in k..n {
                a[i][j] -= f * a[k][j];
            }
            b[i] -= f * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        x[k] = (b[k] - (k + 1..n).map(|j| a[k][j] * x[j]).sum::<f64>()) / a[k][k];
    }
    x
}

/// XYZ weights at `n` nodes over 400–700 nm fitted to the dense colours of soap films (0–1500 nm, 0°–80°).
fn fitted_weights(n: usize) -> (Vec<f64>, Vec<[f64; 3]>) {
    let nodes = sampled_weights(n, THESIS_BAND_NM).unwrap().wavelengths_nm().to_vec();
    let dense = dense_weights();
    let mut rows: Vec<(Vec<f64>, [f64; 3])> = Vec::new();
    for d in (0..=150).map(|i| 10.0 * i as f64) {
        let s = Stack::parse(&format!("air | water {d}nm | air")).unwrap();
        for deg in [0.0, 20.0, 40.0, 60.0, 80.0] {
            let th = f64::to_radians(deg);
            let r: Vec<f64> = nodes.iter().map(|&l| s.evaluate(l, th).unwrap().r()).collect();
            let full: Vec<f64> = dense.wavelengths_nm().iter().map(|&l| s.evaluate(l, th).unwrap().r()).collect();
            rows.push((r, dense.integrate(&full).to_array()));
        }
    }
    let mut w = vec![[0.0; 3]; n];
    for c in 0..3 {
        let mut a = vec![vec![0.0; n]; n];
        let mut b = vec![0.0; n];
        for (r, y) in &rows {
            for i in 0..n {
                b[i] += r[i] * y[c];
                for j in 0..n {
                    a[i][j] += r[i] * r[j];
                }
            }
        }
        for (i, row) in a.iter_mut().enumerate() {
            row[i] += 1e-10; // a whisker of ridge for the nearly collinear nodes
        }
        for (i, x) in solve(a, b).into_iter().enumerate() {
            w[i][c] = x;
        }
    }
    (nodes, w)
}

fn fitted_colors(stack: &Stack, pts: &[(f64, f64)], nodes: &[f64], w: &[[f64; 3]]) -> Vec<Xyz> {
    pts.iter()
        .map(|&(th, o)| {
            let mut acc = [0.0; 3];
            for (&l, wi) in nodes.iter().zip(w) {
                let r = stack.evaluate_offset(l, th, o).unwrap().r();
                for c in 0..3 {
                    acc[c] += wi[c] * r;
                }
            }
            Xyz::new(acc[0], acc[1], acc[2])
        })
        .collect()
}

/// Belcour & Barla's series for a film of index `n` (non-dispersive, in air) of thickness `d + offset`,
/// truncated after `m` harmonics, with `W(t)` tabulated at 1 nm and interpolated linearly.
fn series_colors(n: f64, d: f64, pts: &[(f64, f64)], m: usize, w: &SpectralWeights) -> Vec<Xyz> {
    let t_max = 2.0 * n * (d + THESIS_D_REL_NM) * (m as f64 + 1.0);
    let transform: Vec<[f64; 3]> = (0..=t_max.ceil() as usize + 1)
        .map(|t| {
            let mut acc = [0.0; 3];
            for (&l, wl) in w.wavelengths_nm().iter().zip(w.weights()) {
                let c = (std::f64::consts::TAU * t as f64 / l).cos();
                for k in 0..3 {
                    acc[k] += wl[k] * c;
                }
            }
            acc
        })
        .collect();
    let at = |t: f64| -> [f64; 3] {
        let i = t.floor() as usize;
        let f = t - i as f64;
        [0, 1, 2].map(|k| transform[i][k] * (1.0 - f) + transform[i + 1][k] * f)
    };
    let white = at(0.0);
    pts.iter()
        .map(|&(th, o)| {
            let (s, c) = th.sin_cos();
            let c2 = (1.0 - (s / n).powi(2)).sqrt();
            let opd = 2.0 * n * (d + o).max(0.0) * c2;
            // Fresnel amplitudes air → film (eq. 3.7–3.8); film → air is their negative.
            let rs = (c - n * c2) / (c + n * c2);
            let rp = (n * c - c2) / (n * c + c2);
            let mut acc = [0.0; 3];
            for r12 in [rs, rp] {
                let x = -r12 * r12; // r₁₂ r₂₃ with r₂₃ = −r₁₂
                let k = (1.0 - r12 * r12).powi(2) / (1.0 - x * x);
                let mut sum = white;
                for h in 1..=m {
                    let wt = at(h as f64 * opd);
                    let a = 2.0 * (-x).powi(h as i32);
                    for q in 0..3 {
                        sum[q] += a * wt[q];
                    }
                }
                for q in 0..3 {
                    acc[q] += 0.5 * (white[q] - k * sum[q]);
                }
            }
            Xyz::new(acc[0], acc[1], acc[2])
        })
        .collect()
}

#[test]
fn study_of_fast_film_paths() {
    let dense_w = dense_weights();
    let mut rows: Vec<(String, String, DeltaEStats)> = Vec::new();
    for (name, max_deg) in [("0°–80°", 80.0), ("0°–89.5°", 89.5)] {
        let pts = points(max_deg);
        for s in [SOAP, OIL] {
            let stack = Stack::parse(s).unwrap();
            let dense = reflected_colors(&stack, &dense_w, &pts).unwrap();
            let e = exposure_for(&dense);
            let mut row = |method: String, colors: Vec<Xyz>| {
                let st = DeltaEStats::between(&colors, &dense, e);
                eprintln!("{s:46} {name:9} {method:32} {st}");
                rows.push((format!("{s} {name}"), method, st));
            };
            row("colour table".into(), table_colors(&stack, &pts));
            for n in [5, 8, 12, 16] {
                row(
                    format!("sparse {n}"),
                    reflected_colors(&stack, &sampled_weights(n, THESIS_BAND_NM).unwrap(), &pts).unwrap(),
                );
                let (nodes, w) = fitted_weights(n);
                row(format!("fitted quadrature {n}"), fitted_colors(&stack, &pts, &nodes, &w));
            }
            if s == SOAP {
                for m in [1, 2, 4, 8] {
                    row(format!("Belcour-Barla series M={m}"), series_colors(1.33, 500.0, &pts, m, &dense_w));
                }
            }
        }
    }
    let get = |case: &str, method: &str| rows.iter().find(|r| r.0 == case && r.1 == method).unwrap().2;
    let meets = |x: DeltaEStats| x.mean < 0.1 && x.p99 < 0.5; // issue 17's bound
    let cases = [SOAP, OIL].map(|s| [format!("{s} 0°–80°"), format!("{s} 0°–89.5°")]);
    for case in cases.iter().flatten() {
        // The table meets the bound everywhere, grazing angles included.
        assert!(meets(get(case, "colour table")), "{case}");
        // 5 and 8 wavelengths miss it, sampled evenly or with fitted weights.
        for n in [5, 8] {
            for m in ["sparse", "fitted quadrature"] {
                let x = get(case, &format!("{m} {n}"));
                assert!(!meets(x) && x.p99 > 2.0, "{case} {m} {n}: {x:?}");
            }
        }
    }
    for [to80, _] in &cases {
        // Fitted weights at 16 nodes meet it up to 80° (sparse 16 do not: their p99 is 0.53–0.76) …
        assert!(meets(get(to80, "fitted quadrature 16")) && !meets(get(to80, "sparse 16")), "{to80}");
        // … and the fit beats even sampling at 12 and 16 nodes.
        for n in [12, 16] {
            assert!(get(to80, &format!("fitted quadrature {n}")).mean < get(to80, &format!("sparse {n}")).mean);
        }
    }
    // The fitted 16 nodes fail near grazing incidence on the soap film, where the table holds.
    assert!(!meets(get(&cases[0][1], "fitted quadrature 16")), "{:?}", get(&cases[0][1], "fitted quadrature 16"));
    // The series of one layer converges with the harmonics: two miss the bound, eight meet it, grazing included.
    for case in &cases[0] {
        let (m2, m8) = (get(case, "Belcour-Barla series M=2"), get(case, "Belcour-Barla series M=8"));
        assert!(!meets(m2) && meets(m8) && m8.mean < m2.mean / 10.0, "{case}: {m2:?} {m8:?}");
    }
}
