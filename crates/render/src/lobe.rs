//! The diffraction lobe of a lookup table, for extended light:
//!
//! * [`LobeSampler`] importance-samples it. The table holds `I_p(u, v)` on a u-v grid with
//!   `(u, v, w) = −ω_i − ω_o` (paper sec. 5); for a view `ω_o` a point `(u, v)` is the light direction
//!   `ω_i = (−u − x_o, −v − y_o, √(1 − …))`, so a 2-D distribution over the grid's cells ∝ the luminance
//!   `Y(u, v) = Σ_p w^p I_p^Y(u, v)` is a distribution of light directions, with solid-angle pdf
//!   `p_uv(u, v) cos θ_i` (the hemisphere projects onto the unit disk with `dA = cos θ dω`). `w` varies with
//!   the directions; the luminance is tabulated at [`LOBE_LEVELS`] values `w = −2 c` (the `w` of the mirror
//!   configuration for `cos θ_o = c`) and a view uses the level nearest `cos θ_o`. The pdf a view uses to sample
//!   is the one it evaluates, so the estimator is unbiased whatever the level's mismatch costs in variance; the
//!   factor `C(ω_i, ω_o)` (Fresnel, geometry, shadowing) is left out of the distribution.
//! * [`Prefiltered`] is the real-time counterpart: the table integrated over a square of the u-v plane
//!   (summed-area tables of every power `I_p`), i.e. the lobe convolved with a light of solid angle `Ω`
//!   — a prefiltered area light. A light seen under `Ω` from direction `ω_i` covers about `Ω cos θ_i` of the
//!   u-v plane; its contribution is the mean of the lobe over that square times the light's irradiance,
//!   instead of the lobe's value at the centre.

use iridis_diffraction::table::{grid_index, Lookup};

use crate::math::*;
use crate::sampling::Distribution2d;

/// Number of `w` levels of the lobe's distribution.
pub const LOBE_LEVELS: usize = 8;

/// `cos θ_o` of level `k`: the midpoints of `LOBE_LEVELS` equal bins of `[0, 1]`.
pub fn level_cos(k: usize) -> f64 {
    (k as f64 + 0.5) / LOBE_LEVELS as f64
}

/// The level for a view with `cos θ_o = c`.
pub fn level_of(c: f64) -> usize {
    ((c.clamp(0.0, 1.0) * LOBE_LEVELS as f64) as usize).min(LOBE_LEVELS - 1)
}

/// Importance sampling of a table's diffraction lobe (see the module notes).
#[derive(Debug, Clone)]
pub struct LobeSampler {
    /// Grid values along u and v (the table's).
    pub uv: Vec<f64>,
    /// One distribution over the `(res − 1)²` cells per level; `None` where the lobe is black.
    pub levels: Vec<Option<Distribution2d>>,
}

/// `Σ_p w^p I_p^Y` at grid node `(iu, iv)`.
fn node_luminance(lookup: &Lookup, iu: usize, iv: usize, w: f64) -> f64 {
    let t = &lookup.table;
    let (res, np) = (t.meta.uv_resolution, t.powers());
    let base = ((iv * res + iu) * 3 + 1) * np;
    t.data[base..base + np].iter().rev().fold(0.0, |acc, &x| acc * w + x)
}

impl LobeSampler {
    pub fn new(lookup: &Lookup) -> Self {
        let t = &lookup.table;
        let res = t.meta.uv_resolution;
        let n = res - 1;
        let levels = (0..LOBE_LEVELS)
            .map(|k| {
                let w = -2.0 * level_cos(k);
                let y: Vec<f64> =
                    (0..res * res).map(|i| node_luminance(lookup, i % res, i / res, w).max(0.0)).collect();
                let weights: Vec<f64> = (0..n * n)
                    .map(|c| {
                        let (iu, iv) = (c % n, c / n);
                        let mean = 0.25
                            * (y[iv * res + iu]
                                + y[iv * res + iu + 1]
                                + y[(iv + 1) * res + iu]
                                + y[(iv + 1) * res + iu + 1]);
                        mean * (t.uv[iu + 1] - t.uv[iu]) * (t.uv[iv + 1] - t.uv[iv])
                    })
                    .collect();
                Distribution2d::new(n, n, &weights)
            })
            .collect();
        Self { uv: t.uv.clone(), levels }
    }

    /// Area of cell `(iu, iv)` in the u-v plane.
    fn cell_area(&self, iu: usize, iv: usize) -> f64 {
        (self.uv[iu + 1] - self.uv[iu]) * (self.uv[iv + 1] - self.uv[iv])
    }

    /// The cell index holding `x` along one axis.
    fn cell_of(&self, x: f64) -> Option<usize> {
        let n = self.uv.len() - 1;
        if !(x >= self.uv[0] && x <= self.uv[n]) {
            return None;
        }
        Some((self.uv.partition_point(|&g| g <= x).max(1) - 1).min(n - 1))
    }

