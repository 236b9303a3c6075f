// BRDF maps from an encoded lookup table (iridis_diffraction::encoding): the layout of lookup.wgsl, but every
// cell and channel holds K coefficients in 32-bit words -- the 2N+1 powers I_p or K Chebyshev coefficients in
// t = w + 1, each in f32 (one per word) or f16 (two per word, unpack2x16float, times a per-(channel,
// coefficient) scale) -- summed by Horner's rule in w or Clenshaw's recurrence in t after the same bilinear
// interpolation in the non-linear grid's index space: the numbers of EncodedTable::sum in f32. Grid index,
// shading and display come from lookup_math.wgsl and common.wgsl.

struct EncodedParams {
    wi: vec4<f32>,
    size: u32,
    res: u32,
    np: u32,             // 2N + 1 (unused here, kept for the Table struct)
    flags: u32,          // as lookup.wgsl
    inv_power: f32,
    f0: f32,
    n_re: f32,
    n_im: f32,
    rows_per_chunk: u32,
    coefficients: u32,   // K per channel
    words: u32,          // 32-bit words per channel
    mode: u32,           // bit 0: f16 pairs; bit 1: Chebyshev (else powers)
}

@group(0) @binding(0) var<uniform> P: EncodedParams;
@group(0) @binding(1) var<uniform> D: Display;
@group(0) @binding(2) var<storage, read_write> out_xyz: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> out_rgba: array<u32>;
// words[((iv * res + iu) * 3 + c) * words + j], split by rows of v as in lookup.wgsl.
@group(0) @binding(4) var<storage, read> table0: array<u32>;
@group(0) @binding(5) var<storage, read> table1: array<u32>;
@group(0) @binding(6) var<storage, read> table2: array<u32>;
@group(0) @binding(7) var<storage, read> table3: array<u32>;
// [c * 2 * words + j]: the factor of coefficient j of channel c (f16 only).
@group(0) @binding(8) var<storage, read> scales: array<f32>;

fn fetch_word(chunk: u32, i: u32) -> u32 {
    switch chunk {
        case 0u: { return table0[i]; }
        case 1u: { return table1[i]; }
        case 2u: { return table2[i]; }
        default: { return table3[i]; }
    }
}

// Word `off` of grid row iv + dv (the buffer chosen by the cell's lower row iv).
fn cell_word(iv: u32, dv: u32, off: u32) -> u32 {
    let chunk = min(iv / P.rows_per_chunk, 3u);
    return fetch_word(chunk, (iv - chunk * P.rows_per_chunk + dv) * P.res * 3u * P.words + off);
}

// lookup_math.wgsl's accessor (its lookup_xyz is not used here): the f32 reading of a word.
fn table_value(t: Table, iv: u32, dv: u32, off: u32) -> f32 {
    return bitcast<f32>(cell_word(iv, dv, off));
}

// One step of the sum from the highest coefficient down: Horner (acc = acc w + a) or Clenshaw
// (b_j = a_j + 2 t b_{j+1} - b_{j+2}); state (b_{j+1}, b_{j+2}).
fn sum_step(state: vec2<f32>, a: f32, x: f32, cheb: bool) -> vec2<f32> {
    if (cheb) {
        return vec2<f32>(a + 2.0 * x * state.x - state.y, state.x);
    }
    return vec2<f32>(state.x * x + a, 0.0);
}

fn encoded_xyz(t: Table, wi: vec3<f32>, wr: vec3<f32>) -> vec3<f32> {
    if (wi.z <= 0.0 || wr.z <= 0.0) {
        return vec3<f32>(0.0);
    }
    let u = -wi.x - wr.x;
    let v = -wi.y - wr.y;
    let w = -wi.z - wr.z;
    let res = t.res;
    let qu = grid_index(t, u);
    let qv = grid_index(t, v);
    let iu = min(u32(floor(qu)), res - 2u);
    let iv = min(u32(floor(qv)), res - 2u);
    let fu = qu - f32(iu);
    let fv = qv - f32(iv);
    let w00 = (1.0 - fu) * (1.0 - fv);
    let w01 = fu * (1.0 - fv);
    let w10 = (1.0 - fu) * fv;
    let w11 = fu * fv;
    let words = P.words;
    let b0 = iu * 3u * words;
    let b1 = (iu + 1u) * 3u * words;
    let is_half = (P.mode & 1u) != 0u;
    let cheb = (P.mode & 2u) != 0u;
    // Horner runs in w, Clenshaw in t = w + 1 (w in [-2, 0] onto [-1, 1]).
    let x = select(w, w + 1.0, cheb);
    var out = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c = c + 1u) {
        let o = c * words;
        var state = vec2<f32>(0.0);
        for (var k = 0u; k < words; k = k + 1u) {
            let j = words - 1u - k;
            let a00 = cell_word(iv, 0u, b0 + o + j);
            let a01 = cell_word(iv, 0u, b1 + o + j);
            let a10 = cell_word(iv, 1u, b0 + o + j);
            let a11 = cell_word(iv, 1u, b1 + o + j);
            if (is_half) {
                // Coefficients 2j (low half) and 2j + 1 (high half): the higher one first.
                let s = vec2<f32>(scales[c * 2u * words + 2u * j], scales[c * 2u * words + 2u * j + 1u]);
                let a = (w00 * unpack2x16float(a00) + w01 * unpack2x16float(a01) + w10 * unpack2x16float(a10)
                    + w11 * unpack2x16float(a11)) * s;
                state = sum_step(state, a.y, x, cheb);
                state = sum_step(state, a.x, x, cheb);
            } else {
                let a = w00 * bitcast<f32>(a00) + w01 * bitcast<f32>(a01) + w10 * bitcast<f32>(a10)
                    + w11 * bitcast<f32>(a11);
                state = sum_step(state, a, x, cheb);
            }
        }
        // Clenshaw's last step: f = b_0 - t b_1.
        out[c] = select(state.x, state.x - x * state.y, cheb);
    }
    return lookup_shading(t, wi, wr) * out;
}

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
        xyz = encoded_xyz(t, P.wi.xyz, wr);
    }
    out_xyz[idx] = vec4<f32>(xyz, 0.0);
    if ((P.flags & 4u) != 0u) {
        out_rgba[idx] = display_pixel(xyz, D);
    }
}
