//! The rigorous BRDF of a periodic surface (`brdf eval`, `brdf-map`, `testbench` with `--method rigorous`):
//! the lobes of the scalar model's window-shaped BRDF (the light's coherence window around each order of the
//! unit cell's periodic extension), each scaled so that it carries the efficiency Maxwell's equations give its
//! order (the C-method, `iridis_rigorous`), per polarisation. docs/PHYSICS.md, "The rigorous BRDF".
//!
//! The unit cell is the SURFACE itself (a generated grating, one period of a profile) or, with
//! `--unit-cell auto`, a scan's dominant period with its profile averaged along the ridges
//! ([`crate::grating::averaged_unit_cell`]), a 1-D grating turned to the scan's orientation.

use std::sync::{Arc, Mutex};

use anyhow::{bail, Result};
use iridis_diffraction::geometry::{dot, FresnelConvention, FresnelSource, Shading, Vec3};
use iridis_diffraction::grating::{Efficiency, Lines, LobeEnergy, LobeScaled, Normalisation, ScaledRow, UnitCell};
use iridis_diffraction::{DiffractionError, Evaluator, Patch, Reference};
use serde_json::{json, Value};

use crate::grating::{averaged_unit_cell_at, material_fresnel, RigorousCell, DEFAULT_MATERIAL};
use crate::model::{spectral_setup, taylor_terms_of_unit_cell, ModelOptions};
use crate::report::{with_progress, Report};
use crate::surface::{Source, SurfaceOptions};

/// The largest `L/λ` (a period over the shortest wavelength) the rigorous BRDF takes a unit cell of: 40 for a
/// 1-D profile (81 propagating orders; the solver's default limit is 120 orders each side), 4 per axis for a
/// crossed grating (limit 8).
pub const MAX_PERIOD_OVER_WAVELENGTH: [f64; 2] = [40.0, 4.0];

/// Below this energy (a fraction of the light) an order's Kirchhoff lobe is taken as empty: it cannot carry
/// the rigorous efficiency, which is then counted as missed.
const EMPTY_LOBE: f64 = 1e-12;

/// The unit cell of a rigorous BRDF.
#[derive(Debug, Clone)]
pub struct CellChoice {
    /// One period (the cell's frame: an averaged cell runs along x).
    pub patch: Patch,
    /// With `--unit-cell auto`: the period (nm) and the orientation of its grating vector (degrees from +x).
    pub averaged: Option<(f64, f64)>,
    /// The extent of the SURFACE the cell came from along the cell's grating vector (nm): what the period is
    /// known to (half a DFT step of the scan).
    pub scan_extent_nm: f64,
}

impl CellChoice {
    /// The rotation (rad) from the scan's frame to the cell's.
    pub fn rotation_rad(&self) -> f64 {
        self.averaged.map_or(0.0, |(_, phi)| phi.to_radians())
    }

    /// What the cell is, in words.
    pub fn describe(&self) -> String {
        let (lx, ly) = self.patch.extent();
        match self.averaged {
            Some((d, phi)) => format!(
                "the scan's dominant period, {d:.1} nm along {phi:.1}°, its profile averaged along the ridges (1-D)"
            ),
            None => format!("the SURFACE as one unit cell, {lx:.1} × {ly:.1} nm"),
        }
    }
}

