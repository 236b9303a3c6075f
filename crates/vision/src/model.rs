//! The receptor-noise-limited model (Vorobyev & Osorio 1998) from spectra: quantum catches, von Kries
//! adaptation, colour distance ΔS and achromatic distance ΔL in units of just-noticeable differences (JND),
//! and colour-space coordinates. Equations and their sources: `docs/vision.md`.

use serde::Serialize;

use crate::light::{Background, BackgroundInfo, Light};
pub use crate::noise::ReceptorNoise;
use crate::space::{self, Coordinates, Space};
use crate::system::{Achromatic, SystemInfo, VisualSystem};
use crate::table::SpectraTable;
use crate::VisionError;

/// Neural noise only (constant Weber fractions: bright light), or neural plus photon shot noise
/// `e_i² = e_neural,i² + 2/(Q_i,a + Q_i,b)` with the absolute catches `Q` (pavo's `noise = "quantum"`; the
/// catches are then photon counts, set with the illuminant's scale).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum NoiseModel {
    #[default]
    Neural,
    Quantum,
}

iridis_color::names! {
    NoiseModel {
        Neural => "neural",
        Quantum => "quantum",
    }
    else |s| -> VisionError { VisionError::invalid(format!("unknown noise model '{s}'; expected neural or quantum")) }
}

/// Which achromatic channel ΔL uses.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum AchromaticChoice {
    /// The visual system's own (double cones for birds, the green receptor for bees, …).
    #[default]
    System,
    /// No ΔL.
    Off,
    Use(Achromatic),
}

impl AchromaticChoice {
    /// The channel ΔL uses for `system`, or none.
    pub fn resolve(&self, system: &VisualSystem) -> Option<Achromatic> {
        match self {
            AchromaticChoice::System => system.achromatic.clone(),
            AchromaticChoice::Off => None,
            AchromaticChoice::Use(a) => Some(a.clone()),
        }
    }
}

/// The conditions of an analysis. [`Options::default`]: D65, von Kries to an ideal grey, the system's
/// receptor noise and achromatic channel, neural noise, achromatic Weber fraction 0.1, the system's space.
#[derive(Debug, Clone)]
pub struct Options {
    pub illuminant: Light,
    /// Multiplies the illuminant's photon flux: matters only for absolute catches and quantum noise.
    pub illuminant_scale: f64,
    pub background: Background,
    /// Receptor noise; `None`: the system's.
    pub noise: Option<ReceptorNoise>,
    pub noise_model: NoiseModel,
    pub achromatic: AchromaticChoice,
    /// Weber fraction of the achromatic channel (pavo's `weber.achro`).
    pub achromatic_weber: f64,
    pub space: Space,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            illuminant: Light::builtin("d65").expect("built-in D65"),
            illuminant_scale: 1.0,
            background: Background::Grey(1.0),
            noise: None,
            noise_model: NoiseModel::Neural,
            achromatic: AchromaticChoice::System,
            achromatic_weber: 0.1,
            space: Space::Auto,
        }
    }
}

/// Everything an analysis found: what was assumed, each sample's catches and coordinates, and the distance
/// between every pair of samples. Serialises to the JSON of `iridis vision --json` (docs/json.md).
#[derive(Debug, Clone, Serialize)]
pub struct Analysis {
    pub visual: SystemInfo,
    /// Receptor names, short to long: the order of every per-receptor array.
    pub receptors: Vec<String>,
    pub illuminant: String,
    pub illuminant_scale: f64,
    pub background: BackgroundInfo,
    pub noise: NoiseInfo,
    /// The spectra's wavelength range, the range integrated over.
    pub wavelength_range_nm: [f64; 2],
    /// The space of every sample's `coordinates`, null for none.
    pub colour_space: Option<Space>,
    pub samples: Vec<Sample>,
    /// Every pair of samples (a before b in input order).
    pub distances: Vec<Distance>,
    /// Things the numbers depend on that a reader should know (spectra not covering a receptor, …).
    pub notes: Vec<String>,
}

