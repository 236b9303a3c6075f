//! Rigorous diffraction efficiencies of surface-relief gratings given as height profiles (what an AFM scan
//! gives): the C-method of Chandezon, for profiles periodic in one direction (with conical incidence) and in two
//! (crossed gratings), on metals and dielectrics, TE and TM, with the number of Fourier orders chosen
//! automatically to a stated tolerance. docs/rigorous.md has the method, its equations, conventions and the
//! measured convergence, accuracy and speed.
//!
//! Conventions (docs/PHYSICS.md): `z` is the outward normal, the light direction `ω_i` points from the surface
//! towards the light, `ω_i = (sin θ_i cos φ_i, sin θ_i sin φ_i, cos θ_i)` (x axis = azimuth 0). The reflected
//! order `(m, n)` leaves along `ω_r` with `n₁ ω_r,xy = −n₁ ω_i,xy + (m λ/Λx, n λ/Λy)` (`n₁` the incident
//! medium's index), i.e. `m λ/d = n₁ (sin θ_i − sin θ_r)` in the plane of incidence, `θ_r` positive on the
//! specular side. TE (s): the incident electric field perpendicular to the incident wave's plane of incidence
//! (the plane through `z` and `ω_i`; at normal incidence the plane of azimuth `φ_i`), TM (p): the magnetic
//! field perpendicular to it. Efficiencies are power fractions of the incident flux through the mean plane,
//! summed over the outgoing polarisations (the split into the outgoing wave's own s and p is given too).
//!
//! ```
//! use iridis_rigorous::{solve_1d, Options, Problem, Profile1d};
//! let period = 1000.0;
//! let heights: Vec<f64> = (0..64)
//!     .map(|i| 50.0 * (2.0 * std::f64::consts::PI * i as f64 / 64.0).sin())
//!     .collect();
//! let profile = Profile1d { period_nm: period, heights_nm: heights };
//! let problem = Problem::new(550.0, 0.0, 0.0, num_complex::Complex64::new(1.5, 0.0));
//! let sol = solve_1d(&profile, &problem, &Options::default()).unwrap();
//! assert!(sol.convergence.met);
//! let total = sol.reflected_total.te + sol.transmitted_total.te;
//! assert!((total - 1.0).abs() < 1e-6);
//! ```

#![allow(clippy::needless_range_loop)]

mod bench;
mod cmethod;
// Public but hidden: not part of the API, reachable only so that its unit test can live in tests/ (Cargo.toml,
// `[lib] test = false`); a pure function of its inputs, so exposing it lets no caller break the solver.
#[doc(hidden)]
pub mod surface;
mod waves;

pub use bench::{benchmark, BenchCase, BenchOrder, BenchReport};

use cmethod::{OrderAmplitudes, Orders, RawSolution, Setting};
use num_complex::Complex64;
use rayon::prelude::*;
use serde::Serialize;
use surface::FineSurface;

/// Bad input or a numerical failure.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RigorousError {
    #[error("the period must be a positive number of nanometres, got {0}")]
    InvalidPeriod(f64),
    #[error("the wavelength must be a positive number of nanometres, got {0}")]
    InvalidWavelength(f64),
    #[error("the height profile has a non-finite value ({value}) at sample {index}")]
    NonFiniteHeight { index: usize, value: f64 },
    #[error("a 1-D profile needs at least 3 height samples over one period, got {0}")]
    TooFewSamples(usize),
    #[error("the height grid has {len} values, but rows × cols = {rows} × {cols} = {}", rows * cols)]
    GridSize { rows: usize, cols: usize, len: usize },
    #[error("the rigorous solver needs a height grid of at least 3 × 3 samples over the unit cell (or a profile of one row and at least 3 columns), got {rows} × {cols}")]
    GridTooSmall { rows: usize, cols: usize },
    #[error("the polar angle of incidence must be in [0°, 90°), got {0}°")]
    InvalidPolarAngle(f64),
    #[error("the azimuth of incidence must be a finite angle, got {0}")]
    InvalidAzimuth(f64),
    #[error("the incident medium's index must be a positive real number, got {0}")]
    InvalidIncidentIndex(f64),
    #[error("the substrate's extinction coefficient k must be ≥ 0 (n + ik, k ≥ 0 absorbs), got {0}")]
    NegativeExtinction(f64),
    #[error("the substrate's refractive index must be finite with n ≥ 0 and n + ik ≠ 0, got {0} + {1}i")]
    InvalidSubstrateIndex(f64, f64),
    #[error("coating {layer}: the thickness must be a finite number ≥ 0 nm and the index n + ik finite with n ≥ 0, k ≥ 0, got {thickness} nm, {n} + {k}i")]
    InvalidCoating { layer: usize, thickness: f64, n: f64, k: f64 },
    #[error("the tolerance must be a positive number, got {0}")]
    InvalidTolerance(f64),
    #[error("the order limits are inconsistent: {0}")]
    InvalidOrders(String),
    #[error(
        "{orders} orders propagate each side along a period of {period_nm} nm at λ = {wavelength_nm} nm, more than \
         the {max} the solver resolves: give a shorter period or a longer wavelength (in nm)"
    )]
    TooManyOrders { orders: usize, max: usize, period_nm: f64, wavelength_nm: f64 },
    #[error("numerical failure in the C-method: {0}")]
    Numerical(String),
}

