//! The one reading of the options people type (on the command line, in Python): visual systems, noise,
//! light, background, space — so that every front end accepts the same words and gives the same messages.

use std::path::Path;

use crate::light::{Background, Light, LightUnits};
use crate::model::{AchromaticChoice, NoiseModel, Options, ReceptorNoise};
use crate::space::Space;
use crate::system::{Achromatic, VisualSystem};
use crate::table::{Curve, SpectraTable};
use crate::template::{Chromophore, Droplet};
use crate::VisionError;

/// The options of an analysis as typed; `None` leaves the default (the visual system's own, or
/// [`Options::default`]'s).
#[derive(Debug, Clone, Default)]
pub struct Spec {
    /// A built-in system (`bluetit`) or a CSV of sensitivities; `None` with `lambda_max`.
    pub visual: Option<String>,
    /// Pigment λmax values in nm, `344,436,556`.
    pub lambda_max: Option<String>,
    /// `a1` or `a2` (with `lambda_max`).
    pub chromophore: Option<String>,
    /// One per λmax: `none`, a type and λcut (`C:413`), or λcut and Bmid (`413:0.05`); `T,C:413,Y:507,R:572`.
    pub oil_droplets: Option<String>,
    /// Ocular-media transmittance CSV (wavelength_nm, transmittance).
    pub ocular_media: Option<String>,
    /// A built-in light or a CSV.
    pub illuminant: Option<String>,
    /// `photons` (default) or `energy`: the units of an illuminant CSV.
    pub illuminant_units: Option<String>,
    pub illuminant_scale: Option<f64>,
    /// `none`, `grey`, `grey:0.2` or a CSV.
    pub background: Option<String>,
    pub weber: Option<f64>,
    /// The reference receptor of `weber`: a name, a 1-based position or `longest`.
    pub weber_ref: Option<String>,
    /// Relative receptor densities `1:2:2:4`.
    pub densities: Option<String>,
    /// Noise per receptor `0.13,0.06,0.12` (instead of weber and densities).
    pub receptor_noise: Option<String>,
    /// `neural` or `quantum`.
    pub noise: Option<String>,
    /// `none`, a receptor's name or position, or `NAME+NAME` for a sum.
    pub achromatic: Option<String>,
    /// Refused when there is no achromatic channel (it would change nothing).
    pub achromatic_weber: Option<f64>,
    pub space: Option<String>,
}

fn numbers(s: &str, what: &str, seps: &[char]) -> Result<Vec<f64>, VisionError> {
    s.split(seps)
        .map(str::trim)
        .filter(|p| !p.is_empty())
        .map(|p| {
            let t = p.trim_end_matches("nm");
            t.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| VisionError::invalid(format!("{what} '{s}': '{p}' is not a number")))
        })
        .collect()
}

/// `T,C:413,Y:507,R:572` or `none,413:0.05,…`: one entry per receptor.
pub fn parse_droplets(s: &str) -> Result<Vec<Option<Droplet>>, VisionError> {
    s.split(',')
        .map(str::trim)
        .map(|p| {
            if p.eq_ignore_ascii_case("none") || p.eq_ignore_ascii_case("t") || p.to_ascii_lowercase().starts_with("t:")
            {
                return Ok(None);
            }
            let (a, b) = p.split_once(':').ok_or_else(|| {
                VisionError::invalid(format!(
                    "oil droplet '{p}': expected none, TYPE:LAMBDA_CUT (e.g. C:413) or LAMBDA_CUT:BMID (e.g. 413:0.05)"
                ))
            })?;
            let num = |x: &str| {
                x.trim()
                    .trim_end_matches("nm")
                    .parse::<f64>()
                    .map_err(|_| VisionError::invalid(format!("oil droplet '{p}': '{x}' is not a number")))
            };
            match a.trim().parse() {
                Ok(kind) => Droplet::from_type(kind, num(b)?),
                Err(_) => Droplet::new(num(a)?, num(b)?).map(Some),
            }
        })
        .collect()
}

