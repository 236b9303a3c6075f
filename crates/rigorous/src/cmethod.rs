//! The C-method (Chandezon) at one truncation: eigenmodes of each medium in the translation coordinates
//! `u = z − a(x, y)`, the boundary conditions at `u = 0`, and the Rayleigh amplitudes of the propagating orders.
//!
//! Equation numbers (C1)…(C9) refer to docs/rigorous.md, where the derivation is written out; the method is that
//! of Chandezon, Maystre & Raoult (J. Opt. 11, 235, 1980) in the form of Li, Chandezon, Granet & Plumey
//! (Appl. Opt. 38, 304, 1999) for conical incidence, and of Harris et al. (JOSA A 13, 2041, 1996) and
//! Granet (JOSA A 15, 1121, 1998) for crossed gratings (covariant tangential components).

use crate::surface::{Coeffs, FineSurface};
use crate::waves::{cross, kz_up, sp_basis, V3};
use crate::RigorousError;
use faer::prelude::*;
use faer::Mat;
use num_complex::Complex64 as C64;

const ZERO: C64 = C64 { re: 0.0, im: 0.0 };
const ONE: C64 = C64 { re: 1.0, im: 0.0 };

/// The incidence and media of one solve, normalised by `k0`.
#[derive(Debug, Clone)]
pub(crate) struct Setting {
    /// Permittivity of the incident medium (real: a transparent medium).
    pub eps1: f64,
    /// Permittivity of the substrate, `(n + iκ)²`.
    pub eps2: C64,
    /// Tangential wavevector of the incident wave.
    pub kx0: f64,
    pub ky0: f64,
    /// Azimuth of the plane of incidence (rad), for the s/p basis of waves with no tangential wavevector.
    pub phi: f64,
    /// Grating vectors `λ/Λx`, `λ/Λy` (`kgy` unused for a 1-D profile).
    pub kgx: f64,
    pub kgy: f64,
    /// Conformal coatings from the top: permittivity and thickness (times k0) along z; every interface is the
    /// profile shifted down, `u = const` in the C-method's coordinates.
    pub layers: Vec<(C64, f64)>,
}

/// The Fourier orders kept: `|m| ≤ mx`, `|n| ≤ my`.
#[derive(Debug, Clone)]
pub(crate) struct Orders {
    pub list: Vec<(i64, i64)>,
}

impl Orders {
    pub fn new(mx: usize, my: usize) -> Self {
        let (mx, my) = (mx as i64, my as i64);
        let mut list = Vec::new();
        for n in -my..=my {
            for m in -mx..=mx {
                list.push((m, n));
            }
        }
        Orders { list }
    }
    pub fn len(&self) -> usize {
        self.list.len()
    }
}

/// Amplitudes of one outgoing propagating order in the s/p basis of its own plane of incidence, for TE and TM
/// incidence of unit amplitude.
#[derive(Debug, Clone, Copy)]
pub(crate) struct OrderAmplitudes {
    pub m: i64,
    pub n: i64,
    /// Wavevector (normalised by k0); `kz` signed: positive upwards (reflected), negative (transmitted).
    pub k: [f64; 3],
    /// `[TE incidence, TM incidence]` × `[s, p]` amplitudes.
    pub amp: [[C64; 2]; 2],
    /// Power efficiencies `[TE, TM]` × `[s, p]`.
    pub eff: [[f64; 2]; 2],
}

/// Everything one truncation gives.
#[derive(Debug, Clone)]
pub(crate) struct RawSolution {
    pub reflected: Vec<OrderAmplitudes>,
    pub transmitted: Vec<OrderAmplitudes>,
}

/// A mode in one medium: its covariant tangential field components `(E1, E2, H1, H2)` at `u = 0`, each an
/// `Nf`-vector of Fourier coefficients (C6).
type Column = Vec<C64>;

/// Modes of one medium that satisfy its radiation condition: plane waves of the orders whose `kz² ` has a
/// positive real part (two polarisations each, `s` then `p`), then the numerical eigenmodes.
struct MediumModes {
    /// `(order index, kz)` of each analytic order, in column order (each gives an s and a p column).
    analytic: Vec<(usize, C64)>,
    columns: Vec<Column>,
    /// Propagation constant along u of each column (`k_z` of a plane wave, ρ of an eigenmode).
    rho: Vec<C64>,
}

/// Which way a medium's modes must go: upwards (incident medium, above the surface) or downwards (substrate).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Side {
    Above,
    Below,
}