/// A 1-D profile: heights over one period, sampled uniformly at `x = i · period/len` (`i = 0 … len−1`, the
/// period's end not repeated). The surface is the trigonometric interpolant of the samples (smooth and periodic).
#[derive(Debug, Clone, Serialize)]
pub struct Profile1d {
    pub period_nm: f64,
    pub heights_nm: Vec<f64>,
}

/// A 2-D profile: a `rows × cols` height grid over one unit cell, row-major (`heights_nm[row * cols + col]`),
/// `x = col · Λx/cols`, `y = (rows − 1 − row) · Λy/rows` (row 0 is the top of the displayed image, y grows
/// upwards, as docs/PHYSICS.md says).
#[derive(Debug, Clone, Serialize)]
pub struct Profile2d {
    pub period_x_nm: f64,
    pub period_y_nm: f64,
    pub rows: usize,
    pub cols: usize,
    pub heights_nm: Vec<f64>,
}

/// A conformal coating layer: the profile shifted down by `thickness_nm` along z (every interface is the same
/// surface, as the C-method needs; on slopes the thickness along the normal is `thickness/√(1 + |∇h|²)`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Coating {
    pub thickness_nm: f64,
    /// Complex refractive index `n + ik` (`k ≥ 0`) at the problem's wavelength.
    #[serde(serialize_with = "serialize_index")]
    pub index: Complex64,
}

fn serialize_index<S: serde::Serializer>(n: &Complex64, s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeTuple;
    let mut t = s.serialize_tuple(2)?;
    t.serialize_element(&n.re)?;
    t.serialize_element(&n.im)?;
    t.end()
}

/// One wavelength and direction of incidence, with the media at that wavelength (the caller resolves materials).
#[derive(Debug, Clone)]
pub struct Problem {
    pub wavelength_nm: f64,
    /// Polar angle of the light direction `ω_i` (rad), in `[0, π/2)`.
    pub theta_i_rad: f64,
    /// Azimuth of `ω_i` (rad), from the x axis (the direction across a 1-D profile's grooves).
    pub phi_i_rad: f64,
    /// Real refractive index of the incident medium (1 for air).
    pub incident_index: f64,
    /// Complex refractive index `n + ik` (`k ≥ 0`) of the substrate at this wavelength.
    pub substrate_index: Complex64,
    /// Conformal coatings on the substrate, from the top (incident side) down; empty for a bare substrate.
    pub coatings: Vec<Coating>,
}

impl Problem {
    /// In air: `theta_i_rad`, `phi_i_rad` in radians.
    pub fn new(wavelength_nm: f64, theta_i_rad: f64, phi_i_rad: f64, substrate_index: Complex64) -> Self {
        Problem { wavelength_nm, theta_i_rad, phi_i_rad, incident_index: 1.0, substrate_index, coatings: Vec::new() }
    }

    /// A substrate given by its relative permittivity (e.g. `ε = −20 + 1i`): `n + ik = √ε` with `k ≥ 0`.
    pub fn index_from_permittivity(eps: Complex64) -> Complex64 {
        let n = eps.sqrt();
        if n.im < 0.0 {
            -n
        } else {
            n
        }
    }
}

