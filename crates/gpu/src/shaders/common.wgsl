// Shared by the iridis shaders: complex arithmetic on vec2<f32> (re, im) and the display encoding.

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

fn cdiv(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    let d = dot(b, b);
    return vec2<f32>(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / d;
}

// Principal square root, written so that neither part cancels (|z| ± Re z is only formed where it adds).
fn csqrt(z: vec2<f32>) -> vec2<f32> {
    let r = length(z);
    if (r == 0.0) {
        return vec2<f32>(0.0, 0.0);
    }
    if (z.x >= 0.0) {
        let re = sqrt(0.5 * (r + z.x));
        return vec2<f32>(re, z.y / (2.0 * re));
    }
    var im = sqrt(0.5 * (r - z.x));
    if (z.y < 0.0) {
        im = -im;
    }
    return vec2<f32>(z.y / (2.0 * im), im);
}

// Display: exposure in RU, XYZ -> linear sRGB (IEC 61966-2-1), clip to [0, 1], encode, 8 bits
// (iridis_color::ToneMap::to_rgb8).
struct Display {
    m0: vec4<f32>,
    m1: vec4<f32>,
    m2: vec4<f32>,
    exposure: f32,
    kind: u32,       // 0 sRGB curve, 1 plain gamma, 2 linear
    inv_gamma: f32,
    pad: u32,
}

fn encode(v: f32, kind: u32, inv_gamma: f32) -> f32 {
    if (v <= 0.0) {
        return 0.0;
    }
    if (kind == 0u) {
        if (v <= 0.0031308) {
            return 12.92 * v;
        }
        return 1.055 * pow(v, 1.0 / 2.4) - 0.055;
    }
    if (kind == 1u) {
        return pow(v, inv_gamma);
    }
    return v;
}

fn clip01(v: f32) -> f32 {
    // NaN shows as black, as on the CPU.
    if (!(v >= 0.0)) {
        return 0.0;
    }
    return min(v, 1.0);
}

// Linear sRGB (D65 white = 1) of an XYZ colour.
fn xyz_to_rgb(xyz: vec3<f32>, d: Display) -> vec3<f32> {
    return vec3<f32>(dot(d.m0.xyz, xyz), dot(d.m1.xyz, xyz), dot(d.m2.xyz, xyz));
}

// A linear sRGB colour times the exposure, clipped and encoded.
fn display_rgb(rgb: vec3<f32>, d: Display) -> u32 {
    let s = rgb * d.exposure;
    return pack4x8unorm(vec4<f32>(encode(clip01(s.x), d.kind, d.inv_gamma), encode(clip01(s.y), d.kind, d.inv_gamma),
                                  encode(clip01(s.z), d.kind, d.inv_gamma), 1.0));
}

fn display_pixel(xyz: vec3<f32>, d: Display) -> u32 {
    return display_rgb(xyz_to_rgb(xyz, d), d);
}
