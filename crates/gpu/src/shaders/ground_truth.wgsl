// The ground truth (Dhillon et al. 2014, sec. 6.3; iridis_diffraction::GroundTruth): the coherence-windowed
// Fourier transform of exp(i k w h) summed directly over the height samples, |A(s_k)|^2 at each wavenumber
// s_k = 1/lambda_k of the spectral integral, for a batch of direction pairs. The CPU finishes the colour
// (GroundTruth::xyz_from_power: shading, weights, Nyquist).
//
// The sum in separable form (iridis_diffraction::Lattice): A = sum_t sum_i e^{2 pi i beta h_ti} wx_i wy_t with
// wx_i = sum_m gx_im e^{2 pi i alpha I_m} over the images of column i (lattice column I_m), wy_t likewise;
// alpha = u dx s_k and gamma = v dy s_k (turns per lattice step, 0.64 fixed point, prepared in f64 on the CPU),
// beta = w s_k (turns per nm of height). Phases are fixed-point turns (turns.wgsl), so the large ones --
// alpha I over thousands of columns -- stay exact.
//
// One workgroup per (pair, block of 64 wavenumbers), one wavenumber per invocation; the patch is walked in
// tiles of TILE live columns whose wx each invocation keeps in workgroup memory (its own slots: no sharing,
// no barriers), then row by row.

const WG: u32 = 64u;
const TILE: u32 = 32u;

struct GtParams {
    count: u32,  // wavenumbers
    cols: u32,   // patch columns (row stride of the heights)
    ncl: u32,    // live columns (with an image of non-zero weight)
    nrl: u32,    // live rows
}

@group(0) @binding(0) var<uniform> P: GtParams;
@group(0) @binding(1) var<storage, read> heights: array<f32>;
// [0, ncl): per live column (i, first entry, entries, 0); [ncl, ncl + nrl): per live row (t, first, entries, 0).
@group(0) @binding(2) var<storage, read> spans: array<vec4<u32>>;
// (lattice index I, bitcast weight g) per image.
@group(0) @binding(3) var<storage, read> entries: array<vec2<u32>>;
// [pair * count + k]: (alpha low, alpha high, gamma low, gamma high).
@group(0) @binding(4) var<storage, read> phases: array<vec4<u32>>;
// [pair * count + k]: beta = w s_k.
@group(0) @binding(5) var<storage, read> betas: array<f32>;
// [pair * count + k]: |A|^2.
@group(0) @binding(6) var<storage, read_write> out: array<f32>;

var<workgroup> wx: array<vec2<f32>, 2048>; // TILE * WG

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

// sum of the images' weights times e^{2 pi i alpha I}.
fn image_sum(span: vec4<u32>, alpha: vec2<u32>) -> vec2<f32> {
    var w = vec2<f32>(0.0);
    for (var e = span.y; e < span.y + span.z; e = e + 1u) {
        let en = entries[e];
        w = w + bitcast<f32>(en.y) * cis_turns(turns_times(alpha, en.x));
    }
    return w;
}

@compute @workgroup_size(64, 1, 1)
fn power(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_id) lid: vec3<u32>) {
    let pair = wg.x;
    let k = wg.y * WG + lid.x;
    let kk = min(k, P.count - 1u);
    let ph = phases[pair * P.count + kk];
    let beta = betas[pair * P.count + kk];
    var acc = vec2<f32>(0.0);
    for (var c0 = 0u; c0 < P.ncl; c0 = c0 + TILE) {
        let cn = min(TILE, P.ncl - c0);
        for (var c = 0u; c < cn; c = c + 1u) {
            wx[c * WG + lid.x] = image_sum(spans[c0 + c], ph.xy);
        }
        for (var r = 0u; r < P.nrl; r = r + 1u) {
            let rs = spans[P.ncl + r];
            let wy = image_sum(rs, ph.zw);
            let hb = rs.x * P.cols;
            var row = vec2<f32>(0.0);
            for (var c = 0u; c < cn; c = c + 1u) {
                let h = heights[hb + spans[c0 + c].x];
                row = row + cmul(wx[c * WG + lid.x], cis_turns(turns_of(beta * h)));
            }
            acc = acc + cmul(wy, row);
        }
    }
    if (k < P.count) {
        out[pair * P.count + k] = dot(acc, acc);
    }
}
