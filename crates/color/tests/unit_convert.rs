//! The unit tests of src/convert.rs, moved here so that `cargo test` compiles the library once.

use iridis_color::convert::*;

#[test]
fn matrix_agrees_with_the_printed_inverse() {
    let printed = [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]];
    for r in 0..3 {
        for c in 0..3 {
            assert!((XYZ_TO_SRGB[r][c] - printed[r][c]).abs() < 6e-4);
        }
    }
    // D65 white maps to RGB (1, 1, 1) to the matrix's precision.
    let w = Xyy { x: D65_XY.0, y: D65_XY.1, big_y: 1.0 }.to_xyz().to_linear_srgb();
    for c in w {
        assert!((c - 1.0).abs() < 1e-3, "{w:?}");
    }
}

#[test]
fn transfer_curve_is_continuous_and_inverts() {
    for i in 0..=1000 {
        let v = i as f64 / 1000.0;
        assert!((srgb_decode(srgb_encode(v)) - v).abs() < 1e-14);
        assert!((gamma_decode(gamma_encode(v, 2.2), 2.2) - v).abs() < 1e-14);
    }
    assert!((srgb_encode(1.0) - 1.0).abs() < 1e-15);
    // Both branches meet at the breakpoint (to the standard's rounding).
    let b = 0.003_130_8;
    assert!((12.92 * b - (1.055 * f64::powf(b, 1.0 / 2.4) - 0.055)).abs() < 1e-6);
}
