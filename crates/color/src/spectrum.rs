//! Sampled spectra on arbitrary, strictly increasing wavelength grids.

use std::path::Path;

/// Why a spectrum could not be built or read. Messages name the source, line and value.
#[derive(Debug, thiserror::Error)]
pub enum SpectrumError {
    #[error("{source_name}: cannot read: {message}")]
    Io { source_name: String, message: String },
    #[error("{source_name}:{line}: {message}")]
    Parse { source_name: String, line: usize, message: String },
    #[error("{0}")]
    Invalid(String),
}

/// How the fields of a line of a spectra text file are separated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Separators {
    /// Any of comma, semicolon, tab and space, mixed, empty fields dropped (two- and three-column files:
    /// `400, 0.5`, `400;0.5`, `400   0.5`).
    Any,
    /// The line's own separator — comma, else semicolon, else tab, else runs of spaces — with empty fields kept,
    /// so that column names may hold spaces and a missing value is an error (pavo's multi-column tables).
    OnePerLine,
}

/// A line of a spectra text file that holds data or a header: its number (from 1) and its fields, trimmed.
#[derive(Debug, Clone, PartialEq)]
pub struct TextRow<'a> {
    pub line: usize,
    pub text: &'a str,
    pub fields: Vec<&'a str>,
}

/// The lines of a spectra text file that are not blank and not `#` comments, split into fields: the one
/// reading of the text layout that spectra, sensitivity tables and n, k files share (each checks its own
/// columns and says what it expected).
pub fn text_rows(text: &str, separators: Separators) -> impl Iterator<Item = TextRow<'_>> {
    text.lines().enumerate().filter_map(move |(index, raw)| {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            return None;
        }
        let fields = match separators {
            Separators::Any => line.split([',', ';', '\t', ' ']).filter(|s| !s.is_empty()).collect(),
            Separators::OnePerLine => {
                let sep = [',', ';', '\t'].into_iter().find(|&c| line.contains(c));
                match sep {
                    Some(c) => line.split(c).map(str::trim).collect(),
                    None => line.split(' ').map(str::trim).filter(|s| !s.is_empty()).collect(),
                }
            }
        };
        Some(TextRow { line: index + 1, text: line, fields })
    })
}

/// A spectrum sampled at strictly increasing wavelengths (nm). Between samples it is linear; outside the
/// sampled range [`Spectrum::value_at`] holds the end values (the convention colour-science uses).
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    wavelengths_nm: Vec<f64>,
    values: Vec<f64>,
}

/// The unit a wavelength `x` "nm" was more likely given in, with `x` converted: "µm (0.7 µm is 700 nm)",
/// "metres (5.5e-7 m is 550 nm)" — the user's own number, not a fixed example.
fn unit_read_as_nm(x: f64) -> String {
    if x < 1e-4 {
        format!("metres ({} m is {} nm)", short_number(x), short_number(x * 1e9))
    } else {
        format!("µm ({} µm is {} nm)", short_number(x), short_number(x * 1e3))
    }
}

/// Refuses wavelengths that end below 20 nm (the far UV; every model here is for 300–830 nm light and a little
/// beyond): such numbers are µm or metres read as nm (0.4–0.7 "nm" gave a grey colour with a range warning).
pub fn check_nanometres(wavelengths_nm: &[f64]) -> Result<(), SpectrumError> {
    let hi = wavelengths_nm.iter().copied().filter(|w| w.is_finite()).fold(f64::NEG_INFINITY, f64::max);
    if hi > 0.0 && hi < 20.0 {
        return Err(SpectrumError::Invalid(format!(
            "the wavelengths reach only {hi} nm: that looks like {}; wavelengths are in nm",
            unit_read_as_nm(hi)
        )));
    }
    Ok(())
}

/// The shortest light the diffraction models take (nm): the extreme UV and up. Below it a wavelength is µm or
/// metres read as nm (a grating "at 0.55 nm" listed 3637 orders; a test bench "from 0.38 nm" read a period).
pub const SHORTEST_LIGHT_NM: f64 = 10.0;

