//! Order efficiencies of a SURFACE taken as one unit cell of a grating (`iridis grating`, Python's
//! `iridis.diffraction.grating`): the fraction of the light in each propagating order, per polarisation, with
//! what instruments measure — the hemispherical reflectance (an integrating sphere) and the reflectance a
//! detector of given acceptance sees (a goniometer, a fibre spectrometer) — over a wavelength range.

use std::sync::Arc;

use anyhow::{bail, Context, Result};
use iridis_diffraction::geometry::{dot, FresnelSource, Vec3};
use iridis_diffraction::grating::{Efficiency, GratingAnswer, Lines, Normalisation, OrderEfficiency, UnitCell};
use rayon::prelude::*;
use serde_json::{json, Value};

use crate::report::{with_progress, Report};
use crate::surface::{Source, SurfaceOptions};

/// The medium under the relief when none is given (`--material`): glass-like, `n = 1.5`.
pub const DEFAULT_MATERIAL: &str = "n=1.5";

/// The model behind the efficiencies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GratingMethod {
    /// Stam's scalar (Kirchhoff) model, the one iridis' BRDFs use (`iridis_diffraction::grating`).
    Kirchhoff,
    /// Maxwell's equations solved by the C-method (`iridis_rigorous`, docs/rigorous.md): TE and TM apart,
    /// reflected and transmitted orders, converged to a stated tolerance.
    Rigorous,
}

impl GratingMethod {
    pub fn name(self) -> &'static str {
        match self {
            GratingMethod::Kirchhoff => "kirchhoff",
            GratingMethod::Rigorous => "rigorous",
        }
    }
}

impl std::str::FromStr for GratingMethod {
    type Err = anyhow::Error;
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "kirchhoff" | "scalar" => Ok(GratingMethod::Kirchhoff),
            "rigorous" | "c-method" => Ok(GratingMethod::Rigorous),
            other => bail!(
                "--method '{other}': expected kirchhoff (Stam's scalar model) or rigorous (Maxwell's equations, the \
                 C-method)"
            ),
        }
    }
}

/// The orders at one wavelength, whichever method computed them.
#[derive(Debug, Clone)]
pub struct OrdersAt {
    pub wavelength_nm: f64,
    /// Reflected propagating orders.
    pub orders: Vec<OrderEfficiency>,
    pub reflected_total: Efficiency,
    /// Transmitted propagating orders (rigorous, transparent substrate; empty otherwise).
    pub transmitted_orders: Vec<OrderEfficiency>,
    /// `None` for the scalar model, which has no transmitted field.
    pub transmitted_total: Option<Efficiency>,
    /// What the answer rests on (method-specific keys, docs/json.md).
    pub convergence: Value,
    /// Reflected orders below [`GratingOptions::orders_above`], counted in the totals but not listed.
    pub unlisted: usize,
}

impl OrdersAt {
    /// The orders' azimuths turned by `deg` degrees (from a cell's frame back to the scan's).
    fn rotated(mut self, deg: f64) -> Self {
        for o in self.orders.iter_mut().chain(self.transmitted_orders.iter_mut()) {
            if o.theta_deg > 1e-12 {
                o.phi_deg = (o.phi_deg + deg).rem_euclid(360.0);
            }
        }
        self
    }

    fn kirchhoff(a: GratingAnswer, taylor_terms: usize) -> Self {
        let convergence = json!({"wavelength_nm": a.wavelength_nm, "taylor_terms": taylor_terms,
            "taylor_remainder_bound": iridis_diffraction::grating::TAYLOR_EPSILON,
            "channels": a.channels, "normalisation": a.normalisation,
            "normalisation_residual": a.normalisation_residual, "kirchhoff_sum": a.kirchhoff_sum});
        OrdersAt {
            wavelength_nm: a.wavelength_nm,
            orders: a.orders,
            reflected_total: a.reflected_total,
            transmitted_orders: Vec::new(),
            transmitted_total: None,
            convergence,
            unlisted: 0,
        }
    }

    /// Keeps the orders `keep` says (the mirror order always), counting the others.
    fn listing(mut self, keep: impl Fn(&OrderEfficiency) -> bool) -> Self {
        let before = self.orders.len();
        self.orders.retain(|o| (o.m, o.n) == (0, 0) || keep(o));
        self.orders.shrink_to_fit();
        self.unlisted += before - self.orders.len();
        self
    }

    /// A rigorous solution in the scalar model's terms, rotated back by `rotation` (rad) where the profile
    /// was taken along another axis than x.
    fn rigorous(s: iridis_rigorous::Solution, rotation: f64, along_y: bool) -> Self {
        // The same three numbers in the two crates' types (iridis-rigorous depends on no other iridis crate).
        let e = |x: iridis_rigorous::Efficiency| Efficiency { te: x.te, tm: x.tm, unpolarized: x.unpolarized };
        let map = |o: &iridis_rigorous::Order| OrderEfficiency {
            wavelength_nm: s.wavelength_nm,
            m: if along_y { 0 } else { o.m as i64 },
            n: if along_y { o.m as i64 } else { o.n as i64 },
            theta_deg: o.theta_deg,
            phi_deg: if o.theta_deg.abs() < 1e-12 {
                0.0
            } else {
                (o.phi_deg + rotation.to_degrees()).rem_euclid(360.0)
            },
            efficiency: e(o.efficiency),
        };
        let mut orders: Vec<OrderEfficiency> = s.orders.iter().map(map).collect();
        orders.sort_by_key(|o| (o.m, o.n));
        let mut transmitted: Vec<OrderEfficiency> = s.transmitted_orders.iter().map(map).collect();
        transmitted.sort_by_key(|o| (o.m, o.n));
        let transparent = s.substrate_index[1] == 0.0;
        let mut convergence = serde_json::to_value(&s.convergence).unwrap_or_default();
        convergence["wavelength_nm"] = json!(s.wavelength_nm);
        if error_not_estimated(&convergence) {
            // One truncation compared with itself (5.6e-16): no estimate, and none given to a script, in the
            // history's last step either.
            convergence["estimated_error"] = Value::Null;
            if let Some(last) = convergence["history"].as_array_mut().and_then(|h| h.last_mut()) {
                last["change"] = Value::Null;
            }
        }
        if along_y {
            // The solver took the column as its x: its repeats along "x" are the cell's along y.
            let [kx, ky] = s.convergence.cell_repeats;
            convergence["cell_repeats"] = json!([ky, kx]);
        }
        OrdersAt {
            wavelength_nm: s.wavelength_nm,
            orders,
            reflected_total: e(s.reflected_total),
            transmitted_orders: transmitted,
            transmitted_total: transparent.then(|| e(s.transmitted_total)),
            convergence,
            unlisted: 0,
        }
    }
}

/// A detector looking at the sample: its axis and the half-angle of its acceptance cone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Detector {
    /// Unit vector from the sample towards the detector.
    pub direction: Vec3,
    /// Half-angle of the acceptance cone (rad).
    pub acceptance_rad: f64,
}

