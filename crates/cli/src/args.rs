//! clap value parsers for quantities with units; they delegate to `iridis_color::units`, the one place
//! where units are parsed.

#![allow(dead_code)] // not every command uses every parser

use iridis_color::units;

/// A length in nm (`65nm`, `0.43um`, `65µm`).
pub fn length_nm(s: &str) -> Result<f64, String> {
    units::parse_length_nm(s).map_err(|e| e.0)
}

/// A strictly positive length in nm.
pub fn positive_length_nm(s: &str) -> Result<f64, String> {
    units::parse_positive_length_nm(s).map_err(|e| e.0)
}

/// An angle in radians (`75deg`, `1.2rad`).
pub fn angle_rad(s: &str) -> Result<f64, String> {
    units::parse_angle_rad(s).map_err(|e| e.0)
}

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

/// `--fresnel-convention`: physical (R once) or paper (R², the paper's formula as printed).
pub fn fresnel_convention(s: &str) -> Result<iridis_diffraction::geometry::FresnelConvention, String> {
    iridis_diffraction::geometry::FresnelConvention::parse(s).map_err(|e| e.to_string())
}

/// `--unit-cell`: whole (the patch, its extent the period) or auto (the scan's dominant period).
pub fn unit_cell_auto(s: &str) -> anyhow::Result<bool> {
    match s.trim() {
        "auto" => Ok(true),
        "whole" => Ok(false),
        other => anyhow::bail!("--unit-cell '{other}': expected whole (the patch) or auto (the dominant period)"),
    }
}

/// How to read a SURFACE argument.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct SurfaceOpts {
    /// Pixel size for image surfaces without physical units (e.g. 65nm).
    #[arg(long, value_parser = positive_length_nm)]
    pub pixel_size: Option<f64>,
    /// Height of the brightest grey value for image surfaces (e.g. 300nm).
    #[arg(long, value_parser = positive_length_nm)]
    pub max_height: Option<f64>,
    /// Channel of a multi-channel file, by index or name (`iridis surface channels FILE` lists them);
    /// default the channel named Height, else the first height channel (.npz: the only 2-D array).
    #[arg(long)]
    pub channel: Option<iridis_surface::formats::channel::ChannelSel>,
    /// Unit of heights in files that do not give one (.npy, text, a unitless channel), e.g. m or nm.
    #[arg(long)]
    pub height_unit: Option<String>,
    /// Levelling before the model: plane (default for files), poly, lines (median line correction), rows,
    /// mean or none (built-ins are used as generated unless this is given).
    #[arg(long)]
    pub level: Option<String>,
    #[command(flatten)]
    pub units: UnitFlags,
}

impl SurfaceOpts {
    /// The facade's surface options.
    pub fn options(&self) -> iridis_api::SurfaceOptions {
        iridis_api::SurfaceOptions {
            pixel_size_nm: self.pixel_size,
            max_height_nm: self.max_height,
            channel: self.channel.clone(),
            height_unit: self.height_unit.clone(),
            level: self.level.clone(),
            override_units: self.units.override_units,
            as_height: self.units.as_height,
        }
    }
}

/// How to read SURFACE and the model's parameters, shared by the lab commands.
#[derive(Debug, Clone, clap::Args)]
pub struct LabModel {
    #[command(flatten)]
    pub surface: SurfaceOpts,
    /// Coherence length 4σ_s of the window, a property of the light (default 65um, the paper's; a smaller
    /// patch is taken as one unit cell of a periodic surface; said in the output).
    #[arg(long, value_parser = positive_length_nm)]
    pub coherence: Option<f64>,
    /// Taylor terms: auto (remainder bound 1e-6) or N.
    #[arg(long, default_value = "auto")]
    pub terms: String,
    /// Fresnel factor: schlick[:N] (default schlick:1.5), index:N[+Ki], gold (measured) or a thin-film stack,
    /// e.g. "stack:air | keratin 300nm | n=1.56" (as brdf-map's --fresnel).
    #[arg(long, default_value = "schlick:1.5")]
    pub fresnel: String,
    /// How the Fresnel reflectance enters: physical (R once, the default) or paper (R², the paper's formula as
    /// printed, to reproduce its figures; docs/PHYSICS.md).
    #[arg(long, value_name = "physical|paper", default_value = "physical", value_parser = fresnel_convention)]
    pub fresnel_convention: iridis_diffraction::geometry::FresnelConvention,
    /// Leave out the Cook–Torrance shadowing term.
    #[arg(long)]
    pub no_shadowing: bool,
    /// ε of Stam's wavelength selection (paper: 0.01).
    #[arg(long, default_value_t = 0.01)]
    pub epsilon: f64,
}

impl LabModel {
    /// The facade's lab options.
    pub fn options(&self) -> iridis_api::lab::LabOptions {
        iridis_api::lab::LabOptions {
            surface: self.surface.options(),
            coherence_nm: self.coherence,
            terms: self.terms.clone(),
            fresnel: self.fresnel.clone(),
            convention: self.fresnel_convention,
            shadowing: !self.no_shadowing,
            stam_epsilon: self.epsilon,
        }
    }
}

/// What a SURFACE's own metadata may be overruled by, flattened into every command that reads one.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct UnitFlags {
    /// Let --pixel-size and --height-unit replace the pixel size and height unit an instrument file states
    /// itself (without it the file's win, and a warning names both).
    #[arg(long)]
    pub override_units: bool,
    /// Read a channel that is not a height (an amplitude, error, phase or deformation channel, or one whose
    /// unit is not a length; `iridis surface channels FILE` marks them) as heights anyway.
    #[arg(long)]
    pub as_height: bool,
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
        unit_cell_auto(&self.unit_cell)
    }

    /// Puts the options into the facade's model options, refusing what the method cannot use: a Fresnel
    /// factor (`fresnel`, `paper`: the convention) with the rigorous method, which needs the material.
    pub fn apply(
        &self,
        method: &str,
        fresnel: &str,
        paper: bool,
        model: &mut iridis_api::ModelOptions,
    ) -> anyhow::Result<()> {
        let rigorous = method == iridis_api::brdf::RIGOROUS;
        if rigorous && fresnel.trim() != DEFAULT_FRESNEL {
            anyhow::bail!(
                "the rigorous method needs the medium under the relief (--material gold, keratin, n=1.5, …), not a \
                 Fresnel factor (--fresnel {fresnel})"
            );
        }
        if rigorous && paper {
            anyhow::bail!(
                "--fresnel-convention paper is the scalar model's R² as printed; the rigorous method has none"
            );
        }
        model.material = self.material.clone();
        model.unit_cell_auto = self.auto()?;
        Ok(())
    }
}

/// The `--fresnel` of the scalar methods when none is given.
pub const DEFAULT_FRESNEL: &str = "schlick:1.5";

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
