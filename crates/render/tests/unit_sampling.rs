//! The unit tests of src/sampling.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::math::*;
use iridis_render::sampling::*;

/// `∫ f(ω) dω` over the sphere of directions by the midpoint rule on an `nt × np` grid in (θ, φ), `θ` from
/// the y axis (the tests' check that a pdf over directions integrates to 1).
pub fn sphere_integral(nt: usize, np: usize, mut f: impl FnMut(V3) -> f64) -> f64 {
    let mut acc = 0.0;
    for i in 0..nt {
        let th = std::f64::consts::PI * (i as f64 + 0.5) / nt as f64;
        let dw = th.sin() * std::f64::consts::PI / nt as f64 * std::f64::consts::TAU / np as f64;
        for j in 0..np {
            let ph = std::f64::consts::TAU * (j as f64 + 0.5) / np as f64;
            acc += f([th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()]) * dw;
        }
    }
    acc
}

#[test]
fn the_stream_is_uniform_and_reproducible() {
    seed(7, 3);
    let a: Vec<f64> = (0..4).map(|_| next()).collect();
    seed(7, 3);
    let b: Vec<f64> = (0..4).map(|_| next()).collect();
    assert_eq!(a, b);
    seed(1, 0);
    let n = 200_000;
    let mean = (0..n).map(|_| next()).sum::<f64>() / n as f64;
    // The mean of n uniforms has standard deviation 1/sqrt(12 n) = 6.5e-4.
    assert!((mean - 0.5).abs() < 4.0 * (1.0 / (12.0 * n as f64)).sqrt(), "{mean}");
}

#[test]
fn a_distribution_samples_its_cells_in_proportion() {
    let w = [1.0, 0.0, 3.0, 2.0, 2.0, 0.0];
    let d = Distribution2d::new(3, 2, &w).unwrap();
    let mut counts = [0usize; 6];
    let n = 60_000;
    seed(2, 0);
    for _ in 0..n {
        let (c, r, f) = d.sample(next2());
        assert!((0.0..1.0).contains(&f[0]) && (0.0..1.0).contains(&f[1]));
        counts[r * 3 + c] += 1;
    }
    for k in 0..6 {
        let p = w[k] / 8.0;
        let got = counts[k] as f64 / n as f64;
        // Binomial standard deviation sqrt(p(1-p)/n) ≤ 2e-3.
        assert!((got - p).abs() < 0.01, "cell {k}: {got} vs {p}");
        assert!((d.prob(k % 3, k / 3) - p).abs() < 1e-12);
    }
    assert!(Distribution2d::new(2, 1, &[0.0, 0.0]).is_none());
}

#[test]
fn ggx_visible_normals_have_the_stated_pdf() {
    // The reflected direction's density is G_1(ω_o) D(h) / (4 cos θ_o) wherever it lies above the horizon
    // (samples below it are lost mass, counted as zero), so E[f/pdf] = ∫ f dω over the hemisphere for any f:
    // with f = cos θ_i the integral is π. GGX's D is bounded below on the hemisphere for these α, so the
    // estimator has finite variance and its standard error is measured.
    for (alpha, mu) in [(0.3f64, 0.8f64), (0.7, 0.3), (0.5, 1.0)] {
        let wo = [(1.0 - mu * mu).sqrt(), 0.0, mu];
        let a2 = alpha * alpha;
        seed(11, 0);
        let n = 400_000;
        let (mut acc, mut acc2) = (0.0, 0.0);
        for _ in 0..n {
            let h = ggx_visible_normal(wo, alpha, next2());
            let vh = dot(wo, h);
            let wi = sub(mul(h, 2.0 * vh), wo);
            let x = if wi[2] > 0.0 && vh > 0.0 {
                let pdf = iridis_render::energy::smith_g1(a2, mu) * iridis_render::energy::ggx_d(a2, h[2]) / (4.0 * mu);
                wi[2] / pdf
            } else {
                0.0
            };
            acc += x;
            acc2 += x * x;
        }
        let mean = acc / n as f64;
        let se = ((acc2 / n as f64 - mean * mean) / n as f64).sqrt();
        assert!((mean - std::f64::consts::PI).abs() < 4.0 * se, "α {alpha}, μ {mu}: {mean} ± {se}");
        assert!(se < 0.02, "α {alpha}: standard error {se}");
    }
}

#[test]
fn cosine_and_concentric_samples_have_their_pdfs() {
    // ∫ over the hemisphere of f = 1 + x: 2π, estimated with pdf cos θ / π; the disk map keeps area.
    seed(5, 0);
    let n = [0.3, -0.5, 0.81];
    let n = normalize(n);
    let (t, _) = frame(n);
    let m = 200_000;
    let (mut acc, mut acc2) = (0.0, 0.0);
    for _ in 0..m {
        let w = cosine_hemisphere(n, next2());
        let c = dot(w, n);
        let x = if c > 0.0 { (1.0 + dot(w, t)) / (c / std::f64::consts::PI) } else { 0.0 };
        acc += x;
        acc2 += x * x;
    }
    let mean = acc / m as f64;
    let se = ((acc2 / m as f64 - mean * mean) / m as f64).sqrt();
    assert!((mean - std::f64::consts::TAU).abs() < 4.0 * se, "{mean} ± {se}");
    // Quarter of the disk's area lies in the first quadrant of the square's image.
    let q = (0..m).filter(|_| {
        let d = concentric_disk(next2());
        d[0] > 0.0 && d[1] > 0.0
    });
    let frac = q.count() as f64 / m as f64;
    assert!((frac - 0.25).abs() < 4.0 * (0.25 * 0.75 / m as f64).sqrt(), "{frac}");
}
