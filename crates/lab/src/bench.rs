//! The virtual test bench (paper sec. 6.1, Figures 6–7, Table 1; thesis sec. 5.3, eq. 5.3–5.6, Algorithm 6,
//! Table 5.1).
//!
//! Light falls in the x-z plane at `θ_i` (azimuth 0); the viewer moves in the same plane, `θ_r` signed and
//! positive on the specular side (PHYSICS.md). For every wavelength λ of a grid `Λ` (eq. 5.3) and viewing
//! angle of a grid `Θ` (eq. 5.4) the evaluator's relative reflectance fills the matrix
//! `R = {ρ(λ_i, θ_r^j)}` (eq. 5.5). The peak viewing angle of diffraction order `m` at each λ gives a
//! periodicity from the grating equation (paper eq. 13, thesis eq. 5.2) in this project's frame,
//! `m λ / d = sin θ_i − sin θ_r`, i.e. `d_λ = m λ / (sin θ_i − sin θ_r)` (thesis eq. 5.6, whose `θ_r` is
//! measured on the other side of the normal); their mean and variance over λ are Table 1's numbers.
//!
//! `azimuth` rotates the surface about its normal by `φ` (counter-clockwise seen from above), so the plane of
//! incidence lies at azimuth `−φ` in the surface frame: 0° measures periods along x, 90° along y.
//!
//! The peak search, in spatial frequency `q = (sin θ_i − sin θ_r)/λ` (so order `m` of period `d` sits at
//! `q = m/d`):
//! 1. without a given period, the strongest local maximum on the order's side of the mirror direction, away
//!    from it (`|q| ≥ 1/max_period`), is taken at each λ and the median of `|q|` is read as the first order:
//!    `d₀ = 1/median`; with `--period`, `d₀` is the given period;
//! 2. at each λ the maximum inside the order's window `|q − m/d₀| ≤ 1/(2d₀)` is refined to sub-sample accuracy
//!    by a parabola through the logarithms of the three samples around it (exact for a Gaussian peak); a
//!    maximum on the window's edge is no peak and the wavelength is skipped;
//! 3. every local maximum inside the window with at least a quarter of that wavelength's peak is a ridge
//!    candidate; candidates are grouped by period (gaps above 1.5 % split groups) and groups seen at a quarter
//!    of the wavelengths or more are the ridges (Xenopeltis, paper Figure 7d).

use iridis_diffraction::geometry::{direction, Vec3};
use iridis_diffraction::Evaluator;
use rayon::prelude::*;
use serde::Serialize;

use crate::{LabError, Progress};

/// Geometry and grids of a test-bench run.
#[derive(Debug, Clone)]
pub struct BenchSetup {
    /// Angle of incidence `θ_i` (rad).
    pub incidence: f64,
    /// Rotation of the surface about its normal (rad).
    pub azimuth: f64,
    /// Diffraction order `m` (non-zero).
    pub order: i32,
    /// The wavelength grid `Λ` (nm, increasing).
    pub wavelengths_nm: Vec<f64>,
    /// The viewing-angle grid `Θ` (degrees, signed, uniform and increasing).
    pub angles_deg: Vec<f64>,
    /// A known period (nm) to centre the order's window on, instead of estimating it.
    pub period_hint_nm: Option<f64>,
    /// Longest period considered (nm): responses with `|q| < 1/max_period` belong to the mirror direction.
    pub max_period_nm: f64,
}

