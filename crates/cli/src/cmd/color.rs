//! `iridis color …`: spectra to colours, colour differences (`iridis_api::color`). Parses, calls, prints.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args as ClapArgs, Subcommand};

use crate::progress::Cli;

#[derive(Debug, Subcommand)]
pub enum ColorCommand {
    /// The colour of a spectrum: XYZ, xyY, CIELAB, linear and encoded sRGB, hex.
    #[command(after_help = "\
The spectrum file has two columns, wavelength in nm and value, separated by commas, semicolons, tabs or
spaces; a header line and lines starting with # are allowed. By default the values are a reflectance (or
transmittance) lit by the illuminant and Y = 1 is a perfect white reflector; with --emissive the spectrum is
a light source and its colour is reported at Y = 1. CIELAB is relative to the illuminant's white, with
--emissive too (the white the light is judged against: a light of the illuminant's own spectrum is L* = 100,
a* = b* = 0).

Examples:
  iridis color xyz data/examples/colorchecker_green.csv
  iridis color xyz data/examples/colorchecker_green.csv --illuminant d50 --observer 1964 --json
  iridis color xyz data/cie/d65.csv --emissive")]
    Xyz(XyzArgs),
    /// Colour difference between two CIELAB colours.
    #[command(after_help = "\
Examples:
  iridis color delta-e 50,2.6772,-79.7751 50,0,-82.7485          # 2.0425 ΔE00 (CIEDE2000)
  iridis color delta-e 50,2.6772,-79.7751 50,0,-82.7485 --formula 1976 --json")]
    DeltaE(DeltaEArgs),
}

#[derive(Debug, ClapArgs)]
pub struct XyzArgs {
    /// Spectrum file (CSV: wavelength_nm, value).
    pub spectrum: PathBuf,
    /// Illuminant: d65, d50, a or e (with --emissive, the reference white of CIELAB).
    #[arg(long, default_value = "d65")]
    pub illuminant: String,
    /// Standard observer: 1931 (2°) or 1964 (10°).
    #[arg(long, default_value = "1931")]
    pub observer: String,
    /// The spectrum is a light source, not a reflectance.
    #[arg(long)]
    pub emissive: bool,
    /// The reflectance is in percent (a value of 50 is 50 %): divided by 100.
    #[arg(long)]
    pub percent: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct DeltaEArgs {
    /// First colour as L,a,b.
    #[arg(allow_hyphen_values = true)]
    pub first: String,
    /// Second colour as L,a,b.
    #[arg(allow_hyphen_values = true)]
    pub second: String,
    /// 2000 (CIEDE2000) or 1976 (ΔE*ab).
    #[arg(long, default_value = "2000")]
    pub formula: String,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

pub fn run(command: ColorCommand) -> Result<()> {
    match command {
        ColorCommand::Xyz(a) => {
            let c = iridis_api::color::xyz(&a.spectrum, &a.illuminant, &a.observer, a.emissive, a.percent, &Cli)?;
            crate::output::print_answer(a.json, || Ok(c.to_json()), || c.text())
        }
        ColorCommand::DeltaE(a) => {
            let d = iridis_api::color::delta_e_answer(&a.first, &a.second, &a.formula)?;
            crate::output::print_answer(a.json, || Ok(d.to_json()), || d.text())
        }
    }
}
