//! The unit tests of src/template.rs, moved here so that `cargo test` compiles the library once.

use iridis_filmfit::template::*;

#[test]
fn roles_and_values() {
    let t =
        Template::parse("air | SiO2 {d1=100nm:50nm..0.5um} | n={n=1.7:1.5..2} 30nm | cauchy:{A=1.5:1.4..1.6},0.004")
            .unwrap();
    assert_eq!(t.params.len(), 3);
    assert_eq!(t.params[0].role, Role::Thickness { layer: 0 });
    assert_eq!((t.params[0].lo, t.params[0].hi), (50.0, 500.0));
    assert_eq!(t.params[1].role, Role::Index { medium: 2 });
    assert_eq!(t.params[2].role, Role::Coefficient { medium: 3, coef: 0 });
    let s = t.stack(&[120.0, 1.8, 1.55]).unwrap();
    assert_eq!(s.layers[0].thickness_nm, 120.0);
    assert_eq!(s.layers[1].material.index_at(500.0).unwrap().re, 1.8);
    let n = s.substrate.index_at(400.0).unwrap().re;
    assert!((n - (1.55 + 0.004 / 0.16)).abs() < 1e-14);
}

#[test]
fn bad_templates_say_what() {
    let msg = |s: &str| Template::parse(s).unwrap_err().to_string();
    assert!(msg("air | SiO2 100nm | Si").contains("no free parameter"));
    assert!(msg("air | SiO2 {d1=100nm} | Si").contains("has no range"));
    assert!(msg("air | SiO2 {d1} | Si").contains("NAME=START:LOW..HIGH"));
    assert!(msg("air | SiO2 {d1=100nm:500nm..50nm} | Si").contains("is empty"));
    assert!(msg("air | SiO2 {d1=100nm:-50nm..500nm} | Si").contains("cannot be negative"));
    assert!(msg("air | n={n=1:-1..2} 10nm | Si").contains("must be > 0"));
    assert!(msg("air | SiO2 {d1=600nm:50nm..500nm} | Si").contains("outside its range"));
    assert!(msg("air | SiO2 {d1=100:50..500} | Si").contains("unit"));
    assert!(msg("air | SiO2 {d=1nm:0nm..2nm} | SiO2 {d=1nm:0nm..2nm} | Si").contains("twice"));
    assert!(msg("air | Si{x=1:0..2} 10nm | Si").contains("a parameter may be"));
}
