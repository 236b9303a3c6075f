//! XYZ ↔ xyY, XYZ ↔ linear sRGB (IEC 61966-2-1:1999, D65 white), the sRGB transfer curve and plain gamma.

use serde::Serialize;

/// CIE XYZ tristimulus values; in iridis `Y = 1` is a perfect white reflector.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Xyz {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// CIE xyY: chromaticity (x, y) and luminance Y.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Xyy {
    pub x: f64,
    pub y: f64,
    pub big_y: f64,
}

impl Xyz {
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Self { x, y, z }
    }
    pub fn to_array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }
    pub fn scale(self, s: f64) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }

    /// Chromaticity and luminance. Black has no chromaticity; it gets the D65 white point's, as is customary.
    pub fn to_xyy(self) -> Xyy {
        let sum = self.x + self.y + self.z;
        if sum.abs() < 1e-300 {
            let (x, y) = D65_XY;
            return Xyy { x, y, big_y: self.y };
        }
        Xyy { x: self.x / sum, y: self.y / sum, big_y: self.y }
    }

    /// Linear sRGB (no clipping, no transfer curve).
    pub fn to_linear_srgb(self) -> [f64; 3] {
        mat_mul(&XYZ_TO_SRGB, self.to_array())
    }

    /// Linear sRGB → XYZ.
    pub fn from_linear_srgb(rgb: [f64; 3]) -> Self {
        let [x, y, z] = mat_mul(&SRGB_TO_XYZ, rgb);
        Self::new(x, y, z)
    }
}

impl Xyy {
    pub fn to_xyz(self) -> Xyz {
        if self.y.abs() < 1e-300 {
            return Xyz::new(0.0, 0.0, 0.0);
        }
        Xyz::new(self.x * self.big_y / self.y, self.big_y, (1.0 - self.x - self.y) * self.big_y / self.y)
    }
}

/// CIE 1931 chromaticity of D65 as IEC 61966-2-1 states it.
pub const D65_XY: (f64, f64) = (0.3127, 0.3290);

/// Linear sRGB → XYZ, IEC 61966-2-1:1999 eq. (F.7) (the standard's own four-digit matrix).
pub const SRGB_TO_XYZ: [[f64; 3]; 3] = [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]];

/// XYZ → linear sRGB: the exact inverse of [`SRGB_TO_XYZ`], so that round trips hold to rounding
/// (the standard's printed inverse, 3.2406 …, agrees to its four digits).
pub const XYZ_TO_SRGB: [[f64; 3]; 3] = invert3(SRGB_TO_XYZ);

const fn invert3(m: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    let c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    let c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    let det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    let inv = 1.0 / det;
    [
        [c00 * inv, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv, (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv],
        [c01 * inv, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv, (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv],
        [c02 * inv, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv, (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv],
    ]
}

pub fn mat_mul(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    ]
}

/// The sRGB transfer curve (IEC 61966-2-1 eq. 5), linear → encoded, for values in [0, 1]. Negative values
/// are mirrored so the function is odd and invertible.
pub fn srgb_encode(linear: f64) -> f64 {
    let a = linear.abs();
    let e = if a <= 0.003_130_8 { 12.92 * a } else { 1.055 * a.powf(1.0 / 2.4) - 0.055 };
    e.copysign(linear)
}

/// Inverse of [`srgb_encode`].
pub fn srgb_decode(encoded: f64) -> f64 {
    let a = encoded.abs();
    let l = if a <= 0.040_45 { a / 12.92 } else { ((a + 0.055) / 1.055).powf(2.4) };
    l.copysign(encoded)
}

/// A plain power-law encoding `v^(1/γ)` (the papers' `--gamma 2.2`).
pub fn gamma_encode(linear: f64, gamma: f64) -> f64 {
    linear.abs().powf(1.0 / gamma).copysign(linear)
}

/// Inverse of [`gamma_encode`].
pub fn gamma_decode(encoded: f64, gamma: f64) -> f64 {
    encoded.abs().powf(gamma).copysign(encoded)
}