impl Detector {
    /// The half-angle of the acceptance cone when none is given (`--acceptance`).
    pub const DEFAULT_ACCEPTANCE_DEG: f64 = 2.0;
}

/// What `iridis grating` asks.
#[derive(Debug, Clone)]
pub struct GratingOptions {
    pub method: GratingMethod,
    /// Light direction (towards the light), unit vector above the surface.
    pub light: Vec3,
    /// Wavelengths (nm).
    pub wavelengths_nm: Vec<f64>,
    /// The medium below the relief, as a stack's medium is written: a library name (`gold`, `keratin`),
    /// `n=1.5`, `n=0.2+3.4i` or `file:PATH`; its exact Fresnel reflectances per polarisation. Default `n=1.5`.
    pub material: Option<String>,
    /// Instead of a material, any `--fresnel` source (`schlick:1.5`, `index:…`, `stack:…`).
    pub fresnel: Option<String>,
    /// How the scalar model's channel matrix is normalised (`None`: [`Normalisation::Energy`]); refused with
    /// the rigorous method, whose efficiencies come from Maxwell's equations.
    pub normalisation: Option<Normalisation>,
    pub detector: Option<Detector>,
    /// Take the scan's dominant period as the unit cell, its profile averaged along the ridges, instead of
    /// the whole patch.
    pub unit_cell_auto: bool,
    /// List only the orders of at least this unpolarised efficiency (with the mirror order and those inside
    /// the detector's cone); the totals and colours still count every order. At most `1/orders_above` orders
    /// a wavelength are then kept, where a large scan as one unit cell has hundreds of thousands. 0: all.
    pub orders_above: f64,
}

impl Default for GratingOptions {
    fn default() -> Self {
        Self {
            method: GratingMethod::Kirchhoff,
            light: [0.0, 0.0, 1.0],
            wavelengths_nm: vec![550.0],
            material: None,
            fresnel: None,
            normalisation: None,
            detector: None,
            unit_cell_auto: false,
            orders_above: 0.0,
        }
    }
}

/// The answer: the unit cell, the model and its assumptions, and the orders at each wavelength.
#[derive(Debug, Clone)]
pub struct Grating {
    pub surface: String,
    pub method: GratingMethod,
    pub periods_nm: (f64, f64),
    pub samples: (usize, usize),
    pub lines: Lines,
    /// What reflects: the material or Fresnel source, described.
    pub reflector: String,
    /// Whether the reflector tells TE from TM (Schlick's approximation does not).
    pub polarised: bool,
    pub normalisation: Normalisation,
    /// Taylor terms `N` of the Kirchhoff method's cell; `None` with the rigorous method.
    pub taylor_terms: Option<usize>,
    pub light: Vec3,
    pub detector: Option<Detector>,
    /// With `--unit-cell auto`: the period (nm) and the orientation of its grating vector (degrees from +x)
    /// the cell was averaged along.
    pub averaged: Option<(f64, f64)>,
    /// How the patch, taken whole as the cell, holds its strongest period; `None` with `--unit-cell auto` or
    /// where the patch has no such period.
    pub period_fit: Option<PeriodFit>,
    /// [`GratingOptions::orders_above`].
    pub orders_above: f64,
    pub answers: Vec<OrdersAt>,
}

/// A scan's dominant period as a 1-D unit cell: the heights binned by their phase `(x cos φ + y sin φ)/d mod 1`
/// along the grating vector of the strongest period `d` (what `iridis surface info` finds) and averaged in
/// each bin, i.e. the profile averaged along the ridges. Returns the cell (every row the same, along x), `d`
/// and `φ` (degrees); `None` for a scan without a dominant period.
pub fn averaged_unit_cell(patch: &iridis_diffraction::Patch) -> Option<(iridis_diffraction::Patch, f64, f64)> {
    averaged_unit_cell_at(patch, &crate::surface::dominant_period(patch).ok()?)
}

/// The fewest pixels a period may span for [`averaged_unit_cell`] to take its profile: a 1100 nm sine at 500 nm
/// pixels (2.2 a period) was read as a 1000 nm period of a hundredth of its first order.
pub const MIN_PIXELS_PER_PERIOD: f64 = 4.0;

/// [`averaged_unit_cell`] along a period already found (`peak`), for a caller that has looked at it first;
/// `None` where the period spans fewer than [`MIN_PIXELS_PER_PERIOD`] pixels.
pub fn averaged_unit_cell_at(
    patch: &iridis_diffraction::Patch,
    peak: &iridis_surface::Peak,
) -> Option<(iridis_diffraction::Patch, f64, f64)> {
    let d = peak.period_nm;
    let pixel = patch.dx.min(patch.dy);
    if d < MIN_PIXELS_PER_PERIOD * pixel {
        return None;
    }
    // A sample per pixel along the grating vector, at least 32 and at most 256, and no more than the samples'
    // phases fill (a bin between them would be interpolated).
    let bins = ((d / pixel).round() as usize).clamp(32, 256);
    let row = crate::unit_cell::averaged_profile_filled(patch, d, peak.orientation_deg, bins);
    let bins = row.len();
    let heights: Vec<f64> = row.iter().chain(&row).copied().collect();
    let cell = iridis_diffraction::Patch::from_row_major(2, bins, d / bins as f64, d / bins as f64, &heights).ok()?;
    Some((cell, d, peak.orientation_deg))
}

/// How a patch of `extent_nm` taken as one unit cell holds a period `period_nm` whose grating vector points
/// `orientation_deg` from +x: the periods across it along x and y, and the share of each of the period's orders
/// that lands in the nearest of the cell's orders, `sinc²(δx) sinc²(δy)` with `δ` the periods' distance to a
/// whole number (`sinc x = sin πx/(πx)`: the cell's Fourier coefficient of a plane wave cut at its edges). 1 where
/// the period tiles the cell; test: a shallow sine's orders (`crates/api/tests/unit_grating.rs`).
pub fn period_fit(extent_nm: (f64, f64), period_nm: f64, orientation_deg: f64) -> (f64, f64, f64) {
    let phi = orientation_deg.to_radians();
    let (along_x, along_y) = (extent_nm.0 * phi.cos().abs() / period_nm, extent_nm.1 * phi.sin().abs() / period_nm);
    let sinc2 = |cycles: f64| {
        let d = std::f64::consts::PI * (cycles - cycles.round());
        if d.abs() < 1e-12 {
            1.0
        } else {
            (d.sin() / d).powi(2)
        }
    };
    (along_x, along_y, sinc2(along_x) * sinc2(along_y))
}

/// Below this share of a period's order in the nearest cell order, [`grating`] says that the patch does not
/// hold its period a whole number of times (a mismatch of an eighth of a period or more).
pub const PERIOD_FIT_NOTE_BELOW: f64 = 0.95;

