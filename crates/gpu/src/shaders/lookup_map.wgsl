// What the two BRDF-map shaders share (lookup.wgsl reads an f32 table, lookup_encoded.wgsl an encoded one):
// their parameters, bindings, the table's split into buffers and the map's pixel loop. Each defines
//
//   fn map_xyz(t: Table, wi: vec3<f32>, wr: vec3<f32>) -> vec3<f32>
//
// the XYZ of view direction wr under light direction wi (lookup_math.wgsl's Table, common.wgsl's Display).

struct MapParams {
    wi: vec4<f32>,      // light direction (towards the light), z = normal
    size: u32,          // map side in pixels
    res: u32,           // table samples per axis
    np: u32,            // powers per channel, 2N + 1
    flags: u32,         // bit 0: Cook-Torrance shadowing; bit 1: exact Fresnel of a complex index; bit 2: display;
                        // bit 3: the paper's R^2 Fresnel convention
    inv_power: f32,     // 1 / a of the non-linear grid
    f0: f32,            // Fresnel reflectance at normal incidence
    n_re: f32,          // Schlick: n; exact: Re n
    n_im: f32,          // exact: Im n
    rows_per_chunk: u32, // grid rows (v) whose cells each table buffer serves; it holds one row more
    coefficients: u32,  // encoded: K per channel
    words: u32,         // encoded: 32-bit words per channel
    mode: u32,          // encoded: bit 0 f16 pairs; bit 1 Chebyshev (else powers)
}

@group(0) @binding(0) var<uniform> P: MapParams;
@group(0) @binding(1) var<uniform> D: Display;
@group(0) @binding(2) var<storage, read_write> out_xyz: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> out_rgba: array<u32>;
// The table's 32-bit words [((iv * res + iu) * 3 + c) * stride + j], as in the table file, split by rows of v
// into up to four buffers so that a table larger than one storage binding (e.g. 128 MiB on lavapipe) still
// fits: buffer k holds rows k R .. k R + R (R = rows_per_chunk, one row of overlap, so both rows of a cell are
// in one buffer).
@group(0) @binding(4) var<storage, read> table0: array<u32>;
@group(0) @binding(5) var<storage, read> table1: array<u32>;
@group(0) @binding(6) var<storage, read> table2: array<u32>;
@group(0) @binding(7) var<storage, read> table3: array<u32>;

fn fetch_word(chunk: u32, i: u32) -> u32 {
    switch chunk {
        case 0u: { return table0[i]; }
        case 1u: { return table1[i]; }
        case 2u: { return table2[i]; }
        default: { return table3[i]; }
    }
}

// Word `off` of grid row iv + dv, `stride` words per cell and channel; the buffer is chosen by the cell's
// lower row iv, so both rows of a cell come from the same buffer.
fn cell_word(iv: u32, dv: u32, off: u32, stride: u32) -> u32 {
    let chunk = min(iv / P.rows_per_chunk, 3u);
    return fetch_word(chunk, (iv - chunk * P.rows_per_chunk + dv) * P.res * 3u * stride + off);
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
        let t = Table(P.res, P.np, P.flags & 11u, 0u, P.inv_power, P.f0, P.n_re, P.n_im);
        xyz = map_xyz(t, P.wi.xyz, wr);
    }
    out_xyz[idx] = vec4<f32>(xyz, 0.0);
    if ((P.flags & 4u) != 0u) {
        out_rgba[idx] = display_pixel(xyz, D);
    }
}