/// Refuses a shortest wavelength below [`SHORTEST_LIGHT_NM`], naming the likely unit.
pub fn check_light_nanometres(shortest_nm: f64) -> Result<(), SpectrumError> {
    if shortest_nm.is_finite() && shortest_nm > 0.0 && shortest_nm < SHORTEST_LIGHT_NM {
        // A unit is named only where the number is one (0.55 for µm, 5.5e-7 for metres), not for 9.9 nm.
        let unit = if shortest_nm < 2.0 {
            format!(": it looks like {}; wavelengths are in nm", unit_read_as_nm(shortest_nm))
        } else {
            String::new()
        };
        return Err(SpectrumError::Invalid(format!(
            "a wavelength of {shortest_nm} nm is shorter than the light these models take ({SHORTEST_LIGHT_NM} nm and \
             up){unit}"
        )));
    }
    Ok(())
}

impl Spectrum {
    /// Builds a spectrum, checking that the grid has at least two samples, is strictly increasing and that
    /// every number is finite.
    pub fn new(wavelengths_nm: Vec<f64>, values: Vec<f64>) -> Result<Self, SpectrumError> {
        if wavelengths_nm.len() != values.len() {
            return Err(SpectrumError::Invalid(format!(
                "{} wavelengths but {} values",
                wavelengths_nm.len(),
                values.len()
            )));
        }
        if wavelengths_nm.len() < 2 {
            return Err(SpectrumError::Invalid("a spectrum needs at least two samples".into()));
        }
        check_nanometres(&wavelengths_nm)?;
        for (i, (&w, &v)) in wavelengths_nm.iter().zip(&values).enumerate() {
            if !w.is_finite() || !v.is_finite() {
                return Err(SpectrumError::Invalid(format!("sample {i} is not finite: ({w}, {v})")));
            }
            if i > 0 && w <= wavelengths_nm[i - 1] {
                return Err(SpectrumError::Invalid(format!(
                    "wavelengths must increase: {} nm follows {} nm",
                    w,
                    wavelengths_nm[i - 1]
                )));
            }
        }
        Ok(Self { wavelengths_nm, values })
    }

    /// A spectrum sampled from a function on a uniform grid `from, from + step, …, ≤ to`.
    pub fn from_fn(from_nm: f64, to_nm: f64, step_nm: f64, f: impl Fn(f64) -> f64) -> Result<Self, SpectrumError> {
        let grid = uniform_grid(from_nm, to_nm, step_nm)?;
        let values = grid.iter().map(|&w| f(w)).collect();
        Self::new(grid, values)
    }

    /// Reads a CSV or whitespace-separated text with exactly two columns, wavelength (nm) and value. Blank
    /// lines and lines starting with `#` are skipped; the first other line may be a non-numeric header. Any
    /// later non-numeric row, or a row with other than two columns, is an error naming its line.
    pub fn from_csv_str(text: &str, source_name: &str) -> Result<Self, SpectrumError> {
        let mut wavelengths = Vec::new();
        let mut values = Vec::new();
        let mut header_allowed = true;
        for TextRow { line: line_no, text: line, fields } in text_rows(text, Separators::Any) {
            let parse = |s: &str| s.trim().parse::<f64>();
            let parsed: Vec<_> = fields.iter().map(|f| parse(f)).collect();
            if parsed.iter().any(|p| p.is_err()) {
                if header_allowed && wavelengths.is_empty() {
                    header_allowed = false;
                    continue;
                }
                let bad = fields.iter().zip(&parsed).find(|(_, p)| p.is_err()).map(|(f, _)| *f).unwrap_or("");
                return Err(SpectrumError::Parse {
                    source_name: source_name.into(),
                    line: line_no,
                    message: format!("'{bad}' is not a number (expected: wavelength_nm, value)"),
                });
            }
            header_allowed = false;
            if fields.len() != 2 {
                return Err(SpectrumError::Parse {
                    source_name: source_name.into(),
                    line: line_no,
                    message: format!("expected two columns (wavelength_nm, value), found {} in '{line}'", fields.len()),
                });
            }
            let (w, v) =
                (parsed[0].as_ref().copied().unwrap_or(f64::NAN), parsed[1].as_ref().copied().unwrap_or(f64::NAN));
            let err =
                |message: String| SpectrumError::Parse { source_name: source_name.into(), line: line_no, message };
            if !w.is_finite() || w <= 0.0 {
                return Err(err(format!("wavelength '{}' must be a positive finite number of nm", fields[0])));
            }
            if !v.is_finite() {
                return Err(err(format!("value '{}' is not finite", fields[1])));
            }
            if let Some(&last) = wavelengths.last() {
                if w <= last {
                    return Err(err(format!("wavelengths must increase: {w} nm follows {last} nm")));
                }
            }
            wavelengths.push(w);
            values.push(v);
        }
        if wavelengths.len() < 2 {
            return Err(SpectrumError::Parse {
                source_name: source_name.into(),
                line: text.lines().count(),
                message: format!("found {} data rows; a spectrum needs at least two", wavelengths.len()),
            });
        }
        Self::new(wavelengths, values)
    }

