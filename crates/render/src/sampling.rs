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
