// The scene renderer: iridis_render's ray caster (crates/render/src/render.rs) on the GPU, one pixel per
// invocation. Cameras, spheres, planes and triangle meshes through a BVH, Lambert / GGX microfacet /
// diffraction (lookup_math.wgsl, Algorithm 4) / thin-film (film_math.wgsl, Sussenbach eq. 3.14 with SVT)
// materials, directional and point lights with shadows, uniform / sky / equirectangular environments and the
// procedural textures -- the same formulas as the CPU, in f32. The CPU's recursion (reflected and transmitted
// rays) is an explicit stack of rays, each with the throughput that multiplies its radiance and the CPU's
// `weight` that decides when a ray is no longer worth tracing.
//
// Everything small lives in one array of vec4<f32> (`scene`), integers bit-cast; the layout is written by
// crates/gpu/src/scene.rs, whose constants name each record's fields.

struct Params {
    cam_pos: vec4<f32>,    // perspective/orthographic: position; hemisphere: target. w: camera kind (bits)
    cam_fwd: vec4<f32>,    // forward (hemisphere: normal); w: tan(fov/2) | half height | distance
    cam_right: vec4<f32>,
    cam_up: vec4<f32>,
    env_a: vec4<f32>,      // uniform colour | sky zenith | map: w = intensity
    env_b: vec4<f32>,      // sky horizon | map: x = rotation
    env_c: vec4<f32>,      // sky ground
    env_mean: vec4<f32>,   // mean radiance over the sphere (the ambient level)
    background: vec4<f32>,
    m0: vec4<f32>,         // XYZ -> linear sRGB rows
    m1: vec4<f32>,
    m2: vec4<f32>,
    width: u32,
    height: u32,
    spp: u32,
    row0: u32,             // first row of this dispatch (rendering in bands)
    env_kind: u32,         // 0 none, 1 uniform, 2 sky, 3 map
    env_tex: u32,
    env_visible: u32,
    max_depth: u32,
    n_spheres: u32,
    sphere_base: u32,
    n_planes: u32,
    plane_base: u32,
    n_lights: u32,
    light_base: u32,
    n_nodes: u32,
    node_base: u32,
    tri_base: u32,
    mat_base: u32,
    tex_base: u32,
    sample_base: u32,
    n_lambda: u32,
    energy_base: u32,      // the GGX energy table in `tables` (render::energy): E_0, E_1, their averages
    irr_tex: u32,          // the environment's irradiance map (a texture), NONE: uniform
    env_light_base: u32,   // the environment as ENV_LIGHTS directional lights in `tables`, NONE: none
    sample0: u32,          // progressive accumulation: the first sample of this pass (0: a new image)
    pass_samples: u32,     // samples per pixel in this pass
    integration: u32,      // 0 fast, 1 Monte Carlo (render::integrate::Integration)
    seed: u32,             // the random streams' seed
    n_area: u32,           // area lights (extended.wgsl)
    area_base: u32,
    env_cdf_base: u32,     // the environment's importance sampler in `tables`, NONE: none
    pad: u32,
}

// The parameters and the display in storage, not uniform, buffers: lavapipe specialises a shader on the values of
// uniforms that steer its loops and branches (inlined uniforms), so every scene, camera move or light drag
// compiled a new variant of this shader, loops unrolled, for up to 17 CPU-minutes each (2026-11-26).
@group(0) @binding(0) var<storage, read> P: Params;
@group(0) @binding(1) var<storage, read> D: Display;
@group(0) @binding(2) var<storage, read> scene: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> texels: array<f32>;
// Per film: its media at every wavelength sample (l * n_media + j), then its thicknesses (x).
@group(0) @binding(4) var<storage, read> media: array<vec2<f32>>;
// Per wavelength sample: XYZ weights (xyz) and 2 pi / lambda (w).
@group(0) @binding(5) var<storage, read> weights: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> tables: array<f32>;
@group(0) @binding(7) var<storage, read_write> out_rgb: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> out_rgba: array<u32>;
// Ray-stack overflows: [count, deepest depth that found the stack full], reported once per render.
@group(0) @binding(9) var<storage, read_write> overflow: array<atomic<u32>, 2>;
// Thin films' colour tables (film_math.wgsl's FilmTab, film_rough.wgsl's RoughTab), one vec4 per entry.
@group(0) @binding(10) var<storage, read> film_tables: array<vec4<f32>>;

const PI: f32 = 3.141592653589793;
const TAU: f32 = 6.283185307179586;
const FAR: f32 = 3.0e38;
const NONE: u32 = 0xffffffffu;
// render::light::ENVIRONMENT_LIGHTS: directions and irradiances standing for the environment (diffraction).
const ENV_LIGHTS: u32 = 64u;

fn word(v: f32) -> u32 {
    return bitcast<u32>(v);
}

// ------------------------------------------------------------------ the model hooks

fn table_value(t: Table, iv: u32, dv: u32, off: u32) -> f32 {
    return tables[t.base + (iv + dv) * t.res * 3u * t.np + off];
}

fn film_medium(f: Film, l: u32, j: u32) -> vec2<f32> {
    return media[f.media + l * f.n_media + j];
}

fn film_thickness(f: Film, j: u32) -> f32 {
    return media[f.thickness + j].x;
}

fn film_weight(l: u32) -> vec4<f32> {
    return weights[l];
}

fn film_table_node(k: u32) -> vec4<f32> {
    return film_tables[k];
}

// ------------------------------------------------------------------ small vector helpers (render::math)

// Scaled by the largest component first: a cross product of two edges of a few 1e9 units has a squared length
// beyond f32's range (3.4e38), and `v / length(v)` was then 0, a black mesh.
fn safe_normalize(v: vec3<f32>) -> vec3<f32> {
    let m = max(abs(v.x), max(abs(v.y), abs(v.z)));
    if (m > 1e-30) {
        let u = v / m;
        return u / length(u);
    }
    return vec3<f32>(0.0);
}

fn any_perpendicular(n: vec3<f32>) -> vec3<f32> {
    var a = vec3<f32>(0.0, 1.0, 0.0);
    if (abs(n.x) < 0.9) {
        a = vec3<f32>(1.0, 0.0, 0.0);
    }
    return safe_normalize(cross(n, a));
}

// The part of t perpendicular to n, normalised; zero when t is parallel to n.
fn orthogonalize(t: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return safe_normalize(t - n * dot(t, n));
}

fn reflect_dir(d: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return n * (2.0 * dot(d, n)) - d;
}

fn rotate_about(v: vec3<f32>, k: vec3<f32>, angle: f32) -> vec3<f32> {
    let s = sin(angle);
    let c = cos(angle);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1.0 - c));
}

fn max3(v: vec3<f32>) -> f32 {
    return max(max(max(v.x, v.y), v.z), 0.0);
}

// Ray offset that clears the surface at p, reached after distance t: relative to |p| and t (the error of
// o + t d in f32 is a few ulps of |o| + t <= |p| + 2t), so the same scene renders alike at any scale
// (render::render::eps, with a larger factor for f32).
fn eps(p: vec3<f32>, t: f32) -> f32 {
    return 5e-5 * (max(max(abs(p.x), abs(p.y)), abs(p.z)) + t);
}

fn to_rgb(xyz: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(P.m0.xyz, xyz), dot(P.m1.xyz, xyz), dot(P.m2.xyz, xyz));
}

// ------------------------------------------------------------------ textures (render::texture)

// 64-bit integers as (lo, hi) for the noise hash, which the CPU computes in u64 (mul32: turns.wgsl).
fn mul64(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let lo = mul32(a.x, b.x);
    return vec2<u32>(lo.x, lo.y + a.x * b.y + a.y * b.x);
}

fn from_i32(x: i32) -> vec2<u32> {
    var hi = 0u;
    if (x < 0) {
        hi = 0xffffffffu;
    }
    return vec2<u32>(bitcast<u32>(x), hi);
}

