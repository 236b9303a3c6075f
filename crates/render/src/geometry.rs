//! Geometry: triangle meshes (with normals, UVs and tangent frames), analytic spheres and planes (the
//! procedural snake body of the demo is built in [`crate::snake`]). Intersection routines return a [`Hit`] with the shading frame that the
//! materials need.

use crate::math::*;

/// A triangle mesh in world space.
#[derive(Debug, Clone, Default)]
pub struct Mesh {
    pub name: String,
    pub positions: Vec<V3>,
    /// One unit normal per vertex (computed from the faces when the file has none).
    pub normals: Vec<V3>,
    /// One UV per vertex, if the mesh has them.
    pub uvs: Option<Vec<[f64; 2]>>,
    /// Tangent per triangle corner (`3 · triangle + k`): xyz and the bitangent sign w, from a TANGENT
    /// attribute or MikkTSpace. Present when the mesh has UVs.
    pub corner_tangents: Option<Vec<[f64; 4]>>,
    pub triangles: Vec<[u32; 3]>,
    /// Index into the scene's materials.
    pub material: usize,
    /// The direction "along the body" for the `along` orientation rule, per vertex (the snake's spine).
    pub along: Option<Vec<V3>>,
}

impl Mesh {
    /// Area-weighted vertex normals from the faces (for meshes stored without normals).
    pub fn compute_normals(&mut self) {
        let mut acc = vec![[0.0; 3]; self.positions.len()];
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.positions[i as usize]);
            let n = cross(sub(b, a), sub(c, a)); // length = 2 × area: area weighting
            for &i in t {
                acc[i as usize] = add(acc[i as usize], n);
            }
        }
        self.normals = acc.into_iter().map(|n| try_normalize(n).unwrap_or([0.0, 0.0, 1.0])).collect();
    }

    /// Tangent frames with MikkTSpace (the convention of glTF and Blender) from positions, normals and UVs.
    /// Returns false when the mesh has no UVs.
    pub fn compute_tangents(&mut self) -> bool {
        let Some(uvs) = &self.uvs else { return false };
        struct G<'a> {
            m: &'a Mesh,
            uvs: &'a [[f64; 2]],
            out: Vec<[f64; 4]>,
        }
        impl mikktspace::Geometry for G<'_> {
            fn num_faces(&self) -> usize {
                self.m.triangles.len()
            }
            fn num_vertices_of_face(&self, _face: usize) -> usize {
                3
            }
            fn position(&self, face: usize, vert: usize) -> [f32; 3] {
                self.m.positions[self.m.triangles[face][vert] as usize].map(|x| x as f32)
            }
            fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
                self.m.normals[self.m.triangles[face][vert] as usize].map(|x| x as f32)
            }
            fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
                self.uvs[self.m.triangles[face][vert] as usize].map(|x| x as f32)
            }
            fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
                self.out[face * 3 + vert] = tangent.map(|x| x as f64);
            }
        }
        let mut g = G { m: self, uvs, out: vec![[0.0; 4]; self.triangles.len() * 3] };
        let ok = mikktspace::generate_tangents(&mut g);
        let out = g.out;
        if ok {
            self.corner_tangents = Some(out);
        }
        ok
    }

    pub fn transform(&mut self, t: &Transform) {
        for p in &mut self.positions {
            *p = t.point(*p);
        }
        for n in self.normals.iter_mut() {
            *n = normalize(t.vector(*n));
        }
        if let Some(ts) = &mut self.corner_tangents {
            for c in ts.iter_mut() {
                let v = normalize(t.vector([c[0], c[1], c[2]]));
                *c = [v[0], v[1], v[2], c[3]];
            }
        }
        if let Some(a) = &mut self.along {
            for v in a.iter_mut() {
                *v = normalize(t.vector(*v));
            }
        }
    }

    /// Axis-aligned bounds of the mesh.
    pub fn bounds(&self) -> (V3, V3) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in &self.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }
}