    /// Reads a spectrum file (see [`Spectrum::from_csv_str`]).
    pub fn from_csv_path(path: &Path) -> Result<Self, SpectrumError> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path)
            .map_err(|e| SpectrumError::Io { source_name: name.clone(), message: e.to_string() })?;
        Self::from_csv_str(&text, &name)
    }

    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }
    pub fn values(&self) -> &[f64] {
        &self.values
    }
    /// First and last sampled wavelength (nm).
    pub fn range_nm(&self) -> (f64, f64) {
        (self.wavelengths_nm[0], *self.wavelengths_nm.last().unwrap_or(&self.wavelengths_nm[0]))
    }

    /// Linear interpolation; ends held constant outside the sampled range.
    pub fn value_at(&self, wavelength_nm: f64) -> f64 {
        interpolate_linear(&self.wavelengths_nm, &self.values, wavelength_nm)
    }

    /// The same spectrum sampled on another grid (linear interpolation, ends held).
    pub fn resample(&self, grid_nm: &[f64]) -> Result<Self, SpectrumError> {
        Self::new(grid_nm.to_vec(), grid_nm.iter().map(|&w| self.value_at(w)).collect())
    }

    /// `∫ s(λ) dλ` over the sampled range by the trapezoid rule.
    pub fn integrate(&self) -> f64 {
        trapezoid_weights(&self.wavelengths_nm).iter().zip(&self.values).map(|(w, v)| w * v).sum()
    }

    /// Multiplies two spectra sample by sample on this spectrum's grid.
    pub fn mul(&self, other: &Spectrum) -> Spectrum {
        Spectrum {
            wavelengths_nm: self.wavelengths_nm.clone(),
            values: self.wavelengths_nm.iter().zip(&self.values).map(|(&w, &v)| v * other.value_at(w)).collect(),
        }
    }
}

/// Linear interpolation in a table with strictly increasing `xs`; holds the end values outside.
pub fn interpolate_linear(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let n = xs.len();
    if n == 0 {
        return 0.0;
    }
    if x <= xs[0] {
        return ys[0];
    }
    if x >= xs[n - 1] {
        return ys[n - 1];
    }
    let i = xs.partition_point(|&v| v <= x) - 1;
    let t = (x - xs[i]) / (xs[i + 1] - xs[i]);
    ys[i] + t * (ys[i + 1] - ys[i])
}

/// Trapezoid-rule weights for a strictly increasing grid: `∫ f ≈ Σ wᵢ f(xᵢ)`.
pub fn trapezoid_weights(xs: &[f64]) -> Vec<f64> {
    let n = xs.len();
    let mut w = vec![0.0; n];
    for i in 0..n.saturating_sub(1) {
        let h = 0.5 * (xs[i + 1] - xs[i]);
        w[i] += h;
        w[i + 1] += h;
    }
    w
}

