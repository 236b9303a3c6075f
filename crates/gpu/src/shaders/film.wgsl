// Sussenbach's thin-film shader (ch. 4; the smooth model of section 3.1 after Hirayama et al.): per pixel
// and per wavelength sample, the complex cosines of Snell's law (eq. 3.6), the Fresnel amplitudes of every
// interface (eq. 3.7-3.10), the composite recurrence from the substrate up (eq. 3.3-3.4 seed, eq. 3.1-3.2
// steps), R and T (eq. 3.12-3.13), and XYZ = sum_l w(l) R(l) -- the numbers of
// iridis_thinfilm::Stack::evaluate_offset and FilmColorimeter, in f32.
// Thickness per pixel: every layer's thickness plus an offset (eq. 4.3), the offset a vertical gradient plus
// d_rel (2 alpha - 1) from a grey texture alpha (eq. 4.4, spatially varying thickness); the incidence angle
// varies along x.

struct FilmParams {
    width: u32,
    height: u32,
    n_media: u32,       // N + 2: incident, N layers, substrate
    n_lambda: u32,
    angle0: f32,        // incidence angle (rad) of column 0
    angle1: f32,        // of the last column
    offset_top: f32,    // thickness offset (nm) of row 0
    offset_bottom: f32, // of the last row
    d_rel: f32,         // SVT amplitude (nm)
    flags: u32,         // bit 0: SVT texture; bit 1: display
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(0) var<uniform> P: FilmParams;
@group(0) @binding(1) var<uniform> D: Display;
// Complex index of medium j at wavelength sample l: media[l * n_media + j].
@group(0) @binding(2) var<storage, read> media: array<vec2<f32>>;
// Layer thicknesses (nm), top first.
@group(0) @binding(3) var<storage, read> thickness: array<f32>;
// Per wavelength sample: the XYZ integration weights (xyz) and the wavenumber 2 pi / lambda (w, 1/nm).
@group(0) @binding(4) var<storage, read> weights: array<vec4<f32>>;
// SVT grey values alpha in [0, 1], row-major (one element when unused).
@group(0) @binding(5) var<storage, read> alpha: array<f32>;
// Two vec4 per pixel: reflected XYZ, transmitted XYZ.
@group(0) @binding(6) var<storage, read_write> out_xyz: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> out_rgba: array<u32>;

// Eq. 3.6 on the forward branch: Im(n s_z) > 0, or Re(n s_z) > 0 when the imaginary part vanishes.
fn cosine(s: f32, n: vec2<f32>) -> vec2<f32> {
    let sx = cdiv(vec2<f32>(s, 0.0), n);
    let c = csqrt(vec2<f32>(1.0, 0.0) - cmul(sx, sx));
    let q = cmul(n, c);
    var forward = q.x > 0.0;
    if (abs(q.y) > 100.0 * 1.1920929e-7 * max(length(q), 1.0)) {
        forward = q.y > 0.0;
    }
    if (forward || (q.x == 0.0 && q.y == 0.0)) {
        return c;
    }
    return -c;
}

struct Fr {
    rs: vec2<f32>,
    rp: vec2<f32>,
    ts: vec2<f32>,
    tp: vec2<f32>,
}

// Eq. 3.7-3.10 at the interface from medium (ni, ci) above into (nt, ct) below.
fn fresnel(ni: vec2<f32>, ci: vec2<f32>, nt: vec2<f32>, ct: vec2<f32>) -> Fr {
    let a = cmul(ni, ci);
    let b = cmul(nt, ct);
    let c = cmul(nt, ci);
    let d = cmul(ni, ct);
    let ds = cdiv(vec2<f32>(1.0, 0.0), a + b);
    let dp = cdiv(vec2<f32>(1.0, 0.0), c + d);
    return Fr(cmul(a - b, ds), cmul(c - d, dp), cmul(2.0 * a, ds), cmul(2.0 * a, dp));
}

struct Comp {
    gs: vec2<f32>,
    gp: vec2<f32>,
    ts: vec2<f32>,
    tp: vec2<f32>,
}

// Eq. 3.1-3.2 for one polarisation: g' = (r + g e2) / (1 + r g e2), t' = t tau e1 / (1 + r g e2).
fn recur_g(r: vec2<f32>, g: vec2<f32>, e2: vec2<f32>) -> vec4<f32> {
    let ge = cmul(g, e2);
    let inv = cdiv(vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 0.0) + cmul(r, ge));
    return vec4<f32>(cmul(r + ge, inv), inv);
}

