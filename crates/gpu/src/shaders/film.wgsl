// Film frames (film_math.wgsl over an image): the incidence angle varies along x, the thickness offset along y
// (a gradient) plus d_rel (2 alpha - 1) from a grey texture alpha (eq. 4.4, spatially varying thickness).
// Three entry points: film_frame evaluates every pixel directly (the reference: the recurrence at every
// wavelength sample); film_table fills a colour table over cos theta x offset with the same evaluation
// (iridis_thinfilm::table); film_frame_table shades every pixel from that table (the fast path).

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
    tab_nc: u32,        // colour table: cos theta nodes (uniform on [0, 1])
    tab_no: u32,        // offset nodes (uniform on [tab_o0, tab_o1])
    tab_o0: f32,
    tab_o1: f32,
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
// The colour table: reflected and transmitted XYZ of node (i, j) at 2 (j tab_nc + i) and the next.
@group(0) @binding(8) var<storage, read_write> table: array<vec4<f32>>;

fn film_medium(f: Film, l: u32, j: u32) -> vec2<f32> {
    return media[l * f.n_media + j];
}

fn film_thickness(f: Film, j: u32) -> f32 {
    return thickness[j];
}

fn film_weight(l: u32) -> vec4<f32> {
    return weights[l];
}

fn film_table_node(k: u32) -> vec4<f32> {
    return table[k];
}

struct FramePixel {
    theta: f32,
    offset: f32,
}

fn frame_pixel(id: vec3<u32>) -> FramePixel {
    let idx = id.y * P.width + id.x;
    let fx = f32(id.x) / f32(max(P.width, 2u) - 1u);
    let fy = f32(id.y) / f32(max(P.height, 2u) - 1u);
    let theta = P.angle0 + (P.angle1 - P.angle0) * fx;
    var offset = P.offset_top + (P.offset_bottom - P.offset_top) * fy;
    if ((P.flags & 1u) != 0u) {
        offset = offset + P.d_rel * (alpha[idx] / 0.5 - 1.0);
    }
    return FramePixel(theta, offset);
}

fn write_pixel(idx: u32, c: FilmXyz) {
    out_xyz[2u * idx] = vec4<f32>(c.r, 0.0);
    out_xyz[2u * idx + 1u] = vec4<f32>(c.t, 0.0);
    if ((P.flags & 2u) != 0u) {
        out_rgba[idx] = display_pixel(c.r, D);
    }
}

@compute @workgroup_size(8, 8, 1)
fn film_frame(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= P.width || id.y >= P.height) {
        return;
    }
    let px = frame_pixel(id);
    let c = film_xyz(Film(P.n_media, P.n_lambda, 0u, 0u), sin(px.theta), cos(px.theta), px.offset);
    write_pixel(id.y * P.width + id.x, c);
}

@compute @workgroup_size(8, 8, 1)
fn film_table(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= P.tab_nc || id.y >= P.tab_no) {
        return;
    }
    let c = f32(id.x) / f32(P.tab_nc - 1u);
    var o = P.tab_o0;
    if (P.tab_no > 1u) {
        o = P.tab_o0 + (P.tab_o1 - P.tab_o0) * f32(id.y) / f32(P.tab_no - 1u);
    }
    let x = film_xyz(Film(P.n_media, P.n_lambda, 0u, 0u), sqrt(max(1.0 - c * c, 0.0)), c, o);
    let k = 2u * (id.y * P.tab_nc + id.x);
    table[k] = vec4<f32>(x.r, 0.0);
    table[k + 1u] = vec4<f32>(x.t, 0.0);
}

@compute @workgroup_size(8, 8, 1)
fn film_frame_table(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= P.width || id.y >= P.height) {
        return;
    }
    let px = frame_pixel(id);
    let c = film_table_xyz(FilmTab(0u, P.tab_nc, P.tab_no, P.tab_o0, P.tab_o1), cos(px.theta), px.offset);
    write_pixel(id.y * P.width + id.x, c);
}