/// The unit cell of SURFACE for the rigorous BRDF: the scan's averaged dominant period with `auto`, else the
/// whole patch, refused (naming `--unit-cell auto`) where it is too long a period for the solver.
pub fn unit_cell(
    source: &Source,
    surface: &SurfaceOptions,
    auto: bool,
    lambda_min_nm: f64,
    report: &dyn Report,
) -> Result<CellChoice> {
    let patch = source.patch(surface, report)?;
    if auto {
        let (cell, d, phi) = crate::grating::auto_unit_cell(&patch, source.name(), report)?;
        let extent = patch.extent_along(phi.to_radians());
        return Ok(CellChoice { patch: cell, averaged: Some((d, phi)), scan_extent_nm: extent });
    }
    let lines = Lines::of(&patch);
    let (lx, ly) = patch.extent();
    let (longest, limit) = match lines {
        Lines::AlongX => (lx, MAX_PERIOD_OVER_WAVELENGTH[0]),
        Lines::AlongY => (ly, MAX_PERIOD_OVER_WAVELENGTH[0]),
        Lines::Crossed => (lx.max(ly), MAX_PERIOD_OVER_WAVELENGTH[1]),
    };
    let ratio = longest / lambda_min_nm;
    if ratio > limit {
        bail!(
            "the rigorous method takes SURFACE as one unit cell of a grating, and {} is {:.1} µm across ({}): at \
             {lambda_min_nm:.0} nm that period has about {} propagating orders each side, more than the rigorous \
             BRDF takes ({} at most: it solves the cell at every wavelength of its grid, where `iridis grating \
             --method rigorous` solves few); give --unit-cell auto (the scan's dominant period, its profile averaged along the ridges) \
             or a SURFACE of one period (e.g. 'builtin:sine?size=1100nm&pixel=10nm')",
            source.name(),
            longest / 1000.0,
            if lines == Lines::Crossed { "a crossed grating" } else { "a 1-D grating" },
            ratio.floor(),
            limit
        );
    }
    let extent = if lines == Lines::AlongY { ly } else { lx };
    Ok(CellChoice { patch, averaged: None, scan_extent_nm: extent })
}

/// The rigorous efficiencies as the lobes' target ([`LobeEnergy`]), solved once per (λ, ω_i) and logged.
pub struct RigorousLobes {
    cell: RigorousCell,
    metal: Arc<iridis_lab::laser::MetalFresnel>,
    /// The Fresnel factor of the Kirchhoff lobes being scaled (what each carries before the scaling).
    lobe_fresnel: Arc<dyn FresnelSource>,
    log: Mutex<Vec<SolveLog>>,
    failures: Mutex<Vec<String>>,
}

/// What one solve said about itself.
#[derive(Debug, Clone, Copy)]
struct SolveLog {
    wavelength_nm: f64,
    estimated_error: f64,
    met: bool,
    orders: usize,
    reflected: f64,
    missed: f64,
}

impl std::fmt::Debug for RigorousLobes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RigorousLobes").field("metal", &self.metal.describe()).finish()
    }
}

impl LobeEnergy for RigorousLobes {
    fn name(&self) -> &'static str {
        "rigorous"
    }

    fn scale(&self, cell: &UnitCell, wavelength_nm: f64, wi: Vec3) -> Result<ScaledRow, DiffractionError> {
        let mut row = cell.row(wi, wavelength_nm, Normalisation::Kirchhoff)?;
        let solution = match self.cell.solve(wavelength_nm, wi, self.metal.index(wavelength_nm)) {
            Ok(s) => s,
            Err(e) => {
                // Kept for the front end: a lobe without its factor must not pass for a rigorous one.
                let text = format!("{e:#}");
                if let Ok(mut f) = self.failures.lock() {
                    f.push(text.clone());
                }
                return Err(DiffractionError::Invalid(text));
            }
        };
        let mut shares = vec![[1.0, 1.0]; row.len()];
        let mut carried = 0.0;
        for b in 0..row.len() {
            let wr = row.exit(b);
            // The order leaving along this channel's direction (frames and sign conventions aside).
            let eta = solution
                .orders
                .iter()
                .find(|o| {
                    let d = iridis_diffraction::geometry::direction(o.theta_deg.to_radians(), o.phi_deg.to_radians());
                    (0..3).all(|c| (d[c] - wr[c]).abs() < 1e-6)
                })
                .map_or(Efficiency::default(), |o| o.efficiency);
            let h = [wi[0] + wr[0], wi[1] + wr[1], wi[2] + wr[2]];
            let cos_h = dot(wi, h) / dot(h, h).sqrt();
            // The Kirchhoff lobe carries raw · R(θ_h) (docs/PHYSICS.md, "Order efficiencies").
            let lobe = row.raw[b] * self.lobe_fresnel.reflectance(wavelength_nm, cos_h);
            if lobe > EMPTY_LOBE {
                row.factor[b] = eta.unpolarized / lobe;
                carried += eta.unpolarized;
            } else {
                row.factor[b] = 0.0;
            }
            if eta.unpolarized > 0.0 {
                shares[b] = [eta.te / eta.unpolarized, eta.tm / eta.unpolarized];
            }
        }
        let c = &solution.convergence;
        let reflected = solution.reflected_total.unpolarized;
        if let Ok(mut log) = self.log.lock() {
            log.push(SolveLog {
                wavelength_nm,
                estimated_error: c["estimated_error"].as_f64().unwrap_or(f64::NAN),
                met: c["met"] == json!(true),
                orders: c["orders"][0].as_u64().unwrap_or(0) as usize,
                reflected,
                missed: (reflected - carried).max(0.0),
            });
        }
        Ok(ScaledRow { row, shares: Some(shares) })
    }
}

