//! Small vector helpers on `[f64; 3]` (the same representation as `iridis_diffraction::geometry::Vec3`).

pub type V3 = [f64; 3];

#[inline]
pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
#[inline]
pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline]
pub fn mul(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
#[inline]
pub fn hadamard(a: V3, b: V3) -> V3 {
    [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}
#[inline]
pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline]
pub fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
#[inline]
pub fn length(a: V3) -> f64 {
    dot(a, a).sqrt()
}
/// `a / |a|`, or `None` for a (near) zero vector.
#[inline]
pub fn try_normalize(a: V3) -> Option<V3> {
    let l = length(a);
    (l > 1e-300 && l.is_finite()).then(|| mul(a, 1.0 / l))
}
/// `a / |a|`; a zero vector stays zero.
#[inline]
pub fn normalize(a: V3) -> V3 {
    try_normalize(a).unwrap_or([0.0; 3])
}
/// Mirror direction of `d` (pointing away from the surface) about the normal `n`.
#[inline]
pub fn reflect(d: V3, n: V3) -> V3 {
    sub(mul(n, 2.0 * dot(d, n)), d)
}
/// Any unit vector perpendicular to the unit vector `n`.
pub fn any_perpendicular(n: V3) -> V3 {
    let a = if n[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
    normalize(cross(n, a))
}
/// The part of `t` perpendicular to the unit normal `n`, normalised (Gram–Schmidt); `None` if `t ∥ n`.
pub fn orthogonalize(t: V3, n: V3) -> Option<V3> {
    try_normalize(sub(t, mul(n, dot(t, n))))
}
/// Rotation of `v` about the unit axis `k` by `angle` (Rodrigues).
pub fn rotate_about(v: V3, k: V3, angle: f64) -> V3 {
    let (s, c) = angle.sin_cos();
    add(add(mul(v, c), mul(cross(k, v), s)), mul(k, dot(k, v) * (1.0 - c)))
}

/// A 3×3 matrix, row-major.
pub type M3 = [[f64; 3]; 3];

pub fn mat_vec(m: &M3, v: V3) -> V3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}
pub fn mat_mul(a: &M3, b: &M3) -> M3 {
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    r
}
/// Rotation from Euler angles (radians) applied in the order x, then y, then z.
pub fn euler_xyz(r: V3) -> M3 {
    let (sx, cx) = r[0].sin_cos();
    let (sy, cy) = r[1].sin_cos();
    let (sz, cz) = r[2].sin_cos();
    let rx = [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]];
    let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
    let rz = [[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]];
    mat_mul(&rz, &mat_mul(&ry, &rx))
}

/// An affine transform `p ↦ s · R p + t` (uniform scale, so normals transform with `R`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    pub rotation: M3,
    pub scale: f64,
    pub translation: V3,
}

impl Default for Transform {
    fn default() -> Self {
        Self { rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], scale: 1.0, translation: [0.0; 3] }
    }
}

impl Transform {
    pub fn point(&self, p: V3) -> V3 {
        add(mul(mat_vec(&self.rotation, p), self.scale), self.translation)
    }
    pub fn vector(&self, v: V3) -> V3 {
        mat_vec(&self.rotation, v)
    }
}