// render::texture::hash: a 64-bit mix of the lattice point and the seed, as a number in [0, 1).
fn hash(x: i32, y: i32, seed: u32) -> f32 {
    let k1 = vec2<u32>(0x7F4A7C15u, 0x9E3779B9u);
    let k2 = vec2<u32>(0x27D4EB4Fu, 0xC2B2AE3Du);
    let k3 = vec2<u32>(0x9E3779F9u, 0x165667B1u);
    let k4 = vec2<u32>(0xED558CCDu, 0xFF51AFD7u);
    var h = mul64(from_i32(x), k1) ^ mul64(from_i32(y), k2) ^ mul64(vec2<u32>(seed, 0u), k3);
    h = h ^ vec2<u32>(h.y >> 1u, 0u);
    h = mul64(h, k4);
    h = h ^ vec2<u32>(h.y >> 1u, 0u);
    // (h >> 11) / 2^53: the top 53 bits; f32 keeps the top 24.
    return f32(h.y) * 2.3283064365386963e-10 + f32(h.x >> 11u) * 1.1102230246251565e-16;
}

fn value_noise(x: f32, y: f32, seed: u32) -> f32 {
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let sx = fx * fx * (3.0 - 2.0 * fx);
    let sy = fy * fy * (3.0 - 2.0 * fy);
    let i = i32(x0);
    let j = i32(y0);
    let h00 = hash(i, j, seed);
    let a = h00 + (hash(i + 1, j, seed) - h00) * sx;
    let h01 = hash(i, j + 1, seed);
    let b = h01 + (hash(i + 1, j + 1, seed) - h01) * sx;
    return a + (b - a) * sy;
}

fn fbm(x: f32, y: f32, octaves: u32, seed: u32) -> f32 {
    var sum = 0.0;
    var amp = 1.0;
    var norm = 0.0;
    var f = 1.0;
    for (var o = 0u; o < max(octaves, 1u); o = o + 1u) {
        sum = sum + amp * value_noise(x * f, y * f, seed + o * 7919u);
        norm = norm + amp;
        amp = amp * 0.5;
        f = f * 2.0;
    }
    return sum / norm;
}

fn wrap(i: i32, n: i32) -> u32 {
    return u32(((i % n) + n) % n);
}

fn euclid(x: f32, m: f32) -> f32 {
    return x - m * floor(x / m);
}

// Texture record (3 vec4): [kind, a, b, c] then parameters. Kinds: 0 image [w, h, channels] + [texel base],
// 1 noise [scale, octaves, seed], 2 gradient [from, to, along_u], 3 scales [base] [edge], 4 checker [a, n] [b].
fn sample_texture(index: u32, uv: vec2<f32>, clamp_v: bool) -> vec3<f32> {
    let r = P.tex_base + 3u * index;
    let h = scene[r];
    let a = scene[r + 1u];
    let b = scene[r + 2u];
    let kind = word(h.x);
    if (kind == 0u) {
        let width = i32(word(h.y));
        let height = i32(word(h.z));
        let channels = word(h.w);
        let base = word(a.x);
        let x = euclid(uv.x, 1.0) * f32(width) - 0.5;
        var v = euclid(uv.y, 1.0);
        if (clamp_v) {
            v = clamp(uv.y, 0.0, 1.0);
        }
        let y = v * f32(height) - 0.5;
        let x0 = floor(x);
        let y0 = floor(y);
        let fx = x - x0;
        let fy = y - y0;
        var out = vec3<f32>(0.0);
        for (var dy = 0; dy < 2; dy = dy + 1) {
            var wy = 1.0 - fy;
            if (dy == 1) {
                wy = fy;
            }
            var row = 0u;
            if (clamp_v) {
                row = u32(clamp(i32(y0) + dy, 0, height - 1));
            } else {
                row = wrap(i32(y0) + dy, height);
            }
            for (var dx = 0; dx < 2; dx = dx + 1) {
                var wx = 1.0 - fx;
                if (dx == 1) {
                    wx = fx;
                }
                let col = wrap(i32(x0) + dx, width);
                let t = base + (row * u32(width) + col) * channels;
                let last = channels - 1u;
                out = out + wx * wy * vec3<f32>(texels[t], texels[t + min(1u, last)], texels[t + min(2u, last)]);
            }
        }
        return out;
    }
    if (kind == 1u) {
        let s = a.x;
        return vec3<f32>(fbm(uv.x * s, uv.y * s, word(a.y), word(a.z)));
    }
    if (kind == 2u) {
        var s = uv.y;
        if (word(a.z) != 0u) {
            s = uv.x;
        }
        return vec3<f32>(a.x + (a.y - a.x) * clamp(s, 0.0, 1.0));
    }
    if (kind == 3u) {
        let row = floor(uv.y);
        var x = uv.x;
        if (euclid(row, 2.0) == 1.0) {
            x = x + 0.5;
        }
        let fx = euclid(x, 1.0) - 0.5;
        let fy = euclid(uv.y, 1.0) - 0.5;
        let rr = sqrt(fx * fx + fy * fy) * 2.0;
        let t = pow(clamp((rr - 0.55) / 0.45, 0.0, 1.0), 1.5);
        return a.xyz + (b.xyz - a.xyz) * t;
    }
    let n = a.w;
    let s = euclid(floor(uv.x * n) + floor(uv.y * n), 2.0);
    if (s == 0.0) {
        return a.xyz;
    }
    return b.xyz;
}

// A colour source (one vec4): a constant (w = NONE) or texture number w.
fn color_at(c: vec4<f32>, uv: vec2<f32>) -> vec3<f32> {
    let t = word(c.w);
    if (t == NONE) {
        return c.xyz;
    }
    return sample_texture(t, uv, false);
}

// ------------------------------------------------------------------ lights and environment (render::light)

fn environment(d: vec3<f32>) -> vec3<f32> {
    if (P.env_kind == 1u) {
        return P.env_a.xyz;
    }
    if (P.env_kind == 2u) {
        if (d.y >= 0.0) {
            let y = clamp(d.y, 0.0, 1.0);
            var t = 0.0;
            if (y > 0.0) {
                t = pow(y, 0.6);
            }
            return P.env_b.xyz + (P.env_a.xyz - P.env_b.xyz) * t;
        }
        let t = clamp(-d.y * 8.0, 0.0, 1.0);
        return P.env_b.xyz + (P.env_c.xyz - P.env_b.xyz) * t;
    }
    if (P.env_kind == 3u) {
        let phi = atan2(d.x, -d.z) - P.env_b.x;
        let u = euclid(0.5 + phi / TAU, 1.0);
        let v = acos(clamp(d.y, -1.0, 1.0)) / PI;
        return sample_texture(P.env_tex, vec2<f32>(u, v), true) * P.env_a.w;
    }
    return vec3<f32>(0.0);
}

// E(n)/pi of the environment (render::light::Environment::irradiance): its irradiance map, or the uniform
// radiance.
fn irradiance(n: vec3<f32>) -> vec3<f32> {
    if (P.irr_tex != NONE) {
        let u = euclid(0.5 + atan2(n.x, -n.z) / TAU, 1.0);
        // render::light::irradiance_map_v: the map's first and last rows are the poles themselves.
        let rows = f32(word(scene[P.tex_base + 3u * P.irr_tex].z));
        let v = (acos(clamp(n.y, -1.0, 1.0)) / PI * (rows - 1.0) + 0.5) / rows;
        return sample_texture(P.irr_tex, vec2<f32>(u, v), true);
    }
    if (P.env_kind == 1u) {
        return P.env_a.xyz;
    }
    return P.env_mean.xyz;
}

struct Arrival {
    wi: vec3<f32>,
    dist: f32,
    e: vec3<f32>,
    omega: f32,  // the light's solid angle (0: a delta light)
}

// Lights that reach surfaces as directional lights (render::render::Scene::lights_at): the directional and
// point lights, then on the fast path each area light from its centre (extended.wgsl); Monte Carlo samples
// area lights instead.
fn n_arrivals() -> u32 {
    if (P.integration == 0u) {
        return P.n_lights + P.n_area;
    }
    return P.n_lights;
}

fn monte_carlo() -> bool {
    return P.integration != 0u;
}

