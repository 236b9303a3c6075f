//! The unit tests of src/scene.rs, moved here so that `cargo test` compiles the library once.

use iridis_gpu::scene::*;

#[test]
fn params_fill_the_uniform_exactly() {
    // 12 vec4 then 32 u32 = 80 words = 320 bytes, a multiple of 16 as a uniform needs.
    assert_eq!(PARAM_WORDS * 4 % 16, 0);
    assert_eq!(PARAM_WORDS, 80);
}
