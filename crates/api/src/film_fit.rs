//! Where the light goes in a stack (`iridis thinfilm profile`: absorption per layer, |E|², absorbed power and
//! flux against depth; `iridis_thinfilm::depth`) and fitting a stack to a measured spectrum (`iridis thinfilm
//! fit`; `iridis-filmfit`), with their text, CSV, JSON and plots — Python's `iridis.film.profile` and
//! `iridis.film.fit` call the same functions.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{anyhow, bail, Context, Result};
use iridis_color::spectrum::short_number;
use iridis_color::units::parse_length_nm;
use iridis_filmfit::{FitOptions, FitResult, Quantity, ReadOptions, Reading, Spread, Template};
use iridis_plot::{LinePlot, RgbImage, Series};
use iridis_thinfilm::depth::{depth_profile, DepthProfile};
use iridis_thinfilm::Stack;
use serde_json::json;

use crate::film::{fmt_deg, parse_stack, stack_title};
use crate::report::Report;

// ----------------------------------------------------------------------------------------------------------
// Profile

/// The depth window `FROM:TO` with units (nm below the first interface), FROM above TO.
pub fn parse_depth(w: &str) -> Result<(f64, f64)> {
    let bad = || anyhow!("--depth '{w}': write FROM:TO with units, e.g. --depth=-20nm:200nm");
    let (from, to) = w.split_once(':').ok_or_else(bad)?;
    match (parse_length_nm(from.trim()), parse_length_nm(to.trim())) {
        (Ok(f), Ok(t)) if f < t => Ok((f, t)),
        (Ok(f), Ok(t)) => bail!("--depth {f} nm:{t} nm is empty: FROM must be above (less than) TO"),
        (Err(e), _) | (_, Err(e)) => bail!("--depth '{w}': {}", e.0),
    }
}

/// Where the light goes at one wavelength and angle.
#[derive(Debug, Clone)]
pub struct FilmProfile {
    pub stack: Stack,
    pub title: String,
    pub wavelength_nm: f64,
    pub angle_rad: f64,
    /// `avg`, `s` or `p`, as given (lower case).
    pub polarization: String,
    pub profile: DepthProfile,
}

/// The profile of `stack` at `wavelength_nm` and `angle_rad` for `polarization` (`avg`, `s`, `p`) on `points`
/// depths over `depth` (`FROM:TO`; default [`iridis_thinfilm::depth::default_window`]); what a reader should
/// know about the window is said to `report` and kept in `profile.notes` and `profile.warnings`.
pub fn profile(
    stack: &str,
    wavelength_nm: f64,
    angle_rad: f64,
    polarization: &str,
    points: usize,
    depth: Option<&str>,
    report: &dyn Report,
) -> Result<FilmProfile> {
    let parsed = parse_stack(stack)?;
    let p = crate::film::parse_polarization(polarization)?;
    let window = depth.map(parse_depth).transpose()?;
    if !(2..=1_000_000).contains(&points) {
        bail!("--points must be between 2 and 1000000");
    }
    // Coherent and mixed stacks alike (in inc: layers: incoherent Beer–Lambert beams, no interference).
    let d = depth_profile(&parsed, wavelength_nm, angle_rad, p, points, window)?;
    // The energy balance is an identity of the flux formulas; more than rounding means a bug, not bad input.
    if d.balance.abs() > 1e-9 {
        bail!("internal error: R + T + ΣA − 1 = {:e} (please report with the stack)", d.balance);
    }
    d.notes.iter().for_each(|n| report.note(n));
    d.warnings.iter().for_each(|w| report.warn(w));
    Ok(FilmProfile {
        stack: parsed,
        title: stack_title(stack),
        wavelength_nm,
        angle_rad,
        polarization: p.name().to_string(),
        profile: d,
    })
}

impl FilmProfile {
    /// |E|² and the absorbed power density against depth.
    pub fn plot(&self) -> Result<RgbImage> {
        let d = &self.profile;
        let ab: Vec<f64> = d.absorption_per_nm.iter().map(|v| 1000.0 * v).collect();
        let mut plot = LinePlot::new(
            format!("{}  at {} nm, {}°", self.title, self.wavelength_nm, fmt_deg(self.angle_rad)),
            format!("depth below the first interface (nm); layers end at 0 and {} nm", d.depth_nm),
            "|E|² (incident = 1); absorbed power (fraction per µm)",
        )
        .series(Series::new("|E|²", &d.z_nm, &d.e2))
        .series(Series::new("absorbed power density (1/µm)", &d.z_nm, &ab));
        plot.x_range = Some((d.z_nm[0], d.z_nm[d.z_nm.len() - 1]));
        Ok(plot.render()?)
    }

