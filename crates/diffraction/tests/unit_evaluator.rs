//! The unit tests of src/evaluator.rs (the lobe's radiometric gain), moved here so that `cargo test` compiles the
//! library once.

use iridis_diffraction::evaluator::*;
use iridis_diffraction::{Patch, Shading, SpectralSetup};

/// `G(λ) ∬ |A|² du dv` of a flat patch over one period of its sampled spectrum (`|u| ≤ λ/(2dx)`; a flat
/// patch's `A` does not depend on `w`, so the directions need not lie on the hemisphere): by Parseval
/// `λ² Σg²/(dx dy)` with `Σg = 1`, so exactly 1 when the gain is the window's effective area over λ². The
/// trapezoid rule is exact here: `|A|²` is a trigonometric polynomial of lower degree than the grid.
fn lobe_energy(gt: &GroundTruth, lambda: f64, dx: f64, n: usize) -> f64 {
    let wi = [0.0, 0.0, 1.0];
    let span = lambda / dx;
    let du = span / n as f64;
    let mut sum = 0.0;
    for j in 0..n {
        for i in 0..n {
            let (u, v) = (-0.5 * span + i as f64 * du, -0.5 * span + j as f64 * du);
            sum += gt.amplitude(lambda, wi, [-u, -v, 0.0]).norm_sqr() * du * du;
        }
    }
    sum * gt.radiometric_gain(lambda).unwrap()
}

#[test]
fn the_lobes_gain_is_the_windows_effective_area_also_where_the_patch_cuts_it() {
    let patch = Patch::from_row_major(24, 24, 100.0, 100.0, &[0.0; 576]).unwrap();
    let spectral = SpectralSetup::default();
    for (coherence, aperture) in [(1200.0, Aperture::Finite), (2400.0, Aperture::Finite), (65000.0, Aperture::Finite)] {
        let gt = GroundTruth::with_aperture(&patch, coherence, Shading::default(), &spectral, 41, aperture).unwrap();
        let e = lobe_energy(&gt, 500.0, 100.0, 64);
        let old =
            iridis_diffraction::spectral::radiometric_gain(500.0, coherence) / gt.radiometric_gain(500.0).unwrap();
        eprintln!("coherence {coherence} nm on a 2.4 µm patch: lobe energy {e:.12}, 4πσ_s²/A_eff = {old:.4}");
        assert!((e - 1.0).abs() < 1e-9, "{coherence}: {e}");
        match coherence {
            // The window well inside the patch (edges at 8σ_s): the Gaussian's own 4πσ_s².
            c if c < 2000.0 => assert!((old - 1.0).abs() < 1e-3, "{old}"),
            // As wide as the patch, 4πσ_s² overstated the light by ~1.2×; the paper's 65 µm on it by far more.
            c if c < 10_000.0 => assert!((1.15..1.25).contains(&old), "{old}"),
            _ => assert!(old > 100.0, "{old}"),
        }
    }
}

/// A step that leaves one wavelength in 380–780 nm is refused with the largest step that works (400 nm: two
/// samples), not "the grid needs two samples".
#[test]
fn a_grid_of_one_wavelength_names_the_step_that_works() {
    use iridis_color::{Illuminant, Observer};
    let e = SpectralSetup::new(Illuminant::D65, Observer::Cie1931, 500.0).unwrap_err().to_string();
    assert!(e.contains("380–780 nm at 500 nm steps holds 1 sample(s)") && e.contains("at most 400 nm"), "{e}");
    assert_eq!(
        SpectralSetup::new(Illuminant::D65, Observer::Cie1931, 400.0).unwrap().weights.wavelengths_nm(),
        [380.0, 780.0]
    );
}
