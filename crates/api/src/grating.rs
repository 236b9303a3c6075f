//! Order efficiencies of a SURFACE taken as one unit cell of a grating (`iridis grating`, Python's
//! `iridis.diffraction.grating`): the fraction of the light in each propagating order, per polarisation, with
//! what instruments measure — the hemispherical reflectance (an integrating sphere) and the reflectance a
//! detector of given acceptance sees (a goniometer, a fibre spectrometer) — over a wavelength range.

use std::sync::Arc;

use anyhow::{bail, Context, Result};
use iridis_diffraction::geometry::{dot, FresnelSource, Vec3};
use iridis_diffraction::grating::{GratingAnswer, Lines, Normalisation, UnitCell};
use serde_json::{json, Value};

use crate::report::{with_progress, Report};
use crate::surface::{Source, SurfaceOptions};

/// The model behind the efficiencies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GratingMethod {
    /// Stam's scalar (Kirchhoff) model, the one iridis' BRDFs use (`iridis_diffraction::grating`).
    Kirchhoff,
}

impl GratingMethod {
    pub fn name(self) -> &'static str {
        match self {
            GratingMethod::Kirchhoff => "kirchhoff",
        }
    }
}

impl std::str::FromStr for GratingMethod {
    type Err = anyhow::Error;
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "kirchhoff" | "scalar" => Ok(GratingMethod::Kirchhoff),
            other => bail!("--method '{other}': expected kirchhoff (Stam's scalar model)"),
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
    pub normalisation: Normalisation,
    pub detector: Option<Detector>,
}

impl Default for GratingOptions {
    fn default() -> Self {
        Self {
            method: GratingMethod::Kirchhoff,
            light: [0.0, 0.0, 1.0],
            wavelengths_nm: vec![550.0],
            material: None,
            fresnel: None,
            normalisation: Normalisation::Energy,
            detector: None,
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
    pub taylor_terms: usize,
    pub light: Vec3,
    pub detector: Option<Detector>,
    pub answers: Vec<GratingAnswer>,
}

/// The Fresnel source of a material written as a stack's medium, exact per polarisation at every wavelength
/// of `[from, to]` (refused, naming the range the data have, where they do not cover it).
pub fn material_fresnel(medium: &str, from_nm: f64, to_nm: f64) -> Result<Arc<dyn FresnelSource>> {
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
    let w = &opts.wavelengths_nm;
    if w.is_empty() || w.iter().any(|l| !(l.is_finite() && *l > 0.0)) {
        bail!("the wavelengths must be positive lengths");
    }
    if let Some(d) = opts.detector {
        if !(d.direction[2] > 0.0 && d.acceptance_rad > 0.0 && d.acceptance_rad < std::f64::consts::FRAC_PI_2) {
            bail!("the detector must look from above the surface with an acceptance between 0° and 90°");
        }
    }
    let (from, to) = w.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &l| (a.min(l), b.max(l)));
    let (fresnel, reflector): (Arc<dyn FresnelSource>, String) = match (&opts.material, &opts.fresnel) {
        (Some(_), Some(_)) => bail!("give --material or --fresnel, not both"),
        (None, Some(f)) => {
            let f = crate::fresnel::parse_fresnel_source(f)?;
            let d = f.describe();
            (f, d)
        }
        (m, None) => {
            let medium = m.as_deref().unwrap_or("n=1.5");
            (material_fresnel(medium, from, to)?, format!("{medium} (exact Fresnel, s and p)"))
        }
    };
    let patch = source.patch(surface, report)?;
    let cell = UnitCell::new(&patch, from)?;
    let (lx, ly) = cell.periods();
    report.info(&format!(
        "{}: one unit cell of {:.1} × {:.1} nm ({}×{} samples, {}), N = {} Taylor terms",
        source.name(),
        lx,
        ly,
        patch.cols,
        patch.rows,
        match cell.lines() {
            Lines::AlongX => "a 1-D grating along x: every row the same",
            Lines::AlongY => "a 1-D grating along y: every column the same",
            Lines::Crossed => "a crossed grating",
        },
        cell.taylor_terms()
    ));
    if !fresnel.polarised() {
        report.note(&format!(
            "{}: no polarised form, so TE and TM get the same reflectance (give --material for exact s and p)",
            fresnel.describe()
        ));
    }
    let answers = with_progress(report, w.len() as u64, "orders", |p| {
        cell.spectrum(l, w, fresnel.as_ref(), opts.normalisation, p)
    })?;
    if let Some(a) = answers.iter().find(|a| a.normalisation == "energy-row") {
        report.note(&format!(
            "{} channels at {:.0} nm: the efficiencies are scaled so that this light's orders conserve energy \
             (reciprocity is then approximate; the full scaling runs up to {} channels)",
            a.channels,
            a.wavelength_nm,
            iridis_diffraction::grating::MAX_SINKHORN_CHANNELS
        ));
    }
    Ok(Grating {
        surface: source.name().to_string(),
        method: opts.method,
        periods_nm: (lx, ly),
        samples: (patch.cols, patch.rows),
        lines: cell.lines(),
        reflector,
        polarised: fresnel.polarised(),
        normalisation: opts.normalisation,
        taylor_terms: cell.taylor_terms(),
        light: l,
        detector: opts.detector,
        answers,
    })
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
        if !covers || w.windows(2).any(|p| p[1] - p[0] > 10.0 + 1e-9) {
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

    /// The reflectance a detector sees at one wavelength: the orders inside its acceptance cone (fraction).
    pub fn detector_reflectance(&self, answer: &GratingAnswer) -> Option<f64> {
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
        let convergence: Vec<Value> = self
            .answers
            .iter()
            .map(|a| {
                json!({"wavelength_nm": a.wavelength_nm, "taylor_terms": self.taylor_terms,
                       "taylor_remainder_bound": iridis_diffraction::grating::TAYLOR_EPSILON,
                       "channels": a.channels, "normalisation": a.normalisation,
                       "normalisation_residual": a.normalisation_residual,
                       "kirchhoff_sum": a.kirchhoff_sum})
            })
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
            "unit_cell": {"period_x_nm": self.periods_nm.0, "period_y_nm": self.periods_nm.1,
                          "samples": [self.samples.0, self.samples.1],
                          "kind": match self.lines { Lines::AlongX => "1-D along x", Lines::AlongY => "1-D along y",
                                                     Lines::Crossed => "crossed" }},
            "light": {"theta_deg": deg(l[2].clamp(-1.0, 1.0).acos()), "phi_deg": deg(l[1].atan2(l[0])), "direction": l},
            "reflector": self.reflector,
            "polarised": self.polarised,
            "polarisation": "TE = s, TM = p, with respect to the plane of the light and the order (scalar model: no conversion)",
            "normalisation": self.normalisation.name(),
            "wavelength_nm": self.answers.iter().map(|a| a.wavelength_nm).collect::<Vec<f64>>(),
            "orders": orders,
            "reflected_total": totals,
            "transmitted_total": Value::Null,
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
