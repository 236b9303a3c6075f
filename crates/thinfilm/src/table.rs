//! Film colour tables: the reflected and transmitted XYZ of a stack over `cos θ` × thickness offset, for
//! stacks whose thickness varies by one parameter (every layer plus the same offset: SVT, eq. 4.3). This is
//! Sussenbach's simulation table (section 3.3.4) integrated over the spectrum in advance: a pixel then costs
//! a bilinear lookup instead of the recurrence at every wavelength sample (the GPU's fast film path, issue
//! 17; docs/gpu.md has the study that chose it).
//!
//! **Resolution from the interference period.** A layer of index `n̂_j` and thickness `d_j` contributes the
//! round-trip phase `2φ_j = (4π/λ) d_j q_j`, `q_j = √(n̂_j² − n₀²(1 − c²))` (eq. 3.5–3.6 with `c = cos θ`).
//! The angle axis is `u = √c` (uniform nodes in `u` crowd towards grazing incidence, where a film's
//! transmittance falls as `c²`). Along the offset axis every layer's phase advances together, at most
//! `f_o = max_λ Σ_j 2 |n̂_j| / λ` fringes per nm (`|n̂|`, not `Re n̂`: an absorbing layer's R and T also decay
//! with thickness, at the rate `4π κ/λ`); along `u` at most `f_u = max_λ Σ_j 2 d_j max_u |dq_j/du| / λ`,
//! `dq_j/du = 2u n₀² c / q_j`, with `d_j` at the largest offset. Each axis gets [`NODES_PER_PERIOD`] nodes per
//! period of that fastest fringe, so the bilinear error of the fastest spectral component is at most
//! `(2π/m)²/8` of its amplitude (`m` nodes per period) and the colour, whose weight at the shortest
//! wavelengths is small, does better (measured: docs/gpu.md, test `tables_meet_the_colour_bound`).
//!
//! **What a table cannot do.** Where a non-absorbing layer or the substrate is optically thinner than the
//! incident medium, `q_j` vanishes at its critical angle and `R(c)` has a square-root kink there that no
//! uniform bilinear grid follows ([`TableGrid::for_stack`] refuses: evaluate directly); tables larger than
//! [`MAX_NODES`] are refused too (films many micrometres thick at grazing angles), and so are incoherent
//! layers. Offsets outside the table's range are clamped to its edge.

use iridis_color::{SpectralWeights, Xyz};
use rayon::prelude::*;

use num_complex::Complex64;

use crate::error::ThinFilmError;
use crate::stack::Stack;

/// Nodes per period of the fastest fringe on each axis. Measured against the direct 81-sample colour over
/// 0°–89.5° (test `tables_meet_the_colour_bound`; docs/gpu.md): 12 gives a worst mean ΔE00 of 0.18 and p99 of
/// 4.1, 24 of 0.05 and 1.1, 48 of 0.014 and 0.28 — inside issue 17's bound (mean 0.1, p99 0.5) on every case.
/// The last errors are the transmitted colour of thick films within 1° of grazing incidence, where each
/// interface reflects almost everything and the fringes sharpen (a high-finesse cavity).
pub const NODES_PER_PERIOD: f64 = 48.0;
/// Fewest nodes along `cos θ` (the Fresnel factors vary there even without a layer).
pub const MIN_COS_NODES: usize = 65;
/// Largest table (nodes); 4 Mi nodes are 96 MiB of `f32` XYZ pairs.
pub const MAX_NODES: usize = 1 << 22;
/// `|q_j| / n₀` below this at some angle counts as a critical angle (the table is refused).
const CRITICAL_Q: f64 = 0.05;

/// The nodes of a table: `u = √cos θ` uniform on [0, 1] (nodes crowd towards grazing incidence, where the
/// transmittance of a film falls as `cos² θ`), the offset uniform on `offset_nm` (one node when the range is
/// a point).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableGrid {
    pub cos_nodes: usize,
    pub offset_nodes: usize,
    /// The offsets (nm) of the first and the last node.
    pub offset_nm: (f64, f64),
}

