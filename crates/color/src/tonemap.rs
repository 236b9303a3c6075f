//! From XYZ in relative reflectance to display pixels: exposure in RU, XYZ → linear sRGB, clip, encode.
//!
//! 1 RU (relative unit, `docs/PHYSICS.md`) is the light level at which a mirror at normal incidence just
//! saturates white: a pixel value of `Y = 1` times an exposure of 1 RU is full white.

use crate::convert::{gamma_encode, srgb_encode, Xyz};

/// How linear values in [0, 1] become display values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Encoding {
    /// The sRGB transfer curve (IEC 61966-2-1).
    Srgb,
    /// A plain power law `v^(1/γ)`.
    Gamma(f64),
    /// No encoding (linear output).
    Linear,
}

impl Encoding {
    pub fn encode(self, v: f64) -> f64 {
        match self {
            Encoding::Srgb => srgb_encode(v),
            Encoding::Gamma(g) => gamma_encode(v, g),
            Encoding::Linear => v,
        }
    }

    /// Parses `srgb`, `linear` or a positive number (a gamma).
    pub fn parse(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "srgb" => Ok(Encoding::Srgb),
            "linear" | "1" => Ok(Encoding::Linear),
            other => match other.parse::<f64>() {
                Ok(g) if g.is_finite() && g > 0.0 => Ok(Encoding::Gamma(g)),
                _ => Err(format!("'{s}' is not an encoding: use srgb, linear or a gamma such as 2.2")),
            },
        }
    }
}

/// Exposure and encoding.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToneMap {
    /// Scale applied to XYZ before conversion, in RU.
    pub exposure_ru: f64,
    pub encoding: Encoding,
}

impl Default for ToneMap {
    fn default() -> Self {
        Self { exposure_ru: 1.0, encoding: Encoding::Srgb }
    }
}

impl ToneMap {
    /// Display values in [0, 1]: scale, convert to linear sRGB, clip to [0, 1], encode.
    pub fn to_display(&self, xyz: Xyz) -> [f64; 3] {
        let rgb = xyz.scale(self.exposure_ru).to_linear_srgb();
        rgb.map(|c| self.encoding.encode(if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) }))
    }

    /// 8-bit display pixel.
    pub fn to_rgb8(&self, xyz: Xyz) -> [u8; 3] {
        self.to_display(xyz).map(|c| (c * 255.0 + 0.5).floor().clamp(0.0, 255.0) as u8)
    }
}

/// Hex colour `#rrggbb` of 8-bit pixel values.
pub fn hex(rgb8: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", rgb8[0], rgb8[1], rgb8[2])
}
