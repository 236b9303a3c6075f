//! The unit tests of src/report.rs (collected notes and warnings), moved here so that `cargo test` compiles the
//! library once.

use iridis_api::report::*;

#[test]
fn collect_keeps_lines_in_order_and_empties() {
    let c = Collect::default();
    c.note("a");
    c.warn("b");
    with_progress(&c, 3, "x", |p| p(2));
    assert_eq!(c.take(), vec![(Kind::Note, "a".to_string()), (Kind::Warning, "b".to_string())]);
    assert!(c.take().is_empty());
}