fn tangential(s: &Setting, m: i64, n: i64) -> (f64, f64) {
    (s.kx0 + m as f64 * s.kgx, s.ky0 + n as f64 * s.kgy)
}

/// The covariant tangential components at `u = 0` of the plane wave `E = e exp(i(kx x + ky y + kz z))` of order
/// `q`, as Fourier vectors: `E1 = (e_x + a_x e_z) Φ`, `E2 = (e_y + a_y e_z) Φ`, same for `H = k × e`, with
/// `Φ = exp(i kz a(x, y))` (C7).
fn plane_wave_column(orders: &Orders, q: usize, phi: &[Coeffs; 3], e: &V3, k: &V3) -> Column {
    let h = cross(k, e);
    let nf = orders.len();
    let (mq, nq) = orders.list[q];
    let mut col = vec![ZERO; 4 * nf];
    for (r, &(mr, nr)) in orders.list.iter().enumerate() {
        let (p, s) = (mr - mq, nr - nq);
        let f = phi[0].get(p, s);
        let fx = phi[1].get(p, s);
        let fy = phi[2].get(p, s);
        col[r] = e[0] * f + e[2] * fx;
        col[nf + r] = e[1] * f + e[2] * fy;
        col[2 * nf + r] = h[0] * f + h[2] * fx;
        col[3 * nf + r] = h[1] * f + h[2] * fy;
    }
    col
}

/// Fourier coefficients of `Φ = exp(i kz a)`, `a_x Φ`, `a_y Φ`.
fn phase_coeffs(surf: &FineSurface, kz: C64) -> [Coeffs; 3] {
    let phase = |a: f64| (C64::new(0.0, 1.0) * kz * a).exp();
    [
        surf.coeffs_of(|a, _, _| phase(a)),
        surf.coeffs_of(|a, ax, _| ax * phase(a)),
        surf.coeffs_of(|a, _, ay| ay * phase(a)),
    ]
}

/// Removes from `vals` (indices into the eigenvalues) the eigenvalue nearest each of `targets`, once per target.
fn remove_nearest(eig: &[C64], pool: &mut Vec<usize>, targets: &[C64]) {
    for t in targets {
        if let Some((pos, _)) =
            pool.iter().enumerate().map(|(pos, &i)| (pos, (eig[i] - t).norm())).min_by(|a, b| a.1.total_cmp(&b.1))
        {
            pool.swap_remove(pos);
        }
    }
}

/// Chooses `count` eigenvalues that satisfy the radiation condition of `side`, after removing those that
/// approximate the analytic plane waves (`±kz` of each analytic order, `multiplicity` times each).
fn select_modes(eig: &[C64], analytic_kz: &[C64], multiplicity: usize, side: Side, count: usize) -> Vec<usize> {
    let mut pool: Vec<usize> = (0..eig.len()).collect();
    let mut targets = Vec::new();
    for &kz in analytic_kz {
        for _ in 0..multiplicity {
            targets.push(kz);
            targets.push(-kz);
        }
    }
    remove_nearest(eig, &mut pool, &targets);
    // Above: decaying upwards, Im ρ > 0; below: Im ρ < 0. Sorting by Im and taking `count` is robust against
    // eigenvalues that rounding puts a hair off the real axis.
    let key = |i: &usize| match side {
        Side::Above => -eig[*i].im,
        Side::Below => eig[*i].im,
    };
    pool.sort_by(|a, b| key(a).total_cmp(&key(b)));
    pool.truncate(count);
    pool
}

/// Analytic orders of a medium: those whose `kz²` has a positive real part (propagating in a transparent medium,
/// or weakly damped in a lossy dielectric), with `kz` of the outgoing wave (upwards above, downwards below).
fn analytic_orders(set: &Setting, orders: &Orders, eps: C64, side: Side) -> Vec<(usize, C64)> {
    orders
        .list
        .iter()
        .enumerate()
        .filter_map(|(q, &(m, n))| {
            let (kx, ky) = tangential(set, m, n);
            let kz2 = eps - kx * kx - ky * ky;
            // Orders within 1e-10 of grazing are left to the eigenmodes (their power flux vanishes).
            if kz2.re > 1e-10 * eps.norm() {
                let kz = kz_up(eps, kx, ky);
                Some((q, if side == Side::Above { kz } else { -kz }))
            } else {
                None
            }
        })
        .collect()
}

