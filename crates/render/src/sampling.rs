//! Monte Carlo building blocks: a per-sample random stream, sampling of directions (cosine, GGX visible
//! normals, piecewise-constant 2-D distributions), and the power heuristic of multiple importance sampling.
//! The GPU shader (`scene.wgsl`) implements the same samplers on the same data.
//!
//! Conventions: a pdf is per unit solid angle unless said otherwise; directions point away from the surface.

use std::cell::Cell;

use crate::math::*;

thread_local! {
    static STATE: Cell<u64> = const { Cell::new(0x853c_49e6_748f_ea9b) };
}

/// splitmix64's finaliser: a bijective 64-bit mix.
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Starts the random stream of one camera sample (pixel index, sample index): the render is reproducible
/// whatever the thread that takes the pixel. The stream is thread-local, so the renderer's recursion needs no
/// extra argument; every sample begins with a call to this.
pub fn seed(pixel: u64, sample: u64) {
    STATE.with(|s| s.set(mix64(pixel.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ mix64(sample.wrapping_add(1)))));
}

/// The next uniform number in `[0, 1)` of this thread's stream (splitmix64, 53 bits).
pub fn next() -> f64 {
    STATE.with(|s| {
        let x = s.get().wrapping_add(0x9e37_79b9_7f4a_7c15);
        s.set(x);
        (mix64(x) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    })
}

/// Two uniform numbers.
pub fn next2() -> [f64; 2] {
    [next(), next()]
}

/// The power heuristic (β = 2, Veach 1997, eq. 9.13) for one sample of each of two techniques: the weight of
/// the technique whose pdf is `a` when the other's is `b`. Written as `1 / (1 + (b/a)²)` so that a very
/// peaked pdf (a near-mirror GGX lobe) cannot overflow.
pub fn power_heuristic(a: f64, b: f64) -> f64 {
    if a <= 0.0 {
        return 0.0;
    }
    let r = b / a;
    1.0 / (1.0 + r * r)
}

/// An orthonormal frame `(t, b, n)` around a unit normal (Duff et al. 2017, branchless).
pub fn frame(n: V3) -> (V3, V3) {
    let s = if n[2] >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n[2]);
    let b = n[0] * n[1] * a;
    ([1.0 + s * n[0] * n[0] * a, s * b, -s * n[0]], [b, s + n[1] * n[1] * a, -n[1]])
}

/// `x·t + y·b + z·n`.
pub fn from_local(t: V3, b: V3, n: V3, v: V3) -> V3 {
    add(add(mul(t, v[0]), mul(b, v[1])), mul(n, v[2]))
}

/// A point of the unit disk from the unit square, area-preserving (Shirley & Chiu's concentric map).
pub fn concentric_disk(u: [f64; 2]) -> [f64; 2] {
    let (a, b) = (2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0);
    if a == 0.0 && b == 0.0 {
        return [0.0, 0.0];
    }
    let (r, phi) = if a.abs() > b.abs() {
        (a, std::f64::consts::FRAC_PI_4 * (b / a))
    } else {
        (b, std::f64::consts::FRAC_PI_2 - std::f64::consts::FRAC_PI_4 * (a / b))
    };
    [r * phi.cos(), r * phi.sin()]
}

/// A cosine-distributed direction about `n` (pdf `cos θ / π`).
pub fn cosine_hemisphere(n: V3, u: [f64; 2]) -> V3 {
    let d = concentric_disk(u);
    let z = (1.0 - d[0] * d[0] - d[1] * d[1]).max(0.0).sqrt();
    let (t, b) = frame(n);
    from_local(t, b, n, [d[0], d[1], z])
}

/// A uniformly distributed direction on the sphere (pdf `1 / 4π`).
pub fn uniform_sphere(u: [f64; 2]) -> V3 {
    let z = 1.0 - 2.0 * u[0];
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f64::consts::TAU * u[1];
    [r * phi.cos(), r * phi.sin(), z]
}