impl TableGrid {
    /// The grid that resolves `stack`'s fringes over `offset_nm` (the lowest and the highest thickness
    /// offset that will be looked up) at the wavelengths `grid_nm`, or why no table can (module docs).
    pub fn for_stack(stack: &Stack, grid_nm: &[f64], offset_nm: (f64, f64)) -> Result<Self, ThinFilmError> {
        Self::with_density(stack, grid_nm, offset_nm, NODES_PER_PERIOD)
    }

    /// As [`TableGrid::for_stack`] with `nodes_per_period` nodes per period of the fastest fringe.
    pub fn with_density(
        stack: &Stack,
        grid_nm: &[f64],
        offset_nm: (f64, f64),
        nodes_per_period: f64,
    ) -> Result<Self, ThinFilmError> {
        if stack.has_incoherent() {
            return Err(ThinFilmError::Invalid(format!(
                "stack {stack}: incoherent (inc:) layers have no colour table; evaluate directly"
            )));
        }
        let media = grid_nm
            .iter()
            .map(|&l| stack.materials().map(|m| m.index_at(l)).collect::<Result<Vec<_>, _>>())
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| ThinFilmError::Invalid(format!("stack {stack}: {e}")))?;
        Self::for_indices(&media, &stack.thicknesses(), grid_nm, offset_nm, nodes_per_period)
            .map_err(|e| ThinFilmError::Invalid(format!("stack {stack}: {e}")))
    }

    /// As [`TableGrid::with_density`] from the complex indices at each wavelength of `grid_nm` (incident
    /// medium, layers, substrate) and the layer thicknesses (nm): for stacks whose indices were changed after
    /// parsing (the viewer's controls).
    pub fn for_indices(
        media: &[Vec<Complex64>],
        thicknesses_nm: &[f64],
        grid_nm: &[f64],
        offset_nm: (f64, f64),
        nodes_per_period: f64,
    ) -> Result<Self, ThinFilmError> {
        let (lo, hi) = offset_nm;
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(ThinFilmError::Invalid(format!("table offsets {lo}…{hi} nm must be finite and ordered")));
        }
        if !(nodes_per_period.is_finite() && nodes_per_period >= 1.0) {
            return Err(ThinFilmError::Invalid(format!("{nodes_per_period} nodes per period: need at least 1")));
        }
        if grid_nm.is_empty() || media.len() != grid_nm.len() {
            return Err(ThinFilmError::Invalid("a colour table needs the indices at every wavelength".into()));
        }
        let d = thicknesses_nm;
        // Below −max d every layer is clamped to 0: the colour no longer changes.
        let d_max = d.iter().copied().fold(0.0, f64::max);
        let lo = lo.max(-d_max);
        let hi = hi.max(lo);
        let (mut f_offset, mut f_cos) = (0.0f64, 0.0f64);
        let us: Vec<f64> = (0..=256).map(|i| i as f64 / 256.0).collect();
        for (&l, media) in grid_nm.iter().zip(media) {
            if media.len() != d.len() + 2 {
                return Err(ThinFilmError::Invalid(format!("{} media for {} layers", media.len(), d.len())));
            }
            let n0 = media[0].re;
            let (mut fo, mut fc) = (0.0, 0.0);
            for (j, n) in media.iter().enumerate().skip(1) {
                // |q(c)|² = |n̂² − n₀² + n₀² c²|: where Re n̂² < n₀² its zero (the critical angle, a branch point
                // of q) lies inside 0 < c ≤ 1, off the real axis by |Im n̂²| only. (At Re n̂² = n₀², q = n₀ c:
                // no kink.)
                let z = n * n - n0 * n0;
                let min_q2 = if z.re <= -n0 * n0 { (z + n0 * n0).norm() } else { z.im.abs() };
                if z.re < 0.0 && min_q2.sqrt() < CRITICAL_Q * n0 {
                    let place = if j == media.len() - 1 { "the substrate".to_string() } else { format!("layer {j}") };
                    return Err(ThinFilmError::Invalid(format!(
                        "{place} (n = {:.3}{:+.3}i at {l} nm) is below the incident medium's index {n0:.3}: its \
                         critical angle puts a kink into R(θ) that a colour table cannot follow; evaluate directly",
                        n.re, n.im
                    )));
                }
                if j == media.len() - 1 {
                    continue; // the substrate has no thickness
                }
                let dj = (d[j - 1] + hi).max(0.0);
                // |dq/du| = 2u · n₀² c / |q| with c = u².
                let slope = us
                    .iter()
                    .map(|&u| {
                        let c = u * u;
                        2.0 * u * n0 * n0 * c / (z + n0 * n0 * c * c).sqrt().norm()
                    })
                    .fold(0.0, f64::max);
                // An absorbing layer's R and T also decay with thickness, at the rate 4π κ/λ: |n̂| bounds both.
                fo += 2.0 * n.norm() / l;
                fc += 2.0 * dj * slope / l;
            }
            f_offset = f_offset.max(fo);
            f_cos = f_cos.max(fc);
        }
        let offset_nodes =
            if hi - lo <= 1e-9 { 1 } else { (((hi - lo) * f_offset * nodes_per_period).ceil() as usize + 1).max(2) };
        let cos_nodes = ((f_cos * nodes_per_period).ceil() as usize + 1).max(MIN_COS_NODES);
        let nodes = cos_nodes.saturating_mul(offset_nodes);
        if nodes > MAX_NODES {
            return Err(ThinFilmError::Invalid(format!(
                "over offsets {lo:.0}…{hi:.0} nm the colour table would need {cos_nodes} × {offset_nodes} nodes (more \
                 than {MAX_NODES}): the fringes are too dense; evaluate directly"
            )));
        }
        Ok(Self { cos_nodes, offset_nodes, offset_nm: (lo, if offset_nodes == 1 { lo } else { hi }) })
    }

    /// Nodes in all.
    pub fn len(&self) -> usize {
        self.cos_nodes * self.offset_nodes
    }

    /// True for a grid without nodes (never made by [`TableGrid::for_stack`]).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// `cos θ` of node column `i`: `u²` with `u = i / (cos_nodes − 1)`.
    pub fn cos_at(&self, i: usize) -> f64 {
        let u = i as f64 / (self.cos_nodes - 1) as f64;
        u * u
    }

    /// The offset (nm) of node row `j`.
    pub fn offset_at(&self, j: usize) -> f64 {
        if self.offset_nodes == 1 {
            return self.offset_nm.0;
        }
        let (lo, hi) = self.offset_nm;
        lo + (hi - lo) * j as f64 / (self.offset_nodes - 1) as f64
    }

    /// The cell and the weights of a lookup: `(i, fi, j, fj)` with node `(i, j)` at index `j · cos_nodes + i`,
    /// linear in `√cos θ` and the offset; `cos θ` clamped to [0, 1], the offset to the table's range.
    pub fn locate(&self, cos: f64, offset_nm: f64) -> (usize, f64, usize, f64) {
        let cell = |x: f64, n: usize| -> (usize, f64) {
            if n < 2 {
                return (0, 0.0);
            }
            let x = x.clamp(0.0, (n - 1) as f64);
            let i = (x.floor() as usize).min(n - 2);
            (i, x - i as f64)
        };
        let (i, fi) = cell(cos.clamp(0.0, 1.0).sqrt() * (self.cos_nodes - 1) as f64, self.cos_nodes);
        let (lo, hi) = self.offset_nm;
        let t = if self.offset_nodes > 1 { (offset_nm - lo) / (hi - lo) * (self.offset_nodes - 1) as f64 } else { 0.0 };
        let (j, fj) = cell(t, self.offset_nodes);
        (i, fi, j, fj)
    }
}