    /// What `--json` prints (docs/json.md).
    pub fn to_json(&self) -> serde_json::Value {
        let d = &self.profile;
        let prof = json!({
            "z_nm": d.z_nm, "medium": d.medium, "E2": d.e2, "absorption_per_nm": d.absorption_per_nm, "flux": d.flux,
        });
        json!({
            "stack": self.stack.to_string(), "wavelength_nm": self.wavelength_nm, "angle_deg": self.angle_rad.to_degrees(),
            "polarization": self.polarization, "R": d.r, "T": d.t, "layers": d.layer_names, "A_layers": d.layers,
            "A_substrate": d.substrate, "balance": d.balance, "profile": prof, "notes": d.notes,
            "units": "R, T, A and flux are fractions of the incident power; absorption_per_nm per nm of depth; E2 \
                      relative to the incident wave; z_nm below the first interface",
            "warnings": d.warnings,
        })
    }

    /// The profile as CSV: z_nm, medium, E2, absorption_per_nm, flux.
    pub fn csv(&self) -> String {
        let d = &self.profile;
        let mut out = String::from("z_nm,medium,E2,absorption_per_nm,flux\n");
        for i in 0..d.z_nm.len() {
            let _ = writeln!(out, "{},{},{},{},{}", d.z_nm[i], d.medium[i], d.e2[i], d.absorption_per_nm[i], d.flux[i]);
        }
        out
    }

    /// Where the light goes, for people.
    pub fn text(&self) -> String {
        let d = &self.profile;
        let mut o = format!("stack  {}\n", self.stack);
        let _ = writeln!(o, "{} nm at {}°, {}", self.wavelength_nm, fmt_deg(self.angle_rad), self.polarization);
        let _ = writeln!(o, "{:<40} {:>12}", "where the light goes", "fraction");
        let _ = writeln!(o, "{:<40} {:>12.7}", "reflected (R)", d.r);
        for (i, (n, v)) in d.layer_names.iter().zip(d.layers.iter()).enumerate() {
            let _ = writeln!(o, "{:<40} {:>12.7}", format!("absorbed in layer {} ({n})", i + 1), v);
        }
        if d.substrate > 0.0 {
            let _ = writeln!(o, "{:<40} {:>12.7}", "absorbed in the substrate", d.substrate);
        }
        let _ = writeln!(o, "{:<40} {:>12.7}", "transmitted (T)", d.t);
        let _ = writeln!(o, "{:<40} {:>12.1e}", "R + T + ΣA − 1", d.balance);
        // The samples are not printed here: say how many were taken, and where they are (else --points and
        // --depth would seem to do nothing).
        if let (Some(top), Some(bottom)) = (d.z_nm.first(), d.z_nm.last()) {
            let _ = writeln!(
                o,
                "profile: {} depth samples, z from {top:.1} to {bottom:.1} nm (|E|², absorption: CSV, JSON, plot)",
                d.z_nm.len()
            );
        }
        o
    }
}

// ----------------------------------------------------------------------------------------------------------
// Fit

/// χ²/dof (with σ = 1) below which a fit meets its data to round-off: a computed spectrum gives ~1e-32, a measured
/// one its noise squared (~1e-6 for 0.1 %).
pub const ROUND_OFF_CHI2: f64 = 1e-20;