/// A half vector from GGX's distribution of normals visible from `wo` (Heitz 2018, "Sampling the GGX
/// Distribution of Visible Normals", JCGT 7(4)), isotropic `α`, in the frame whose z is the normal: its pdf
/// is `G_1(ω_o) max(0, ω_o·h) D(h) / cos θ_o`, and the reflected direction's is that over `4 ω_o·h`.
pub fn ggx_visible_normal(wo: V3, alpha: f64, u: [f64; 2]) -> V3 {
    let vh = normalize([alpha * wo[0], alpha * wo[1], wo[2]]);
    let len2 = vh[0] * vh[0] + vh[1] * vh[1];
    let t1 = if len2 > 0.0 { mul([-vh[1], vh[0], 0.0], 1.0 / len2.sqrt()) } else { [1.0, 0.0, 0.0] };
    let t2 = cross(vh, t1);
    let r = u[0].sqrt();
    let phi = std::f64::consts::TAU * u[1];
    let (p1, mut p2) = (r * phi.cos(), r * phi.sin());
    let s = 0.5 * (1.0 + vh[2]);
    p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * p2;
    let nh = add(add(mul(t1, p1), mul(t2, p2)), mul(vh, (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt()));
    normalize([alpha * nh[0], alpha * nh[1], nh[2].max(1e-12)])
}

/// A piecewise-constant distribution over the cells of a `cols × rows` grid: a row by the marginal, a column
/// by that row's conditional (inverse CDFs, binary search). The weights need not be normalised.
#[derive(Debug, Clone)]
pub struct Distribution2d {
    pub cols: usize,
    pub rows: usize,
    /// Row CDF, `rows + 1` values from 0 to 1.
    pub marginal: Vec<f64>,
    /// Per row, its column CDF (`cols + 1` values from 0 to 1).
    pub conditional: Vec<f64>,
    /// Probability of each cell (row-major).
    pub prob: Vec<f64>,
}

impl Distribution2d {
    /// `None` when every weight is zero (nothing to sample).
    pub fn new(cols: usize, rows: usize, weights: &[f64]) -> Option<Self> {
        assert_eq!(weights.len(), cols * rows, "a weight per cell");
        let total: f64 = weights.iter().map(|w| w.max(0.0)).sum();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let mut marginal = vec![0.0; rows + 1];
        let mut conditional = vec![0.0; rows * (cols + 1)];
        for r in 0..rows {
            let row = &weights[r * cols..(r + 1) * cols];
            let sum: f64 = row.iter().map(|w| w.max(0.0)).sum();
            marginal[r + 1] = marginal[r] + sum / total;
            let c = &mut conditional[r * (cols + 1)..(r + 1) * (cols + 1)];
            for (k, w) in row.iter().enumerate() {
                c[k + 1] = c[k] + if sum > 0.0 { w.max(0.0) / sum } else { 1.0 / cols as f64 };
            }
            c[cols] = 1.0;
        }
        marginal[rows] = 1.0;
        let prob = weights.iter().map(|w| w.max(0.0) / total).collect();
        Some(Self { cols, rows, marginal, conditional, prob })
    }

    /// A cell and the position inside it (`[0, 1)²`, for a uniform point in the cell) from two uniform numbers.
    pub fn sample(&self, u: [f64; 2]) -> (usize, usize, [f64; 2]) {
        let (r, fr) = invert(&self.marginal, u[1]);
        let c0 = r * (self.cols + 1);
        let (c, fc) = invert(&self.conditional[c0..c0 + self.cols + 1], u[0]);
        (c, r, [fc, fr])
    }

    /// Probability of cell `(col, row)`.
    pub fn prob(&self, col: usize, row: usize) -> f64 {
        self.prob[row * self.cols + col]
    }
}

/// The interval of a CDF (`n + 1` increasing values from 0 to 1) that holds `u`, and where in it `u` lies.
fn invert(cdf: &[f64], u: f64) -> (usize, f64) {
    let n = cdf.len() - 1;
    // The last index whose value is ≤ u, skipping empty intervals.
    let i = (cdf.partition_point(|&c| c <= u).max(1) - 1).min(n - 1);
    let w = cdf[i + 1] - cdf[i];
    let f = if w > 0.0 { ((u - cdf[i]) / w).clamp(0.0, 1.0 - 1e-12) } else { 0.5 };
    (i, f)
}

/// `∫ f(ω) dω` over the sphere of directions by the midpoint rule on an `nt × np` grid in (θ, φ), `θ` from
/// the y axis (the tests' check that a pdf over directions integrates to 1).
#[cfg(test)]
pub(crate) fn sphere_integral(nt: usize, np: usize, mut f: impl FnMut(V3) -> f64) -> f64 {
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

#[cfg(test)]
mod tests {
    use super::*;

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
                    let pdf = crate::energy::smith_g1(a2, mu) * crate::energy::ggx_d(a2, h[2]) / (4.0 * mu);
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
}
