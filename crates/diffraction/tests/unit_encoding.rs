//! The unit tests of src/encoding.rs (table encodings: names, Chebyshev interpolation, half-float scale), moved here
//! so that `cargo test` compiles the library once.

use iridis_diffraction::encoding::*;

#[test]
fn names_round_trip_and_bad_names_say_what_works() {
    for e in [
        TableEncoding::F32,
        TableEncoding::F16,
        TableEncoding::Chebyshev { terms: 12, half: false },
        TableEncoding::Chebyshev { terms: 16, half: true },
    ] {
        assert_eq!(e.name().parse::<TableEncoding>().unwrap(), e);
    }
    for bad in ["f64", "cheb", "cheb1", "cheb999", "chebx-f16"] {
        let msg = bad.parse::<TableEncoding>().unwrap_err().to_string();
        assert!(msg.contains("f16") && msg.contains("chebK"), "{msg}");
    }
}

#[test]
fn chebyshev_interpolation_reproduces_a_polynomial_of_its_degree() {
    // 3 − 2t + 0.5t² − t³ at 4 nodes is exact: compare with Horner at arbitrary points.
    let p = [3.0, -2.0, 0.5, -1.0];
    let f = |t: f64| p.iter().rev().fold(0.0, |acc, c| acc * t + c);
    let a = chebyshev_coefficients(&chebyshev_nodes(4).iter().map(|&t| f(t)).collect::<Vec<_>>());
    for t in [-1.0, -0.3, 0.0, 0.77, 1.0] {
        assert!((clenshaw(&a, t) - f(t)).abs() < 1e-13, "t = {t}");
    }
}

#[test]
fn half_scale_is_a_power_of_two_that_keeps_the_maximum_below_the_half_range() {
    for max in [1e-30f32, 3.7e-5, 1.0, 2.0, 6.1e4, 1e30] {
        let s = half_scale(max);
        assert_eq!(s.log2().fract(), 0.0);
        let scaled = max / s;
        assert!((16384.0..=32768.0).contains(&scaled), "{max}: {scaled}");
    }
}
