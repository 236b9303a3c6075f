//! A bounding-volume hierarchy over the triangles of all meshes: axis-aligned boxes, split at the median
//! centroid along the longest axis (balanced, built in O(n log n)), flat node array, stack traversal with the
//! nearer child first.

use crate::geometry::{intersect_triangle, Mesh};
use crate::math::V3;

/// A triangle reference: mesh index and triangle index.
#[derive(Debug, Clone, Copy)]
pub struct TriRef {
    pub mesh: u32,
    pub tri: u32,
}

/// A node of the flat array: its box, and either a leaf's primitives or its right child.
#[derive(Debug, Clone, Copy)]
pub struct Node {
    pub lo: V3,
    pub hi: V3,
    /// Leaf: first primitive (index into [`Bvh::prims`]); inner: index of the right child (the left child
    /// follows the node).
    pub start: u32,
    /// Number of primitives in a leaf; 0 for an inner node.
    pub count: u32,
}

#[derive(Debug, Clone, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    pub prims: Vec<TriRef>,
}

const LEAF: usize = 4;

impl Bvh {
    /// The flat node array, root first (what a GPU traverses).
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    pub fn build(meshes: &[Mesh]) -> Self {
        let mut prims = Vec::new();
        for (mi, m) in meshes.iter().enumerate() {
            for (ti, t) in m.triangles.iter().enumerate() {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                let lo = [0, 1, 2].map(|k| a[k].min(b[k]).min(c[k]));
                let hi = [0, 1, 2].map(|k| a[k].max(b[k]).max(c[k]));
                prims.push((TriRef { mesh: mi as u32, tri: ti as u32 }, lo, hi));
            }
        }
        let mut bvh = Bvh { nodes: Vec::with_capacity(2 * prims.len() / LEAF + 1), prims: Vec::new() };
        if !prims.is_empty() {
            let n = prims.len();
            bvh.build_node(&mut prims, 0, n);
        }
        bvh.prims = prims.into_iter().map(|p| p.0).collect();
        bvh
    }

    fn build_node(&mut self, prims: &mut [(TriRef, V3, V3)], start: usize, end: usize) -> usize {
        let slice = &mut prims[start..end];
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut clo = [f64::INFINITY; 3];
        let mut chi = [f64::NEG_INFINITY; 3];
        for (_, l, h) in slice.iter() {
            for k in 0..3 {
                lo[k] = lo[k].min(l[k]);
                hi[k] = hi[k].max(h[k]);
                let c = 0.5 * (l[k] + h[k]);
                clo[k] = clo[k].min(c);
                chi[k] = chi[k].max(c);
            }
        }
        let idx = self.nodes.len();
        self.nodes.push(Node { lo, hi, start: start as u32, count: (end - start) as u32 });
        let ext = [0, 1, 2].map(|k| chi[k] - clo[k]);
        let axis = if ext[0] >= ext[1] && ext[0] >= ext[2] {
            0
        } else if ext[1] >= ext[2] {
            1
        } else {
            2
        };
        if end - start <= LEAF || ext[axis] <= 0.0 {
            return idx;
        }
        let mid = (end - start) / 2;
        let key = |p: &(TriRef, V3, V3)| p.1[axis] + p.2[axis];
        slice.select_nth_unstable_by(mid, |a, b| key(a).total_cmp(&key(b)));
        self.build_node(prims, start, start + mid);
        let right = self.build_node(prims, start + mid, end);
        self.nodes[idx].start = right as u32;
        self.nodes[idx].count = 0;
        idx
    }

    /// The nearest triangle hit before `t_max`: `(t, b1, b2, primitive)`.
    pub fn intersect(&self, meshes: &[Mesh], o: V3, d: V3, mut t_max: f64) -> Option<(f64, f64, f64, TriRef)> {
        if self.nodes.is_empty() {
            return None;
        }
        let inv = d.map(|x| 1.0 / x);
        let mut best = None;
        let mut stack = [0u32; 64];
        let mut sp = 1;
        while sp > 0 {
            sp -= 1;
            let node = self.nodes[stack[sp] as usize];
            if slab(&node, o, inv, t_max).is_none() {
                continue;
            }
            if node.count > 0 {
                for p in &self.prims[node.start as usize..(node.start + node.count) as usize] {
                    let m = &meshes[p.mesh as usize];
                    let [a, b, c] = m.triangles[p.tri as usize].map(|i| m.positions[i as usize]);
                    if let Some((t, u, v)) = intersect_triangle(o, d, a, b, c, t_max) {
                        t_max = t;
                        best = Some((t, u, v, *p));
                    }
                }
            } else {
                let left = stack[sp] + 1;
                let right = node.start;
                let tl = slab(&self.nodes[left as usize], o, inv, t_max);
                let tr = slab(&self.nodes[right as usize], o, inv, t_max);
                // Push the farther child first so the nearer one is visited next.
                match (tl, tr) {
                    (Some(a), Some(b)) => {
                        let (near, far) = if a <= b { (left, right) } else { (right, left) };
                        stack[sp] = far;
                        stack[sp + 1] = near;
                        sp += 2;
                    }
                    (Some(_), None) => {
                        stack[sp] = left;
                        sp += 1;
                    }
                    (None, Some(_)) => {
                        stack[sp] = right;
                        sp += 1;
                    }
                    (None, None) => {}
                }
            }
        }
        best
    }
}

/// Entry distance of the ray into the node's box, if it enters before `t_max`.
#[inline]
fn slab(n: &Node, o: V3, inv: V3, t_max: f64) -> Option<f64> {
    let mut t0 = 0.0f64;
    let mut t1 = t_max;
    for k in 0..3 {
        let a = (n.lo[k] - o[k]) * inv[k];
        let b = (n.hi[k] - o[k]) * inv[k];
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        // NaN (0 · ∞ on a box face) compares false and leaves the interval unchanged.
        if a > t0 {
            t0 = a;
        }
        if b < t1 {
            t1 = b;
        }
    }
    (t0 <= t1).then_some(t0)
}