fn step(c: Comp, f: Fr, phi: vec2<f32>) -> Comp {
    // e^{i phi} with Im phi >= 0 on the forward branch; the real part reduced to [-pi, pi] first.
    let tau = 6.283185307179586;
    let re = phi.x - tau * round(phi.x / tau);
    let e1 = exp(-phi.y) * vec2<f32>(cos(re), sin(re));
    let e2 = cmul(e1, e1);
    let s = recur_g(f.rs, c.gs, e2);
    let p = recur_g(f.rp, c.gp, e2);
    return Comp(s.xy, p.xy, cmul(cmul(f.ts, c.ts), cmul(e1, s.zw)), cmul(cmul(f.tp, c.tp), cmul(e1, p.zw)));
}

@compute @workgroup_size(8, 8, 1)
fn film_frame(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= P.width || id.y >= P.height) {
        return;
    }
    let idx = id.y * P.width + id.x;
    let fx = f32(id.x) / f32(max(P.width, 2u) - 1u);
    let fy = f32(id.y) / f32(max(P.height, 2u) - 1u);
    let theta = P.angle0 + (P.angle1 - P.angle0) * fx;
    var offset = P.offset_top + (P.offset_bottom - P.offset_top) * fy;
    if ((P.flags & 1u) != 0u) {
        offset = offset + P.d_rel * (alpha[idx] / 0.5 - 1.0);
    }
    let sin_t = sin(theta);
    let cos_t = max(cos(theta), 0.0);
    let m = P.n_media;
    let last = m - 1u;
    var xyz_r = vec3<f32>(0.0);
    var xyz_t = vec3<f32>(0.0);
    for (var l = 0u; l < P.n_lambda; l = l + 1u) {
        let wt = weights[l];
        let k = wt.w;
        let base = l * m;
        let n0 = media[base];
        let s = n0.x * sin_t;
        let c0 = vec2<f32>(cos_t, 0.0);
        let n_sub = media[base + last];
        let c_sub = cosine(s, n_sub);
        // Seed (eq. 3.3-3.4): the bottom interface, between medium last - 1 and the substrate.
        var j = last - 1u;
        var n_up = media[base + j];
        var c_up = c0;
        if (j > 0u) {
            c_up = cosine(s, n_up);
        }
        let fb = fresnel(n_up, c_up, n_sub, c_sub);
        var comp = Comp(fb.rs, fb.rp, fb.ts, fb.tp);
        // Layers from the bottom up: layer j (medium j) lies under interface B_j.
        while (j > 0u) {
            let n_layer = n_up;
            let c_layer = c_up;
            let d = max(thickness[j - 1u] + offset, 0.0);
            let phi = (k * d) * cmul(n_layer, c_layer);
            n_up = media[base + j - 1u];
            c_up = c0;
            if (j > 1u) {
                c_up = cosine(s, n_up);
            }
            comp = step(comp, fresnel(n_up, c_up, n_layer, c_layer), phi);
            j = j - 1u;
        }
        let r = 0.5 * (dot(comp.gs, comp.gs) + dot(comp.gp, comp.gp));
        // Eq. 3.13: Re(n_sub s_z,sub) / (n0 cos theta); nothing through an absorbing or evanescent substrate.
        var tf = 0.0;
        let num = cmul(n_sub, c_sub).x;
        let den = n0.x * cos_t;
        if (n_sub.y <= 0.0 && num > 0.0 && den > 0.0) {
            tf = num / den;
        }
        let t = tf * 0.5 * (dot(comp.ts, comp.ts) + dot(comp.tp, comp.tp));
        xyz_r = xyz_r + r * wt.xyz;
        xyz_t = xyz_t + t * wt.xyz;
    }
    out_xyz[2u * idx] = vec4<f32>(xyz_r, 0.0);
    out_xyz[2u * idx + 1u] = vec4<f32>(xyz_t, 0.0);
    if ((P.flags & 2u) != 0u) {
        out_rgba[idx] = display_pixel(xyz_r, D);
    }
}
