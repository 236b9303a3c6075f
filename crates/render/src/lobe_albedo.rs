//! The energy a diffraction material's lobe reflects, for the energy-conserving blend of its texture.
//!
//! A diffraction material in radiometric units reflects `A(ω_o) = ∫ f_r cos θ_i dω_i` of a uniform sky into
//! `ω_o` ([`iridis_diffraction::energy::directional_albedo`], `R(θ_o)` for a flat surface, less for a rough
//! one). Its texture, a Lambertian lobe under it, may then take only what the lobe leaves: as for the dielectric
//! microfacet (Kulla & Conty 2017), `f_d = ρ_d (1 − A(ω_i))(1 − A(ω_o)) / (π (1 − A_avg))`, reciprocal, and in
//! a uniform environment `∫ f_d cos θ_i dω_i = ρ_d (1 − A(ω_o))`, so lobe plus texture return exactly what a white
//! texture receives (the white furnace, `crates/render/tests/white_furnace.rs`). `A_avg = (1/π) ∫ A cos θ dω`.
//!
//! The diffraction lobe is anisotropic (gratings, nanofingers along a direction), so `A` is tabulated over
//! `cos θ` and azimuth in the material's local frame and interpolated bilinearly (periodic in azimuth).

use iridis_diffraction::energy::{directional_albedo, AlbedoGrid};
use iridis_diffraction::Evaluator;
use rayon::prelude::*;

use crate::error::RenderError;
use crate::light::Rgb;
use crate::math::V3;

/// Midpoint nodes in `cos θ` and uniform azimuths of the albedo table: within the tests' bound of the
/// exact integral for the built-in surfaces (the lobe's albedo varies slowly with direction).
pub const COS_NODES: usize = 10;
pub const AZIMUTHS: usize = 16;
/// The most quadrature points per axis (a 101² table is integrated on its grid refined once, 201 points).
const MAX_QUADRATURE_RES: usize = 201;

/// `A(ω)` as linear sRGB over the hemisphere (per unit radiance of a white sky), and its cosine-weighted mean.
#[derive(Debug, Clone)]
pub struct LobeAlbedo {
    /// `[cos node][azimuth]`.
    values: Vec<Rgb>,
    average: Rgb,
}

impl LobeAlbedo {
    /// Integrates the evaluator's lobe, times `scale` (the factor that makes its colour the reflected fraction:
    /// `R₀` for a radiometric table), at every node.
    pub fn compute(eval: &dyn Evaluator, scale: f64) -> Result<Self, RenderError> {
        let grid =
            AlbedoGrid::for_evaluator(eval, MAX_QUADRATURE_RES).map_err(|e| RenderError::Input(e.to_string()))?;
        let values: Vec<Rgb> = (0..COS_NODES * AZIMUTHS)
            .into_par_iter()
            .map(|k| {
                let (c, a) = (cos_node(k / AZIMUTHS), azimuth(k % AZIMUTHS));
                let s = (1.0 - c * c).sqrt();
                let xyz = directional_albedo(eval, [s * a.cos(), s * a.sin(), c], &grid);
                xyz.to_linear_srgb().map(|v| v * scale)
            })
            .collect();
        // (1/π) ∫ A cos θ dω = ∫₀¹ 2μ ⟨A⟩_φ dμ by the midpoint rule on the cos nodes.
        let mut average = [0.0; 3];
        for (k, v) in values.iter().enumerate() {
            let w = 2.0 * cos_node(k / AZIMUTHS) / (COS_NODES * AZIMUTHS) as f64;
            for c in 0..3 {
                average[c] += w * v[c];
            }
        }
        Ok(Self { values, average })
    }

    /// `A` for a direction in the local frame (`z` the normal), bilinear between the nodes.
    pub fn at(&self, local: V3) -> Rgb {
        let c = local[2].clamp(0.0, 1.0);
        let fc = (c * COS_NODES as f64 - 0.5).clamp(0.0, (COS_NODES - 1) as f64);
        let (c0, tc) = (fc.floor() as usize, fc.fract());
        let c1 = (c0 + 1).min(COS_NODES - 1);
        let a = local[1].atan2(local[0]).rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU * AZIMUTHS as f64;
        let (a0, ta) = (a.floor() as usize % AZIMUTHS, a.fract());
        let a1 = (a0 + 1) % AZIMUTHS;
        let v = |ci: usize, ai: usize| self.values[ci * AZIMUTHS + ai];
        let mut out = [0.0; 3];
        for k in 0..3 {
            let lo = v(c0, a0)[k] * (1.0 - ta) + v(c0, a1)[k] * ta;
            let hi = v(c1, a0)[k] * (1.0 - ta) + v(c1, a1)[k] * ta;
            out[k] = lo * (1.0 - tc) + hi * tc;
        }
        out
    }

    /// The table, `[cos node][azimuth]` (node `i` at `cos θ = (i + ½)/COS_NODES`, azimuth `j` at `2π j/AZIMUTHS`
    /// from the material's `t`), as the GPU uploads it.
    pub fn nodes(&self) -> &[Rgb] {
        &self.values
    }

    /// The cosine-weighted mean `A_avg`.
    pub fn average(&self) -> Rgb {
        self.average
    }

    /// The texture's share `(1 − A(ω_i))(1 − A(ω_o)) / (1 − A_avg)` per channel (0 where the lobe reflects all).
    pub fn diffuse_share(&self, wi_local: V3, wo_local: V3) -> Rgb {
        let (ai, ao) = (self.at(wi_local), self.at(wo_local));
        std::array::from_fn(|k| {
            let rest = 1.0 - self.average[k];
            if rest <= 1e-9 {
                0.0
            } else {
                (1.0 - ai[k]).max(0.0) * (1.0 - ao[k]).max(0.0) / rest
            }
        })
    }

    /// The share of a uniform environment's light the texture takes at `ω_o`: `1 − A(ω_o)` (the integral of
    /// [`LobeAlbedo::diffuse_share`] against `cos θ_i / π`).
    pub fn environment_share(&self, wo_local: V3) -> Rgb {
        self.at(wo_local).map(|a| (1.0 - a).max(0.0))
    }
}

fn cos_node(i: usize) -> f64 {
    (i as f64 + 0.5) / COS_NODES as f64
}

fn azimuth(j: usize) -> f64 {
    std::f64::consts::TAU * j as f64 / AZIMUTHS as f64
}