/// A colour table: reflected and transmitted XYZ at every node of a [`TableGrid`], node `(i, j)` at
/// `j · cos_nodes + i`, and bilinear interpolation between them.
#[derive(Debug, Clone, PartialEq)]
pub struct FilmTable {
    pub grid: TableGrid,
    pub reflected: Vec<Xyz>,
    pub transmitted: Vec<Xyz>,
}

impl FilmTable {
    /// Evaluates the stack at every node (the general `f64` path, eq. 3.1–3.13, and `weights`), in parallel.
    pub fn build(stack: &Stack, weights: &SpectralWeights, grid: TableGrid) -> Result<Self, ThinFilmError> {
        let invariant = stack.is_wavelength_invariant();
        let columns: Vec<Vec<(Xyz, Xyz)>> = (0..grid.cos_nodes)
            .into_par_iter()
            .map(|i| {
                let angle = grid.cos_at(i).clamp(0.0, 1.0).acos();
                let prepared = if invariant { Some(stack.prepare(angle)?) } else { None };
                let mut r = vec![0.0; weights.wavelengths_nm().len()];
                let mut t = r.clone();
                (0..grid.offset_nodes)
                    .map(|j| {
                        let o = grid.offset_at(j);
                        for (k, &l) in weights.wavelengths_nm().iter().enumerate() {
                            let x = match &prepared {
                                Some(p) => p.evaluate_offset(l, o)?,
                                None => stack.evaluate_offset(l, angle, o)?,
                            };
                            r[k] = x.r();
                            t[k] = x.t();
                        }
                        Ok((weights.integrate(&r), weights.integrate(&t)))
                    })
                    .collect()
            })
            .collect::<Result<_, ThinFilmError>>()?;
        let mut reflected = vec![Xyz::default(); grid.len()];
        let mut transmitted = reflected.clone();
        for (i, col) in columns.iter().enumerate() {
            for (j, &(r, t)) in col.iter().enumerate() {
                reflected[j * grid.cos_nodes + i] = r;
                transmitted[j * grid.cos_nodes + i] = t;
            }
        }
        Ok(Self { grid, reflected, transmitted })
    }

