//! Area lights: spheres, disks and rectangles of uniform radiance. A surface point samples them — a sphere by
//! the cone of directions it subtends (uniform in solid angle), a disk or rectangle by area — and asks the pdf
//! of a direction that another technique chose (multiple importance sampling, `crate::integrate`). Units:
//! `radiance` is in RU, so that a uniform environment of radiance 1 and a surface surrounded by area lights of
//! radiance 1 are the same white furnace. A sphere of radiance `L` and angular radius `α` gives a surface
//! facing it the irradiance of a directional light of `L sin²α` RU (exactly, while it is wholly above the
//! horizon); a disk of radius `r` seen head-on from distance `d` gives `L r² / (r² + d²)`.

use crate::light::Rgb;
use crate::math::*;
use crate::sampling::{concentric_disk, frame, from_local};

/// The emitting shape. Disks and rectangles emit from their front face (towards `normal`) only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    Sphere {
        center: V3,
        radius: f64,
    },
    Disk {
        center: V3,
        normal: V3,
        radius: f64,
    },
    /// `size = [w, h]` along `tangent` and `normal × tangent`.
    Rectangle {
        center: V3,
        normal: V3,
        tangent: V3,
        size: [f64; 2],
    },
}

/// An area light of uniform radiance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaLight {
    pub shape: Shape,
    /// Radiance (RU, linear sRGB).
    pub radiance: Rgb,
    /// Whether camera rays see it (reflections and sampled rays always do).
    pub visible: bool,
}

/// A direction towards a light chosen by sampling it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightSample {
    pub wi: V3,
    /// Distance to the sampled point on the light (the shadow ray's length).
    pub dist: f64,
    /// Solid-angle pdf of `wi`.
    pub pdf: f64,
}

/// The light seen as one directional light (the fast path): direction to its centre, distance, the
/// irradiance factor `e / L` (RU of a directional light per unit radiance) and the solid angle it subtends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Representative {
    pub wi: V3,
    pub dist: f64,
    pub e_per_radiance: f64,
    pub solid_angle: f64,
}

/// `1 − cos θ_max` of the cone a sphere of squared radius `r2` subtends at squared distance `d2` (stable for
/// small cones: `sin² / (1 + cos)`).
fn cone_one_minus_cos(r2: f64, d2: f64) -> f64 {
    let sin2 = (r2 / d2).min(1.0);
    sin2 / (1.0 + (1.0 - sin2).sqrt())
}

/// The cone a sphere light subtends from `p`: the vector to its centre, the squared distance and `1 − cos α`;
/// `None` from inside (a sphere light is seen from outside).
fn sphere_cone(center: V3, radius: f64, p: V3) -> Option<(V3, f64, f64)> {
    let dc = sub(center, p);
    let d2 = dot(dc, dc);
    if d2 <= radius * radius {
        return None;
    }
    Some((dc, d2, cone_one_minus_cos(radius * radius, d2)))
}

impl Shape {
    /// Scales every length about the origin (`Scene::scale`).
    pub fn scaled(self, s: f64) -> Self {
        match self {
            Shape::Sphere { center, radius } => Shape::Sphere { center: mul(center, s), radius: radius * s },
            Shape::Disk { center, normal, radius } => {
                Shape::Disk { center: mul(center, s), normal, radius: radius * s }
            }
            Shape::Rectangle { center, normal, tangent, size } => {
                Shape::Rectangle { center: mul(center, s), normal, tangent, size: [size[0] * s, size[1] * s] }
            }
        }
    }

    /// The flat shapes' area and frame `(centre, normal, t, b)`.
    fn flat(&self) -> Option<(V3, V3, f64)> {
        match *self {
            Shape::Sphere { .. } => None,
            Shape::Disk { center, normal, radius } => Some((center, normal, std::f64::consts::PI * radius * radius)),
            Shape::Rectangle { center, normal, size, .. } => Some((center, normal, size[0] * size[1])),
        }
    }

    /// Where a ray from `o` along `d` (unit) meets the emitting surface, nearer than `t_max`.
    pub fn intersect(&self, o: V3, d: V3, t_max: f64) -> Option<f64> {
        match *self {
            Shape::Sphere { center, radius } => {
                let oc = sub(o, center);
                let hb = dot(oc, d);
                let c = dot(oc, oc) - radius * radius;
                let disc = hb * hb - c;
                if disc < 0.0 {
                    return None;
                }
                let sq = disc.sqrt();
                // The near root from outside (c > 0); from inside, none: a sphere light is seen from outside.
                let t = if c > 0.0 { -hb - sq } else { return None };
                (t > 0.0 && t < t_max).then_some(t)
            }
            Shape::Disk { center, normal, radius } => {
                let (t, q) = front_plane_hit(o, d, center, normal, t_max)?;
                (dot(q, q) <= radius * radius).then_some(t)
            }
            Shape::Rectangle { center, normal, tangent, size } => {
                let (t, q) = front_plane_hit(o, d, center, normal, t_max)?;
                let b = cross(normal, tangent);
                (dot(q, tangent).abs() <= 0.5 * size[0] && dot(q, b).abs() <= 0.5 * size[1]).then_some(t)
            }
        }
    }

