//! The procedural snake (issue 19): a body along a planar sine-wave spine, with a flattened belly, a neck and
//! a wider, flatter head, covered with individually curved, overlapping scale plates — dorsal scales in
//! longitudinal rows (alternate rows offset by half a scale, as on real snakes), keeled or smooth, and wide
//! ventral plates along the belly — as real triangles.
//!
//! Each plate is a patch over plate coordinates `(a, b)`: `a` from its base (anterior, tucked under the plate
//! in front of it) to its free tip (posterior), `b` across it from −1 to 1. It lies on the body at the height
//! [`PlateShape::height`] above the body surface: a tilt that lifts the free tip over the next plate, a dome
//! across, a slight arch along, and on keeled scales a ridge along the midline. Normals are those of the
//! displaced surface; the orientation field (`Mesh::along`, the `along` rule) follows the plate's long axis
//! from base to tip — "nanofingers run parallel to snake scales (from the anterior end towards the posterior
//! end of the animal)", paper sec. 7 — converging slightly towards the tip, and lies in the plate's tangent
//! plane, so both the normal and the nanostructure's axis vary across every scale.
//!
//! Why triangles and not a normal and orientation map on a smooth tube: the overlapping edges are then real —
//! they cast shadows on the next scale, show in silhouette, hide the plate below at grazing view — and the
//! GPU renderer and glTF files get the relief with no extra machinery (the per-vertex normal and `along`
//! field travel with the triangles; the glTF export writes `along` as TANGENT). The price is triangles: about
//! 130 per plate.

use std::cell::RefCell;
use std::f64::consts::{PI, TAU};

use crate::geometry::Mesh;
use crate::math::*;

/// The relief of the scales.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScaleKind {
    /// The smooth tube of earlier versions (texture scales only, `tiles` repeats of the UV square).
    None,
    /// Smooth, domed plates (Xenopeltis: smooth, glossy scales).
    Smooth,
    /// Plates with a ridge along the midline on the upper rows (Elaphe: weakly keeled dorsal scales).
    Keeled,
}

impl ScaleKind {
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "none" => Some(ScaleKind::None),
            "smooth" => Some(ScaleKind::Smooth),
            "keeled" => Some(ScaleKind::Keeled),
            _ => None,
        }
    }
}

/// Parameters of the procedural snake.
#[derive(Debug, Clone, PartialEq)]
pub struct SnakeParams {
    /// Length of the spine (scene units).
    pub length: f64,
    /// Largest radius of the body.
    pub radius: f64,
    /// Number of full sine waves along the body.
    pub waves: f64,
    /// Amplitude of the sideways undulation.
    pub amplitude: f64,
    /// Rings along the body and vertices around it (the smooth tube, `ScaleKind::None`).
    pub rings: usize,
    pub segments: usize,
    /// How many times the UV square repeats along the body and around it.
    pub tiles: [f64; 2],
    pub scales: ScaleKind,
    /// Dorsal scale rows around the body (Elaphe guttata 27, Xenopeltis unicolor 15).
    pub scale_rows: usize,
    /// Spacing of the scales along the body where it is thickest (scene units); 0: 1.6 × a row's width.
    pub scale_length: f64,
    /// The part of the body that is built, as fractions of the spine from tail (0) to head (1).
    pub section: [f64; 2],
    /// Vertices along and across each dorsal plate (keeled plates get four more across, ventral plates six):
    /// fewer for a whole snake seen from afar, more for close-ups.
    pub scale_grid: [usize; 2],
}

impl Default for SnakeParams {
    fn default() -> Self {
        Self {
            length: 10.0,
            radius: 0.45,
            waves: 1.5,
            amplitude: 0.9,
            rings: 400,
            segments: 48,
            tiles: [40.0, 4.0],
            scales: ScaleKind::None,
            scale_rows: 19,
            scale_length: 0.0,
            section: [0.0, 1.0],
            scale_grid: [13, 11],
        }
    }
}

/// Half-angle of the belly covered by ventral plates, about the ventral midline (φ = π).
pub const VENTRAL_HALF_ANGLE: f64 = 0.3 * PI;

/// The body's cross-section squashes below its centre line to this fraction (a flattened belly).
const BELLY_FLAT: f64 = 0.6;