    /// A light direction (local frame, z the normal) for the view `lo` and its solid-angle pdf; `None` where
    /// the drawn `(u, v)` has no light direction above the horizon (that mass is lost: the estimator counts it
    /// as zero, which keeps it unbiased).
    pub fn sample(&self, lo: V3, u: [f64; 2]) -> Option<(V3, f64)> {
        let d = self.levels[level_of(lo[2])].as_ref()?;
        let (iu, iv, f) = d.sample(u);
        let uu = self.uv[iu] + f[0] * (self.uv[iu + 1] - self.uv[iu]);
        let vv = self.uv[iv] + f[1] * (self.uv[iv + 1] - self.uv[iv]);
        let (x, y) = (-uu - lo[0], -vv - lo[1]);
        let s2 = x * x + y * y;
        if s2 >= 1.0 {
            return None;
        }
        let z = (1.0 - s2).sqrt();
        Some(([x, y, z], d.prob(iu, iv) / self.cell_area(iu, iv) * z))
    }

    /// The solid-angle pdf of light direction `li` for the view `lo` (local frame).
    pub fn pdf(&self, lo: V3, li: V3) -> f64 {
        if li[2] <= 0.0 {
            return 0.0;
        }
        let Some(d) = self.levels[level_of(lo[2])].as_ref() else { return 0.0 };
        match (self.cell_of(-li[0] - lo[0]), self.cell_of(-li[1] - lo[1])) {
            (Some(iu), Some(iv)) => d.prob(iu, iv) / self.cell_area(iu, iv) * li[2],
            _ => 0.0,
        }
    }
}

/// Summed-area tables of every power `I_p` of a lookup table over the u-v plane (see the module notes): the
/// exact integral of the table's values interpolated bilinearly in `u` and `v` between grid nodes, from three
/// prefix tables — the double integral `F` at the nodes, and the single integrals along `v` at each node's `u`
/// (`C`) and along `u` at each node's `v` (`R`) — that make the integral up to any point inside a cell exact
/// too (a piecewise-linear interpolation of `F` alone would flatten the interpolant inside a cell).
#[derive(Debug, Clone)]
pub struct Prefiltered {
    pub res: usize,
    pub np: usize,
    pub uv: Vec<f64>,
    pub uv_power: f64,
    /// `F[((iv · res + iu) · 3 + c) · np + p] = ∫_{u_0}^{u_iu} ∫_{v_0}^{v_iv} I_p du dv` (the table's layout).
    pub f: Vec<f64>,
    /// `C[…] = ∫_{v_0}^{v_iv} I_p(u_iu, v) dv`.
    pub c: Vec<f64>,
    /// `R[…] = ∫_{u_0}^{u_iu} I_p(u, v_iv) du`.
    pub r: Vec<f64>,
}

impl Prefiltered {
    pub fn new(lookup: &Lookup) -> Self {
        let t = &lookup.table;
        let (res, np) = (t.meta.uv_resolution, t.powers());
        let idx = |iu: usize, iv: usize, c: usize, p: usize| ((iv * res + iu) * 3 + c) * np + p;
        let at = |iu: usize, iv: usize, c: usize, p: usize| t.data[idx(iu, iv, c, p)];
        let n = res * res * 3 * np;
        let (mut f, mut cc, mut rr) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for iv in 0..res {
            for iu in 0..res {
                for c in 0..3 {
                    for p in 0..np {
                        // The trapezoid rule is exact for the bilinear interpolant.
                        if iv > 0 {
                            let dv = t.uv[iv] - t.uv[iv - 1];
                            cc[idx(iu, iv, c, p)] =
                                cc[idx(iu, iv - 1, c, p)] + 0.5 * dv * (at(iu, iv - 1, c, p) + at(iu, iv, c, p));
                        }
                        if iu > 0 {
                            let du = t.uv[iu] - t.uv[iu - 1];
                            rr[idx(iu, iv, c, p)] =
                                rr[idx(iu - 1, iv, c, p)] + 0.5 * du * (at(iu - 1, iv, c, p) + at(iu, iv, c, p));
                        }
                        if iu > 0 && iv > 0 {
                            let area = (t.uv[iu] - t.uv[iu - 1]) * (t.uv[iv] - t.uv[iv - 1]);
                            let cell = 0.25
                                * (at(iu - 1, iv - 1, c, p)
                                    + at(iu, iv - 1, c, p)
                                    + at(iu - 1, iv, c, p)
                                    + at(iu, iv, c, p))
                                * area;
                            f[idx(iu, iv, c, p)] = cell + f[idx(iu - 1, iv, c, p)] + f[idx(iu, iv - 1, c, p)]
                                - f[idx(iu - 1, iv - 1, c, p)];
                        }
                    }
                }
            }
        }
        Self { res, np, uv: t.uv.clone(), uv_power: t.meta.uv_power, f, c: cc, r: rr }
    }

