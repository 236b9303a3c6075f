//! The wavelength grid and the colour weights of the spectral integral (paper eq. 9):
//! `X = Σ_λ w_x(λ) ρ_λ` with `w_x = S(λ) x̄(λ) Δλ / Σ S ȳ Δλ`, so a normal-incidence mirror has `Y = 1`.
//!
//! [`Units`] says what `ρ` is: the paper's relative reflectance, whose mirror peak is 1 at every λ, or the
//! radiometric BRDF, whose integral over the hemisphere is the reflected fraction of the light.

use iridis_color::spectrum::uniform_grid;
use iridis_color::{Illuminant, Observer, SpectralWeights};

use crate::DiffractionError;

/// What the evaluators' `ρ` and colours measure.
///
/// * `Relative` (the paper's eq. 4, 9): `ρ_λ = C |A|²` is relative to the specular peak of a flat mirror, which
///   is 1 at every wavelength. The lobe of that mirror is a Gaussian of solid angle `λ²/(4πσ_s²)` (`4σ_s` the
///   coherence length), so its hemispherical integral — the light it reflects — is that small number, and
///   grows as `λ²`: a display convention (images are scaled by an exposure in RU), not an energy.
/// * `Radiometric`: `ρ_λ · 4πσ_s²/λ²`, i.e. `f_r cos θ_i / R₀` with `f_r` the BRDF: a flat surface of
///   normal-incidence reflectance `R₀` reflects `R(θ)` of the light at every λ (Parseval of the window), a rough
///   one at most that. Multiply by `R₀` for the BRDF of a real surface (the renderer does).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Units {
    #[default]
    Relative,
    Radiometric,
}

iridis_color::names! {
    Units {
        Relative => "relative" | "paper",
        Radiometric => "radiometric" | "absolute",
    }
    else |s| -> DiffractionError {
        DiffractionError::Invalid(format!(
            "units '{s}': expected relative (the paper's: a flat mirror's peak is 1) or radiometric (the BRDF: \
             a flat mirror reflects R(θ) of the light)"
        ))
    }
}

/// `4πσ_s²/λ²` with `σ_s = coherence/4`: the inverse of the solid angle of a flat mirror's lobe under the Gaussian
/// coherence window, `∫ G(u/λ, v/λ)² du dv = πλ²σ_f² = λ²/(4πσ_s²)` (`σ_f = 1/(2πσ_s)`). Multiplying the
/// relative `ρ` by it makes the lobe's integral over projected solid angle `R/R₀` (docs/PHYSICS.md).
pub fn radiometric_gain(wavelength_nm: f64, coherence_nm: f64) -> f64 {
    let sigma_s = coherence_nm / 4.0;
    4.0 * std::f64::consts::PI * sigma_s * sigma_s / (wavelength_nm * wavelength_nm)
}

/// The standard deviation, in direction cosines `(u, v)`, of a lobe's intensity `G(u/λ, v/λ)²` under the
/// coherence window: `λσ_f/√2 = λ/(2√2 πσ_s)` with `σ_s = coherence/4` (docs/PHYSICS.md, "Coherence window").
/// The windowed spectrum is a sum of such lobes, so no feature of the BRDF — a mirror's reflection, a grating's
/// order — is narrower: a map or screen that samples directions much further apart can miss it.
pub fn lobe_sigma_uv(wavelength_nm: f64, coherence_nm: f64) -> f64 {
    let sigma_s = coherence_nm / 4.0;
    wavelength_nm / (2.0 * std::f64::consts::SQRT_2 * std::f64::consts::PI * sigma_s)
}

