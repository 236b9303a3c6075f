//! The unit tests of src/model.rs, moved here so that `cargo test` compiles the library once.

use iridis_vision::model::*;
use iridis_vision::noise::ReceptorNoise;
use iridis_vision::space::Space;
use iridis_vision::system::VisualSystem;
use iridis_vision::template::Chromophore;

fn grid() -> Vec<f64> {
    (300..=700).map(f64::from).collect()
}

fn bump(centre: f64, width: f64) -> Vec<f64> {
    grid().iter().map(|l| 0.05 + 0.6 * (-0.5 * ((l - centre) / width).powi(2)).exp()).collect()
}

fn spectra() -> Vec<(String, Vec<f64>)> {
    vec![
        ("blue".into(), bump(450.0, 30.0)),
        ("green".into(), bump(530.0, 40.0)),
        ("uv".into(), bump(360.0, 25.0)),
        ("blue_copy".into(), bump(450.0, 30.0)),
    ]
}

#[test]
fn identical_spectra_are_zero_jnd_apart() {
    for id in ["bluetit", "avian-uv", "human", "honeybee", "ball-python"] {
        let s = VisualSystem::builtin(id).unwrap();
        let a = analyse(&spectra(), &grid(), &s, &Options::default()).unwrap();
        let d = a.distance("blue", "blue_copy").unwrap();
        assert_eq!(d.delta_s, Some(0.0), "{id}");
        assert_eq!(d.delta_l, Some(0.0), "{id}");
        assert!(a.distance("blue", "green").unwrap().delta_s.unwrap() > 1.0, "{id}");
    }
}

#[test]
fn scaling_the_illuminant_changes_nothing_after_von_kries() {
    let s = VisualSystem::builtin("bluetit").unwrap();
    let base = analyse(&spectra(), &grid(), &s, &Options::default()).unwrap();
    let scaled = analyse(&spectra(), &grid(), &s, &Options { illuminant_scale: 1234.5, ..Options::default() }).unwrap();
    for (x, y) in base.samples.iter().zip(&scaled.samples) {
        for (p, q) in x.quantum_catches.iter().zip(&y.quantum_catches) {
            assert!((p - q).abs() <= 1e-14 * p.abs(), "{p} {q}");
        }
        for (p, q) in x.absolute_catches.iter().zip(&y.absolute_catches) {
            assert!((q / p - 1234.5).abs() < 1e-9);
        }
    }
    for (x, y) in base.distances.iter().zip(&scaled.distances) {
        assert!((x.delta_s.unwrap() - y.delta_s.unwrap()).abs() < 1e-12);
        assert!((x.delta_l.unwrap() - y.delta_l.unwrap()).abs() < 1e-12);
    }
}

#[test]
fn delta_s_two_receptors_closed_form() {
    // Dichromat (Vorobyev & Osorio 1998): ΔS² = (Δf1 − Δf2)² / (e1² + e2²).
    let d = delta_s(&[0.3, -0.1], &[0.1, 0.2]).unwrap();
    assert!((d - 0.4 / (0.01f64 + 0.04).sqrt()).abs() < 1e-14);
    // A change that scales every catch alike (brightness only) is no colour change.
    assert!(delta_s(&[0.7, 0.7, 0.7, 0.7], &[0.2, 0.14, 0.14, 0.1]).unwrap() < 1e-15);
    assert_eq!(delta_s(&[0.1], &[0.1]), None);
}

#[test]
fn noise_from_weber_and_densities() {
    // pavo's defaults for birds: Weber 0.1 of LWS, densities 1:2:2:4 → e = 0.2, 0.1414, 0.1414, 0.1.
    let e = ReceptorNoise::Weber { weber: 0.1, reference: 3, densities: vec![1.0, 2.0, 2.0, 4.0] }.per_receptor();
    let want = [0.2, 0.1 * 2f64.sqrt(), 0.1 * 2f64.sqrt(), 0.1];
    for (a, b) in e.iter().zip(want) {
        assert!((a - b).abs() < 1e-15);
    }
    assert!(ReceptorNoise::PerReceptor(vec![0.1, 0.2]).check(3).is_err());
}

#[test]
fn bad_input_is_refused_with_a_reason() {
    let s = VisualSystem::from_lambda_max(&[360.0, 550.0], Chromophore::A1, &[]).unwrap();
    let short = vec![("a".to_string(), vec![0.5, 0.5])];
    let e = analyse(&short, &[400.0, 300.0], &s, &Options::default()).unwrap_err().to_string();
    assert!(e.contains("increase"), "{e}");
    let e = analyse(&spectra(), &grid(), &s, &Options { space: Space::Tetrahedron, ..Options::default() })
        .unwrap_err()
        .to_string();
    assert!(e.contains("tetrahedron needs 4"), "{e}");
    // Spectra far from the receptors: background catches nothing.
    let far: Vec<f64> = (900..=950).map(f64::from).collect();
    let e = analyse(&[("x".into(), vec![1.0; far.len()])], &far, &s, &Options::default()).unwrap_err().to_string();
    assert!(e.contains("catches no light"), "{e}");
}

#[test]
fn notes_say_when_spectra_miss_the_ultraviolet() {
    let s = VisualSystem::builtin("avian-uv").unwrap();
    let g: Vec<f64> = (380..=780).step_by(5).map(f64::from).collect();
    let sp = vec![("flat".to_string(), vec![0.5; g.len()]), ("flat2".to_string(), vec![0.4; g.len()])];
    let a = analyse(&sp, &g, &s, &Options::default()).unwrap();
    assert!(a.notes.iter().any(|n| n.contains("UVS")), "{:?}", a.notes);
    // Flat spectra are achromatic: the relative catches all equal 1/4 after von Kries to grey.
    for r in &a.samples[0].relative_catches {
        assert!((r - 0.25).abs() < 1e-12);
    }
    // and two greys differ only in brightness: ΔS = 0, ΔL = ln(0.5/0.4)/0.1.
    let d = &a.distances[0];
    assert!(d.delta_s.unwrap() < 1e-12);
    assert!((d.delta_l.unwrap() - (0.5f64 / 0.4).ln() / 0.1).abs() < 1e-12);
}

/// Spectra sampled more than 1 nm apart are interpolated linearly onto 1 nm before the catches are integrated (as
/// pavo's `as.rspec`): a linear ramp given at 300, 500 and 700 nm is then the same ramp as at every nanometre,
/// and its catches are the same to rounding (they were integrated over the three samples alone: every receptor
/// caught about the value at 500 nm), with a note.
#[test]
fn coarse_spectra_are_integrated_on_1_nm_as_pavo_does() {
    let s = VisualSystem::builtin("bluetit").unwrap();
    let ramp = |l: f64| 0.1 + 0.5 * (l - 300.0) / 400.0;
    let fine =
        analyse(&[("r".into(), grid().iter().map(|&l| ramp(l)).collect())], &grid(), &s, &Options::default()).unwrap();
    let coarse_grid = [300.0, 500.0, 700.0];
    let coarse =
        analyse(&[("r".into(), coarse_grid.iter().map(|&l| ramp(l)).collect())], &coarse_grid, &s, &Options::default())
            .unwrap();
    for (a, b) in fine.samples[0].absolute_catches.iter().zip(&coarse.samples[0].absolute_catches) {
        assert!((a - b).abs() < 1e-12 * a, "{a} against {b}");
    }
    assert!(coarse.notes.iter().any(|n| n.contains("200 nm apart") && n.contains("as.rspec")), "{:?}", coarse.notes);
    assert!(!fine.notes.iter().any(|n| n.contains("as.rspec")));
}
