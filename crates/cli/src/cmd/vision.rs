//! `iridis vision`: how different spectra look to an animal — quantum catches, colour-space coordinates and
//! the receptor-noise-limited distances ΔS, ΔL in JND (`iridis-vision`; docs/vision.md). Parses, makes one
//! library call, prints.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args as ClapArgs;
use iridis_vision::{analyse_table, Analysis, Spec, SpectraTable};

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
    /// Units of an illuminant CSV: photons or energy.
    #[arg(long, default_value = "photons")]
    pub illuminant_units: String,
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
    /// Weber fraction of the achromatic channel.
    #[arg(long, default_value_t = 0.1)]
    pub weber_achromatic: f64,
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
            illuminant_units: Some(self.illuminant_units.clone()),
            illuminant_scale: Some(self.illuminant_scale),
            background: Some(self.background.clone()),
            weber: self.weber,
            weber_ref: self.weber_ref.clone(),
            densities: self.densities.clone(),
            receptor_noise: self.receptor_noise.clone(),
            noise: Some(self.noise.clone()),
            achromatic: self.achromatic.clone(),
            achromatic_weber: Some(self.weber_achromatic),
            space: Some(self.space.clone()),
        }
    }
}

pub fn run(a: VisionArgs) -> Result<()> {
    let spec = a.spec();
    let system = spec.system().context("--visual")?;
    let options = spec.options(&system)?;
    let mut table = SpectraTable::from_csv_path(&a.spectra)?;
    if a.percent {
        for (_, v) in &mut table.samples {
            v.iter_mut().for_each(|x| *x /= 100.0);
        }
    }
    let analysis = analyse_table(&table, &system, &options)?;
    if a.json {
        return crate::output::print_json(&serde_json::to_value(&analysis)?);
    }
    crate::output::write_stdout_bytes(text(&a, &table, &analysis).as_bytes())?;
    for n in &analysis.notes {
        eprintln!("note: {n}");
    }
    Ok(())
}

fn join(v: &[f64], digits: usize) -> String {
    v.iter().map(|x| format!("{x:.digits$}")).collect::<Vec<_>>().join(", ")
}

/// The analysis for people: what was assumed, then tables with units.
fn text(a: &VisionArgs, table: &SpectraTable, r: &Analysis) -> String {
    let mut o = String::new();
    let names = r.receptors.join(", ");
    let _ = writeln!(o, "visual       {} — receptors {names}", r.visual.name);
    let _ = writeln!(o, "source       {}", r.visual.source);
    let bg = match r.background.kind.as_str() {
        "none" => "no von Kries adaptation".to_string(),
        "grey" => format!("von Kries to a grey of reflectance {}", r.background.reflectance.unwrap_or(1.0)),
        _ => format!("von Kries to {}", r.background.source.as_deref().unwrap_or("a spectrum")),
    };
    let _ = writeln!(o, "light        {} ×{}; {bg}", r.illuminant, r.illuminant_scale);
    let noise = match (r.noise.weber, &r.noise.reference, &r.noise.densities) {
        (Some(w), Some(rf), Some(d)) => format!(
            "{} noise, Weber fraction {w} of {rf}, densities {} → e = {}",
            serde_json::to_value(r.noise.model).ok().and_then(|v| v.as_str().map(String::from)).unwrap_or_default(),
            d.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(":"),
            join(&r.noise.receptor_noise, 3)
        ),
        _ => format!("noise per receptor e = {}", join(&r.noise.receptor_noise, 3)),
    };
    let achro = match (&r.noise.achromatic, r.noise.achromatic_weber) {
        (Some(c), Some(w)) => format!("; achromatic: {c}, Weber fraction {w}"),
        _ => "; no achromatic channel".into(),
    };
    let _ = writeln!(o, "noise        {noise}{achro}");
    let _ = writeln!(
        o,
        "spectra      {}: {} samples, {}–{} nm",
        a.spectra.display(),
        table.samples.len(),
        r.wavelength_range_nm[0],
        r.wavelength_range_nm[1]
    );
    let width = r.samples.iter().map(|s| s.name.chars().count()).max().unwrap_or(6).max(6);
    let _ = writeln!(
        o,
        "\nquantum catches q ({}; relative catches in brackets)",
        if r.background.kind == "none" { "absolute" } else { "relative to the background" }
    );
    let _ = write!(o, "  {:<width$}", "sample");
    for n in &r.receptors {
        let _ = write!(o, " {n:>18}");
    }
    let _ = writeln!(o);
    for s in &r.samples {
        let _ = write!(o, "  {:<width$}", s.name);
        for (q, rel) in s.quantum_catches.iter().zip(&s.relative_catches) {
            let _ = write!(o, " {:>18}", format!("{q:.4} ({rel:.3})"));
        }
        let _ = writeln!(o);
    }
    if let Some(space) = r.colour_space {
        let _ = writeln!(
            o,
            "\ncolour space: {space} (position; hue in degrees from +x; chroma = distance from the achromatic point)"
        );
        for s in &r.samples {
            if let Some(c) = &s.coordinates {
                let hue = c.hue_deg.map_or("—".to_string(), |h| format!("{h:.1}°"));
                let elev = c.elevation_deg.map_or(String::new(), |e| format!(", elevation {e:.1}°"));
                let _ = writeln!(
                    o,
                    "  {:<width$}  ({})  hue {hue}{elev}, chroma {:.4}",
                    s.name,
                    join(&c.position, 4),
                    c.chroma
                );
            }
        }
    }
    let _ = writeln!(o, "\ndistances (JND: 1 is just noticeable)");
    let _ = writeln!(o, "  {:<width$}  {:<width$}  {:>10}  {:>10}", "a", "b", "ΔS (JND)", "ΔL (JND)");
    let f = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x:.3}"));
    for d in &r.distances {
        let _ = writeln!(o, "  {:<width$}  {:<width$}  {:>10}  {:>10}", d.a, d.b, f(d.delta_s), f(d.delta_l));
    }
    o
}
