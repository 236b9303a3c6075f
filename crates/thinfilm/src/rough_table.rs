//! Colour tables of the LSRS model (Sussenbach section 3.2, Algorithm 2) for rendering: the composite
//! specular reflectance `k_r` and the diffuse radiance factor `π k_d` of a rough film integrated over the
//! spectrum in advance, as XYZ, so that a hit costs interpolation instead of the HTSG series at every
//! wavelength (the GPU's rough films, issue 17).
//!
//! Algorithm 2 tabulates `k_r(θ_v, λ)` and `k_d(θ_v, θ_l, λ)` at one relative azimuth; a renderer needs any
//! azimuth and, with spatially varying thickness, any offset, and only the colour. So the tables here are
//! `k_r` XYZ over (thickness offset, `θ_v`) and `π k_d` XYZ over (offset, azimuth `φ_l − φ_v` ∈ [0, π],
//! `θ_l`, `θ_v`), angles uniform in degrees from 0° to 90° as Algorithm 2's grid, multilinear in between.
//!
//! The diffuse term factors per polarisation and wavelength into a part that depends on the layers (the
//! transport `T(θ)` of each side, `RoughStack::side_factor`, which changes with the offset) and one that
//! does not (the HTSG directional-diffuse geometry of the rough interface and its Fresnel power at the local
//! angle): `k_d = (n₀/n_N)² Σ_pol G_pol(ω_l, ω_v) T_pol(θ_l) T_pol(θ_v) / 2` (module [`crate::rough`]). Each
//! part is computed once per node and wavelength and the products are summed over the spectrum, so a node
//! holds exactly [`RoughStack::evaluate`]'s value integrated with the weights (tested to 1e-12). Both angle
//! axes are the same grid and every node is symmetric in `(θ_l, θ_v)` where the model is reciprocal, so the
//! table keeps Helmholtz reciprocity exactly between nodes as well.

use std::f64::consts::PI;

use iridis_color::{SpectralWeights, Xyz};
use num_complex::Complex64;
use rayon::prelude::*;

use crate::error::ThinFilmError;
use crate::htsg::local_fresnel;
use crate::rough::RoughStack;
use crate::rough_stack::Side;

/// Angle nodes (0°–90°) and azimuth nodes (0–π) of the default table: 3° and 10° steps.
pub const ANGLE_NODES: usize = 31;
pub const AZIMUTH_NODES: usize = 19;

/// The tables of one rough film (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct RoughColorTable {
    /// Nodes of `θ_v` and `θ_l`, uniform over 0°–90°.
    pub angles: usize,
    /// Nodes of the relative azimuth, uniform over 0–π.
    pub azimuths: usize,
    /// Nodes of the thickness offset over `offset_nm` (one for a film without SVT).
    pub offsets: usize,
    pub offset_nm: (f64, f64),
    /// `k_r` XYZ at `[offset][θ_v]`.
    pub specular: Vec<Xyz>,
    /// `π k_d` XYZ at `[offset][azimuth][θ_l][θ_v]`.
    pub diffuse: Vec<Xyz>,
}

/// The cell of `x` on `n` uniform nodes from 0 to `span`: `(i, t)`, clamped.
fn cell(x: f64, span: f64, n: usize) -> (usize, f64) {
    if n < 2 || span <= 0.0 {
        return (0, 0.0);
    }
    let u = (x / span).clamp(0.0, 1.0) * (n - 1) as f64;
    let i = (u.floor() as usize).min(n - 2);
    (i, u - i as f64)
}

