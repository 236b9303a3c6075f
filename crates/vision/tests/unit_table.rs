//! The unit tests of src/table.rs, moved here so that `cargo test` compiles the library once.

use iridis_vision::table::*;

#[test]
fn pavo_layout_round_trips() {
    let t = SpectraTable::parse("wl,a,b\n300,0.1,0.2\n301,0.3,0.4\n", "t").unwrap();
    assert_eq!(t.samples[1], ("b".to_string(), vec![0.2, 0.4]));
    assert_eq!(SpectraTable::parse(&t.to_csv(), "again").unwrap(), t);
    let t = SpectraTable::parse("# c\n300\t1\n310\t2\n", "t").unwrap();
    assert_eq!(t.samples[0].0, "sample1");
}

#[test]
fn errors_name_the_line() {
    let e = SpectraTable::parse("wl,a\n300,1\n310,x\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:3") && e.contains("'x'"), "{e}");
    let e = SpectraTable::parse("wl,a\n300,1\n290,2\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:3") && e.contains("increase"), "{e}");
    let e = SpectraTable::parse("wl,a,b\n300,1\n310,2,3\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:2") && e.contains("expected 3 columns"), "{e}");
    assert!(SpectraTable::parse("wl,a\n300,1\n", "f.csv").is_err());
}

#[test]
fn curves_are_zero_outside() {
    let c = Curve::new(vec![400.0, 500.0], vec![1.0, 3.0]).unwrap();
    assert_eq!(c.at(450.0), 2.0);
    assert_eq!(c.at(399.0), 0.0);
    assert_eq!(c.at(501.0), 0.0);
}
