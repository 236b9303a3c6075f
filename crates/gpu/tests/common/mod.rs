//! What the GPU test files share: the adapter, or a skip when the user asked for one.

use iridis_gpu::Gpu;

/// The adapter, opened once per test process and shared by its tests (or `None` when `IRIDIS_SKIP_GPU=1` says to
/// skip; without either, a failure with the driver hint). One device means one compilation of each pipeline per
/// process: on lavapipe the scene shader takes minutes, and tests running in parallel on devices of their own
/// each compiled it at the same time.
pub fn gpu() -> Option<&'static Gpu> {
    static GPU: std::sync::OnceLock<Option<Gpu>> = std::sync::OnceLock::new();
    GPU.get_or_init(|| match Gpu::new() {
        Ok(g) => {
            eprintln!("adapter: {}", g.adapter_name());
            Some(g)
        }
        Err(e) if std::env::var("IRIDIS_SKIP_GPU").as_deref() == Ok("1") => {
            eprintln!("GPU test skipped (IRIDIS_SKIP_GPU=1): {e}");
            None
        }
        Err(e) => panic!("{e}\nThe GPU tests need a Vulkan adapter; set IRIDIS_SKIP_GPU=1 to skip them."),
    })
    .as_ref()
}