/// How the number of Fourier orders is chosen.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Options {
    /// The largest change of any propagating order's efficiency between two truncations, relative to
    /// `max(η, efficiency_floor)`, at which the answer is accepted (default 1e-3).
    pub tolerance: f64,
    /// Below this efficiency the change is measured in absolute terms, `tolerance × efficiency_floor`
    /// (default 1e-3: relative 1e-3 above η = 1e-3, absolute 1e-6 below).
    pub efficiency_floor: f64,
    /// Smallest truncation `M` (orders `−M … M` along each periodic direction); raised to hold every
    /// propagating order with a margin. `None`: 8 for a 1-D profile, 3 for a 2-D one.
    pub min_orders: Option<usize>,
    /// Largest `M` tried; reaching it without meeting the tolerance is reported (`convergence.met = false`).
    /// `None`: 120 for a 1-D profile, 8 for a 2-D one (a 4·17² = 1156 eigenproblem per medium).
    pub max_orders: Option<usize>,
    /// Solve at exactly this `M` and the next step up (for the error estimate), no search.
    pub fixed_orders: Option<usize>,
}

impl Options {
    /// Defaults for a 1-D profile: tolerance 1e-3, `M` from 8 up to 120 (the same as `default()` gives a 1-D
    /// profile).
    pub fn default_1d() -> Self {
        Options { min_orders: Some(8), max_orders: Some(120), ..Options::default() }
    }
    /// Defaults for a 2-D profile: tolerance 1e-3, `M` from 3 up to 8 along each direction (the same as
    /// `default()` gives a 2-D profile).
    pub fn default_2d() -> Self {
        Options { min_orders: Some(3), max_orders: Some(8), ..Options::default() }
    }
    fn limits(&self, two_d: bool) -> (usize, usize) {
        let (lo, hi) = if two_d { (3, 8) } else { (8, 120) };
        (self.min_orders.unwrap_or(lo), self.max_orders.unwrap_or(hi))
    }
}

impl Default for Options {
    /// Tolerance 1e-3 (relative above η = 1e-3), order limits chosen by the dimension of the profile.
    fn default() -> Self {
        Options { tolerance: 1e-3, efficiency_floor: 1e-3, min_orders: None, max_orders: None, fixed_orders: None }
    }
}

/// Efficiencies for TE and TM incidence and their mean (unpolarised light).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Efficiency {
    pub te: f64,
    pub tm: f64,
    pub unpolarized: f64,
}

impl Efficiency {
    fn new(te: f64, tm: f64) -> Self {
        Efficiency { te, tm, unpolarized: 0.5 * (te + tm) }
    }
    fn add(self, o: Efficiency) -> Self {
        Efficiency::new(self.te + o.te, self.tm + o.tm)
    }
}

/// One propagating diffraction order.
#[derive(Debug, Clone, Serialize)]
pub struct Order {
    pub m: i32,
    pub n: i32,
    /// Polar angle of the outgoing direction (degrees from the normal, upwards for reflected orders, downwards
    /// for transmitted ones).
    pub theta_deg: f64,
    /// Azimuth of the outgoing direction (degrees, `atan2(ω_y, ω_x)`, in (−180°, 180°]; 180° is the specular side
    /// for light from azimuth 0).
    pub phi_deg: f64,
    /// Power efficiency summed over the outgoing polarisations.
    pub efficiency: Efficiency,
    /// The part that leaves s-polarised (with respect to the outgoing wave's own plane of incidence).
    pub into_s: Efficiency,
    /// The part that leaves p-polarised.
    pub into_p: Efficiency,
}

/// One step of the order search.
#[derive(Debug, Clone, Serialize)]
pub struct ConvergenceStep {
    /// Truncation `[Mx, My]` (orders `−M … M`; `My = 0` for a 1-D profile).
    pub orders: [usize; 2],
    /// Largest change of a propagating efficiency from the previous step, relative to `max(η, floor)`
    /// (`None` at the first step).
    pub change: Option<f64>,
}

/// How an answer was converged: returned with every solution.
#[derive(Debug, Clone, Serialize)]
pub struct Convergence {
    pub method: &'static str,
    /// Truncation `[Mx, My]` of the answer (orders `−M … M` along x and y).
    pub orders: [usize; 2],
    /// Number of Fourier harmonics in the answer's expansion, `(2Mx + 1)(2My + 1)`.
    pub harmonics: usize,
    /// The truncation it was compared with (the previous step).
    pub compared_with: [usize; 2],
    /// Largest change of any propagating order's efficiency (TE and TM, reflected and transmitted) between the
    /// two truncations, relative to `max(η, efficiency_floor)`: the error estimate of the answer.
    pub estimated_error: f64,
    pub tolerance: f64,
    pub efficiency_floor: f64,
    /// Whether `estimated_error ≤ tolerance`.
    pub met: bool,
    /// Whether the search stopped at `max_orders` (or at the fixed truncation asked for).
    pub capped: bool,
    /// For a lossless stack (substrate and coatings), `|R + T − 1|` of the answer (worst of TE, TM), an
    /// independent check; the search does not accept a truncation whose energy error exceeds the tolerance.
    pub energy_error: Option<f64>,
    pub history: Vec<ConvergenceStep>,
    /// How many times the cell repeats itself exactly along x and y: the solver takes one repeat (period
    /// `Λ/k`), whose truncation `orders` is, and numbers the answer's orders in the cell's (`m = k·m'`). A cell
    /// of eight periods solved whole coupled only every eighth order, so its truncation search stopped at ±1.5 of
    /// the true period's orders with R + T = 104.9 %.
    pub cell_repeats: [usize; 2],
}

