//! Spectrum → XYZ: `X = ∫ R(λ) S(λ) x̄(λ) dλ / ∫ S(λ) ȳ(λ) dλ` (likewise Y, Z) by the trapezoid rule, so
//! that a perfect reflector (R ≡ 1) has `Y = 1` on every grid.

use crate::cie::{Illuminant, Observer};
use crate::convert::Xyz;
use crate::spectrum::{trapezoid_weights, Spectrum};

/// Per-sample integration weights on a fixed wavelength grid: `XYZ = Σᵢ wᵢ R(λᵢ)`.
///
/// Build once per grid, illuminant and observer; then a spectral value costs three multiply-adds. Film,
/// diffraction and rendering code all integrate through this type, so the normalisation lives here only.
#[derive(Debug, Clone)]
pub struct SpectralWeights {
    wavelengths_nm: Vec<f64>,
    weights: Vec<[f64; 3]>,
}

impl SpectralWeights {
    /// Weights for reflectance (or any relative quantity) lit by `illuminant` and seen by `observer`.
    /// The grid must be strictly increasing; CMFs are zero outside 360–830 nm.
    pub fn new(grid_nm: &[f64], illuminant: Illuminant, observer: Observer) -> Self {
        Self::with_light(grid_nm, |w| illuminant.spd().value_at(w), observer)
    }

    /// Weights for an arbitrary light spectrum `light(λ)` (e.g. a laser or a measured lamp).
    pub fn with_light(grid_nm: &[f64], light: impl Fn(f64) -> f64, observer: Observer) -> Self {
        let cmfs = observer.cmfs();
        let trap = trapezoid_weights(grid_nm);
        let mut weights: Vec<[f64; 3]> = grid_nm
            .iter()
            .zip(&trap)
            .map(|(&w, &dw)| {
                let s = light(w) * dw;
                let [x, y, z] = cmfs.at(w);
                [x * s, y * s, z * s]
            })
            .collect();
        let norm: f64 = weights.iter().map(|w| w[1]).sum();
        if norm > 0.0 {
            for w in &mut weights {
                for c in w.iter_mut() {
                    *c /= norm;
                }
            }
        }
        Self { wavelengths_nm: grid_nm.to_vec(), weights }
    }

    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    /// The same weights with each sample's triple multiplied by `factor(λ)`: a spectral factor that the
    /// integral should carry without renormalising (e.g. a quantity that is not a reflectance relative to the
    /// light, such as the diffraction BRDF's radiometric gain `4πσ_s²/λ²`).
    pub fn scaled(&self, factor: impl Fn(f64) -> f64) -> Self {
        let weights = self
            .wavelengths_nm
            .iter()
            .zip(&self.weights)
            .map(|(&l, w)| {
                let f = factor(l);
                [w[0] * f, w[1] * f, w[2] * f]
            })
            .collect();
        Self { wavelengths_nm: self.wavelengths_nm.clone(), weights }
    }
    /// The weight triple of each sample.
    pub fn weights(&self) -> &[[f64; 3]] {
        &self.weights
    }

    /// `Σᵢ wᵢ vᵢ` for values sampled on this grid.
    pub fn integrate(&self, values: &[f64]) -> Xyz {
        debug_assert_eq!(values.len(), self.weights.len());
        let mut acc = [0.0; 3];
        for (w, &v) in self.weights.iter().zip(values) {
            acc[0] += w[0] * v;
            acc[1] += w[1] * v;
            acc[2] += w[2] * v;
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }

    /// The XYZ of a perfect reflector: the white point of this light, `Y = 1`.
    pub fn white(&self) -> Xyz {
        let mut acc = [0.0; 3];
        for w in &self.weights {
            for c in 0..3 {
                acc[c] += w[c];
            }
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }
}

/// The observer's own 1 nm grid, 360–830 nm.
pub fn observer_grid(observer: Observer) -> &'static [f64] {
    &observer.cmfs().wavelengths_nm
}

/// XYZ of a reflectance (or transmittance) spectrum under an illuminant, integrated on the observer's 1 nm
/// grid (the spectrum is interpolated linearly onto it, its end values held outside its range).
pub fn reflectance_to_xyz(reflectance: &Spectrum, illuminant: Illuminant, observer: Observer) -> Xyz {
    let grid = observer_grid(observer);
    let w = SpectralWeights::new(grid, illuminant, observer);
    let values: Vec<f64> = grid.iter().map(|&l| reflectance.value_at(l)).collect();
    w.integrate(&values)
}

/// XYZ of a light source's own spectrum, normalised to `Y = 1` (its chromaticity at unit luminance).
pub fn emission_to_xyz(light: &Spectrum, observer: Observer) -> Xyz {
    let grid = observer_grid(observer);
    let w = SpectralWeights::with_light(grid, |l| light.value_at(l), observer);
    w.white()
}

/// The white point (XYZ of a perfect reflector, `Y = 1`) of an illuminant for an observer.
pub fn white_point(illuminant: Illuminant, observer: Observer) -> Xyz {
    SpectralWeights::new(observer_grid(observer), illuminant, observer).white()
}
