// Rough films (the LSRS model, Sussenbach sec. 3.2, Algorithm 2) from colour tables made on the CPU
// (iridis_thinfilm::rough_table::RoughColorTable, and the diffuse albedo of
// iridis_render::material::ThinFilm::rough_env_table): k_r XYZ over [offset][theta_v], pi k_d XYZ over
// [offset][azimuth][theta_l][theta_v] (angles uniform over 0-90 degrees, azimuth over 0-pi), the diffuse
// albedo over [cos theta_v][offset]. One vec4 (xyz) per node through the hook film_table_node (film_math.wgsl).

struct RoughTab {
    spec: u32,      // first node of k_r
    diffuse: u32,   // first node of pi k_d
    env: u32,       // first node of the diffuse albedo
    angles: u32,
    azimuths: u32,
    offsets: u32,
    env_cos: u32,   // nodes of the albedo's cos theta_v axis (uniform on [env_c0, env_c1])
    env_off: u32,   // and of its offset axis (uniform on [env_o0, env_o1])
    o0: f32,        // offsets of the k_r and k_d tables' first and last node
    o1: f32,
    env_o0: f32,
    env_o1: f32,
    env_c0: f32,
    env_c1: f32,
}

struct NodeCell {
    i: u32,
    j: u32,   // the next node (i itself on a one-node axis)
    t: f32,
}

// The cell of x on n uniform nodes over [a, b], clamped.
fn uniform_cell(x: f32, a: f32, b: f32, n: u32) -> NodeCell {
    if (n < 2u || b <= a) {
        return NodeCell(0u, 0u, 0.0);
    }
    let u = clamp((x - a) / (b - a), 0.0, 1.0) * f32(n - 1u);
    let i = min(u32(u), n - 2u);
    return NodeCell(i, i + 1u, u - f32(i));
}

// k_r XYZ at the view angle's cosine and a thickness offset (RoughColorTable::specular_at).
fn rough_specular(t: RoughTab, cos_v: f32, offset: f32) -> vec3<f32> {
    let v = uniform_cell(acos(clamp(cos_v, 0.0, 1.0)), 0.0, 0.5 * PI, t.angles);
    let o = uniform_cell(offset, t.o0, t.o1, t.offsets);
    let a = mix(film_table_node(t.spec + o.i * t.angles + v.i), film_table_node(t.spec + o.i * t.angles + v.j), v.t);
    let b = mix(film_table_node(t.spec + o.j * t.angles + v.i), film_table_node(t.spec + o.j * t.angles + v.j), v.t);
    return mix(a, b, o.t).xyz;
}

// pi k_d XYZ at the view and light cosines, their relative azimuth in [0, pi] and an offset
// (RoughColorTable::diffuse_at); zero for light below the surface.
fn rough_diffuse(t: RoughTab, cos_v: f32, cos_l: f32, azimuth: f32, offset: f32) -> vec3<f32> {
    if (cos_l <= 0.0) {
        return vec3<f32>(0.0);
    }
    let v = uniform_cell(acos(clamp(cos_v, 0.0, 1.0)), 0.0, 0.5 * PI, t.angles);
    let l = uniform_cell(acos(min(cos_l, 1.0)), 0.0, 0.5 * PI, t.angles);
    let a = uniform_cell(azimuth, 0.0, PI, t.azimuths);
    let o = uniform_cell(offset, t.o0, t.o1, t.offsets);
    let n = t.angles;
    var acc = vec3<f32>(0.0);
    for (var k = 0u; k < 16u; k = k + 1u) {
        let oj = select(o.i, o.j, (k & 8u) != 0u);
        let aj = select(a.i, a.j, (k & 4u) != 0u);
        let lj = select(l.i, l.j, (k & 2u) != 0u);
        let vj = select(v.i, v.j, (k & 1u) != 0u);
        let w = select(1.0 - o.t, o.t, (k & 8u) != 0u) * select(1.0 - a.t, a.t, (k & 4u) != 0u)
            * select(1.0 - l.t, l.t, (k & 2u) != 0u) * select(1.0 - v.t, v.t, (k & 1u) != 0u);
        acc = acc + w * film_table_node(t.diffuse + ((oj * t.azimuths + aj) * n + lj) * n + vj).xyz;
    }
    return acc;
}

// The diffuse albedo XYZ (ThinFilm::rough_env_diffuse): bilinear in (cos theta_v, offset), clamped.
fn rough_env(t: RoughTab, cos_v: f32, offset: f32) -> vec3<f32> {
    let c = uniform_cell(cos_v, t.env_c0, t.env_c1, t.env_cos);
    let o = uniform_cell(offset, t.env_o0, t.env_o1, t.env_off);
    let a = mix(film_table_node(t.env + c.i * t.env_off + o.i), film_table_node(t.env + c.i * t.env_off + o.j), o.t);
    let b = mix(film_table_node(t.env + c.j * t.env_off + o.i), film_table_node(t.env + c.j * t.env_off + o.j), o.t);
    return mix(a, b, c.t).xyz;
}

// The azimuth of wi relative to wo about n, in [0, pi] (render::material::relative_azimuth); pi where either
// lies along the normal.
fn relative_azimuth(n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let a = wi - n * dot(n, wi);
    let b = wo - n * dot(n, wo);
    if (length(a) < 1e-7 || length(b) < 1e-7) {
        return PI;
    }
    return acos(clamp(dot(normalize(a), normalize(b)), -1.0, 1.0));
}
