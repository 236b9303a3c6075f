//! Sampled curves (sensitivities, lights, transmittances) and multi-column spectra tables.

use std::path::Path;

use crate::VisionError;
use iridis_color::spectrum::{text_rows, Separators, TextRow};

/// A curve sampled at strictly increasing wavelengths, linear between samples and **zero outside** them (a
/// receptor is blind, and a tabulated light dark, where nothing was measured).
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    wavelengths_nm: Vec<f64>,
    values: Vec<f64>,
}

impl Curve {
    /// Checks that there are at least two samples, the grid increases strictly and every number is finite.
    pub fn new(wavelengths_nm: Vec<f64>, values: Vec<f64>) -> Result<Self, VisionError> {
        check_grid(&wavelengths_nm, "curve")?;
        check_values(&wavelengths_nm, &values, None)?;
        Ok(Self { wavelengths_nm, values })
    }

    /// A two-column CSV (wavelength_nm, value); see [`SpectraTable::parse`] for the syntax.
    pub fn from_csv_str(text: &str, source_name: &str) -> Result<Self, VisionError> {
        let t = SpectraTable::parse(text, source_name)?;
        if t.samples.len() != 1 {
            return Err(VisionError::invalid(format!(
                "{source_name}: expected two columns (wavelength_nm, value), found {} value columns",
                t.samples.len()
            )));
        }
        let (_, v) = t.samples.into_iter().next().unwrap_or_default();
        Curve::new(t.wavelengths_nm, v)
    }

    pub fn from_csv_path(path: &Path) -> Result<Self, VisionError> {
        Self::from_csv_str(&read(path)?, &path.display().to_string())
    }

    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }
    pub fn values(&self) -> &[f64] {
        &self.values
    }
    /// First and last sampled wavelength.
    pub fn range_nm(&self) -> (f64, f64) {
        (self.wavelengths_nm[0], self.wavelengths_nm[self.wavelengths_nm.len() - 1])
    }

    /// Linear interpolation inside the sampled range, zero outside it.
    pub fn at(&self, wavelength_nm: f64) -> f64 {
        let (lo, hi) = self.range_nm();
        if !(lo..=hi).contains(&wavelength_nm) {
            return 0.0;
        }
        iridis_color::spectrum::interpolate_linear(&self.wavelengths_nm, &self.values, wavelength_nm)
    }

    /// The same curve with every value multiplied by `factor`.
    pub fn scaled(&self, factor: f64) -> Curve {
        Curve { wavelengths_nm: self.wavelengths_nm.clone(), values: self.values.iter().map(|v| v * factor).collect() }
    }
}

pub(crate) fn read(path: &Path) -> Result<String, VisionError> {
    std::fs::read_to_string(path)
        .map_err(|e| VisionError::Io { source_name: path.display().to_string(), message: e.to_string() })
}

fn check_grid(w: &[f64], what: &str) -> Result<(), VisionError> {
    if w.len() < 2 {
        return Err(VisionError::invalid(format!("a {what} needs at least two wavelengths, got {}", w.len())));
    }
    for (i, &x) in w.iter().enumerate() {
        if !(x.is_finite() && x > 0.0) {
            return Err(VisionError::invalid(format!("wavelength {x} nm is not a positive finite number")));
        }
        if i > 0 && x <= w[i - 1] {
            return Err(VisionError::invalid(format!("wavelengths must increase: {x} nm follows {} nm", w[i - 1])));
        }
    }
    Ok(())
}

/// Checks that `values` holds one finite number per wavelength of the grid `w`; `spectrum` names the column
/// of a table in the messages (`None` for a lone curve).
fn check_values(w: &[f64], values: &[f64], spectrum: Option<&str>) -> Result<(), VisionError> {
    if values.len() != w.len() {
        return Err(VisionError::invalid(match spectrum {
            None => format!("{} wavelengths but {} values", w.len(), values.len()),
            Some(name) => format!("spectrum '{name}' has {} values for {} wavelengths", values.len(), w.len()),
        }));
    }
    if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        let message = format!("value {v} at {} nm is not finite", w[i]);
        return Err(VisionError::invalid(match spectrum {
            None => message,
            Some(name) => format!("spectrum '{name}': {message}"),
        }));
    }
    Ok(())
}