impl BenchSetup {
    /// The paper's bench: `θ_i`, surface azimuth, order, λ from `from` to `to` in `step` (nm), viewing angles
    /// from `angle_min` to `angle_max` in `angle_step` (degrees).
    pub fn new(
        incidence: f64,
        azimuth: f64,
        order: i32,
        (from, to, step): (f64, f64, f64),
        (angle_min, angle_max, angle_step): (f64, f64, f64),
    ) -> Result<Self, LabError> {
        if !(incidence.is_finite() && (0.0..std::f64::consts::FRAC_PI_2).contains(&incidence)) {
            return Err(LabError::invalid(format!("incidence {:.3}° must be in [0°, 90°)", incidence.to_degrees())));
        }
        if !azimuth.is_finite() {
            return Err(LabError::invalid("the azimuth must be a finite angle"));
        }
        // Beyond one turn: degrees given for radians (Python's azimuth=90 measured along 5157°).
        if azimuth.abs() > std::f64::consts::TAU + 1e-9 {
            return Err(LabError::invalid(format!(
                "azimuth {:.2}° is beyond one turn (±360°): an angle in degrees given as radians? (90° is {:.4} rad)",
                azimuth.to_degrees(),
                std::f64::consts::FRAC_PI_2
            )));
        }
        if order == 0 {
            return Err(LabError::invalid(
                "order 0 is the mirror direction and carries no period; use --order 1 (or −1, 2, …)",
            ));
        }
        if !(from.is_finite() && to.is_finite() && step.is_finite()) || step <= 0.0 || to < from || from <= 0.0 {
            return Err(LabError::invalid(format!(
                "wavelength range {from}–{to} nm in steps of {step} nm: need 0 < from ≤ to and step > 0"
            )));
        }
        iridis_color::spectrum::check_light_nanometres(from).map_err(|e| LabError::invalid(e.to_string()))?;
        let wavelengths_nm =
            iridis_color::spectrum::range_grid(from, to, step).map_err(|e| LabError::invalid(e.to_string()))?;
        if !(angle_step.is_finite() && angle_step > 0.0) {
            return Err(LabError::invalid(format!("angle step {angle_step}° must be positive")));
        }
        if !(angle_min.is_finite() && angle_max.is_finite() && angle_min < angle_max)
            || angle_min <= -90.0
            || angle_max >= 90.0
        {
            return Err(LabError::invalid(format!(
                "viewing angles {angle_min}°…{angle_max}° must lie strictly between −90° and 90°, the first below \
                 the second"
            )));
        }
        // Counted in f64: a tiny step's count would wrap past usize.
        let n = ((angle_max - angle_min) / angle_step + 1e-9).floor() + 1.0;
        if n < 3.0 {
            return Err(LabError::invalid("the viewing-angle grid needs at least three angles"));
        }
        if n * wavelengths_nm.len() as f64 > 50_000_000.0 {
            return Err(LabError::invalid(format!(
                "{} angles × {} wavelengths is too many; use a coarser --angle-step or --step",
                iridis_color::spectrum::short_number(n),
                wavelengths_nm.len()
            )));
        }
        let n = n as usize;
        let angles_deg = (0..n).map(|k| angle_min + k as f64 * angle_step).collect();
        Ok(Self {
            incidence,
            azimuth,
            order,
            wavelengths_nm,
            angles_deg,
            period_hint_nm: None,
            max_period_nm: 10_000.0,
        })
    }

    /// The direction towards the light, in the surface frame.
    pub fn light(&self) -> Vec3 {
        direction(self.incidence, -self.azimuth)
    }

    /// The direction towards the viewer at signed `θ_r` (degrees), in the surface frame.
    pub fn viewer(&self, theta_r_deg: f64) -> Vec3 {
        let t = theta_r_deg.to_radians();
        let (s, c) = (-self.azimuth).sin_cos();
        [-t.sin() * c, -t.sin() * s, t.cos()]
    }

    /// Spatial frequency `q = (sin θ_i − sin θ_r)/λ` (1/nm) of a viewing angle.
    pub fn frequency(&self, wavelength_nm: f64, theta_r_deg: f64) -> f64 {
        (self.incidence.sin() - theta_r_deg.to_radians().sin()) / wavelength_nm
    }

    /// The viewing angle (degrees) of order `m` for period `d`, or `None` where the order is evanescent.
    pub fn grating_angle(&self, m: f64, wavelength_nm: f64, period_nm: f64) -> Option<f64> {
        let s = self.incidence.sin() - m * wavelength_nm / period_nm;
        (s.abs() < 1.0).then(|| s.asin().to_degrees())
    }
}

/// The reflectance matrix `R(λ, θ_r)` of thesis eq. 5.5.
#[derive(Debug, Clone)]
pub struct ReflectanceMatrix {
    pub wavelengths_nm: Vec<f64>,
    pub angles_deg: Vec<f64>,
    /// `values[i · angles + j] = ρ(λ_i, θ_r^j)`.
    pub values: Vec<f64>,
}

impl ReflectanceMatrix {
    pub fn row(&self, i: usize) -> &[f64] {
        let n = self.angles_deg.len();
        &self.values[i * n..(i + 1) * n]
    }
}

