//! The command line's own option blocks and value parsers; those of lengths and angles are the library's
//! (`iridis_api::args`), with the option structs that derive `clap::Args` there.

#![allow(dead_code)] // not every command uses every parser

use iridis_diffraction::geometry::FresnelConvention;

pub use iridis_api::args::{angle_rad, fresnel_convention, length_nm, positive_length_nm};

/// Parses a direction `θ[,φ]` of the flag `--FLAG` (`--incidence`, `--light`, `--view`) into `(θ, φ)` in
/// radians, refusing θ outside [0°, 90°) (the BRDF is defined above the surface).
pub fn polar_azimuth(flag: &str, s: &str) -> anyhow::Result<(f64, f64)> {
    let mut parts = s.split(',');
    let theta = angle_rad(parts.next().unwrap_or("")).map_err(|e| anyhow::anyhow!("--{flag} '{s}': {e}"))?;
    let phi = match parts.next() {
        Some(p) => angle_rad(p).map_err(|e| anyhow::anyhow!("--{flag} '{s}': {e}"))?,
        None => 0.0,
    };
    if parts.next().is_some() {
        anyhow::bail!("--{flag} '{s}': write θ or θ,φ, e.g. 20deg,180deg");
    }
    if !(0.0..std::f64::consts::FRAC_PI_2).contains(&theta) {
        anyhow::bail!("--{flag} '{s}': θ must be in [0°, 90°) (above the surface)");
    }
    Ok((theta, phi))
}

/// The rigorous method's options, flattened into `brdf eval`, `brdf-map` and `testbench`.
#[derive(Debug, Clone, clap::Args)]
pub struct RigorousOpts {
    /// With --method rigorous: the medium under the relief, a library name (gold, keratin, …), n=1.5,
    /// n=0.2+3.4i or file:PATH [default: n=1.5]. `brdf eval`'s scalar methods estimate their error on a scan
    /// over it [default there: keratin].
    #[arg(long)]
    pub material: Option<String>,
    /// With --method rigorous: the unit cell, whole (SURFACE is one period of the grating) or auto (a scan's
    /// strongest period, its profile averaged along the ridges: a 1-D grating at that orientation).
    #[arg(long, value_name = "whole|auto", default_value = "whole")]
    pub unit_cell: String,
}

impl RigorousOpts {
    /// Whether `--unit-cell auto` was given.
    pub fn auto(&self) -> anyhow::Result<bool> {
        iridis_api::brdf::unit_cell_auto(&self.unit_cell)
    }

    /// Puts the options into the facade's model options (the library refuses what the method cannot use).
    pub fn apply(&self, model: &mut iridis_api::ModelOptions) -> anyhow::Result<()> {
        model.material = self.material.clone();
        model.unit_cell_auto = self.auto()?;
        Ok(())
    }
}

// ----------------------------------------------------------------------------------------------------------
// Thin films (`iridis thinfilm …`)

use anyhow::{bail, Result};
use iridis_api::film_run::{RoughLight, RoughLights};
use iridis_api::rough::RoughOptions;
use iridis_thinfilm::rough::DiffuseTransport;
use std::path::PathBuf;

/// Flags of the rough model, flattened into `spectrum`, `color`, `table`, `chart` and `bench`.
#[derive(Debug, Clone, clap::Args)]
pub struct RoughArgs {
    /// Rough substrate (LSRS model with the HTSG BRDF): rms roughness σ of the last interface, e.g. 25nm.
    /// Needs --correlation. Valid for σ > 0, 2σ/τ ≤ 1 and τ²/(2√3σ) ≥ λ in the medium above the substrate.
    #[arg(long, value_parser = length_nm, requires = "correlation", help_heading = "Rough substrate (LSRS)")]
    pub roughness: Option<f64>,
    /// Autocorrelation length τ of the rough interface, e.g. 300nm (Sussenbach Listing 3.6).
    #[arg(long, value_parser = length_nm, requires = "roughness", help_heading = "Rough substrate (LSRS)")]
    pub correlation: Option<f64>,
    /// Light angle θ_l of the diffuse part (spectrum, color); default: the view angle (--angle).
    #[arg(long, value_parser = angle_rad, requires = "roughness", help_heading = "Rough substrate (LSRS)")]
    pub light_angle: Option<f64>,
    /// Light angles FROM:TO:STEP of the table's diffuse part; default: the same as --angles.
    #[arg(long, requires = "roughness", help_heading = "Rough substrate (LSRS)")]
    pub light_angles: Option<String>,
    /// Azimuth of the light relative to the viewer; 180deg puts the light on the far side of the normal in
    /// the viewer's plane (the mirror configuration).
    #[arg(long, default_value = "180deg", value_parser = angle_rad, requires = "roughness")]
    #[arg(help_heading = "Rough substrate (LSRS)")]
    pub azimuth: f64,
    /// Terms of the HTSG directional-diffuse series (the thesis' D-iterations, 5 in Listing 3.6); default:
    /// as many as needed for an error bound of 1e-6 of the lobe's peak.
    #[arg(long, requires = "roughness", help_heading = "Rough substrate (LSRS)")]
    pub d_iterations: Option<usize>,
    /// How diffuse light crosses the layers: multiple (the default: the light the layers turn back and the
    /// light trapped beyond the escape cone is scattered again until it leaves; reciprocal, a lossless film on
    /// a mirror reflects everything), single (alias reciprocal: one scattering, power transmittances both
    /// ways; faster, without that light, and not energy-conserving: up to 4 % more than received on a lossless
    /// film over a mirror; docs/rough-films.md) or thesis (eq. 3.18–3.19 as printed; creates
    /// energy, not reciprocal — for comparison with the thesis only).
    #[arg(long, default_value = "multiple", value_name = "multiple|single|thesis", value_parser = diffuse_transport)]
    #[arg(requires = "roughness", help_heading = "Rough substrate (LSRS)")]
    pub diffuse_transport: DiffuseTransport,
}