/// The body: spine, cross-section and the scale coordinate along it.
#[derive(Debug, Clone)]
pub struct Body {
    p: SnakeParams,
    /// σ (scale spacings from the tail tip) at `s = k / (n − 1)`.
    sigma: Vec<f64>,
    /// The cross-sections [`Body::surface`] computed last, by `s` (see [`Sections`]).
    sections: RefCell<Sections>,
}

/// The cross-section of the body at one `s`: what [`Body::surface`] needs besides the angle.
#[derive(Debug, Clone, Copy)]
struct Section {
    side: V3,
    up: V3,
    half_width: f64,
    half_height: f64,
    centre: V3,
}

/// A small cache of cross-sections by the bits of `s`, each slot holding the last one that hashed there. A plate
/// vertex's point, normal and nanostructure axis take about 90 body points by central differences, at about 9
/// distinct `s`: the section (six transcendental functions) was computed for each of them, and building the
/// mesh was two thirds of loading a snake scene. Holds values only, so the mesh is bit-for-bit the same.
#[derive(Debug, Clone)]
struct Sections([Option<(u64, Section)>; 64]);

impl Default for Sections {
    fn default() -> Self {
        Sections([None; 64])
    }
}

fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Where the head begins (fraction of the spine) and the neck's centre just behind it.
const HEAD_START: f64 = 0.935;
const NECK: f64 = 0.925;
/// Where the head is widest (the jaws); it tapers from there to the snout at `s = 1`.
const JAWS: f64 = 0.95;

/// Where the eyes sit: along the spine, around the head from the dorsal midline, and their radius as a
/// fraction of the head's half-height there.
pub const EYE_S: f64 = 0.972;
const EYE_PHI: f64 = 1.05;
const EYE_RADIUS: f64 = 0.16;

impl Body {
    pub fn new(p: &SnakeParams) -> Self {
        let mut b = Body { p: p.clone(), sigma: Vec::new(), sections: RefCell::default() };
        // σ(s) = ∫ |spine'(s)| / L(s) ds: scales shorten with the body's width towards the tail and lengthen
        // on the head (its large shields).
        let n = 8192;
        let mut sigma = Vec::with_capacity(n);
        let mut acc = 0.0;
        let mut prev = 0.0;
        for k in 0..n {
            let s = k as f64 / (n - 1) as f64;
            let f = length(b.spine_derivative(s)) / b.scale_spacing(s);
            if k > 0 {
                acc += 0.5 * (f + prev) / (n - 1) as f64;
            }
            prev = f;
            sigma.push(acc);
        }
        b.sigma = sigma;
        b
    }

    pub fn params(&self) -> &SnakeParams {
        &self.p
    }

    /// The spine in the x–z plane (y up), tail at −x, head at +x.
    pub fn spine(&self, s: f64) -> V3 {
        let p = &self.p;
        let x = (s - 0.5) * p.length;
        let z = p.amplitude * (TAU * p.waves * s).sin() * (0.4 + 0.6 * s);
        [x, 0.0, z]
    }

    fn spine_derivative(&self, s: f64) -> V3 {
        let p = &self.p;
        let w = TAU * p.waves;
        let dz = p.amplitude * (w * (w * s).cos() * (0.4 + 0.6 * s) + 0.6 * (w * s).sin());
        [p.length, 0.0, dz]
    }

    /// Unit tangent (tail → head), side (right of the body, looking head-wards from above: `T × up`) and up.
    pub fn frame(&self, s: f64) -> (V3, V3, V3) {
        let t = normalize(self.spine_derivative(s));
        let side = normalize(cross(t, [0.0, 1.0, 0.0]));
        (t, side, cross(side, t))
    }

    /// Half-width and half-height of the cross-section: a long taper to the pointed tail, a neck, a head
    /// wider than the neck and flatter than the body, tapering from the jaws to a rounded snout.
    pub fn half_axes(&self, s: f64) -> (f64, f64) {
        let s = s.clamp(0.0, 1.0);
        let tail = (s / 0.6).min(1.0).powf(0.7).max(0.02);
        let neck = 1.0 - 0.1 * (-((s - NECK) / 0.012).powi(2)).exp();
        let head = smoothstep(HEAD_START - 0.01, HEAD_START + 0.02, s);
        // From the jaws (widest) to the tip of the snout, an elliptical taper: narrow in plan, rounded in profile.
        let x = ((s - JAWS) / (1.0 - JAWS)).clamp(0.0, 1.0);
        let snout = (1.0 - x * x).sqrt();
        let r = self.p.radius * tail * neck;
        (r * (1.0 + 0.12 * head) * snout.powf(0.9).max(0.04), r * (1.0 - 0.35 * head) * snout.powf(0.5).max(0.04))
    }