/// Fills `R(λ, θ_r)` with the evaluator's spectral reflectance, all cores; `progress(wavelengths_done)`.
pub fn reflectance_matrix(
    evaluator: &dyn Evaluator,
    setup: &BenchSetup,
    progress: Progress,
) -> Result<ReflectanceMatrix, LabError> {
    let wi = setup.light();
    if evaluator.reflectance(setup.wavelengths_nm[0], wi, setup.viewer(0.0)).is_none() {
        return Err(LabError::invalid(format!(
            "the {} method integrates over wavelength in advance and has no spectral reflectance for the test \
             bench; use reference, ground-truth, nmm, pq, stam-periodic or stam-gaussian",
            evaluator.name()
        )));
    }
    let viewers: Vec<Vec3> = setup.angles_deg.iter().map(|&a| setup.viewer(a)).collect();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let rows: Vec<Vec<f64>> = setup
        .wavelengths_nm
        .par_iter()
        .map(|&l| {
            let row = viewers.iter().map(|&wr| evaluator.reflectance(l, wi, wr).unwrap_or(0.0)).collect();
            progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
            row
        })
        .collect();
    Ok(ReflectanceMatrix {
        wavelengths_nm: setup.wavelengths_nm.clone(),
        angles_deg: setup.angles_deg.clone(),
        values: rows.into_iter().flatten().collect(),
    })
}

/// The peak of one order at one wavelength.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Peak {
    pub wavelength_nm: f64,
    /// Peak viewing angle (degrees, signed as in PHYSICS.md).
    pub angle_deg: f64,
    /// `d_λ = m λ / (sin θ_i − sin θ_r)` (thesis eq. 5.6 in this frame).
    pub period_nm: f64,
    /// `ρ` at the sample nearest the peak.
    pub reflectance: f64,
}

/// Mean and (population) variance of the per-wavelength periods.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Periodicity {
    pub mean: f64,
    pub variance: f64,
}

/// Largest relative spread `√variance / mean` of the per-wavelength periods for which a direction counts as
/// having a definite period. A grating's periods agree to ≲ 0.01 % (blazed 2500 nm: 0.004 %); along the
/// Elaphe-like fingers, which have no period (paper sec. 7), they spread by ≈ 8 %.
pub const DEFINITE_SPREAD: f64 = 0.01;

/// Smallest ratio of the strongest ridge's strength to every other ridge's for a direction to have one
/// definite period. A patch's spectrum is a set of DFT spikes `1/L` apart, so even a structure without a
/// period (the Elaphe-like fingers along their length) can put one spike at the same place for every λ — a
/// tiny spread — while two or three other ridges are nearly as strong (measured: 1.26× the next). A grating
/// has one ridge; the Xenopeltis-like rows' strongest ridge carries 1.97× the next.
pub const DOMINANT_RIDGE: f64 = 1.5;

impl Periodicity {
    /// `√variance / mean`.
    pub fn relative_spread(&self) -> f64 {
        self.variance.max(0.0).sqrt() / self.mean.abs()
    }

    /// Whether the peaks follow one period (spread ≤ [`DEFINITE_SPREAD`]).
    pub fn is_definite(&self) -> bool {
        self.relative_spread() <= DEFINITE_SPREAD
    }
}

/// A ridge of the reflectance matrix: the peaks of one sub-structure's period.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Ridge {
    pub period_nm: f64,
    pub variance: f64,
    /// Wavelengths at which the ridge has a peak.
    pub wavelengths: usize,
    /// Mean reflectance of its peaks.
    pub strength: f64,
    pub peaks: Vec<Peak>,
}

/// Everything the test bench measures.
#[derive(Debug, Clone)]
pub struct BenchResult {
    pub order: i32,
    pub incidence_deg: f64,
    pub azimuth_deg: f64,
    pub peaks: Vec<Peak>,
    pub periodicity: Periodicity,
    /// The period that centred the order's window (given, or the first-order estimate).
    pub window_period_nm: f64,
    /// Ridges, strongest first (reported when more than one).
    pub ridges: Vec<Ridge>,
    /// The patch the matrix came from, when known ([`BenchResult::on_patch`]): its DFT grid limits the period.
    pub grid: Option<PatchGrid>,
}

