// Extended light on the GPU: area lights (render::area), the environment's importance sampler
// (render::light::EnvSampler), the diffraction lobe's sampler and prefiltered tables (render::lobe), the
// samplers of render::sampling and the Monte Carlo integrator of render::integrate -- the same distributions
// on the same data (uploaded by crates/gpu/src/scene.rs), with the GPU's own random numbers, so that a
// converged GPU image equals the converged CPU image (not sample for sample).

// ------------------------------------------------------------------ random numbers

var<private> rng_state: u32;

// PCG's output permutation of an LCG step (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering").
fn pcg_hash(v: u32) -> u32 {
    let s = v * 747796405u + 2891336453u;
    let w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}

// The stream of one camera sample of one pixel (render::sampling::seed).
fn seed_rng(pixel: u32, sample: u32) {
    rng_state = pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(P.seed)));
}

// Uniform in [0, 1): 24 bits.
fn rand() -> f32 {
    rng_state = pcg_hash(rng_state);
    return f32(rng_state >> 8u) * 5.9604645e-8;
}

fn rand2() -> vec2<f32> {
    let a = rand();
    return vec2<f32>(a, rand());
}

// The power heuristic for one sample of each of two techniques (render::sampling::power_heuristic).
fn power_heuristic(a: f32, b: f32) -> f32 {
    if (a <= 0.0) {
        return 0.0;
    }
    let r = b / a;
    return 1.0 / (1.0 + r * r);
}

// ------------------------------------------------------------------ directions

struct Frame {
    t: vec3<f32>,
    b: vec3<f32>,
}

// An orthonormal frame about a unit normal (Duff et al. 2017; render::sampling::frame).
fn frame_of(n: vec3<f32>) -> Frame {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    return Frame(vec3<f32>(1.0 + s * n.x * n.x * a, s * b, -s * n.x), vec3<f32>(b, s + n.y * n.y * a, -n.y));
}

fn concentric_disk(u: vec2<f32>) -> vec2<f32> {
    let a = 2.0 * u.x - 1.0;
    let b = 2.0 * u.y - 1.0;
    if (a == 0.0 && b == 0.0) {
        return vec2<f32>(0.0);
    }
    var r = b;
    var phi = 0.5 * PI - 0.25 * PI * (a / b);
    if (abs(a) > abs(b)) {
        r = a;
        phi = 0.25 * PI * (b / a);
    }
    return r * vec2<f32>(cos(phi), sin(phi));
}

fn cosine_hemisphere(n: vec3<f32>, u: vec2<f32>) -> vec3<f32> {
    let d = concentric_disk(u);
    let z = sqrt(max(1.0 - dot(d, d), 0.0));
    let f = frame_of(n);
    return f.t * d.x + f.b * d.y + n * z;
}

// A GGX visible normal for wo (local frame, z the normal), isotropic alpha (Heitz 2018).
fn ggx_visible_normal(wo: vec3<f32>, alpha: f32, u: vec2<f32>) -> vec3<f32> {
    let vh = normalize(vec3<f32>(alpha * wo.x, alpha * wo.y, wo.z));
    let len2 = vh.x * vh.x + vh.y * vh.y;
    var t1 = vec3<f32>(1.0, 0.0, 0.0);
    if (len2 > 0.0) {
        t1 = vec3<f32>(-vh.y, vh.x, 0.0) / sqrt(len2);
    }
    let t2 = cross(vh, t1);
    let r = sqrt(u.x);
    let phi = TAU * u.y;
    let p1 = r * cos(phi);
    var p2 = r * sin(phi);
    let s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(1.0 - p1 * p1, 0.0)) + s * p2;
    let nh = t1 * p1 + t2 * p2 + vh * sqrt(max(1.0 - p1 * p1 - p2 * p2, 0.0));
    return normalize(vec3<f32>(alpha * nh.x, alpha * nh.y, max(nh.z, 1e-12)));
}

// ------------------------------------------------------------------ piecewise-constant distributions

// render::sampling::Distribution2d in `tables` at base: row CDF (rows + 1), each row's column CDF
// (rows * (cols + 1)), each cell's probability (rows * cols).