/// What the rigorous BRDF rests on, for the person (text) and `--json` (keys in docs/json.md).
#[derive(Debug, Clone)]
pub struct RigorousSummary {
    pub material: String,
    pub unit_cell: String,
    pub period_nm: (f64, f64),
    pub orientation_deg: Option<f64>,
    /// Solves so far (one per wavelength and light direction).
    pub solves: usize,
    /// The largest estimated relative error of any solve (the solver's convergence estimate).
    pub worst_estimated_error: f64,
    /// Wavelengths (nm) where the solver reached its order limit before the tolerance.
    pub unmet_nm: Vec<f64>,
    /// The largest truncation `M` (orders −M…M) any solve used.
    pub max_orders: usize,
    /// The largest share of the light in an order whose Kirchhoff lobe is empty (it cannot be shown).
    pub missed: f64,
    /// The hemispherical reflectance's range over the solves (unpolarised).
    pub reflected_range: (f64, f64),
}

impl RigorousSummary {
    /// One line of assumptions.
    pub fn sentence(&self) -> String {
        format!(
            "rigorous BRDF: lobes shaped by the light's coherence window around each order, each carrying the \
             order's C-method efficiency (Maxwell's equations; TE/TM apart, unpolarised their mean); material {}; \
             unit cell {}; {} solve(s), orders up to ±{}, estimated error ≤ {:.1e} (relative){}; hemispherical \
             reflectance {:.2}–{:.2} % (unpolarised)",
            self.material,
            self.unit_cell,
            self.solves,
            self.max_orders,
            self.worst_estimated_error,
            if self.unmet_nm.is_empty() { String::new() } else { " — tolerance not met at some wavelengths".into() },
            100.0 * self.reflected_range.0,
            100.0 * self.reflected_range.1,
        )
    }

    pub fn to_json(&self) -> Value {
        json!({
            "method": "rigorous (C-method efficiencies on the coherence window's lobes)",
            "material": self.material,
            "unit_cell": self.unit_cell,
            "period_nm": [self.period_nm.0, self.period_nm.1],
            "orientation_deg": self.orientation_deg,
            "polarisation": "s = TE, p = TM of the incident light with respect to its plane of incidence; each order's efficiency sums both outgoing polarisations; unpolarised the mean",
            "solves": self.solves,
            "max_orders": self.max_orders,
            "worst_estimated_error": self.worst_estimated_error,
            "tolerance_unmet_nm": self.unmet_nm,
            "missed_efficiency": self.missed,
            "reflected_total_range": [self.reflected_range.0, self.reflected_range.1],
        })
    }
}

/// The rigorous BRDF: [`LobeScaled`] with [`RigorousLobes`], in the scan's frame.
pub struct RigorousBrdf {
    scaled: LobeScaled,
    lobes: Arc<RigorousLobes>,
    cell: CellChoice,
    material: String,
}

impl std::fmt::Debug for RigorousBrdf {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RigorousBrdf").field("material", &self.material).field("cell", &self.cell.describe()).finish()
    }
}

/// Turns a direction of the scan's frame into the cell's (by −`angle` about the normal).
fn to_cell(v: Vec3, angle: f64) -> Vec3 {
    if angle == 0.0 {
        return v;
    }
    let (s, c) = (-angle).sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]
}

