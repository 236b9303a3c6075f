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
        match self {
            ReceptorNoise::Weber { weber, reference, densities } => {
                if !positive(*weber) {
                    return Err(VisionError::invalid(format!("Weber fraction {weber} must be a positive number")));
                }
                one_positive_per_receptor(densities, n, "receptor densities", " (e.g. 1:2:2:4)", "receptor density")?;
                if *reference >= n {
                    return Err(VisionError::invalid(format!("reference receptor {} of {n}", reference + 1)));
                }
            }
            ReceptorNoise::PerReceptor(e) => one_positive_per_receptor(e, n, "noise values", "", "receptor noise")?,
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

fn positive(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

/// Checks that `values` holds one positive number per receptor of `n`: `many` names them in the count's
/// message, which ends with `example`, and `one` names a value that is not positive.
fn one_positive_per_receptor(
    values: &[f64],
    n: usize,
    many: &str,
    example: &str,
    one: &str,
) -> Result<(), VisionError> {
    if values.len() != n {
        return Err(VisionError::invalid(format!(
            "{} {many} for {n} receptors: give one per receptor, short to long{example}",
            values.len()
        )));
    }
    if let Some(v) = values.iter().find(|v| !positive(**v)) {
        return Err(VisionError::invalid(format!("{one} {v} must be a positive number")));
    }
    Ok(())
}