    /// Spacing of the transverse scale rows at `s` (scene units along the spine).
    fn scale_spacing(&self, s: f64) -> f64 {
        let (w, _) = self.half_axes(s);
        let base = if self.p.scale_length > 0.0 { self.p.scale_length } else { 1.6 * self.row_width_max() };
        let head = smoothstep(HEAD_START, HEAD_START + 0.02, s);
        base * (w / self.p.radius).clamp(0.1, 1.0).sqrt().max(0.3) * (1.0 + 1.5 * head)
    }

    /// The width of a dorsal row where the body is thickest (an arc of the round part of the section).
    pub fn row_width_max(&self) -> f64 {
        self.p.radius * dorsal_row_angle(self.p.scale_rows)
    }

    /// σ, the number of scale spacings from the tail tip to `s`.
    pub fn sigma_of(&self, s: f64) -> f64 {
        let n = self.sigma.len();
        let x = s.clamp(0.0, 1.0) * (n - 1) as f64;
        let i = (x.floor() as usize).min(n - 2);
        let f = x - i as f64;
        self.sigma[i] + (self.sigma[i + 1] - self.sigma[i]) * f
    }

    /// The inverse of [`Body::sigma_of`] (σ beyond the ends extrapolates linearly).
    pub fn s_of_sigma(&self, sigma: f64) -> f64 {
        let n = self.sigma.len();
        let i = self.sigma.partition_point(|&x| x <= sigma).clamp(1, n - 1);
        let (a, b) = (self.sigma[i - 1], self.sigma[i]);
        ((i - 1) as f64 + (sigma - a) / (b - a)) / (n - 1) as f64
    }

    /// The point of the body surface at `s` and angle `phi` around it (0 on the dorsal midline, π/2 on the
    /// right side, ±π on the ventral midline). The belly rests on `y = 0`.
    pub fn surface(&self, s: f64, phi: f64) -> V3 {
        let Section { side, up, half_width: rw, half_height: rh, centre: c } = self.section(s);
        let (sp, cp) = phi.sin_cos();
        // Below the centre line the section squashes smoothly (C¹) to BELLY_FLAT at the ventral midline.
        let flat = if cp < 0.0 { 1.0 - (1.0 - BELLY_FLAT) * cp * cp } else { 1.0 };
        add(c, add(mul(side, rw * sp), mul(up, rh * cp * flat)))
    }

    /// The cross-section at `s`, from [`Sections`] when it was computed lately.
    fn section(&self, s: f64) -> Section {
        let bits = s.to_bits();
        let slot = (bits.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 58) as usize;
        if let Some((b, section)) = self.sections.borrow().0[slot] {
            if b == bits {
                return section;
            }
        }
        let (_, side, up) = self.frame(s);
        let (half_width, half_height) = self.half_axes(s);
        let centre = add(self.spine(s.clamp(0.0, 1.0)), [0.0, half_height * BELLY_FLAT, 0.0]);
        let section = Section { side, up, half_width, half_height, centre };
        self.sections.borrow_mut().0[slot] = Some((bits, section));
        section
    }

    /// Outward unit normal of the body surface at `(s, phi)` (central differences of [`Body::surface`]).
    pub fn normal(&self, s: f64, phi: f64) -> V3 {
        let (ds, dp) = (1e-5, 1e-5);
        let ps = sub(self.surface(s + ds, phi), self.surface(s - ds, phi));
        let pp = sub(self.surface(s, phi + dp), self.surface(s, phi - dp));
        // s runs tail → head, φ from the back to the right side: ∂P/∂φ × ∂P/∂s points outwards.
        let n = normalize(cross(pp, ps));
        if n == [0.0; 3] {
            // At the pointed ends: away from the spine.
            return normalize(sub(self.surface(s, phi), self.spine(s.clamp(0.0, 1.0))));
        }
        n
    }
}