fn diffuse_transport(s: &str) -> Result<DiffuseTransport, String> {
    DiffuseTransport::parse(s).map_err(|e| e.to_string())
}

impl RoughArgs {
    /// True when the rough model was asked for.
    pub fn is_set(&self) -> bool {
        self.roughness.is_some() || self.correlation.is_some()
    }

    /// The facade's rough-model options (both σ and τ given).
    pub fn options(&self) -> Result<RoughOptions> {
        let (Some(sigma_nm), Some(tau_nm)) = (self.roughness, self.correlation) else {
            bail!("the rough model needs both --roughness and --correlation");
        };
        Ok(RoughOptions { sigma_nm, tau_nm, d_iterations: self.d_iterations, transport: self.diffuse_transport })
    }

    /// The rough substrate of spectrum, color, chart and bench, when asked for (the light at --light-angle, else
    /// at the view angle; --azimuth); refuses the table's --light-angles.
    pub fn light(&self) -> Result<Option<RoughLight>> {
        if !self.is_set() {
            return Ok(None);
        }
        if self.light_angles.is_some() {
            bail!("--light-angles is for 'table' (spectrum, color and chart take --light-angle)");
        }
        Ok(Some(RoughLight { options: self.options()?, light: self.light_angle, azimuth: self.azimuth }))
    }

    /// The rough substrate of table, when asked for (--light-angles, --azimuth); refuses --light-angle.
    pub fn lights(&self) -> Result<Option<RoughLights>> {
        if !self.is_set() {
            return Ok(None);
        }
        if self.light_angle.is_some() {
            bail!("--light-angle is for 'spectrum' and 'color'; the table takes --light-angles FROM:TO:STEP");
        }
        Ok(Some(RoughLights { options: self.options()?, lights: self.light_angles.clone(), azimuth: self.azimuth }))
    }
}

#[derive(Debug, clap::Args)]
/// `iridis thinfilm profile`.
pub struct ProfileArgs {
    /// The stack, e.g. "air | Au 30nm | glass" (inc: layers: incoherent intensities, no interference, in them).
    #[arg(long)]
    pub stack: String,
    /// Vacuum wavelength (with unit).
    #[arg(long, value_parser = length_nm)]
    pub wavelength: f64,
    /// Angle of incidence (0deg–90deg).
    #[arg(long, default_value = "0deg", value_parser = angle_rad)]
    pub angle: f64,
    /// avg (unpolarised), s or p.
    #[arg(long, default_value = "avg")]
    pub polarization: String,
    /// Number of depth samples of the profile, evenly over its window (--depth).
    #[arg(long, default_value_t = 400)]
    pub points: usize,
    /// The depth window of the profile, FROM:TO below the first interface (e.g. --depth=-20nm:200nm); default
    /// 100 nm above the stack to 100 nm into the substrate, or into the first inc: layer under the films.
    #[arg(long, value_name = "FROM:TO")]
    pub depth: Option<String>,
    /// Print JSON (absorption per layer and the profile).
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print the profile as CSV (z_nm, medium, E2, absorption_per_nm, flux).
    #[arg(long)]
    pub csv: bool,
    /// Plot |E|² and the absorbed power density against depth (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

#[derive(Debug, clap::Args)]
/// `iridis thinfilm fit`.
pub struct FitArgs {
    /// The measured spectrum: columns of wavelength and R, T, or psi and delta (degrees), separated by
    /// commas, tabs, semicolons or spaces, with or without a header ("Wavelength (nm),Reflectance (%)", …);
    /// what was read is printed (separator, columns, unit, percent).
    pub measured: PathBuf,
    #[command(flatten)]
    pub request: iridis_api::film_fit::FitRequest,
    /// Plot measured against fitted (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Write the fitted curve as CSV (wavelength_nm, measured, fitted, residual).
    #[arg(long)]
    pub output: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Options shared by the commands that build Taylor terms (`precompute`, `brdf-map`, `brdf eval`, `brdf vision`).
#[derive(Debug, Clone, clap::Args)]
pub struct ModelOpts {
    /// Taylor terms: `auto` (from the remainder bound) or a number N (terms 0..N).
    #[arg(long, default_value = "auto")]
    pub terms: String,
    /// Coherence length 4σ_s of the Gaussian window, a property of the light (default 65um, the paper's; a
    /// smaller patch is taken as one unit cell of a periodic surface; said in the output). At least 4 pixels.
    #[arg(long, value_parser = positive_length_nm)]
    pub coherence: Option<f64>,
    /// Wavelength step of the spectral integral (≤ 5nm recommended).
    #[arg(long, alias = "dlambda", value_parser = positive_length_nm)]
    pub step: Option<f64>,
    /// Energy-conserving lobes (reference, ground-truth): each scaled by its order's factor in the patch's
    /// energy-normalised channel matrix, so that the BRDF never returns more light than it receives (Kirchhoff's
    /// obliquity factor as printed returns up to twice it at grazing light).
    #[arg(long)]
    pub conserve_energy: bool,
}

/// The CIE colour of the model commands' spectra (`precompute`, `brdf-map`, `brdf eval`; not `brdf vision`,
/// where an animal's receptors and its own `--illuminant` take their place).
#[derive(Debug, Clone, clap::Args)]
pub struct ColourOpts {
    /// Illuminant: d65, d50, a, e.
    #[arg(long)]
    pub illuminant: Option<String>,
    /// Observer: 1931 or 1964.
    #[arg(long)]
    pub observer: Option<String>,
}

impl ModelOpts {
    /// The facade's model options, with the CIE colour of `colour`.
    pub fn with_colour(&self, colour: &ColourOpts) -> iridis_api::ModelOptions {
        iridis_api::ModelOptions {
            illuminant: colour.illuminant.clone(),
            observer: colour.observer.clone(),
            ..self.options()
        }
    }

