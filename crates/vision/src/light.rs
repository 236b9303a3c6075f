//! Illuminants (in photon flux: quantum catches count photons) and the backgrounds receptors adapt to.

use std::path::Path;

use iridis_color::Illuminant;
use serde::Serialize;

use crate::table::Curve;
use crate::VisionError;

/// A light, as relative photon flux per nm.
#[derive(Debug, Clone, PartialEq)]
pub struct Light {
    /// What it is, e.g. "D65 (CIE, photon flux)".
    pub name: String,
    spectrum: LightSpectrum,
}

#[derive(Debug, Clone, PartialEq)]
enum LightSpectrum {
    /// The same photon flux at every wavelength (pavo's "ideal").
    Flat,
    /// `factor · table(λ)` (photons), or `factor · table(λ) · λ` when the table is in energy units: the table
    /// is interpolated in the units it was measured in, then converted.
    Tabulated { table: Curve, energy: bool, factor: f64 },
}

/// Whether a light's table is in photon units or in energy units (converted by `× λ`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LightUnits {
    #[default]
    Photons,
    Energy,
}

const BUILTIN: &[(&str, &str)] = &[
    ("d65", "CIE D65 daylight (CIE table from 300 nm)"),
    ("d50", "CIE D50"),
    ("a", "CIE illuminant A (tungsten, 2856 K)"),
    ("e", "CIE equal-energy illuminant E"),
    ("bluesky", "open blue sky (Endler 1993, as tabulated in pavo), 300–700 nm"),
    ("forestshade", "forest shade (Endler 1993, as tabulated in pavo), 300–700 nm"),
    ("ideal", "the same photon flux at every wavelength (pavo's 'ideal')"),
];

impl Light {
    /// The built-in lights: (name, description).
    pub fn builtin_names() -> &'static [(&'static str, &'static str)] {
        BUILTIN
    }

    /// A built-in light. The CIE illuminants (relative energy) are converted to photon flux (`× λ`); every
    /// tabulated light is scaled to a maximum of 1 over 300–700 nm (as pavo's are), which von Kries
    /// adaptation makes irrelevant.
    pub fn builtin(name: &str) -> Result<Self, VisionError> {
        let key = name.trim().to_ascii_lowercase();
        let cie = |ill: Illuminant| -> Result<Light, VisionError> {
            let spd = ill.spd();
            let c = Curve::new(spd.wavelengths_nm().to_vec(), spd.values().to_vec())?;
            Ok(Light {
                name: format!("{} (CIE, converted to photon flux)", ill.name()),
                spectrum: LightSpectrum::Tabulated { table: c, energy: true, factor: 1.0 },
            }
            .max_one())
        };
        match key.as_str() {
            "d65" => cie(Illuminant::D65),
            "d50" => cie(Illuminant::D50),
            "a" => cie(Illuminant::A),
            "e" => cie(Illuminant::E),
            "bluesky" | "blue-sky" => Ok(Light {
                name: "blue sky (Endler 1993)".into(),
                spectrum: tabulated_photons(
                    Curve::from_csv_str(
                        include_str!("../../../data/vision/illuminant_endler1993_bluesky.csv"),
                        "bluesky",
                    )
                    .expect("malformed built-in light"),
                ),
            }),
            "forestshade" | "forest-shade" => Ok(Light {
                name: "forest shade (Endler 1993)".into(),
                spectrum: tabulated_photons(
                    Curve::from_csv_str(
                        include_str!("../../../data/vision/illuminant_endler1993_forestshade.csv"),
                        "forestshade",
                    )
                    .expect("malformed built-in light"),
                ),
            }),
            "ideal" | "flat" => Ok(Light { name: "ideal (flat photon flux)".into(), spectrum: LightSpectrum::Flat }),
            _ => Err(VisionError::invalid(format!(
                "unknown illuminant '{name}'; built in: {} (or a CSV file: wavelength_nm, flux)",
                BUILTIN.iter().map(|(k, _)| *k).collect::<Vec<_>>().join(", ")
            ))),
        }
    }

    /// A light from a sampled spectrum (zero outside its range), in photon or energy units.
    pub fn from_curve(name: impl Into<String>, curve: Curve, units: LightUnits) -> Result<Self, VisionError> {
        if let Some(v) = curve.values().iter().find(|v| **v < 0.0) {
            return Err(VisionError::invalid(format!("illuminant value {v} is negative")));
        }
        let energy = units == LightUnits::Energy;
        Ok(Light { name: name.into(), spectrum: LightSpectrum::Tabulated { table: curve, energy, factor: 1.0 } })
    }

    /// A light from a two-column CSV file.
    pub fn from_csv_path(path: &Path, units: LightUnits) -> Result<Self, VisionError> {
        let unit = match units {
            LightUnits::Photons => "photon flux",
            LightUnits::Energy => "energy, converted to photon flux",
        };
        Self::from_curve(format!("{} ({unit})", path.display()), Curve::from_csv_path(path)?, units)
    }

    /// A built-in name or, when it names an existing file, a CSV light.
    pub fn parse(spec: &str, units: LightUnits) -> Result<Self, VisionError> {
        if Self::names_a_file(spec) {
            return Self::from_csv_path(Path::new(spec), units);
        }
        Self::builtin(spec)
    }

    /// Whether `spec` is read as a CSV file (a name with an extension that exists, or is no built-in's) rather
    /// than as a built-in light, whose units are its own.
    pub fn names_a_file(spec: &str) -> bool {
        let path = Path::new(spec);
        path.extension().is_some() && (path.exists() || !BUILTIN.iter().any(|(k, _)| spec.eq_ignore_ascii_case(k)))
    }

    /// Relative photon flux at `λ`.
    pub fn at(&self, wavelength_nm: f64) -> f64 {
        match &self.spectrum {
            LightSpectrum::Flat => 1.0,
            LightSpectrum::Tabulated { table, energy, factor } => {
                let v = factor * table.at(wavelength_nm);
                if *energy {
                    v * wavelength_nm
                } else {
                    v
                }
            }
        }
    }

    /// The tabulated range, `None` for a flat light.
    pub fn range_nm(&self) -> Option<(f64, f64)> {
        match &self.spectrum {
            LightSpectrum::Flat => None,
            LightSpectrum::Tabulated { table, .. } => Some(table.range_nm()),
        }
    }

    fn max_one(self) -> Self {
        let m = (300..=700).map(|l| self.at(l as f64)).fold(0.0, f64::max);
        match self.spectrum {
            LightSpectrum::Tabulated { table, energy, factor } if m > 0.0 => {
                Light { name: self.name, spectrum: LightSpectrum::Tabulated { table, energy, factor: factor / m } }
            }
            spectrum => Light { name: self.name, spectrum },
        }
    }
}