/// The noise behind the JND.
#[derive(Debug, Clone, Serialize)]
pub struct NoiseInfo {
    pub model: NoiseModel,
    /// The Weber fraction of the reference receptor, null when noise is given per receptor.
    pub weber: Option<f64>,
    /// The reference receptor, null when noise is given per receptor.
    pub reference: Option<String>,
    /// Relative receptor densities, null when noise is given per receptor.
    pub densities: Option<Vec<f64>>,
    /// The neural noise `e_i` of each receptor channel.
    pub receptor_noise: Vec<f64>,
    /// The achromatic channel, null when there is none.
    pub achromatic: Option<String>,
    /// Its Weber fraction, null when there is no achromatic channel.
    pub achromatic_weber: Option<f64>,
}

/// One sample's receptor signals.
#[derive(Debug, Clone, Serialize)]
pub struct Sample {
    pub name: String,
    /// The catches ΔS is computed from: von Kries-adapted `q_i = Q_i / Q_i,background` (absolute `Q_i` with
    /// no background).
    pub quantum_catches: Vec<f64>,
    /// `Q_i = ∫ R(λ) I(λ) T(λ) S_i(λ) dλ` (relative units: unit-area sensitivities, the illuminant as given).
    pub absolute_catches: Vec<f64>,
    /// `quantum_catches / Σ quantum_catches`.
    pub relative_catches: Vec<f64>,
    /// The absolute catch of the achromatic channel, null without one.
    pub achromatic_catch: Option<f64>,
    /// The sample's place in the colour space, null with none.
    pub coordinates: Option<Coordinates>,
}

/// The distance between two samples, in JND.
#[derive(Debug, Clone, Serialize)]
pub struct Distance {
    pub a: String,
    pub b: String,
    /// Colour (chromatic) distance ΔS; null when a catch is zero (no logarithm) or with one receptor.
    pub delta_s: Option<f64>,
    /// Achromatic distance ΔL; null without an achromatic channel or when its catch is zero.
    pub delta_l: Option<f64>,
}

impl Analysis {
    /// The distance between two samples by name (either order).
    pub fn distance(&self, a: &str, b: &str) -> Option<&Distance> {
        self.distances.iter().find(|d| (d.a == a && d.b == b) || (d.a == b && d.b == a))
    }
}

/// `ΔS` in JND from the receptor signal differences `Δf_i = ln(q_i,a / q_i,b)` and channel noises `e_i`, for
/// any number of receptors n ≥ 2 (Vorobyev & Osorio 1998; the n-receptor sum as in pavo's `coldist`):
/// `ΔS² = Σ_{i<j} (Π_{k≠i,j} e_k)² (Δf_i − Δf_j)² / Σ_i (Π_{k≠i} e_k)²`.
/// For n = 2 it is `(Δf_1 − Δf_2)²/(e_1² + e_2²)`.
pub fn delta_s(delta_f: &[f64], e: &[f64]) -> Option<f64> {
    let n = delta_f.len();
    if n < 2 || e.len() != n {
        return None;
    }
    let prod_except =
        |skip: &[usize]| -> f64 { e.iter().enumerate().filter(|(k, _)| !skip.contains(k)).map(|(_, v)| v).product() };
    let mut num = 0.0;
    for i in 0..n {
        for j in i + 1..n {
            num += (prod_except(&[i, j]) * (delta_f[i] - delta_f[j])).powi(2);
        }
    }
    let den: f64 = (0..n).map(|i| prod_except(&[i]).powi(2)).sum();
    Some((num / den).sqrt())
}

/// Trapezoid weights of a strictly increasing grid.
fn trapezoid(w: &[f64]) -> Vec<f64> {
    iridis_color::spectrum::trapezoid_weights(w)
}

