// The lookup diffraction shader (Dhillon et al. 2014, eq. 10-12 and sec. 5; Single 2014, Algorithm 3):
// X = C(wi, wr) * sum_p w^p I_p(u, v) per channel X, Y, Z, with (u, v, w) = -wi - wr, the tables I_p on the
// non-linear grid u_i = 2 sign(s_i) |s_i|^a, bilinear interpolation in the grid's index space and Horner's rule
// in w -- the numbers of iridis_diffraction::Lookup (Precision::F32), one BRDF-map pixel per invocation.

struct LookupParams {
    wi: vec4<f32>,      // light direction (towards the light), z = normal
    size: u32,          // map side in pixels
    res: u32,           // table samples per axis
    np: u32,            // powers per channel, 2N + 1
    flags: u32,         // bit 0: Cook-Torrance shadowing; bit 1: exact Fresnel of a complex index; bit 2: display
    inv_power: f32,     // 1 / a of the non-linear grid
    f0: f32,            // Fresnel reflectance at normal incidence
    n_re: f32,          // Schlick: n; exact: Re n
    n_im: f32,          // exact: Im n
    rows_per_chunk: u32, // grid rows (v) whose cells each table buffer serves; it holds one row more
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<uniform> P: LookupParams;
@group(0) @binding(1) var<uniform> D: Display;
// I[((iv * res + iu) * 3 + c) * np + p], as in the table file, split by rows of v into up to four buffers
// so that a table larger than one storage binding (e.g. 128 MiB on lavapipe) still fits: buffer k holds rows
// k R .. k R + R (R = rows_per_chunk, one row of overlap, so both rows of a cell are in one buffer).
@group(0) @binding(2) var<storage, read_write> out_xyz: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> out_rgba: array<u32>;
@group(0) @binding(4) var<storage, read> table0: array<f32>;
@group(0) @binding(5) var<storage, read> table1: array<f32>;
@group(0) @binding(6) var<storage, read> table2: array<f32>;
@group(0) @binding(7) var<storage, read> table3: array<f32>;

fn fetch(chunk: u32, i: u32) -> f32 {
    switch chunk {
        case 0u: { return table0[i]; }
        case 1u: { return table1[i]; }
        case 2u: { return table2[i]; }
        default: { return table3[i]; }
    }
}

// Continuous index of u in [-2, 2] on the grid (iridis_diffraction::table::grid_index).
fn grid_index(u: f32) -> f32 {
    var s = 0.0;
    if (u != 0.0) {
        s = sign(u) * pow(min(abs(u) * 0.5, 1.0), P.inv_power);
    }
    return max((s + 1.0) * 0.5 * f32(P.res - 1u), 0.0);
}

// Unpolarised Fresnel reflectance from index 1 into n (complex cosines from Snell's law).
fn fresnel_index(cos_in: f32) -> f32 {
    let n = vec2<f32>(P.n_re, P.n_im);
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

fn fresnel(cos_in: f32) -> f32 {
    if ((P.flags & 2u) != 0u) {
        return fresnel_index(cos_in);
    }
    // Schlick (thesis App. D): F0 + (1 - F0)(1 - cos)^5.
    let m = 1.0 - clamp(cos_in, 0.0, 1.0);
    return P.f0 + (1.0 - P.f0) * m * m * m * m * m;
}

// C = F^2 (1 + wi.wr)^2 / (F0^2 (cos_i + cos_r)^2 cos_r) times the Cook-Torrance term (paper eq. 2-4,
// PHYSICS.md), F at the half-vector angle.
fn shading(wi: vec3<f32>, wr: vec3<f32>) -> f32 {
    let ci = wi.z;
    let cr = wr.z;
    let w = ci + cr;
    var h = wi + wr;
    let hl = length(h);
    if (hl < 1e-30) {
        return 0.0;
    }
    h = h / hl;
    let f = fresnel(dot(wi, h));
    let g1 = 1.0 + dot(wi, wr);
    var c = (f * f) * (g1 * g1) / (P.f0 * P.f0 * w * w * cr);
    if ((P.flags & 1u) != 0u) {
        let nh = h.z;
        let vh = dot(wr, h);
        if (vh <= 0.0) {
            return 0.0;
        }
        c = c * min(min(2.0 * nh * wr.z / vh, 2.0 * nh * wi.z / vh), 1.0);
    }
    return c;
}

fn lookup_xyz(wi: vec3<f32>, wr: vec3<f32>) -> vec3<f32> {
    if (wi.z <= 0.0 || wr.z <= 0.0) {
        return vec3<f32>(0.0);
    }
    let u = -wi.x - wr.x;
    let v = -wi.y - wr.y;
    let w = -wi.z - wr.z;
    let res = P.res;
    let np = P.np;
    let qu = grid_index(u);
    let qv = grid_index(v);
    let iu = min(u32(floor(qu)), res - 2u);
    let iv = min(u32(floor(qv)), res - 2u);
    let fu = qu - f32(iu);
    let fv = qv - f32(iv);
    let chunk = min(iv / P.rows_per_chunk, 3u);
    let lv = iv - chunk * P.rows_per_chunk;
    let w00 = (1.0 - fu) * (1.0 - fv);
    let w01 = fu * (1.0 - fv);
    let w10 = (1.0 - fu) * fv;
    let w11 = fu * fv;
    let b00 = (lv * res + iu) * 3u * np;
    let b01 = (lv * res + iu + 1u) * 3u * np;
    let b10 = ((lv + 1u) * res + iu) * 3u * np;
    let b11 = ((lv + 1u) * res + iu + 1u) * 3u * np;
    var out = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c = c + 1u) {
        let o = c * np;
        var acc = 0.0;
        for (var k = 0u; k < np; k = k + 1u) {
            let p = np - 1u - k;
            let ip = w00 * fetch(chunk, b00 + o + p) + w01 * fetch(chunk, b01 + o + p)
                + w10 * fetch(chunk, b10 + o + p) + w11 * fetch(chunk, b11 + o + p);
            acc = acc * w + ip;
        }
        out[c] = acc;
    }
    return shading(wi, wr) * out;
}

// One pixel of a BRDF map (iridis_diffraction::map): pixel (col, row) shows the view direction
// (x, y, sqrt(1 - x^2 - y^2)), x = (2 col + 1 - size) / size, y = (size - 2 row - 1) / size; black outside
// the unit disk. The disk test and 1 - x^2 - y^2 are exact integer arithmetic.
@compute @workgroup_size(8, 8, 1)
fn brdf_map(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = P.size;
    if (id.x >= size || id.y >= size) {
        return;
    }
    let idx = id.y * size + id.x;
    let a = i32(2u * id.x + 1u) - i32(size);
    let b = i32(size) - i32(2u * id.y + 1u);
    let rest = i32(size * size) - a * a - b * b;
    var xyz = vec3<f32>(0.0);
    if (rest > 0) {
        let fs = f32(size);
        let wr = vec3<f32>(f32(a) / fs, f32(b) / fs, sqrt(f32(rest)) / fs);
        xyz = lookup_xyz(P.wi.xyz, wr);
    }
    out_xyz[idx] = vec4<f32>(xyz, 0.0);
    if ((P.flags & 4u) != 0u) {
        out_rgba[idx] = display_pixel(xyz, D);
    }
}