/// What to fit and how the measured file is read (`iridis thinfilm fit`'s options; with the feature `cli`, its
/// flags).
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct FitRequest {
    /// The stack with free parameters {NAME=START:LOW..HIGH}, e.g. "air | SiO2 {d1=100nm:50nm..500nm} | Si".
    #[cfg_attr(feature = "cli", arg(long))]
    pub stack: String,
    /// Angle of incidence (0deg–90deg).
    #[cfg_attr(feature = "cli", arg(long = "angle", value_name = "ANGLE", default_value = "0deg"))]
    #[cfg_attr(feature = "cli", arg(value_parser = crate::args::angle_rad))]
    pub angle_rad: f64,
    /// What was measured: R, T (unpolarised) or psi-delta (ellipsometry, degrees).
    #[cfg_attr(feature = "cli", arg(long, default_value = "R"))]
    pub quantity: String,
    /// 1σ measurement uncertainty: a number (same for every point) or the name of a CSV column (for
    /// psi-delta two names, "spsi,sdelta"). The weights are 1/σ². Without it σ is estimated from the scatter.
    // At most one of `sigma` and `weights`.
    #[cfg_attr(feature = "cli", arg(long, conflicts_with = "weights"))]
    pub sigma: Option<String>,
    /// Weights w = 1/σ² of the measured values: a number (the same for every point), the name of a CSV
    /// column ("w_psi,w_delta" for psi-delta), or a separate CSV file with wavelength_nm and w (w_psi and
    /// w_delta) in the measurement's rows. Equivalent to --sigma 1/√w.
    #[cfg_attr(feature = "cli", arg(long))]
    pub weights: Option<String>,
    /// Grid points per thickness range for the multi-start search (0: automatic, about one per 10 nm;
    /// 1: a single local fit from the start values).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 0))]
    pub grid: usize,
    /// The columns to fit, by header name or number from 1: wavelength then R (or T), or wavelength, psi,
    /// delta, e.g. --columns "Wavelength (nm),R sample" or --columns 1,3. Default: found from the header.
    #[cfg_attr(feature = "cli", arg(long, value_name = "WL,VALUE[,VALUE]"))]
    pub columns: Option<String>,
    /// The values are in percent (`Some(true)`) or fractions (`Some(false)`); `None`: detected and said. The
    /// flag `--percent` gives `Some(true)`.
    #[cfg_attr(feature = "cli", arg(long, num_args = 0, default_missing_value = "true"))]
    #[cfg_attr(feature = "cli", arg(help = PERCENT_HELP))]
    pub percent: Option<bool>,
    /// Fit only wavelengths from this one on (with unit, e.g. 400nm).
    #[cfg_attr(feature = "cli", arg(long = "from", value_name = "FROM", value_parser = crate::args::length_nm))]
    pub from_nm: Option<f64>,
    /// Fit only wavelengths up to this one (with unit, e.g. 826nm).
    #[cfg_attr(feature = "cli", arg(long = "to", value_name = "TO", value_parser = crate::args::length_nm))]
    pub to_nm: Option<f64>,
}

/// `--percent`'s help: the command line cannot say "fractions", so the detection is the default.
#[cfg(feature = "cli")]
const PERCENT_HELP: &str =
    "The values are in percent (default: detected from a \"%\" in the header or values above 1.5, and said)";

/// A fit with what was read.
#[derive(Debug, Clone)]
pub struct FilmFit {
    pub request: FitRequest,
    pub quantity: Quantity,
    pub template: Template,
    /// The measured file as named.
    pub source: String,
    pub reading: Reading,
    pub result: FitResult,
    pub seconds: f64,
}

/// Reads the measured spectrum in `path` as the request says and fits the stack to it; warnings (a grid too
/// coarse for the stack's fringes, a parameter on a bound of its range) go to `report`.
pub fn fit_file(path: &Path, request: &FitRequest, report: &dyn Report) -> Result<FilmFit> {
    let (o, template) = (read_options(request)?, Template::parse(&request.stack)?);
    let text = std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let source = path.display().to_string();
    let reading = iridis_filmfit::read(&text, &source, &o, &|p| std::fs::read_to_string(p).map_err(|e| e.to_string()))?;
    fit_reading(reading, template, o.quantity, source, request, report)
}

/// [`fit_file`] of a measurement given as arrays (Python's `fit((wavelengths_nm, values[, sigma]))`): wavelengths
/// in nm, values as fractions unless the request says percent, ψ and Δ interleaved; `--from`/`--to`, `--sigma`
/// or `--weights` (a number) apply as to a file, `--columns` is refused.
pub fn fit_arrays(
    wavelength_nm: Vec<f64>,
    values: Vec<f64>,
    sigma: Option<Vec<f64>>,
    request: &FitRequest,
    report: &dyn Report,
) -> Result<FilmFit> {
    let (o, template) = (read_options(request)?, Template::parse(&request.stack)?);
    let reading = iridis_filmfit::read_arrays(wavelength_nm, values, sigma, &o)?;
    fit_reading(reading, template, o.quantity, "measured (arrays)".into(), request, report)
}

/// How the request reads a measurement.
fn read_options(request: &FitRequest) -> Result<ReadOptions> {
    let mut o = ReadOptions::new(request.quantity.parse()?);
    o.columns = request.columns.clone();
    o.percent = request.percent;
    o.from_nm = request.from_nm;
    o.to_nm = request.to_nm;
    o.spread = match (&request.sigma, &request.weights) {
        (Some(_), Some(_)) => bail!("--sigma and --weights say the same (the weights are 1/σ²): give one"),
        (Some(s), None) => Some((s.clone(), Spread::Sigma)),
        (None, Some(w)) => Some((w.clone(), Spread::Weight)),
        (None, None) => None,
    };
    Ok(o)
}