/// From spectra to what an animal sees: each sample's quantum catches and coordinates and the ΔS, ΔL between
/// every pair. `spectra` are (name, values) on `wavelengths_nm` (strictly increasing, nm): reflectances (or
/// transmittances, or any factor on the illuminant), as fractions. Integrals run over the spectra's grid by
/// the trapezoid rule, a grid coarser than 1 nm interpolated onto 1 nm first ([`SpectraTable::on_1nm_grid`]);
/// sensitivities, light and background are sampled onto it.
pub fn analyse(
    spectra: &[(String, Vec<f64>)],
    wavelengths_nm: &[f64],
    system: &VisualSystem,
    options: &Options,
) -> Result<Analysis, VisionError> {
    let table = SpectraTable::new(wavelengths_nm.to_vec(), spectra.to_vec())?;
    analyse_table(&table, system, options)
}

/// [`analyse`] on a [`SpectraTable`] (a pavo CSV as read).
pub fn analyse_table(table: &SpectraTable, system: &VisualSystem, options: &Options) -> Result<Analysis, VisionError> {
    iridis_color::spectrum::check_nanometres(&table.wavelengths_nm).map_err(|e| VisionError::invalid(e.to_string()))?;
    let mut notes = Vec::new();
    let fine = table.on_1nm_grid();
    let table = match &fine {
        Some((t, widest)) => {
            notes.push(format!(
                "the spectra, sampled up to {widest} nm apart, were interpolated linearly onto 1 nm (as pavo's \
                 as.rspec does) before the catches were integrated"
            ));
            t
        }
        None => table,
    };
    let wl = &table.wavelengths_nm;
    let n = system.receptors.len();
    if !(options.illuminant_scale.is_finite() && options.illuminant_scale > 0.0) {
        return Err(VisionError::invalid(format!(
            "illuminant scale {} must be a positive number",
            options.illuminant_scale
        )));
    }
    if !(options.achromatic_weber.is_finite() && options.achromatic_weber > 0.0) {
        return Err(VisionError::invalid(format!(
            "achromatic Weber fraction {} must be a positive number",
            options.achromatic_weber
        )));
    }
    let noise = options.noise.clone().unwrap_or_else(|| system.noise.clone());
    noise.check(n)?;
    let achromatic = options.achromatic.resolve(system);
    if let Some(a) = &achromatic {
        let indices = match a {
            Achromatic::Receptor(i) => vec![*i],
            Achromatic::Sum(v) => v.clone(),
            Achromatic::Own(_) => Vec::new(),
        };
        if let Some(i) = indices.iter().find(|i| **i >= n) {
            return Err(VisionError::invalid(format!("achromatic receptor {} of {n}", i + 1)));
        }
    }
    let space = match options.space {
        Space::Auto => match system.space {
            Space::Auto => Space::for_receptors(n),
            s => s,
        },
        s => s,
    };
    if let Some(k) = space.receptors() {
        if k != n {
            return Err(VisionError::invalid(format!("the {space} needs {k} receptors; {} has {n}", system.name)));
        }
    }
    if space == Space::Hexagon && options.background == Background::None {
        return Err(VisionError::invalid(
            "the hexagon needs a background to adapt to (Chittka 1992): give --background grey or a spectrum",
        ));
    }

    // Per-sample-independent factors: weight × light × ocular media × sensitivity.
    let trap = trapezoid(wl);
    let light: Vec<f64> = wl
        .iter()
        .zip(&trap)
        .map(|(&l, w)| w * options.illuminant.at(l) * options.illuminant_scale * system.media(l))
        .collect();
    let kernel: Vec<Vec<f64>> =
        system.receptors.iter().map(|r| wl.iter().zip(&light).map(|(&l, k)| k * r.sensitivity(l)).collect()).collect();
    let achro_kernel: Option<Vec<f64>> = achromatic.as_ref().map(|a| match a {
        Achromatic::Receptor(i) => kernel[*i].clone(),
        Achromatic::Sum(v) => (0..wl.len()).map(|k| v.iter().map(|i| kernel[*i][k]).sum()).collect(),
        Achromatic::Own(r) => wl.iter().zip(&light).map(|(&l, k)| k * r.sensitivity(l)).collect(),
    });
    let catch = |kern: &[f64], values: &dyn Fn(usize) -> f64| -> f64 {
        kern.iter().enumerate().map(|(k, s)| s * values(k)).sum()
    };

    // von Kries: the background's catch under the same light (Vorobyev & Osorio 1998; Chittka 1992).
    let background_catch: Option<Vec<f64>> = match &options.background {
        Background::None => None,
        b => {
            let refl: Vec<f64> = wl.iter().map(|&l| b.reflectance(l).unwrap_or(0.0)).collect();
            let qb: Vec<f64> = kernel.iter().map(|kern| catch(kern, &|k| refl[k])).collect();
            if let Some(i) = qb.iter().position(|q| q.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)) {
                return Err(VisionError::invalid(format!(
                    "receptor {} catches no light from the background over the spectra's {}–{} nm under {}: \
                     von Kries adaptation is undefined",
                    system.receptors[i].name,
                    wl[0],
                    wl[wl.len() - 1],
                    options.illuminant.name
                )));
            }
            Some(qb)
        }
    };

    let (lo, hi) = (wl[0], wl[wl.len() - 1]);
    coverage_notes(system, options, lo, hi, &mut notes)?;
    let mut samples = Vec::with_capacity(table.samples.len());
    for (name, values) in &table.samples {
        if let Some(v) = values.iter().find(|v| **v < 0.0) {
            notes.push(format!("spectrum '{name}' has negative values (e.g. {v}); they were used as they are"));
        }
        let absolute: Vec<f64> = kernel.iter().map(|kern| catch(kern, &|k| values[k])).collect();
        let adapted: Vec<f64> = match &background_catch {
            Some(qb) => absolute.iter().zip(qb).map(|(q, b)| q / b).collect(),
            None => absolute.clone(),
        };
        let total: f64 = adapted.iter().sum();
        let relative: Vec<f64> = adapted.iter().map(|q| if total != 0.0 { q / total } else { f64::NAN }).collect();
        let coordinates = match space {
            Space::Hexagon => space::hexagon(&adapted),
            Space::None | Space::Auto => None,
            s if total > 0.0 => space::simplex(s, &relative),
            _ => None,
        };
        samples.push(Sample {
            name: name.clone(),
            quantum_catches: adapted,
            absolute_catches: absolute,
            relative_catches: relative.iter().map(|v| if v.is_finite() { *v } else { 0.0 }).collect(),
            achromatic_catch: achro_kernel.as_ref().map(|kern| catch(kern, &|k| values[k])),
            coordinates,
        });
    }
    for s in &samples {
        if let Some(i) = s.quantum_catches.iter().position(|q| q.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater))
        {
            notes.push(format!(
                "sample '{}': receptor {} catches no light; its ΔS is undefined (null)",
                s.name, system.receptors[i].name
            ));
        }
    }
    if n < 2 {
        notes.push("one receptor class: no colour vision, ΔS is undefined (null)".into());
    }

    let e_neural = noise.per_receptor();
    let mut distances = Vec::with_capacity(samples.len() * samples.len().saturating_sub(1) / 2);
    for a in 0..samples.len() {
        for b in a + 1..samples.len() {
            let (sa, sb) = (&samples[a], &samples[b]);
            let logs_ok = sa.quantum_catches.iter().chain(&sb.quantum_catches).all(|q| *q > 0.0);
            let delta_s_value = if logs_ok {
                let df: Vec<f64> =
                    sa.quantum_catches.iter().zip(&sb.quantum_catches).map(|(x, y)| (x / y).ln()).collect();
                let e: Vec<f64> = match options.noise_model {
                    NoiseModel::Neural => e_neural.clone(),
                    NoiseModel::Quantum => e_neural
                        .iter()
                        .enumerate()
                        .map(|(i, en)| (en * en + 2.0 / (sa.absolute_catches[i] + sb.absolute_catches[i])).sqrt())
                        .collect(),
                };
                delta_s(&df, &e)
            } else {
                None
            };
            let delta_l = match (sa.achromatic_catch, sb.achromatic_catch) {
                (Some(x), Some(y)) if x > 0.0 && y > 0.0 => {
                    let w = match options.noise_model {
                        NoiseModel::Neural => options.achromatic_weber,
                        NoiseModel::Quantum => (options.achromatic_weber.powi(2) + 2.0 / (x + y)).sqrt(),
                    };
                    Some((x / y).ln().abs() / w)
                }
                _ => None,
            };
            distances.push(Distance { a: sa.name.clone(), b: sb.name.clone(), delta_s: delta_s_value, delta_l });
        }
    }

    let (weber, reference, densities) = match &noise {
        ReceptorNoise::Weber { weber, reference, densities } => {
            (Some(*weber), Some(system.receptors[*reference].name.clone()), Some(densities.clone()))
        }
        ReceptorNoise::PerReceptor(_) => (None, None, None),
    };
    Ok(Analysis {
        visual: system.info(),
        receptors: system.receptor_names(),
        illuminant: options.illuminant.name.clone(),
        illuminant_scale: options.illuminant_scale,
        background: options.background.describe(),
        noise: NoiseInfo {
            model: options.noise_model,
            weber,
            reference,
            densities,
            receptor_noise: e_neural,
            achromatic: achromatic.as_ref().map(|a| system.achromatic_name(a)),
            achromatic_weber: achromatic.as_ref().map(|_| options.achromatic_weber),
        },
        wavelength_range_nm: [lo, hi],
        colour_space: (space != Space::None).then_some(space),
        samples,
        distances,
        notes,
    })
}

