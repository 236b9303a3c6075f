//! Convergence sweeps (paper sec. 7, Figures 14–17): one method's BRDF map for each value of one parameter,
//! its CIEDE2000 error against a ground truth (by default that of the method's own model,
//! [`Method::model_truth`]), the periodic-extension error (periodic against finite-aperture ground truth) beside
//! it, a contact sheet and an error-against-parameter plot.
//!
//! Parameters and the methods that have them:
//! * `terms` — Taylor terms `N` (eq. 6, 10): reference, lookup, nmm, pq;
//! * `dlambda` — wavelength step Δλ of the spectral integral (eq. 9, 11; Figure 17): reference, lookup, nmm,
//!   pq, stam-periodic, stam-gaussian;
//! * `coherence` — coherence length `4σ_s` (Figure 16): every method; the ground truth is recomputed at the
//!   same coherence, so the error measures the method, not the change of physics;
//! * `uv-power`, `uv-resolution` — the lookup table's grid (sec. 5, Figure 14): lookup only.

use iridis_color::Xyz;
use iridis_diffraction::SpectralSetup;
use serde::Serialize;

use crate::compare::{delta_e_map, stats};
use crate::image::Pixels;
use crate::methods::{Method, Workbench};
use crate::{LabError, Progress};

/// A swept parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Param {
    Terms,
    DLambda,
    Coherence,
    UvPower,
    UvResolution,
}

impl Param {
    pub const ALL: [Param; 5] = [Param::Terms, Param::DLambda, Param::Coherence, Param::UvPower, Param::UvResolution];

    /// Axis label with unit.
    pub fn label(self) -> &'static str {
        match self {
            Param::Terms => "Taylor terms N",
            Param::DLambda => "wavelength step Δλ (nm)",
            Param::Coherence => "coherence length 4σs (µm)",
            Param::UvPower => "u-v grid exponent a",
            Param::UvResolution => "u-v samples per axis",
        }
    }

    /// The unit of the values in the JSON (`points[].value`): nm for lengths, none for counts and exponents.
    pub fn value_unit(self) -> &'static str {
        match self {
            Param::DLambda | Param::Coherence => "nm",
            Param::Terms | Param::UvPower | Param::UvResolution => "",
        }
    }

    /// Whether `method` has this parameter.
    pub fn applies_to(self, method: Method) -> bool {
        use Method::*;
        match self {
            Param::Terms => method.uses_taylor_terms(),
            Param::DLambda => !method.is_ground_truth(),
            Param::Coherence => true,
            Param::UvPower | Param::UvResolution => method == Lookup,
        }
    }

    /// The value as displayed (coherence in µm).
    pub fn display(self, v: f64) -> String {
        match self {
            Param::Coherence => format!("{} µm", v / 1000.0),
            Param::DLambda => format!("{v} nm"),
            Param::UvPower => format!("{v}"),
            _ => format!("{}", v.round() as i64),
        }
    }
}

iridis_color::names! {
    Param {
        Terms => "terms",
        DLambda => "dlambda",
        Coherence => "coherence",
        UvPower => "uv-power",
        UvResolution => "uv-resolution",
    }
    else |s| -> LabError { LabError::unknown_name("sweep parameter", s, Param::ALL.map(Param::name)) }
}

/// An error at one exposure: (exposure in RU, mean ΔE00, 95th percentile).
pub type ErrorAt = (f64, f64, f64);

/// The ΔE00 statistics of `image` against `truth` at each exposure.
fn errors_at(exposures: &[f64], image: &[Option<Xyz>], truth: &[Option<Xyz>]) -> Vec<ErrorAt> {
    exposures
        .iter()
        .map(|&x| {
            let s = stats(&delta_e_map(image, truth, x));
            (x, s.mean, s.p95)
        })
        .collect()
}

/// One value of the sweep.
#[derive(Debug, Clone, Serialize)]
pub struct Point {
    pub value: f64,
    /// CIEDE2000 against the ground truth at each exposure: (exposure, mean, p95).
    pub errors: Vec<(f64, f64, f64)>,
    /// The periodic-extension error at each exposure, (exposure, mean, p95): the periodic ground truth against
    /// the finite-aperture one at this point's settings — how far the two models of the patch part, whatever
    /// the method.
    pub extension: Vec<(f64, f64, f64)>,
    #[serde(skip)]
    pub image: Vec<Option<Xyz>>,
    /// The share of the ground truth's map shown as clipped white at each exposure
    /// ([`crate::compare::clipped_white`]).
    #[serde(skip)]
    pub truth_clipped: Vec<f64>,
}