    /// The grid cell and the linear fraction inside it of coordinate `x`, clamped to the grid.
    fn locate(&self, x: f64) -> (usize, f64) {
        let n = self.res - 1;
        let x = x.clamp(self.uv[0], self.uv[n]);
        let i = (grid_index(x, self.res, self.uv_power).floor() as usize).min(n - 1);
        let (a, b) = (self.uv[i], self.uv[i + 1]);
        (i, ((x - a) / (b - a)).clamp(0.0, 1.0))
    }

    /// `∫_{u_0}^{u} ∫_{v_0}^{v} I_p` for every channel and power, added with `sign` into `out` (`3 · np`).
    fn accumulate(&self, table: &[f64], u: f64, v: f64, sign: f64, out: &mut [f64]) {
        let (i, t) = self.locate(u);
        let (j, s) = self.locate(v);
        let (du, dv) = (self.uv[i + 1] - self.uv[i], self.uv[j + 1] - self.uv[j]);
        // Weights of the nodes' F, C, R and values (module notes: the cell's share is the bilinear interpolant
        // integrated over [u_i, u] × [v_j, v]).
        let (a0, a1) = (t - 0.5 * t * t, 0.5 * t * t);
        let (b0, b1) = (s - 0.5 * s * s, 0.5 * s * s);
        let np = self.np;
        let base = |iu: usize, iv: usize| (iv * self.res + iu) * 3 * np;
        let terms: [(&[f64], usize, f64); 9] = [
            (&self.f, base(i, j), 1.0),
            (&self.c, base(i, j), du * a0),
            (&self.c, base(i + 1, j), du * a1),
            (&self.r, base(i, j), dv * b0),
            (&self.r, base(i, j + 1), dv * b1),
            (table, base(i, j), du * dv * a0 * b0),
            (table, base(i + 1, j), du * dv * a1 * b0),
            (table, base(i, j + 1), du * dv * a0 * b1),
            (table, base(i + 1, j + 1), du * dv * a1 * b1),
        ];
        for (src, b, w) in terms {
            let w = w * sign;
            if w != 0.0 {
                for (o, x) in out.iter_mut().zip(&src[b..b + 3 * np]) {
                    *o += w * x;
                }
            }
        }
    }

    /// `Σ_p w^p ∫∫ I_p` over `[u0, u1] × [v0, v1]`, per channel.
    pub fn integral(&self, table: &[f64], u0: f64, u1: f64, v0: f64, v1: f64, w: f64) -> [f64; 3] {
        let mut acc = vec![0.0; 3 * self.np];
        for (u, v, sign) in [(u1, v1, 1.0), (u0, v1, -1.0), (u1, v0, -1.0), (u0, v0, 1.0)] {
            self.accumulate(table, u, v, sign, &mut acc);
        }
        let np = self.np;
        [0, 1, 2].map(|c| acc[c * np..(c + 1) * np].iter().rev().fold(0.0, |a, &x| a * w + x))
    }

    /// The mean of `Σ_p w^p I_p` over the square of area `Ω cos θ_i` centred on the `(u, v)` of the
    /// directions (local frame): the lobe seen through a light of solid angle `omega` around `li`. A square
    /// narrower than the grid's cell there is averaged by 2 × 2 Gauss points of the lookup itself (the lookup
    /// interpolates in the grid's index space, which the tables' interpolation in `u`, `v` approaches only
    /// across many cells); a wider one exactly by the tables.
    pub fn mean(&self, lookup: &Lookup, li: V3, lo: V3, omega: f64) -> [f64; 3] {
        let (u, v, w) = (-li[0] - lo[0], -li[1] - lo[1], -li[2] - lo[2]);
        let half = 0.5 * (omega * li[2].max(0.0)).sqrt();
        if half <= 0.0 {
            return lookup.sum(u, v, w);
        }
        let cell = |x: f64| {
            let (i, _) = self.locate(x);
            self.uv[i + 1] - self.uv[i]
        };
        if 2.0 * half < cell(u).min(cell(v)) {
            let g = half / 3f64.sqrt();
            let mut acc = [0.0; 3];
            for (du, dv) in [(-g, -g), (g, -g), (-g, g), (g, g)] {
                let x = lookup.sum(u + du, v + dv, w);
                for c in 0..3 {
                    acc[c] += 0.25 * x[c];
                }
            }
            return acc;
        }
        let s = self.integral(&lookup.table.data, u - half, u + half, v - half, v + half, w);
        s.map(|x| x / (4.0 * half * half))
    }
}
