//! Energy bookkeeping for the GGX microfacet model: the directional albedo of its single-scattering specular
//! lobe, tabulated over roughness × `cos θ`, so that
//!
//! * a multiple-scattering lobe restores what single scattering loses (Kulla & Conty, "Revisiting Physically
//!   Based Shading at Imageworks", SIGGRAPH 2017 course: `f_ms = (1 − E(μ_i))(1 − E(μ_o)) / (π (1 − E_avg))`,
//!   tinted by `F_avg² E_avg / (1 − F_avg (1 − E_avg))`), and
//! * the diffuse lobe under a dielectric coat takes exactly what the specular leaves (Kelemen & Szirmay-Kalos
//!   2001; Kulla & Conty's "energy-conserving diffuse"): `f_d = ρ (1 − E_s(μ_i))(1 − E_s(μ_o)) / (π (1 − E_s,avg))`,
//!   whose cosine-weighted integral over `ω_i` is `ρ (1 − E_s(μ_o))`.
//!
//! With Schlick's `F = F_0 + (1 − F_0)(1 − v·h)^5` the single-scattering albedo is linear in `F_0`:
//! `E_ss(μ; F_0) = F_0 (E_0(μ) − E_1(μ)) + E_1(μ)`, where `E_0` is the albedo with `F = 1` and `E_1` the one with
//! `F = (1 − v·h)^5`; one table of `E_0` and `E_1` serves every index and colour. The GPU samples the same
//! table (uploaded by `iridis-gpu`), so both renderers conserve energy alike.

use std::sync::OnceLock;

/// Roughness nodes (uniform in `[0, 1]`).
pub const N_ROUGH: usize = 32;
/// `cos θ` nodes (uniform in `[0, 1]`).
pub const N_MU: usize = 64;

/// `E_0`, `E_1` (row-major: roughness × μ) and their cosine-weighted averages `2∫ E μ dμ` per roughness.
#[derive(Debug, Clone)]
pub struct EnergyTable {
    pub e0: Vec<f64>,
    pub e1: Vec<f64>,
    pub avg0: Vec<f64>,
    pub avg1: Vec<f64>,
}

/// The GGX `α²` of a roughness (`α = roughness²`, floored as in [`crate::material::Microfacet::reflect`]).
pub fn alpha2(roughness: f64) -> f64 {
    let a = (roughness * roughness).max(1e-4);
    a * a
}

/// GGX normal distribution `D(h)` for `n·h`.
pub fn ggx_d(a2: f64, nh: f64) -> f64 {
    let q = nh * nh * (a2 - 1.0) + 1.0;
    a2 / (std::f64::consts::PI * q * q)
}

/// Smith's separable masking for one direction (`G_1` of GGX).
pub fn smith_g1(a2: f64, c: f64) -> f64 {
    2.0 * c / (c + (a2 + (1.0 - a2) * c * c).sqrt())
}

/// `(E_0, E_1)` at one roughness and `μ_o = cos θ_o`: the GGX lobe's directional albedo with `F = 1` and with
/// `F = (1 − v·h)^5`. Quadrature over half vectors drawn by GGX's inverse CDF on a stratified grid
/// (`tan² θ_h = α² u / (1 − u)`), where the estimator is `G (v·h) / (μ_o n·h)` (Walter et al. 2007, eq. 38–41).
pub fn albedo(roughness: f64, mu_o: f64) -> (f64, f64) {
    const NU: usize = 128;
    const NV: usize = 64;
    let a2 = alpha2(roughness);
    let mu = mu_o.clamp(1e-4, 1.0);
    let wo = [(1.0 - mu * mu).sqrt(), 0.0, mu];
    // The lobe is symmetric about the plane of wo and n: half the azimuths, counted twice. Only the cosine of
    // the azimuth enters `v·h` (wo has no y component); it is the same for every half-vector ring, so it is
    // taken once per azimuth instead of once per sample (the cosines were most of the table's time).
    let cos_phi: [f64; NV] = std::array::from_fn(|j| (std::f64::consts::PI * (j as f64 + 0.5) / NV as f64).cos());
    let (mut s0, mut s1) = (0.0, 0.0);
    for i in 0..NU {
        let u = (i as f64 + 0.5) / NU as f64;
        let t2 = a2 * u / (1.0 - u);
        let nh = 1.0 / (1.0 + t2).sqrt();
        let sh = (1.0 - nh * nh).max(0.0).sqrt();
        for &cos_phi in &cos_phi {
            let vh = wo[0] * (sh * cos_phi) + wo[2] * nh;
            if vh <= 0.0 {
                continue;
            }
            let mu_i = 2.0 * vh * nh - mu;
            if mu_i <= 0.0 {
                continue;
            }
            let w = smith_g1(a2, mu_i) * smith_g1(a2, mu) * vh / (mu * nh);
            s0 += w;
            s1 += w * (1.0 - vh).powi(5);
        }
    }
    let n = (NU * NV) as f64;
    (s0 / n, s1 / n)
}