fn analytic_columns(
    set: &Setting,
    orders: &Orders,
    surf: &FineSurface,
    eps: C64,
    analytic: &[(usize, C64)],
) -> Vec<Column> {
    let mut cols = Vec::with_capacity(2 * analytic.len());
    for &(q, kz) in analytic {
        let (m, n) = orders.list[q];
        let (kx, ky) = tangential(set, m, n);
        let k = [C64::new(kx, 0.0), C64::new(ky, 0.0), kz];
        let (s, p) = sp_basis(&k, eps, set.phi);
        let phi = phase_coeffs(surf, kz);
        cols.push(plane_wave_column(orders, q, &phi, &s, &k));
        cols.push(plane_wave_column(orders, q, &phi, &p, &k));
    }
    cols
}

fn toeplitz(c: &Coeffs, orders: &Orders) -> Mat<C64> {
    let nf = orders.len();
    Mat::from_fn(nf, nf, |r, s| {
        let (mr, nr) = orders.list[r];
        let (ms, ns) = orders.list[s];
        c.get(mr - ms, nr - ns)
    })
}

fn eigen(a: &Mat<C64>) -> Result<(Vec<C64>, Mat<C64>), RigorousError> {
    let evd = a.eigen().map_err(|e| RigorousError::Numerical(format!("eigendecomposition failed: {e:?}")))?;
    let s = evd.S();
    let vals: Vec<C64> = (0..a.nrows()).map(|i| s[i]).collect();
    Ok((vals, evd.U().to_owned()))
}

/// The eigen-solutions of a medium's problem, from which [`modes`] picks each side's eigenmodes.
struct Eigenmodes {
    /// The eigenvalues ρ.
    rho: Vec<C64>,
    /// How many eigenvalues each plane-wave order has near its `±k_z` ([`select_modes`]): 1 in the scalar 1-D
    /// problem, 2 (the two polarisations) in the 2-D one.
    multiplicity: usize,
    /// The columns of eigenmode `i`: two for the 1-D problem (`E_y`-type and `H_y`-type), one for the 2-D one.
    columns: Box<dyn Fn(usize) -> Vec<Column>>,
}

/// The eigenmodes of a medium for a 1-D profile `a(x)` (no y dependence of the surface); conical incidence:
/// `E_y` and `H_y` each satisfy the scalar problem (C3)
/// `ρ [F; G] = [[0, I], [C⁻¹(κ² − α²), C⁻¹(αȦ + Ȧα)]] [F; G]`, `C = [[1 + ȧ²]]`, `κ² = ε − k_y²`,
/// and every eigenmode gives two columns, `E_y`-type and `H_y`-type, with the tangential components of (C5).
fn eigenmodes_1d(set: &Setting, orders: &Orders, surf: &FineSurface, eps: C64) -> Result<Eigenmodes, RigorousError> {
    let nf = orders.len();
    let adot = toeplitz(&surf.coeffs_of(|_, ax, _| C64::new(ax, 0.0)), orders);
    let cmat = toeplitz(&surf.coeffs_of(|_, ax, _| C64::new(1.0 + ax * ax, 0.0)), orders);
    let alpha: Vec<f64> = orders.list.iter().map(|&(m, n)| tangential(set, m, n).0).collect();
    let ky = set.ky0;
    let kappa2 = eps - ky * ky;
    // Right-hand side blocks: diag(κ² − α²) and αȦ + Ȧα.
    let mut rhs = Mat::<C64>::zeros(nf, 2 * nf);
    for r in 0..nf {
        rhs[(r, r)] = kappa2 - alpha[r] * alpha[r];
        for c in 0..nf {
            rhs[(r, nf + c)] = adot[(r, c)] * (alpha[r] + alpha[c]);
        }
    }
    let lu = cmat.partial_piv_lu();
    let sol = lu.solve(&rhs);
    let mut a = Mat::<C64>::zeros(2 * nf, 2 * nf);
    for r in 0..nf {
        a[(r, nf + r)] = ONE;
        for c in 0..2 * nf {
            a[(nf + r, c)] = sol[(r, c)];
        }
    }
    let (rho, vecs) = eigen(&a)?;
    let columns = move |i: usize| {
        // N = C G − Ȧ α F: the Fourier vector of the normal derivative operator (C4).
        let f: Vec<C64> = (0..nf).map(|r| vecs[(r, i)]).collect();
        let g: Vec<C64> = (0..nf).map(|r| vecs[(nf + r, i)]).collect();
        // Column by column (the matrices are column-major): every row's sum runs over c in order, as a row-by-row
        // loop would, but the rows' sums are independent, so they no longer wait on one another.
        let mut nvec = vec![ZERO; nf];
        for c in 0..nf {
            let (gc, hc) = (g[c], alpha[c] * f[c]);
            for ((n, &cc), &ac) in nvec.iter_mut().zip(cmat.col_as_slice(c)).zip(adot.col_as_slice(c)) {
                *n += cc * gc - ac * hc;
            }
        }
        let mut e_col = vec![ZERO; 4 * nf];
        let mut h_col = vec![ZERO; 4 * nf];
        for r in 0..nf {
            // E_y-type mode (E_y = F, H_y = 0) and H_y-type mode (E_y = 0, H_y = F), (C5).
            e_col[r] = -ky * alpha[r] * f[r] / kappa2;
            e_col[nf + r] = f[r];
            e_col[2 * nf + r] = -eps * nvec[r] / kappa2;
            h_col[r] = nvec[r] / kappa2;
            h_col[2 * nf + r] = -ky * alpha[r] * f[r] / kappa2;
            h_col[3 * nf + r] = f[r];
        }
        vec![e_col, h_col]
    };
    Ok(Eigenmodes { rho, multiplicity: 1, columns: Box::new(columns) })
}