/// A patch taken as one unit cell and its strongest period, a grating's (at least a tenth of the height
/// variance): how many times the cell holds it and how much of each of its orders the cell keeps in one order
/// ([`period_fit`]). In `iridis grating --json` as `unit_cell.period_fit`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PeriodFit {
    pub period_nm: f64,
    /// The grating vector's direction, degrees from +x.
    pub orientation_deg: f64,
    /// The period's share of the height variance (0–1).
    pub variance_share: f64,
    /// Periods across the cell along x and y.
    pub cycles: (f64, f64),
    /// The share of each of the period's orders in the nearest of the cell's orders (0–1; 1 where it tiles).
    pub nearest_order_share: f64,
}

impl PeriodFit {
    /// The fit of `patch`'s strongest period, or `None` where it has none that carries a tenth of the variance.
    pub fn of(patch: &iridis_diffraction::Patch) -> Option<Self> {
        let peak = crate::surface::strongest_period(patch).filter(|p| p.power >= 0.1)?;
        let (x, y, share) = period_fit(patch.extent(), peak.period_nm, peak.orientation_deg);
        Some(PeriodFit {
            period_nm: peak.period_nm,
            orientation_deg: peak.orientation_deg,
            variance_share: peak.power,
            cycles: (x, y),
            nearest_order_share: share,
        })
    }

    /// The note where the period does not tile the cell (its orders keep less than [`PERIOD_FIT_NOTE_BELOW`]).
    pub fn note(&self) -> Option<String> {
        if self.nearest_order_share >= PERIOD_FIT_NOTE_BELOW {
            return None;
        }
        let (x, y) = self.cycles;
        let held = match (x >= 0.01, y >= 0.01) {
            (true, true) => format!("{x:.2} times along x and {y:.2} along y"),
            (false, true) => format!("{y:.2} times along y"),
            _ => format!("{x:.2} times along x"),
        };
        Some(format!(
            "the patch holds its strongest period ({:.1} nm along {:.1}°, {:.0} % of the height variance) {held}, \
             not a whole number: as one unit cell it repeats with a step at its edge, and each of the period's \
             orders falls between two of the cell's, the nearest taking about {:.0} % of its light; --unit-cell \
             auto takes the period itself as the cell",
            self.period_nm,
            self.orientation_deg,
            100.0 * self.variance_share,
            100.0 * self.nearest_order_share
        ))
    }

    /// Where the period tiles the cell more than once: which of the cell's orders are the period's (the listing
    /// numbers the cell's; a 65 µm scan of a 1100 nm sine has its first orders at m = ±59).
    pub fn order_numbering(&self) -> Option<String> {
        let (x, y) = self.cycles;
        let held = x.hypot(y);
        if held < 1.5 {
            return None;
        }
        let (m, n) = (x.round() as i64, y.round() as i64);
        Some(format!(
            "the cell holds its strongest period ({:.1} nm along {:.1}°) {held:.2} times: the orders listed are the \
             cell's, and the period's order k is the cell's ({m}, {n}) × k, its first orders ±({m}, {n}); others \
             listed carry the light of the rest of the relief (and of the period's cut at the cell's edge, where it \
             does not tile); --unit-cell auto numbers the period's own",
            self.period_nm, self.orientation_deg
        ))
    }

    /// `unit_cell.period_fit` of `iridis grating --json` (keys in docs/json.md).
    pub fn to_json(&self) -> Value {
        json!({"period_nm": self.period_nm, "orientation_deg": self.orientation_deg,
               "variance_share": self.variance_share, "cycles_x": self.cycles.0, "cycles_y": self.cycles.1,
               "nearest_order_share": self.nearest_order_share, "tiles": self.note().is_none()})
    }
}

/// `--unit-cell auto`: the scan's strongest period as the unit cell, its profile averaged along the ridges
/// ([`averaged_unit_cell`]), said in a note; refused where the scan has no dominant period. Returns the cell, its
/// period (nm) and direction (degrees).
pub fn auto_unit_cell(
    patch: &iridis_diffraction::Patch,
    name: &str,
    report: &dyn Report,
) -> Result<(iridis_diffraction::Patch, f64, f64)> {
    let peak = match crate::surface::dominant_period(patch) {
        Ok(peak) => peak,
        // A random surface's strongest peak is no grating's period: taken as one, its orders were printed as if.
        Err(Some((strongest, next))) => bail!(
            "--unit-cell auto: {name} has no dominant period to take as the unit cell: {}; `iridis surface info` \
             lists them",
            crate::surface::why_not_dominant(&strongest, next)
        ),
        Err(None) => {
            bail!("--unit-cell auto: {name} has no period to take as the unit cell (its spectrum has no peak)")
        }
    };
    let Some((cell, d, phi)) = averaged_unit_cell_at(patch, &peak) else {
        let pixel = patch.dx.min(patch.dy);
        bail!(
            "--unit-cell auto: {name}'s strongest period, {:.0} nm, spans {:.1} pixels of {pixel:.0} nm: too few to \
             take its profile from (at least {MIN_PIXELS_PER_PERIOD}); the scan's pixel is too coarse for this \
             period (its true period may differ: the spectrum aliases under 2 pixels a period)",
            peak.period_nm,
            peak.period_nm / pixel
        );
    };
    // How much of the relief the cell stands for: a period under noise keeps little of it.
    report.note(&format!(
        "unit cell: the strongest period, {d:.1} nm along {phi:.1}°, its profile averaged along the ridges over the \
         whole scan ({} samples), {:.1} % of its height variance; orders (m, 0) are numbered along the period, \
         directions given in the scan's frame",
        cell.cols,
        100.0 * crate::unit_cell::variance_share(&cell, patch)
    ));
    Ok((cell, d, phi))
}

/// The Fresnel source of a material written as a stack's medium, exact per polarisation at every wavelength
/// of `[from, to]` (refused, naming the range the data have, where they do not cover it).
pub fn material_fresnel(medium: &str, from_nm: f64, to_nm: f64) -> Result<Arc<iridis_lab::laser::MetalFresnel>> {
    let stack: iridis_thinfilm::Stack =
        format!("air | {medium}").parse().with_context(|| format!("--material '{medium}'"))?;
    let m = stack.substrate;
    let (lo, hi) = m.range_nm();
    if from_nm < lo || to_nm > hi {
        bail!(
            "--material '{medium}': its data cover {lo:.0}–{hi:.0} nm, not the {from_nm:.0}–{to_nm:.0} nm asked; \
             narrow --from/--to or give another material"
        );
    }
    Ok(Arc::new(iridis_lab::laser::MetalFresnel::new(m, from_nm, to_nm)?))
}