    /// Reflected and transmitted XYZ at `cos θ` and a thickness offset (nm), bilinear.
    pub fn lookup(&self, cos: f64, offset_nm: f64) -> (Xyz, Xyz) {
        let (i, fi, j, fj) = self.grid.locate(cos, offset_nm);
        let nc = self.grid.cos_nodes;
        let j1 = (j + 1).min(self.grid.offset_nodes - 1);
        let mix = |v: &[Xyz]| {
            let at = |i: usize, j: usize| v[j * nc + i].to_array();
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i, j1), at(i + 1, j1));
            let m = [0, 1, 2].map(|k| {
                let lo = a[k] + (b[k] - a[k]) * fi;
                let hi = c[k] + (d[k] - c[k]) * fi;
                lo + (hi - lo) * fj
            });
            Xyz::new(m[0], m[1], m[2])
        };
        (mix(&self.reflected), mix(&self.transmitted))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn weights() -> SpectralWeights {
        let grid = iridis_color::spectrum::uniform_grid(380.0, 780.0, 5.0).unwrap();
        SpectralWeights::new(&grid, iridis_color::Illuminant::D65, iridis_color::Observer::Cie1931)
    }

    #[test]
    fn resolution_follows_the_fringe_period() {
        let w = weights();
        // Water 500 nm in air over ±400 nm: f_o = 2·1.33/380 fringes per nm over 800 nm.
        let s = Stack::parse("air | water 500nm | air").unwrap();
        let g = TableGrid::for_stack(&s, w.wavelengths_nm(), (-400.0, 400.0)).unwrap();
        assert_eq!(g.offset_nodes, (800.0 * 2.0 * 1.33 / 380.0 * NODES_PER_PERIOD).ceil() as usize + 1);
        // f_u = 2 · 900 nm · (2/1.33, the slope of q in u at u = 1) / 380 nm.
        let m = NODES_PER_PERIOD;
        assert_eq!(g.cos_nodes, ((2.0 * 900.0 * 2.0 / 1.33 / 380.0 * m).ceil() as usize + 1).max(MIN_COS_NODES));
        // Ten times thicker: ten times the cos nodes, the same offset nodes.
        let t = Stack::parse("air | water 5000nm | air").unwrap();
        let h = TableGrid::for_stack(&t, w.wavelengths_nm(), (-400.0, 400.0)).unwrap();
        assert_eq!(h.offset_nodes, g.offset_nodes);
        assert_eq!(h.cos_nodes, (2.0 * 5400.0 * 2.0 / 1.33 / 380.0 * NODES_PER_PERIOD).ceil() as usize + 1);
        // Offsets below −d clamp every layer to 0: the range starts there; a point range has one row.
        let g = TableGrid::for_stack(&s, w.wavelengths_nm(), (-900.0, -600.0)).unwrap();
        assert_eq!((g.offset_nodes, g.offset_nm), (1, (-500.0, -500.0)));
        assert_eq!(TableGrid::for_stack(&s, w.wavelengths_nm(), (0.0, 0.0)).unwrap().offset_nodes, 1);
    }

    #[test]
    fn what_a_table_cannot_do_is_refused_with_the_reason() {
        let w = weights();
        let e =
            TableGrid::for_stack(&Stack::parse("n=1.5 | n=1.0 300nm | n=1.5").unwrap(), w.wavelengths_nm(), (0.0, 0.0))
                .unwrap_err()
                .to_string();
        assert!(e.contains("layer 1") && e.contains("critical angle"), "{e}");
        let e =
            TableGrid::for_stack(&Stack::parse("glass | n=1.6 100nm | air").unwrap(), w.wavelengths_nm(), (0.0, 0.0))
                .unwrap_err()
                .to_string();
        assert!(e.contains("substrate") && e.contains("critical angle"), "{e}");
        let e =
            TableGrid::for_stack(&Stack::parse("air | water 5mm | air").unwrap(), w.wavelengths_nm(), (-100.0, 100.0))
                .unwrap_err()
                .to_string();
        assert!(e.contains("too dense"), "{e}");
        assert!(TableGrid::for_stack(
            &Stack::parse("air | inc:BK7 1mm | air").unwrap(),
            w.wavelengths_nm(),
            (0.0, 0.0)
        )
        .is_err());
        // A metal layer is absorbing: its index below the incident medium's has no critical angle.
        assert!(TableGrid::for_stack(&Stack::parse("air | Au 30nm | glass").unwrap(), w.wavelengths_nm(), (0.0, 0.0))
            .is_ok());
    }

    #[test]
    fn nodes_hold_the_direct_colour_and_cells_interpolate() {
        let w = weights();
        let s = Stack::parse("air | gasoline 216nm | water 220nm | asphalt").unwrap();
        let g = TableGrid::for_stack(&s, w.wavelengths_nm(), (-100.0, 100.0)).unwrap();
        let t = FilmTable::build(&s, &w, g).unwrap();
        for (i, j) in [(0, 0), (7, 3), (g.cos_nodes - 1, g.offset_nodes - 1)] {
            let (c, o) = (g.cos_at(i), g.offset_at(j));
            let direct: Vec<(f64, f64)> = w
                .wavelengths_nm()
                .iter()
                .map(|&l| {
                    let x = s.evaluate_offset(l, c.acos(), o).unwrap();
                    (x.r(), x.t())
                })
                .collect();
            let r = w.integrate(&direct.iter().map(|x| x.0).collect::<Vec<_>>());
            let (tr, tt) = t.lookup(c, o);
            assert!((tr.y - r.y).abs() < 1e-12 && (tr.x - r.x).abs() < 1e-12, "{i} {j}");
            assert!((tr.y + tt.y - 1.0).abs() < 1e-12); // lossless: R + T = 1 at the nodes
        }
        // Halfway between two nodes: the mean of the two.
        let (a, _) = t.lookup(g.cos_at(10), g.offset_at(2));
        let (b, _) = t.lookup(g.cos_at(11), g.offset_at(2));
        let u = 0.5 * (g.cos_at(10).sqrt() + g.cos_at(11).sqrt());
        let (m, _) = t.lookup(u * u, g.offset_at(2));
        assert!((m.y - 0.5 * (a.y + b.y)).abs() < 1e-12);
        // Outside the range: the edge.
        assert_eq!(t.lookup(0.3, 500.0), t.lookup(0.3, 100.0));
    }
}