/// The most samples a wavelength grid may hold (one per 0.04 pm over 380–780 nm).
pub const MAX_GRID_SAMPLES: usize = 10_000_000;

/// `x` as a person reads it: at most four decimals, trailing zeros dropped (`5`, `2.5`, `694.0001`), and in
/// exponent form with five significant digits beyond a billion or below a ten-thousandth (`1e300`, `1e-17`,
/// `3.3333e9`), not hundreds of digits.
pub fn short_number(x: f64) -> String {
    if x != 0.0 && x.is_finite() && !(1e-4..1e9).contains(&x.abs()) {
        // Five significant digits, trailing zeros dropped: 1e300, 2.5e-17, 3.3333e9.
        let e = format!("{x:.4e}");
        let (mantissa, exponent) = e.split_once('e').unwrap_or((&e, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    format!("{x:.4}").trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `from, from + step, …` up to `to`, which is the last sample where the step divides the range (within a
/// millionth of a step); see [`range_grid`] for a range a person gave.
pub fn uniform_grid(from_nm: f64, to_nm: f64, step_nm: f64) -> Result<Vec<f64>, SpectrumError> {
    if !(from_nm.is_finite() && to_nm.is_finite() && step_nm.is_finite()) || step_nm <= 0.0 || to_nm < from_nm {
        return Err(SpectrumError::Invalid(format!(
            "bad wavelength range {from_nm} nm to {to_nm} nm in steps of {step_nm} nm (need from ≤ to, step > 0)"
        )));
    }
    // Counted in f64 first: a count past usize (a 1e-17 nm step, a 1e300 nm end) would wrap to an empty grid.
    let n = ((to_nm - from_nm) / step_nm + 1e-6).floor() + 1.0;
    if n > MAX_GRID_SAMPLES as f64 {
        return Err(SpectrumError::Invalid(format!(
            "{} nm to {} nm in steps of {} nm is {} samples, more than {MAX_GRID_SAMPLES}: give a larger step or a \
             shorter range",
            short_number(from_nm),
            short_number(to_nm),
            short_number(step_nm),
            short_number(n)
        )));
    }
    Ok((0..n as usize).map(|i| from_nm + i as f64 * step_nm).collect())
}

/// [`uniform_grid`] for a range a person gave (`--from 400nm --to 700nm --step 5nm`): both ends are samples,
/// so a step that does not divide the range is refused, naming where the grid would end — rather than
/// silently stopping short of `to` (400–700 nm in 7 nm steps ends at 694 nm).
pub fn range_grid(from_nm: f64, to_nm: f64, step_nm: f64) -> Result<Vec<f64>, SpectrumError> {
    let grid = uniform_grid(from_nm, to_nm, step_nm)?;
    if whole_steps(from_nm, to_nm, step_nm).is_err() {
        let last = grid[grid.len() - 1];
        let nm = short_number;
        return Err(SpectrumError::Invalid(format!(
            "{}–{} nm is not a whole number of {} nm steps: the last wavelength would be {} nm; give a step that \
             divides the {} nm range, or end at {} nm",
            nm(from_nm),
            nm(to_nm),
            nm(step_nm),
            nm(last),
            nm(to_nm - from_nm),
            nm(last)
        )));
    }
    Ok(grid)
}

/// The number of `step`s from `from` to `to` where it is whole (within a millionth of a step), else their
/// fractional count: whether a range given as its ends and a step has both ends on its grid. A step longer
/// than a range of two distinct ends is not whole (it would drop `to`), however small the fraction.
pub(crate) fn whole_steps(from: f64, to: f64, step: f64) -> Result<usize, f64> {
    let steps = (to - from) / step;
    // Two ends that differ by more than rounding (1100 nm against 1.1 µm is 2e-13 apart) with less than half a
    // step between them are not whole however small the fraction: the step is longer than the range.
    let distinct = to - from > 1e-9 * from.abs().max(to.abs());
    if (steps - steps.round()).abs() > 1e-6 || (distinct && steps.round() == 0.0) {
        Err(steps)
    } else {
        Ok(steps.round() as usize)
    }
}