/// Centres and radius of the two eyes (on the upper sides of the head, a little sunk into it).
pub fn eyes(p: &SnakeParams) -> [(V3, f64); 2] {
    let body = Body::new(p);
    let (_, rh) = body.half_axes(EYE_S);
    let r = EYE_RADIUS * rh;
    [-EYE_PHI, EYE_PHI].map(|phi| {
        let c = add(body.surface(EYE_S, phi), mul(body.normal(EYE_S, phi), 0.35 * r));
        (c, r)
    })
}

/// The angle around the body of one dorsal row.
pub fn dorsal_row_angle(rows: usize) -> f64 {
    2.0 * (PI - VENTRAL_HALF_ANGLE) / rows.max(1) as f64
}

/// A dorsal plate's half-width at its widest, in rows: neighbouring rows overlap by 0.2 of a row on each side.
pub const DORSAL_HALF_WIDTH: f64 = 0.7;

/// A plate's length along the body, in scale spacings: plates overlap the next one by `PLATE_LENGTH − 1`.
pub const PLATE_LENGTH: f64 = 1.45;

/// The shape of a scale plate, in units of its row width `w` (heights) and plate coordinates `(a, b)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlateShape {
    /// Rise of the plate from base to tip (the tilt that lifts the free edge over the next plate), × w.
    pub lift: f64,
    /// Dome height across the plate (`dome · (1 − b²)`), × w.
    pub dome: f64,
    /// Arch along the plate (`arch · sin(π a)`), × w.
    pub arch: f64,
    /// Keel height along the midline, × w (0: smooth).
    pub keel: f64,
    /// Keel width in `b`.
    pub keel_width: f64,
    /// How far the plate's edge curls down under its neighbours near `|b| = 1` (ventral plates), × w.
    pub tuck: f64,
}

impl PlateShape {
    /// A keeled dorsal scale (Elaphe): its tip lifted 10° over a plate 2.3 row widths long (`lift` 0.41 w), a
    /// dome whose edges slope 14° (`dome` 0.087 w over a half-width of 0.7 w), a slight arch, and a ridge
    /// along the midline whose flanks slope about 25°, strongest on the upper rows. Where two plates overlap,
    /// their `a` differ by at least ½ spacing (0.345 in `a`), so the upper one stands `0.345·lift` higher; the
    /// dome takes back at most half its height there (the sides overlap by 0.2 w), so it must stay under
    /// `0.69·lift`.
    pub fn keeled(keel: f64) -> Self {
        PlateShape { lift: 0.41, dome: 0.087, arch: 0.03, keel: 0.076 * keel, keel_width: 0.18, tuck: 0.0 }
    }

    /// A smooth dorsal scale (Xenopeltis): flatter and tighter, its tip lifted 6° (`lift` 0.25 w), a dome
    /// whose edges slope 8° (`dome` 0.05 w).
    pub fn smooth() -> Self {
        PlateShape { lift: 0.25, dome: 0.05, arch: 0.02, keel: 0.0, keel_width: 0.18, tuck: 0.0 }
    }

    /// A ventral plate: wide, flatter, its sides curled down (by 0.3 w) under the lowest dorsal rows.
    pub fn ventral() -> Self {
        PlateShape { lift: 0.2, dome: 0.06, arch: 0.02, keel: 0.0, keel_width: 0.18, tuck: 0.3 }
    }

    /// Height above the body surface in units of the row width (the closed form every normal comes from):
    /// `lift·(a − ¼) + dome·(1 − b²) + arch·sin(πa) + keel·e^{−(b/k)²}·smoothstep(0.1, 0.45, a) − tuck·smoothstep(0.7, 0.87, |b|)`.
    pub fn height(&self, a: f64, b: f64) -> f64 {
        let mut h = self.lift * (a - 0.25) + self.dome * (1.0 - b * b) + self.arch * (PI * a).sin();
        if self.keel != 0.0 {
            h += self.keel * (-(b / self.keel_width).powi(2)).exp() * smoothstep(0.1, 0.45, a);
        }
        if self.tuck != 0.0 {
            h -= self.tuck * smoothstep(0.7, 0.87, b.abs());
        }
        h
    }

