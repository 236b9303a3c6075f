// BRDF maps with the lookup diffraction model (lookup_math.wgsl) from an f32 table: one map pixel per
// invocation (lookup_map.wgsl), the table's words read as f32.

// I[((iv * res + iu) * 3 + c) * np + p] (lookup_math.wgsl's accessor).
fn table_value(t: Table, iv: u32, dv: u32, off: u32) -> f32 {
    return bitcast<f32>(cell_word(iv, dv, off, t.np));
}

fn map_xyz(t: Table, wi: vec3<f32>, wr: vec3<f32>) -> vec3<f32> {
    return lookup_xyz(t, wi, wr);
}
