// Film frames (film_math.wgsl over an image): the incidence angle varies along x, the thickness offset along y
// (a gradient) plus d_rel (2 alpha - 1) from a grey texture alpha (eq. 4.4, spatially varying thickness).

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

fn film_medium(f: Film, l: u32, j: u32) -> vec2<f32> {
    return media[l * f.n_media + j];
}

fn film_thickness(f: Film, j: u32) -> f32 {
    return thickness[j];
}

fn film_weight(l: u32) -> vec4<f32> {
    return weights[l];
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
    let c = film_xyz(Film(P.n_media, P.n_lambda, 0u, 0u), sin(theta), cos(theta), offset);
    out_xyz[2u * idx] = vec4<f32>(c.r, 0.0);
    out_xyz[2u * idx + 1u] = vec4<f32>(c.t, 0.0);
    if ((P.flags & 2u) != 0u) {
        out_rgba[idx] = display_pixel(c.r, D);
    }
}