impl RigorousBrdf {
    /// The rigorous BRDF of `cell` on `material` (a stack's medium: `gold`, `keratin`, `n=1.5`, …; default
    /// [`DEFAULT_MATERIAL`]) with the model's window (coherence) and wavelength grid.
    pub fn new(cell: CellChoice, material: Option<&str>, model: &ModelOptions, report: &dyn Report) -> Result<Self> {
        let spectral = spectral_setup(model, report)?;
        let w = spectral.wavelengths();
        let (from, to) = (w.first().copied().unwrap_or(380.0), w.last().copied().unwrap_or(780.0));
        let medium = material.unwrap_or(DEFAULT_MATERIAL);
        let metal = material_fresnel(medium, from, to)?;
        let rigorous = RigorousCell::new(&cell.patch, Lines::of(&cell.patch), report);
        let terms = Arc::new(taylor_terms_of_unit_cell(&cell.patch, model, report)?);
        // No shadowing: each lobe's energy is set by Maxwell's equations, the window gives its shape only.
        let shading = Shading { fresnel: metal.clone(), shadowing: false, convention: FresnelConvention::Physical };
        let inner = Reference { terms, shading, spectral: spectral.clone() };
        let lobes = Arc::new(RigorousLobes {
            cell: rigorous,
            metal: metal.clone(),
            lobe_fresnel: metal,
            log: Mutex::new(Vec::new()),
            failures: Mutex::new(Vec::new()),
        });
        let scaled = LobeScaled::new(Box::new(inner), &cell.patch, spectral, lobes.clone())?;
        Ok(Self { scaled, lobes, cell, material: medium.to_string() })
    }

    /// Solves Maxwell's equations for light from `wi` (scan's frame) at every wavelength, in parallel, with
    /// progress: what a map or a test bench does before asking many views.
    pub fn prepare(&self, wi: Vec3, report: &dyn Report) -> Result<()> {
        let steps = self.scaled.preparation_steps() as u64;
        let wi = to_cell(wi, self.cell.rotation_rad());
        with_progress(report, steps, "rigorous orders", |p| self.scaled.prepare(wi, p))?;
        if let Some(err) = self.failures().first() {
            bail!("the rigorous solver failed: {err}");
        }
        let s = self.summary();
        if !s.unmet_nm.is_empty() {
            report.warn(&format!(
                "the rigorous solver reached its order limit before the tolerance at {} wavelength(s) ({:.0}–{:.0} \
                 nm): the lobes there carry the estimated error {:.1e}",
                s.unmet_nm.len(),
                s.unmet_nm.first().copied().unwrap_or(0.0),
                s.unmet_nm.last().copied().unwrap_or(0.0),
                s.worst_estimated_error
            ));
        }
        if s.missed > 1e-4 {
            report.warn(&format!(
                "up to {:.2} % of the light leaves in orders whose scalar lobe is empty (a zero of the Kirchhoff \
                 amplitude at the order's centre): the map cannot show it",
                100.0 * s.missed
            ));
        }
        Ok(())
    }

    /// [`RigorousBrdf::summary`] of an evaluator that is one (a point query's record of what it rests on).
    pub fn summary_of(e: &dyn Evaluator) -> Option<RigorousSummary> {
        e.as_any().downcast_ref::<RigorousBrdf>().map(RigorousBrdf::summary)
    }

    /// The assumptions and the solver's convergence so far.
    pub fn summary(&self) -> RigorousSummary {
        let log = self.lobes.log.lock().map(|l| l.clone()).unwrap_or_default();
        let mut unmet: Vec<f64> = log.iter().filter(|s| !s.met).map(|s| s.wavelength_nm).collect();
        unmet.sort_by(|a, b| a.total_cmp(b));
        unmet.dedup();
        RigorousSummary {
            material: self.material.clone(),
            unit_cell: self.cell.describe(),
            period_nm: self.cell.patch.extent(),
            orientation_deg: self.cell.averaged.map(|(_, phi)| phi),
            solves: log.len(),
            worst_estimated_error: log.iter().map(|s| s.estimated_error).fold(0.0, f64::max),
            unmet_nm: unmet,
            max_orders: log.iter().map(|s| s.orders).max().unwrap_or(0),
            missed: log.iter().map(|s| s.missed).fold(0.0, f64::max),
            reflected_range: log
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| (a.min(s.reflected), b.max(s.reflected))),
        }
    }

    /// The solver's failures so far (a view whose lobes could not be scaled; none after a successful
    /// [`RigorousBrdf::prepare`] for the light asked).
    pub fn failures(&self) -> Vec<String> {
        self.lobes.failures.lock().map(|f| f.clone()).unwrap_or_default()
    }

    /// The unit cell.
    pub fn cell(&self) -> &CellChoice {
        &self.cell
    }
}

