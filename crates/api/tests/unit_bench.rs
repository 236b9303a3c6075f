//! The unit tests of src/bench/mod.rs (the benchmarks' statistics), moved here so that `cargo test` compiles the
//! library once.

use iridis_api::bench::*;
use std::time::Duration;

#[test]
fn delta_e_statistics_rank_and_clip() {
    // Identical colours differ by nothing; colours both far above white are both shown white.
    let w = iridis_color::Xyz::from_linear_srgb([1.0, 1.0, 1.0]);
    let s = DeltaEStats::between(&[w.scale(3.0)], &[w.scale(5.0)], 1.0);
    assert!(s.max < 1e-9, "{s:?}");
    // 100 pairs: 99 equal, one black against white (ΔE00 = 100 between L* 0 and 100).
    let mut a = vec![w.scale(0.5); 100];
    let b = a.clone();
    a[7] = iridis_color::Xyz::from_linear_srgb([0.0, 0.0, 0.0]);
    let mut b2 = b;
    b2[7] = w;
    let s = DeltaEStats::between(&a, &b2, 1.0);
    assert!((s.max - 100.0).abs() < 0.01, "{s:?}");
    assert!((s.mean - s.max / 100.0).abs() < 1e-12);
    // Nearest rank: the 95th and 99th of 100 are the 95th and 99th smallest, both 0 here (one pair in 100 is
    // the 100th percentile, the maximum).
    assert_eq!((s.p95, s.p99, s.count), (0.0, 0.0, 100));
}

#[test]
fn frame_statistics_nearest_rank() {
    let t: Vec<Duration> = (1..=200).map(Duration::from_millis).collect();
    let s = FrameStats::of(&t);
    assert_eq!((s.min, s.median, s.p99), (1.0, 100.0, 198.0));
    assert!((s.mean - 100.5).abs() < 1e-9);
}

#[test]
fn samples_spread_and_disk() {
    assert_eq!(sample(10, 3), vec![0, 4, 8]);
    // The disk of a map covers about π/4 of it.
    let n = disk_pixels(64).len() as f64 / (64.0 * 64.0);
    assert!((n - std::f64::consts::FRAC_PI_4).abs() < 0.02, "{n}");
}

/// `bench gpu SCENE` refuses the shaders' options set away from their defaults, so the command line's defaults
/// (clap attributes) must be the library's (`GpuBenchOptions::default`, which Python starts from).
#[cfg(feature = "cli")]
#[test]
fn the_gpu_benchs_command_line_defaults_are_the_librarys() {
    use clap::{Args, FromArgMatches};
    use iridis_api::bench::gpu::GpuBenchOptions;
    let m = GpuBenchOptions::augment_args(clap::Command::new("gpu")).try_get_matches_from(["gpu"]).unwrap();
    let cli = GpuBenchOptions::from_arg_matches(&m).unwrap();
    assert_eq!(format!("{cli:?}"), format!("{:?}", GpuBenchOptions::default()));
}