/// A surface point seen by a ray, with everything shading needs.
#[derive(Debug, Clone, Copy)]
pub struct Hit {
    pub t: f64,
    pub p: V3,
    /// Interpolated shading normal, unit length, on the side the ray came from.
    pub n: V3,
    /// Geometric normal, unit length, on the side the ray came from.
    pub ng: V3,
    /// Whether the ray hit the outside (front) of the surface.
    pub front: bool,
    pub uv: [f64; 2],
    /// The tangent attribute (mesh TANGENT/MikkTSpace, or the analytic dP/du), if any.
    pub tangent: Option<V3>,
    /// The bitangent's sign w of the tangent attribute (glTF: `B = (N × T) · w`); 1 without one.
    pub tangent_sign: f64,
    /// The "along the body" direction, if the object defines one.
    pub along: Option<V3>,
    pub material: usize,
}

/// Möller–Trumbore ray–triangle intersection: `(t, b1, b2)` with barycentrics of vertices 1 and 2.
#[inline]
pub fn intersect_triangle(o: V3, d: V3, a: V3, b: V3, c: V3, t_max: f64) -> Option<(f64, f64, f64)> {
    let e1 = sub(b, a);
    let e2 = sub(c, a);
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-14 * (length(e1) * length(e2)).max(1e-300) {
        return None;
    }
    let inv = 1.0 / det;
    let s = sub(o, a);
    let u = dot(s, p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = dot(e2, q) * inv;
    (t > 1e-9 && t < t_max).then_some((t, u, v))
}

/// Builds the hit record of triangle `tri` of `mesh` at barycentrics `(b1, b2)`.
pub fn triangle_hit(mesh: &Mesh, tri: usize, o: V3, d: V3, t: f64, b1: f64, b2: f64) -> Hit {
    let idx = mesh.triangles[tri].map(|i| i as usize);
    let w = [1.0 - b1 - b2, b1, b2];
    let [a, b, c] = idx.map(|i| mesh.positions[i]);
    let ng0 = normalize(cross(sub(b, a), sub(c, a)));
    let interp = |v: [V3; 3]| add(add(mul(v[0], w[0]), mul(v[1], w[1])), mul(v[2], w[2]));
    let mut n = try_normalize(interp(idx.map(|i| mesh.normals[i]))).unwrap_or(ng0);
    let front = dot(ng0, d) < 0.0;
    let ng = if front { ng0 } else { mul(ng0, -1.0) };
    if dot(n, ng) < 0.0 {
        n = mul(n, -1.0);
    }
    let uv = match &mesh.uvs {
        Some(uvs) => {
            let q = idx.map(|i| uvs[i]);
            [q[0][0] * w[0] + q[1][0] * w[1] + q[2][0] * w[2], q[0][1] * w[0] + q[1][1] * w[1] + q[2][1] * w[2]]
        }
        None => [0.0, 0.0],
    };
    let tangent = mesh.corner_tangents.as_ref().and_then(|ts| {
        let c = [0, 1, 2].map(|k| {
            let q = ts[tri * 3 + k];
            [q[0], q[1], q[2]]
        });
        orthogonalize(interp(c), n)
    });
    let along = mesh.along.as_ref().and_then(|al| orthogonalize(interp(idx.map(|i| al[i])), n));
    let tangent_sign = mesh.corner_tangents.as_ref().map_or(1.0, |ts| if ts[tri * 3][3] < 0.0 { -1.0 } else { 1.0 });
    Hit { t, p: add(o, mul(d, t)), n, ng, front, uv, tangent, tangent_sign, along, material: mesh.material }
}

/// An analytic sphere; its pole axis is world `+y` (glTF's up), `u` runs around it (east), `v` from the top
/// (`v = 0`) to the bottom (`v = 1`), so a texture's top row lies on the top of the sphere.
#[derive(Debug, Clone)]
pub struct Sphere {
    pub center: V3,
    pub radius: f64,
    pub material: usize,
}

impl Sphere {
    pub fn intersect(&self, o: V3, d: V3, t_max: f64) -> Option<Hit> {
        let oc = sub(o, self.center);
        let a = dot(d, d);
        let hb = dot(oc, d);
        let c = dot(oc, oc) - self.radius * self.radius;
        let disc = hb * hb - a * c;
        if disc < 0.0 {
            return None;
        }
        let sq = disc.sqrt();
        let eps = 1e-9 * self.radius.max(1.0);
        let t = [(-hb - sq) / a, (-hb + sq) / a].into_iter().find(|&t| t > eps && t < t_max)?;
        let p = add(o, mul(d, t));
        let n0 = mul(sub(p, self.center), 1.0 / self.radius);
        let front = dot(n0, d) < 0.0;
        let n = if front { n0 } else { mul(n0, -1.0) };
        let phi = n0[0].atan2(n0[2]); // azimuth about +y, 0 towards +z
        let u = (phi / std::f64::consts::TAU).rem_euclid(1.0);
        let v = n0[1].clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
        // dP/du is horizontal (east); dP/dv points down the meridian (south).
        let east = try_normalize([n0[2], 0.0, -n0[0]]).unwrap_or([1.0, 0.0, 0.0]);
        let south = cross(east, n0);
        let south = orthogonalize(south, n).unwrap_or(south);
        Some(Hit {
            t,
            p,
            n,
            ng: n,
            front,
            uv: [u, v],
            tangent: orthogonalize(east, n),
            tangent_sign: 1.0,
            along: Some(south),
            material: self.material,
        })
    }
}

/// A plane through `center` with unit normal `normal`; `tangent` (in the plane) is `+u`, `n × t` is `+v`.
/// With `size = Some([w, h])` a `w × h` rectangle centred on `center`, UV `[0,1]²` across it (v up);
/// without, infinite, UV = coordinates in scene units.
#[derive(Debug, Clone)]
pub struct Plane {
    pub center: V3,
    pub normal: V3,
    pub tangent: V3,
    pub size: Option<[f64; 2]>,
    /// Scene units per UV unit of an infinite plane (1: UVs are scene coordinates; [`crate::Scene::scale`]
    /// scales it with the scene).
    pub uv_unit: f64,
    pub material: usize,
}

impl Plane {
    pub fn intersect(&self, o: V3, d: V3, t_max: f64) -> Option<Hit> {
        let den = dot(d, self.normal);
        if den.abs() < 1e-15 {
            return None;
        }
        let t = dot(sub(self.center, o), self.normal) / den;
        if !(t > 1e-9 && t < t_max) {
            return None;
        }
        let p = add(o, mul(d, t));
        let b = cross(self.normal, self.tangent);
        let r = sub(p, self.center);
        let (x, y) = (dot(r, self.tangent), dot(r, b));
        let uv = match self.size {
            Some([w, h]) => {
                if x.abs() > w / 2.0 || y.abs() > h / 2.0 {
                    return None;
                }
                [x / w + 0.5, 0.5 - y / h]
            }
            None => [x / self.uv_unit, -y / self.uv_unit],
        };
        let front = den < 0.0;
        let n = if front { self.normal } else { mul(self.normal, -1.0) };
        Some(Hit {
            t,
            p,
            n,
            ng: n,
            front,
            uv,
            tangent: Some(self.tangent),
            tangent_sign: 1.0,
            along: Some(self.tangent),
            material: self.material,
        })
    }
}

/// Ray offset along the normal that clears the surface at a hit without skipping thin features. Relative to
/// the hit's magnitude and the distance the ray travelled to it (the rounding error of `o + t d` is bounded by
/// a few ulps of `|o| + t|d| ≤ |p| + 2t`, as in pbrt's error bounds), so a scene renders alike at any scale.
pub(crate) fn eps(h: &Hit) -> f64 {
    let p = h.p;
    1e-8 * (p[0].abs().max(p[1].abs()).max(p[2].abs()) + h.t)
}
