//! The noise of the receptor channels that limits colour discrimination (Vorobyev & Osorio 1998): part of a
//! visual system's data ([`crate::system`]), used by the receptor-noise-limited model ([`crate::model`]).

use crate::VisionError;

/// The noise of each receptor channel, `e_i` (a Weber fraction: the JND in `ln q`).
#[derive(Debug, Clone, PartialEq)]
pub enum ReceptorNoise {
    /// The Weber fraction `weber` of the receptor `reference` and the relative densities of the receptor
    /// classes: `e_i = weber · √(η_ref / η_i)` (noise falls as the square root of the number of receptors
    /// pooled; pavo's `coldist(n, weber, weber.ref)`).
    Weber { weber: f64, reference: usize, densities: Vec<f64> },
    /// `e_i` given for every receptor (pavo: `weber` as a vector).
    PerReceptor(Vec<f64>),
}

impl ReceptorNoise {
    /// Checks the numbers against a system of `n` receptors.
    pub fn check(&self, n: usize) -> Result<(), VisionError> {
        let positive = |v: f64| v.is_finite() && v > 0.0;
        match self {
            ReceptorNoise::Weber { weber, reference, densities } => {
                if !positive(*weber) {
                    return Err(VisionError::invalid(format!("Weber fraction {weber} must be a positive number")));
                }
                if densities.len() != n {
                    return Err(VisionError::invalid(format!(
                        "{} receptor densities for {n} receptors: give one per receptor, short to long (e.g. 1:2:2:4)",
                        densities.len()
                    )));
                }
                if let Some(d) = densities.iter().find(|d| !positive(**d)) {
                    return Err(VisionError::invalid(format!("receptor density {d} must be a positive number")));
                }
                if *reference >= n {
                    return Err(VisionError::invalid(format!("reference receptor {} of {n}", reference + 1)));
                }
            }
            ReceptorNoise::PerReceptor(e) => {
                if e.len() != n {
                    return Err(VisionError::invalid(format!(
                        "{} noise values for {n} receptors: give one per receptor, short to long",
                        e.len()
                    )));
                }
                if let Some(v) = e.iter().find(|v| !positive(**v)) {
                    return Err(VisionError::invalid(format!("receptor noise {v} must be a positive number")));
                }
            }
        }
        Ok(())
    }

    /// The neural noise `e_i` of each receptor channel.
    pub fn per_receptor(&self) -> Vec<f64> {
        match self {
            ReceptorNoise::Weber { weber, reference, densities } => {
                densities.iter().map(|d| weber * (densities[*reference] / d).sqrt()).collect()
            }
            ReceptorNoise::PerReceptor(e) => e.clone(),
        }
    }
}
