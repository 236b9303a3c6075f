// The lookup diffraction model (Dhillon et al. 2014, eq. 10-12 and sec. 5; Single 2014, Algorithm 3):
// X = C(wi, wr) * sum_p w^p I_p(u, v) per channel X, Y, Z, with (u, v, w) = -wi - wr, the tables I_p on the
// non-linear grid u_i = 2 sign(s_i) |s_i|^a, bilinear interpolation in the grid's index space and Horner's rule
// in w -- the numbers of iridis_diffraction::Lookup (Precision::F32). Shared by the BRDF-map shader
// (lookup.wgsl) and the scene renderer (scene.wgsl); each defines where the numbers live:
//
//   fn table_value(t: Table, iv: u32, dv: u32, off: u32) -> f32
//
// returns I at grid row iv + dv (iv: the lower row of the cell being interpolated, dv: 0 or 1) and offset
// off = (iu * 3 + c) * np + p within that row, the layout of the table file.

struct Table {
    res: u32,        // samples per axis
    np: u32,         // powers per channel, 2N + 1
    flags: u32,      // bit 0: Cook-Torrance shadowing; bit 1: exact Fresnel of a complex index; bit 3: paper's R^2
    base: u32,       // where the table starts in its buffer (used by table_value)
    inv_power: f32,  // 1 / a of the non-linear grid
    f0: f32,         // Fresnel reflectance at normal incidence
    n_re: f32,       // Schlick: n; exact: Re n
    n_im: f32,       // exact: Im n
}

// Continuous index of u in [-2, 2] on the grid (iridis_diffraction::table::grid_index).
fn grid_index(t: Table, u: f32) -> f32 {
    var s = 0.0;
    if (u != 0.0) {
        s = sign(u) * pow(min(abs(u) * 0.5, 1.0), t.inv_power);
    }
    return max((s + 1.0) * 0.5 * f32(t.res - 1u), 0.0);
}

// The grid cell holding (u, v): its lower nodes (iu, iv) and the bilinear weights of its nodes in the grid's
// index space, w = (w00, w01, w10, w11) for (iu, iv), (iu + 1, iv), (iu, iv + 1), (iu + 1, iv + 1).
struct GridCell {
    iu: u32,
    iv: u32,
    w: vec4<f32>,
}

fn grid_cell(t: Table, u: f32, v: f32) -> GridCell {
    let qu = grid_index(t, u);
    let qv = grid_index(t, v);
    let iu = min(u32(floor(qu)), t.res - 2u);
    let iv = min(u32(floor(qv)), t.res - 2u);
    let fu = qu - f32(iu);
    let fv = qv - f32(iv);
    return GridCell(iu, iv, vec4<f32>((1.0 - fu) * (1.0 - fv), fu * (1.0 - fv), (1.0 - fu) * fv, fu * fv));
}

// Unpolarised Fresnel reflectance from index 1 into n (complex cosines from Snell's law).
fn fresnel_index(t: Table, cos_in: f32) -> f32 {
    let n = vec2<f32>(t.n_re, t.n_im);
    let ci = clamp(cos_in, 0.0, 1.0);
    let sin2 = 1.0 - ci * ci;
    let cos_t = csqrt(vec2<f32>(1.0, 0.0) - cdiv(vec2<f32>(sin2, 0.0), cmul(n, n)));
    let nct = cmul(n, cos_t);
    let c = vec2<f32>(ci, 0.0);
    let rs = cdiv(c - nct, c + nct);
    let nci = n * ci;
    let rp = cdiv(nci - cos_t, nci + cos_t);
    return 0.5 * (dot(rs, rs) + dot(rp, rp));
}

fn lookup_fresnel(t: Table, cos_in: f32) -> f32 {
    if ((t.flags & 2u) != 0u) {
        return fresnel_index(t, cos_in);
    }
    // Schlick (thesis App. D): F0 + (1 - F0)(1 - cos)^5.
    let m = 1.0 - clamp(cos_in, 0.0, 1.0);
    return t.f0 + (1.0 - t.f0) * m * m * m * m * m;
}

// C = (R/R0) (1 + wi.wr)^2 / ((cos_i + cos_r)^2 cos_r) times the Cook-Torrance term (paper eq. 2-4 with Stam's
// F^2 = the power reflectance R, PHYSICS.md), R at the half-vector angle; (R/R0)^2 under the paper's convention
// (flag bit 3), as iridis_diffraction::Shading::factor.
fn lookup_shading(t: Table, wi: vec3<f32>, wr: vec3<f32>) -> f32 {
    let ci = wi.z;
    let cr = wr.z;
    let w = ci + cr;
    var h = wi + wr;
    let hl = length(h);
    if (hl < 1e-30) {
        return 0.0;
    }
    h = h / hl;
    let f = lookup_fresnel(t, dot(wi, h));
    let g1 = 1.0 + dot(wi, wr);
    var fr = f / t.f0;
    if ((t.flags & 8u) != 0u) {
        fr = fr * fr;
    }
    var c = fr * (g1 * g1) / (w * w * cr);
    if ((t.flags & 1u) != 0u) {
        let nh = h.z;
        let vh = dot(wr, h);
        if (vh <= 0.0) {
            return 0.0;
        }
        c = c * min(min(2.0 * nh * wr.z / vh, 2.0 * nh * wi.z / vh), 1.0);
    }
    return c;
}

// The three channels' I_p at offset b (a node's offset in its row) of grid row iv + dv.
fn table_value3(t: Table, iv: u32, dv: u32, b: u32, p: u32) -> vec3<f32> {
    return vec3<f32>(table_value(t, iv, dv, b + p), table_value(t, iv, dv, b + t.np + p),
                     table_value(t, iv, dv, b + 2u * t.np + p));
}

// sum_p w^p I_p(u, v) per channel: bilinear in the grid's index space, Horner's rule in w. One loop over the
// powers for the three channels (lavapipe counts every loop iteration against a limit, extended.wgsl).
fn table_sum(t: Table, u: f32, v: f32, w: f32) -> vec3<f32> {
    let np = t.np;
    let cell = grid_cell(t, u, v);
    let iv = cell.iv;
    let b0 = cell.iu * 3u * np;
    let b1 = (cell.iu + 1u) * 3u * np;
    var acc = vec3<f32>(0.0);
    for (var k = 0u; k < np; k = k + 1u) {
        let p = np - 1u - k;
        let ip = cell.w.x * table_value3(t, iv, 0u, b0, p) + cell.w.y * table_value3(t, iv, 0u, b1, p)
            + cell.w.z * table_value3(t, iv, 1u, b0, p) + cell.w.w * table_value3(t, iv, 1u, b1, p);
        acc = acc * w + ip;
    }
    return acc;
}

// XYZ for light direction wi and view direction wr in the surface's frame (z = normal, x = the
// nanostructure's x axis).
fn lookup_xyz(t: Table, wi: vec3<f32>, wr: vec3<f32>) -> vec3<f32> {
    if (wi.z <= 0.0 || wr.z <= 0.0) {
        return vec3<f32>(0.0);
    }
    return lookup_shading(t, wi, wr) * table_sum(t, -wi.x - wr.x, -wi.y - wr.y, -wi.z - wr.z);
}
