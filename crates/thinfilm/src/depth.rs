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
    /// What a reader of the profile should know: the default window stopping at an incoherent layer.
    pub notes: Vec<String>,
    /// Layers the samples do not resolve.
    pub warnings: Vec<String>,
}

/// The profile of `stack` at `wavelength_nm` and `angle_rad` for `points` depths evenly over `window`
/// (nm below the first interface; default [`default_window`]).
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
    let mut notes = Vec::new();
    let (z0, z1) = match window {
        Some(w) => w,
        None => {
            let (w, note) = default_window(stack);
            notes.extend(note);
            w
        }
    };
    if !(z0.is_finite() && z1.is_finite() && z0 < z1) {
        return Err(ThinFilmError::Invalid(format!(
            "depth window {z0} nm to {z1} nm is empty: the first depth must be above (less than) the second"
        )));
    }
    let warnings = unresolved_layers(stack, (z0, z1), points);
    let pts: Vec<_> = (0..points).map(|i| f.at(z0 + (z1 - z0) * i as f64 / (points - 1) as f64)).collect();
    Ok(DepthProfile {
        r,
        t,
        layers,
        layer_names: stack.layers.iter().map(layer_name).collect(),
        substrate,
        balance,
        depth_nm,
        z_nm: pts.iter().map(|p| p.z_nm).collect(),
        medium: pts.iter().map(|p| p.medium).collect(),
        e2: pts.iter().map(|p| pick(p.e2_s, p.e2_p)).collect(),
        absorption_per_nm: pts.iter().map(|p| pick(p.absorption_s, p.absorption_p)).collect(),
        flux: pts.iter().map(|p| pick(p.poynting_s, p.poynting_p)).collect(),
        notes,
        warnings,
    })
}

fn layer_name(l: &crate::stack::Layer) -> String {
    format!("{}{} {} nm", if l.incoherent { "inc:" } else { "" }, l.material.name(), l.thickness_nm)
}

/// The depth window when none is given: 100 nm above the stack to 100 nm into the substrate, or, for films on an
/// incoherent layer (a coated slide), to 100 nm into that layer, with a note. A millimetre of glass in the window
/// spread the samples a micrometre apart, and the films above it got none.
pub fn default_window(stack: &Stack) -> ((f64, f64), Option<String>) {
    let mut top = 0.0;
    for (i, l) in stack.layers.iter().enumerate() {
        if l.incoherent && stack.layers[..i].iter().any(|above| !above.incoherent) {
            let note = format!(
                "the depth window ends 100 nm into layer {} ({}), the incoherent layer under the films; \
                 --depth FROM:TO to see deeper",
                i + 1,
                layer_name(l)
            );
            return ((-100.0, top + 100.0), Some(note));
        }
        top += l.thickness_nm;
    }
    ((-100.0, top + 100.0), None)
}

/// A note for each layer inside the window that fewer than two of the `points` samples fall in: its |E|² and
/// absorption are not resolved (the table's absorbed fractions are exact whatever the samples).
fn unresolved_layers(stack: &Stack, (z0, z1): (f64, f64), points: usize) -> Vec<String> {
    let step = (z1 - z0) / (points - 1) as f64;
    let mut notes = Vec::new();
    let mut top = 0.0;
    for (i, l) in stack.layers.iter().enumerate() {
        let bottom = top + l.thickness_nm;
        let (a, b) = (top.max(z0), bottom.min(z1));
        if b > a {
            // Samples z0 + k·step with a ≤ z < b.
            let first = ((a - z0) / step).ceil();
            let inside = (((b - z0) / step).ceil() - first).max(0.0);
            if inside < 2.0 {
                notes.push(format!(
                    "layer {} ({}) gets {inside} of the {points} depth samples, which are {} nm apart: its |E|² and \
                     absorption density are not resolved (its absorbed fraction is exact); --depth FROM:TO to \
                     zoom in, or more --points",
                    i + 1,
                    layer_name(l),
                    if step >= 10.0 { format!("{step:.1}") } else { iridis_color::spectrum::short_number(step) }
                ));
            }
        }
        top = bottom;
    }
    notes
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

    /// Films on a 1 mm slide: the default window ends 100 nm into the slide (the 400 samples were 2.5 µm apart
    /// over the millimetre, and the 60 and 50 nm films got none), and says so; a slide on top of films keeps the
    /// whole stack in the window. A 30 nm film that one of five samples falls in is named; 400 samples resolve it.
    #[test]
    fn the_default_window_stops_at_a_slide_under_films_and_missed_layers_are_named() {
        let slide = Stack::parse("air | TiO2 60nm | Si 50nm | inc:glass 1mm | air").unwrap();
        let (w, note) = default_window(&slide);
        assert_eq!(w, (-100.0, 210.0));
        assert!(note.unwrap().contains("layer 3 (inc:glass 1000000 nm)"));
        let p = depth_profile(&slide, 550.0, 0.0, Polarization::Average, 400, None).unwrap();
        assert_eq!((p.z_nm[0], p.z_nm[399]), (-100.0, 210.0));
        assert!(p.medium.iter().filter(|&&m| m == 1).count() >= 70 && p.warnings.is_empty(), "{:?}", p.warnings);
        let on_top = Stack::parse("air | inc:glass 1mm | TiO2 60nm | air").unwrap();
        assert_eq!(default_window(&on_top), ((-100.0, 1_000_160.0), None));
        let p = depth_profile(&on_top, 550.0, 0.0, Polarization::Average, 400, None).unwrap();
        assert!(p.warnings.len() == 1 && p.warnings[0].contains("layer 2 (tio2 60 nm) gets 0 of the 400"));

        let gold = Stack::parse("air | Au 30nm | glass").unwrap();
        // Samples at −100, −42.5, 15, 72.5 and 130 nm: one in the film.
        let p = depth_profile(&gold, 500.0, 0.0, Polarization::Average, 5, None).unwrap();
        assert!(p.notes.is_empty() && p.warnings.len() == 1, "{p:?}");
        assert!(p.warnings[0].contains("gets 1 of the 5 depth samples, which are 57.5 nm apart"), "{}", p.warnings[0]);
        assert!(depth_profile(&gold, 500.0, 0.0, Polarization::Average, 400, None).unwrap().warnings.is_empty());
    }
}
