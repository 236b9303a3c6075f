//! What the GPU test files share: the adapter, or a skip when the user asked for one; and how far apart two
//! images look. The example `extended_light` includes this file too.
#![allow(dead_code)] // each user takes its subset

use iridis_gpu::Gpu;
use iridis_render::Image;
use iridis_thinfilm::accuracy::DeltaEStats;

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

/// One scene test at a time, across every file of the test binary: several scene renderers on lavapipe at once
/// (one device each) were seen to stop making progress (0 % CPU for minutes, 2026-11-23), while each runs to
/// completion alone.
pub fn one_scene_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    static SERIAL: std::sync::Mutex<()> = std::sync::Mutex::new(());
    SERIAL.lock().unwrap_or_else(|e| e.into_inner())
}

/// The per-pixel CIEDE2000 between two images as displayed (linear sRGB scaled by `exposure`, clipped to the
/// cube): the benches' one ΔE statistics (`iridis_thinfilm::accuracy::DeltaEStats`).
pub fn image_delta_e(a: &Image, b: &Image, exposure: f64) -> DeltaEStats {
    DeltaEStats::between(&a.to_xyz(), &b.to_xyz(), exposure)
}

/// Mean and 99th percentile of [`image_delta_e`] at exposure 1; a pixel that is not a finite number fails (the
/// display would show it black).
pub fn delta_e(a: &Image, b: &Image) -> (f64, f64) {
    assert!(a.data.iter().chain(&b.data).flatten().all(|c| c.is_finite()), "a pixel is not a finite number");
    let s = image_delta_e(a, b, 1.0);
    (s.mean, s.p99)
}