/// Order efficiencies of the unit cell SURFACE (its extent the periods) for `opts`.
pub fn grating(
    source: &Source,
    surface: &SurfaceOptions,
    opts: &GratingOptions,
    report: &dyn Report,
) -> Result<Grating> {
    let l = opts.light;
    if !(l.iter().all(|v| v.is_finite()) && (dot(l, l).sqrt() - 1.0).abs() < 1e-9 && l[2] > 0.0) {
        bail!("the light must come from above the surface (θ < 90°)");
    }
    if !(0.0..1.0).contains(&opts.orders_above) {
        bail!("--orders-above {}: the efficiency must be from 0 up to 1 (100 %)", opts.orders_above);
    }
    let shortest = opts.wavelengths_nm.iter().copied().fold(f64::INFINITY, f64::min);
    iridis_color::spectrum::check_light_nanometres(shortest)?;
    let w = &opts.wavelengths_nm;
    if w.is_empty() {
        bail!("no wavelength given: give one, or a range");
    }
    if let Some(bad) = w.iter().find(|l| !(l.is_finite() && **l > 0.0)) {
        bail!("the wavelengths must be positive lengths in nm, not {bad}");
    }
    if !(opts.orders_above.is_finite() && (0.0..1.0).contains(&opts.orders_above)) {
        bail!("the efficiency above which orders are listed must be a fraction from 0 up to 1");
    }
    if let (GratingMethod::Rigorous, Some(n)) = (opts.method, opts.normalisation) {
        bail!(
            "--normalisation {} would be ignored: it scales the scalar (Kirchhoff) model's channel matrix, and the \
             rigorous method's efficiencies come from Maxwell's equations (--compare runs both)",
            n.name()
        );
    }
    let normalisation = opts.normalisation.unwrap_or(Normalisation::Energy);
    if let Some(d) = opts.detector {
        if !(d.direction[2] > 0.0 && d.acceptance_rad > 0.0 && d.acceptance_rad < std::f64::consts::FRAC_PI_2) {
            bail!("the detector must look from above the surface with an acceptance between 0° and 90°");
        }
    }
    let (from, to) = w.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &l| (a.min(l), b.max(l)));
    let mut substrate = None;
    let (fresnel, reflector): (Arc<dyn FresnelSource>, String) = match (&opts.material, &opts.fresnel) {
        (Some(_), Some(_)) => bail!("give --material or --fresnel, not both"),
        (None, Some(_)) if opts.method == GratingMethod::Rigorous => bail!(
            "the rigorous method needs the material under the relief (--material gold, n=1.5, n=0.2+3.4i, …), \
             not a Fresnel approximation"
        ),
        (None, Some(f)) => {
            let f = crate::fresnel::parse_fresnel_source(f)?;
            let d = f.describe();
            (f, d)
        }
        (m, None) => {
            let medium = m.as_deref().unwrap_or(DEFAULT_MATERIAL);
            let metal = material_fresnel(medium, from, to)?;
            substrate = Some(metal.clone());
            (metal, format!("{medium} (exact Fresnel, s and p)"))
        }
    };
    let mut patch = source.patch(surface, report)?;
    let mut averaged = None;
    // The light in the cell's frame: an averaged cell runs along its grating vector at φ, so rotate by −φ.
    let mut l = l;
    if opts.unit_cell_auto {
        let (cell, d, phi) = auto_unit_cell(&patch, source.name(), report)?;
        patch = cell;
        averaged = Some((d, phi));
        let (s, c) = (-phi.to_radians()).sin_cos();
        l = [c * l[0] - s * l[1], s * l[0] + c * l[1], l[2]];
    }
    // Only a patch taken whole as the cell can hold its period a fractional number of times.
    let fit = if averaged.is_none() { PeriodFit::of(&patch) } else { None };
    if let Some(note) = fit.and_then(|f| f.note().or_else(|| f.order_numbering())) {
        report.note(&note);
    }
    // Kirchhoff's unit cell keeps only the DFT bins this light's orders read (a large scan's memory); the
    // rigorous solver takes the patch itself, so its Taylor terms are not made (nor their depth limit met).
    let cell = match opts.method {
        GratingMethod::Kirchhoff => Some(UnitCell::for_light(&patch, l, w)?),
        GratingMethod::Rigorous => None,
    };
    let lines = Lines::of(&patch);
    let (lx, ly) = patch.extent();
    report.info(&format!(
        "{}: one unit cell of {:.1} × {:.1} nm ({}×{} samples, {}){}",
        source.name(),
        lx,
        ly,
        patch.cols,
        patch.rows,
        match lines {
            Lines::AlongX => "a 1-D grating along x: every row the same",
            Lines::AlongY => "a 1-D grating along y: every column the same",
            Lines::Crossed => "a crossed grating",
        },
        cell.as_ref().map_or(String::new(), |c| format!(", N = {} Taylor terms", c.taylor_terms()))
    ));
    // An order is listed at or above the asked efficiency, or inside the detector's cone (its reflectance
    // sums them); directions in the cell's frame are turned back by φ for the detector.
    let keep = |o: &OrderEfficiency, averaged: Option<(f64, f64)>| {
        opts.orders_above <= 0.0
            || o.efficiency.unpolarized >= opts.orders_above
            || opts.detector.is_some_and(|d| {
                let phi = o.phi_deg + averaged.map_or(0.0, |(_, p)| p);
                let (t, p) = (o.theta_deg.to_radians(), phi.to_radians());
                dot([t.sin() * p.cos(), t.sin() * p.sin(), t.cos()], d.direction) >= d.acceptance_rad.cos() - 1e-12
            })
    };
    let answers: Vec<OrdersAt> = match &cell {
        Some(cell) => {
            if !fresnel.polarised() {
                report.note(&format!(
                    "{}: no polarised form, so TE and TM get the same reflectance (give --material for exact s and p)",
                    fresnel.describe()
                ));
            }
            // One wavelength at a time, its orders listed as asked before the next: memory scales with the
            // orders kept, not with every order of every wavelength.
            let done = std::sync::atomic::AtomicUsize::new(0);
            let a = with_progress(report, w.len() as u64, "orders", |p| {
                w.par_iter()
                    .map(|&lambda| {
                        let a = cell.efficiencies(l, lambda, fresnel.as_ref(), normalisation)?;
                        p(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
                        let row_only = (a.normalisation == "energy-row").then_some((a.channels, a.wavelength_nm));
                        let listed = OrdersAt::kirchhoff(a, cell.taylor_terms()).listing(|o| keep(o, averaged));
                        Ok((listed, row_only))
                    })
                    .collect::<Result<Vec<_>, iridis_diffraction::DiffractionError>>()
            })?;
            if let Some((channels, lambda)) = a.iter().find_map(|(_, r)| *r) {
                report.note(&format!(
                    "{channels} channels at {lambda:.0} nm: the efficiencies are scaled so that this light's orders \
                     conserve energy (reciprocity is then approximate; the full scaling runs up to {} channels)",
                    iridis_diffraction::grating::MAX_SINKHORN_CHANNELS
                ));
            }
            a.into_iter().map(|(a, _)| a).collect()
        }
        None => {
            let metal = substrate.expect("the rigorous method has a material");
            rigorous(&patch, lines, l, w, &metal, report)?
                .into_iter()
                .map(|a| a.listing(|o| keep(o, averaged)))
                .collect()
        }
    };
    let g = Grating {
        surface: source.name().to_string(),
        method: opts.method,
        periods_nm: (lx, ly),
        samples: (patch.cols, patch.rows),
        lines,
        reflector,
        polarised: fresnel.polarised(),
        normalisation,
        taylor_terms: cell.as_ref().map(UnitCell::taylor_terms),
        light: opts.light,
        detector: opts.detector,
        averaged,
        period_fit: fit,
        orders_above: opts.orders_above,
        answers: match averaged {
            Some((_, phi)) => answers.into_iter().map(|a| a.rotated(phi)).collect(),
            None => answers,
        },
    };
    if let Some(w) = g.detector_misses_every_order() {
        report.warn(&w);
    }
    Ok(g)
}

