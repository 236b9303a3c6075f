//! Where the light goes in a stack at one wavelength and angle (`iridis thinfilm profile`,
//! `iridis.thinfilm.profile`): R, T, the power absorbed in each layer and in the substrate, and |E|², the
//! absorbed power density and the flux against depth, for s, p or unpolarised light — the front ends print or
//! return this, they compute nothing.

use crate::color::Polarization;
use crate::error::ThinFilmError;
use crate::stack::Stack;

/// The result of [`depth_profile`]; every fraction is of the incident power.
#[derive(Debug, Clone, PartialEq)]
pub struct DepthProfile {
    pub r: f64,
    pub t: f64,
    /// Absorbed in each layer (top first; rounding noise below 1e-14 printed as 0).
    pub layers: Vec<f64>,
    /// "material thickness nm" per layer (`inc:` for incoherent ones).
    pub layer_names: Vec<String>,
    /// Absorbed in an absorbing substrate.
    pub substrate: f64,
    /// `R + T + ΣA − 1` (rounding: an identity of the flux formulas).
    pub balance: f64,
    /// The stack's total thickness (nm).
    pub depth_nm: f64,
    /// The samples, from the top of the window down: depth (nm below the first interface), medium (0 incident,
    /// N + 1 substrate), |E|² (incident = 1), absorbed power per nm, flux (Poynting, incident = 1).
    pub z_nm: Vec<f64>,
    pub medium: Vec<usize>,
    pub e2: Vec<f64>,
    pub absorption_per_nm: Vec<f64>,
    pub flux: Vec<f64>,
}

/// The profile of `stack` at `wavelength_nm` and `angle_rad` for `points` depths evenly over `window`
/// (nm below the first interface; default 100 nm above the stack to 100 nm into the substrate).
pub fn depth_profile(
    stack: &Stack,
    wavelength_nm: f64,
    angle_rad: f64,
    polarization: Polarization,
    points: usize,
    window: Option<(f64, f64)>,
) -> Result<DepthProfile, ThinFilmError> {
    if !(2..=1_000_000).contains(&points) {
        return Err(ThinFilmError::Invalid(format!("{points} depth samples: give 2 to 1000000")));
    }
    let pick = |s: f64, p: f64| match polarization {
        Polarization::S => s,
        Polarization::P => p,
        Polarization::Average => 0.5 * (s + p),
    };
    let abs = stack.absorption(wavelength_nm, angle_rad)?;
    let clean = |v: f64| if v.abs() < 1e-14 { 0.0 } else { v };
    let layers: Vec<f64> = abs.layers_s.iter().zip(&abs.layers_p).map(|(s, p)| clean(pick(*s, *p))).collect();
    let (r, t, substrate) = (pick(abs.r_s, abs.r_p), pick(abs.t_s, abs.t_p), pick(abs.substrate_s, abs.substrate_p));
    let balance = r + t + layers.iter().sum::<f64>() + substrate - 1.0;
    let f = stack.profile(wavelength_nm, angle_rad)?;
    let depth_nm = f.depth_nm();
    let (z0, z1) = window.unwrap_or((-100.0, depth_nm + 100.0));
    if !(z0.is_finite() && z1.is_finite() && z0 < z1) {
        return Err(ThinFilmError::Invalid(format!(
            "depth window {z0} nm to {z1} nm is empty: the first depth must be above (less than) the second"
        )));
    }
    let pts: Vec<_> = (0..points).map(|i| f.at(z0 + (z1 - z0) * i as f64 / (points - 1) as f64)).collect();
    Ok(DepthProfile {
        r,
        t,
        layers,
        layer_names: stack
            .layers
            .iter()
            .map(|l| format!("{}{} {} nm", if l.incoherent { "inc:" } else { "" }, l.material.name(), l.thickness_nm))
            .collect(),
        substrate,
        balance,
        depth_nm,
        z_nm: pts.iter().map(|p| p.z_nm).collect(),
        medium: pts.iter().map(|p| p.medium).collect(),
        e2: pts.iter().map(|p| pick(p.e2_s, p.e2_p)).collect(),
        absorption_per_nm: pts.iter().map(|p| pick(p.absorption_s, p.absorption_p)).collect(),
        flux: pts.iter().map(|p| pick(p.poynting_s, p.poynting_p)).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_is_accounted_for_and_the_flux_drops_by_what_is_absorbed() {
        let stack = Stack::parse("air | Au 30nm | glass").unwrap();
        let p = depth_profile(&stack, 500.0, 0.3, Polarization::Average, 301, Some((-10.0, 50.0))).unwrap();
        assert!(p.balance.abs() < 1e-12, "{}", p.balance);
        // Flux just above the stack is 1 − R, just below it T; their difference is the gold's absorption.
        let at = |z: f64| p.z_nm.iter().position(|&x| (x - z).abs() < 1e-9).unwrap();
        let (top, bottom) = (p.flux[at(0.0)], p.flux[at(30.0)]);
        assert!((top - (1.0 - p.r)).abs() < 1e-9 && (bottom - p.t).abs() < 1e-9, "{top} {bottom} {p:?}");
        assert!((top - bottom - p.layers[0]).abs() < 1e-9);
        assert!(depth_profile(&stack, 500.0, 0.3, Polarization::S, 1, None).is_err());
        assert!(depth_profile(&stack, 500.0, 0.3, Polarization::S, 10, Some((5.0, 5.0))).is_err());
    }
}
