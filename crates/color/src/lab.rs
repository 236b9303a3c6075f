//! CIELAB (CIE 15:2004 §8.2.1) and the colour differences ΔE*ab (1976) and CIEDE2000.

use serde::Serialize;

use crate::convert::Xyz;

/// CIE 1976 L*a*b*.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Lab {
    pub l: f64,
    pub a: f64,
    pub b: f64,
}

/// CIELAB's default white: the XYZ of a perfect reflector under CIE D65 for the CIE 1931 2° observer, `Y = 1`,
/// integrated from the committed CIE tables like every other white ([`crate::integrate::white_point`]), so
/// that the colour of a spectrum under D65 and its CIELAB agree. (0.95047, 1, 1.08883); computed once.
pub fn d65_white() -> Xyz {
    static WHITE: std::sync::OnceLock<Xyz> = std::sync::OnceLock::new();
    *WHITE.get_or_init(|| crate::integrate::white_point(crate::Illuminant::D65, crate::Observer::Cie1931))
}

const EPSILON: f64 = 216.0 / 24389.0; // (6/29)^3
const KAPPA: f64 = 24389.0 / 27.0; // (29/3)^3

impl Lab {
    pub const fn new(l: f64, a: f64, b: f64) -> Self {
        Self { l, a, b }
    }
    pub fn to_array(self) -> [f64; 3] {
        [self.l, self.a, self.b]
    }

    /// XYZ → L*a*b* relative to the white `white` (use the XYZ of the illuminant, `Y_w = 1`).
    pub fn from_xyz(xyz: Xyz, white: Xyz) -> Self {
        let f = |t: f64| {
            if t > EPSILON {
                t.cbrt()
            } else {
                (KAPPA * t + 16.0) / 116.0
            }
        };
        let (fx, fy, fz) = (f(xyz.x / white.x), f(xyz.y / white.y), f(xyz.z / white.z));
        Lab::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz))
    }

    /// XYZ → L*a*b* relative to the default white, D65 for the CIE 1931 observer ([`d65_white`]): the
    /// usual choice, and the white of sRGB.
    pub fn from_xyz_d65(xyz: Xyz) -> Self {
        Self::from_xyz(xyz, d65_white())
    }

    /// L*a*b* → XYZ relative to the default white ([`d65_white`]); the inverse of [`Lab::from_xyz_d65`].
    pub fn to_xyz_d65(self) -> Xyz {
        self.to_xyz(d65_white())
    }

    /// L*a*b* → XYZ relative to `white`; the exact inverse of [`Lab::from_xyz`].
    pub fn to_xyz(self, white: Xyz) -> Xyz {
        let fy = (self.l + 16.0) / 116.0;
        let fx = fy + self.a / 500.0;
        let fz = fy - self.b / 200.0;
        let finv = |f: f64| {
            let f3 = f * f * f;
            if f3 > EPSILON {
                f3
            } else {
                (116.0 * f - 16.0) / KAPPA
            }
        };
        let yr = if self.l > KAPPA * EPSILON { fy * fy * fy } else { self.l / KAPPA };
        Xyz::new(finv(fx) * white.x, yr * white.y, finv(fz) * white.z)
    }
}

/// The CIELAB colour of `xyz` as a display shows it at `exposure` (RU, docs/PHYSICS.md), the way a camera
/// records it: XYZ × exposure → linear sRGB (IEC 61966-2-1) → clipped to [0, 1] (a channel that is not a number
/// shown as 0) → back to XYZ → CIELAB relative to the display's white, linear sRGB (1, 1, 1), so that display
/// white is L* = 100, a* = b* = 0. Every ΔE between images in iridis is taken between these colours: the
/// method comparisons of the paper's sec. 6.3, the benches and the GPU's agreement with the CPU.
pub fn displayed_lab(xyz: Xyz, exposure: f64) -> Lab {
    let rgb = xyz.scale(exposure).to_linear_srgb().map(|c| if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) });
    Lab::from_xyz(Xyz::from_linear_srgb(rgb), Xyz::from_linear_srgb([1.0; 3]))
}

/// CIEDE2000 between the displayed colours ([`displayed_lab`]) of `a` and `b` at one exposure.
pub fn delta_e_displayed(a: Xyz, b: Xyz, exposure: f64) -> f64 {
    delta_e_2000(displayed_lab(a, exposure), displayed_lab(b, exposure))
}

/// Which colour difference: CIEDE2000 or ΔE*ab (CIE 1976), as `--formula` and Python's `formula=` name them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DeltaEFormula {
    Ciede2000,
    Cie1976,
}

crate::names! {
    DeltaEFormula {
        Ciede2000 => "2000" | "ciede2000" | "de2000",
        Cie1976 => "1976" | "cie76" | "cie1976" | "ab",
    }
    else |s| -> String { format!("unknown ΔE formula '{}'; expected 2000 (CIEDE2000) or 1976 (ΔE*ab)", s.trim()) }
}

/// The largest |L*|, |a*|, |b*| a colour difference takes: CIELAB's colours lie within L* 0–100 and a*, b* of
/// about ±200 (an over-exposed light a few hundred L*); far beyond, the formulas' squares lose all precision
/// and then overflow to NaN.
pub const MAX_LAB_COMPONENT: f64 = 1e6;