// Light record (2 vec4): [direction | position, kind (0 directional, 1 point, 2 laser spot)], [irradiance
// rgb, laser: record of its frame [t, profile texture], [b, cos theta_i], [n, 0]]. An index past them is an area
// light's representative (e = 0 where it cannot be seen).
fn arrive(i: u32, p: vec3<f32>) -> Arrival {
    if (i >= P.n_lights) {
        let r = area_representative(i - P.n_lights, p);
        return Arrival(r.wi, r.dist, r.e, r.omega);
    }
    let r = P.light_base + 2u * i;
    let a = scene[r];
    let e = scene[r + 1u].xyz;
    let kind = word(a.w);
    if (kind == 0u) {
        return Arrival(a.xyz, FAR, e, 0.0);
    }
    let d = a.xyz - p;
    let r2 = max(dot(d, d), 1e-12);
    let dist = sqrt(r2);
    if (kind == 2u) {
        // render::light::LaserSpot::arrive: the sample's reflection of the beam towards p, from its profile.
        let f = word(scene[r + 1u].w);
        let t = scene[f];
        let b = scene[f + 1u];
        let n = scene[f + 2u].xyz;
        let wo = -d / dist;
        if (dot(-d, n) <= 0.0) {
            return Arrival(d / dist, dist, vec3<f32>(0.0), 0.0);
        }
        let uv = vec2<f32>((dot(wo, t.xyz) + 1.0) * 0.5, (1.0 - dot(wo, b.xyz)) * 0.5);
        let refl = sample_texture(word(t.w), uv, false);
        return Arrival(d / dist, dist, e * refl * (dot(wo, n) / (b.w * r2)), 0.0);
    }
    return Arrival(d / dist, dist, e / r2, 0.0);
}

// ------------------------------------------------------------------ geometry (render::geometry, render::bvh)

struct Prim {
    t: f32,
    kind: u32,  // 0 none, 1 sphere, 2 plane, 3 triangle
    index: u32,
    b1: f32,
    b2: f32,
}

fn sphere_t(i: u32, o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    let s = scene[P.sphere_base + 2u * i];
    let oc = o - s.xyz;
    let a = dot(d, d);
    let hb = dot(oc, d);
    let c = dot(oc, oc) - s.w * s.w;
    let disc = hb * hb - a * c;
    if (disc < 0.0) {
        return -1.0;
    }
    let sq = sqrt(disc);
    let e = 1e-6 * s.w;
    let t0 = (-hb - sq) / a;
    if (t0 > e && t0 < t_max) {
        return t0;
    }
    let t1 = (-hb + sq) / a;
    if (t1 > e && t1 < t_max) {
        return t1;
    }
    return -1.0;
}

// Plane record (4 vec4): [centre, has size], [normal, width], [tangent, height], [material, UV unit].
fn plane_t(i: u32, o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    let r = P.plane_base + 4u * i;
    let c = scene[r];
    let n = scene[r + 1u];
    let tg = scene[r + 2u];
    let den = dot(d, n.xyz);
    if (abs(den) < 1e-20) {
        return -1.0;
    }
    let t = dot(c.xyz - o, n.xyz) / den;
    if (!(t > 0.0 && t < t_max)) {
        return -1.0;
    }
    if (word(c.w) != 0u) {
        let rel = o + d * t - c.xyz;
        let b = cross(n.xyz, tg.xyz);
        if (abs(dot(rel, tg.xyz)) > n.w * 0.5 || abs(dot(rel, b)) > tg.w * 0.5) {
            return -1.0;
        }
    }
    return t;
}

// Moller-Trumbore: (t, b1, b2), t < 0 for a miss.
fn triangle_t(i: u32, o: vec3<f32>, d: vec3<f32>, t_max: f32) -> vec3<f32> {
    let r = P.tri_base + 14u * i;
    let a = scene[r].xyz;
    let e1 = scene[r + 1u].xyz - a;
    let e2 = scene[r + 2u].xyz - a;
    let p = cross(d, e2);
    let det = dot(e1, p);
    if (abs(det) < 1e-12 * length(e1) * length(e2)) {
        return vec3<f32>(-1.0, 0.0, 0.0);
    }
    let inv = 1.0 / det;
    let s = o - a;
    let u = dot(s, p) * inv;
    if (u < 0.0 || u > 1.0) {
        return vec3<f32>(-1.0, 0.0, 0.0);
    }
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    if (v < 0.0 || u + v > 1.0) {
        return vec3<f32>(-1.0, 0.0, 0.0);
    }
    let t = dot(e2, q) * inv;
    if (t > 0.0 && t < t_max) {
        return vec3<f32>(t, u, v);
    }
    return vec3<f32>(-1.0, 0.0, 0.0);
}

// Entry distance into a BVH node's box, or -1.
fn slab(i: u32, o: vec3<f32>, inv: vec3<f32>, t_max: f32) -> f32 {
    let lo = scene[P.node_base + 2u * i].xyz;
    let hi = scene[P.node_base + 2u * i + 1u].xyz;
    let a = (lo - o) * inv;
    let b = (hi - o) * inv;
    let t0 = max(max(max(min(a.x, b.x), min(a.y, b.y)), min(a.z, b.z)), 0.0);
    let t1 = min(min(min(max(a.x, b.x), max(a.y, b.y)), max(a.z, b.z)), t_max);
    if (t0 <= t1) {
        return t0;
    }
    return -1.0;
}

// The nearest primitive along a ray before t_max.
fn intersect(o: vec3<f32>, d: vec3<f32>, t_max_in: f32) -> Prim {
    var best = Prim(t_max_in, 0u, 0u, 0.0, 0.0);
    for (var i = 0u; i < P.n_spheres; i = i + 1u) {
        let t = sphere_t(i, o, d, best.t);
        if (t > 0.0) {
            best = Prim(t, 1u, i, 0.0, 0.0);
        }
    }
    for (var i = 0u; i < P.n_planes; i = i + 1u) {
        let t = plane_t(i, o, d, best.t);
        if (t > 0.0) {
            best = Prim(t, 2u, i, 0.0, 0.0);
        }
    }
    if (P.n_nodes > 0u) {
        // Axis-parallel rays: 1/0 = inf, and 0 * inf = NaN drops out of min/max like the CPU's comparisons.
        let inv = 1.0 / d;
        var stack: array<u32, 64>;
        var sp = 1u;
        stack[0] = 0u;
        while (sp > 0u) {
            sp = sp - 1u;
            let node = stack[sp];
            if (slab(node, o, inv, best.t) < 0.0) {
                continue;
            }
            let meta_lo = scene[P.node_base + 2u * node];
            let meta_hi = scene[P.node_base + 2u * node + 1u];
            let start = word(meta_lo.w);
            let count = word(meta_hi.w);
            if (count > 0u) {
                for (var k = start; k < start + count; k = k + 1u) {
                    let h = triangle_t(k, o, d, best.t);
                    if (h.x > 0.0) {
                        best = Prim(h.x, 3u, k, h.y, h.z);
                    }
                }
            } else {
                let left = node + 1u;
                let right = start;
                let tl = slab(left, o, inv, best.t);
                let tr = slab(right, o, inv, best.t);
                if (tl >= 0.0 && tr >= 0.0) {
                    if (tl <= tr) {
                        stack[sp] = right;
                        stack[sp + 1u] = left;
                    } else {
                        stack[sp] = left;
                        stack[sp + 1u] = right;
                    }
                    sp = sp + 2u;
                } else if (tl >= 0.0) {
                    stack[sp] = left;
                    sp = sp + 1u;
                } else if (tr >= 0.0) {
                    stack[sp] = right;
                    sp = sp + 1u;
                }
                sp = min(sp, 62u);
            }
        }
    }
    return best;
}

struct Hit {
    t: f32,
    p: vec3<f32>,
    n: vec3<f32>,
    ng: vec3<f32>,
    uv: vec2<f32>,
    tangent: vec3<f32>,  // zero: none
    along: vec3<f32>,    // zero: none
    material: u32,
    tsign: f32,          // the tangent's bitangent sign w (B = (N x T) w); 1 without one
}

