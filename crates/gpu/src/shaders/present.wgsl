// The viewer's present pass: the displayed 8-bit pixels that a frame shader packed with pack4x8unorm
// (`out_rgba`, row-major) stored into the texture that egui draws, on the GPU, so that no frame is copied to
// the CPU. The texture's format is rgba8unorm for the store; egui samples it through an rgba8unorm-srgb view,
// which decodes the sRGB-encoded bytes as egui's own textures do.

@group(0) @binding(0) var<storage, read> packed: array<u32>;
@group(0) @binding(1) var frame: texture_storage_2d<rgba8unorm, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(frame);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let c = unpack4x8unorm(packed[id.y * size.x + id.x]);
    textureStore(frame, vec2<i32>(id.xy), vec4<f32>(c.rgb, 1.0));
}