/// Modes of a medium for each of `sides`: the analytic plane-wave columns (C7), then the eigenmodes of the 1-D
/// (C3) or 2-D (C8) problem for the orders that are not plane waves (two columns per missing order).
fn modes(
    set: &Setting,
    orders: &Orders,
    surf: &FineSurface,
    two_d: bool,
    eps: C64,
    sides: &[Side],
) -> Result<Vec<MediumModes>, RigorousError> {
    let mut out: Vec<MediumModes> = sides.iter().map(|&side| start_modes(set, orders, surf, eps, side)).collect();
    let missing = orders.len() - out[0].analytic.len();
    if missing > 0 {
        // Each missing order gives two columns: one eigenmode of the 1-D problem, two of the 2-D one.
        let (eig, need) = if two_d {
            (eigenmodes_2d(set, orders, surf, eps)?, 2 * missing)
        } else {
            (eigenmodes_1d(set, orders, surf, eps)?, missing)
        };
        for (mm, &side) in out.iter_mut().zip(sides) {
            let akz: Vec<C64> = mm.analytic.iter().map(|a| a.1).collect();
            for i in select_modes(&eig.rho, &akz, eig.multiplicity, side, need) {
                for column in (eig.columns)(i) {
                    mm.columns.push(column);
                    mm.rho.push(eig.rho[i]);
                }
            }
        }
    }
    Ok(out)
}

/// The analytic plane-wave columns of a medium for one side (C7); the eigenmodes are appended later.
fn start_modes(set: &Setting, orders: &Orders, surf: &FineSurface, eps: C64, side: Side) -> MediumModes {
    let analytic = analytic_orders(set, orders, eps, side);
    let columns = analytic_columns(set, orders, surf, eps, &analytic);
    let rho = analytic.iter().flat_map(|a| [a.1, a.1]).collect();
    MediumModes { analytic, columns, rho }
}