/// A unit cell as the rigorous solver takes it: a 1-D profile where it is one (along x, or along y by a
/// rotation of the light by −90°) and a crossed grating otherwise.
#[derive(Debug, Clone)]
pub struct RigorousCell {
    shape: RigorousShape,
}

#[derive(Debug, Clone)]
enum RigorousShape {
    /// The profile, the rotation (rad) from the solver's frame to the cell's, and whether it runs along y.
    OneD(iridis_rigorous::Profile1d, f64, bool),
    TwoD(iridis_rigorous::Profile2d),
}

impl RigorousCell {
    /// The solver's form of `patch` (its extent the periods; `lines` from [`UnitCell::lines`]).
    pub fn new(patch: &iridis_diffraction::Patch, lines: Lines, report: &dyn Report) -> Self {
        use iridis_rigorous::{Profile1d, Profile2d};
        let (rows, cols) = (patch.rows, patch.cols);
        let (lx, ly) = patch.extent();
        let shape = match lines {
            Lines::AlongX => {
                RigorousShape::OneD(Profile1d { period_nm: lx, heights_nm: patch.heights[..cols].to_vec() }, 0.0, false)
            }
            // Columns all the same: the profile runs along y; in the solver's frame (profile along x) the
            // light's azimuth is φ − 90°, and its orders (m, 0) are the surface's (0, m).
            Lines::AlongY => RigorousShape::OneD(
                Profile1d { period_nm: ly, heights_nm: (0..rows).map(|j| patch.heights[j * cols]).collect() },
                std::f64::consts::FRAC_PI_2,
                true,
            ),
            Lines::Crossed => {
                if rows * cols > 64 * 64 {
                    report.note(&format!(
                        "a crossed grating of {cols}×{rows} samples: the C-method's cost grows as (2M+1)⁶ with the \
                         orders M it needs; a 1-D unit cell (rows all the same) is far faster"
                    ));
                }
                // Back to the readers' row order (row 0 at the top), as the solver takes it.
                let heights = (0..rows).rev().flat_map(|j| patch.heights[j * cols..(j + 1) * cols].to_vec()).collect();
                RigorousShape::TwoD(Profile2d { period_x_nm: lx, period_y_nm: ly, rows, cols, heights_nm: heights })
            }
        };
        Self { shape }
    }

    /// The orders of light from `light` (unit vector, in the cell's frame) at one wavelength over a substrate
    /// of complex index `index`, in the scalar model's terms (the cell's frame).
    pub fn solve(&self, wavelength_nm: f64, light: Vec3, index: num_complex::Complex64) -> Result<OrdersAt> {
        use iridis_rigorous::{solve_1d, solve_2d, Options, Problem};
        let theta = light[2].clamp(-1.0, 1.0).acos();
        let phi = light[1].atan2(light[0]);
        let options = Options::default();
        let r = match &self.shape {
            RigorousShape::OneD(profile, rot, along_y) => {
                let problem = Problem::new(wavelength_nm, theta, phi - rot, index);
                solve_1d(profile, &problem, &options).map(|s| OrdersAt::rigorous(s, *rot, *along_y))
            }
            RigorousShape::TwoD(profile) => {
                solve_2d(profile, &Problem::new(wavelength_nm, theta, phi, index), &options)
                    .map(|s| OrdersAt::rigorous(s, 0.0, false))
            }
        };
        r.map_err(|e| anyhow::anyhow!("the rigorous solver at {wavelength_nm} nm: {e}"))
    }

    /// Whether the solver sees a 1-D profile (a crossed grating costs far more).
    pub fn is_one_d(&self) -> bool {
        matches!(self.shape, RigorousShape::OneD(..))
    }
}