    /// A direction from `p` towards the shape, from two uniform numbers; `None` where `p` cannot see the
    /// emitting side (inside a sphere, behind a disk or rectangle).
    pub fn sample(&self, p: V3, u: [f64; 2]) -> Option<LightSample> {
        match *self {
            Shape::Sphere { center, radius } => {
                let (dc, d2, omc) = sphere_cone(center, radius, p)?;
                // cos θ = 1 − u (1 − cos θ_max), uniform in solid angle within the cone.
                let x = u[0] * omc;
                let cos_t = 1.0 - x;
                let sin_t = (x * (2.0 - x)).max(0.0).sqrt();
                let phi = std::f64::consts::TAU * u[1];
                let axis = mul(dc, 1.0 / d2.sqrt());
                let (t, b) = frame(axis);
                let wi = normalize(from_local(t, b, axis, [sin_t * phi.cos(), sin_t * phi.sin(), cos_t]));
                // Distance to the near surface along wi (the discriminant is ≥ 0 inside the cone, up to rounding).
                let hb = dot(dc, wi);
                let dist = hb - (radius * radius - (d2 - hb * hb)).max(0.0).sqrt();
                Some(LightSample { wi, dist: dist.max(0.0), pdf: 1.0 / (std::f64::consts::TAU * omc) })
            }
            Shape::Disk { center, normal, radius } => {
                let d = concentric_disk(u);
                let (t, b) = frame(normal);
                let q = add(center, from_local(t, b, normal, [radius * d[0], radius * d[1], 0.0]));
                self.towards_point(p, q)
            }
            Shape::Rectangle { center, normal, tangent, size } => {
                let b = cross(normal, tangent);
                let q = add(add(center, mul(tangent, (u[0] - 0.5) * size[0])), mul(b, (u[1] - 0.5) * size[1]));
                self.towards_point(p, q)
            }
        }
    }

    /// Area sampling of a flat shape: the direction to `q` and the area pdf converted to solid angle,
    /// `dist² / (cos θ_l A)`.
    fn towards_point(&self, p: V3, q: V3) -> Option<LightSample> {
        let (_, normal, area) = self.flat()?;
        let v = sub(q, p);
        let dist = length(v);
        if dist <= 0.0 {
            return None;
        }
        let wi = mul(v, 1.0 / dist);
        let cos_l = -dot(normal, wi);
        (cos_l > 0.0).then(|| LightSample { wi, dist, pdf: dist * dist / (cos_l * area) })
    }

    /// The solid-angle pdf with which [`Shape::sample`] at `p` picks `wi` (0 where it cannot).
    pub fn pdf(&self, p: V3, wi: V3) -> f64 {
        match *self {
            Shape::Sphere { center, radius } => {
                let dc = sub(center, p);
                let d2 = dot(dc, dc);
                if d2 <= radius * radius {
                    return 0.0;
                }
                let omc = cone_one_minus_cos(radius * radius, d2);
                // Inside the cone: 1 − cos(angle to the axis) ≤ 1 − cos θ_max.
                let c = dot(dc, wi) / d2.sqrt();
                if 1.0 - c > omc {
                    return 0.0;
                }
                1.0 / (std::f64::consts::TAU * omc)
            }
            _ => {
                let Some((_, normal, area)) = self.flat() else { return 0.0 };
                match self.intersect(p, wi, f64::INFINITY) {
                    Some(t) => t * t / (-dot(normal, wi) * area),
                    None => 0.0,
                }
            }
        }
    }

    /// The shape as one directional light from `p` (the fast path); `None` where `p` cannot see it. The
    /// irradiance factor is exact for a sphere wholly above the horizon (`sin²α`, a sphere light lights like a
    /// point light) and for a surface facing a disk on its axis (`A cos θ_l / (d² + A/π)`, i.e. `r²/(r² + d²)`).
    pub fn representative(&self, p: V3) -> Option<Representative> {
        match *self {
            Shape::Sphere { center, radius } => {
                let (dc, d2, omc) = sphere_cone(center, radius, p)?;
                let d = d2.sqrt();
                Some(Representative {
                    wi: mul(dc, 1.0 / d),
                    dist: d - radius,
                    e_per_radiance: radius * radius / d2,
                    solid_angle: std::f64::consts::TAU * omc,
                })
            }
            _ => {
                let (center, normal, area) = self.flat()?;
                let v = sub(center, p);
                let d2 = dot(v, v);
                let d = d2.sqrt();
                if d <= 0.0 {
                    return None;
                }
                let wi = mul(v, 1.0 / d);
                let cos_l = -dot(normal, wi);
                if cos_l <= 0.0 {
                    return None;
                }
                Some(Representative {
                    wi,
                    dist: d,
                    e_per_radiance: area * cos_l / (d2 + area / std::f64::consts::PI) / std::f64::consts::PI,
                    solid_angle: (area * cos_l / d2).min(std::f64::consts::TAU),
                })
            }
        }
    }
}

impl AreaLight {
    /// Scales every length about the origin; the radiance stays (what a point receives is unchanged).
    pub fn scaled(self, s: f64) -> Self {
        Self { shape: self.shape.scaled(s), ..self }
    }
}

/// Where the ray `o + t d` meets the plane through `center` with `normal` from its front side, `0 < t < t_max`:
/// `t` and the hit point relative to `center`. A flat light emits from its front only.
fn front_plane_hit(o: V3, d: V3, center: V3, normal: V3, t_max: f64) -> Option<(f64, V3)> {
    let den = dot(d, normal);
    if den >= 0.0 {
        return None;
    }
    let t = dot(sub(center, o), normal) / den;
    if !(t > 0.0 && t < t_max) {
        return None;
    }
    Some((t, sub(add(o, mul(d, t)), center)))
}