/// Checks a sweep's values: positive, whole numbers where counts are meant, within each parameter's range.
pub fn check_values(param: Param, values: &[f64]) -> Result<(), LabError> {
    if values.is_empty() {
        return Err(LabError::invalid("give at least one value to sweep (--values …)"));
    }
    for &v in values {
        let bad = match param {
            Param::Terms => !(v >= 1.0 && v.fract() == 0.0 && v <= 200.0),
            Param::DLambda => !(v > 0.0 && v <= 100.0),
            Param::Coherence => !(v.is_finite() && v > 0.0),
            Param::UvPower => !(v.is_finite() && (1.0..=20.0).contains(&v)),
            Param::UvResolution => !(v.fract() == 0.0 && (3.0..=4001.0).contains(&v)),
        };
        if bad {
            return Err(LabError::invalid(format!(
                "{} = {v} is out of range ({})",
                param.name(),
                match param {
                    Param::Terms => "a whole number 1–200",
                    Param::DLambda => "above 0 nm, at most 100 nm",
                    Param::Coherence => "a positive length",
                    Param::UvPower => "1–20",
                    Param::UvResolution => "a whole number 3–4001",
                }
            )));
        }
    }
    Ok(())
}

/// Runs the sweep: the ground-truth images `against` and, for the periodic-extension error, the other aperture's
/// (once, or per value for `coherence`), then the method's image and error at each value. `against` is a ground
/// truth, usually `method.model_truth()`. `progress(values_done)`.
#[allow(clippy::too_many_arguments)]
pub fn run(
    bench: &Workbench,
    method: Method,
    param: Param,
    values: &[f64],
    pixels: &Pixels,
    exposures: &[f64],
    against: Method,
    progress: Progress,
) -> Result<(Vec<Option<Xyz>>, Vec<Point>), LabError> {
    if !against.is_ground_truth() {
        return Err(LabError::invalid(format!(
            "a sweep measures against a ground truth (ground-truth or ground-truth-periodic), not {against}"
        )));
    }
    if !param.applies_to(method) {
        let who: Vec<&str> = Method::ALL.iter().filter(|m| param.applies_to(**m)).map(|m| m.name()).collect();
        return Err(LabError::invalid(format!(
            "the {} method has no parameter '{}'; it applies to: {}",
            method.name(),
            param.name(),
            who.join(", ")
        )));
    }
    check_values(param, values)?;
    if param == Param::Coherence {
        // Every value before the first is computed, not at its turn minutes later.
        for &v in values {
            bench.patch.check_coherence(v)?;
        }
    }
    let image_of = |b: &Workbench, m: Method| -> Result<Vec<Option<Xyz>>, LabError> {
        let gt = b.evaluator(m, &crate::no_progress)?;
        b.render(gt.as_ref(), pixels, &crate::no_progress)
    };
    // The truth and the periodic-extension error at one setting.
    let truths_of = |b: &Workbench| -> Result<(Vec<Option<Xyz>>, Vec<ErrorAt>), LabError> {
        let periodic = image_of(b, Method::GroundTruthPeriodic)?;
        let finite = image_of(b, Method::GroundTruth)?;
        let extension = errors_at(exposures, &periodic, &finite);
        Ok((if against == Method::GroundTruth { finite } else { periodic }, extension))
    };
    let clipped_of = |truth: &[Option<Xyz>]| -> Vec<f64> {
        exposures.iter().map(|&x| crate::compare::clipped_white(truth, x)).collect()
    };
    // Computed once where the truth does not change with the value (every parameter but coherence).
    let (base_truth, base_extension) =
        if param == Param::Coherence { (Vec::new(), Vec::new()) } else { truths_of(bench)? };
    let base_clipped = clipped_of(&base_truth);
    let mut points = Vec::new();
    for (k, &v) in values.iter().enumerate() {
        let mut config = bench.config.clone();
        match param {
            Param::Terms => config.terms = Some(v as usize),
            Param::DLambda => {
                let s = &config.spectral;
                let l = s.wavelengths();
                let mut n = SpectralSetup::with_range(s.illuminant, s.observer, l[0], l[l.len() - 1], v)?;
                if let Some(light) = &config.light {
                    n = crate::methods::spectral_with_light(light, s.observer, l[0], l[l.len() - 1], v)?;
                }
                config.spectral = n;
            }
            Param::Coherence => config.coherence_nm = v,
            Param::UvPower => config.table.uv_power = v,
            Param::UvResolution => config.table.uv_resolution = v as usize,
        }
        let b = Workbench::new(bench.patch.clone(), config, bench.surface.clone())?;
        let e = b.evaluator(method, &crate::no_progress)?;
        let image = b.render(e.as_ref(), pixels, &crate::no_progress)?;
        let (errors, extension, truth_clipped) = if param == Param::Coherence {
            let (truth, extension) = truths_of(&b)?;
            (errors_at(exposures, &image, &truth), extension, clipped_of(&truth))
        } else {
            (errors_at(exposures, &image, &base_truth), base_extension.clone(), base_clipped.clone())
        };
        points.push(Point { value: v, errors, extension, image, truth_clipped });
        progress(k + 1);
    }
    Ok((base_truth, points))
}