/// The patch's extent along the measured direction and the coherence a bench ran with. A patch of extent `L`
/// there has a spectrum sampled `1/L` apart along it. Where the window is wider than the patch
/// ([`PatchGrid::quantised`]), the patch is one unit cell of a periodic surface: its orders sit on that grid
/// and a period `d` is read to ± half a step, `d²/(2L)` (a 2500 nm grating on a 65 µm extent: ± 48 nm — and
/// exact when the period divides the extent, as Table 1's does). Otherwise the window's own resolution limits
/// it: `± d² σ_f`, `σ_f = 1/(2πσ_s)` the window's width in frequency.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchGrid {
    /// The patch's extent along the measured direction (nm).
    pub extent_nm: f64,
    pub coherence_nm: f64,
}

impl PatchGrid {
    /// The period's uncertainty (nm): half a DFT step, or the window's resolution (above).
    pub fn uncertainty_nm(&self, period_nm: f64) -> f64 {
        if self.quantised() {
            period_nm * period_nm / (2.0 * self.extent_nm)
        } else {
            let sigma_f = 1.0 / (std::f64::consts::TAU * self.coherence_nm / 4.0);
            period_nm * period_nm * sigma_f
        }
    }

    /// The window is wider than the patch along the measured direction, so the period sits on the DFT grid.
    pub fn quantised(&self) -> bool {
        self.coherence_nm > self.extent_nm
    }
}

impl BenchResult {
    /// One definite period: the peaks follow one period ([`Periodicity::is_definite`]) and, where the matrix
    /// has several ridges, the strongest dominates every other by [`DOMINANT_RIDGE`]. (How precisely the
    /// period is known is [`BenchResult::uncertainty_nm`].)
    pub fn is_definite(&self) -> bool {
        self.periodicity.is_definite() && !matches!(self.ridge_dominance(), Some(d) if d < DOMINANT_RIDGE)
    }

    /// Records the patch the matrix came from: its extent along the measured direction and the window.
    pub fn on_patch(mut self, extent_nm: f64, coherence_nm: f64) -> Self {
        self.grid = Some(PatchGrid { extent_nm, coherence_nm });
        self
    }

    /// Whether the period was read off the DFT grid of a patch smaller than the window.
    pub fn is_quantised(&self) -> bool {
        self.grid.is_some_and(|g| g.quantised())
    }

    /// `±` of the mean period ([`PatchGrid::uncertainty_nm`]), when the patch is known.
    pub fn uncertainty_nm(&self) -> Option<f64> {
        self.grid.map(|g| g.uncertainty_nm(self.periodicity.mean))
    }

    /// The strength of the strongest ridge relative to the next, where there are several.
    pub fn ridge_dominance(&self) -> Option<f64> {
        match self.ridges.as_slice() {
            [first, second, ..] if second.strength > 0.0 => Some(first.strength / second.strength),
            _ => None,
        }
    }

    /// The JSON of issue 6: `{"periodicity_nm":{"mean","variance","relative_spread","definite","uncertainty",
    /// "quantised"},"patch_extent_nm","coherence_nm","order",
    /// "incidence_deg","azimuth_deg",
    /// "peaks":[{"wavelength_nm","angle_deg","period_nm"}],"ridges":[…]}`.
    pub fn to_json(&self) -> serde_json::Value {
        let ridges: Vec<serde_json::Value> = if self.ridges.len() > 1 {
            self.ridges
                .iter()
                .map(|r| {
                    serde_json::json!({"period_nm": r.period_nm, "variance": r.variance,
                        "wavelengths": r.wavelengths, "strength": r.strength})
                })
                .collect()
        } else {
            Vec::new()
        };
        serde_json::json!({
            "periodicity_nm": {"mean": self.periodicity.mean, "variance": self.periodicity.variance,
                "relative_spread": self.periodicity.relative_spread(), "definite": self.is_definite(),
                "uncertainty": self.uncertainty_nm(), "quantised": self.is_quantised()},
            "patch_extent_nm": self.grid.map(|g| g.extent_nm),
            "coherence_nm": self.grid.map(|g| g.coherence_nm),
            "order": self.order,
            "incidence_deg": self.incidence_deg,
            "azimuth_deg": self.azimuth_deg,
            "window_period_nm": self.window_period_nm,
            "peaks": self.peaks.iter().map(|p| serde_json::json!({
                "wavelength_nm": p.wavelength_nm, "angle_deg": p.angle_deg, "period_nm": p.period_nm,
                "reflectance": p.reflectance})).collect::<Vec<_>>(),
            "ridges": ridges,
        })
    }
}