/// Says when the spectra (or the light) leave out part of a receptor's sensitivity.
/// Refuses spectra that hold under 1 % of a receptor's sensitivity: its relative catch would be the ratio of its
/// tails in the sample and in the background (a 500–510 nm spectrum gave the blue tit's UVS a catch of 0.2).
fn coverage_notes(
    system: &VisualSystem,
    options: &Options,
    lo: f64,
    hi: f64,
    notes: &mut Vec<String>,
) -> Result<(), VisionError> {
    for r in &system.receptors {
        // Over the range sensitivities are normalised on (pavo's 300–700 nm): natural light has next to nothing
        // below 300 nm, so the β band of a UV pigment's template reaching below it is not a gap in the data.
        let grid = (300..=700).map(f64::from);
        let (mut inside, mut total) = (0.0, 0.0);
        for l in grid {
            let s = r.sensitivity(l) * system.media(l);
            total += s;
            if (lo..=hi).contains(&l) {
                inside += s;
            }
        }
        if total > 0.0 && inside / total < 0.01 {
            return Err(VisionError::invalid(format!(
                "the spectra cover {lo}–{hi} nm, which holds {:.2} % of receptor {}'s sensitivity over 300–700 nm: its \
                 catch would be of its tails alone; give spectra over most of 300–700 nm",
                100.0 * inside / total,
                r.name
            )));
        }
        if total > 0.0 && inside / total < 0.99 {
            notes.push(format!(
                "the spectra cover {lo}–{hi} nm: {:.1} % of receptor {}'s sensitivity over 300–700 nm lies outside and is left out",
                100.0 * (1.0 - inside / total),
                r.name
            ));
        }
    }
    if let Some((llo, lhi)) = options.illuminant.range_nm() {
        if lo < llo || hi > lhi {
            notes.push(format!(
                "the illuminant {} is tabulated over {llo}–{lhi} nm only; beyond it the spectra get no light",
                options.illuminant.name
            ));
        }
    }
    Ok(())
}
