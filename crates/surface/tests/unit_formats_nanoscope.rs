//! The unit tests of src/formats/nanoscope.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::nanoscope::*;

#[test]
fn scale_lines() {
    let (k, soft, u) = parse_z_scale("V [Sens. Zsens] (0.001952197 V/LSB) 127.9392 V").unwrap();
    assert_eq!((k.as_deref(), soft, u.as_str()), (Some("Sens. Zsens"), 127.9392, "V"));
    let (_, soft, u) =
        parse_z_scale("V [Sens. LogStiffnessSens] (0.00000000745058 log(Arb)/LSB) 32.00000 log(Arb)").unwrap();
    assert_eq!((soft, u.as_str()), (32.0, "log(Arb)"));
    assert_eq!(parse_sens("V 4.273442 nm/V").unwrap(), (4.273442, "nm".to_string()));
    assert_eq!(length_unit("~m"), Some(1000.0));
}