fn make_hit(h: Prim, o: vec3<f32>, d: vec3<f32>) -> Hit {
    let p = o + d * h.t;
    if (h.kind == 1u) {
        let s = scene[P.sphere_base + 2u * h.index];
        let material = word(scene[P.sphere_base + 2u * h.index + 1u].x);
        let n0 = (p - s.xyz) / s.w;
        var n = n0;
        if (dot(n0, d) >= 0.0) {
            n = -n0;
        }
        let u = euclid(atan2(n0.x, n0.z) / TAU, 1.0);
        let v = acos(clamp(n0.y, -1.0, 1.0)) / PI;
        var east = safe_normalize(vec3<f32>(n0.z, 0.0, -n0.x));
        if (dot(east, east) == 0.0) {
            east = vec3<f32>(1.0, 0.0, 0.0);
        }
        var south = cross(east, n0);
        let so = orthogonalize(south, n);
        if (dot(so, so) > 0.0) {
            south = so;
        }
        return Hit(h.t, p, n, n, vec2<f32>(u, v), orthogonalize(east, n), south, material, 1.0);
    }
    if (h.kind == 2u) {
        let r = P.plane_base + 4u * h.index;
        let c = scene[r];
        let nw = scene[r + 1u];
        let tg = scene[r + 2u];
        let material = word(scene[r + 3u].x);
        let b = cross(nw.xyz, tg.xyz);
        let rel = p - c.xyz;
        let x = dot(rel, tg.xyz);
        let y = dot(rel, b);
        var uv = vec2<f32>(x, -y) / scene[r + 3u].y;
        if (word(c.w) != 0u) {
            uv = vec2<f32>(x / nw.w + 0.5, 0.5 - y / tg.w);
        }
        var n = nw.xyz;
        if (dot(d, nw.xyz) >= 0.0) {
            n = -n;
        }
        return Hit(h.t, p, n, n, uv, tg.xyz, tg.xyz, material, 1.0);
    }
    // Triangle record (14 vec4): p0 [material], p1 [flags: 1 uv, 2 tangents, 4 along], p2, n0..n2,
    // [uv0, uv1], [uv2], t0..t2 (xyz, sign), a0..a2.
    let r = P.tri_base + 14u * h.index;
    let w = vec3<f32>(1.0 - h.b1 - h.b2, h.b1, h.b2);
    let a = scene[r];
    let b = scene[r + 1u];
    let c = scene[r + 2u].xyz;
    let material = word(a.w);
    let flags = word(b.w);
    let ng0 = safe_normalize(cross(b.xyz - a.xyz, c - a.xyz));
    var n = safe_normalize(scene[r + 3u].xyz * w.x + scene[r + 4u].xyz * w.y + scene[r + 5u].xyz * w.z);
    if (dot(n, n) == 0.0) {
        n = ng0;
    }
    var ng = ng0;
    if (dot(ng0, d) >= 0.0) {
        ng = -ng0;
    }
    if (dot(n, ng) < 0.0) {
        n = -n;
    }
    var uv = vec2<f32>(0.0);
    if ((flags & 1u) != 0u) {
        let q01 = scene[r + 6u];
        let q2 = scene[r + 7u];
        uv = q01.xy * w.x + q01.zw * w.y + q2.xy * w.z;
    }
    var tangent = vec3<f32>(0.0);
    var tsign = 1.0;
    if ((flags & 2u) != 0u) {
        tangent = orthogonalize(scene[r + 8u].xyz * w.x + scene[r + 9u].xyz * w.y + scene[r + 10u].xyz * w.z, n);
        tsign = select(1.0, -1.0, scene[r + 8u].w < 0.0);
    }
    var along = vec3<f32>(0.0);
    if ((flags & 4u) != 0u) {
        along = orthogonalize(scene[r + 11u].xyz * w.x + scene[r + 12u].xyz * w.y + scene[r + 13u].xyz * w.z, n);
    }
    return Hit(h.t, p, n, ng, uv, tangent, along, material, tsign);
}

// Material record (8 vec4); word 0 of the first: 0 Lambert, 1 microfacet, 2 diffraction, 3 thin film.
fn transmissive(m: u32) -> bool {
    let h = scene[P.mat_base + 8u * m];
    return word(h.x) == 3u && (word(scene[P.mat_base + 8u * m + 1u].w) & 2u) != 0u;
}

fn material_of(h: Prim) -> u32 {
    if (h.kind == 1u) {
        return word(scene[P.sphere_base + 2u * h.index + 1u].x);
    }
    if (h.kind == 2u) {
        return word(scene[P.plane_base + 4u * h.index + 3u].x);
    }
    return word(scene[P.tri_base + 14u * h.index].w);
}

// Whether something opaque lies between p and a light dist away along wi (transmissive films cast no shadow).
fn occluded(p: vec3<f32>, wi: vec3<f32>, dist: f32) -> bool {
    var o = p;
    var left = dist;
    for (var k = 0; k < 16; k = k + 1) {
        let h = intersect(o, wi, left);
        if (h.kind == 0u) {
            return false;
        }
        if (!transmissive(material_of(h))) {
            return true;
        }
        let q = o + wi * h.t;
        o = q + wi * eps(q, h.t);
        left = left - h.t;
    }
    return true;
}

// ------------------------------------------------------------------ materials (render::material)

struct Microfacet {
    color: vec4<f32>,
    roughness: f32,
    metallic: f32,
    ior: f32,
}

// The GGX energy table (render::energy::lookup): (E_0, E_1, E_0 avg, E_1 avg) at (roughness, mu), bilinear.
const N_ROUGH: u32 = 32u;
const N_MU: u32 = 64u;

fn energy_bilinear(o: u32, i: u32, j: u32, fx: f32, fy: f32) -> f32 {
    let g00 = tables[o + i * N_MU + j];
    let g01 = tables[o + i * N_MU + j + 1u];
    let g10 = tables[o + (i + 1u) * N_MU + j];
    let g11 = tables[o + (i + 1u) * N_MU + j + 1u];
    let a = g00 + (g01 - g00) * fy;
    let b = g10 + (g11 - g10) * fy;
    return a + (b - a) * fx;
}

fn energy_lookup(rough: f32, mu: f32) -> vec4<f32> {
    let x = clamp(rough, 0.0, 1.0) * f32(N_ROUGH - 1u);
    let y = clamp(mu, 0.0, 1.0) * f32(N_MU - 1u);
    let i = min(u32(x), N_ROUGH - 2u);
    let j = min(u32(y), N_MU - 2u);
    let fx = x - f32(i);
    let fy = y - f32(j);
    let b = P.energy_base;
    let n = N_ROUGH * N_MU;
    let av = b + 2u * n;
    let a0 = tables[av + i] + (tables[av + i + 1u] - tables[av + i]) * fx;
    let a1 = tables[av + N_ROUGH + i] + (tables[av + N_ROUGH + i + 1u] - tables[av + N_ROUGH + i]) * fx;
    return vec4<f32>(energy_bilinear(b, i, j, fx, fy), energy_bilinear(b + n, i, j, fx, fy), a0, a1);
}

// render::energy::spec_energy: (E_s, E_s avg, F_ms, E_0) of a lobe with Schlick reflectance f0.
fn spec_energy(rough: f32, mu: f32, f0: f32) -> vec4<f32> {
    let e = energy_lookup(rough, mu);
    let f_avg = f0 + (1.0 - f0) / 21.0;
    let f_ms = f_avg * f_avg * e.z / max(1.0 - f_avg * (1.0 - e.z), 1e-12);
    let e_ss = f0 * (e.x - e.y) + e.y;
    let e_ss_avg = f0 * (e.z - e.w) + e.w;
    return vec4<f32>(min(e_ss + f_ms * (1.0 - e.x), 1.0), min(e_ss_avg + f_ms * (1.0 - e.z), 1.0), f_ms, e.x);
}

fn coat_f0(m: Microfacet) -> f32 {
    return ((m.ior - 1.0) / (m.ior + 1.0)) * ((m.ior - 1.0) / (m.ior + 1.0));
}

// pi f cos(theta_i) of the single-scattering GGX lobe with F = 1 (render::material::Microfacet::ggx_single).
fn ggx_single(m: Microfacet, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let ci = dot(n, wi);
    let co = dot(n, wo);
    if (ci <= 0.0 || co <= 0.0) {
        return 0.0;
    }
    let a = max(m.roughness * m.roughness, 1e-4);
    let a2 = a * a;
    let nh = max(dot(n, safe_normalize(wi + wo)), 0.0);
    let q = nh * nh * (a2 - 1.0) + 1.0;
    let dd = a2 / (PI * q * q);
    let g = 2.0 * ci / (ci + sqrt(a2 + (1.0 - a2) * ci * ci)) * 2.0 * co / (co + sqrt(a2 + (1.0 - a2) * co * co));
    return dd * g / (4.0 * co) * PI;
}

