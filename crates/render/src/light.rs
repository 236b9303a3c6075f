//! Lights and the environment. Radiometry is in relative units (RU, PHYSICS.md): a directional light of
//! intensity 1 RU on a normal-incidence mirror gives `Y = 1`, which an image at exposure 1 shows as white.
//! Colours are linear sRGB triples; `[1, 1, 1]` is D65 white.

use iridis_color::{Illuminant, Observer, Xyz};

use crate::math::*;
use crate::texture::Texture;

/// Linear sRGB (D65 white = `[1, 1, 1]`).
pub type Rgb = [f64; 3];

/// The colour of an illuminant relative to D65, in linear sRGB: `rgb(S) / rgb(D65)` per channel, with each
/// white point normalised to `Y = 1`. D65 gives exactly `[1, 1, 1]`, so a D65 light leaves the diffraction
/// tables (integrated under D65) unchanged; another spectrum tints them by this ratio (a von Kries-style
/// approximation: the tables are not re-integrated).
pub fn illuminant_tint(ill: Illuminant) -> Rgb {
    let rgb = |i: Illuminant| {
        let w = iridis_color::integrate::white_point(i, Observer::Cie1931);
        Xyz::new(w.x / w.y, 1.0, w.z / w.y).to_linear_srgb()
    };
    let (s, d) = (rgb(ill), rgb(Illuminant::D65));
    [s[0] / d[0], s[1] / d[1], s[2] / d[2]]
}

/// A light source.
#[derive(Debug, Clone, PartialEq)]
pub enum Light {
    /// Parallel light from `direction` (unit, pointing towards the light), irradiance `rgb` (RU).
    Directional { direction: V3, rgb: Rgb },
    /// A point at `position`; `rgb` is the irradiance (RU) at distance 1, falling off as `1/r²`.
    Point { position: V3, rgb: Rgb },
}

impl Light {
    /// Direction towards the light, distance to it and the irradiance arriving at `p`.
    pub fn arrive(&self, p: V3) -> (V3, f64, Rgb) {
        match *self {
            Light::Directional { direction, rgb } => (direction, f64::INFINITY, rgb),
            Light::Point { position, rgb } => {
                let d = sub(position, p);
                let r2 = dot(d, d).max(1e-12);
                (mul(d, 1.0 / r2.sqrt()), r2.sqrt(), mul(rgb, 1.0 / r2))
            }
        }
    }
}

/// Light arriving from far away in every direction.
#[derive(Debug, Clone, Default)]
pub enum Environment {
    /// No environment: black.
    #[default]
    None,
    /// The same radiance from every direction.
    Uniform(Rgb),
    /// A procedural sky: `zenith` overhead blending to `horizon`, `ground` below (y is up).
    Sky { zenith: Rgb, horizon: Rgb, ground: Rgb },
    /// An equirectangular (latitude–longitude) HDR image: row 0 is straight up (+y), the centre column looks
    /// towards −z, `rotation` turns it about +y. Texture values are linear sRGB radiance × `intensity`.
    Map { texture: Box<Texture>, rotation: f64, intensity: f64, mean: Rgb },
}

impl Environment {
    /// Radiance arriving from direction `d` (unit, pointing away from the scene).
    pub fn radiance(&self, d: V3) -> Rgb {
        match self {
            Environment::None => [0.0; 3],
            Environment::Uniform(c) => *c,
            Environment::Sky { zenith, horizon, ground } => {
                if d[1] >= 0.0 {
                    let t = d[1].clamp(0.0, 1.0).powf(0.6);
                    [0, 1, 2].map(|k| horizon[k] + (zenith[k] - horizon[k]) * t)
                } else {
                    let t = (-d[1] * 8.0).clamp(0.0, 1.0);
                    [0, 1, 2].map(|k| horizon[k] + (ground[k] - horizon[k]) * t)
                }
            }
            Environment::Map { texture, rotation, intensity, .. } => {
                let (u, v) = equirect_uv(d, *rotation);
                mul(texture.sample_with([u, v], true), *intensity)
            }
        }
    }

    /// Mean radiance over the sphere (the ambient level used by diffuse materials).
    pub fn mean(&self) -> Rgb {
        match self {
            Environment::None => [0.0; 3],
            Environment::Uniform(c) => *c,
            Environment::Sky { zenith, horizon, ground } => {
                // Area-weighted average over the sphere of the profiles above (numerical, 1000 bands in y).
                let mut acc = [0.0; 3];
                let n = 1000;
                for i in 0..n {
                    let y = -1.0 + (2 * i + 1) as f64 / n as f64;
                    let c = Environment::Sky { zenith: *zenith, horizon: *horizon, ground: *ground }.radiance([
                        (1.0 - y * y).sqrt(),
                        y,
                        0.0,
                    ]);
                    acc = add(acc, mul(c, 1.0 / n as f64));
                }
                acc
            }
            Environment::Map { mean, .. } => *mean,
        }
    }
}

/// Equirectangular coordinates of a direction: `u` is the longitude (0.5 at −z), `v` from +y (0) to −y (1).
pub fn equirect_uv(d: V3, rotation: f64) -> (f64, f64) {
    let phi = d[0].atan2(-d[2]) - rotation;
    let u = 0.5 + phi / std::f64::consts::TAU;
    let v = d[1].clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
    (u.rem_euclid(1.0), v)
}

/// The solid-angle-weighted mean of an equirectangular map (rows weighted by `sin θ`).
pub fn equirect_mean(texture: &Texture, intensity: f64) -> Rgb {
    let Texture::Image { width, height, .. } = texture else { return [0.0; 3] };
    let (w, h) = (*width, *height);
    let (mut acc, mut wsum) = ([0.0; 3], 0.0);
    for r in 0..h {
        let theta = (r as f64 + 0.5) / h as f64 * std::f64::consts::PI;
        let s = theta.sin();
        for c in 0..w {
            let v = texture.sample_with([(c as f64 + 0.5) / w as f64, (r as f64 + 0.5) / h as f64], true);
            acc = add(acc, mul(v, s));
            wsum += s;
        }
    }
    mul(acc, intensity / wsum.max(1e-300))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d65_tint_is_white_and_a_is_warm() {
        let t = illuminant_tint(Illuminant::D65);
        assert!(t.iter().all(|c| (c - 1.0).abs() < 1e-12));
        let a = illuminant_tint(Illuminant::A);
        assert!(a[0] > 1.0 && a[2] < 0.5, "{a:?}");
    }

    #[test]
    fn equirect_poles_and_centre() {
        assert!(equirect_uv([0.0, 1.0, 0.0], 0.0).1 < 1e-12);
        let (u, v) = equirect_uv([0.0, 0.0, -1.0], 0.0);
        assert!((u - 0.5).abs() < 1e-12 && (v - 0.5).abs() < 1e-12);
        let uni = Environment::Uniform([0.2, 0.3, 0.4]);
        assert_eq!(uni.mean(), [0.2, 0.3, 0.4]);
    }
}