fn tabulated_photons(table: Curve) -> LightSpectrum {
    LightSpectrum::Tabulated { table, energy: false, factor: 1.0 }
}

/// What the receptors adapt to (von Kries: each receptor's catch is divided by its catch of the background
/// under the same light).
#[derive(Debug, Clone, PartialEq)]
pub enum Background {
    /// No adaptation: the absolute catches are the receptor signals.
    None,
    /// A spectrally flat grey of this reflectance (1 = pavo's "ideal" white background).
    Grey(f64),
    /// A reflectance spectrum (e.g. green foliage), linear between samples, end values held beyond.
    Spectrum { name: String, reflectance: Curve },
}

impl Background {
    /// `none`, `grey`, `grey:0.2` or a CSV file (wavelength_nm, reflectance).
    pub fn parse(spec: &str) -> Result<Self, VisionError> {
        let s = spec.trim();
        match s.to_ascii_lowercase().as_str() {
            "none" => return Ok(Background::None),
            "grey" | "gray" | "ideal" | "white" => return Ok(Background::Grey(1.0)),
            _ => {}
        }
        if let Some(v) = s.strip_prefix("grey:").or_else(|| s.strip_prefix("gray:")) {
            return match v.trim().parse::<f64>() {
                Ok(g) if g.is_finite() && g > 0.0 => Ok(Background::Grey(g)),
                _ => Err(VisionError::invalid(format!(
                    "background '{spec}': the grey's reflectance must be a positive number"
                ))),
            };
        }
        let path = Path::new(s);
        if path.extension().is_some() {
            return Ok(Background::Spectrum { name: s.to_string(), reflectance: Curve::from_csv_path(path)? });
        }
        Err(VisionError::invalid(format!(
            "unknown background '{spec}'; expected none, grey, grey:REFLECTANCE or a CSV file (wavelength_nm, reflectance)"
        )))
    }

    /// Reflectance at `λ` (`None` when there is no adaptation).
    pub fn reflectance(&self, wavelength_nm: f64) -> Option<f64> {
        match self {
            Background::None => None,
            Background::Grey(g) => Some(*g),
            Background::Spectrum { reflectance, .. } => {
                let (lo, hi) = reflectance.range_nm();
                Some(reflectance.at(wavelength_nm.clamp(lo, hi)))
            }
        }
    }

    pub fn describe(&self) -> BackgroundInfo {
        match self {
            Background::None => BackgroundInfo { kind: "none".into(), reflectance: None, source: None },
            Background::Grey(g) => BackgroundInfo { kind: "grey".into(), reflectance: Some(*g), source: None },
            Background::Spectrum { name, .. } => {
                BackgroundInfo { kind: "spectrum".into(), reflectance: None, source: Some(name.clone()) }
            }
        }
    }
}

/// The background as an analysis reports it.
#[derive(Debug, Clone, Serialize)]
pub struct BackgroundInfo {
    /// `none` (no von Kries adaptation), `grey` or `spectrum`.
    pub kind: String,
    /// The grey's reflectance, null otherwise.
    pub reflectance: Option<f64>,
    /// The spectrum's file, null otherwise.
    pub source: Option<String>,
}
