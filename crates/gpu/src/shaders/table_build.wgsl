// The lookup tables I_p(u, v) of `iridis precompute` (Dhillon et al. 2014, eq. 8-12), one grid point per
// invocation: at each wavelength the coherence-windowed DFT of every Taylor term at f = (-u/lambda, -v/lambda)
// (eq. 8), G_n = k^n/n! F_n (eq. 6), d_p = sum_{a+b=p} Re(G_a conj G_b) (eq. 11-12), summed over wavelengths
// with the XYZ weights -- iridis_diffraction::LookupTable::build in f32. The CPU prepares everything that needs
// f64: the bins each (grid value, wavelength) takes and their window weights (separable: g = gx gy), the
// coefficients scaled by 1/H^n (H = max |h|, so they stay below 1 in f32), and (kH)^n/n!.
//
// NT = N + 1 and NP = 2N + 1 are prepended by crates/gpu/src/table_build.rs.

struct BuildParams {
    res: u32,        // grid samples per axis
    nl: u32,         // wavelengths
    row0: u32,       // first grid row (v) of this dispatch
    rows: u32,       // grid rows in this dispatch
    nbx: u32,        // window slots per (u, lambda) record
    nby: u32,        // window slots per (v, lambda) record
    width_s: u32,    // bins per row of the cropped coefficient array
    ybase: u32,      // where the v windows start in `win`
    smin: i32,       // first bin s (along x) of the crop
    tmin: i32,       // first bin t (along y) of the crop
    threshold: f32,  // the window's edge: a bin counts while ex + ey <= threshold (|f - f_st| <= 4 sigma_f)
    pad: u32,
}

@group(0) @binding(0) var<uniform> P: BuildParams;
// rec[iu * nl + l] = (first bin s, bin count) along x; rec[(res + iv) * nl + l] the same along y; count 0: the
// frequency lies beyond Nyquist (the CPU's within_nyquist), nothing is added.
@group(0) @binding(1) var<storage, read> rec: array<vec2<i32>>;
// (g, e) per bin of a record: g = exp(-e), e = (f - s/L)^2 / (2 sigma_f^2); x records first, y from ybase.
@group(0) @binding(2) var<storage, read> win: array<vec2<f32>>;
// c_n / H^n at bin (s, t): [((t - tmin) * width_s + (s - smin)) * NT + n], (re, im).
@group(0) @binding(3) var<storage, read> coef: array<vec2<f32>>;
// [l * 4 + c]: XYZ weight of wavelength l; from nl * 4: [l * NT + n] = (k_l H)^n / n!.
@group(0) @binding(4) var<storage, read> spectral: array<f32>;
// I[((iv - row0) * res + iu) * 3 * NP + c * NP + p]: the file's layout, rows of this dispatch only.
@group(0) @binding(5) var<storage, read_write> out: array<f32>;

@compute @workgroup_size(8, 8, 1)
fn build(@builtin(global_invocation_id) id: vec3<u32>) {
    let iu = id.x;
    if (iu >= P.res || id.y >= P.rows) {
        return;
    }
    let iv = P.row0 + id.y;
    var acc: array<f32, 3u * NP>;
    var f: array<vec2<f32>, NT>;
    for (var l = 0u; l < P.nl; l = l + 1u) {
        let xr = rec[iu * P.nl + l];
        let yr = rec[(P.res + iv) * P.nl + l];
        if (xr.y <= 0 || yr.y <= 0) {
            continue;
        }
        for (var n = 0u; n < NT; n = n + 1u) {
            f[n] = vec2<f32>(0.0);
        }
        // F_n = sum over the window's bins of c_n g (eq. 8).
        let xw = (iu * P.nl + l) * P.nbx;
        let yw = P.ybase + (iv * P.nl + l) * P.nby;
        for (var jt = 0; jt < yr.y; jt = jt + 1) {
            let gy = win[yw + u32(jt)];
            let row = u32(yr.x + jt - P.tmin) * P.width_s;
            for (var js = 0; js < xr.y; js = js + 1) {
                let gx = win[xw + u32(js)];
                if (gx.y + gy.y > P.threshold) {
                    continue;
                }
                let g = gx.x * gy.x;
                let base = (row + u32(xr.x + js - P.smin)) * NT;
                for (var n = 0u; n < NT; n = n + 1u) {
                    f[n] = f[n] + coef[base + n] * g;
                }
            }
        }
        let sb = P.nl * 4u + l * NT;
        for (var n = 0u; n < NT; n = n + 1u) {
            f[n] = f[n] * spectral[sb + n];
        }
        let w = vec3<f32>(spectral[l * 4u], spectral[l * 4u + 1u], spectral[l * 4u + 2u]);
        // d_p = sum_{a+b=p} Re(G_a conj G_b) = 2 sum_{a<b} ... + |G_{p/2}|^2 (p even).
        for (var p = 0u; p < NP; p = p + 1u) {
            var d = 0.0;
            var a = 0u;
            if (p > NT - 1u) {
                a = p - (NT - 1u);
            }
            for (; 2u * a < p; a = a + 1u) {
                d = d + dot(f[a], f[p - a]);
            }
            d = 2.0 * d;
            if ((p & 1u) == 0u) {
                let h = f[p / 2u];
                d = d + dot(h, h);
            }
            acc[p] = acc[p] + w.x * d;
            acc[NP + p] = acc[NP + p] + w.y * d;
            acc[2u * NP + p] = acc[2u * NP + p] + w.z * d;
        }
    }
    let o = (id.y * P.res + iu) * 3u * NP;
    for (var k = 0u; k < 3u * NP; k = k + 1u) {
        out[o + k] = acc[k];
    }
}