// render::material::Microfacet::reflect: mix(dielectric, metal, metallic), Kulla-Conty multiple scattering,
// the dielectric's diffuse lobe taking what its specular leaves. An index-matched coat (ior 1) is Lambertian.
fn microfacet_reflect(m: Microfacet, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>, albedo: vec3<f32>) -> vec3<f32> {
    let ci = dot(n, wi);
    let co = dot(n, wo);
    if (ci <= 0.0 || co <= 0.0) {
        return vec3<f32>(0.0);
    }
    let h = safe_normalize(wi + wo);
    let x = 1.0 - clamp(dot(wi, h), 0.0, 1.0);
    let x5 = x * x * x * x * x;
    // ggx_single is already pi f cos(theta_i) (as the CPU's `single`); multiplying by ci again made the GPU's
    // specular highlights from lights cos(theta_i) too dark (found by the glTF metal quads, 26 % at 42 degrees).
    let single = ggx_single(m, n, wi, wo);
    let ei = energy_lookup(m.roughness, ci);
    let eo = energy_lookup(m.roughness, co);
    let multi = (1.0 - ei.x) * (1.0 - eo.x) / max(1.0 - eo.z, 1e-9) * ci;
    var dielectric = albedo * ci;
    if (m.ior != 1.0) {
        let f0 = coat_f0(m);
        let si = spec_energy(m.roughness, ci, f0);
        let so = spec_energy(m.roughness, co, f0);
        let k = (1.0 - si.x) * (1.0 - so.x) / max(1.0 - so.y, 1e-9) * ci;
        dielectric = vec3<f32>(single * (f0 + (1.0 - f0) * x5) + multi * so.z) + albedo * k;
    }
    var metal = vec3<f32>(0.0);
    if (m.metallic > 0.0) {
        let fms = vec3<f32>(spec_energy(m.roughness, co, albedo.x).z, spec_energy(m.roughness, co, albedo.y).z,
                            spec_energy(m.roughness, co, albedo.z).z);
        metal = single * (albedo + (vec3<f32>(1.0) - albedo) * x5) + multi * fms;
    }
    return (1.0 - m.metallic) * dielectric + m.metallic * metal;
}

// render::material::Microfacet::env_weights: the specular and diffuse shares of uniform environment light.
struct EnvWeights {
    spec: vec3<f32>,
    diffuse: vec3<f32>,
}

fn env_weights(m: Microfacet, cos_o: f32, albedo: vec3<f32>) -> EnvWeights {
    var es_d = 0.0;
    var dif = 1.0;
    if (m.ior != 1.0) {
        es_d = spec_energy(m.roughness, cos_o, coat_f0(m)).x;
        dif = 1.0 - es_d;
    }
    var metal = vec3<f32>(0.0);
    if (m.metallic > 0.0) {
        metal = vec3<f32>(spec_energy(m.roughness, cos_o, albedo.x).x, spec_energy(m.roughness, cos_o, albedo.y).x,
                          spec_energy(m.roughness, cos_o, albedo.z).x);
    }
    return EnvWeights(vec3<f32>((1.0 - m.metallic) * es_d) + m.metallic * metal, albedo * ((1.0 - m.metallic) * dif));
}

fn schlick(n: f32, cosv: f32) -> f32 {
    let f0 = ((n - 1.0) / (n + 1.0)) * ((n - 1.0) / (n + 1.0));
    let x = 1.0 - clamp(cosv, 0.0, 1.0);
    return f0 + (1.0 - f0) * (x * x * x * x * x);
}

// The nanostructure's x axis at a hit (render::material::Orientation::tangent).
fn orientation(h: Hit, rule: u32, dir: vec3<f32>, tex: u32, angle: f32) -> vec3<f32> {
    let n = h.n;
    var base = h.tangent;
    if (dot(base, base) == 0.0) {
        base = any_perpendicular(n);
    }
    var t = base;
    if (rule == 1u) {
        if (dot(h.along, h.along) > 0.0) {
            t = h.along;
        }
    } else if (rule == 2u) {
        t = orthogonalize(dir, n);
    } else if (rule == 3u) {
        let c = sample_texture(tex, h.uv, false);
        let b = cross(n, base);
        t = safe_normalize(base * (2.0 * c.x - 1.0) + b * (2.0 * c.y - 1.0));
    }
    if (dot(t, t) == 0.0) {
        t = base;
    }
    if (angle != 0.0) {
        t = safe_normalize(rotate_about(t, n, angle));
    }
    return t;
}

// ------------------------------------------------------------------ the ray stack

struct Ray {
    o: vec3<f32>,
    d: vec3<f32>,
    throughput: vec3<f32>,
    depth: u32,
    weight: f32,
    pdf: f32,  // a BRDF sample's pdf (Monte Carlo: the lights it meets are weighted by MIS); 0: a mirror's ray
}

const STACK: u32 = 24u;
var<private> rays: array<Ray, STACK>;
var<private> n_rays: u32;
var<private> radiance: vec3<f32>;

// Queues a secondary ray; if the stack is full, the environment's radiance stands in (as for a ray past
// max_depth on the CPU) and the overflow is counted, with its depth, for the host to report.
fn push_ray(o: vec3<f32>, d: vec3<f32>, throughput: vec3<f32>, depth: u32, weight: f32) {
    push_sampled(o, d, throughput, depth, weight, 0.0);
}

// The environment's radiance along a ray that leaves the scene, weighted against its own sampling when a BRDF
// sampled the ray (render::integrate::Scene::sampled_radiance).
fn escaped(d: vec3<f32>, pdf: f32) -> vec3<f32> {
    return environment(d) * brdf_weight(pdf, env_pdf(d));
}

// Queues a ray (a BRDF's sample with its pdf, or a mirror's with pdf 0).
fn push_sampled(o: vec3<f32>, d: vec3<f32>, throughput: vec3<f32>, depth: u32, weight: f32, pdf: f32) {
    if (max3(throughput) <= 0.0) {
        return;
    }
    if (n_rays < STACK) {
        rays[n_rays] = Ray(o, d, throughput, depth, weight, pdf);
        n_rays = n_rays + 1u;
    } else {
        radiance = radiance + throughput * escaped(d, pdf);
        atomicAdd(&overflow[0], 1u);
        atomicMax(&overflow[1], depth);
    }
}

// The microfacet record at r, at texture coordinate uv: the metallic-roughness texture (w, NONE: none)
// scales roughness by its G and metallic by its B channel (render::material::Microfacet::at).
fn microfacet_at(r: u32, uv: vec2<f32>) -> Microfacet {
    let p = scene[r + 1u];
    let mr = word(p.w);
    if (mr == NONE) {
        return Microfacet(scene[r], p.x, p.y, p.z);
    }
    let s = sample_texture(mr, uv, false);
    return Microfacet(scene[r], clamp(p.x * s.y, 0.0, 1.0), clamp(p.y * s.z, 0.0, 1.0), p.z);
}

// Algorithm 4 for one light (render::material::Diffraction::shade_light):
// (1 - w_d) c_diffraction + (1 - alpha) c_texture + w_d c_texture, k = [scale_ru, w_diffuse, ambient, fresnel_n].
// A light of solid angle omega > 0 (an area light, a cell of the environment) sees the lobe averaged over it
// (the prefiltered tables at pref, render::material::Diffraction::xyz_filtered).
// render::lobe_albedo::LobeAlbedo (the energy blend): A(omega) as linear sRGB at ALBEDO_COS midpoints in cos
// theta x ALBEDO_AZ azimuths from t, then A_avg, at `base` in `tables`.
const ALBEDO_COS: u32 = 10u;
const ALBEDO_AZ: u32 = 16u;

fn albedo_node(base: u32, c: u32, a: u32) -> vec3<f32> {
    let q = base + 3u * (c * ALBEDO_AZ + a);
    return vec3<f32>(tables[q], tables[q + 1u], tables[q + 2u]);
}