/// The answer for one problem.
#[derive(Debug, Clone, Serialize)]
pub struct Solution {
    pub wavelength_nm: f64,
    pub theta_i_deg: f64,
    pub phi_i_deg: f64,
    pub incident_index: f64,
    /// Substrate index `[n, k]`.
    pub substrate_index: [f64; 2],
    pub coatings: Vec<Coating>,
    /// Reflected propagating orders.
    pub orders: Vec<Order>,
    /// Transmitted propagating orders (empty for an absorbing substrate, where nothing leaves below).
    pub transmitted_orders: Vec<Order>,
    pub reflected_total: Efficiency,
    pub transmitted_total: Efficiency,
    /// `1 − R − T`: absorbed in the substrate (zero up to the error for a lossless one).
    pub absorbed: Efficiency,
    pub convergence: Convergence,
}

/// A grating for the batch function.
#[derive(Debug, Clone, Serialize)]
pub enum Grating {
    OneD(Profile1d),
    TwoD(Profile2d),
}

fn check_period(p: f64) -> Result<(), RigorousError> {
    if p.is_finite() && p > 0.0 {
        Ok(())
    } else {
        Err(RigorousError::InvalidPeriod(p))
    }
}

fn check_heights(h: &[f64]) -> Result<(), RigorousError> {
    match h.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(RigorousError::NonFiniteHeight { index, value: h[index] }),
        None => Ok(()),
    }
}

fn check_problem(p: &Problem) -> Result<(), RigorousError> {
    if !(p.wavelength_nm.is_finite() && p.wavelength_nm > 0.0) {
        return Err(RigorousError::InvalidWavelength(p.wavelength_nm));
    }
    if !(p.theta_i_rad.is_finite() && p.theta_i_rad >= 0.0 && p.theta_i_rad < std::f64::consts::FRAC_PI_2) {
        return Err(RigorousError::InvalidPolarAngle(p.theta_i_rad.to_degrees()));
    }
    if !p.phi_i_rad.is_finite() {
        return Err(RigorousError::InvalidAzimuth(p.phi_i_rad));
    }
    if !(p.incident_index.is_finite() && p.incident_index > 0.0) {
        return Err(RigorousError::InvalidIncidentIndex(p.incident_index));
    }
    let n = p.substrate_index;
    if !(n.re.is_finite() && n.im.is_finite()) || n.re < 0.0 || n.norm() == 0.0 {
        return Err(RigorousError::InvalidSubstrateIndex(n.re, n.im));
    }
    if n.im < 0.0 {
        return Err(RigorousError::NegativeExtinction(n.im));
    }
    for (layer, c) in p.coatings.iter().enumerate() {
        let ok = c.thickness_nm.is_finite()
            && c.thickness_nm >= 0.0
            && c.index.re.is_finite()
            && c.index.im.is_finite()
            && c.index.re >= 0.0
            && c.index.im >= 0.0
            && c.index.norm() > 0.0;
        if !ok {
            return Err(RigorousError::InvalidCoating {
                layer,
                thickness: c.thickness_nm,
                n: c.index.re,
                k: c.index.im,
            });
        }
    }
    Ok(())
}

fn check_options(o: &Options) -> Result<(), RigorousError> {
    if !(o.tolerance.is_finite() && o.tolerance > 0.0) {
        return Err(RigorousError::InvalidTolerance(o.tolerance));
    }
    if !(o.efficiency_floor.is_finite() && o.efficiency_floor > 0.0) {
        return Err(RigorousError::InvalidOrders(format!(
            "efficiency_floor must be positive, got {}",
            o.efficiency_floor
        )));
    }
    let (lo, hi) = o.limits(false);
    let (lo2, hi2) = o.limits(true);
    if hi < lo.max(1) || hi2 < lo2.max(1) {
        return Err(RigorousError::InvalidOrders(format!(
            "max_orders {:?} is below min_orders {:?} (or below 1)",
            o.max_orders, o.min_orders
        )));
    }
    Ok(())
}