/// Wavelength samples and their XYZ weights.
#[derive(Debug, Clone)]
pub struct SpectralSetup {
    pub illuminant: Illuminant,
    pub observer: Observer,
    pub step_nm: f64,
    pub weights: SpectralWeights,
    /// A light that replaces the illuminant (a laser, a lamp): its relative power at each grid wavelength,
    /// recorded in lookup tables built with it. `None`: the illuminant's weights.
    pub light: Option<Vec<f64>>,
    /// What `ρ` measures; [`SpectralSetup::radiometric`] switches to the BRDF.
    pub units: Units,
    /// The coherence length the radiometric weights were made for (`None` in relative units): a table or
    /// evaluator built with another coherence would be mis-scaled, and refuses.
    pub radiometric_coherence_nm: Option<f64>,
}

impl SpectralSetup {
    /// 380–780 nm in steps of `step_nm` (the paper uses 5 nm and shows artefacts at ≥ 10 nm).
    pub fn new(illuminant: Illuminant, observer: Observer, step_nm: f64) -> Result<Self, DiffractionError> {
        Self::with_range(illuminant, observer, 380.0, 780.0, step_nm)
    }

    pub fn with_range(
        illuminant: Illuminant,
        observer: Observer,
        from_nm: f64,
        to_nm: f64,
        step_nm: f64,
    ) -> Result<Self, DiffractionError> {
        let grid = uniform_grid(from_nm, to_nm, step_nm).map_err(|e| DiffractionError::Invalid(e.to_string()))?;
        if grid.len() < 2 {
            return Err(DiffractionError::Invalid(format!(
                "the wavelength grid {from_nm}–{to_nm} nm at {step_nm} nm steps holds {} sample(s); the spectral \
                 integral needs two or more: give a step of at most {} nm",
                grid.len(),
                to_nm - from_nm
            )));
        }
        Ok(Self {
            illuminant,
            observer,
            step_nm,
            weights: SpectralWeights::new(&grid, illuminant, observer),
            light: None,
            units: Units::Relative,
            radiometric_coherence_nm: None,
        })
    }

    /// The same grid with weights that make every evaluator's colour radiometric for a coherence length
    /// (`w(λ) · 4πσ_s²/λ²`, [`radiometric_gain`]). Call it last, after any custom light is set.
    pub fn radiometric(&self, coherence_nm: f64) -> Result<Self, DiffractionError> {
        if !(coherence_nm.is_finite() && coherence_nm > 0.0) {
            return Err(DiffractionError::Invalid(format!("coherence length {coherence_nm} nm must be positive")));
        }
        if self.units == Units::Radiometric {
            return match self.radiometric_coherence_nm {
                Some(c) if c == coherence_nm => Ok(self.clone()),
                c => Err(DiffractionError::Invalid(format!(
                    "these weights are radiometric for a coherence of {c:?} nm, not {coherence_nm} nm"
                ))),
            };
        }
        Ok(Self {
            weights: self.weights.scaled(|l| radiometric_gain(l, coherence_nm)),
            units: Units::Radiometric,
            radiometric_coherence_nm: Some(coherence_nm),
            ..self.clone()
        })
    }

    /// Refuses radiometric weights made for another coherence length than an evaluator's or table's.
    pub fn check_coherence(&self, coherence_nm: f64) -> Result<(), DiffractionError> {
        match (self.units, self.radiometric_coherence_nm) {
            (Units::Radiometric, Some(c)) if (c - coherence_nm).abs() > 1e-9 * c.abs() => {
                Err(DiffractionError::Invalid(format!(
                    "radiometric weights made for a coherence of {c} nm used with {coherence_nm} nm: the lobe's \
                     solid angle differs; make the weights with SpectralSetup::radiometric({coherence_nm})"
                )))
            }
            _ => Ok(()),
        }
    }

    pub fn wavelengths(&self) -> &[f64] {
        self.weights.wavelengths_nm()
    }

    /// What lights the scene, as a table records it: the illuminant's name, or `light` for a custom spectrum.
    pub fn light_name(&self) -> &'static str {
        if self.light.is_some() {
            "light"
        } else {
            self.illuminant.name()
        }
    }
}

impl Default for SpectralSetup {
    fn default() -> Self {
        Self::new(Illuminant::D65, Observer::Cie1931, 5.0).expect("the default grid is valid")
    }
}
