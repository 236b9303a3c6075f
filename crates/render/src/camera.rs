//! Cameras: perspective, orthographic, and the hemisphere camera that shows a material's BRDF map.

use crate::math::*;

#[derive(Debug, Clone, PartialEq)]
pub enum Camera {
    /// A pinhole at `position` looking along `forward`; `tan_half` = tan(vertical fov / 2).
    Perspective { position: V3, forward: V3, right: V3, up: V3, tan_half: f64 },
    /// Parallel rays along `forward`; `half_height` = half the view height in scene units.
    Orthographic { position: V3, forward: V3, right: V3, up: V3, half_height: f64 },
    /// The BRDF-map camera (paper sec. 7): image point `(x, y) ∈ [−1, 1]²` looks at `target` from the direction
    /// `x·right + y·up + √(1 − x² − y²)·normal` (outside the unit disk: black), so a plane through `target`
    /// with normal `normal` and tangent `right` is seen exactly as `iridis brdf-map` shows it.
    Hemisphere { target: V3, normal: V3, right: V3, up: V3, distance: f64 },
}

/// An orthonormal frame (forward, right, up) from a viewing direction and an approximate up vector.
pub fn frame(forward: V3, up: V3) -> Option<(V3, V3, V3)> {
    let f = try_normalize(forward)?;
    let r = try_normalize(cross(f, up))?;
    Some((f, r, cross(r, f)))
}

impl Camera {
    /// The ray through image point `(x, y)`, `x ∈ [−1, 1]` to the right and `y ∈ [−1, 1]` upwards (`aspect` =
    /// width / height stretches x for perspective and orthographic cameras). `None`: nothing there (black).
    pub fn ray(&self, x: f64, y: f64, aspect: f64) -> Option<(V3, V3)> {
        match *self {
            Camera::Perspective { position, forward, right, up, tan_half } => {
                let d = add(forward, add(mul(right, x * aspect * tan_half), mul(up, y * tan_half)));
                Some((position, normalize(d)))
            }
            Camera::Orthographic { position, forward, right, up, half_height } => {
                let o = add(position, add(mul(right, x * aspect * half_height), mul(up, y * half_height)));
                Some((o, forward))
            }
            Camera::Hemisphere { target, normal, right, up, distance } => {
                let r2 = x * x + y * y;
                if r2 >= 1.0 {
                    return None;
                }
                let v = add(add(mul(right, x), mul(up, y)), mul(normal, (1.0 - r2).sqrt()));
                Some((add(target, mul(v, distance)), mul(v, -1.0)))
            }
        }
    }
}