/// Spectra on one wavelength grid: the CSV that pavo reads (`as.rspec`) and writes — a wavelength column
/// (nm) and one column per sample, the first line naming the columns.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectraTable {
    pub wavelengths_nm: Vec<f64>,
    /// (name, values on the grid) per sample.
    pub samples: Vec<(String, Vec<f64>)>,
}

impl SpectraTable {
    /// The table interpolated linearly onto whole nanometres from its first to its last wavelength, as pavo's
    /// `as.rspec` does, where its samples lie more than 1 nm apart (the receptors' curves, tens of nm wide, were
    /// integrated over the samples alone: a 100 nm grid gave every receptor the catch of one sample); `None`
    /// where they are 1 nm apart or closer. Returns the table and the widest step it had (nm).
    pub fn on_1nm_grid(&self) -> Option<(SpectraTable, f64)> {
        let wl = &self.wavelengths_nm;
        let widest = wl.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
        if widest <= 1.0 + 1e-9 {
            return None;
        }
        let grid: Vec<f64> = (wl[0].ceil() as i64..=wl[wl.len() - 1].floor() as i64).map(|l| l as f64).collect();
        let samples = self
            .samples
            .iter()
            .map(|(name, v)| {
                let at = |l: f64| iridis_color::spectrum::interpolate_linear(wl, v, l);
                (name.clone(), grid.iter().map(|&l| at(l)).collect())
            })
            .collect();
        Some((SpectraTable { wavelengths_nm: grid, samples }, widest))
    }

    /// Builds a table, checking the grid and that every sample has one finite value per wavelength.
    pub fn new(wavelengths_nm: Vec<f64>, samples: Vec<(String, Vec<f64>)>) -> Result<Self, VisionError> {
        check_grid(&wavelengths_nm, "spectrum")?;
        if samples.is_empty() {
            return Err(VisionError::invalid("no spectra: the table has a wavelength column only"));
        }
        for (name, v) in &samples {
            check_values(&wavelengths_nm, v, Some(name))?;
        }
        Ok(Self { wavelengths_nm, samples })
    }

