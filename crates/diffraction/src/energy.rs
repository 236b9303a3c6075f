//! The diffraction lobe's energy: its directional albedo `A(ω_o) = ∫ f_r(ω_i, ω_o) cos θ_i dω_i`.
//!
//! An evaluator's colour is `ρ = f_r cos θ_i` (the paper's eq. 9 carries the `cos θ_i`), so
//! `A(ω_o) = ∫ ρ dω_i`. Over the unit disk of `(x, y) = ω_i,xy`, `dω_i = dx dy / cos θ_i`, and with the paper's
//! `(u, v) = −ω_i,xy − ω_o,xy` (a shift) `dx dy = du dv`:
//!
//! `A(ω_o) = ∬ ρ(ω_i(u, v), ω_o) / cos θ_i du dv`.
//!
//! The lobe lives on the `(u, v)` plane around the orders `u = mλ/d`, with the specular peak at `u = v = 0`: the
//! same plane the lookup tables sample, densely near 0 (paper sec. 5). The quadrature here uses such a grid
//! (for a lookup table, its own grid refined: the integral is that of what the evaluator returns). In
//! [`crate::Units::Radiometric`] a flat surface gives `A = R(θ_o)/R₀`, a rough one less (tests:
//! `crates/diffraction/tests/energy.rs`).

use iridis_color::Xyz;

use crate::evaluator::Evaluator;
use crate::geometry::Vec3;
use crate::table::grid_value;

/// The smallest `cos θ_i` the quadrature divides by (see [`directional_albedo`]).
const RIM_COS: f64 = 1e-3;

/// Nodes and trapezoid weights of one axis of the `(u, v)` quadrature.
#[derive(Debug, Clone)]
pub struct AlbedoGrid {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl AlbedoGrid {
    /// The trapezoid rule on increasing nodes covering `[−2, 2]` (every `ω_i` of the hemisphere for every `ω_o`).
    pub fn from_nodes(nodes: &[f64]) -> Result<Self, crate::DiffractionError> {
        let n = nodes.len();
        let increasing = nodes.windows(2).all(|w| w[1] > w[0]);
        if n < 3 || !increasing || nodes[0] > -2.0 + 1e-12 || nodes[n - 1] < 2.0 - 1e-12 {
            return Err(crate::DiffractionError::Invalid(
                "the albedo grid needs at least three increasing nodes from −2 to 2".into(),
            ));
        }
        let mut weights = vec![0.0; n];
        for i in 0..n - 1 {
            let h = (nodes[i + 1] - nodes[i]) / 2.0;
            weights[i] += h;
            weights[i + 1] += h;
        }
        Ok(Self { nodes: nodes.to_vec(), weights })
    }

    /// The lookup tables' grid, `2·sign(s)|s|^power` at `res` points (paper sec. 5).
    pub fn power(res: usize, power: f64) -> Result<Self, crate::DiffractionError> {
        let nodes: Vec<f64> = (0..res.max(3)).map(|i| grid_value(i, res.max(3), power)).collect();
        Self::from_nodes(&nodes)
    }

    /// The grid for an evaluator: for a lookup table its own grid refined once (every cell halved in index
    /// space), at most `max_res` points; else the paper's power-5 grid at `max_res` points. On a table's own
    /// nodes the trapezoid rule over-counts a narrow lobe (a flat patch at 32 µm coherence, 101² table: +1.1 %
    /// against the 801-point integral of the same interpolant); halved, +0.25 %.
    pub fn for_evaluator(eval: &dyn Evaluator, max_res: usize) -> Result<Self, crate::DiffractionError> {
        match eval.as_lookup() {
            Some(l) => Self::power((2 * l.table.uv.len() - 1).min(max_res), l.table.meta.uv_power),
            None => Self::power(max_res, 5.0),
        }
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
}

/// `A(ω_o)` in the evaluator's units (colour weights of its spectral setup): XYZ of the light the lobe reflects
/// into `ω_o` from a uniform white sky, per unit radiance. `wo` is a unit vector in the surface frame with
/// `wo[2] > 0`; below the horizon the albedo is 0.
pub fn directional_albedo(eval: &dyn Evaluator, wo: Vec3, grid: &AlbedoGrid) -> Xyz {
    if wo[2] <= 0.0 {
        return Xyz::default();
    }
    let mut acc = [0.0; 3];
    for (&v, &wv) in grid.nodes.iter().zip(&grid.weights) {
        let y = -v - wo[1];
        if y.abs() >= 1.0 {
            continue;
        }
        for (&u, &wu) in grid.nodes.iter().zip(&grid.weights) {
            let x = -u - wo[0];
            let r2 = x * x + y * y;
            if r2 >= 1.0 {
                continue;
            }
            let cos_i = (1.0 - r2).sqrt();
            let c = eval.xyz([x, y, cos_i], wo);
            // 1/cos θ_i is integrable at the rim but not by the trapezoid rule; with shadowing (the default)
            // ρ falls as cos θ_i there and the quotient stays finite, without it the floor bounds a node's share.
            let w = wu * wv / cos_i.max(RIM_COS);
            acc[0] += w * c.x;
            acc[1] += w * c.y;
            acc[2] += w * c.z;
        }
    }
    Xyz::new(acc[0], acc[1], acc[2])
}
