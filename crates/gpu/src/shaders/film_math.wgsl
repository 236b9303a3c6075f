// Sussenbach's thin-film model (ch. 3-4; the smooth model of section 3.1 after Hirayama et al.): per wavelength
// sample the complex cosines of Snell's law (eq. 3.6), the Fresnel amplitudes of every interface
// (eq. 3.7-3.10), the composite recurrence from the substrate up (eq. 3.3-3.4 seed, eq. 3.1-3.2 steps), R and
// T (eq. 3.12-3.13), and XYZ = sum_l w(l) R(l) -- the numbers of iridis_thinfilm::Stack::evaluate_offset and
// FilmColorimeter, in f32. Shared by the film-frame shader (film.wgsl) and the scene renderer (scene.wgsl);
// each defines where the stack lives:
//
//   fn film_medium(f: Film, l: u32, j: u32) -> vec2<f32>   complex index of medium j (0 = incident) at sample l
//   fn film_thickness(f: Film, j: u32) -> f32              thickness (nm) of layer j (0 = top)
//   fn film_weight(l: u32) -> vec4<f32>                    XYZ weights of sample l and its wavenumber 2 pi / l

struct Film {
    n_media: u32,   // N + 2: incident, N layers, substrate
    n_lambda: u32,  // wavelength samples
    media: u32,     // where the stack's indices start (used by film_medium)
    thickness: u32, // where its thicknesses start (used by film_thickness)
}

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
fn film_fresnel(ni: vec2<f32>, ci: vec2<f32>, nt: vec2<f32>, ct: vec2<f32>) -> Fr {
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

fn film_step(c: Comp, f: Fr, phi: vec2<f32>) -> Comp {
    // e^{i phi} with Im phi >= 0 on the forward branch; the real part reduced to [-pi, pi] first.
    let tau = 6.283185307179586;
    let re = phi.x - tau * round(phi.x / tau);
    let e1 = exp(-phi.y) * vec2<f32>(cos(re), sin(re));
    let e2 = cmul(e1, e1);
    let s = recur_g(f.rs, c.gs, e2);
    let p = recur_g(f.rp, c.gp, e2);
    return Comp(s.xy, p.xy, cmul(cmul(f.ts, c.ts), cmul(e1, s.zw)), cmul(cmul(f.tp, c.tp), cmul(e1, p.zw)));
}

struct FilmXyz {
    r: vec3<f32>,
    t: vec3<f32>,
}

// Reflected and transmitted XYZ (unpolarised) at incidence angle theta (sin_t, cos_t), every layer's thickness
// plus offset (nm, clamped at 0; eq. 4.3).
fn film_xyz(f: Film, sin_t: f32, cos_t_in: f32, offset: f32) -> FilmXyz {
    let cos_t = max(cos_t_in, 0.0);
    let last = f.n_media - 1u;
    var xyz_r = vec3<f32>(0.0);
    var xyz_t = vec3<f32>(0.0);
    for (var l = 0u; l < f.n_lambda; l = l + 1u) {
        let wt = film_weight(l);
        let k = wt.w;
        let n0 = film_medium(f, l, 0u);
        let s = n0.x * sin_t;
        let c0 = vec2<f32>(cos_t, 0.0);
        let n_sub = film_medium(f, l, last);
        let c_sub = cosine(s, n_sub);
        // Seed (eq. 3.3-3.4): the bottom interface, between medium last - 1 and the substrate.
        var j = last - 1u;
        var n_up = film_medium(f, l, j);
        var c_up = c0;
        if (j > 0u) {
            c_up = cosine(s, n_up);
        }
        let fb = film_fresnel(n_up, c_up, n_sub, c_sub);
        var comp = Comp(fb.rs, fb.rp, fb.ts, fb.tp);
        // Layers from the bottom up: layer j (medium j) lies under interface B_j.
        while (j > 0u) {
            let n_layer = n_up;
            let c_layer = c_up;
            let d = max(film_thickness(f, j - 1u) + offset, 0.0);
            let phi = (k * d) * cmul(n_layer, c_layer);
            n_up = film_medium(f, l, j - 1u);
            c_up = c0;
            if (j > 1u) {
                c_up = cosine(s, n_up);
            }
            comp = film_step(comp, film_fresnel(n_up, c_up, n_layer, c_layer), phi);
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
    return FilmXyz(xyz_r, xyz_t);
}

// A colour table (iridis_thinfilm::table::FilmTable): reflected and transmitted XYZ over cos theta (nc nodes,
// uniform on [0, 1]) x thickness offset (no nodes, uniform on [o0, o1]); node (i, j) is the two vec4 at
// base + 2 (j nc + i). Where it lives is the shader's hook:
//
//   fn film_table_node(k: u32) -> vec4<f32>
struct FilmTab {
    base: u32,
    nc: u32,
    no: u32,
    o0: f32,
    o1: f32,
}

// Bilinear in (cos theta, offset), both clamped to the table (TableGrid::locate).
fn film_table_xyz(t: FilmTab, cos_t: f32, offset: f32) -> FilmXyz {
    let x = clamp(cos_t, 0.0, 1.0) * f32(t.nc - 1u);
    let i = min(u32(x), t.nc - 2u);
    let fi = x - f32(i);
    var j = 0u;
    var j1 = 0u;
    var fj = 0.0;
    if (t.no > 1u) {
        let y = clamp((offset - t.o0) / (t.o1 - t.o0), 0.0, 1.0) * f32(t.no - 1u);
        j = min(u32(y), t.no - 2u);
        fj = y - f32(j);
        j1 = j + 1u;
    }
    let a = t.base + 2u * (j * t.nc + i);
    let b = t.base + 2u * (j1 * t.nc + i);
    let r = mix(mix(film_table_node(a), film_table_node(a + 2u), fi),
                mix(film_table_node(b), film_table_node(b + 2u), fi), fj);
    let tr = mix(mix(film_table_node(a + 1u), film_table_node(a + 3u), fi),
                 mix(film_table_node(b + 1u), film_table_node(b + 3u), fi), fj);
    return FilmXyz(r.xyz, tr.xyz);
}