/// The normalised setting of a problem on a grating with the given periods (nm).
fn setting(p: &Problem, period_x: f64, period_y: f64) -> Setting {
    let n1 = p.incident_index;
    let (st, (sp, cp)) = (p.theta_i_rad.sin(), p.phi_i_rad.sin_cos());
    Setting {
        eps1: n1 * n1,
        eps2: p.substrate_index * p.substrate_index,
        // The incident wave travels along −ω_i.
        kx0: -n1 * st * cp,
        ky0: -n1 * st * sp,
        phi: p.phi_i_rad,
        kgx: p.wavelength_nm / period_x,
        kgy: p.wavelength_nm / period_y,
        layers: p
            .coatings
            .iter()
            .map(|c| (c.index * c.index, 2.0 * std::f64::consts::PI / p.wavelength_nm * c.thickness_nm))
            .collect(),
    }
}

/// The most orders propagating each side along a direction that the solver takes, for a 1-D and a 2-D
/// profile: the truncation must hold them, and the eigenproblem grows as (2M+1)² (1-D: 2001² complex, 64 MB a
/// matrix) or (2M+1)⁴ (2-D: 4·33² = 4356², 300 MB).
pub const MAX_PROPAGATING: [usize; 2] = [1000, 16];

/// Largest |m| (or |n|) of an order propagating in either medium along one direction.
fn propagating_extent(k0: f64, kg: f64, n_max: f64) -> usize {
    // |k0 + m kg| < n_max for propagating orders; the extent is bounded by (n_max + |k0|)/kg.
    ((n_max + k0.abs()) / kg).floor() as usize
}

fn next_pow2_at_least(n: usize) -> usize {
    n.next_power_of_two()
}

/// Largest change between two truncations of the same problem, relative to `max(η, floor)`; orders are
/// matched by (m, n) and side.
fn max_change(a: &RawSolution, b: &RawSolution, floor: f64) -> f64 {
    let key = |o: &OrderAmplitudes, side: u8| (side, o.m, o.n);
    let mut worst: f64 = 0.0;
    let list_a: Vec<_> =
        a.reflected.iter().map(|o| (key(o, 0), o)).chain(a.transmitted.iter().map(|o| (key(o, 1), o))).collect();
    for (kb, ob) in b.reflected.iter().map(|o| (key(o, 0), o)).chain(b.transmitted.iter().map(|o| (key(o, 1), o))) {
        let oa = list_a.iter().find(|(ka, _)| *ka == kb).map(|(_, o)| *o);
        for pol in 0..2 {
            let eb = ob.eff[pol][0] + ob.eff[pol][1];
            let ea = oa.map(|o| o.eff[pol][0] + o.eff[pol][1]).unwrap_or(0.0);
            worst = worst.max((eb - ea).abs() / eb.max(floor));
        }
    }
    worst
}

/// The truncations the search walks through.
fn truncation_steps(start: usize, opts: &Options, two_d: bool) -> Vec<usize> {
    let max_orders = opts.limits(two_d).1;
    if let Some(m) = opts.fixed_orders {
        let m = m.max(start);
        return vec![m, m + if two_d { 2 } else { (m / 4).max(2) }];
    }
    let mut steps = vec![start.min(max_orders)];
    loop {
        let last = *steps.last().unwrap();
        if last >= max_orders {
            break;
        }
        let next = if two_d { last + 1 } else { last + (last / 2).max(4) };
        steps.push(next.min(max_orders));
    }
    if steps.len() == 1 {
        // Even at the cap, compare with a smaller truncation for an error estimate.
        let m = steps[0];
        let prev = if two_d { m.saturating_sub(1) } else { m - (m / 3).max(1).min(m) };
        steps.insert(0, prev);
    }
    steps
}

fn to_order(o: &OrderAmplitudes, n_medium: f64) -> Order {
    let eff = |sp: usize| Efficiency::new(o.eff[0][sp], o.eff[1][sp]);
    let (s, p) = (eff(0), eff(1));
    let kt = o.k[0].hypot(o.k[1]);
    let theta = (kt / n_medium).min(1.0).asin().to_degrees();
    let phi = if kt > 0.0 { o.k[1].atan2(o.k[0]).to_degrees() } else { 0.0 };
    Order { m: o.m as i32, n: o.n as i32, theta_deg: theta, phi_deg: phi, efficiency: s.add(p), into_s: s, into_p: p }
}