    /// The facade's model options (default CIE colour).
    pub fn options(&self) -> iridis_api::ModelOptions {
        iridis_api::ModelOptions {
            terms: self.terms.clone(),
            coherence_nm: self.coherence,
            step_nm: self.step,
            conserve_energy: self.conserve_energy,
            // light: none (any); --material and --unit-cell: set by `RigorousOpts::apply` where taken.
            ..Default::default()
        }
    }
}

/// The shading factors around |A|² (`C` of paper eq. 2–4), shared by `brdf-map` and `brdf eval`.
#[derive(Debug, Clone, clap::Args)]
pub struct ShadingOpts {
    /// Fresnel factor: schlick[:N] (default schlick:1.5), index:N or index:N+Ki (gold near 550 nm:
    /// index:0.2+3.4i), gold (measured, Johnson & Christy) or a thin-film stack, e.g. "stack:air | keratin
    /// 300nm | n=1.56" (the last two depend on λ: reference or ground-truth).
    #[arg(long, default_value = iridis_api::fresnel::DEFAULT_FRESNEL)]
    pub fresnel: String,
    /// How the Fresnel reflectance enters: physical (R once, the default) or paper (R², the paper's formula as
    /// printed, to reproduce its figures; docs/PHYSICS.md).
    #[arg(long, value_name = "physical|paper", default_value = "physical", value_parser = fresnel_convention)]
    pub fresnel_convention: FresnelConvention,
    /// Leave out the Cook-Torrance shadowing term.
    #[arg(long)]
    pub no_shadowing: bool,
}

impl ShadingOpts {
    pub fn shading(&self) -> anyhow::Result<iridis_diffraction::Shading> {
        iridis_api::fresnel::shading(&self.fresnel, self.fresnel_convention, !self.no_shadowing)
    }
}

/// Parses `--incidence θ[,φ]` into a light direction, refusing θ ≥ 90°.
pub fn parse_incidence(s: &str) -> anyhow::Result<[f64; 3]> {
    let (theta, phi) = polar_azimuth("incidence", s)?;
    Ok(iridis_diffraction::geometry::direction(theta, phi))
}

/// A fraction from 0 up to 1, written as a number (`1e-3`) or a percentage (`0.1%`).
pub fn fraction(s: &str) -> Result<f64, String> {
    let t = s.trim();
    let v = match t.strip_suffix('%') {
        Some(p) => p.trim().parse::<f64>().map(|v| v / 100.0),
        None => t.parse::<f64>(),
    }
    .map_err(|_| format!("'{s}': expected a fraction (1e-3) or a percentage (0.1%)"))?;
    if v.is_finite() && (0.0..1.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("'{s}': the efficiency must be from 0 up to 1 (100 %)"))
    }
}

#[cfg(test)]
mod brdf_args_tests {
    use super::*;

    #[test]
    fn incidence_parses() {
        assert!(parse_incidence("90deg").is_err());
        assert!(parse_incidence("20deg,0deg,1deg").is_err());
        let d = parse_incidence("0deg").unwrap();
        assert!((d[2] - 1.0).abs() < 1e-15);
    }
}
