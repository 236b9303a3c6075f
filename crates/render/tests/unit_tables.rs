//! The unit tests of src/tables.rs, moved here so that `cargo test` compiles the library once.

use iridis_diffraction::table::TableParams;
use iridis_diffraction::Units;
use iridis_render::tables::*;

/// The key changes with each thing that changes the table's content, and only with those.
#[test]
fn builtin_key_follows_the_content() {
    let p = TableParams { uv_resolution: 201, uv_power: 5.0 };
    let k = builtin_key("elaphe", "fnv1a64:0123456789abcdef", p, 30, Units::Relative);
    assert_eq!(k, builtin_key("elaphe", "fnv1a64:0123456789abcdef", p, 30, Units::Relative));
    assert!(k.starts_with("elaphe-"));
    for other in [
        builtin_key("elaphe", "fnv1a64:0123456789abcdee", p, 30, Units::Relative),
        builtin_key("elaphe", "fnv1a64:0123456789abcdef", TableParams { uv_resolution: 202, ..p }, 30, Units::Relative),
        builtin_key("elaphe", "fnv1a64:0123456789abcdef", TableParams { uv_power: 4.0, ..p }, 30, Units::Relative),
        builtin_key("elaphe", "fnv1a64:0123456789abcdef", p, 31, Units::Relative),
        builtin_key("elaphe", "fnv1a64:0123456789abcdef", p, 30, Units::Radiometric),
    ] {
        assert_ne!(k, other);
    }
}

/// A changed generator makes another height field, hence another fingerprint and key: two built-ins
/// stand in for "before" and "after" a change of the generator.
#[test]
fn a_changed_height_field_gets_a_new_key() {
    let p = TableParams { uv_resolution: 31, uv_power: 5.0 };
    let (a, b) = (builtin_patch("sine").unwrap(), builtin_patch("blazed").unwrap());
    assert_ne!(a.fingerprint(), b.fingerprint());
    assert_ne!(
        builtin_key("x", &a.fingerprint(), p, 10, Units::Relative),
        builtin_key("x", &b.fingerprint(), p, 10, Units::Relative)
    );
}