/// The rigorous solutions at every wavelength (in parallel), the unit cell as [`RigorousCell`] takes it.
fn rigorous(
    patch: &iridis_diffraction::Patch,
    lines: Lines,
    light: Vec3,
    wavelengths_nm: &[f64],
    metal: &iridis_lab::laser::MetalFresnel,
    report: &dyn Report,
) -> Result<Vec<OrdersAt>> {
    let cell = RigorousCell::new(patch, lines, report);
    let done = std::sync::atomic::AtomicUsize::new(0);
    let solutions = with_progress(report, wavelengths_nm.len() as u64, "rigorous orders", |p| {
        wavelengths_nm
            .par_iter()
            .map(|&l| {
                let r = cell.solve(l, light, metal.index(l));
                p(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
                r
            })
            .collect::<Result<Vec<_>>>()
    })?;
    let unmet: Vec<String> = solutions
        .iter()
        .filter(|s| s.convergence["met"] == json!(false))
        .map(|s| {
            if error_not_estimated(&s.convergence) {
                format!(
                    "{:.0} nm (no estimate: the truncation could not grow past the propagating orders)",
                    s.wavelength_nm
                )
            } else {
                format!(
                    "{:.0} nm (±{:.2e})",
                    s.wavelength_nm,
                    s.convergence["estimated_error"].as_f64().unwrap_or(f64::NAN)
                )
            }
        })
        .collect();
    if !unmet.is_empty() {
        report.warn(&format!(
            "the rigorous solver reached its order limit before the tolerance at {}: the efficiencies there are not \
             converged (the error estimated in brackets, where there is one)",
            unmet.join(", ")
        ));
    }
    // Light created or lost over a lossless medium: not an answer with an error bar but no answer (a crossed
    // lamellar grating at 250 nm printed 4017 % reflected beside "NOT met").
    let unphysical: Vec<String> = solutions
        .iter()
        .filter_map(|s| {
            // Over a lossless medium R + T = 1; over any passive one R ≤ 1 (gold at 250 nm reflected 1961 %).
            let r = s.reflected_total.te.max(s.reflected_total.tm);
            match s.convergence["energy_error"].as_f64() {
                Some(e) if e > UNPHYSICAL_ENERGY_ERROR => {
                    Some(format!("{:.0} nm (R + T − 1 = {e:.2e})", s.wavelength_nm))
                }
                _ if r > 1.0 + UNPHYSICAL_ENERGY_ERROR => {
                    Some(format!("{:.0} nm (R = {:.1} %)", s.wavelength_nm, 100.0 * r))
                }
                _ => None,
            }
        })
        .collect();
    if !unphysical.is_empty() {
        report.warn(&format!(
            "at {} the rigorous answer creates or loses light (energy conservation: R + T = 1 over a lossless \
             medium, R ≤ 1 over any): its efficiencies are not physical, do not use them (the C-method converges \
             slowly or not at all on sharp-edged, lamellar or crossed reliefs: docs/rigorous.md)",
            unphysical.join(", ")
        ));
    }
    Ok(solutions)
}

/// Above this |R + T − 1| over a lossless medium a rigorous answer is said to be no answer (a converged one is
/// within its tolerance, 1e-3 by default).
pub const UNPHYSICAL_ENERGY_ERROR: f64 = 0.01;

/// Whether a rigorous answer's convergence record has no error estimate: not met, and its truncation could not
/// grow past the propagating orders, so the "estimate" compared one truncation with itself.
pub fn error_not_estimated(convergence: &Value) -> bool {
    convergence["met"] != Value::Bool(true) && convergence["orders"] == convergence["compared_with"]
}

fn deg(r: f64) -> f64 {
    (r.to_degrees() * 1e9).round() / 1e9
}

/// The colours of a grating under D65 (CIE 1931), when its wavelengths span the visible 380–780 nm.
#[derive(Debug, Clone)]
pub struct GratingColours {
    /// The mirror order (0, 0): what the surface shows where it does not diffract.
    pub specular: iridis_color::Xyz,
    /// Every other order together.
    pub diffracted: iridis_color::Xyz,
    /// All orders (what an integrating sphere sees).
    pub reflected: iridis_color::Xyz,
    pub white: iridis_color::Xyz,
}

impl GratingColours {
    /// The diffracted share of the reflected light, weighted by D65 × ȳ (luminous).
    pub fn diffracted_share(&self) -> f64 {
        if self.reflected.y > 0.0 {
            self.diffracted.y / self.reflected.y
        } else {
            0.0
        }
    }
}

impl Grating {
    /// The colours of the specular order, the diffracted orders and all of them under D65, for unpolarised
    /// light; `None` unless the wavelengths span 380–780 nm at steps of at most 10 nm.
    pub fn colours(&self) -> Option<GratingColours> {
        let w: Vec<f64> = self.answers.iter().map(|a| a.wavelength_nm).collect();
        let covers = w.first().is_some_and(|&l| l <= 380.0) && w.last().is_some_and(|&l| l >= 780.0);
        if !covers || w.windows(2).any(|p| p[1] - p[0] > COLOUR_STEP_NM + 1e-9) {
            return None;
        }
        let weights =
            iridis_color::SpectralWeights::new(&w, iridis_color::Illuminant::D65, iridis_color::Observer::Cie1931);
        let spec: Vec<f64> = self
            .answers
            .iter()
            .map(|a| a.orders.iter().find(|o| (o.m, o.n) == (0, 0)).map_or(0.0, |o| o.efficiency.unpolarized))
            .collect();
        let total: Vec<f64> = self.answers.iter().map(|a| a.reflected_total.unpolarized).collect();
        let diffracted: Vec<f64> = total.iter().zip(&spec).map(|(t, s)| (t - s).max(0.0)).collect();
        Some(GratingColours {
            specular: weights.integrate(&spec),
            diffracted: weights.integrate(&diffracted),
            reflected: weights.integrate(&total),
            white: weights.white(),
        })
    }

    /// Where no order enters the detector's cone at any wavelength asked (its column is 0 % throughout), the
    /// sentence that says so, with the order that passes nearest its axis.
    pub fn detector_misses_every_order(&self) -> Option<String> {
        let d = self.detector?;
        let angle = |o: &OrderEfficiency| {
            let (t, p) = (o.theta_deg.to_radians(), o.phi_deg.to_radians());
            dot([t.sin() * p.cos(), t.sin() * p.sin(), t.cos()], d.direction).clamp(-1.0, 1.0).acos()
        };
        let orders = self.answers.iter().flat_map(|a| &a.orders);
        let nearest = orders.min_by(|a, b| angle(a).total_cmp(&angle(b)))?;
        if angle(nearest) <= d.acceptance_rad {
            return None;
        }
        let axis = d.direction[2].clamp(-1.0, 1.0).acos().to_degrees();
        let azimuth = d.direction[1].atan2(d.direction[0]).to_degrees().rem_euclid(360.0);
        Some(format!(
            "no order enters the detector's ±{:.2}° cone (θ {axis:.1}°, φ {azimuth:.1}°) at any wavelength asked, so \
             its column is 0 %: the nearest, order ({}, {}) at {} nm, passes {:.1}° from its axis; move the detector \
             (--detector) or widen --acceptance",
            d.acceptance_rad.to_degrees(),
            nearest.m,
            nearest.n,
            iridis_color::spectrum::short_number(nearest.wavelength_nm),
            angle(nearest).to_degrees()
        ))
    }

    /// The reflectance a detector sees at one wavelength: the orders inside its acceptance cone (fraction).
    pub fn detector_reflectance(&self, answer: &OrdersAt) -> Option<f64> {
        let d = self.detector?;
        let cos_cone = d.acceptance_rad.cos();
        Some(
            answer
                .orders
                .iter()
                .filter(|o| {
                    let (t, p) = (o.theta_deg.to_radians(), o.phi_deg.to_radians());
                    let wr = [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()];
                    dot(wr, d.direction) >= cos_cone
                })
                .map(|o| o.efficiency.unpolarized)
                .fold(0.0, |a, b| a + b),
        )
    }

    /// What `iridis grating --json` prints (keys in docs/json.md).
    pub fn to_json(&self) -> Value {
        let l = self.light;
        let orders: Vec<Value> = self
            .answers
            .iter()
            .flat_map(|a| a.orders.iter().map(|o| serde_json::to_value(o).unwrap_or_default()))
            .collect();
        let totals: Vec<Value> = self
            .answers
            .iter()
            .map(|a| {
                json!({"wavelength_nm": a.wavelength_nm, "te": a.reflected_total.te, "tm": a.reflected_total.tm,
                       "unpolarized": a.reflected_total.unpolarized})
            })
            .collect();
        let convergence: Vec<Value> = self.answers.iter().map(|a| a.convergence.clone()).collect();
        let transmitted: Vec<Value> = self
            .answers
            .iter()
            .filter_map(|a| {
                a.transmitted_total.map(
                    |t| json!({"wavelength_nm": a.wavelength_nm, "te": t.te, "tm": t.tm, "unpolarized": t.unpolarized}),
                )
            })
            .collect();
        let transmitted_orders: Vec<Value> = self
            .answers
            .iter()
            .flat_map(|a| a.transmitted_orders.iter().map(|o| serde_json::to_value(o).unwrap_or_default()))
            .collect();
        let detector = self.detector.map(|d| {
            let (t, p) = (d.direction[2].clamp(-1.0, 1.0).acos(), d.direction[1].atan2(d.direction[0]));
            let spectrum: Vec<Value> = self
                .answers
                .iter()
                .map(|a| json!({"wavelength_nm": a.wavelength_nm, "reflectance": self.detector_reflectance(a)}))
                .collect();
            json!({"theta_deg": deg(t), "phi_deg": deg(p), "acceptance_deg": deg(d.acceptance_rad),
                   "spectrum": spectrum})
        });
        json!({
            "surface": self.surface,
            "method": self.method.name(),
            "unit_cell": {"period_x_nm": if self.lines == Lines::AlongY { Value::Null } else { json!(self.periods_nm.0) },
                          "period_y_nm": if self.lines == Lines::AlongX { Value::Null } else { json!(self.periods_nm.1) },
                          "samples": [self.samples.0, self.samples.1],
                          "kind": match (self.averaged, self.lines) {
                              (Some(_), _) => "1-D, the scan's dominant period averaged along its ridges",
                              (None, Lines::AlongX) => "1-D along x", (None, Lines::AlongY) => "1-D along y",
                              (None, Lines::Crossed) => "crossed" },
                          "orientation_deg": self.averaged.map_or(Value::Null, |(_, phi)| json!(phi)),
                          "period_fit": self.period_fit.as_ref().map(PeriodFit::to_json)},
            "light": {"theta_deg": deg(l[2].clamp(-1.0, 1.0).acos()), "phi_deg": deg(l[1].atan2(l[0])), "direction": l},
            "reflector": self.reflector,
            "polarised": self.polarised,
            "polarisation": match self.method {
                GratingMethod::Kirchhoff => "TE = s, TM = p, with respect to the plane of the light and the order (scalar model: no conversion)",
                GratingMethod::Rigorous => "TE: the incident electric field perpendicular to the incident plane of incidence, TM: the magnetic field; each order's efficiency sums both outgoing polarisations",
            },
            "normalisation": match self.method {
                GratingMethod::Kirchhoff => self.normalisation.name(),
                GratingMethod::Rigorous => "none (Maxwell's equations conserve energy)",
            },
            "wavelength_nm": self.answers.iter().map(|a| a.wavelength_nm).collect::<Vec<f64>>(),
            "orders": orders,
            "unlisted_orders": (self.orders_above > 0.0).then(|| json!({
                "below_efficiency": self.orders_above,
                "per_wavelength": self.answers.iter().map(|a| a.unlisted).collect::<Vec<usize>>(),
                "note": "orders below this efficiency are counted in the totals and colours but not listed",
            })),
            "reflected_total": totals,
            "transmitted_total": if transmitted.is_empty() { Value::Null } else { Value::Array(transmitted) },
            "transmitted_orders": transmitted_orders,
            "detector": detector,
            "colour": self.colours().map(|c| json!({
                "illuminant": "d65", "observer": "1931",
                "specular": crate::color::colour_report(c.specular, c.white),
                "diffracted": crate::color::colour_report(c.diffracted, c.white),
                "reflected": crate::color::colour_report(c.reflected, c.white),
                "diffracted_share": c.diffracted_share(),
            })),
            "convergence": convergence,
            "units": "efficiencies are fractions of the incident power (1 = 100 %)",
        })
    }
}

/// How far the scalar model is from Maxwell's equations on one unit cell: the same orders compared wavelength
/// by wavelength, and the colours of the light they send (issue 28: "the scalar model's error on the user's
/// own scan").
#[derive(Debug, Clone)]
pub struct ScalarError {
    /// Per order present in both (reflected), at each wavelength: (λ, m, n, scalar, rigorous).
    pub orders: Vec<(f64, i64, i64, Efficiency, Efficiency)>,
    /// The largest relative error of any order whose rigorous efficiency exceeds `floor`, TE, TM, unpolarised.
    pub worst: Efficiency,
    /// Where the worst unpolarised error is: (λ, m, n).
    pub worst_at: Option<(f64, i64, i64)>,
    /// The largest relative error of the total reflectance, unpolarised.
    pub total: f64,
    /// CIEDE2000 between the scalar and rigorous colours of the diffracted orders and of the mirror order (D65,
    /// 380–780 nm), where the wavelengths span it.
    pub delta_e_diffracted: Option<f64>,
    pub delta_e_specular: Option<f64>,
    pub floor: f64,
}

/// The shortest period that can send a visible diffraction order out of a surface: `d > λ/2`, λ ≥ 380 nm.
pub const VISIBLE_PERIOD_NM: f64 = 190.0;

/// The share of the reflected light (D65 × ȳ) a structure must diffract to count as diffracting: below it a
/// scan looks like a mirror of its specular colour (`iridis report` draws no maps and runs no test bench).
pub const DIFFRACTS_SHARE: f64 = 1e-3;

/// The shortest period with a visible first order under light at 45°, where `iridis report` measures its shares
/// (with 0°): a first order leaves for `λ < d (1 + sin θ_i)`, so `d > 380 nm / (1 + sin 45°)` ≈ 223 nm.
pub const FIRST_ORDER_AT_45_NM: f64 = 380.0 / (1.0 + std::f64::consts::FRAC_1_SQRT_2);

/// Whether a scan diffracts visible light: a diffracted share worth drawing at 0° or 45° (`diffracted_shares`,
/// [`DIFFRACTS_SHARE`]) and, where periods were found (`longest_period_nm`), one with a visible first order at
/// those angles ([`FIRST_ORDER_AT_45_NM`]). A scan with only shorter periods still sends light into the orders
/// of its own extent as a unit cell — its edges and the tilt plane levelling leaves on a periodic relief (a
/// 200 nm sine levelled sent 9.9 % there), not its structure — hence both conditions; a scan with no period
/// found (structure longer than a quarter of it, or none) is judged by its share alone.
pub fn diffracts_visible_light(longest_period_nm: Option<f64>, diffracted_shares: &[f64]) -> bool {
    longest_period_nm.is_none_or(|p| p >= FIRST_ORDER_AT_45_NM)
        && diffracted_shares.iter().any(|&s| s >= DIFFRACTS_SHARE)
}

/// The coherence length (nm) for BRDF maps of a scan of extent `extent_nm` whose strongest period is
/// `strongest_period_nm`: under the light's 65 µm a smaller scan shows the discrete orders of its periodic
/// extension, narrower than a pixel; half the scan's shorter side, never under four of its strongest periods
/// (a strip of a grating keeps its orders), lets each pixel see the scan's spectrum, and never under what the
/// pixels carry (`4·max(dx, dy)`: a 3 × 3-sample scan had the report pick 120 nm and then refuse it). `None`: the
/// light's own.
pub fn map_coherence_nm(extent_nm: [f64; 2], strongest_period_nm: f64, pixel_nm: [f64; 2]) -> Option<f64> {
    let c = (0.5 * extent_nm[0].min(extent_nm[1]))
        .max(4.0 * strongest_period_nm)
        .max(iridis_diffraction::patch::min_coherence_nm(pixel_nm[0], pixel_nm[1]));
    (c < iridis_diffraction::DEFAULT_COHERENCE_NM).then_some(c)
}

/// The coarsest wavelength step at which a grating's answer carries colours (over 380–780 nm).
pub const COLOUR_STEP_NM: f64 = 10.0;

/// The efficiency below which an order is not compared relatively: an order counts where either model puts at
/// least this in it, its error relative to Maxwell's efficiency or to this floor where Maxwell's is below it.
pub const COMPARE_FLOOR: f64 = 1e-3;

/// The scalar model's error on one order, `(scalar − rigorous)/max(rigorous, floor)`, where either model puts at
/// least `floor` in it ([`COMPARE_FLOOR`]); `None` where both are below. An order Kirchhoff fills at 7.2 % and
/// Maxwell's equations at 0.006 % counts (it was left out, judged on Maxwell's value alone): +7200 % of the floor.
pub fn relative_error(scalar: f64, rigorous: f64, floor: f64) -> Option<f64> {
    (scalar.max(rigorous) >= floor).then(|| (scalar - rigorous) / rigorous.max(floor))
}

/// Above this worst relative error of an order's efficiency (unpolarised), or above [`SCALAR_WARN_DELTA_E`]
/// in the colour of the diffracted light, the front ends warn that the scalar model's numbers are not to be
/// trusted on the structure (`iridis report`, `brdf eval`).
pub const SCALAR_WARN_RELATIVE: f64 = 0.2;
/// CIEDE2000 of the diffracted light's colour above which the front ends warn ([`SCALAR_WARN_RELATIVE`]).
pub const SCALAR_WARN_DELTA_E: f64 = 2.0;

/// Compares the scalar and rigorous answers of the same unit cell and light.
pub fn scalar_error(scalar: &Grating, rigorous: &Grating) -> ScalarError {
    let rel = |a: f64, b: f64| relative_error(a, b, COMPARE_FLOOR).map_or(0.0, f64::abs);
    let mut orders = Vec::new();
    let mut total = 0.0f64;
    for (k, r) in scalar.answers.iter().zip(&rigorous.answers) {
        for ro in &r.orders {
            let Some(ko) = k.orders.iter().find(|o| (o.m, o.n) == (ro.m, ro.n)) else { continue };
            orders.push((r.wavelength_nm, ro.m, ro.n, ko.efficiency, ro.efficiency));
        }
        total = total.max(rel(k.reflected_total.unpolarized, r.reflected_total.unpolarized));
    }
    let de = |f: fn(&GratingColours) -> iridis_color::Xyz| {
        let (a, b) = (scalar.colours()?, rigorous.colours()?);
        Some(iridis_color::lab::delta_e_2000(
            iridis_color::Lab::from_xyz(f(&a), a.white),
            iridis_color::Lab::from_xyz(f(&b), b.white),
        ))
    };
    // The worst errors over every order (the floor of the listing is 0).
    ScalarError {
        orders,
        worst: Efficiency::default(),
        worst_at: None,
        total,
        delta_e_diffracted: de(|c| c.diffracted),
        delta_e_specular: de(|c| c.specular),
        floor: COMPARE_FLOOR,
    }
    .judged_above(0.0)
}

impl ScalarError {
    /// The same comparison judged on the orders either model puts at or above `orders_above` (`--orders-above`:
    /// those listed, or that should be), each with either model's efficiency above the floor
    /// ([`relative_error`]): the worst relative errors (TE, TM, unpolarised) and where the unpolarised one is.
    /// Computed from every order of both models, so an order listed by one and under the floor in the other is
    /// still compared.
    pub fn judged_above(mut self, orders_above: f64) -> Self {
        let rel = |a: f64, b: f64| relative_error(a, b, self.floor).map_or(0.0, f64::abs);
        let (mut worst, mut worst_at) = (Efficiency::default(), None);
        for &(l, m, n, k, r) in &self.orders {
            if k.unpolarized.max(r.unpolarized) < orders_above {
                continue;
            }
            worst.te = worst.te.max(rel(k.te, r.te));
            worst.tm = worst.tm.max(rel(k.tm, r.tm));
            let u = rel(k.unpolarized, r.unpolarized);
            if u > worst.unpolarized {
                worst.unpolarized = u;
                worst_at = Some((l, m, n));
            }
        }
        self.orders.retain(|&(_, _, _, k, r)| k.unpolarized.max(r.unpolarized) >= orders_above);
        (self.worst, self.worst_at) = (worst, worst_at);
        self
    }

    /// Whether the scalar model is off by more than the front ends' threshold ([`SCALAR_WARN_RELATIVE`],
    /// [`SCALAR_WARN_DELTA_E`]).
    pub fn above_threshold(&self) -> bool {
        self.worst.unpolarized > SCALAR_WARN_RELATIVE
            || self.delta_e_diffracted.is_some_and(|d| d > SCALAR_WARN_DELTA_E)
    }

    /// What `iridis grating --compare --json` prints (keys in docs/json.md).
    pub fn to_json(&self, scalar: &Grating, rigorous: &Grating) -> Value {
        let e = |x: Efficiency| json!({"te": x.te, "tm": x.tm, "unpolarized": x.unpolarized});
        let rel = |a: f64, b: f64| relative_error(a, b, self.floor);
        let orders: Vec<Value> = self
            .orders
            .iter()
            .map(|&(l, m, n, a, b)| {
                json!({"wavelength_nm": l, "m": m, "n": n, "kirchhoff": e(a), "rigorous": e(b),
                       "relative_error": {"te": rel(a.te, b.te), "tm": rel(a.tm, b.tm),
                                          "unpolarized": rel(a.unpolarized, b.unpolarized)}})
            })
            .collect();
        let totals: Vec<Value> = scalar
            .answers
            .iter()
            .zip(&rigorous.answers)
            .map(|(k, r)| {
                json!({"wavelength_nm": k.wavelength_nm, "kirchhoff": e(k.reflected_total),
                       "rigorous": e(r.reflected_total)})
            })
            .collect();
        json!({
            "surface": scalar.surface,
            "unit_cell": {"period_x_nm": scalar.periods_nm.0, "period_y_nm": scalar.periods_nm.1},
            "light": {"theta_deg": deg(scalar.light[2].clamp(-1.0, 1.0).acos()),
                      "phi_deg": deg(scalar.light[1].atan2(scalar.light[0]))},
            "reflector": rigorous.reflector,
            "wavelength_nm": scalar.answers.iter().map(|a| a.wavelength_nm).collect::<Vec<f64>>(),
            "orders": orders,
            "reflected_total": totals,
            "worst_relative_error": e(self.worst),
            "worst_at": self.worst_at.map(|(l, m, n)| json!({"wavelength_nm": l, "m": m, "n": n})),
            "total_relative_error": self.total,
            "delta_e00_diffracted": self.delta_e_diffracted,
            "delta_e00_specular": self.delta_e_specular,
            "efficiency_floor": self.floor,
            "rigorous_converged": rigorous.answers.iter().all(|a| a.convergence["met"] == json!(true)),
            "rigorous_tolerance": rigorous.answers.first().map_or(Value::Null, |a| a.convergence["tolerance"].clone()),
            "kirchhoff_normalisation": scalar.normalisation.name(),
        })
    }
}