impl Evaluator for RigorousBrdf {
    fn name(&self) -> &'static str {
        "rigorous"
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        let a = self.cell.rotation_rad();
        self.scaled.reflectance(wavelength_nm, to_cell(wi, a), to_cell(wr, a))
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> iridis_color::Xyz {
        let a = self.cell.rotation_rad();
        self.scaled.xyz(to_cell(wi, a), to_cell(wr, a))
    }
    fn shading(&self) -> Option<&Shading> {
        self.scaled.shading()
    }
    fn radiometric_gain(&self, wavelength_nm: f64) -> Option<f64> {
        self.scaled.radiometric_gain(wavelength_nm)
    }
    fn coherence_nm(&self) -> Option<f64> {
        self.scaled.coherence_nm()
    }
    fn polarisation(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<[f64; 2]> {
        let a = self.cell.rotation_rad();
        self.scaled.polarisation(wavelength_nm, to_cell(wi, a), to_cell(wr, a))
    }
}

/// The rigorous BRDF of SURFACE for the model's options (`material`, `unit_cell_auto`, the window and
/// wavelength grid).
pub fn evaluator(
    source: &Source,
    model: &ModelOptions,
    surface: &SurfaceOptions,
    report: &dyn Report,
) -> Result<RigorousBrdf> {
    // Its warnings are said once, by the evaluator below.
    let spectral = spectral_setup(model, &crate::report::Quiet)?;
    let from = spectral.wavelengths().first().copied().unwrap_or(380.0);
    let cell = unit_cell(source, surface, model.unit_cell_auto, from, report)?;
    RigorousBrdf::new(cell, model.material.as_deref(), model, report)
}

/// The share of a scan's height variance its dominant period must carry for `brdf eval` to state the scalar
/// model's error on it (built-ins: Elaphe 0.62, the blazed grating 0.61, Xenopeltis 0.042; the Gaussian random
/// surface 0.011, a patch of one period 0).
pub const MIN_PERIOD_SHARE: f64 = 0.02;

/// The medium the scalar model's error on a scan is estimated over when none is given: keratin, what snake and
/// insect cuticle is made of (as `iridis report`).
pub const SCAN_MATERIAL: &str = "keratin";

/// How far the scalar model is from Maxwell's equations on a scan's averaged dominant period, for one light
/// (what `brdf eval` says with a Kirchhoff method).
#[derive(Debug, Clone)]
pub struct ScanScalarError {
    pub error: crate::grating::ScalarError,
    /// The dominant period (nm) and its orientation (degrees).
    pub period_nm: f64,
    pub orientation_deg: f64,
    pub material: String,
    /// The averaged profile's height variance over the scan's: how much of the relief the check covers (the
    /// Xenopeltis-like skin, whose grains each have their own spacings, keeps about 1 %; Elaphe's rows 69 %).
    pub variance_share: f64,
}

/// Below this share of the scan's height variance in the averaged profile, the scalar-error sentence says that
/// the rest of the relief is not in the check.
pub const CHECK_COVERS_LITTLE: f64 = 0.25;

impl ScanScalarError {
    /// One sentence with the numbers.
    pub fn sentence(&self) -> String {
        // Orders of the averaged 1-D cell: m counts the dominant period's orders.
        let at = self.error.worst_at.map_or(String::new(), |(l, m, _)| format!(" (order {m} at {l:.0} nm)"));
        let share = 100.0 * self.variance_share;
        let rest = if self.variance_share < CHECK_COVERS_LITTLE {
            format!("; the other {:.0} % of the relief is not in this check", 100.0 - share)
        } else {
            String::new()
        };
        format!(
            "the scalar (Kirchhoff) model behind this BRDF is off by up to {:.1} % in an order's efficiency{at}{} \
             against Maxwell's equations on this scan's dominant period ({:.1} nm along {:.1}°, its profile averaged \
             along the ridges, {share:.1} % of the scan's height variance, on {}, this light, unpolarised, \
             380–780 nm){rest}",
            100.0 * self.error.worst.unpolarized,
            match self.error.delta_e_diffracted {
                Some(d) => format!(" and by ΔE00 {d:.2} in the colour of the diffracted light"),
                None => String::new(),
            },
            self.period_nm,
            self.orientation_deg,
            self.material
        )
    }