/// The table, computed once a process (about 0.1 CPU-s in a release build).
pub fn table() -> &'static EnergyTable {
    static T: OnceLock<EnergyTable> = OnceLock::new();
    T.get_or_init(|| {
        use rayon::prelude::*;
        let rows: Vec<(Vec<f64>, Vec<f64>)> = (0..N_ROUGH)
            .into_par_iter()
            .map(|r| {
                let rough = r as f64 / (N_ROUGH - 1) as f64;
                (0..N_MU).map(|m| albedo(rough, m as f64 / (N_MU - 1) as f64)).unzip()
            })
            .collect();
        let mut t = EnergyTable { e0: Vec::new(), e1: Vec::new(), avg0: Vec::new(), avg1: Vec::new() };
        for (e0, e1) in rows {
            // 2 ∫ E μ dμ by the trapezoid rule on the μ nodes.
            let avg = |e: &[f64]| {
                let h = 1.0 / (N_MU - 1) as f64;
                (0..N_MU)
                    .map(|m| {
                        let w = if m == 0 || m == N_MU - 1 { 0.5 } else { 1.0 };
                        w * h * 2.0 * e[m] * m as f64 * h
                    })
                    .sum::<f64>()
            };
            t.avg0.push(avg(&e0));
            t.avg1.push(avg(&e1));
            t.e0.extend(e0);
            t.e1.extend(e1);
        }
        t
    })
}

/// Bilinear lookup at `(roughness, μ)` of `E_0` and `E_1`, and the linear one of their averages.
pub fn lookup(roughness: f64, mu: f64) -> ([f64; 2], [f64; 2]) {
    let t = table();
    let x = roughness.clamp(0.0, 1.0) * (N_ROUGH - 1) as f64;
    let y = mu.clamp(0.0, 1.0) * (N_MU - 1) as f64;
    let (i, j) = ((x as usize).min(N_ROUGH - 2), (y as usize).min(N_MU - 2));
    let (fx, fy) = (x - i as f64, y - j as f64);
    let at = |v: &[f64]| {
        let g = |r: usize, m: usize| v[r * N_MU + m];
        let a = g(i, j) + (g(i, j + 1) - g(i, j)) * fy;
        let b = g(i + 1, j) + (g(i + 1, j + 1) - g(i + 1, j)) * fy;
        a + (b - a) * fx
    };
    let avg = |v: &[f64]| v[i] + (v[i + 1] - v[i]) * fx;
    ([at(&t.e0), at(&t.e1)], [avg(&t.avg0), avg(&t.avg1)])
}

/// The specular part of a GGX surface with Schlick reflectance `F_0` (one channel), as energy: the directional
/// albedo `E_s(μ)` (single + multiple scattering), its average `E_s,avg`, the multiple-scattering tint `F_ms`,
/// and `E_0(μ)`, `E_0,avg` for the multiple-scattering lobe.
#[derive(Debug, Clone, Copy)]
pub struct SpecEnergy {
    pub e_s: f64,
    pub e_s_avg: f64,
    pub f_ms: f64,
    pub e0: f64,
    pub e0_avg: f64,
}

/// The energy of a lobe with Schlick reflectance `F_0` at a roughness and `μ`.
pub fn spec_energy(roughness: f64, mu: f64, f0: f64) -> SpecEnergy {
    let ([e0, e1], [a0, a1]) = lookup(roughness, mu);
    // Schlick's average over the hemisphere, 2∫F μ dμ = F_0 + (1 − F_0)/21 (Kulla & Conty).
    let f_avg = f0 + (1.0 - f0) / 21.0;
    let f_ms = f_avg * f_avg * a0 / (1.0 - f_avg * (1.0 - a0)).max(1e-12);
    let e_ss = f0 * (e0 - e1) + e1;
    let e_ss_avg = f0 * (a0 - a1) + a1;
    SpecEnergy {
        e_s: (e_ss + f_ms * (1.0 - e0)).min(1.0),
        e_s_avg: (e_ss_avg + f_ms * (1.0 - a0)).min(1.0),
        f_ms,
        e0,
        e0_avg: a0,
    }
}
