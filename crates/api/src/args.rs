//! The command line's value parsers for quantities with units (feature `cli`), used by the option structs
//! that derive `clap::Args` here and by `iridis`' own; they delegate to `iridis_color::units`, the one place
//! where units are parsed.

use iridis_color::units;
use iridis_diffraction::geometry::FresnelConvention;

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

/// `--fresnel-convention`: physical (R once) or paper (R², the paper's formula as printed).
pub fn fresnel_convention(s: &str) -> Result<FresnelConvention, String> {
    FresnelConvention::parse(s).map_err(|e| e.to_string())
}
