//! Fewer wavelength samples: the grids of the direct colour evaluation (`--spectral-samples N`) and
//! Sussenbach's sparse-sampling experiment (section 5.2.2), which measures what each sample count costs in
//! colour against the dense evaluation (docs/gpu.md has the measured table).
//!
//! The thesis samples "between the 400 and 700 nanometer interval" with a Perlin-noise SVT of
//! `d_rel = 95 nm` and judges the images by eye; here the same film is evaluated over a grid of incidence
//! angles (0°–80°) and thickness offsets (±95 nm, the range the noise texture sweeps), and every colour is
//! compared with the dense evaluation (81 samples, 380–780 nm at 5 nm) in CIEDE2000 as displayed, the
//! brightest reference colour at `Y = 1`. The weights of a sparse grid are the trapezoid rule of
//! [`SpectralWeights`], normalised so that a perfect reflector has `Y = 1` on that grid.

use iridis_color::{Illuminant, Observer, SpectralWeights, Xyz};
use rayon::prelude::*;

use crate::accuracy::DeltaEStats;
use crate::error::ThinFilmError;
use crate::stack::Stack;

/// The band of Sussenbach's sparse sampling (section 5.2.2).
pub const THESIS_BAND_NM: (f64, f64) = (400.0, 700.0);
/// The band of the dense evaluation (and of `--spectral-samples`).
pub const FULL_BAND_NM: (f64, f64) = (380.0, 780.0);
/// The SVT amplitude of the thesis' experiment.
pub const THESIS_D_REL_NM: f64 = 95.0;

/// `n` wavelengths evenly over `band` (both ends included), with D65 / CIE 1931 weights.
pub fn sampled_weights(n: usize, band: (f64, f64)) -> Result<SpectralWeights, ThinFilmError> {
    let (lo, hi) = band;
    if !(2..=4096).contains(&n) {
        return Err(ThinFilmError::Invalid(format!("{n} wavelength samples: use 2 to 4096")));
    }
    if !(lo.is_finite() && hi.is_finite() && 0.0 < lo && lo < hi) {
        return Err(ThinFilmError::Invalid(format!("wavelength band {lo}–{hi} nm must be positive and increasing")));
    }
    let grid: Vec<f64> = (0..n).map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64).collect();
    Ok(SpectralWeights::new(&grid, Illuminant::D65, Observer::Cie1931))
}

/// The dense reference: 81 samples over 380–780 nm (5 nm).
pub fn dense_weights() -> SpectralWeights {
    sampled_weights(81, FULL_BAND_NM).expect("a valid grid")
}

/// The points of the experiment: `angles` incidence angles from 0° to 80° × `offsets` thickness offsets
/// over `±d_rel`, as (angle in rad, offset in nm).
pub fn experiment_points(angles: usize, offsets: usize, d_rel_nm: f64) -> Vec<(f64, f64)> {
    let (na, no) = (angles.max(2), offsets.max(2));
    (0..no)
        .flat_map(|j| {
            (0..na).map(move |i| {
                let theta = (80.0 * i as f64 / (na - 1) as f64).to_radians();
                (theta, d_rel_nm * (2.0 * j as f64 / (no - 1) as f64 - 1.0))
            })
        })
        .collect()
}

/// The reflected colour of `stack` at every point (angle in rad, offset in nm) with `weights`, in parallel.
pub fn reflected_colors(
    stack: &Stack,
    weights: &SpectralWeights,
    points: &[(f64, f64)],
) -> Result<Vec<Xyz>, ThinFilmError> {
    points
        .par_iter()
        .map(|&(theta, o)| {
            let r = weights
                .wavelengths_nm()
                .iter()
                .map(|&l| stack.evaluate_offset(l, theta, o).map(|x| x.r()))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(weights.integrate(&r))
        })
        .collect()
}

/// The exposure that shows the brightest of `colors` at `Y = 1`.
pub fn exposure_for(colors: &[Xyz]) -> f64 {
    1.0 / colors.iter().map(|x| x.y).fold(1e-9, f64::max)
}

/// Sussenbach's experiment: for each sample count, ΔE00 of the colours from that many samples evenly over
/// `band` against the dense evaluation, over [`experiment_points`] (48 × 48 points, `±d_rel`). With
/// `white_balanced`, each sparse colour is scaled per channel so that a perfect reflector gives the dense
/// grid's white (a sparse grid's own white is off: its `X` and `Z` weights sum to other values), which
/// separates the cost of the white point from that of the fringes.
pub fn sparse_experiment(
    stack: &Stack,
    counts: &[usize],
    band: (f64, f64),
    d_rel_nm: f64,
    white_balanced: bool,
) -> Result<Vec<(usize, DeltaEStats)>, ThinFilmError> {
    let points = experiment_points(48, 48, d_rel_nm);
    let reference = dense_weights();
    let dense = reflected_colors(stack, &reference, &points)?;
    let exposure = exposure_for(&dense);
    counts
        .iter()
        .map(|&n| {
            let w = sampled_weights(n, band)?;
            let mut sparse = reflected_colors(stack, &w, &points)?;
            if white_balanced {
                let (a, b) = (reference.white().to_array(), w.white().to_array());
                for x in &mut sparse {
                    let v = x.to_array();
                    *x = Xyz::new(v[0] * a[0] / b[0], v[1] * a[1] / b[1], v[2] * a[2] / b[2]);
                }
            }
            Ok((n, DeltaEStats::between(&sparse, &dense, exposure)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids() {
        let w = sampled_weights(5, THESIS_BAND_NM).unwrap();
        assert_eq!(w.wavelengths_nm(), &[400.0, 475.0, 550.0, 625.0, 700.0]);
        assert!((w.white().y - 1.0).abs() < 1e-12);
        let d = dense_weights();
        assert_eq!(d.wavelengths_nm().len(), 81);
        assert!((d.wavelengths_nm()[1] - 385.0).abs() < 1e-12);
        assert!(sampled_weights(1, THESIS_BAND_NM).is_err());
        assert!(sampled_weights(5, (700.0, 400.0)).is_err());
        let p = experiment_points(3, 2, 95.0);
        assert_eq!(p.len(), 6);
        assert_eq!(p[0], (0.0, -95.0));
        assert!((p[5].0 - 80f64.to_radians()).abs() < 1e-15 && p[5].1 == 95.0);
    }
}