/// Contact sheet: each value's map at `exposure_ru`, titled with the value and its mean ΔE.
pub fn contact_sheet(
    param: Param,
    method: Method,
    points: &[Point],
    pixels: &Pixels,
    exposure_ru: f64,
) -> Result<iridis_plot::RgbImage, LabError> {
    let mut tiles = Vec::new();
    for p in points {
        let img = crate::image::to_rgb(&p.image, pixels.width, pixels.height, exposure_ru);
        let err = p.errors.iter().find(|e| e.0 == exposure_ru).map(|e| e.1).unwrap_or(f64::NAN);
        let title = format!("{} {} = {}  (ΔE {:.2})", method.name(), param.name(), param.display(p.value), err);
        let tile = iridis_plot::ImagePlot::view_directions(title, &img, (420, 440)).render()?;
        tiles.push(tile);
    }
    let cols = (points.len() as f64).sqrt().ceil() as usize;
    Ok(crate::image::contact_sheet(&tiles, cols.max(1)))
}

/// The error-against-parameter plot: mean and 95th-percentile ΔE per exposure.
pub fn error_plot(param: Param, method: Method, points: &[Point]) -> Result<iridis_plot::RgbImage, LabError> {
    use iridis_plot::{LinePlot, Series};
    let xs: Vec<f64> =
        points.iter().map(|p| if param == Param::Coherence { p.value / 1000.0 } else { p.value }).collect();
    let mut plot = LinePlot::new(
        format!("{} against the ground truth: CIEDE2000 vs {}", method.name(), param.name()),
        param.label(),
        "ΔE00 (CIEDE2000)",
    );
    let exposures: Vec<f64> = points.first().map(|p| p.errors.iter().map(|e| e.0).collect()).unwrap_or_default();
    for (k, &x) in exposures.iter().enumerate() {
        let mean: Vec<f64> = points.iter().map(|p| p.errors[k].1).collect();
        let p95: Vec<f64> = points.iter().map(|p| p.errors[k].2).collect();
        let color = iridis_plot::PALETTE[k % iridis_plot::PALETTE.len()];
        plot = plot.series(Series::new(format!("mean, {x} RU"), &xs, &mean).with_color([color.0, color.1, color.2]));
        // Same exposure, same colour; the statistic is told by the line: mean solid, 95th percentile dashed.
        plot = plot.series(
            Series::new(format!("95th percentile, {x} RU"), &xs, &p95).with_color([color.0, color.1, color.2]).dashed(),
        );
    }
    if let Some(first) = exposures.first() {
        // The periodic-extension error at the first exposure, for scale: the models' own difference.
        let ext: Vec<f64> = points.iter().map(|p| p.extension.first().map(|e| e.1).unwrap_or(f64::NAN)).collect();
        let mut s = Series::new(format!("periodic vs finite ground truth, mean, {first} RU"), &xs, &ext)
            .with_color([120, 120, 120]);
        s.emphasis = false;
        plot = plot.series(s);
    }
    let lo = 0.0;
    let hi = points
        .iter()
        .flat_map(|p| p.errors.iter().map(|e| e.2).chain(p.extension.first().map(|e| e.1)))
        .fold(0.0f64, f64::max)
        .max(1e-3)
        * 1.1;
    plot.y_range = Some((lo, hi));
    Ok(plot.render()?)
}