    /// `(∂h/∂a, ∂h/∂b)` of [`PlateShape::height`], in closed form.
    pub fn gradient(&self, a: f64, b: f64) -> (f64, f64) {
        let mut ha = self.lift + self.arch * PI * (PI * a).cos();
        let mut hb = -2.0 * self.dome * b;
        if self.keel != 0.0 {
            let k = self.keel_width;
            let g = (-(b / k).powi(2)).exp();
            let t = ((a - 0.1) / 0.35).clamp(0.0, 1.0);
            let sm = t * t * (3.0 - 2.0 * t);
            let dsm = if (0.0..1.0).contains(&t) && a > 0.1 { 6.0 * t * (1.0 - t) / 0.35 } else { 0.0 };
            ha += self.keel * g * dsm;
            hb += self.keel * g * (-2.0 * b / (k * k)) * sm;
        }
        if self.tuck != 0.0 {
            let t = ((b.abs() - 0.7) / 0.17).clamp(0.0, 1.0);
            let d = if t > 0.0 && t < 1.0 { 6.0 * t * (1.0 - t) / 0.17 } else { 0.0 };
            hb -= self.tuck * d * b.signum();
        }
        (ha, hb)
    }
}

/// One scale plate on the body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plate {
    /// σ of the plate's base (its anterior end; the tip lies `PLATE_LENGTH` spacings towards the tail).
    pub sigma_base: f64,
    /// Angle of its midline around the body.
    pub phi: f64,
    /// Half its width at the widest, as an angle around the body.
    pub half_angle: f64,
    /// Row width (the unit of its heights).
    pub w: f64,
    pub shape: PlateShape,
    /// Dorsal scales narrow towards base and tip; ventral plates are as wide along their whole length.
    pub dorsal: bool,
}

/// The plate's half-width profile along `a`: for dorsal scales a rounded shield, the super-ellipse
/// `|x|^2.5 + |y|^2.5 = 1` widest at `a = 0.55` (rounded at base and tip); constant for ventral plates.
fn half_width(dorsal: bool, a: f64) -> f64 {
    if dorsal {
        let x = if a < WIDEST { (WIDEST - a) / WIDEST } else { (a - WIDEST) / (1.0 - WIDEST) };
        (1.0 - x.clamp(0.0, 1.0).powf(OUTLINE_POWER)).max(0.0).powf(1.0 / OUTLINE_POWER)
    } else {
        1.0
    }
}

/// Where a dorsal plate is widest (in `a`) and the exponent of its super-elliptic outline.
pub const WIDEST: f64 = 0.55;
const OUTLINE_POWER: f64 = 2.5;

/// Normals and orientations at the plate's very base and tip (where its width goes to zero) are taken this
/// close to them instead.
const END_GUARD: f64 = 0.004;

/// How much the lines of the orientation field converge from base to tip (`b` scales by `1 − CONVERGE·a`).
pub const CONVERGE: f64 = 0.3;

impl Plate {
    /// Body coordinates `(s, φ)` of the plate point `(a, b)`.
    pub fn body_coords(&self, body: &Body, a: f64, b: f64) -> (f64, f64) {
        let sigma = self.sigma_base - a * PLATE_LENGTH;
        (body.s_of_sigma(sigma), self.phi + b * half_width(self.dorsal, a) * self.half_angle)
    }

    /// The plate point `(a, b)`: the body surface there, raised along its normal by the plate's height.
    pub fn point(&self, body: &Body, a: f64, b: f64) -> V3 {
        let (s, phi) = self.body_coords(body, a, b);
        add(body.surface(s, phi), mul(body.normal(s, phi), self.w * self.shape.height(a, b)))
    }

    /// `(∂P/∂a, ∂P/∂b)` by central differences of [`Plate::point`] (a smooth closed form).
    pub fn derivatives(&self, body: &Body, a: f64, b: f64) -> (V3, V3) {
        let a = a.clamp(END_GUARD, 1.0 - END_GUARD);
        let e = 1e-5;
        let pa = mul(sub(self.point(body, a + e, b), self.point(body, a - e, b)), 0.5 / e);
        let pb = mul(sub(self.point(body, a, b + e), self.point(body, a, b - e)), 0.5 / e);
        (pa, pb)
    }

    /// Unit normal of the plate at `(a, b)`, on the outside of the body.
    pub fn normal(&self, body: &Body, a: f64, b: f64) -> V3 {
        let a = a.clamp(END_GUARD, 1.0 - END_GUARD);
        let (pa, pb) = self.derivatives(body, a, b);
        self.outward_normal(body, a, b, pa, pb)
    }

