//! The unit tests of src/grating_bench.rs (the grating benchmark's options and its peer), moved here so that
//! `cargo test` compiles the library once.

use iridis_api::grating_bench::*;
use serde_json::json;

#[test]
fn bad_options_are_refused_with_the_flag_named() {
    let q = iridis_api::Quiet;
    for (opts, flag) in [
        (GratingBenchOptions { repeats: 0, ..Default::default() }, "--repeats 0"),
        (GratingBenchOptions { peer_seconds: f64::NAN, ..Default::default() }, "--peer-seconds"),
        (GratingBenchOptions { batch: 0, ..Default::default() }, "--batch 0"),
    ] {
        let e = bench_grating(&opts, &q).unwrap_err().to_string();
        assert!(e.contains(flag), "{e}");
    }
}

#[test]
fn a_missing_python_is_a_note_not_an_error() {
    let note = run_grcwa("/nonexistent/python3", &json!({}), true).unwrap_err();
    assert!(note.contains("/nonexistent/python3 not found") && note.contains("grcwa not timed"), "{note}");
}
