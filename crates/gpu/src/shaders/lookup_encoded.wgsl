// BRDF maps from an encoded lookup table (iridis_diffraction::encoding): the layout of lookup.wgsl, but every
// cell and channel holds K coefficients in 32-bit words -- the 2N+1 powers I_p or K Chebyshev coefficients in
// t = w + 1, each in f32 (one per word) or f16 (two per word, unpack2x16float, times a per-(channel,
// coefficient) scale) -- summed by Horner's rule in w or Clenshaw's recurrence in t after the same bilinear
// interpolation in the non-linear grid's index space: the numbers of EncodedTable::sum in f32. Grid index,
// shading and display come from lookup_math.wgsl and common.wgsl, bindings and the pixel loop from
// lookup_map.wgsl.

// [c * 2 * words + j]: the factor of coefficient j of channel c (f16 only).
@group(0) @binding(8) var<storage, read> scales: array<f32>;

// lookup_math.wgsl's accessor (its lookup_xyz is not used here): the f32 reading of a word.
fn table_value(t: Table, iv: u32, dv: u32, off: u32) -> f32 {
    return bitcast<f32>(cell_word(iv, dv, off, P.words));
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
    let cell = grid_cell(t, u, v);
    let iv = cell.iv;
    let cw = cell.w;
    let words = P.words;
    let b0 = cell.iu * 3u * words;
    let b1 = (cell.iu + 1u) * 3u * words;
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
            let a00 = cell_word(iv, 0u, b0 + o + j, words);
            let a01 = cell_word(iv, 0u, b1 + o + j, words);
            let a10 = cell_word(iv, 1u, b0 + o + j, words);
            let a11 = cell_word(iv, 1u, b1 + o + j, words);
            if (is_half) {
                // Coefficients 2j (low half) and 2j + 1 (high half): the higher one first.
                let s = vec2<f32>(scales[c * 2u * words + 2u * j], scales[c * 2u * words + 2u * j + 1u]);
                let a = (cw.x * unpack2x16float(a00) + cw.y * unpack2x16float(a01) + cw.z * unpack2x16float(a10)
                    + cw.w * unpack2x16float(a11)) * s;
                state = sum_step(state, a.y, x, cheb);
                state = sum_step(state, a.x, x, cheb);
            } else {
                let a = cw.x * bitcast<f32>(a00) + cw.y * bitcast<f32>(a01) + cw.z * bitcast<f32>(a10)
                    + cw.w * bitcast<f32>(a11);
                state = sum_step(state, a, x, cheb);
            }
        }
        // Clenshaw's last step: f = b_0 - t b_1.
        out[c] = select(state.x, state.x - x * state.y, cheb);
    }
    return lookup_shading(t, wi, wr) * out;
}

fn map_xyz(t: Table, wi: vec3<f32>, wr: vec3<f32>) -> vec3<f32> {
    return encoded_xyz(t, wi, wr);
}