/// Runs the order search for one problem on a prepared grating.
fn solve_auto(
    problem: &Problem,
    opts: &Options,
    two_d: bool,
    period_x: f64,
    period_y: f64,
    make_surface: &dyn Fn(usize, usize) -> FineSurface,
) -> Result<Solution, RigorousError> {
    check_problem(problem)?;
    check_options(opts)?;
    let set = setting(problem, period_x, period_y);
    let n_max = problem
        .coatings
        .iter()
        .map(|c| c.index.re)
        .fold(problem.incident_index.max(problem.substrate_index.re), f64::max);
    let px = propagating_extent(set.kx0, set.kgx, n_max);
    let py = if two_d { propagating_extent(set.ky0, set.kgy, n_max) } else { 0 };
    // Every propagating order must be inside the truncation, so more than the cap cannot be solved (a
    // wavelength in µm read as nm: 1100 nm at 0.5 nm over n = 1.5 is 3300 orders each side, an eigenproblem of
    // gigabytes).
    let cap = MAX_PROPAGATING[usize::from(two_d)];
    if px.max(py) > cap {
        return Err(RigorousError::TooManyOrders {
            orders: px.max(py),
            max: cap,
            period_nm: if px >= py { period_x } else { period_y },
            wavelength_nm: problem.wavelength_nm,
        });
    }
    let margin = if two_d { 1 } else { 4 };
    // Every propagating order must be inside the truncation; the automatic search starts with a margin.
    let start = opts.limits(two_d).0.max(px.max(py) + margin);
    let steps = truncation_steps(if opts.fixed_orders.is_some() { px.max(py) } else { start }, opts, two_d);
    let lossless = problem.substrate_index.im == 0.0 && problem.coatings.iter().all(|c| c.index.im == 0.0);
    // |R + T − 1| of a truncation: a lossless answer that loses or makes light is not converged, whatever the
    // change from the previous truncation says.
    let energy_of = |raw: &RawSolution| {
        lossless.then(|| {
            (0..2)
                .map(|pol| {
                    let total: f64 =
                        raw.reflected.iter().chain(&raw.transmitted).map(|o| o.eff[pol][0] + o.eff[pol][1]).sum();
                    (1.0 - total).abs()
                })
                .fold(0.0, f64::max)
        })
    };
    let mut history = Vec::new();
    let mut prev: Option<(RawSolution, [usize; 2])> = None;
    let mut result = None;
    for (i, &m) in steps.iter().enumerate() {
        let (mx, my) = if two_d { (m.max(px), m.max(py)) } else { (m.max(px), 0) };
        let orders = Orders::new(mx, my);
        let lx = next_pow2_at_least((8 * mx + 16).max(32));
        let ly = if two_d { next_pow2_at_least((8 * my + 16).max(32)) } else { 1 };
        let surf = make_surface(lx, ly);
        let raw = cmethod::solve(&set, &orders, &surf, two_d)?;
        let change = prev.as_ref().map(|(p, _)| max_change(p, &raw, opts.efficiency_floor));
        history.push(ConvergenceStep { orders: [mx, my], change });
        let last = i + 1 == steps.len();
        if let Some(c) = change {
            // A comparison tests only the axes whose truncation grew: a crossed cell pinned at its cap along x
            // (the search raised y alone) says nothing of x's convergence (an 8-period near-tile read 1e-12).
            let grew = prev.as_ref().is_some_and(|(_, p)| p[0] != mx && (!two_d || p[1] != my));
            let met = grew && c <= opts.tolerance && energy_of(&raw).is_none_or(|e| e <= opts.tolerance);
            if met || last {
                // Untested along an axis, the change is no estimate; |R + T − 1| is a floor of the error.
                let estimate = if grew { c } else { c.max(energy_of(&raw).unwrap_or(0.0)) };
                result = Some((raw, [mx, my], prev.as_ref().map(|p| p.1).unwrap(), estimate, met, last));
                break;
            }
        }
        prev = Some((raw, [mx, my]));
    }
    let (raw, ord, cmp, err, met, capped) = result.expect("at least two truncations are solved");
    let orders: Vec<Order> = raw.reflected.iter().map(|o| to_order(o, problem.incident_index)).collect();
    let transmitted_orders: Vec<Order> = if problem.substrate_index.im == 0.0 {
        raw.transmitted.iter().map(|o| to_order(o, problem.substrate_index.re)).collect()
    } else {
        Vec::new()
    };
    let sum = |v: &[Order]| v.iter().fold(Efficiency::default(), |a, o| a.add(o.efficiency));
    let reflected_total = sum(&orders);
    let transmitted_total = sum(&transmitted_orders);
    let absorbed = Efficiency::new(
        1.0 - reflected_total.te - transmitted_total.te,
        1.0 - reflected_total.tm - transmitted_total.tm,
    );
    let energy_error = energy_of(&raw);
    Ok(Solution {
        wavelength_nm: problem.wavelength_nm,
        theta_i_deg: problem.theta_i_rad.to_degrees(),
        phi_i_deg: problem.phi_i_rad.to_degrees(),
        incident_index: problem.incident_index,
        substrate_index: [problem.substrate_index.re, problem.substrate_index.im],
        coatings: problem.coatings.clone(),
        orders,
        transmitted_orders,
        reflected_total,
        transmitted_total,
        absorbed,
        convergence: Convergence {
            method: if two_d { "C-method (2-D, covariant)" } else { "C-method (1-D, conical)" },
            orders: ord,
            harmonics: (2 * ord[0] + 1) * (2 * ord[1] + 1),
            compared_with: cmp,
            estimated_error: err,
            tolerance: opts.tolerance,
            efficiency_floor: opts.efficiency_floor,
            met,
            capped,
            energy_error,
            history,
            cell_repeats: [1, 1],
        },
    })
}