// The last index i < n with cdf[i] <= u (the interval of u), tables[base .. base + n + 1].
fn cdf_find(base: u32, n: u32, u: f32) -> u32 {
    var lo = 0u;
    var hi = n;
    while (hi - lo > 1u) {
        let mid = (lo + hi) / 2u;
        if (tables[base + mid] <= u) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

fn cdf_fraction(base: u32, i: u32, u: f32) -> f32 {
    let a = tables[base + i];
    let w = tables[base + i + 1u] - a;
    if (w <= 0.0) {
        return 0.5;
    }
    return clamp((u - a) / w, 0.0, 0.99999994);
}

struct Cell {
    col: u32,
    row: u32,
    f: vec2<f32>,
}

fn dist_sample(base: u32, cols: u32, rows: u32, u: vec2<f32>) -> Cell {
    let r = cdf_find(base, rows, u.y);
    let fr = cdf_fraction(base, r, u.y);
    let cb = base + rows + 1u + r * (cols + 1u);
    let c = cdf_find(cb, cols, u.x);
    return Cell(c, r, vec2<f32>(cdf_fraction(cb, c, u.x), fr));
}

fn dist_prob(base: u32, cols: u32, rows: u32, c: u32, r: u32) -> f32 {
    return tables[base + rows + 1u + rows * (cols + 1u) + r * cols + c];
}

// ------------------------------------------------------------------ the environment's sampler

// At P.env_cdf_base: [columns, rows], then the distribution (equirectangular cells, row 0 = +y, no rotation).
struct DirPdf {
    d: vec3<f32>,
    pdf: f32,
}

fn cell_solid_angle(r: u32, cols: u32, rows: u32) -> f32 {
    let t0 = f32(r) / f32(rows) * PI;
    let t1 = f32(r + 1u) / f32(rows) * PI;
    return TAU / f32(cols) * (cos(t0) - cos(t1));
}

fn env_sample(u: vec2<f32>) -> DirPdf {
    let cols = u32(tables[P.env_cdf_base]);
    let rows = u32(tables[P.env_cdf_base + 1u]);
    let base = P.env_cdf_base + 2u;
    let c = dist_sample(base, cols, rows, u);
    let t0 = f32(c.row) / f32(rows) * PI;
    let t1 = f32(c.row + 1u) / f32(rows) * PI;
    let cos_t = clamp(cos(t0) + (cos(t1) - cos(t0)) * c.f.y, -1.0, 1.0);
    let sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    let phi = ((f32(c.col) + c.f.x) / f32(cols) - 0.5) * TAU;
    let d = vec3<f32>(sin_t * sin(phi), cos_t, -sin_t * cos(phi));
    return DirPdf(d, dist_prob(base, cols, rows, c.col, c.row) / cell_solid_angle(c.row, cols, rows));
}

fn env_pdf(d: vec3<f32>) -> f32 {
    if (P.env_cdf_base == NONE) {
        return 0.0;
    }
    let cols = u32(tables[P.env_cdf_base]);
    let rows = u32(tables[P.env_cdf_base + 1u]);
    let u = euclid(0.5 + atan2(d.x, -d.z) / TAU, 1.0);
    let v = acos(clamp(d.y, -1.0, 1.0)) / PI;
    let c = min(u32(u * f32(cols)), cols - 1u);
    let r = min(u32(v * f32(rows)), rows - 1u);
    return dist_prob(P.env_cdf_base + 2u, cols, rows, c, r) / cell_solid_angle(r, cols, rows);
}

// ------------------------------------------------------------------ area lights (render::area)

// Record (4 vec4): [centre, kind: 0 sphere, 1 disk, 2 rectangle], [normal, radius | width],
// [tangent, height], [radiance, visible to the camera].

struct AreaSample {
    wi: vec3<f32>,
    dist: f32,
    pdf: f32,
    ok: bool,
}

fn area_rec(k: u32, i: u32) -> vec4<f32> {
    return scene[P.area_base + 4u * k + i];
}

fn area_radiance(k: u32) -> vec3<f32> {
    return area_rec(k, 3u).xyz;
}

fn cone_one_minus_cos(r2: f32, d2: f32) -> f32 {
    let sin2 = min(r2 / d2, 1.0);
    return sin2 / (1.0 + sqrt(1.0 - sin2));
}

fn flat_area(k: u32) -> f32 {
    let a = area_rec(k, 0u);
    let b = area_rec(k, 1u);
    if (word(a.w) == 1u) {
        return PI * b.w * b.w;
    }
    return b.w * area_rec(k, 2u).w;
}

// Where a ray meets the emitting surface before t_max, or -1 (render::area::Shape::intersect).
fn area_t(k: u32, o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    let a = area_rec(k, 0u);
    let b = area_rec(k, 1u);
    let kind = word(a.w);
    if (kind == 0u) {
        let oc = o - a.xyz;
        let hb = dot(oc, d);
        let c = dot(oc, oc) - b.w * b.w;
        let disc = hb * hb - c;
        if (disc < 0.0 || c <= 0.0) {
            return -1.0;
        }
        let t = -hb - sqrt(disc);
        if (t > 0.0 && t < t_max) {
            return t;
        }
        return -1.0;
    }
    let n = b.xyz;
    let den = dot(d, n);
    if (den >= 0.0) {
        return -1.0;
    }
    let t = dot(a.xyz - o, n) / den;
    if (!(t > 0.0 && t < t_max)) {
        return -1.0;
    }
    let q = o + d * t - a.xyz;
    if (kind == 1u) {
        if (dot(q, q) <= b.w * b.w) {
            return t;
        }
        return -1.0;
    }
    let tg = area_rec(k, 2u);
    let bt = cross(n, tg.xyz);
    if (abs(dot(q, tg.xyz)) <= 0.5 * b.w && abs(dot(q, bt)) <= 0.5 * tg.w) {
        return t;
    }
    return -1.0;
}

struct LightHit {
    t: f32,
    k: u32,
}

// The nearest area light along a ray before t_max (camera rays see only the visible ones), but light `skip`.
fn hit_area_but(o: vec3<f32>, d: vec3<f32>, t_max: f32, camera: bool, skip: u32) -> LightHit {
    var best = LightHit(t_max, NONE);
    for (var k = 0u; k < P.n_area; k = k + 1u) {
        if ((camera && word(area_rec(k, 3u).w) == 0u) || k == skip) {
            continue;
        }
        let t = area_t(k, o, d, best.t);
        if (t > 0.0) {
            best = LightHit(t, k);
        }
    }
    return best;
}

fn hit_area(o: vec3<f32>, d: vec3<f32>, t_max: f32, camera: bool) -> LightHit {
    return hit_area_but(o, d, t_max, camera, NONE);
}

fn area_sample(k: u32, p: vec3<f32>, u: vec2<f32>) -> AreaSample {
    let a = area_rec(k, 0u);
    let b = area_rec(k, 1u);
    let kind = word(a.w);
    let none = AreaSample(vec3<f32>(0.0, 0.0, 1.0), 0.0, 0.0, false);
    if (kind == 0u) {
        let dc = a.xyz - p;
        let d2 = dot(dc, dc);
        if (d2 <= b.w * b.w) {
            return none;
        }
        let omc = cone_one_minus_cos(b.w * b.w, d2);
        let x = u.x * omc;
        let cos_t = 1.0 - x;
        let sin_t = sqrt(max(x * (2.0 - x), 0.0));
        let phi = TAU * u.y;
        let axis = dc / sqrt(d2);
        let f = frame_of(axis);
        let wi = normalize(f.t * (sin_t * cos(phi)) + f.b * (sin_t * sin(phi)) + axis * cos_t);
        let hb = dot(dc, wi);
        let dist = hb - sqrt(max(b.w * b.w - (d2 - hb * hb), 0.0));
        return AreaSample(wi, max(dist, 0.0), 1.0 / (TAU * omc), true);
    }
    let n = b.xyz;
    var q = a.xyz;
    if (kind == 1u) {
        let dd = concentric_disk(u) * b.w;
        let f = frame_of(n);
        q = q + f.t * dd.x + f.b * dd.y;
    } else {
        let tg = area_rec(k, 2u);
        q = q + tg.xyz * ((u.x - 0.5) * b.w) + cross(n, tg.xyz) * ((u.y - 0.5) * tg.w);
    }
    let v = q - p;
    let dist = length(v);
    if (dist <= 0.0) {
        return none;
    }
    let wi = v / dist;
    let cos_l = -dot(n, wi);
    if (cos_l <= 0.0) {
        return none;
    }
    return AreaSample(wi, dist, dist * dist / (cos_l * flat_area(k)), true);
}

fn area_pdf(k: u32, p: vec3<f32>, wi: vec3<f32>) -> f32 {
    let a = area_rec(k, 0u);
    let b = area_rec(k, 1u);
    if (word(a.w) == 0u) {
        let dc = a.xyz - p;
        let d2 = dot(dc, dc);
        if (d2 <= b.w * b.w) {
            return 0.0;
        }
        let omc = cone_one_minus_cos(b.w * b.w, d2);
        if (1.0 - dot(dc, wi) / sqrt(d2) > omc) {
            return 0.0;
        }
        return 1.0 / (TAU * omc);
    }
    let t = area_t(k, p, wi, FAR);
    if (t <= 0.0) {
        return 0.0;
    }
    return t * t / (-dot(b.xyz, wi) * flat_area(k));
}

// The light as one directional light from its centre (render::area::Shape::representative): e = L * factor,
// and the solid angle it subtends; e = 0 where p cannot see it.
struct Representative {
    wi: vec3<f32>,
    dist: f32,
    e: vec3<f32>,
    omega: f32,
}

fn area_representative(k: u32, p: vec3<f32>) -> Representative {
    let a = area_rec(k, 0u);
    let b = area_rec(k, 1u);
    let none = Representative(vec3<f32>(0.0, 0.0, 1.0), 0.0, vec3<f32>(0.0), 0.0);
    let v = a.xyz - p;
    let d2 = dot(v, v);
    let d = sqrt(d2);
    if (word(a.w) == 0u) {
        if (d2 <= b.w * b.w) {
            return none;
        }
        let omc = cone_one_minus_cos(b.w * b.w, d2);
        return Representative(v / d, d - b.w, area_radiance(k) * (b.w * b.w / d2), TAU * omc);
    }
    if (d <= 0.0) {
        return none;
    }
    let wi = v / d;
    let cos_l = -dot(b.xyz, wi);
    if (cos_l <= 0.0) {
        return none;
    }
    let area = flat_area(k);
    let e = area * cos_l / (d2 + area / PI) / PI;
    return Representative(wi, d, area_radiance(k) * e, min(area * cos_l / d2, TAU));
}

// ------------------------------------------------------------------ the diffraction lobe (render::lobe)

const LOBE_LEVELS: u32 = 8u;

// Grid value of node i (iridis_diffraction::table::grid_value).
fn grid_value(t: Table, i: u32) -> f32 {
    let s = -1.0 + 2.0 * f32(i) / f32(t.res - 1u);
    return 2.0 * sign(s) * pow(abs(s), 1.0 / t.inv_power);
}

fn lobe_block(t: Table) -> u32 {
    let n = t.res - 1u;
    return (n + 1u) + n * (n + 1u) + n * n;
}

fn lobe_level(cos_o: f32) -> u32 {
    return min(u32(clamp(cos_o, 0.0, 1.0) * f32(LOBE_LEVELS)), LOBE_LEVELS - 1u);
}

struct LocalPdf {
    li: vec3<f32>,
    pdf: f32,
    ok: bool,
}

fn lobe_sample(t: Table, lobe: u32, lo: vec3<f32>, u: vec2<f32>) -> LocalPdf {
    let n = t.res - 1u;
    let base = lobe + lobe_level(lo.z) * lobe_block(t);
    let none = LocalPdf(vec3<f32>(0.0, 0.0, 1.0), 0.0, false);
    if (tables[base + n] < 0.5) {
        return none;
    }
    let c = dist_sample(base, n, n, u);
    let u0 = grid_value(t, c.col);
    let u1 = grid_value(t, c.col + 1u);
    let v0 = grid_value(t, c.row);
    let v1 = grid_value(t, c.row + 1u);
    let uu = u0 + c.f.x * (u1 - u0);
    let vv = v0 + c.f.y * (v1 - v0);
    let x = -uu - lo.x;
    let y = -vv - lo.y;
    let s2 = x * x + y * y;
    if (s2 >= 1.0) {
        return none;
    }
    let z = sqrt(1.0 - s2);
    let p = dist_prob(base, n, n, c.col, c.row) / ((u1 - u0) * (v1 - v0)) * z;
    return LocalPdf(vec3<f32>(x, y, z), p, true);
}

fn lobe_cell(t: Table, x: f32) -> u32 {
    return min(u32(floor(grid_index(t, x))), t.res - 2u);
}

fn lobe_pdf(t: Table, lobe: u32, lo: vec3<f32>, li: vec3<f32>) -> f32 {
    let n = t.res - 1u;
    let base = lobe + lobe_level(lo.z) * lobe_block(t);
    if (li.z <= 0.0 || tables[base + n] < 0.5) {
        return 0.0;
    }
    let u = -li.x - lo.x;
    let v = -li.y - lo.y;
    if (abs(u) > 2.0 || abs(v) > 2.0) {
        return 0.0;
    }
    let iu = lobe_cell(t, u);
    let iv = lobe_cell(t, v);
    let area = (grid_value(t, iu + 1u) - grid_value(t, iu)) * (grid_value(t, iv + 1u) - grid_value(t, iv));
    return dist_prob(base, n, n, iu, iv) / area * li.z;
}

// I_p of the three channels at `node` (the offset of a grid node's `3 np` numbers) of an array in `tables`.
fn node3(base: u32, node: u32, np: u32, p: u32) -> vec3<f32> {
    let q = base + node + p;
    return vec3<f32>(tables[q], tables[q + np], tables[q + 2u * np]);
}

// The grid cell holding x (clamped to the grid) and the linear fraction inside it (render::lobe::locate).
struct Located {
    i: u32,
    f: f32,
    a: f32,
    b: f32,
}

fn locate(t: Table, x_in: f32) -> Located {
    let x = clamp(x_in, -2.0, 2.0);
    let i = lobe_cell(t, x);
    let a = grid_value(t, i);
    let b = grid_value(t, i + 1u);
    return Located(i, clamp((x - a) / (b - a), 0.0, 1.0), a, b);
}

// The integral from the grid's origin to (u, v) of the power p of the three channels, exact for the bilinear
// interpolant (render::lobe::Prefiltered::accumulate): the prefix tables F, C, R (at pref, pref + size,
// pref + 2 size) and the table's own nodes at the cell's corners.
struct Corner {
    n00: u32,
    n10: u32,
    n01: u32,
    n11: u32,
    wc: vec2<f32>,  // weights of C at (i, j), (i + 1, j)
    wr: vec2<f32>,  // weights of R at (i, j), (i, j + 1)
    wt: vec4<f32>,  // weights of the table at (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)
}

fn corner(t: Table, u: f32, v: f32) -> Corner {
    let row = t.res * 3u * t.np;
    let lu = locate(t, u);
    let lv = locate(t, v);
    let du = lu.b - lu.a;
    let dv = lv.b - lv.a;
    let a = vec2<f32>(lu.f - 0.5 * lu.f * lu.f, 0.5 * lu.f * lu.f);
    let b = vec2<f32>(lv.f - 0.5 * lv.f * lv.f, 0.5 * lv.f * lv.f);
    let n00 = lv.i * row + lu.i * 3u * t.np;
    let wt = du * dv * vec4<f32>(a.x * b.x, a.y * b.x, a.x * b.y, a.y * b.y);
    return Corner(n00, n00 + 3u * t.np, n00 + row, n00 + row + 3u * t.np, du * a, dv * b, wt);
}

fn corner_power(t: Table, pref: u32, c: Corner, p: u32) -> vec3<f32> {
    let np = t.np;
    let size = t.res * t.res * 3u * np;
    let cc = pref + size;
    let rr = pref + 2u * size;
    return node3(pref, c.n00, np, p) + c.wc.x * node3(cc, c.n00, np, p) + c.wc.y * node3(cc, c.n10, np, p)
        + c.wr.x * node3(rr, c.n00, np, p) + c.wr.y * node3(rr, c.n01, np, p)
        + c.wt.x * node3(t.base, c.n00, np, p) + c.wt.y * node3(t.base, c.n10, np, p)
        + c.wt.z * node3(t.base, c.n01, np, p) + c.wt.w * node3(t.base, c.n11, np, p);
}

// The integral of sum_p w^p I_p over [u0, u1] x [v0, v1] per channel (render::lobe::Prefiltered::integral):
// the four corners' prefix integrals combined per power, then Horner's rule in w. One loop over the powers:
// lavapipe (llvmpipe) ends every loop after 65535 iterations in all, counted across the loops nested in
// the shader's outermost one, so that a camera sample whose lights run more silently loses them (the
// environment's 64 lights times a loop per channel, corner and term did).
fn prefiltered_box(t: Table, pref: u32, u0: f32, u1: f32, v0: f32, v1: f32, w: f32) -> vec3<f32> {
    let c11 = corner(t, u1, v1);
    let c01 = corner(t, u0, v1);
    let c10 = corner(t, u1, v0);
    let c00 = corner(t, u0, v0);
    var acc = vec3<f32>(0.0);
    for (var k = 0u; k < t.np; k = k + 1u) {
        let p = t.np - 1u - k;
        let s = corner_power(t, pref, c11, p) - corner_power(t, pref, c01, p) - corner_power(t, pref, c10, p)
            + corner_power(t, pref, c00, p);
        acc = acc * w + s;
    }
    return acc;
}

// The lobe averaged over a light of solid angle omega around li (render::lobe::Prefiltered::mean), XYZ
// without the shading factor: 2 x 2 Gauss points of the lookup for a square narrower than the grid's cell,
// the prefix tables otherwise.
fn prefiltered_sum(t: Table, pref: u32, li: vec3<f32>, lo: vec3<f32>, omega: f32) -> vec3<f32> {
    let u = -li.x - lo.x;
    let v = -li.y - lo.y;
    let w = -li.z - lo.z;
    let half = 0.5 * sqrt(omega * max(li.z, 0.0));
    let cu = locate(t, u);
    let cv = locate(t, v);
    if (half > 0.0 && 2.0 * half >= min(cu.b - cu.a, cv.b - cv.a)) {
        return prefiltered_box(t, pref, u - half, u + half, v - half, v + half, w) / (4.0 * half * half);
    }
    let g = half / sqrt(3.0);
    var out = vec3<f32>(0.0);
    for (var k = 0u; k < 4u; k = k + 1u) {
        let su = select(-g, g, (k & 1u) != 0u);
        let sv = select(-g, g, (k & 2u) != 0u);
        out = out + 0.25 * table_sum(t, u + su, v + sv, w);
    }
    return out;
}

// ------------------------------------------------------------------ surfaces (render::integrate::Surface)

struct Surf {
    kind: u32,            // 0 Lambert, 1 microfacet, 2 film over a base, 3 diffraction, 4 rough film's diffuse
    n: vec3<f32>,
    albedo: vec3<f32>,
    m: Microfacet,        // the microfacet, or the film's base
    p_spec: f32,          // probability of sampling the GGX lobe (else the cosine lobe)
    film: Film,
    offset: f32,
    factor: f32,
    table: Table,
    dk: vec4<f32>,        // diffraction: [scale_ru, w_diffuse, ambient, fresnel_n]
    t: vec3<f32>,         // diffraction: the nanostructure's frame t, n x t
    b: vec3<f32>,
    tex: vec3<f32>,
    lobe: u32,            // the lobe's distributions in `tables`, NONE: none
    albedo_table: u32,    // the energy blend's albedo table in `tables`, NONE: Algorithm 4
    metal: u32,           // a film over a metallic base: the metal stack's media block, NONE: none
    rough: u32,           // a rough film: its material record (rough_tab)
    // The fast path's extras (shade_fast): a diffraction's prefiltered tables (NONE: none); a film's colour table
    // (when `tabbed`) and its reflectance at the view, r_view (linear sRGB).
    pref: u32,
    tabbed: bool,
    tab: FilmTab,
    r_view: vec3<f32>,
}

const DIFFRACTION_LOBE_PROBABILITY: f32 = 0.75;

fn spec_probability(spec: vec3<f32>, diffuse: vec3<f32>) -> f32 {
    let s = max3(spec);
    let d = max3(diffuse);
    if (s + d <= 0.0) {
        return 0.5;
    }
    return clamp(s / (s + d), 0.1, 0.9);
}

fn no_film() -> Film {
    return Film(0u, 0u, 0u, 0u);
}

fn no_table() -> Table {
    return Table(2u, 1u, 0u, 0u, 1.0, 1.0, 1.0, 0.0);
}

fn surf_basic(kind: u32, n: vec3<f32>, albedo: vec3<f32>, m: Microfacet, p_spec: f32) -> Surf {
    return Surf(kind, n, albedo, m, p_spec, no_film(), 0.0, 1.0, no_table(), vec4<f32>(0.0), vec3<f32>(0.0),
                vec3<f32>(0.0), vec3<f32>(0.0), NONE, NONE, NONE, NONE, NONE, false, FilmTab(0u, 0u, 0u, 0.0, 0.0),
                vec3<f32>(0.0));
}

fn surf_lambert(n: vec3<f32>, albedo: vec3<f32>) -> Surf {
    return surf_basic(0u, n, albedo, Microfacet(vec4<f32>(0.0), 1.0, 0.0, 1.0), 0.0);
}

fn surf_microfacet(m: Microfacet, n: vec3<f32>, albedo: vec3<f32>, cos_o: f32) -> Surf {
    let ew = env_weights(m, cos_o, albedo);
    return surf_basic(1u, n, albedo, m, spec_probability(ew.spec, ew.diffuse));
}

fn surf_film(film: Film, base: Microfacet, n: vec3<f32>, albedo: vec3<f32>, offset: f32, factor: f32,
             r_view: vec3<f32>, metal: u32) -> Surf {
    let diffuse = (vec3<f32>(1.0) - r_view) * albedo * (1.0 - base.metallic);
    var s = surf_basic(2u, n, albedo, base, spec_probability(max(r_view, vec3<f32>(base.metallic)), diffuse));
    s.film = film;
    s.offset = offset;
    s.factor = factor;
    s.metal = metal;
    s.r_view = r_view;
    return s;
}

// pi f cos(theta_i) of the film over its base for light from wi (render::material::ThinFilm::over_base_light),
// without the factor: the GGX lobe carries the film's reflectance over the dielectric and, for a metallic base,
// over the metal (the metal stack `metal`), mixed by the base's metallic; the diffuse takes what the film over
// the dielectric lets through.
fn film_base_light(film: Film, base: Microfacet, albedo: vec3<f32>, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>,
                   offset: f32, metal: u32) -> vec3<f32> {
    let ci = dot(n, wi);
    if (ci <= 0.0 || dot(n, wo) <= 0.0) {
        return vec3<f32>(0.0);
    }
    let vh = clamp(dot(wi, safe_normalize(wi + wo)), 0.0, 1.0);
    let sin_h = sqrt(max(1.0 - vh * vh, 0.0));
    let rl = to_rgb(film_xyz(film, sin_h, vh, offset).r);
    let spec = film_specular(film, metal, base.metallic, sin_h, vh, offset, rl);
    let diffuse = albedo * (1.0 - base.metallic);
    return ggx_single(base, n, wi, wo) * spec + (vec3<f32>(1.0) - rl) * diffuse * ci;
}

fn surf_eval(s: Surf, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    if (s.kind == 0u) {
        return s.albedo * max(dot(s.n, wi), 0.0);
    }
    if (s.kind == 1u) {
        return microfacet_reflect(s.m, s.n, wi, wo, s.albedo);
    }
    if (s.kind == 2u) {
        var out = film_base_light(s.film, s.m, s.albedo, s.n, wi, wo, s.offset, s.metal) * s.factor;
        if (s.factor < 1.0) {
            out = out + microfacet_reflect(s.m, s.n, wi, wo, s.albedo) * (1.0 - s.factor);
        }
        return out;
    }
    if (s.kind == 4u) {
        // pi k_d cos theta_l of the rough film (render::integrate::Surface::RoughDiffuse), times its factor.
        let cl = dot(s.n, wi);
        let co = dot(s.n, wo);
        if (cl <= 0.0 || co <= 0.0) {
            return vec3<f32>(0.0);
        }
        let d = rough_diffuse(rough_tab(s.rough), co, cl, relative_azimuth(s.n, wi, wo), s.offset);
        return to_rgb(d) * (cl * s.factor);
    }
    let lo = vec3<f32>(dot(wo, s.t), dot(wo, s.b), dot(wo, s.n));
    return diffraction_light(s.table, s.dk, s.tex, s.t, s.b, s.n, lo, wi, wo, vec3<f32>(1.0), 0.0, NONE,
                             s.albedo_table, false);
}

struct SurfSample {
    wi: vec3<f32>,
    ok: bool,
}

fn surf_sample(s: Surf, wo: vec3<f32>, u: vec3<f32>) -> SurfSample {
    let n = s.n;
    let cosine = SurfSample(cosine_hemisphere(n, u.yz), true);
    let none = SurfSample(n, false);
    if (s.kind == 1u || s.kind == 2u) {
        if (u.x >= s.p_spec) {
            return cosine;
        }
        let f = frame_of(n);
        let lo = vec3<f32>(dot(wo, f.t), dot(wo, f.b), dot(wo, n));
        if (lo.z <= 0.0) {
            return none;
        }
        let alpha = max(s.m.roughness * s.m.roughness, 1e-4);
        let h = ggx_visible_normal(lo, alpha, u.yz);
        let li = h * (2.0 * dot(lo, h)) - lo;
        if (li.z <= 0.0) {
            return none;
        }
        return SurfSample(normalize(f.t * li.x + f.b * li.y + n * li.z), true);
    }
    if (s.kind == 3u && s.lobe != NONE && u.x < DIFFRACTION_LOBE_PROBABILITY) {
        let lo = vec3<f32>(dot(wo, s.t), dot(wo, s.b), dot(wo, n));
        let x = lobe_sample(s.table, s.lobe, lo, u.yz);
        if (!x.ok) {
            return none;
        }
        return SurfSample(normalize(s.t * x.li.x + s.b * x.li.y + n * x.li.z), true);
    }
    return cosine;
}

fn surf_pdf(s: Surf, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let n = s.n;
    let ci = dot(n, wi);
    if (ci <= 0.0) {
        return 0.0;
    }
    let cosine = ci / PI;
    if (s.kind == 1u || s.kind == 2u) {
        let co = dot(n, wo);
        if (co <= 0.0) {
            return (1.0 - s.p_spec) * cosine;
        }
        let a = max(s.m.roughness * s.m.roughness, 1e-4);
        let a2 = a * a;
        let nh = max(dot(n, safe_normalize(wi + wo)), 0.0);
        let q = nh * nh * (a2 - 1.0) + 1.0;
        let dd = a2 / (PI * q * q);
        let g1 = 2.0 * co / (co + sqrt(a2 + (1.0 - a2) * co * co));
        return s.p_spec * g1 * dd / (4.0 * co) + (1.0 - s.p_spec) * cosine;
    }
    if (s.kind == 3u && s.lobe != NONE) {
        let lo = vec3<f32>(dot(wo, s.t), dot(wo, s.b), dot(wo, n));
        let li = vec3<f32>(dot(wi, s.t), dot(wi, s.b), ci);
        let p = DIFFRACTION_LOBE_PROBABILITY;
        return p * lobe_pdf(s.table, s.lobe, lo, li) + (1.0 - p) * cosine;
    }
    return cosine;
}

// ------------------------------------------------------------------ the Monte Carlo integrator

// Weight of a light sample whose pdf is `light` where the BRDF's is `brdf`, and the other way round (MIS).
fn brdf_weight(brdf: f32, light: f32) -> f32 {
    if (brdf <= 0.0) {
        return 1.0;  // a mirror's ray: its light is not sampled otherwise
    }
    return power_heuristic(brdf, light);
}

// Every light at a hit whose surface is s, by Monte Carlo (render::integrate::Scene::extended_light, with the
// directional and point lights): one pass over the techniques -- each delta light, one sample of each area
// light, one of the environment, then the BRDF's sample, queued as a ray -- so that the compiler emits the
// surface's evaluation once. `ambient` is added as it is (Algorithm 4's ambient term).
fn shade_mc(h: Hit, s: Surf, wo: vec3<f32>, depth: u32, weight: f32, thr: vec3<f32>, ambient: vec3<f32>) {
    let o = h.p + h.ng * eps(h.p, h.t);
    var out = ambient;
    let n_env = select(0u, 1u, P.env_cdf_base != NONE);
    let n_tech = P.n_lights + P.n_area + n_env + 1u;
    for (var i = 0u; i < n_tech; i = i + 1u) {
        var wi = vec3<f32>(0.0, 0.0, 1.0);
        var dist = FAR;
        var le = vec3<f32>(0.0);
        var p_light = 0.0;
        var skip_light = NONE;
        let brdf = i + 1u == n_tech;
        if (i < P.n_lights) {
            let l = arrive(i, h.p);
            wi = l.wi;
            dist = l.dist;
            le = l.e;
        } else if (i < P.n_lights + P.n_area) {
            let k = i - P.n_lights;
            let x = area_sample(k, h.p, rand2());
            if (!x.ok) {
                continue;
            }
            wi = x.wi;
            dist = x.dist * (1.0 - 1e-5);
            le = area_radiance(k);
            p_light = x.pdf;
            skip_light = k;
        } else if (!brdf) {
            let e = env_sample(rand2());
            wi = e.d;
            le = environment(e.d);
            p_light = e.pdf;
        } else {
            let smp = surf_sample(s, wo, vec3<f32>(rand(), rand(), rand()));
            if (!smp.ok) {
                continue;
            }
            wi = smp.wi;
        }
        if (dot(wi, h.ng) <= 0.0) {
            continue;
        }
        let f = surf_eval(s, wi, wo);
        if (max3(f) <= 0.0) {
            continue;
        }
        let delta = i < P.n_lights;
        var p_brdf = 0.0;
        if (!delta) {
            p_brdf = surf_pdf(s, wi, wo);
        }
        if (brdf) {
            if (p_brdf > 0.0) {
                let tp = f / (PI * p_brdf);
                push_sampled(o, wi, thr * tp, depth + 1u, weight * max3(tp), p_brdf);
            }
            continue;
        }
        // One shadow test for the delta lights' and the sampled lights' segments alike, so that the compiled shader
        // holds one copy of the scene's traversal here; a sampled segment is also blocked by an area light other
        // than the one it goes to (render::integrate::Scene::blocked).
        if (!delta && (!(p_light > 0.0) || hit_area_but(o, wi, dist, false, skip_light).k != NONE)) {
            continue;
        }
        if (occluded(o, wi, dist)) {
            continue;
        }
        if (delta) {
            out = out + f * le;
        } else {
            out = out + f * le * (power_heuristic(p_light, p_brdf) / (PI * p_light));
        }
    }
    radiance = radiance + thr * out;
}
