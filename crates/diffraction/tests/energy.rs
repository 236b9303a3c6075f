//! Issue 21, energy of the diffraction BRDF in radiometric units (`Units::Radiometric`, docs/PHYSICS.md):
//! a flat surface reflects `R(θ)/R₀` of the light (the closed form of Schlick's Fresnel, not a value of ours), a
//! rough one no more, and the BRDF `ρ/cos θ_i` is reciprocal.

use std::sync::Arc;

use iridis_diffraction::energy::{directional_albedo, AlbedoGrid};
use iridis_diffraction::geometry::{direction, Shading};
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::taylor::terms_for_bound;
use iridis_diffraction::{Evaluator, Fresnel, Patch, Reference, SpectralSetup, TaylorTerms, Units};

/// A coherence length half the 6.4 µm patch: the rough patch's lobe is wide (λ/(2πσ_s) ≈ 0.1 in u).
const COHERENCE: f64 = 3200.0;
/// For the flat patch (whose only Fourier coefficient is the mean, so any window fits it): a narrow lobe
/// (≈ 0.01 in u), over which the Kirchhoff factor `C/cos θ_i` is constant to a few 1e-4 at normal incidence.
const NARROW: f64 = 32000.0;

fn patch(h: impl Fn(usize, usize) -> f64) -> Patch {
    let n = 64;
    let heights: Vec<f64> = (0..n * n).map(|k| h(k / n, k % n)).collect();
    Patch::from_row_major(n, n, 100.0, 100.0, &heights).unwrap()
}

fn lookup(p: &Patch, units: Units, coherence: f64) -> Lookup {
    lookup_at(p, units, coherence, 101)
}

fn lookup_at(p: &Patch, units: Units, coherence: f64, res: usize) -> Lookup {
    let n = terms_for_bound(p.max_abs_height, 380.0, 1e-6).unwrap();
    let terms = TaylorTerms::compute(p, n, coherence).unwrap();
    let mut spectral = SpectralSetup::default();
    if units == Units::Radiometric {
        spectral = spectral.radiometric(coherence).unwrap();
    }
    let params = TableParams { uv_resolution: res, uv_power: 5.0 };
    let table = LookupTable::build(&terms, &spectral, params, "test", &|_| {}).unwrap();
    assert_eq!(table.meta.units, units.name());
    Lookup::new(Arc::new(table), Shading::default(), Precision::F64).unwrap()
}

fn schlick(cos: f64) -> f64 {
    let f0 = 0.04;
    f0 + (1.0 - f0) * (1.0 - cos).powi(5)
}

/// A random surface with 40 nm rms heights: a wide diffuse-like lobe.
fn rough() -> Patch {
    let mut seed = 11u64;
    let mut rnd = move || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let noise: Vec<f64> = (0..64 * 64).map(|_| rnd()).collect();
    // Smoothed over 3×3 pixels so the heights are correlated over ~300 nm, the scale that scatters visibly.
    patch(|r, c| {
        let mut s = 0.0;
        for dr in 0..3 {
            for dc in 0..3 {
                s += noise[((r + dr) % 64) * 64 + (c + dc) % 64];
            }
        }
        s * 140.0
    })
}

#[test]
fn a_flat_surface_reflects_the_fresnel_fraction_and_a_rough_one_no_more() {
    // A 201² table (a 101² one's bilinear interpolation over-counts this narrow lobe by 1.1 %, 201² by 0.3 %),
    // integrated on the refined grid of 401 points.
    let flat = lookup_at(&patch(|_, _| 0.0), Units::Radiometric, NARROW, 201);
    let grid = AlbedoGrid::for_evaluator(&flat, 401).unwrap();
    for theta in [0.0f64, 20.0, 40.0, 60.0, 75.0] {
        let wo = direction(theta.to_radians(), 0.7);
        let a = directional_albedo(&flat, wo, &grid).y;
        let expected = schlick(theta.to_radians().cos()) / 0.04;
        eprintln!("θ_o = {theta}°: flat A = {a:.4}, R/R₀ = {expected:.4}");
        // Measured: +0.3 % at 0° (the table's interpolation), +1.8 % at 75°, where the lobe averages R(θ_h) over
        // ±2° of a steep, convex Schlick curve (R/R₀ goes 6.37 → 6.48 over that mean).
        assert!((a / expected - 1.0).abs() < 0.025, "θ_o = {theta}°: flat A {a}, R/R₀ {expected}");
    }
    // A rough surface under a window as wide as a quarter of the patch: its lobe spreads over tens of degrees
    // and reflects no more than the flat surface under the same window (whose lobe is as wide as the window
    // makes it: there the Kirchhoff factor's growth across the lobe shows, up to 13 % over R/R₀ at 60°).
    let (flat, rough) =
        (lookup(&patch(|_, _| 0.0), Units::Radiometric, COHERENCE), lookup(&rough(), Units::Radiometric, COHERENCE));
    let grid = AlbedoGrid::for_evaluator(&flat, 201).unwrap();
    for theta in [0.0f64, 30.0, 60.0] {
        let wo = direction(theta.to_radians(), 0.7);
        let (a, r) = (directional_albedo(&flat, wo, &grid).y, directional_albedo(&rough, wo, &grid).y);
        eprintln!("θ_o = {theta}°, 3.2 µm window: flat A = {a:.4}, rough A = {r:.4}");
        assert!(r <= a * 1.01 && r > 0.2 * a, "θ_o = {theta}°: rough {r}, flat {a}");
    }
}