fn check_profile_1d(profile: &Profile1d) -> Result<(), RigorousError> {
    check_period(profile.period_nm)?;
    if profile.heights_nm.len() < 3 {
        return Err(RigorousError::TooFewSamples(profile.heights_nm.len()));
    }
    check_heights(&profile.heights_nm)
}

fn check_profile_2d(p: &Profile2d) -> Result<(), RigorousError> {
    check_period(p.period_x_nm)?;
    check_period(p.period_y_nm)?;
    if p.rows * p.cols != p.heights_nm.len() {
        return Err(RigorousError::GridSize { rows: p.rows, cols: p.cols, len: p.heights_nm.len() });
    }
    if p.cols < 3 || (p.rows != 1 && p.rows < 3) {
        return Err(RigorousError::GridTooSmall { rows: p.rows, cols: p.cols });
    }
    check_heights(&p.heights_nm)
}

/// How many times `n` samples along one axis repeat exactly (the largest `k` dividing `n`, one repeat keeping at
/// least 3 samples, with `height(i, j) = height(i + n/k, j)` for every `i` and every `j` of the `other` axis,
/// within 1e-9 of the height range: a tiled cell's rounding, not a measured relief's noise).
fn repeats(n: usize, other: usize, height: impl Fn(usize, usize) -> f64, range: f64) -> usize {
    let tolerance = 1e-9 * range;
    (2..=n / 3)
        .rev()
        .filter(|k| n.is_multiple_of(*k))
        .find(|&k| {
            let step = n / k;
            (0..other).all(|j| (0..n - step).all(|i| (height(i, j) - height(i + step, j)).abs() <= tolerance))
        })
        .unwrap_or(1)
}

fn height_range(h: &[f64]) -> f64 {
    let (lo, hi) = h.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    hi - lo
}

/// The answer on one repeat of a cell that repeats `k = [kx, ky]` times, with its orders numbered in the cell's.
fn renumbered(mut s: Solution, k: [usize; 2]) -> Solution {
    for o in s.orders.iter_mut().chain(s.transmitted_orders.iter_mut()) {
        o.m *= k[0] as i32;
        o.n *= k[1] as i32;
    }
    s.convergence.cell_repeats = k;
    s
}

