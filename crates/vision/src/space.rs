//! Colour-space coordinates: the receptor-space simplices (a line for dichromats, Maxwell's triangle for
//! trichromats, the tetrahedron for tetrachromats) from relative quantum catches, and Chittka's (1992)
//! colour hexagon for bees from von Kries-adapted catches.

use std::fmt;

use serde::Serialize;

use crate::VisionError;

/// Which colour space coordinates are given in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Space {
    /// The visual system's own choice (a simplex matching its number of receptors; the hexagon for bees).
    #[default]
    Auto,
    /// Dichromat: `x = (l − s)/√2` (pavo's `dispace`).
    Line,
    /// Trichromat, Maxwell's triangle: `x = (l − m)/√2`, `y = √(2/3) (s − (l + m)/2)` (pavo's `trispace`).
    Triangle,
    /// Tetrachromat (Goldsmith 1990; Endler & Mielke 2005; Stoddard & Prum 2008): achromatic point at the
    /// origin, each vertex 0.75 from it.
    Tetrahedron,
    /// Bee colour hexagon (Chittka 1992): receptor excitations `E = q/(q + 1)` of the adapted catches.
    Hexagon,
    /// No coordinates.
    None,
}

iridis_color::names! {
    Space {
        Auto => "auto",
        Line => "line" | "di" | "dispace",
        Triangle => "triangle" | "tri" | "trispace" | "maxwell",
        Tetrahedron => "tetrahedron" | "tetra" | "tcs",
        Hexagon => "hexagon" | "hex",
        None => "none",
    }
    else |s| -> VisionError {
        VisionError::invalid(format!(
            "unknown colour space '{s}'; expected auto, line, triangle, tetrahedron, hexagon or none"
        ))
    }
}

impl fmt::Display for Space {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Space {
    /// The simplex for `n` receptors (none for other counts).
    pub fn for_receptors(n: usize) -> Space {
        match n {
            2 => Space::Line,
            3 => Space::Triangle,
            4 => Space::Tetrahedron,
            _ => Space::None,
        }
    }

    /// How many receptors the space needs.
    pub fn receptors(self) -> Option<usize> {
        match self {
            Space::Line => Some(2),
            Space::Triangle | Space::Hexagon => Some(3),
            Space::Tetrahedron => Some(4),
            Space::Auto | Space::None => None,
        }
    }
}

/// A sample's place in a colour space.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Coordinates {
    pub space: Space,
    /// x (line), x, y (triangle, hexagon) or x, y, z (tetrahedron).
    pub position: Vec<f64>,
    /// Hue: the angle of (x, y) from the +x axis, counter-clockwise, in degrees [0, 360); null on a line and
    /// at the achromatic point.
    pub hue_deg: Option<f64>,
    /// Tetrahedron only: the angle of the point above the x-y plane, degrees (−90 to 90); null at the
    /// achromatic point.
    pub elevation_deg: Option<f64>,
    /// Distance from the achromatic point (the origin).
    pub chroma: f64,
    /// Hexagon only: the receptor excitations `E = q/(q + 1)`.
    pub excitations: Option<Vec<f64>>,
}

/// Closer than this to the achromatic point (rounding of an achromatic sample) a point has no hue.
const ACHROMATIC: f64 = 1e-12;

fn hue(x: f64, y: f64) -> f64 {
    let h = y.atan2(x).to_degrees();
    if h < 0.0 {
        h + 360.0
    } else {
        h
    }
}

/// Coordinates in a simplex from relative catches (summing to 1, short to long).
pub fn simplex(space: Space, rel: &[f64]) -> Option<Coordinates> {
    let (position, hue_deg, elevation_deg) = match (space, rel) {
        (Space::Line, [s, l]) => (vec![(l - s) / 2f64.sqrt()], None, None),
        (Space::Triangle, [s, m, l]) => {
            let (x, y) = ((l - m) / 2f64.sqrt(), (2.0f64 / 3.0).sqrt() * (s - (l + m) / 2.0));
            (vec![x, y], Some(hue(x, y)), None)
        }
        (Space::Tetrahedron, [u, s, m, l]) => {
            let x = (1.0 - 2.0 * s - m - u) / 2.0 * 1.5f64.sqrt();
            let y = (-1.0 + 3.0 * m + u) / (2.0 * 2f64.sqrt());
            let z = u - 0.25;
            let r = (x * x + y * y + z * z).sqrt();
            let elevation = if r > 0.0 { (z / r).asin().to_degrees() } else { 0.0 };
            let _ = l;
            (vec![x, y, z], Some(hue(x, y)), Some(elevation))
        }
        _ => return None,
    };
    let chroma = position.iter().map(|v| v * v).sum::<f64>().sqrt();
    let (hue_deg, elevation_deg) = if chroma < ACHROMATIC { (None, None) } else { (hue_deg, elevation_deg) };
    Some(Coordinates { space, position, hue_deg, elevation_deg, chroma, excitations: None })
}

/// Chittka's (1992) hexagon from von Kries-adapted catches `q` of the UV, blue and green receptors:
/// `E = q/(q + 1)`, `x = (√3/2)(E_G − E_UV)`, `y = E_B − (E_UV + E_G)/2`.
pub fn hexagon(q: &[f64]) -> Option<Coordinates> {
    let [qu, qb, qg] = q else { return None };
    let e = [qu / (qu + 1.0), qb / (qb + 1.0), qg / (qg + 1.0)];
    let x = 3f64.sqrt() / 2.0 * (e[2] - e[0]);
    let y = e[1] - 0.5 * (e[0] + e[2]);
    let chroma = (x * x + y * y).sqrt();
    Some(Coordinates {
        space: Space::Hexagon,
        position: vec![x, y],
        hue_deg: (chroma >= ACHROMATIC).then(|| hue(x, y)),
        elevation_deg: None,
        chroma,
        excitations: Some(e.to_vec()),
    })
}