    /// `brdf eval --json`'s `scalar_error` (keys in docs/json.md).
    pub fn to_json(&self) -> Value {
        let e = &self.error;
        json!({
            "period_nm": self.period_nm,
            "orientation_deg": self.orientation_deg,
            "height_variance_share": self.variance_share,
            "units": "relative errors, efficiencies and shares are fractions (0.2 = 20 %)",
            "material": self.material,
            "wavelength_nm": [380.0, 780.0, 10.0],
            "worst_relative_error": {"te": e.worst.te, "tm": e.worst.tm, "unpolarized": e.worst.unpolarized},
            "worst_at": e.worst_at.map(|(l, m, _)| json!({"wavelength_nm": l, "order": m})),
            "total_relative_error": e.total,
            "delta_e00_diffracted": e.delta_e_diffracted,
            "delta_e00_specular": e.delta_e_specular,
            "above_threshold": e.above_threshold(),
            "threshold": {"relative": crate::grating::SCALAR_WARN_RELATIVE, "delta_e00": crate::grating::SCALAR_WARN_DELTA_E},
        })
    }
}

/// The scalar model's error on SURFACE's averaged dominant period for light `wi` (scan's frame), 380–780 nm
/// at 10 nm (what the colours need), over `material` (default [`SCAN_MATERIAL`]); `None` for a surface
/// without a dominant period.
pub fn scalar_error_of_scan(
    source: &Source,
    surface: &SurfaceOptions,
    wi: Vec3,
    material: Option<&str>,
    report: &dyn Report,
) -> Result<Option<ScanScalarError>> {
    use crate::grating::{grating, scalar_error, GratingMethod, GratingOptions};
    let patch = source.patch(surface, &crate::report::Quiet)?;
    // A scan with a dominant period (`surface::is_dominant`: a patch of one period, or a random surface, has none
    // worth averaging) that carries a share of the height variance worth checking.
    let Some(peak) = crate::surface::dominant_period(&patch).ok().filter(|p| p.power >= MIN_PERIOD_SHARE) else {
        return Ok(None);
    };
    let Some((cell, d, phi)) = averaged_unit_cell_at(&patch, &peak) else { return Ok(None) };
    let variance_share = crate::unit_cell::variance_share(&cell, &patch);
    let material = material.unwrap_or(SCAN_MATERIAL).to_string();
    let cell = Source::Patch { patch: cell, name: format!("{} (averaged period)", source.name()) };
    let opts = GratingOptions {
        light: to_cell(wi, phi.to_radians()),
        wavelengths_nm: iridis_color::spectrum::uniform_grid(380.0, 780.0, 10.0)?,
        material: Some(material.clone()),
        ..Default::default()
    };
    let quiet = crate::report::Quiet;
    let k = grating(&cell, surface, &GratingOptions { method: GratingMethod::Kirchhoff, ..opts.clone() }, &quiet)?;
    let r = crate::report::with_step(report, "the scalar model's error (rigorous orders)", || {
        grating(&cell, surface, &GratingOptions { method: GratingMethod::Rigorous, ..opts }, &quiet)
    })?;
    Ok(Some(ScanScalarError {
        error: scalar_error(&k, &r),
        period_nm: d,
        orientation_deg: phi,
        material,
        variance_share,
    }))
}