#[test]
fn relative_and_radiometric_tables_differ_by_the_lobe_solid_angle() {
    // The relative table's flat-mirror lobe integrates to λ²/(4πσ_s²) (R/R₀ at normal incidence): at 550 nm
    // and σ_s = 8 µm that is 3.8e-4. Integrated over D65 × ȳ it is Σ w_y λ²/(4πσ_s²).
    let flat_rel = lookup_at(&patch(|_, _| 0.0), Units::Relative, NARROW, 201);
    let grid = AlbedoGrid::for_evaluator(&flat_rel, 401).unwrap();
    let a = directional_albedo(&flat_rel, [0.0, 0.0, 1.0], &grid).y;
    let spectral = SpectralSetup::default();
    let sigma_s: f64 = NARROW / 4.0;
    let expected: f64 = spectral
        .wavelengths()
        .iter()
        .zip(spectral.weights.weights())
        .map(|(l, w)| w[1] * l * l / (4.0 * std::f64::consts::PI * sigma_s * sigma_s))
        .sum();
    eprintln!("relative flat mirror: A = {a:.4e}, Σ w_y λ²/(4πσ_s²) = {expected:.4e}");
    assert!((a / expected - 1.0).abs() < 0.01, "{a} vs {expected}");
}

#[test]
fn the_radiometric_brdf_is_reciprocal() {
    // An asymmetric (blazed) profile along x, so a wrong sign or a missing cos θ_i would show.
    let blazed = patch(|_, c| 120.0 * ((c % 16) as f64 / 16.0));
    let l = lookup(&blazed, Units::Radiometric, COHERENCE);
    let mut worst = 0.0f64;
    for (ti, pi, to, po) in
        [(10.0, 0.0, 50.0, 3.0), (35.0, 1.0, 20.0, 2.5), (70.0, 4.0, 15.0, 0.3), (5.0, 2.0, 80.0, 5.0)]
    {
        let (a, b) = (direction(f64::to_radians(ti), pi), direction(f64::to_radians(to), po));
        let f_ab = l.xyz(a, b).y / a[2];
        let f_ba = l.xyz(b, a).y / b[2];
        worst = worst.max((f_ab - f_ba).abs() / f_ab.abs().max(f_ba.abs()).max(1e-300));
    }
    eprintln!("radiometric lookup: worst relative |f(a,b) − f(b,a)| = {worst:.1e}");
    assert!(worst < 1e-12, "{worst}");
}

#[test]
fn the_reference_evaluator_takes_the_same_units() {
    // The reference method (per-λ windowed DFT) with radiometric weights gives the flat albedo R/R₀ too.
    let p = patch(|_, _| 0.0);
    let terms = Arc::new(TaylorTerms::compute(&p, 2, COHERENCE).unwrap());
    let spectral = SpectralSetup::default().radiometric(COHERENCE).unwrap();
    let shading = Shading { fresnel: Arc::new(Fresnel::Schlick { n: 1.5 }), ..Shading::default() };
    let reference = Reference { terms, shading, spectral };
    // The lobe (≈ 0.1 wide in u) sits at u = v = 0, where the power-5 grid 2·s⁵ is densest: with 401 points
    // |u| < 0.05 still holds ~190 of the nodes, so the trapezoid rule resolves the lobe as with 801, and the bound
    // (2 %, against a measured 0.6 % physical excess) keeps its meaning. 801 points (IRIDIS_EXHAUSTIVE=1) are four
    // times the evaluations: 33 CPU s of the 39 of this file's tests.
    let points = if std::env::var("IRIDIS_EXHAUSTIVE").as_deref() == Ok("1") { 801 } else { 401 };
    let grid = AlbedoGrid::power(points, 5.0).unwrap();
    let a = directional_albedo(&reference, direction(0.5, 0.0), &grid).y;
    let expected = schlick(0.5f64.cos()) / 0.04;
    eprintln!("reference, flat, θ_o = 0.5 rad, {points} points: A = {a:.6}, R/R₀ = {expected:.6}");
    // Measured (probe, 801 points): 1.0064 × R/R₀ at normal incidence, the Kirchhoff factor's growth over a lobe
    // ≈ 0.1 wide in u; this test at 0.5 rad.
    assert!((a / expected - 1.0).abs() < 0.02, "{a} vs {expected}");
    // A radiometric setup made for another coherence is refused where it would mis-scale a table.
    let other = SpectralSetup::default().radiometric(2.0 * COHERENCE).unwrap();
    let err = LookupTable::build(
        &TaylorTerms::compute(&p, 2, COHERENCE).unwrap(),
        &other,
        TableParams::default(),
        "x",
        &|_| {},
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("coherence"), "{err}");
}