impl DeltaEFormula {
    /// The difference's symbol and formula, as a number's unit: `ΔE00 (CIEDE2000)`, `ΔE*ab (CIE 1976)`.
    pub fn label(self) -> &'static str {
        match self {
            DeltaEFormula::Ciede2000 => "ΔE00 (CIEDE2000)",
            DeltaEFormula::Cie1976 => "ΔE*ab (CIE 1976)",
        }
    }

    /// The difference between `p` and `q` by this formula.
    pub fn delta_e(self, p: Lab, q: Lab) -> f64 {
        match self {
            DeltaEFormula::Ciede2000 => delta_e_2000(p, q),
            DeltaEFormula::Cie1976 => delta_e_1976(p, q),
        }
    }

    /// [`Self::delta_e`] of colours a person gave: a component that is not finite or beyond
    /// [`MAX_LAB_COMPONENT`] is an error naming it, not a NaN.
    pub fn delta_e_checked(self, p: Lab, q: Lab) -> Result<f64, String> {
        for (which, c) in [("first", p), ("second", q)] {
            for (name, v) in [("L*", c.l), ("a*", c.a), ("b*", c.b)] {
                if !(v.is_finite() && v.abs() <= MAX_LAB_COMPONENT) {
                    return Err(format!(
                        "the {which} colour's {name} = {v:e} is outside CIELAB (L* 0–100, a* and b* within about \
                         ±200; at most ±{MAX_LAB_COMPONENT:e} is taken)"
                    ));
                }
            }
        }
        Ok(self.delta_e(p, q))
    }
}

/// ΔE*ab, CIE 1976: Euclidean distance in L*a*b*.
pub fn delta_e_1976(p: Lab, q: Lab) -> f64 {
    ((p.l - q.l).powi(2) + (p.a - q.a).powi(2) + (p.b - q.b).powi(2)).sqrt()
}

/// CIEDE2000 with k_L = k_C = k_H = 1, following Sharma, Wu & Dalal (2005), eq. (1)–(22), including
/// their notes on the hue angle when a chroma is zero and on the mean hue.
pub fn delta_e_2000(p: Lab, q: Lab) -> f64 {
    use std::f64::consts::PI;
    let deg = PI / 180.0;
    let c1 = p.a.hypot(p.b);
    let c2 = q.a.hypot(q.b);
    let c_bar = 0.5 * (c1 + c2);
    let c7 = c_bar.powi(7);
    let g = 0.5 * (1.0 - (c7 / (c7 + 25f64.powi(7))).sqrt());
    let a1 = (1.0 + g) * p.a;
    let a2 = (1.0 + g) * q.a;
    let c1p = a1.hypot(p.b);
    let c2p = a2.hypot(q.b);
    let hue = |b: f64, a: f64| {
        if b == 0.0 && a == 0.0 {
            0.0
        } else {
            let h = b.atan2(a);
            if h < 0.0 {
                h + 2.0 * PI
            } else {
                h
            }
        }
    };
    let h1p = hue(p.b, a1);
    let h2p = hue(q.b, a2);

    let dl = q.l - p.l;
    let dc = c2p - c1p;
    let dh_angle = if c1p * c2p == 0.0 {
        0.0
    } else {
        let d = h2p - h1p;
        if d > PI {
            d - 2.0 * PI
        } else if d < -PI {
            d + 2.0 * PI
        } else {
            d
        }
    };
    let dh = 2.0 * (c1p * c2p).sqrt() * (0.5 * dh_angle).sin();

    let l_bar = 0.5 * (p.l + q.l);
    let cp_bar = 0.5 * (c1p + c2p);
    let hp_bar = if c1p * c2p == 0.0 {
        h1p + h2p
    } else if (h1p - h2p).abs() <= PI {
        0.5 * (h1p + h2p)
    } else if h1p + h2p < 2.0 * PI {
        0.5 * (h1p + h2p + 2.0 * PI)
    } else {
        0.5 * (h1p + h2p - 2.0 * PI)
    };
    let t = 1.0 - 0.17 * (hp_bar - 30.0 * deg).cos()
        + 0.24 * (2.0 * hp_bar).cos()
        + 0.32 * (3.0 * hp_bar + 6.0 * deg).cos()
        - 0.20 * (4.0 * hp_bar - 63.0 * deg).cos();
    let d_theta = 30.0 * deg * (-((hp_bar / deg - 275.0) / 25.0).powi(2)).exp();
    let cp7 = cp_bar.powi(7);
    let r_c = 2.0 * (cp7 / (cp7 + 25f64.powi(7))).sqrt();
    let l50 = (l_bar - 50.0).powi(2);
    let s_l = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let s_c = 1.0 + 0.045 * cp_bar;
    let s_h = 1.0 + 0.015 * cp_bar * t;
    let r_t = -(2.0 * d_theta).sin() * r_c;
    let (tl, tc, th) = (dl / s_l, dc / s_c, dh / s_h);
    (tl * tl + tc * tc + th * th + r_t * tc * th).sqrt()
}