// A for a local direction (z the normal), bilinear, periodic in azimuth (LobeAlbedo::at).
fn lobe_albedo(base: u32, l: vec3<f32>) -> vec3<f32> {
    let fc = clamp(clamp(l.z, 0.0, 1.0) * f32(ALBEDO_COS) - 0.5, 0.0, f32(ALBEDO_COS - 1u));
    let c0 = u32(floor(fc));
    let tc = fc - floor(fc);
    let c1 = min(c0 + 1u, ALBEDO_COS - 1u);
    let a = euclid(atan2(l.y, l.x), TAU) / TAU * f32(ALBEDO_AZ);
    let ta = a - floor(a);
    let a0 = u32(floor(a)) % ALBEDO_AZ;
    let a1 = (a0 + 1u) % ALBEDO_AZ;
    let lo = mix(albedo_node(base, c0, a0), albedo_node(base, c0, a1), ta);
    let hi = mix(albedo_node(base, c1, a0), albedo_node(base, c1, a1), ta);
    return mix(lo, hi, tc);
}

// The texture's share under the energy blend, (1 - A(wi))(1 - A(wo)) / (1 - A_avg) (LobeAlbedo::diffuse_share).
fn energy_share(base: u32, li: vec3<f32>, lo: vec3<f32>) -> vec3<f32> {
    let q = base + 3u * ALBEDO_COS * ALBEDO_AZ;
    let rest = vec3<f32>(1.0) - vec3<f32>(tables[q], tables[q + 1u], tables[q + 2u]);
    let s = max(vec3<f32>(1.0) - lobe_albedo(base, li), vec3<f32>(0.0))
        * max(vec3<f32>(1.0) - lobe_albedo(base, lo), vec3<f32>(0.0));
    return select(s / max(rest, vec3<f32>(1e-9)), vec3<f32>(0.0), rest <= vec3<f32>(1e-9));
}

// One light on a diffraction material (render::material::Diffraction::shade_light_filtered): the lobe (averaged
// over the light's solid angle omega where the prefiltered tables exist) and the texture, blended by Algorithm 4
// or, with an albedo table (`albedo` != NONE), by the energy blend. `lobe_only`: a cell of the environment under
// the energy blend, whose texture takes the irradiance instead (Diffraction::shade_environment_light).
fn diffraction_light(table: Table, k: vec4<f32>, tex: vec3<f32>, t: vec3<f32>, b: vec3<f32>, n: vec3<f32>,
                     lo: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>, e: vec3<f32>, omega: f32, pref: u32,
                     albedo: u32, lobe_only: bool) -> vec3<f32> {
    let li = vec3<f32>(dot(wi, t), dot(wi, b), dot(wi, n));
    if (li.z <= 0.0 || lo.z <= 0.0) {
        return vec3<f32>(0.0);
    }
    var xyz = vec3<f32>(0.0);
    if (omega > 0.0 && pref != NONE) {
        xyz = lookup_shading(table, li, lo) * prefiltered_sum(table, pref, li, lo, omega);
    } else {
        xyz = lookup_xyz(table, li, lo);
    }
    let c_diff = to_rgb(xyz) * e * k.x;
    if (lobe_only) {
        return c_diff * (1.0 - k.y);
    }
    let c_tex = tex * e * li.z;
    var rest = vec3<f32>(0.0);
    if (albedo != NONE) {
        rest = c_tex * energy_share(albedo, li, lo);
    } else {
        let hv = safe_normalize(wi + wo);
        rest = c_tex * (1.0 - min(abs(schlick(k.w, dot(wi, hv))), 1.0));
    }
    return c_diff * (1.0 - k.y) + rest + c_tex * k.y;
}

// glTF's normalTexture (render::material::Microfacet::normal_at): rec = [texture, scale], NONE: none. The
// tangent-space normal 2 rgb - 1 (x, y times scale) in the frame (T, (N x T) w, N) replaces the shading normal,
// unless it faces away from the geometric normal or the hit has no tangent.
fn normal_mapped(h: Hit, rec: vec4<f32>) -> Hit {
    let tex = word(rec.x);
    if (tex == NONE || dot(h.tangent, h.tangent) == 0.0) {
        return h;
    }
    let s = sample_texture(tex, h.uv, false);
    let x = (2.0 * s.x - 1.0) * rec.y;
    let y = (2.0 * s.y - 1.0) * rec.y;
    let z = 2.0 * s.z - 1.0;
    let b = cross(h.n, h.tangent) * h.tsign;
    let n = safe_normalize(h.tangent * x + b * y + h.n * z);
    if (dot(n, n) == 0.0 || dot(n, h.ng) <= 0.0) {
        return h;
    }
    return Hit(h.t, h.p, n, h.ng, h.uv, orthogonalize(h.tangent, n), h.along, h.material, h.tsign);
}

fn shade(h_in: Hit, d: vec3<f32>, depth: u32, weight: f32, thr: vec3<f32>) {
    let wo = -d;
    let r = P.mat_base + 8u * h_in.material;
    let kind = word(scene[r].x);
    // A microfacet's records, or a film's base's: [colour], [roughness, metallic, ior, metallic-roughness
    // texture], [normal texture] from `mrec` (NONE: none). Its normal texture replaces the shading normal first.
    // Each texture is read at one place for every kind (normal, metallic-roughness, colour), as the compiled
    // shader inlines every call.
    var mrec = NONE;
    if (kind == 1u) {
        mrec = r + 1u;
    }
    if (kind == 3u && (word(scene[r + 1u].w) & 4u) != 0u) {
        mrec = r + 3u;
    }
    var h = h_in;
    var m = Microfacet(vec4<f32>(0.0), 1.0, 0.0, 1.0);
    var color = scene[r + 1u];  // a Lambertian's colour, a diffraction's texture colour
    if (mrec != NONE) {
        h = normal_mapped(h_in, scene[mrec + 2u]);
        m = microfacet_at(mrec, h.uv);
        color = m.color;
    }
    var albedo = vec3<f32>(0.0);
    if (kind != 3u || mrec != NONE) {
        albedo = color_at(color, h.uv);
    }
    // Each kind makes its surface, and one call below shades it, by Monte Carlo or the fast path (one copy of
    // each in the compiled shader, which inlines every call). A film alone is a mirror and shades here.
    let mc = monte_carlo();
    var s = surf_lambert(h.n, vec3<f32>(0.0));
    var ambient = vec3<f32>(0.0);
    if (kind == 0u) {
        s = surf_lambert(h.n, albedo);
    } else if (kind == 1u) {
        s = surf_microfacet(m, h.n, albedo, clamp(dot(h.n, wo), 0.0, 1.0));
    } else if (kind == 2u) {
        // Diffraction: [kind], texture colour, [scale_ru, w_diffuse, ambient, fresnel_n],
        // [direction, rule], [angle, orientation texture], table words, table numbers,
        // [lobe distributions, prefiltered tables, energy blend's albedo table] in `tables` (NONE: none).
        let k = scene[r + 2u];
        let od = scene[r + 3u];
        let oa = scene[r + 4u];
        let tw = scene[r + 5u];
        let tf = scene[r + 6u];
        let ext = scene[r + 7u];
        let table = Table(word(tw.x), word(tw.y), word(tw.z), word(tw.w), tf.x, tf.y, tf.z, tf.w);
        let t = orientation(h, word(od.w), od.xyz, word(oa.y), oa.x);
        let tex = albedo;
        s = surf_basic(3u, h.n, tex, Microfacet(vec4<f32>(0.0), 1.0, 0.0, 1.0), 0.0);
        s.table = table;
        s.dk = k;
        s.t = t;
        s.b = cross(h.n, t);
        s.tex = tex;
        s.lobe = word(ext.x);
        s.albedo_table = word(ext.z);
        s.pref = word(ext.y);
        ambient = tex * k.z;
    } else {
        // Thin film: [kind], [n_media, media, thickness, flags: 1 SVT, 2 transmission, 4 base, 8 colour table,
        // 16 rough], [SVT texture, d_rel, factor, media of the film over a metallic base's metal (NONE: none)],
        // then a base's three records (colour, [roughness, metallic, ior], normal texture) or a rough film's
        // tables (four records, scene.rs), and a colour table's [first node, cos nodes, offset nodes] and [first
        // offset, last offset] at r + 6, r + 7.
        let fw = scene[r + 1u];
        let sv = scene[r + 2u];
        let flags = word(fw.w);
        let factor = sv.z;
        let cosv = clamp(dot(h.n, wo), 0.0, 1.0);
        var offset = 0.0;
        if ((flags & 1u) != 0u) {
            let alpha = sample_texture(word(sv.x), h.uv, false).x;
            offset = sv.y * (alpha / 0.5 - 1.0);
        }
        if ((flags & 16u) != 0u) {
            // Rough films from their tables. Monte Carlo: the diffuse lobe pi k_d cos theta_l as a surface
            // (render::integrate::Surface::RoughDiffuse) for every light and the BRDF's samples, k_r along the
            // mirror as in the fast path.
            if (mc) {
                rough_mirror(rough_tab(r), h, wo, cosv, offset, factor, depth, weight, thr);
            }
            s.kind = 4u;
            s.rough = r;
            s.offset = offset;
            s.factor = factor;
        } else {
            let film = Film(word(fw.x), P.n_lambda, word(fw.y), word(fw.z));
            let tw = scene[r + 6u];
            let to = scene[r + 7u];
            let tab = FilmTab(word(tw.x), word(tw.y), word(tw.z), to.x, to.y);
            let tabbed = (flags & 8u) != 0u;
            let c = film_colors(film, tabbed, tab, cosv, offset);
            if ((flags & 4u) == 0u) {
                // A film alone: a mirror (and a window), whose rays are traced -- the reflected ray, then the
                // transmitted one, through one push (one copy in the compiled shader).
                let n_out = select(1u, 2u, (flags & 2u) != 0u);
                for (var k = 0u; k < n_out; k = k + 1u) {
                    var side = h.ng;
                    var dir = reflect_dir(wo, h.n);
                    var xyz = c.r;
                    if (k == 1u) {
                        side = -h.ng;
                        dir = d;
                        xyz = c.t;
                    }
                    let rgb = to_rgb(xyz) * factor;
                    push_ray(h.p + side * eps(h.p, h.t), dir, thr * rgb, depth + 1u, weight * max3(rgb));
                }
                return;
            }
            // The film over the base and the base alone, mixed by the factor, as one BRDF for every light (over a
            // metallic base, the metal stack's reflectance).
            s = surf_film(film, m, h.n, albedo, offset, factor, to_rgb(c.r), word(sv.w));
            s.tabbed = tabbed;
            s.tab = tab;
        }
    }
    if (mc) {
        shade_mc(h, s, wo, depth, weight, thr, ambient);
    } else {
        shade_fast(h, s, wo, depth, weight, thr);
    }
}