impl RoughColorTable {
    /// Builds the tables of `rough` for thickness offsets over `offset_nm` on `offsets` nodes (one node: the
    /// first offset), with `angles` × `azimuths` direction nodes and the colour weights `weights`.
    pub fn build(
        rough: &RoughStack,
        weights: &SpectralWeights,
        angles: usize,
        azimuths: usize,
        offsets: usize,
        offset_nm: (f64, f64),
    ) -> Result<Self, ThinFilmError> {
        if angles < 2 || azimuths < 2 || offsets < 1 {
            return Err(ThinFilmError::Invalid(format!(
                "a rough colour table needs ≥ 2 angle and azimuth nodes and ≥ 1 offset node ({angles}, {azimuths}, \
                 {offsets})"
            )));
        }
        let (lo, hi) = offset_nm;
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(ThinFilmError::Invalid(format!("table offsets {lo}…{hi} nm must be finite and ordered")));
        }
        let offset_at = |j: usize| if offsets == 1 { lo } else { lo + (hi - lo) * j as f64 / (offsets - 1) as f64 };
        let theta = |i: usize| 0.5 * PI * i as f64 / (angles - 1) as f64;
        let azimuth = |a: usize| PI * a as f64 / (azimuths - 1) as f64;
        let stacks: Vec<RoughStack> = (0..offsets)
            .map(|j| {
                let mut r = rough.clone();
                for l in &mut r.stack.layers {
                    l.thickness_nm = (l.thickness_nm + offset_at(j)).max(0.0);
                }
                r
            })
            .collect();
        let (na, nt, no) = (azimuths, angles, offsets);
        let planes = na * nt * nt;
        // Per wavelength: k_r[o][θ], the diffuse transports per side and polarisation [o][θ][pol], and what the
        // interface's part needs (the directions in medium N, their shadowing and K factors, the indices on
        // either side of the rough interface, the radiance factor).
        struct Spectral {
            specular: Vec<f64>,
            view: Vec<[f64; 2]>,
            light: Vec<[f64; 2]>,
            /// With multiple scattering: `(n₀/n_N)² K_pol` at `[o][θ_l][θ_v]` (eq. M5), else empty.
            multiple: Vec<[f64; 2]>,
            k: f64,
            n_upper: Complex64,
            n_sub: Complex64,
            rad: f64,
            /// `(sin θ, cos θ)` in medium N at each angle node (`None`: no light there).
            dirs: Vec<Option<(f64, f64)>>,
            /// The shadowing `S(θ)` and the `K(θ)` of σ₀ at each angle node.
            shadow_k: Vec<(f64, f64)>,
        }
        let multiple = rough.transport == crate::rough::DiffuseTransport::Multiple;
        let r = &rough.htsg.roughness;
        let per_lambda: Vec<Spectral> = weights
            .wavelengths_nm()
            .par_iter()
            .map(|&lambda| -> Result<Spectral, ThinFilmError> {
                let (n_upper, k) = rough.upper(lambda)?;
                // The lobe does not depend on the thicknesses: one for every offset.
                let lobe = if multiple { Some(rough.lobe(lambda, n_upper, k)?) } else { None };
                let mut specular = vec![0.0; no * nt];
                let mut view = vec![[0.0; 2]; no * nt];
                let mut light = vec![[0.0; 2]; no * nt];
                let mut extra = if multiple { vec![[0.0; 2]; no * nt * nt] } else { Vec::new() };
                let mut dirs = vec![None; nt];
                let mut rad = 0.0;
                let mut n_sub = n_upper;
                for (j, r) in stacks.iter().enumerate() {
                    let at = match &lobe {
                        Some(l) => r.at_with(lambda, l)?,
                        None => r.at(lambda)?,
                    };
                    let mut here = vec![None; nt];
                    for i in 0..nt {
                        let side = Side::new(&r.stack, lambda, theta(i))?;
                        let seed = side.seed(&r.htsg, k);
                        let gs = side.specular(&seed);
                        specular[j * nt + i] = 0.5 * (gs.gamma_s.norm_sqr() + gs.gamma_p.norm_sqr());
                        view[j * nt + i] = at.side_factor(&side, &seed, true);
                        light[j * nt + i] = at.side_factor(&side, &seed, false);
                        here[i] = side.dir;
                        if j == 0 {
                            dirs[i] = side.dir;
                            rad = r.radiance(&side);
                            n_sub = side.media[side.n() + 1].n;
                        }
                    }
                    if multiple {
                        for il in 0..nt {
                            for iv in 0..nt {
                                if let (Some(dl), Some(dv)) = (here[il], here[iv]) {
                                    let x = at.multiple_term(dl, dv);
                                    extra[(j * nt + il) * nt + iv] = [rad * x[0], rad * x[1]];
                                }
                            }
                        }
                    }
                }
                // S(θ) and K(θ) once per angle node (σ₀(θ_l, θ_v) and S(θ_l) S(θ_v) once per pair of angles
                // below, as `diffuse_geometry` computes them).
                let shadow_k = dirs.iter().map(|d| d.map_or((0.0, 0.0), |(_, c)| r.shadowing_and_k(c))).collect();
                Ok(Spectral { specular, view, light, multiple: extra, k, n_upper, n_sub, rad, dirs, shadow_k })
            })
            .collect::<Result<_, _>>()?;
        let nl = per_lambda.len();
        // The interface's part G_pol at `[pair θ_l ≤ θ_v][λ][azimuth]` (the spectral sums below read it in that
        // order), for θ_l ≤ θ_v only: it is reciprocal (HTSG's D, shadowing and geometric factor, and the Fresnel
        // power at the local angle, are symmetric in the two directions, and the roughness is isotropic, so
        // swapping them at relative azimuth φ is the same pair mirrored), so (θ_v, θ_l) reads (θ_l, θ_v): half
        // the HTSG series of the table.
        let azimuth_trig: Vec<(f64, f64)> = (0..azimuths).map(|a| (azimuth(a).cos(), azimuth(a).sin())).collect();
        let pairs: Vec<(usize, usize)> = (0..nt).flat_map(|il| (il..nt).map(move |iv| (il, iv))).collect();
        // Where (θ_l, θ_v) of either order finds its pair's chunk.
        let mut chunk_of = vec![0; nt * nt];
        for (c, &(il, iv)) in pairs.iter().enumerate() {
            chunk_of[il * nt + iv] = c;
            chunk_of[iv * nt + il] = c;
        }
        let mut geometry = vec![[0.0; 2]; pairs.len() * nl * na];
        geometry.par_chunks_mut(nl * na).zip(&pairs).try_for_each(|(out, &(il, iv))| -> Result<(), ThinFilmError> {
            for (p, out) in per_lambda.iter().zip(out.chunks_mut(na)) {
                let (Some((sl, cl)), Some((sv, cv))) = (p.dirs[il], p.dirs[iv]) else { continue };
                let sigma0 = r.effective_sigma_from_k(p.shadow_k[il].1 + p.shadow_k[iv].1);
                let shadow = p.shadow_k[il].0 * p.shadow_k[iv].0;
                for (g, &(cos_az, sin_az)) in out.iter_mut().zip(&azimuth_trig) {
                    let wl = [sl * cos_az, sl * sin_az, cl];
                    let geo = rough.htsg.diffuse_geometry_with(wl, [sv, 0.0, cv], p.k, sigma0, shadow)?;
                    let f = local_fresnel(p.n_upper, p.n_sub, geo.cos_local);
                    *g = [p.rad * geo.factor * f.r_s.norm_sqr(), p.rad * geo.factor * f.r_p.norm_sqr()];
                }
            }
            Ok(())
        })?;
        let w = weights.weights();
        let mut specular = vec![Xyz::default(); no * nt];
        for (idx, s) in specular.iter_mut().enumerate() {
            let mut acc = [0.0; 3];
            for (p, wl) in per_lambda.iter().zip(w) {
                for c in 0..3 {
                    acc[c] += wl[c] * p.specular[idx];
                }
            }
            *s = Xyz::new(acc[0], acc[1], acc[2]);
        }
        // The spectral sums, one offset at a time: its layers' factors gathered with λ innermost, every sum in
        // wavelength order (each node the same sum as the direct model's colour integral).
        let mut diffuse = vec![Xyz::default(); no * planes];
        diffuse.par_chunks_mut(planes).enumerate().for_each(|(j, out)| {
            // This offset's `n` entries of a per-wavelength field, as `[entry][λ]`.
            let gather = |field: fn(&Spectral) -> &[[f64; 2]], n: usize| -> Vec<[f64; 2]> {
                (0..n * nl).map(|x| field(&per_lambda[x % nl])[j * n + x / nl]).collect()
            };
            let light = gather(|p| &p.light, nt);
            let view = gather(|p| &p.view, nt);
            let extra = if multiple { gather(|p| &p.multiple, nt * nt) } else { Vec::new() };
            let mut acc = vec![[0.0; 3]; na];
            for il in 0..nt {
                for iv in 0..nt {
                    let c = chunk_of[il * nt + iv];
                    let g_pair = &geometry[c * nl * na..(c + 1) * nl * na];
                    acc.iter_mut().for_each(|a| *a = [0.0; 3]);
                    for li in 0..nl {
                        let (l, v) = (light[il * nl + li], view[iv * nl + li]);
                        let x = if multiple { Some(extra[(il * nt + iv) * nl + li]) } else { None };
                        let wl = w[li];
                        for (a, &g) in acc.iter_mut().zip(&g_pair[li * na..(li + 1) * na]) {
                            let g = match x {
                                Some(x) => [g[0] + x[0], g[1] + x[1]],
                                None => g,
                            };
                            // π k_d = π · ½ Σ_pol (G_pol + K_pol) T_pol(θ_l) T_pol(θ_v)
                            let kd = 0.5 * PI * (g[0] * l[0] * v[0] + g[1] * l[1] * v[1]);
                            for c in 0..3 {
                                a[c] += wl[c] * kd;
                            }
                        }
                    }
                    for (ia, a) in acc.iter().enumerate() {
                        out[(ia * nt + il) * nt + iv] = Xyz::new(a[0], a[1], a[2]);
                    }
                }
            }
        });
        Ok(Self { angles, azimuths, offsets, offset_nm: (lo, if offsets == 1 { lo } else { hi }), specular, diffuse })
    }

    fn offset_cell(&self, offset_nm: f64) -> (usize, f64) {
        let (lo, hi) = self.offset_nm;
        cell(offset_nm - lo, hi - lo, self.offsets)
    }

    /// `k_r` XYZ at the view angle's cosine and an offset, linear in `θ_v` and the offset.
    pub fn specular_at(&self, cos_view: f64, offset_nm: f64) -> Xyz {
        let (i, ti) = cell(cos_view.clamp(0.0, 1.0).acos(), 0.5 * PI, self.angles);
        let (j, tj) = self.offset_cell(offset_nm);
        let j1 = (j + 1).min(self.offsets - 1);
        let at = |j: usize, i: usize| self.specular[j * self.angles + i].to_array();
        let lerp = |a: [f64; 3], b: [f64; 3], t: f64| [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t);
        let v = lerp(lerp(at(j, i), at(j, i + 1), ti), lerp(at(j1, i), at(j1, i + 1), ti), tj);
        Xyz::new(v[0], v[1], v[2])
    }

    /// `π k_d` XYZ at the view and light cosines, their relative azimuth (rad, folded into [0, π]) and an
    /// offset, multilinear in `θ_v`, `θ_l`, the azimuth and the offset; zero for light below the surface.
    pub fn diffuse_at(&self, cos_view: f64, cos_light: f64, azimuth_rad: f64, offset_nm: f64) -> Xyz {
        if cos_light <= 0.0 {
            return Xyz::default();
        }
        let nt = self.angles;
        let (iv, tv) = cell(cos_view.clamp(0.0, 1.0).acos(), 0.5 * PI, nt);
        let (il, tl) = cell(cos_light.min(1.0).acos(), 0.5 * PI, nt);
        let az = azimuth_rad.rem_euclid(2.0 * PI);
        let (ia, ta) = cell(if az > PI { 2.0 * PI - az } else { az }, PI, self.azimuths);
        let (j, tj) = self.offset_cell(offset_nm);
        let j1 = (j + 1).min(self.offsets - 1);
        let mut acc = [0.0; 3];
        for (jj, wj) in [(j, 1.0 - tj), (j1, tj)] {
            for (a, wa) in [(ia, 1.0 - ta), (ia + 1, ta)] {
                for (l, wl) in [(il, 1.0 - tl), (il + 1, tl)] {
                    for (v, wv) in [(iv, 1.0 - tv), (iv + 1, tv)] {
                        let w = wj * wa * wl * wv;
                        if w == 0.0 {
                            continue;
                        }
                        let x = self.diffuse[((jj * self.azimuths + a) * nt + l) * nt + v].to_array();
                        for c in 0..3 {
                            acc[c] += w * x[c];
                        }
                    }
                }
            }
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::htsg::{Htsg, Roughness, Series};
    use crate::stack::Stack;

    fn rough(stack: &str, sigma: f64, tau: f64) -> RoughStack {
        RoughStack::new(Stack::parse(stack).unwrap(), Htsg::new(Roughness::new(sigma, tau).unwrap(), Series::default()))
    }

    fn weights() -> SpectralWeights {
        let grid = iridis_color::spectrum::uniform_grid(380.0, 780.0, 10.0).unwrap();
        SpectralWeights::new(&grid, iridis_color::Illuminant::D65, iridis_color::Observer::Cie1931)
    }

    /// `k_r` and `π k_d` XYZ of the direct model at one configuration.
    fn direct(r: &RoughStack, w: &SpectralWeights, view: f64, light: f64, az: f64, offset: f64) -> (Xyz, Xyz) {
        let mut r = r.clone();
        for l in &mut r.stack.layers {
            l.thickness_nm = (l.thickness_nm + offset).max(0.0);
        }
        let (kr, kd): (Vec<f64>, Vec<f64>) = w
            .wavelengths_nm()
            .iter()
            .map(|&l| {
                let x = r.evaluate(l, view, light, az).unwrap();
                (x.k_r(), PI * x.k_d())
            })
            .unzip();
        (w.integrate(&kr), w.integrate(&kd))
    }

    #[test]
    fn nodes_are_the_direct_model() {
        let w = weights();
        for s in ["air | water 348nm | Si", "air | n=1.38 100nm | n=2.1+0.3i 50nm | Si"] {
            let r = rough(s, 25.0, 300.0);
            let t = RoughColorTable::build(&r, &w, 7, 5, 3, (-40.0, 40.0)).unwrap();
            for (iv, il, a, j) in [(0, 0, 0, 0), (2, 5, 4, 1), (6, 3, 1, 2), (3, 3, 2, 0)] {
                let (v, l) = ((15.0 * iv as f64).to_radians(), (15.0 * il as f64).to_radians());
                let (az, o) = (PI * a as f64 / 4.0, -40.0 + 40.0 * j as f64);
                let (kr, kd) = direct(&r, &w, v, l, az, o);
                let (tr, td) = (t.specular_at(v.cos(), o), t.diffuse_at(v.cos(), l.cos(), az, o));
                for (p, q) in [(tr, kr), (td, kd)] {
                    for (x, y) in p.to_array().into_iter().zip(q.to_array()) {
                        assert!((x - y).abs() <= 1e-12 * y.abs().max(1e-3), "{s} {iv} {il} {a} {j}: {x} vs {y}");
                    }
                }
            }
        }
    }

    #[test]
    fn light_below_the_surface_gives_no_diffuse_and_azimuth_folds() {
        let w = weights();
        let t = RoughColorTable::build(&rough("air | water 348nm | Si", 25.0, 300.0), &w, 7, 5, 1, (0.0, 0.0)).unwrap();
        assert_eq!(t.diffuse_at(0.8, -0.1, 1.0, 0.0), Xyz::default());
        assert_eq!(t.diffuse_at(0.8, 0.5, 1.0, 0.0), t.diffuse_at(0.8, 0.5, 2.0 * PI - 1.0, 0.0));
        assert_eq!(t.diffuse_at(0.8, 0.5, 1.0, 0.0), t.diffuse_at(0.8, 0.5, -1.0, 0.0));
        assert!(RoughColorTable::build(&rough("air | water 348nm | Si", 25.0, 300.0), &w, 1, 5, 1, (0.0, 0.0)).is_err());
    }
}
