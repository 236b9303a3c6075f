// The phase arithmetic of ground_truth.wgsl on given inputs (iridis_gpu::ground_truth::phase_accuracy):
// (cos, sin) of 2 pi (frac(alpha I) + x), alpha a 0.64 fixed-point turn, I a lattice index, x a height phase.

@group(0) @binding(0) var<storage, read> cases: array<vec4<u32>>; // (alpha low, alpha high, I, bitcast x)
@group(0) @binding(1) var<storage, read_write> result: array<vec2<f32>>;

@compute @workgroup_size(64, 1, 1)
fn check(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= arrayLength(&cases)) {
        return;
    }
    let c = cases[id.x];
    result[id.x] = cis_turns(turns_times(c.xy, c.z) + turns_of(bitcast<f32>(c.w)));
}