// The specular reflectance of a film over a base of metallic m: (1 - m) R over the dielectric + m R over the
// metal (media block `metal`, NONE: the dielectric's alone), from the dielectric's R (linear sRGB).
fn film_specular(film: Film, metal: u32, m: f32, sin_t: f32, cos_t: f32, offset: f32, r_dielectric: vec3<f32>)
        -> vec3<f32> {
    if (metal == NONE || m <= 0.0) {
        return r_dielectric;
    }
    let over_metal = Film(film.n_media, film.n_lambda, metal, film.thickness);
    return (1.0 - m) * r_dielectric + m * to_rgb(film_xyz(over_metal, sin_t, cos_t, offset).r);
}

// A smooth film's colours at cos theta and an offset: from its colour table where it has one (the fast path),
// else the recurrence at every wavelength sample.
fn film_colors(film: Film, tabbed: bool, tab: FilmTab, cos_t: f32, offset: f32) -> FilmXyz {
    if (tabbed) {
        return film_table_xyz(tab, cos_t, offset);
    }
    return film_xyz(film, sqrt(max(1.0 - cos_t * cos_t, 0.0)), cos_t, offset);
}

// A rough film's tables from its material record `r` (scene.rs).
fn rough_tab(r: u32) -> RoughTab {
    let a = scene[r + 3u];
    let b = scene[r + 4u];
    let c = scene[r + 5u];
    let e = scene[r + 6u];
    let sizes = word(a.w);
    return RoughTab(word(a.x), word(a.y), word(a.z), sizes & 0xffffu, sizes >> 16u, word(b.x), word(b.y), word(b.z),
                    c.x, c.y, c.z, c.w, e.x, e.y);
}

// The specular part of a rough film, k_r along the mirror ray (both paths).
fn rough_mirror(t: RoughTab, h: Hit, wo: vec3<f32>, cosv: f32, offset: f32, factor: f32, depth: u32, weight: f32,
                thr: vec3<f32>) {
    let s = to_rgb(rough_specular(t, cosv, offset)) * factor;
    push_ray(h.p + h.ng * eps(h.p, h.t), reflect_dir(wo, h.n), thr * s, depth + 1u, weight * max3(s));
}