/// The eigenmodes of a medium for a 2-D profile `a(x, y)`: the covariant Maxwell equations in the translation
/// coordinates (C8) as `ρ Ψ = P Ψ` for `Ψ = (E1, E2, H1, H2)`, one column per eigenmode.
fn eigenmodes_2d(set: &Setting, orders: &Orders, surf: &FineSurface, eps: C64) -> Result<Eigenmodes, RigorousError> {
    let nf = orders.len();
    let g = |ax: f64, ay: f64| 1.0 / (1.0 + ax * ax + ay * ay);
    let t_g = toeplitz(&surf.coeffs_of(|_, ax, ay| C64::new(g(ax, ay), 0.0)), orders);
    let t_xg = toeplitz(&surf.coeffs_of(|_, ax, ay| C64::new(ax * g(ax, ay), 0.0)), orders);
    let t_yg = toeplitz(&surf.coeffs_of(|_, ax, ay| C64::new(ay * g(ax, ay), 0.0)), orders);
    let t_xxg = toeplitz(&surf.coeffs_of(|_, ax, ay| C64::new(ax * ax * g(ax, ay), 0.0)), orders);
    let t_xyg = toeplitz(&surf.coeffs_of(|_, ax, ay| C64::new(ax * ay * g(ax, ay), 0.0)), orders);
    let t_yyg = toeplitz(&surf.coeffs_of(|_, ax, ay| C64::new(ay * ay * g(ax, ay), 0.0)), orders);
    let kt: Vec<(f64, f64)> = orders.list.iter().map(|&(m, n)| tangential(set, m, n)).collect();
    let inv_eps = ONE / eps;
    let mut p = Mat::<C64>::zeros(4 * nf, 4 * nf);
    for r in 0..nf {
        let (ar, br) = kt[r];
        for c in 0..nf {
            let (ac, bc) = kt[c];
            let (tg, txg, tyg) = (t_g[(r, c)], t_xg[(r, c)], t_yg[(r, c)]);
            let (txx, txy, tyy) = (t_xxg[(r, c)], t_xyg[(r, c)], t_yyg[(r, c)]);
            // Rows of E3, H3 and of a_x E3, a_y E3, a_x H3, a_y H3 over the blocks (E1, E2, H1, H2).
            let e3 = [txg, tyg, inv_eps * tg * bc, -inv_eps * tg * ac];
            let h3 = [-tg * bc, tg * ac, txg, tyg];
            let xe3 = [txx, txy, inv_eps * txg * bc, -inv_eps * txg * ac];
            let ye3 = [txy, tyy, inv_eps * tyg * bc, -inv_eps * tyg * ac];
            let xh3 = [-txg * bc, txg * ac, txx, txy];
            let yh3 = [-tyg * bc, tyg * ac, txy, tyy];
            for b in 0..4 {
                let cc = b * nf + c;
                p[(r, cc)] = ar * e3[b] - yh3[b];
                p[(nf + r, cc)] = br * e3[b] + xh3[b];
                p[(2 * nf + r, cc)] = ar * h3[b] + eps * ye3[b];
                p[(3 * nf + r, cc)] = br * h3[b] - eps * xe3[b];
            }
        }
        p[(r, 3 * nf + r)] += ONE;
        p[(nf + r, 2 * nf + r)] -= ONE;
        p[(2 * nf + r, nf + r)] -= eps;
        p[(3 * nf + r, r)] += eps;
    }
    let (rho, vecs) = eigen(&p)?;
    let columns = move |i: usize| vec![(0..4 * nf).map(|r| vecs[(r, i)]).collect()];
    Ok(Eigenmodes { rho, multiplicity: 2, columns: Box::new(columns) })
}