/// Diffraction efficiencies of a 1-D profile (grooves along y), any incidence (conical when `φ_i ≠ 0, π`).
/// A profile that repeats itself within its period is solved on one repeat ([`Convergence::cell_repeats`]).
pub fn solve_1d(profile: &Profile1d, problem: &Problem, opts: &Options) -> Result<Solution, RigorousError> {
    check_profile_1d(profile)?;
    let h = &profile.heights_nm;
    let k = repeats(h.len(), 1, |i, _| h[i], height_range(h));
    if k > 1 {
        let one = Profile1d { period_nm: profile.period_nm / k as f64, heights_nm: h[..h.len() / k].to_vec() };
        return solve_1d(&one, problem, opts).map(|s| renumbered(s, [k, 1]));
    }
    let k0 = 2.0 * std::f64::consts::PI / problem.wavelength_nm;
    let s = profile.heights_nm.len();
    let make = |lx: usize, _ly: usize| {
        let lx = lx.max(next_pow2_at_least(2 * s));
        FineSurface::from_samples(s, 1, &profile.heights_nm, profile.period_nm, 1.0, k0, lx, 1)
    };
    check_problem(problem)?;
    solve_auto(problem, opts, false, profile.period_nm, 1.0, &make)
}

/// Diffraction efficiencies of a 2-D profile (crossed grating). A grid that repeats itself within the cell is
/// solved on one repeat ([`Convergence::cell_repeats`]).
pub fn solve_2d(profile: &Profile2d, problem: &Problem, opts: &Options) -> Result<Solution, RigorousError> {
    check_profile_2d(profile)?;
    check_problem(problem)?;
    let (rows, cols, h) = (profile.rows, profile.cols, &profile.heights_nm);
    let range = height_range(h);
    let kx = repeats(cols, rows, |i, j| h[j * cols + i], range);
    let ky = if rows == 1 { 1 } else { repeats(rows, cols, |j, i| h[j * cols + i], range) };
    if kx * ky > 1 {
        let (r, c) = (rows / ky, cols / kx);
        // The top-left repeat (rows 0 … r−1 of the displayed image; any repeat is the cell's, shifted).
        let heights_nm = (0..r).flat_map(|j| h[j * cols..j * cols + c].iter().copied()).collect();
        let one = Profile2d {
            period_x_nm: profile.period_x_nm / kx as f64,
            period_y_nm: profile.period_y_nm / ky as f64,
            rows: r,
            cols: c,
            heights_nm,
        };
        return solve_2d(&one, problem, opts).map(|s| renumbered(s, [kx, ky]));
    }
    let k0 = 2.0 * std::f64::consts::PI / problem.wavelength_nm;
    // Reorder rows so that y increases with the storage index (y = (rows − 1 − row) dy).
    let (rows, cols) = (profile.rows, profile.cols);
    let mut h = Vec::with_capacity(rows * cols);
    for j in 0..rows {
        let row = rows - 1 - j;
        h.extend_from_slice(&profile.heights_nm[row * cols..(row + 1) * cols]);
    }
    let make = |lx: usize, ly: usize| {
        let lx = lx.max(next_pow2_at_least(2 * cols));
        let ly = ly.max(next_pow2_at_least(2 * rows));
        FineSurface::from_samples(cols, rows, &h, profile.period_x_nm, profile.period_y_nm, k0, lx, ly)
    };
    solve_auto(problem, opts, true, profile.period_x_nm, profile.period_y_nm, &make)
}

/// Solves many problems (wavelengths, incidences, substrate indices) on one grating, in parallel (rayon); the
/// answers come back in the order of `problems`.
pub fn solve_batch(grating: &Grating, problems: &[Problem], opts: &Options) -> Vec<Result<Solution, RigorousError>> {
    problems
        .par_iter()
        .map(|p| match grating {
            Grating::OneD(g) => solve_1d(g, p, opts),
            Grating::TwoD(g) => solve_2d(g, p, opts),
        })
        .collect()
}

/// Samples `h(x)` at `samples` points over one period (helper for generated profiles and tests).
pub fn sample_1d(period_nm: f64, samples: usize, h: impl Fn(f64) -> f64) -> Profile1d {
    Profile1d { period_nm, heights_nm: (0..samples).map(|i| h(i as f64 * period_nm / samples as f64)).collect() }
}

/// Samples `h(x, y)` on a `rows × cols` grid with the row convention of [`Profile2d`].
pub fn sample_2d(
    period_x_nm: f64,
    period_y_nm: f64,
    rows: usize,
    cols: usize,
    h: impl Fn(f64, f64) -> f64,
) -> Profile2d {
    let mut heights = Vec::with_capacity(rows * cols);
    for row in 0..rows {
        let y = (rows - 1 - row) as f64 * period_y_nm / rows as f64;
        for col in 0..cols {
            heights.push(h(col as f64 * period_x_nm / cols as f64, y));
        }
    }
    Profile2d { period_x_nm, period_y_nm, rows, cols, heights_nm: heights }
}
