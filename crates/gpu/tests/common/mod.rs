//! What the GPU test files share: the adapter, or a skip when the user asked for one.

use iridis_gpu::Gpu;

/// The adapter, or `None` when `IRIDIS_SKIP_GPU=1` says to skip; without either, a failure with the driver hint.
pub fn gpu() -> Option<Gpu> {
    match Gpu::new() {
        Ok(g) => {
            eprintln!("adapter: {}", g.adapter_name());
            Some(g)
        }
        Err(e) if std::env::var("IRIDIS_SKIP_GPU").as_deref() == Ok("1") => {
            eprintln!("GPU test skipped (IRIDIS_SKIP_GPU=1): {e}");
            None
        }
        Err(e) => panic!("{e}\nThe GPU tests need a Vulkan adapter; set IRIDIS_SKIP_GPU=1 to skip them."),
    }
}