    /// [`Plate::normal`] and [`Plate::orientation`] at `(a, b)` from one set of derivatives (the mesh needs
    /// both at every vertex; each alone takes the derivatives again, 20 evaluations of the body surface).
    pub fn normal_and_orientation(&self, body: &Body, a: f64, b: f64) -> (V3, V3) {
        let a = a.clamp(END_GUARD, 1.0 - END_GUARD);
        let (pa, pb) = self.derivatives(body, a, b);
        let n = self.outward_normal(body, a, b, pa, pb);
        (n, self.axis(a, b, pa, pb, n))
    }

    /// The unit normal `∂P/∂b × ∂P/∂a`, turned to the outside of the body.
    fn outward_normal(&self, body: &Body, a: f64, b: f64, pa: V3, pb: V3) -> V3 {
        let n = normalize(cross(pb, pa));
        let (s, phi) = self.body_coords(body, a, b);
        if dot(n, body.normal(s, phi)) < 0.0 {
            mul(n, -1.0)
        } else {
            n
        }
    }

    /// The nanostructure's axis at `(a, b)`: the plate's long axis from base to tip — the direction of the
    /// field line `φ − φ_c = c·(1 − CONVERGE·a)·half_angle` through the point, straight along the body and
    /// converging slightly towards the tip whatever the outline does — in the plate's tangent plane. In plate
    /// coordinates the line has `db/da = −b·(CONVERGE/(1 − CONVERGE·a) + hw'(a)/hw(a))`.
    pub fn orientation(&self, body: &Body, a: f64, b: f64) -> V3 {
        self.normal_and_orientation(body, a, b).1
    }

    /// [`Plate::orientation`] at a clamped `a`, given the derivatives there and the plate's normal.
    fn axis(&self, a: f64, b: f64, pa: V3, pb: V3, n: V3) -> V3 {
        let e = 1e-6;
        let hw = half_width(self.dorsal, a);
        let dhw = (half_width(self.dorsal, a + e) - half_width(self.dorsal, a - e)) / (2.0 * e);
        let db_da = -b * (CONVERGE / (1.0 - CONVERGE * a) + dhw / hw);
        orthogonalize(add(pa, mul(pb, db_da)), n).unwrap_or_else(|| normalize(pa))
    }
}

/// Every plate of the body whose centre lies in the section, dorsal rows then ventral plates.
pub fn plates(body: &Body) -> Vec<Plate> {
    let p = body.params();
    let rows = p.scale_rows.max(3);
    let dphi = dorsal_row_angle(rows);
    let (s0, s1) = (p.section[0].clamp(0.0, 1.0), p.section[1].clamp(0.0, 1.0));
    let total = body.sigma_of(1.0);
    let mut out = Vec::new();
    // Plates whose base lies at σ = k (+ ½ on odd rows); the tip reaches PLATE_LENGTH spacings tail-wards.
    let n = total.ceil() as i64 + 1;
    for k in 0..=n {
        for j in 0..rows {
            let phi = -(PI - VENTRAL_HALF_ANGLE) + (j as f64 + 0.5) * dphi;
            let sigma_base = k as f64 + if j % 2 == 1 { 0.5 } else { 0.0 };
            let centre = body.s_of_sigma(sigma_base - 0.5 * PLATE_LENGTH);
            if sigma_base - 0.5 * PLATE_LENGTH < 0.0 || sigma_base - 0.5 * PLATE_LENGTH > total {
                continue;
            }
            if centre < s0 || centre > s1 {
                continue;
            }
            let (rw, _) = body.half_axes(centre);
            // Keels on the upper rows only (as on Elaphe guttata), fading out down the flanks.
            let upper = (1.5 * phi.cos()).clamp(0.0, 1.0);
            let shape = if p.scales == ScaleKind::Keeled { PlateShape::keeled(upper) } else { PlateShape::smooth() };
            out.push(Plate {
                sigma_base,
                phi,
                half_angle: DORSAL_HALF_WIDTH * dphi,
                w: rw * dphi,
                shape,
                dorsal: true,
            });
        }
        let sigma_base = k as f64 + 0.25;
        let c = sigma_base - 0.5 * PLATE_LENGTH;
        if c >= 0.0 && c <= total {
            let centre = body.s_of_sigma(c);
            if centre >= s0 && centre <= s1 {
                let (rw, _) = body.half_axes(centre);
                out.push(Plate {
                    sigma_base,
                    phi: PI,
                    half_angle: VENTRAL_HALF_ANGLE * 1.12,
                    w: rw * dphi,
                    shape: PlateShape::ventral(),
                    dorsal: false,
                });
            }
        }
    }
    out
}

