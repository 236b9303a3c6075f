//! The unit tests of src/spec.rs, moved here so that `cargo test` compiles the library once.

use iridis_vision::model::ReceptorNoise;
use iridis_vision::spec::*;
use iridis_vision::template::Droplet;

#[test]
fn specs_resolve_and_refuse() {
    let s = Spec { lambda_max: Some("344,436,556".into()), densities: Some("1:2:4".into()), ..Spec::default() };
    let sys = s.system().unwrap();
    let o = s.options(&sys).unwrap();
    assert_eq!(o.noise, Some(ReceptorNoise::Weber { weber: 0.1, reference: 2, densities: vec![1.0, 2.0, 4.0] }));
    let d = parse_droplets("T,C:413,Y:507,413:0.05").unwrap();
    assert!(d[0].is_none() && d[1].is_some() && d[3] == Some(Droplet::new(413.0, 0.05).unwrap()));
    assert!(parse_droplets("Q:400").unwrap_err().to_string().contains("'Q:400'"));
    let both = Spec { visual: Some("bluetit".into()), lambda_max: Some("400".into()), ..Spec::default() };
    assert!(both.system().unwrap_err().to_string().contains("not both"));
    let bee = Spec { visual: Some("honeybee".into()), weber: Some(0.05), ..Spec::default() };
    let sys = bee.system().unwrap();
    let e = bee.options(&sys).unwrap().noise.unwrap().per_receptor();
    assert_eq!(e, vec![0.05, 0.05, 0.05]);
    let bad = Spec { visual: Some("human".into()), weber_ref: Some("Q".into()), ..Spec::default() };
    let sys = bad.system().unwrap();
    assert!(bad.options(&sys).unwrap_err().to_string().contains("S, M, L"));
}