impl Spec {
    /// The visual system the spec names.
    pub fn system(&self) -> Result<VisualSystem, VisionError> {
        let mut system = match (&self.visual, &self.lambda_max) {
            (Some(_), Some(_)) => {
                return Err(VisionError::invalid("give a visual system or λmax values, not both"));
            }
            (None, None) => {
                return Err(VisionError::invalid("no visual system: give one by name, a CSV or λmax values"))
            }
            (Some(v), None) => {
                if self.chromophore.is_some() || self.oil_droplets.is_some() {
                    return Err(VisionError::invalid("a chromophore and oil droplets go with λmax values"));
                }
                let path = Path::new(v);
                if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("csv") || e.eq_ignore_ascii_case("txt")) {
                    VisualSystem::from_table(v, SpectraTable::from_csv_path(path)?)?
                } else {
                    VisualSystem::builtin(v)?
                }
            }
            (None, Some(l)) => {
                let chromophore: Chromophore = self.chromophore.as_deref().unwrap_or("a1").parse()?;
                let droplets = self.oil_droplets.as_deref().map(parse_droplets).transpose()?.unwrap_or_default();
                VisualSystem::from_lambda_max(&numbers(l, "λmax", &[',', ' '])?, chromophore, &droplets)?
            }
        };
        if let Some(m) = &self.ocular_media {
            system.ocular_media = Some((m.clone(), Curve::from_csv_path(Path::new(m))?));
        }
        Ok(system)
    }

    /// The options for `system`.
    pub fn options(&self, system: &VisualSystem) -> Result<Options, VisionError> {
        let mut o = Options::default();
        let units = match self.illuminant_units.as_deref().map(|s| s.trim().to_ascii_lowercase()) {
            None => LightUnits::Photons,
            Some(u) if u == "photons" || u == "quanta" => LightUnits::Photons,
            Some(u) if u == "energy" => LightUnits::Energy,
            Some(u) => return Err(VisionError::invalid(format!("illuminant units '{u}': expected photons or energy"))),
        };
        if self.illuminant_units.is_some() && !self.illuminant.as_deref().is_some_and(Light::names_a_file) {
            return Err(VisionError::invalid(format!(
                "--illuminant-units would be ignored: they are the units of an illuminant CSV, and {} is a built-in \
                 light with its own",
                self.illuminant.as_deref().unwrap_or("the default illuminant")
            )));
        }
        if let Some(i) = &self.illuminant {
            o.illuminant = Light::parse(i, units)?;
        }
        if let Some(s) = self.illuminant_scale {
            o.illuminant_scale = s;
        }
        if let Some(b) = &self.background {
            o.background = Background::parse(b)?;
        }
        if let Some(n) = &self.noise {
            o.noise_model = n.parse::<NoiseModel>()?;
        }
        let n = system.receptors.len();
        o.noise = match (&self.receptor_noise, self.weber, &self.weber_ref, &self.densities) {
            (Some(_), Some(_), _, _) | (Some(_), _, Some(_), _) | (Some(_), _, _, Some(_)) => {
                return Err(VisionError::invalid(
                    "noise per receptor replaces the Weber fraction, its reference receptor and the densities: give one or the other",
                ))
            }
            (Some(e), ..) => Some(ReceptorNoise::PerReceptor(numbers(e, "receptor noise", &[',', ':'])?)),
            (None, None, None, None) => None,
            (None, w, r, d) => {
                let (w0, r0, d0) = match &system.noise {
                    ReceptorNoise::Weber { weber, reference, densities } => (*weber, *reference, densities.clone()),
                    // A system with noise per receptor: a Weber fraction given alone applies to the longest
                    // receptor with equal densities.
                    ReceptorNoise::PerReceptor(_) => (0.1, n - 1, vec![1.0; n]),
                };
                Some(ReceptorNoise::Weber {
                    weber: w.unwrap_or(w0),
                    reference: r.as_deref().map(|r| system.receptor_index(r)).transpose()?.unwrap_or(r0),
                    densities: d.as_deref().map(|d| numbers(d, "densities", &[':', ','])).transpose()?.unwrap_or(d0),
                })
            }
        };
        if let Some(a) = &self.achromatic {
            o.achromatic = if a.trim().eq_ignore_ascii_case("none") {
                AchromaticChoice::Off
            } else if a.contains('+') {
                AchromaticChoice::Use(Achromatic::Sum(
                    a.split('+').map(|k| system.receptor_index(k)).collect::<Result<_, _>>()?,
                ))
            } else {
                AchromaticChoice::Use(Achromatic::Receptor(system.receptor_index(a)?))
            };
        }
        if let Some(w) = self.achromatic_weber {
            if o.achromatic.resolve(system).is_none() {
                let why = if matches!(o.achromatic, AchromaticChoice::Off) {
                    "--achromatic none leaves no achromatic channel"
                } else {
                    "this visual system has no achromatic channel"
                };
                return Err(VisionError::invalid(format!(
                    "--weber-achromatic {w} would be ignored: {why} (give --achromatic with a receptor or NAME+NAME \
                     for ΔL)"
                )));
            }
            o.achromatic_weber = w;
        }
        if let Some(s) = &self.space {
            o.space = s.parse::<Space>()?;
        }
        Ok(o)
    }
}