/// Solves one truncation: modes above, in each coating layer (both directions) and below, the boundary
/// conditions at every interface `u = u_i` (C9), Rayleigh amplitudes and power efficiencies of the propagating
/// orders for TE and TM incidence.
pub(crate) fn solve(
    set: &Setting,
    orders: &Orders,
    surf: &FineSurface,
    two_d: bool,
) -> Result<RawSolution, RigorousError> {
    let nf = orders.len();
    let eps1 = C64::new(set.eps1, 0.0);
    let modes = |eps, sides: &[Side]| modes(set, orders, surf, two_d, eps, sides);
    // Column blocks in order: above (up), each layer (up, then down), substrate (down). Each block is
    // normalised where it is launched: up-going modes at the interface below them, down-going at the one above,
    // so no factor exp(iρ d) ever grows.
    let nl = set.layers.len();
    let mut blocks: Vec<MediumModes> = modes(eps1, &[Side::Above])?;
    for &(eps, _) in &set.layers {
        blocks.extend(modes(eps, &[Side::Above, Side::Below])?);
    }
    let below = modes(set.eps2, &[Side::Below])?.pop().expect("one side asked");
    blocks.push(below);
    let n_unknown: usize = blocks.iter().map(|b| b.columns.len()).sum();
    if n_unknown != 4 * nf * (nl + 1) {
        return Err(RigorousError::Numerical(format!(
            "mode count {n_unknown} does not match the {} boundary conditions",
            4 * nf * (nl + 1)
        )));
    }
    // Incident wave: order (0, 0), travelling down; TE = s, TM = p of its own plane of incidence.
    let q0 = orders.list.iter().position(|&o| o == (0, 0)).expect("order (0,0) is always kept");
    let kz_inc = -kz_up(eps1, set.kx0, set.ky0);
    let k_inc = [C64::new(set.kx0, 0.0), C64::new(set.ky0, 0.0), kz_inc];
    let (s_inc, p_inc) = sp_basis(&k_inc, eps1, set.phi);
    let phi_inc = phase_coeffs(surf, kz_inc);
    let inc_te = plane_wave_column(orders, q0, &phi_inc, &s_inc, &k_inc);
    let inc_tm = plane_wave_column(orders, q0, &phi_inc, &p_inc, &k_inc);

    // A x = −incident: at interface i, the columns of the medium above minus those of the medium below, each
    // times exp(iρ (u_i − u_launch)); then every column scaled to unit max-norm (equilibration).
    let n = 4 * nf * (nl + 1);
    let mut a = Mat::<C64>::zeros(n, n);
    let mut col0 = 0;
    let mut scale = Vec::with_capacity(n);
    for (b, block) in blocks.iter().enumerate() {
        // Block b: 0 above; 1 + 2l (up) and 2 + 2l (down) in layer l; 2 nl + 1 the substrate. It meets
        // interface `top` (as the medium below it) and `bottom` (as the medium above it).
        let (medium, up) = if b == 0 {
            (0, true)
        } else if b == 2 * nl + 1 {
            (nl + 1, false)
        } else {
            (b.div_ceil(2), b % 2 == 1)
        };
        let d = if medium >= 1 && medium <= nl { set.layers[medium - 1].1 } else { 0.0 };
        for (j, col) in block.columns.iter().enumerate() {
            let rho = block.rho[j];
            // (interface, sign, factor): the medium above interface i enters with +, the one below with −.
            let mut hits: Vec<(usize, f64, C64)> = Vec::new();
            if medium > 0 {
                // Its top interface is medium − 1; up-going modes launched at the bottom travel d to it.
                let f = if up { (C64::new(0.0, 1.0) * rho * d).exp() } else { ONE };
                hits.push((medium - 1, -1.0, f));
            }
            if medium <= nl {
                // Its bottom interface is `medium`; down-going modes launched at the top travel d to it.
                let f = if up { ONE } else { (C64::new(0.0, -1.0) * rho * d).exp() };
                hits.push((medium, 1.0, f));
            }
            let mut mx: f64 = 0.0;
            for &(_, _, f) in &hits {
                mx = mx.max(col.iter().map(|v| (v * f).norm()).fold(0.0, f64::max));
            }
            let mx = mx.max(1e-300);
            scale.push(1.0 / mx);
            for &(i, sign, f) in &hits {
                for r in 0..4 * nf {
                    a[(4 * nf * i + r, col0 + j)] = col[r] * f * (sign / mx);
                }
            }
        }
        col0 += block.columns.len();
    }
    let mut rhs = Mat::<C64>::zeros(n, 2);
    for r in 0..4 * nf {
        rhs[(r, 0)] = -inc_te[r];
        rhs[(r, 1)] = -inc_tm[r];
    }
    let x = a.partial_piv_lu().solve(&rhs);
    if (0..n).any(|r| !(x[(r, 0)].is_finite() && x[(r, 1)].is_finite())) {
        return Err(RigorousError::Numerical("the boundary-value system is singular".into()));
    }
    let amp = |j: usize, pol: usize| x[(j, pol)] * scale[j];
    let kz0 = -kz_inc.re;
    let collect = |modes: &MediumModes, offset: usize, lossless: bool| -> Vec<OrderAmplitudes> {
        modes
            .analytic
            .iter()
            .enumerate()
            .map(|(i, &(q, kz))| {
                let (m, nn) = orders.list[q];
                let (kx, ky) = tangential(set, m, nn);
                let mut oa = OrderAmplitudes { m, n: nn, k: [kx, ky, kz.re], amp: [[ZERO; 2]; 2], eff: [[0.0; 2]; 2] };
                for pol in 0..2 {
                    for sp in 0..2 {
                        let a = amp(offset + 2 * i + sp, pol);
                        oa.amp[pol][sp] = a;
                        // Power flux ½ |kz| |A|² against the incident ½ kz0 (C10); none leaves through a lossy medium.
                        oa.eff[pol][sp] = if lossless { kz.re.abs() * a.norm_sqr() / kz0 } else { 0.0 };
                    }
                }
                oa
            })
            .collect()
    };
    let last = blocks.last().expect("substrate block");
    Ok(RawSolution {
        reflected: collect(&blocks[0], 0, true),
        transmitted: collect(last, n - last.columns.len(), set.eps2.im == 0.0),
    })
}