/// Vertices along and across `plate`'s grid.
fn plate_grid(p: &SnakeParams, plate: &Plate) -> (usize, usize) {
    let [along, across] = p.scale_grid.map(|n| n.max(3));
    if !plate.dorsal {
        (along, across + 6)
    } else if plate.shape.keel > 0.0 {
        (along, across + 4)
    } else {
        (along, across)
    }
}

/// Rings of the inner tube per unit of `s` and vertices around it.
const TUBE_RINGS: f64 = 250.0;
// Public but hidden: not API, reachable only for the crate's tests in tests/ (Cargo.toml, `[lib] test = false`).
#[doc(hidden)]
pub const TUBE_SEGMENTS: usize = 48;
/// Depth of the inner tube under the body surface, in row widths.
const TUBE_DEPTH: f64 = 0.45;

/// The number of triangles [`scaled_snake_mesh`] makes for `p` (cheap: the plates are laid out, not built).
pub fn triangle_count(p: &SnakeParams) -> usize {
    let body = Body::new(p);
    let plates: usize = plates(&body)
        .iter()
        .map(|pl| {
            let (na, nb) = plate_grid(p, pl);
            2 * (na - 1) * (nb - 1)
        })
        .sum();
    let (s0, s1) = (p.section[0].clamp(0.0, 1.0), p.section[1].clamp(0.0, 1.0));
    plates + 2 * tube_rings(s0, s1) * TUBE_SEGMENTS
}

/// Rings of the inner tube between spine positions `s0` and `s1` (at least 2).
// Public but hidden: not API, a pure helper reachable only for the crate's tests in tests/ (Cargo.toml,
// `[lib] test = false`).
#[doc(hidden)]
pub fn tube_rings(s0: f64, s1: f64) -> usize {
    ((s1 - s0) * TUBE_RINGS).ceil().max(2.0) as usize
}

/// The scaled snake as one mesh: every plate of [`plates`] as a grid of triangles with the plate's normals,
/// the orientation field as `along`, and UVs in body coordinates (`u = s·tiles[0]` from tail to head,
/// `v = (½ + φ/2π)·tiles[1]`: the dorsal midline at `v = ½`, the belly at 0 ≡ 1), plus a dark inner tube a
/// little under the plates that closes any gap between them.
pub fn scaled_snake_mesh(p: &SnakeParams, material: usize) -> Mesh {
    let body = Body::new(p);
    let mut m = Mesh { name: "snake".into(), material, ..Default::default() };
    let mut uvs = Vec::new();
    let mut along = Vec::new();
    let uv_of = |s: f64, phi: f64| [s * p.tiles[0], (0.5 + phi / TAU) * p.tiles[1]];
    for plate in plates(&body) {
        let (na, nb) = plate_grid(p, &plate);
        let start = m.positions.len() as u32;
        for i in 0..na {
            // Denser towards the tip, where the plate shows and its outline rounds off.
            let a = 1.0 - (1.0 - i as f64 / (na - 1) as f64).powf(1.6);
            for jb in 0..nb {
                let b = -1.0 + 2.0 * jb as f64 / (nb - 1) as f64;
                let (s, phi) = plate.body_coords(&body, a, b);
                let (normal, axis) = plate.normal_and_orientation(&body, a, b);
                m.positions.push(plate.point(&body, a, b));
                m.normals.push(normal);
                along.push(axis);
                uvs.push(uv_of(s, phi));
            }
        }
        for i in 0..na - 1 {
            for jb in 0..nb - 1 {
                let v = start + (i * nb + jb) as u32;
                let (r, d, rd) = (v + 1, v + nb as u32, v + nb as u32 + 1);
                m.triangles.push([v, d, r]);
                m.triangles.push([r, d, rd]);
            }
        }
    }
    // The inner tube, 0.45 row widths under the body surface: below every plate (the lowest, a ventral
    // plate's curled side, reaches −0.35 w).
    let (s0, s1) = (p.section[0].clamp(0.0, 1.0), p.section[1].clamp(0.0, 1.0));
    let rings = tube_rings(s0, s1);
    let segs = TUBE_SEGMENTS;
    let dphi = dorsal_row_angle(p.scale_rows.max(3));
    let start = m.positions.len() as u32;
    for i in 0..=rings {
        let s = s0 + (s1 - s0) * i as f64 / rings as f64;
        let (rw, _) = body.half_axes(s);
        for j in 0..=segs {
            let phi = -PI + TAU * j as f64 / segs as f64;
            let n = body.normal(s, phi);
            m.positions.push(add(body.surface(s, phi), mul(n, -TUBE_DEPTH * rw * dphi)));
            m.normals.push(n);
            along.push(body.frame(s).0);
            uvs.push(uv_of(s, phi));
        }
    }
    let row = (segs + 1) as u32;
    for i in 0..rings as u32 {
        for j in 0..segs as u32 {
            let a = start + i * row + j;
            let b = a + row;
            m.triangles.push([a, b, a + 1]);
            m.triangles.push([a + 1, b, b + 1]);
        }
    }
    m.uvs = Some(uvs);
    m.along = Some(along);
    m.compute_tangents();
    m
}