/// The fit of what was read, with the warnings of [`fit_file`].
fn fit_reading(
    reading: Reading,
    template: Template,
    quantity: Quantity,
    source: String,
    request: &FitRequest,
    report: &dyn Report,
) -> Result<FilmFit> {
    let mut sorted = reading.data.wavelength_nm.clone();
    sorted.sort_by(f64::total_cmp);
    // Rows at one wavelength are one measurement each: said, and a fit with no more distinct wavelengths than
    // parameters is refused (19 rows at 500 nm fitted a thickness "121.5 ± 4.8 nm", one of a periodic family).
    let mut distinct = sorted.clone();
    distinct.dedup();
    let repeated = sorted.len() - distinct.len();
    if distinct.len() <= template.params.len() {
        bail!(
            "{} rows at {} distinct wavelength{} cannot fix {} fitted parameter{}: a film's spectrum repeats with its \
             thickness, so a fit needs more wavelengths than parameters",
            sorted.len(),
            distinct.len(),
            if distinct.len() == 1 { "" } else { "s" },
            template.params.len(),
            if template.params.len() == 1 { "" } else { "s" }
        );
    }
    if repeated > 0 {
        report.warn(&format!(
            "{repeated} of the {} rows repeat a wavelength already read: each counts as its own measurement, so those \
             wavelengths weigh more in χ² (average repeated measurements first if they are one)",
            sorted.len()
        ));
    }
    if let Some(w) = iridis_thinfilm::sampling::check(&template.base, request.angle_rad, &sorted) {
        report.warn(&format!("the measured wavelengths: {}", w.message));
    }
    let thicknesses = template.thickness_params().len();
    if request.grid > 1 && thicknesses == 0 {
        bail!(
            "--grid {} would be ignored: it spaces the multi-start search over the fitted thicknesses' ranges \
             (e.g. {{d=120nm:50nm..300nm}}), and this stack fits none; one local fit is run",
            request.grid
        );
    }
    let cap = iridis_filmfit::fit::max_grid_points(thicknesses);
    if request.grid > cap {
        report.warn(&format!(
            "--grid {}: at most {cap} points a thickness range with {thicknesses} thicknesses fitted (about 4000 \
             starts in all), so {cap}",
            request.grid
        ));
    }
    let opt = FitOptions { angle_rad: request.angle_rad, quantity, grid: request.grid, ..FitOptions::default() };
    let t0 = Instant::now();
    let result = iridis_filmfit::fit(&template, &reading.data, &opt)?;
    let seconds = t0.elapsed().as_secs_f64();
    for (p, at) in template.params.iter().zip(&result.at_bound) {
        if *at {
            report.warn(&format!(
                "{} ended on a bound of its range {}..{}: widen the range; its uncertainty is not meaningful",
                p.name, p.lo, p.hi
            ));
        }
    }
    Ok(FilmFit { request: request.clone(), quantity, template, source, reading, result, seconds })
}

impl FilmFit {
    /// The fitted curve: wavelength_nm, measured, fitted, residual.
    pub fn csv(&self) -> String {
        let (data, r) = (&self.reading.data, &self.result);
        let mut out = String::from("wavelength_nm,measured,fitted,residual\n");
        let k = self.quantity.width();
        for (i, w) in data.wavelength_nm.iter().enumerate() {
            for j in 0..k {
                let (m, f) = (data.values[i * k + j], r.fitted[i * k + j]);
                let _ = writeln!(out, "{w},{m},{f},{}", m - f);
            }
        }
        out
    }

    /// Measured against fitted.
    pub fn plot(&self) -> Result<RgbImage> {
        let (data, r, quantity) = (&self.reading.data, &self.result, self.quantity);
        let k = quantity.width();
        let labels: &[&str] = if k == 2 { &["ψ (°)", "Δ (°)"] } else { &[quantity.name()] };
        let mut plot = LinePlot::new(
            format!("measured and fitted {}, χ²/dof = {:.3}", quantity.name(), r.reduced_chi2),
            "wavelength (nm)",
            if k == 2 { "ψ, Δ (degrees)" } else { "fraction of incident power" },
        );
        for (j, label) in labels.iter().enumerate() {
            let m: Vec<f64> = (0..data.wavelength_nm.len()).map(|i| data.values[i * k + j]).collect();
            let f: Vec<f64> = (0..data.wavelength_nm.len()).map(|i| r.fitted[i * k + j]).collect();
            let mut meas = Series::new(format!("measured {label}"), &data.wavelength_nm, &m);
            meas.emphasis = false;
            plot = plot.series(meas).series(Series::new(format!("fitted {label}"), &data.wavelength_nm, &f));
        }
        Ok(plot.render()?)
    }