// The fast path (render::render::Scene::shade) at a hit whose surface is s (every kind but a film alone): the
// directional and point lights and each area light from its centre, shadowed -- on a diffraction material also
// the environment as ENV_LIGHTS directional lights, unshadowed like the irradiance map (render.rs) -- then the
// environment. One loop over the lights serves every kind, so that the compiled shader (which inlines every call)
// holds one shadow ray and one copy of each kind's BRDF, not one of each per kind. A film over a base of factor
// < 1 is also its base alone (weight 1 - factor): its lights sum in `lobe` beside the film's in `out`.
fn shade_fast(h: Hit, s: Surf, wo: vec3<f32>, depth: u32, weight: f32, thr: vec3<f32>) {
    let o = h.p + h.ng * eps(h.p, h.t);
    let irr = irradiance(h.n);
    let cosv = clamp(dot(h.n, wo), 0.0, 1.0);
    // The microfacet lobe (a microfacet material, a film's base alone) and the film over its base.
    let with_lobe = s.kind == 1u || (s.kind == 2u && s.factor < 1.0);
    let with_film = s.kind == 2u && s.factor > 0.0;
    var lobe = vec3<f32>(0.0);
    var out = vec3<f32>(0.0);
    if (s.kind == 0u) {
        out = s.albedo * irr;
    } else if (s.kind == 3u) {
        out = s.tex * s.dk.z;
    }
    let diffuse = s.albedo * (1.0 - s.m.metallic);  // under a film: the base's diffuse albedo
    let lo = vec3<f32>(dot(wo, s.t), dot(wo, s.b), dot(wo, h.n));  // diffraction: wo in the nanostructure's frame
    var rt: RoughTab;
    if (s.kind == 4u) {
        rt = rough_tab(s.rough);
    }
    let n_lit = n_arrivals();
    var n_env = 0u;
    if (s.kind == 3u && P.env_light_base != NONE) {
        n_env = ENV_LIGHTS;
    }
    for (var i = 0u; i < n_lit + n_env; i = i + 1u) {
        // render::light::ENVIRONMENT_LIGHT_SPREAD (4): an environment light's lobe is averaged over four cells.
        var l = Arrival(vec3<f32>(0.0, 0.0, 1.0), FAR, vec3<f32>(0.0), 4.0 * 4.0 * PI / f32(ENV_LIGHTS));
        if (i < n_lit) {
            l = arrive(i, h.p);
            if (!(max3(l.e) > 0.0 && dot(l.wi, h.ng) > 0.0) || occluded(o, l.wi, l.dist)) {
                continue;
            }
        } else {
            let q = P.env_light_base + 6u * (i - n_lit);
            l.wi = vec3<f32>(tables[q], tables[q + 1u], tables[q + 2u]);
            if (dot(l.wi, h.ng) <= 0.0) {
                continue;
            }
            l.e = vec3<f32>(tables[q + 3u], tables[q + 4u], tables[q + 5u]);
        }
        if (s.kind == 0u) {
            out = out + s.albedo * l.e * max(dot(h.n, l.wi), 0.0);
        }
        if (with_lobe) {
            lobe = lobe + microfacet_reflect(s.m, h.n, l.wi, wo, s.albedo) * l.e;
        }
        if (with_film) {
            // The film's reflectance R replaces the base's specular Fresnel (over a metallic base mixed with the
            // film over the metal), the diffuse takes 1 - R per channel (Scene::shade_film_over_base).
            let vh = clamp(dot(l.wi, safe_normalize(l.wi + wo)), 0.0, 1.0);
            let sh = sqrt(max(1.0 - vh * vh, 0.0));
            let rl = to_rgb(film_colors(s.film, s.tabbed, s.tab, vh, s.offset).r);
            let spec = film_specular(s.film, s.metal, s.m.metallic, sh, vh, s.offset, rl);
            let ci = max(dot(h.n, l.wi), 0.0);
            out = out + l.e * (ggx_single(s.m, h.n, l.wi, wo) * spec + (vec3<f32>(1.0) - rl) * diffuse * ci);
        }
        if (s.kind == 3u) {
            out = out + diffraction_light(s.table, s.dk, s.tex, s.t, s.b, h.n, lo, l.wi, wo, l.e, l.omega, s.pref,
                                          s.albedo_table, s.albedo_table != NONE && i >= n_lit);
        }
        if (s.kind == 4u) {
            // A rough film (eq. 3.20): the lights' diffuse pi k_d cos theta_l from its tables.
            let cl = dot(h.n, l.wi);
            let d = rough_diffuse(rt, cosv, cl, relative_azimuth(h.n, l.wi, wo), s.offset);
            out = out + to_rgb(d) * l.e * (max(cl, 0.0) * s.factor);
        }
    }
    // Environment light on the microfacet lobe, then on the film: the diffuse share lit by the irradiance around
    // the normal, the specular share by the mirror direction blurred towards the irradiance around it with
    // roughness, a ray along it when smooth enough. One pass each through one copy of the mirror's code.
    for (var part = 0u; part < 2u; part = part + 1u) {
        var acc = vec3<f32>(0.0);  // the lights and the diffuse share
        var spec = vec3<f32>(0.0);
        var t = thr;
        var w = weight;
        var trace = true;
        if (part == 0u) {
            if (!with_lobe) {
                continue;
            }
            if (s.kind == 2u) {
                t = thr * (1.0 - s.factor);
                w = weight * (1.0 - s.factor);
            }
            let ew = env_weights(s.m, cosv, s.albedo);
            acc = lobe + ew.diffuse * irr;
            spec = ew.spec;
            trace = depth < P.max_depth;
        } else {
            if (!with_film) {
                continue;
            }
            // The film's diffuse takes 1 - R of the irradiance; its specular R (over the metal too).
            t = thr * s.factor;
            w = weight * s.factor;
            acc = out + (vec3<f32>(1.0) - s.r_view) * diffuse * irr;
            spec = film_specular(s.film, s.metal, s.m.metallic, sqrt(max(1.0 - cosv * cosv, 0.0)), cosv, s.offset,
                                 s.r_view);
        }
        let dir = reflect_dir(wo, h.n);
        let blurred = irradiance(dir);
        let rough = min(s.m.roughness / 0.6, 1.0);
        if (s.m.roughness < 0.6 && trace) {
            push_ray(o, dir, t * spec * (1.0 - rough), depth + 1u, w * max3(spec));
            acc = acc + spec * blurred * rough;
        } else {
            acc = acc + spec * blurred;
        }
        radiance = radiance + t * acc;
    }
    if (s.kind == 3u && s.albedo_table != NONE && lo.z > 0.0) {
        // The energy blend's texture takes (1 - A(wo)) of the irradiance around the normal
        // (Diffraction::environment_diffuse).
        let share = max(vec3<f32>(1.0) - lobe_albedo(s.albedo_table, lo), vec3<f32>(0.0));
        out = out + s.tex * irr * ((1.0 - s.dk.y) * share + s.dk.y);
    }
    if (s.kind == 4u) {
        // A rough film's environment: its diffuse albedo times the irradiance, and k_r along the mirror ray.
        out = out + to_rgb(rough_env(rt, cosv, s.offset)) * irr * s.factor;
    }
    if (s.kind == 0u || s.kind == 3u || s.kind == 4u) {
        radiance = radiance + thr * out;
    }
    if (s.kind == 4u) {
        rough_mirror(rt, h, wo, cosv, s.offset, s.factor, depth, weight, thr);
    }
}

// Radiance (linear sRGB, RU) along a camera ray, its reflections and transmissions. The camera ray is the
// first ray of the stack, so that `shade` has one call site (the compiled shader inlines every call).
fn primary(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    radiance = vec3<f32>(0.0);
    rays[0] = Ray(o, d, vec3<f32>(1.0), 0u, 1.0, 0.0);
    n_rays = 1u;
    var camera = true;
    while (n_rays > 0u) {
        n_rays = n_rays - 1u;
        let ray = rays[n_rays];
        let first = camera;
        camera = false;
        // A ray past max_depth or too weak to matter takes the environment's radiance as a ray that meets nothing
        // does (below: one place for both, the compiled shader inlining every call).
        let cut = !first && (ray.depth > P.max_depth || ray.weight < 2e-3);
        var h = Prim(FAR, 0u, 0u, 0.0, 0.0);
        if (!cut) {
            h = intersect(ray.o, ray.d, FAR);
            // The area lights the camera sees; in Monte Carlo, those secondary rays meet too (weighted against
            // light sampling when a BRDF sampled the ray) -- the fast path lights surfaces by them directly.
            if (first || monte_carlo()) {
                let l = hit_area(ray.o, ray.d, h.t, first);
                if (l.k != NONE) {
                    let w = brdf_weight(ray.pdf, area_pdf(l.k, ray.o, ray.d));
                    radiance = radiance + ray.throughput * area_radiance(l.k) * w;
                    continue;
                }
            }
        }
        if (h.kind == 0u) {
            if (first && P.env_visible == 0u) {
                radiance = P.background.xyz;
            } else {
                // The camera ray's pdf is 0: its `escaped` is the environment's radiance itself (weight 1).
                let e = escaped(ray.d, ray.pdf);
                if (first) {
                    radiance = e;
                } else {
                    radiance = radiance + ray.throughput * e;
                }
            }
            continue;
        }
        shade(make_hit(h, ray.o, ray.d), ray.d, ray.depth, ray.weight, ray.throughput);
    }
    return radiance;
}

// ------------------------------------------------------------------ cameras (render::camera)

struct CamRay {
    o: vec3<f32>,
    d: vec3<f32>,
    ok: bool,
}

fn camera_ray(x: f32, y: f32, aspect: f32) -> CamRay {
    let kind = word(P.cam_pos.w);
    let f = P.cam_fwd.xyz;
    let r = P.cam_right.xyz;
    let u = P.cam_up.xyz;
    let s = P.cam_fwd.w;
    if (kind == 0u) {
        return CamRay(P.cam_pos.xyz, normalize(f + r * (x * aspect * s) + u * (y * s)), true);
    }
    if (kind == 1u) {
        return CamRay(P.cam_pos.xyz + r * (x * aspect * s) + u * (y * s), f, true);
    }
    let r2 = x * x + y * y;
    if (r2 >= 1.0) {
        return CamRay(vec3<f32>(0.0), vec3<f32>(0.0), false);
    }
    let v = r * x + u * y + f * sqrt(1.0 - r2);
    return CamRay(P.cam_pos.xyz + v * s, -v, true);
}

@compute @workgroup_size(8, 8, 1)
fn render_scene(@builtin(global_invocation_id) id: vec3<u32>) {
    let col = id.x;
    let row = P.row0 + id.y;
    if (col >= P.width || row >= P.height) {
        return;
    }
    let aspect = f32(P.width) / f32(P.height);
    let idx = row * P.width + col;
    var acc = vec3<f32>(0.0);
    // Samples sample0 .. sample0 + pass_samples of the pixel's P.spp (progressive accumulation).
    for (var s = P.sample0; s < P.sample0 + P.pass_samples; s = s + 1u) {
        seed_rng(idx, s);
        let j = scene[P.sample_base + s % P.spp].xy;
        let x = -1.0 + 2.0 * (f32(col) + j.x) / f32(P.width);
        let y = 1.0 - 2.0 * (f32(row) + j.y) / f32(P.height);
        let ray = camera_ray(x, y, aspect);
        if (ray.ok) {
            acc = acc + primary(ray.o, ray.d);
        }
    }
    // The running mean of every sample so far.
    var rgb = acc / f32(P.pass_samples);
    if (P.sample0 > 0u) {
        rgb = (out_rgb[idx].xyz * f32(P.sample0) + acc) / f32(P.sample0 + P.pass_samples);
    }
    out_rgb[idx] = vec4<f32>(rgb, 1.0);
    out_rgba[idx] = display_rgb(rgb, D);
}