/// Sub-sample offset (in samples, within ±½) of a maximum at `j` by a parabola through the logarithms.
fn refine(row: &[f64], j: usize) -> f64 {
    if j == 0 || j + 1 >= row.len() {
        return 0.0;
    }
    let (a, b, c) = (row[j - 1], row[j], row[j + 1]);
    if a > 0.0 && b > 0.0 && c > 0.0 {
        let (la, lb, lc) = (a.ln(), b.ln(), c.ln());
        let den = la - 2.0 * lb + lc;
        if den < 0.0 {
            return (0.5 * (la - lc) / den).clamp(-0.5, 0.5);
        }
    }
    let den = a - 2.0 * b + c;
    if den < 0.0 {
        (0.5 * (a - c) / den).clamp(-0.5, 0.5)
    } else {
        0.0
    }
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn mean_variance(v: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let n = v.clone().count().max(1) as f64;
    let mean = v.clone().sum::<f64>() / n;
    let var = v.map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
    (mean, var)
}

/// Below this share of the matrix's brightest reflectance (the mirror lobe's) a response is round-off, not light:
/// the sums that cancel where a surface has no period leave ~1e-34 (the blazed grating along its grooves read a
/// "definite" 6517 nm from them). A real order is far above it (a 1 nm sine's first order, 1e-4).
pub const ROUND_OFF_SHARE: f64 = 1e-12;

/// Peak viewing angles, periodicity and ridges of order `setup.order` (thesis Algorithm 6, eq. 5.6).
pub fn analyse(matrix: &ReflectanceMatrix, setup: &BenchSetup) -> Result<BenchResult, LabError> {
    let floor = ROUND_OFF_SHARE * matrix.values.iter().copied().filter(|v| v.is_finite()).fold(0.0, f64::max);
    let m = setup.order as f64;
    let sign = m.signum();
    let q_min = 1.0 / setup.max_period_nm;
    let step = if matrix.angles_deg.len() > 1 { matrix.angles_deg[1] - matrix.angles_deg[0] } else { 1.0 };
    let q = |l: f64, a: f64| setup.frequency(l, a);
    // Step 1: the window's period.
    let d0 = match setup.period_hint_nm {
        Some(d) => {
            if !(d.is_finite() && d > 0.0) {
                return Err(LabError::invalid(format!("period {d} nm must be positive")));
            }
            d
        }
        None => {
            let mut qs: Vec<f64> = Vec::new();
            for (i, &l) in matrix.wavelengths_nm.iter().enumerate() {
                let row = matrix.row(i);
                // The strongest local maximum (the mirror lobe's tail falls monotonically and has none).
                let n = row.len();
                let best = matrix
                    .angles_deg
                    .iter()
                    .enumerate()
                    .filter(|&(j, &a)| {
                        q(l, a) * sign >= q_min && j > 0 && j + 1 < n && row[j] >= row[j - 1] && row[j] > row[j + 1]
                    })
                    .max_by(|x, y| row[x.0].total_cmp(&row[y.0]));
                if let Some((j, &a)) = best {
                    if row[j] > floor {
                        qs.push(q(l, a).abs());
                    }
                }
            }
            if qs.is_empty() {
                return Err(LabError::invalid(format!(
                    "no light on the side of order {} at any wavelength (nothing above {ROUND_OFF_SHARE:e} of the \
                     mirror's reflectance: round-off): the surface has no period along azimuth {:.1}°, or the \
                     viewing angles miss it; `surface info` gives its periods' orientations, and order m > 0 lies \
                     between the mirror direction and the normal",
                    setup.order,
                    setup.azimuth.to_degrees()
                )));
            }
            1.0 / median(&mut qs)
        }
    };
    let q_centre = m / d0;
    let half = 0.5 / d0;
    let in_window = |l: f64, a: f64| {
        let f = q(l, a);
        (f - q_centre).abs() <= half && f * sign >= q_min
    };
    let period_of = |l: f64, a: f64| m * l / (setup.incidence.sin() - a.to_radians().sin());
    let mut peaks = Vec::new();
    let mut candidates: Vec<(usize, Peak)> = Vec::new();
    for (i, &l) in matrix.wavelengths_nm.iter().enumerate() {
        let row = matrix.row(i);
        let inside: Vec<usize> = (0..row.len()).filter(|&j| in_window(l, matrix.angles_deg[j])).collect();
        let Some(&jbest) = inside.iter().max_by(|&&x, &&y| row[x].total_cmp(&row[y])) else { continue };
        let is_interior = |j: usize| {
            j > 0
                && j + 1 < row.len()
                && in_window(l, matrix.angles_deg[j - 1])
                && in_window(l, matrix.angles_deg[j + 1])
        };
        if row[jbest] <= floor || !is_interior(jbest) || row[jbest - 1] > row[jbest] || row[jbest + 1] > row[jbest] {
            continue;
        }
        let make = |j: usize| {
            let a = matrix.angles_deg[j] + refine(row, j) * step;
            Peak { wavelength_nm: l, angle_deg: a, period_nm: period_of(l, a), reflectance: row[j] }
        };
        peaks.push(make(jbest));
        for &j in &inside {
            if is_interior(j) && row[j] >= 0.25 * row[jbest] && row[j] >= row[j - 1] && row[j] > row[j + 1] {
                candidates.push((i, make(j)));
            }
        }
    }
    if peaks.is_empty() {
        return Err(LabError::invalid(format!(
            "order {} has no peak inside the viewing angles {:.2}°…{:.2}° at any wavelength (window period {:.1} nm); \
             widen the angles or give --period",
            setup.order,
            matrix.angles_deg[0],
            matrix.angles_deg[matrix.angles_deg.len() - 1],
            d0
        )));
    }
    let (mean, variance) = mean_variance(peaks.iter().map(|p| p.period_nm));
    let ridges = ridges(candidates, matrix.wavelengths_nm.len());
    Ok(BenchResult {
        order: setup.order,
        incidence_deg: setup.incidence.to_degrees(),
        azimuth_deg: setup.azimuth.to_degrees(),
        peaks,
        periodicity: Periodicity { mean, variance },
        window_period_nm: d0,
        ridges,
        grid: None,
    })
}

/// Groups ridge candidates by period: sorted by period, a relative gap above 1.5 % starts a new group; a group
/// keeps one peak per wavelength (the strongest) and counts as a ridge when seen at ≥ ¼ of the wavelengths.
fn ridges(mut candidates: Vec<(usize, Peak)>, wavelengths: usize) -> Vec<Ridge> {
    candidates.sort_by(|a, b| a.1.period_nm.total_cmp(&b.1.period_nm));
    let mut groups: Vec<Vec<(usize, Peak)>> = Vec::new();
    for c in candidates {
        match groups.last_mut() {
            Some(g) if (c.1.period_nm - g[g.len() - 1].1.period_nm).abs() <= 0.015 * c.1.period_nm.abs() => g.push(c),
            _ => groups.push(vec![c]),
        }
    }
    let mut out: Vec<Ridge> = groups
        .into_iter()
        .filter_map(|g| {
            let mut best: std::collections::BTreeMap<usize, Peak> = std::collections::BTreeMap::new();
            for (i, p) in g {
                let e = best.entry(i).or_insert(p);
                if p.reflectance > e.reflectance {
                    *e = p;
                }
            }
            if (best.len() as f64) < 0.25 * wavelengths as f64 {
                return None;
            }
            let peaks: Vec<Peak> = best.into_values().collect();
            let (mean, var) = mean_variance(peaks.iter().map(|p| p.period_nm));
            let strength = peaks.iter().map(|p| p.reflectance).sum::<f64>() / peaks.len() as f64;
            Some(Ridge { period_nm: mean, variance: var, wavelengths: peaks.len(), strength, peaks })
        })
        .collect();
    out.sort_by(|a, b| b.strength.total_cmp(&a.strength));
    out
}

/// Runs the bench: the matrix and its analysis.
pub fn run(
    evaluator: &dyn Evaluator,
    setup: &BenchSetup,
    progress: Progress,
) -> Result<(ReflectanceMatrix, BenchResult), LabError> {
    let matrix = reflectance_matrix(evaluator, setup, progress)?;
    let result = analyse(&matrix, setup)?;
    Ok((matrix, result))
}

/// The plot of paper Figure 7 / thesis Figure 5.8: a heat map of `R(λ, θ_r)` (normalised to the strongest
/// response away from the mirror direction, which would otherwise swamp it), the measured peak curve, the
/// grating-equation curve for `curve_period_nm`, and one curve per ridge when there are several.
pub fn plot(
    matrix: &ReflectanceMatrix,
    setup: &BenchSetup,
    result: &BenchResult,
    curve_period_nm: f64,
    title: &str,
) -> Result<iridis_plot::RgbImage, LabError> {
    use iridis_plot::{magma, ColorBar, ImagePlot, RgbImage, Series};
    let (nl, na) = (matrix.wavelengths_nm.len(), matrix.angles_deg.len());
    // Normalisation: the maximum outside the mirror's neighbourhood.
    let q_min = 1.0 / setup.max_period_nm;
    let mut vmax = 0.0f64;
    for (i, &l) in matrix.wavelengths_nm.iter().enumerate() {
        for (j, &a) in matrix.angles_deg.iter().enumerate() {
            if setup.frequency(l, a).abs() >= q_min {
                vmax = vmax.max(matrix.values[i * na + j]);
            }
        }
    }
    if vmax <= 0.0 {
        vmax = matrix.values.iter().cloned().fold(1e-300, f64::max);
    }
    // Max-pool the angle axis to at most 600 rows so narrow peaks survive the display's resampling.
    let rows = na.min(600);
    let cols = nl;
    let mut pixels = RgbImage::new(cols as u32, rows as u32);
    for r in 0..rows {
        // Row 0 is the top: the largest angle.
        let (j0, j1) = ((rows - 1 - r) * na / rows, ((rows - r) * na / rows).max((rows - 1 - r) * na / rows + 1));
        for i in 0..cols {
            let v = (j0..j1.min(na)).map(|j| matrix.values[i * na + j]).fold(0.0, f64::max);
            pixels.put(i as u32, r as u32, magma((v / vmax).sqrt()));
        }
    }
    let ls: Vec<f64> = matrix.wavelengths_nm.clone();
    let grating: Vec<(f64, f64)> = ls
        .iter()
        .filter_map(|&l| setup.grating_angle(setup.order as f64, l, curve_period_nm).map(|a| (l, a)))
        .collect();
    let mut g =
        Series::new(format!("grating equation, d = {curve_period_nm:.2} nm"), &[], &[]).with_color([0, 200, 255]);
    g.points = grating;
    let mut overlays = vec![g];
    let mut peak_curve = Series::new(
        format!("peak viewing angle, order {}", setup.order),
        &result.peaks.iter().map(|p| p.wavelength_nm).collect::<Vec<_>>(),
        &result.peaks.iter().map(|p| p.angle_deg).collect::<Vec<_>>(),
    )
    .with_color([255, 255, 255]);
    peak_curve.emphasis = false;
    overlays.push(peak_curve);
    if result.ridges.len() > 1 {
        for (k, r) in result.ridges.iter().enumerate().take(4) {
            let mut s = Series::new(format!("ridge {}: d = {:.1} nm", k + 1, r.period_nm), &[], &[])
                .with_color([[120, 255, 120], [255, 170, 60], [255, 90, 200], [200, 200, 200]][k]);
            s.points = ls
                .iter()
                .filter_map(|&l| setup.grating_angle(setup.order as f64, l, r.period_nm).map(|a| (l, a)))
                .collect();
            overlays.push(s);
        }
    }
    let img = ImagePlot {
        title: title.to_string(),
        x_label: "wavelength λ (nm)".into(),
        y_label: "viewing angle θr (deg)".into(),
        x_range: (ls[0], ls[ls.len() - 1]),
        y_range: (matrix.angles_deg[0], matrix.angles_deg[na - 1]),
        pixels: &pixels,
        overlays,
        colorbar: Some(ColorBar { label: "√(R / R_max off mirror)".into(), min: 0.0, max: 1.0, map: magma }),
        size: (900, 640),
    }
    .render()?;
    Ok(img)
}