/// The snake body: a tube of `rings × segments` vertices around a spine in the x–z plane (y up), lying on
/// `y = 0` (its belly touches the ground), head at `+x`. The radius tapers to a point at the tail and to a
/// rounded head; `u` runs along the body (tail → head, repeating `tiles[0]` times), `v` around it, and the
/// `along` attribute is the spine's direction (tail → head), the rule the paper uses for the nanofingers.
/// With scales (`p.scales` smooth or keeled), the body of this module covered with plates instead.
pub fn snake_mesh(p: &SnakeParams, material: usize) -> Mesh {
    if p.scales != ScaleKind::None {
        return scaled_snake_mesh(p, material);
    }
    let n_r = p.rings.max(8);
    let n_s = p.segments.max(6);
    let spine = |s: f64| -> V3 {
        let x = (s - 0.5) * p.length;
        let z = p.amplitude * (std::f64::consts::TAU * p.waves * s).sin() * (0.4 + 0.6 * s);
        [x, 0.0, z]
    };
    let radius = |s: f64| -> f64 {
        let tail = (s / 0.6).min(1.0).powf(0.7); // long taper to the tail tip
        let head = if s > 0.97 { ((1.0 - s) / 0.03).max(0.0).sqrt() } else { 1.0 };
        let neck = 1.0 - 0.25 * (-((s - 0.93) / 0.02).powi(2)).exp();
        p.radius * tail.max(0.02) * head.max(0.05) * neck
    };
    let mut m = Mesh { name: "snake".into(), material, ..Default::default() };
    let mut uvs = Vec::new();
    let mut along = Vec::new();
    for i in 0..n_r {
        let s = i as f64 / (n_r - 1) as f64;
        let ds = 1e-4;
        let tan = normalize(sub(spine((s + ds).min(1.0)), spine((s - ds).max(0.0))));
        let up = [0.0, 1.0, 0.0];
        let side = normalize(cross(tan, up));
        let up = cross(side, tan);
        let r = radius(s);
        let c = add(spine(s), [0.0, r, 0.0]);
        for j in 0..=n_s {
            let a = std::f64::consts::TAU * j as f64 / n_s as f64;
            let dir = add(mul(up, a.cos()), mul(side, a.sin()));
            // A slightly flattened belly: the cross-section squashes below the centre line.
            let flat = if dir[1] < 0.0 { 0.6 } else { 1.0 };
            let off = add(mul(side, r * a.sin()), mul(up, r * a.cos() * flat));
            m.positions.push(add(c, off));
            uvs.push([s * p.tiles[0], j as f64 / n_s as f64 * p.tiles[1]]);
            along.push(tan);
        }
    }
    let row = (n_s + 1) as u32;
    for i in 0..(n_r - 1) as u32 {
        for j in 0..n_s as u32 {
            let a = i * row + j;
            let b = a + row;
            m.triangles.push([a, a + 1, b]);
            m.triangles.push([a + 1, b + 1, b]);
        }
    }
    m.uvs = Some(uvs);
    m.along = Some(along);
    m.compute_normals();
    // The seam column duplicates positions: average the normals across it so the tube shades smoothly.
    for i in 0..n_r {
        let (a, b) = (i * (n_s + 1), i * (n_s + 1) + n_s);
        let n = normalize(add(m.normals[a], m.normals[b]));
        m.normals[a] = n;
        m.normals[b] = n;
    }
    m.compute_tangents();
    m
}