    /// Parses CSV text: fields separated by commas, semicolons, tabs or spaces; blank lines and lines starting
    /// with `#` skipped; an optional header line (the first that is not all numbers) names the columns
    /// (the first column is the wavelength; without a header the samples are `sample1`, `sample2`, …).
    /// Errors name the source and line.
    pub fn parse(text: &str, source_name: &str) -> Result<Self, VisionError> {
        let mut header: Option<Vec<String>> = None;
        let mut rows: Vec<Vec<f64>> = Vec::new();
        let err = |line: usize, message: String| VisionError::Parse { source_name: source_name.into(), line, message };
        for TextRow { line: line_no, fields, .. } in text_rows(text, Separators::OnePerLine) {
            let parsed: Vec<Result<f64, _>> = fields.iter().map(|f| f.parse::<f64>()).collect();
            if parsed.iter().any(|p| p.is_err()) {
                if header.is_none() && rows.is_empty() {
                    header = Some(fields.iter().map(|f| f.trim_matches('"').to_string()).collect());
                    continue;
                }
                let bad = fields.iter().zip(&parsed).find(|(_, p)| p.is_err()).map(|(f, _)| *f).unwrap_or("");
                return Err(err(line_no, format!("'{bad}' is not a number")));
            }
            let values: Vec<f64> = parsed.into_iter().map(|p| p.unwrap_or(f64::NAN)).collect();
            let width = header.as_ref().map(Vec::len).or_else(|| rows.first().map(Vec::len)).unwrap_or(values.len());
            if values.len() != width {
                return Err(err(line_no, format!("expected {width} columns, found {}", values.len())));
            }
            if values.len() < 2 {
                return Err(err(line_no, "expected a wavelength column and at least one value column".into()));
            }
            if let Some(bad) = values.iter().find(|v| !v.is_finite()) {
                return Err(err(line_no, format!("{bad} is not a finite number")));
            }
            if values[0].partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                return Err(err(line_no, format!("wavelength {} nm must be positive", values[0])));
            }
            if let Some(last) = rows.last() {
                if values[0] <= last[0] {
                    return Err(err(
                        line_no,
                        format!("wavelengths must increase: {} nm follows {} nm", values[0], last[0]),
                    ));
                }
            }
            rows.push(values);
        }
        if rows.len() < 2 {
            return Err(err(
                text.lines().count(),
                format!("found {} data rows; spectra need at least two", rows.len()),
            ));
        }
        let ncols = rows[0].len();
        let names: Vec<String> = match header {
            Some(h) => h.into_iter().skip(1).collect(),
            None => (1..ncols).map(|i| format!("sample{i}")).collect(),
        };
        let wavelengths = rows.iter().map(|r| r[0]).collect();
        let samples =
            names.into_iter().enumerate().map(|(j, name)| (name, rows.iter().map(|r| r[j + 1]).collect())).collect();
        Self::new(wavelengths, samples)
    }

    pub fn from_csv_path(path: &Path) -> Result<Self, VisionError> {
        Self::parse(&read(path)?, &path.display().to_string())
    }

    /// The table as CSV text, pavo's layout: `wl,NAME1,NAME2,…` then one row per wavelength.
    pub fn to_csv(&self) -> String {
        let mut out = String::from("wl");
        for (name, _) in &self.samples {
            out.push(',');
            out.push_str(&csv_field(name));
        }
        out.push('\n');
        for (i, w) in self.wavelengths_nm.iter().enumerate() {
            out.push_str(&w.to_string());
            for (_, v) in &self.samples {
                out.push(',');
                out.push_str(&v[i].to_string());
            }
            out.push('\n');
        }
        out
    }
}

/// A column name as one CSV field: quoted when it holds a separator or a quote.
fn csv_field(name: &str) -> String {
    if name.contains([',', ';', '"', '\n']) {
        format!("\"{}\"", name.replace('"', "\"\""))
    } else {
        name.to_string()
    }
}

/// A reflectance above this (150 %) is most likely a value in percent (pavo's spectra often are).
pub const PERCENT_ABOVE: f64 = 1.5;

/// The note for reflectance spectra whose largest value is above [`PERCENT_ABOVE`]: read as fractions, they are
/// most likely percent; `divide` says how to divide them by 100 (`--percent`, or by hand). The quantum catches
/// scale with the values and a hexagon's coordinates change (`E = q/(q + 1)`); ΔS and ΔL of the receptor-noise
/// model (log ratios of catches) do not under neural noise, but do under quantum noise, which depends on the
/// absolute catches (a percent table read as fractions gave ΔS 13.7 for 1.57). `quantum_noise`: the noise is
/// the quantum model's, named by a flag (the model reads tables, not the other way round).
pub fn percent_note(spectra: &[(String, Vec<f64>)], divide: &str, quantum_noise: bool) -> Option<String> {
    let (name, v) = spectra
        .iter()
        .flat_map(|(name, v)| v.iter().map(move |x| (name, *x)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .filter(|b| b.1 > PERCENT_ABOVE)?;
    let distances = if quantum_noise {
        "and so do ΔS and ΔL, whose quantum noise depends on the absolute catches"
    } else {
        "ΔS and ΔL of the receptor-noise model do not"
    };
    Some(format!(
        "spectrum '{name}' reaches {v}, read as a reflectance of {:.0} %: if the values are percent, {divide}; the \
         quantum catches scale with them and a hexagon's coordinates change, {distances}",
        100.0 * v
    ))
}
