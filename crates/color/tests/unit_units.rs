//! The unit tests of src/units.rs, moved here so that `cargo test` compiles the library once.

use iridis_color::units::*;

#[test]
fn values_print_as_written() {
    assert_eq!(degrees(parse_angle_rad("30deg").unwrap()), 30.0);
    assert_eq!(degrees(parse_angle_rad("29.5deg").unwrap()), 29.5);
    assert_eq!(tidy(6.4000000000000006e-6), 6.4e-6);
    assert_eq!(tidy(-0.1 - 0.2), -0.3);
    assert_eq!(format_length(1100.0), "1100nm");
    assert_eq!(format_length(6400.000000000001), "6.4um");
    assert_eq!(format_length(2500.0 * 6f64.to_radians().tan()), "262.761nm");
    assert_eq!(format_length(65e6), "65mm");
    assert_eq!(format_length(4000.0), "4000nm");
    assert_eq!(format_angle(parse_angle_rad("30deg").unwrap()), "30deg");
    assert_eq!(format_angle(0.0), "0deg");
}

#[test]
fn messages_say_what_to_write() {
    // An angle takes "an"; a length "a".
    assert!(parse_angle_rad("30").unwrap_err().0.contains("write an angle with a unit"));
    assert!(parse_length_nm("30").unwrap_err().0.contains("write a length with a unit"));
    // nan and inf are numbers to Rust but not lengths: no 'nannm' suggestion.
    for s in ["nan", "inf", "-inf"] {
        let e = parse_length_nm(s).unwrap_err().0;
        assert!(!e.contains("nannm") && !e.contains("infnm") && e.contains("finite") && e.contains("65nm"), "{e}");
    }
    // A range's example is in the range's own quantity.
    assert!(parse_range("0deg:80deg", parse_angle_rad).unwrap_err().0.contains("e.g. 0deg:80deg:1deg"));
    assert!(parse_range("0nm", parse_length_nm).unwrap_err().0.contains("e.g. 0nm:2000nm:2nm"));
}

#[test]
fn lengths() {
    assert_eq!(parse_length_nm("65nm").unwrap(), 65.0);
    assert!((parse_length_nm("0.43um").unwrap() - 430.0).abs() < 1e-9);
    assert_eq!(parse_length_nm("65µm").unwrap(), 65_000.0);
    assert_eq!(parse_length_nm("65μm").unwrap(), 65_000.0);
    assert_eq!(parse_length_nm("2.5 um").unwrap(), 2_500.0);
    assert!(parse_length_nm("65").unwrap_err().0.contains("no unit"));
    assert!(parse_length_nm("abc").is_err());
    assert!(parse_length_nm("NaNnm").is_err());
    assert!(parse_positive_length_nm("-3nm").is_err());
}

#[test]
fn angles_and_ranges() {
    assert!((parse_angle_rad("75deg").unwrap() - 75f64.to_radians()).abs() < 1e-15);
    assert!((parse_angle_rad("90°").unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    assert_eq!(parse_angle_rad("1rad").unwrap(), 1.0);
    let r = parse_range("1deg:90deg:1deg", parse_angle_rad).unwrap();
    assert_eq!(r.len(), 90);
    let r = parse_range("0nm:2000nm:2nm", parse_length_nm).unwrap();
    assert_eq!((r.len(), r[1000]), (1001, 2000.0));
    assert!(parse_range("0nm:10nm", parse_length_nm).is_err());
    // TO is a value: a STEP that does not divide the range (1000/300 = 3.333 steps) is refused, where the list
    // stopped at 900 nm before; 0.1 nm steps over 400 nm end on TO despite the rounding of 4000 additions.
    let e = parse_range("0nm:1000nm:300nm", parse_length_nm).unwrap_err().0;
    assert!(e.contains("(TO − FROM)/STEP = 3.333 is not a whole number") && e.contains("short of 1000nm"), "{e}");
    let r = parse_range("380nm:780nm:0.1nm", parse_length_nm).unwrap();
    assert_eq!(r.len(), 4001);
    assert!((r[4000] - 780.0).abs() < 1e-9);
    assert_eq!(parse_range("10deg:10deg:5deg", parse_angle_rad).unwrap().len(), 1);
}

/// Ranges a person can mistype by orders of magnitude: a step so small its count passes usize (it wrapped to an
/// empty grid, which the callers indexed and panicked on), an end of 1e300 nm, and a step longer than the range
/// (one sample, the end silently dropped).
#[test]
fn absurd_ranges_are_refused_not_wrapped() {
    use iridis_color::spectrum::{range_grid, short_number, uniform_grid};
    let e = uniform_grid(380.0, 780.0, 1e-17).unwrap_err().to_string();
    assert!(e.contains("4e19 samples, more than 10000000"), "{e}");
    let e = range_grid(380.0, 1e300, 5.0).unwrap_err().to_string();
    assert!(e.contains("1e300 nm") && e.contains("2e299 samples"), "{e}");
    let e = range_grid(380.0, 780.0, 1e300).unwrap_err().to_string();
    assert!(e.contains("not a whole number of 1e300 nm steps") && e.contains("would be 380 nm"), "{e}");
    // The ends alone, and a step equal to the range, are still whole.
    assert_eq!(range_grid(500.0, 500.0, 5.0).unwrap(), [500.0]);
    assert_eq!(range_grid(400.0, 700.0, 300.0).unwrap(), [400.0, 700.0]);
    // Ends equal but for rounding (1100 nm and 1.1 µm) are one sample, not a step longer than the range.
    let to = parse_length_nm("1.1um").unwrap();
    assert_eq!(range_grid(1100.0, to, 5.0).unwrap(), [1100.0]);
    let e = parse_range("0deg:10deg:1e-300deg", parse_angle_rad).unwrap_err().0;
    assert!(e.contains("has 1e301 values, more than 1000000"), "{e}");
    assert!(parse_range("0deg:10deg:1e300deg", parse_angle_rad).unwrap_err().0.contains("does not end on TO"));
    assert_eq!(short_number(694.00012), "694.0001");
    assert_eq!(short_number(1e300), "1e300");
    assert_eq!(short_number(2.5e-17), "2.5e-17");
    assert_eq!(short_number(1e10 / 3.0), "3.3333e9");
    // A length past a kilometre prints in exponent form and reads back.
    assert_eq!(format_length(1e300), "1e294mm");
    assert_eq!(parse_length_nm(&format_length(1e300)).unwrap(), 1e300);
}
