//! The wavelength grid and the colour weights of the spectral integral (paper eq. 9):
//! `X = Σ_λ w_x(λ) ρ_λ` with `w_x = S(λ) x̄(λ) Δλ / Σ S ȳ Δλ`, so a normal-incidence mirror has `Y = 1`.

use iridis_color::spectrum::uniform_grid;
use iridis_color::{Illuminant, Observer, SpectralWeights};

use crate::DiffractionError;

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
            return Err(DiffractionError::Invalid("the wavelength grid needs at least two samples".into()));
        }
        Ok(Self {
            illuminant,
            observer,
            step_nm,
            weights: SpectralWeights::new(&grid, illuminant, observer),
            light: None,
        })
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
