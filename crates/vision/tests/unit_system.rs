//! The unit tests of src/system.rs, moved here so that `cargo test` compiles the library once.

use iridis_vision::system::*;
use iridis_vision::template::Chromophore;

#[test]
fn every_builtin_loads_with_unit_sensitivities() {
    for (id, _) in VisualSystem::builtin_names() {
        let s = VisualSystem::builtin(id).unwrap();
        assert!(!s.receptors.is_empty(), "{id}");
        for r in &s.receptors {
            let sum: f64 = (300..=700).map(|l| r.sensitivity(l as f64)).sum();
            assert!((sum - 1.0).abs() < 1e-12, "{id} {}: {sum}", r.name);
        }
        assert!(s.noise.check(s.receptors.len()).is_ok(), "{id}");
    }
    assert!(VisualSystem::builtin("avg.uv").unwrap().id == "avian-uv");
    let e = VisualSystem::builtin("cat").unwrap_err().to_string();
    assert!(e.contains("'cat'") && e.contains("bluetit"), "{e}");
}

#[test]
fn peaks_where_the_sources_put_them() {
    // Human quantal cone fundamentals peak near 441, 541, 566 nm (Stockman & Sharpe 2000, quantal).
    let h = VisualSystem::builtin("human").unwrap();
    let p: Vec<f64> = h.receptors.iter().map(Receptor::peak_nm).collect();
    assert!((p[0] - 441.0).abs() <= 3.0 && (p[1] - 541.0).abs() <= 3.0 && (p[2] - 566.0).abs() <= 3.0, "{p:?}");
    // Templates without droplets peak at λmax (within the template's 1 nm grid and its fit).
    let b = VisualSystem::builtin("honeybee").unwrap();
    for (r, l) in b.receptors.iter().zip([344.0, 436.0, 556.0]) {
        assert!((r.peak_nm() - l).abs() <= 2.0, "{}: {}", r.name, r.peak_nm());
    }
    // Oil droplets push the bird's cone peaks to longer wavelengths than the pigment's λmax.
    let t = VisualSystem::builtin("bluetit").unwrap();
    for r in &t.receptors[1..] {
        assert!(r.peak_nm() > r.lambda_max_nm().unwrap() + 2.0, "{}", r.name);
    }
}

#[test]
fn custom_systems_sort_and_check() {
    let s = VisualSystem::from_lambda_max(&[556.0, 344.0, 436.0], Chromophore::A1, &[]).unwrap();
    assert_eq!(s.receptor_names(), vec!["λ344", "λ436", "λ556"]);
    assert_eq!(s.receptor_index("longest").unwrap(), 2);
    assert!(VisualSystem::from_lambda_max(&[344.0, 436.0], Chromophore::A1, &[None]).is_err());
    assert!(VisualSystem::from_lambda_max(&[1000.0], Chromophore::A1, &[]).is_err());
}
