//! `iridis vision`: how different spectra look to an animal — quantum catches, colour-space coordinates and
//! the receptor-noise-limited distances ΔS, ΔL in JND (`iridis-vision`; docs/vision.md). Parses, makes one
//! library call, prints.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args as ClapArgs;
use iridis_vision::Spec;

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
SPECTRA is a CSV as pavo reads and writes it: a wavelength column (nm) and one column per sample, the first line
naming them (reflectances as fractions; --percent for percent). Every pair of samples is compared.

Quantum catches Q = ∫ R(λ) I(λ) T(λ) S(λ) dλ (trapezoid rule on the spectra's grid; I the illuminant in photon
flux, T the ocular media, S each receptor's sensitivity with unit area over 300–700 nm) are adapted to the
background (von Kries: q = Q/Q_background; --background none keeps Q). ΔS is the receptor-noise-limited colour
distance of Vorobyev & Osorio (1998) in JND from Δf = ln(q_a/q_b) and the noise of each receptor channel
(e_i = weber·√(density_ref/density_i), or --receptor-noise per receptor; --noise quantum adds 2/(Q_a + Q_b));
ΔL = |ln(A_a/A_b)|/weber_achromatic for the achromatic channel A. Coordinates: the tetrahedron (4 receptors),
the triangle (3), the line (2) or the bee hexagon (Chittka 1992).

Visual systems (--visual): human, avian-uv, avian-v, bluetit, honeybee, ball-python (sources: docs/vision.md), or
a CSV of sensitivities (wavelength, one column per receptor, short to long); or --lambda-max for templates
(Govardovskii et al. 2000) with --oil-droplets (Hart & Vorobyev 2005). Illuminants: d65, d50, a, e, bluesky,
forestshade (Endler 1993), ideal, or a CSV (--illuminant-units photons|energy).

Examples:
  iridis vision data/examples/vision_spectra.csv --visual bluetit
  iridis vision data/examples/vision_spectra.csv --visual avian-uv --illuminant forestshade --json
  iridis vision data/examples/vision_spectra.csv --visual honeybee --background data/examples/colorchecker_green.csv
  iridis vision data/examples/vision_spectra.csv --lambda-max 360,445,510,565 --oil-droplets T,C:415,Y:505,R:570 --densities 1:2:2:4
  iridis vision data/examples/vision_spectra.csv --visual human --weber 0.05 --space none")]
pub struct VisionArgs {
    /// Spectra CSV: a wavelength column (nm) and one column per sample.
    pub spectra: PathBuf,
    /// Visual system: human, avian-uv, avian-v, bluetit, honeybee, ball-python, or a CSV of sensitivities.
    #[arg(long, conflicts_with = "lambda_max")]
    pub visual: Option<String>,
    /// Pigment λmax values (nm) for template receptors, e.g. 344,436,556.
    #[arg(long)]
    pub lambda_max: Option<String>,
    /// Chromophore of the --lambda-max pigments: a1 or a2.
    #[arg(long, requires = "lambda_max")]
    pub chromophore: Option<String>,
    /// Oil droplets, one per --lambda-max: none, TYPE:λCUT (T, C, Y, R, P; e.g. C:413) or λCUT:BMID.
    #[arg(long, requires = "lambda_max")]
    pub oil_droplets: Option<String>,
    /// Ocular-media transmittance CSV (wavelength_nm, transmittance), for a custom system.
    #[arg(long)]
    pub ocular_media: Option<String>,
    /// Illuminant: d65, d50, a, e, bluesky, forestshade, ideal, or a CSV (wavelength_nm, flux).
    #[arg(long, default_value = "d65")]
    pub illuminant: String,
    /// Units of an illuminant CSV: photons or energy [default: photons]; refused with a built-in light.
    #[arg(long)]
    pub illuminant_units: Option<String>,
    /// Multiplies the illuminant (matters for absolute catches and --noise quantum only).
    #[arg(long, default_value_t = 1.0)]
    pub illuminant_scale: f64,
    /// Background for von Kries adaptation: grey, grey:REFLECTANCE, none, or a reflectance CSV.
    #[arg(long, default_value = "grey")]
    pub background: String,
    /// Weber fraction of the reference receptor (default: the visual system's).
    #[arg(long)]
    pub weber: Option<f64>,
    /// Reference receptor of --weber: a name, a position (1 = shortest) or longest.
    #[arg(long)]
    pub weber_ref: Option<String>,
    /// Relative receptor densities, short to long, e.g. 1:2:2:4.
    #[arg(long)]
    pub densities: Option<String>,
    /// Noise per receptor channel instead of --weber and --densities, e.g. 0.13,0.06,0.12.
    #[arg(long)]
    pub receptor_noise: Option<String>,
    /// Noise model: neural, or quantum (adds photon shot noise from the absolute catches).
    #[arg(long, default_value = "neural")]
    pub noise: String,
    /// Achromatic channel for ΔL: none, a receptor (name or position) or a sum NAME+NAME (default: the system's).
    #[arg(long)]
    pub achromatic: Option<String>,
    /// Weber fraction of the achromatic channel [default: 0.1]; refused when there is none.
    #[arg(long)]
    pub weber_achromatic: Option<f64>,
    /// Colour space of the coordinates: auto, line, triangle, tetrahedron, hexagon or none.
    #[arg(long, default_value = "auto")]
    pub space: String,
    /// The spectra are in percent: divide them by 100.
    #[arg(long)]
    pub percent: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

impl VisionArgs {
    fn spec(&self) -> Spec {
        Spec {
            visual: self.visual.clone(),
            lambda_max: self.lambda_max.clone(),
            chromophore: self.chromophore.clone(),
            oil_droplets: self.oil_droplets.clone(),
            ocular_media: self.ocular_media.clone(),
            illuminant: Some(self.illuminant.clone()),
            illuminant_units: self.illuminant_units.clone(),
            illuminant_scale: Some(self.illuminant_scale),
            background: Some(self.background.clone()),
            weber: self.weber,
            weber_ref: self.weber_ref.clone(),
            densities: self.densities.clone(),
            receptor_noise: self.receptor_noise.clone(),
            noise: Some(self.noise.clone()),
            achromatic: self.achromatic.clone(),
            achromatic_weber: self.weber_achromatic,
            space: Some(self.space.clone()),
        }
    }
}

pub fn run(a: VisionArgs) -> Result<()> {
    let v = iridis_api::vision::analyse_file(&a.spectra, &a.spec(), a.percent)?;
    crate::output::print_answer(a.json, || v.to_json(), || v.text())?;
    if !a.json {
        v.analysis.notes.iter().for_each(|n| eprintln!("note: {n}"));
    }
    Ok(())
}