    /// What `--json` prints (docs/json.md).
    pub fn to_json(&self) -> serde_json::Value {
        let (r, data, reading) = (&self.result, &self.reading.data, &self.reading);
        json!({
            "stack": self.request.stack, "quantity": self.quantity.name(), "angle_deg": self.request.angle_rad.to_degrees(),
            "names": r.names, "units": self.template.params.iter().map(|p| p.unit()).collect::<Vec<_>>(),
            "values": r.values, "sigma": r.sigma, "correlation": r.correlation,
            "chi2": r.chi2, "dof": r.dof, "reduced_chi2": r.reduced_chi2, "sigma_given": r.sigma_given,
            "at_bound": r.at_bound, "starts": r.starts_tried, "evaluations": r.evaluations, "jacobian": r.jacobian, "seconds": self.seconds,
            "fitted": r.fitted, "wavelength_nm": data.wavelength_nm, "measured": data.values,
            "read": { "columns": reading.columns, "percent": reading.percent, "notes": reading.notes },
            "notes": self.notes(),
        })
    }

    /// How the uncertainties were found, where no σ was given (text and JSON alike); below [`ROUND_OFF_CHI2`] the
    /// data are the model's own.
    pub fn notes(&self) -> Vec<String> {
        let r = &self.result;
        let mut notes = Vec::new();
        if !r.sigma_given {
            notes.push(
                "no --sigma or --weights: χ² uses σ = 1 and the uncertainties are scaled by √(χ²/dof), i.e. σ is \
                 estimated from the scatter"
                    .to_string(),
            );
            // Round-off, not noise: a measured spectrum's χ²/dof with σ = 1 is about its noise², ~1e-6.
            if r.reduced_chi2 < ROUND_OFF_CHI2 {
                notes.push(format!(
                    "the model meets the data to round-off (χ²/dof = {}, as for computed spectra): the scatter is \
                     nil, and so are the uncertainties; give --sigma (the measurement's noise) for uncertainties",
                    short_number(r.reduced_chi2)
                ));
            }
        }
        notes
    }

    /// The values with 1σ, χ² and the correlation matrix, for people.
    pub fn text(&self) -> String {
        let (r, data, params) = (&self.result, &self.reading.data, &self.template.params);
        let mut o = format!("stack     {}\n", self.request.stack);
        let _ = writeln!(
            o,
            "data      {} ({} wavelengths, {} at {}°)",
            self.source,
            data.wavelength_nm.len(),
            self.quantity.name(),
            fmt_deg(self.request.angle_rad)
        );
        for note in &self.reading.notes {
            let _ = writeln!(o, "read      {note}");
        }
        let _ = writeln!(o, "{:<12} {:>16} {:>14}", "parameter", "value", "1σ");
        for (k, p) in params.iter().enumerate() {
            let _ = writeln!(o, "{:<12} {:>16.6} {:>14.3e} {}", p.name, r.values[k], r.sigma[k], p.unit());
        }
        // Small χ² (σ = 1 on fractions) in exponent form: 3.3393e-6, not 0.0000.
        let _ = writeln!(
            o,
            "χ² = {} for {} degrees of freedom (χ²/dof = {})",
            short_number(r.chi2),
            r.dof,
            short_number(r.reduced_chi2)
        );
        let notes = self.notes();
        if let Some(first) = notes.first() {
            let _ = writeln!(o, "{first}");
        }
        for n in notes.iter().skip(1) {
            let _ = writeln!(o, "note: {n}");
        }
        if params.len() > 1 {
            o += "correlation\n";
            let mut head = format!("{:<12}", "");
            for p in params {
                let _ = write!(head, " {:>8}", p.name);
            }
            let _ = writeln!(o, "{head}");
            for (k, p) in params.iter().enumerate() {
                let mut row = format!("{:<12}", p.name);
                for v in &r.correlation[k] {
                    let _ = write!(row, " {v:>8.3}");
                }
                let _ = writeln!(o, "{row}");
            }
        }
        let _ = writeln!(
            o,
            "{} starts searched, {} spectra evaluated, {} derivatives, {:.3} s",
            r.starts_tried, r.evaluations, r.jacobian, self.seconds
        );
        o
    }
}
