//! Physical laws that every evaluator must obey: the grating equation, the flat mirror, the blaze direction,
//! reciprocity of |A|², and agreement between the methods where their assumptions coincide.

use crate::common;

use std::sync::Arc;

use iridis_color::{Illuminant, Observer};
use iridis_diffraction::evaluator::{Evaluator, GroundTruth, Reference};
use iridis_diffraction::geometry::{direction, FresnelConvention, Shading};
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::taylor::terms_for_bound;
use iridis_diffraction::{Patch, SpectralSetup, TaylorTerms};

/// A 1-D profile repeated over `rows` rows, `periods` periods of `period_px` samples.
fn grating(profile: impl Fn(f64) -> f64, period_nm: f64, period_px: usize, periods: usize, rows: usize) -> Patch {
    let cols = period_px * periods;
    let dx = period_nm / period_px as f64;
    let mut h = Vec::with_capacity(rows * cols);
    for _ in 0..rows {
        for i in 0..cols {
            let phase = (i % period_px) as f64 / period_px as f64;
            h.push(profile(phase));
        }
    }
    Patch::from_row_major(rows, cols, dx, dx, &h).unwrap()
}

/// Light at θ_i in the x-z plane (azimuth 0); viewer at signed θ_r in the same plane, positive on the
/// specular side (PHYSICS.md's test-bench frame).
fn light(theta_i_deg: f64) -> [f64; 3] {
    direction(theta_i_deg.to_radians(), 0.0)
}
fn viewer(theta_r_deg: f64) -> [f64; 3] {
    let t = theta_r_deg.to_radians();
    [-t.sin(), 0.0, t.cos()]
}

/// Viewing angle (deg) of the strongest response in `[from, to]`, sampled every `step` degrees.
fn peak(f: impl Fn(f64) -> f64, from: f64, to: f64, step: f64) -> (f64, f64) {
    let mut best = (from, f64::NEG_INFINITY);
    let mut a = from;
    while a <= to {
        let v = f(a);
        if v > best.1 {
            best = (a, v);
        }
        a += step;
    }
    best
}

/// θ_r of order m from `m λ / d = sin θ_i − sin θ_r`.
fn grating_angle(m: f64, lambda: f64, d: f64, theta_i_deg: f64) -> f64 {
    (theta_i_deg.to_radians().sin() - m * lambda / d).asin().to_degrees()
}

const COHERENCE: f64 = 20_000.0;

fn sine_patch() -> (Patch, f64) {
    let d = 2000.0;
    (grating(|t| 40.0 * (std::f64::consts::TAU * t).sin(), d, 40, 16, 4), d)
}

#[test]
fn sinusoidal_grating_obeys_the_grating_equation_ground_truth_and_reference() {
    let (patch, d) = sine_patch();
    let spectral = SpectralSetup::default();
    let n = terms_for_bound(patch.max_abs_height, 380.0, 1e-8).unwrap();
    let terms = Arc::new(TaylorTerms::compute(&patch, n, COHERENCE).unwrap());
    let reference = Reference { terms, shading: Shading::default(), spectral: spectral.clone() };
    let truth = GroundTruth::new(&patch, COHERENCE, Shading::default(), &spectral, 3).unwrap();
    for theta_i in [0.0, 30.0, 75.0] {
        for lambda in [420.0, 550.0, 680.0] {
            for m in [1.0, -1.0] {
                let expected = grating_angle(m, lambda, d, theta_i);
                if !expected.is_finite() || expected.abs() > 85.0 {
                    continue;
                }
                for e in [&reference as &dyn Evaluator, &truth] {
                    let (got, _) = peak(
                        |a| e.reflectance(lambda, light(theta_i), viewer(a)).unwrap(),
                        expected - 3.0,
                        expected + 3.0,
                        0.02,
                    );
                    // Angular resolution: the window's width λσ_f in sin θ, i.e. λσ_f / cos θ_r in angle
                    // (0.9°–3° here). The peak must sit well inside it.
                    let sigma_f = 1.0 / (std::f64::consts::TAU * COHERENCE / 4.0);
                    let resolution = (lambda * sigma_f / expected.to_radians().cos()).to_degrees();
                    assert!(
                        (got - expected).abs() < 0.1 * resolution,
                        "{} θi={theta_i} λ={lambda} m={m}: peak at {got:.3}°, grating equation {expected:.3}°",
                        e.name()
                    );
                }
            }
        }
    }
}

/// The f64 lookup of a patch in a narrow band (550–555 nm), so the λ-integrated table has sharp orders.
fn narrow_band_lookup(patch: &Patch, params: TableParams, name: &str) -> Lookup {
    let spectral = SpectralSetup::with_range(Illuminant::E, Observer::Cie1931, 550.0, 555.0, 5.0).unwrap();
    let n = terms_for_bound(patch.max_abs_height, 550.0, 1e-8).unwrap();
    let terms = TaylorTerms::compute(patch, n, COHERENCE).unwrap();
    let table = Arc::new(LookupTable::build(&terms, &spectral, params, name, &|_| {}).unwrap());
    Lookup::new(table, Shading::default(), Precision::F64).unwrap()
}

#[test]
fn sinusoidal_grating_obeys_the_grating_equation_lookup() {
    let (patch, d) = sine_patch();
    // A narrow band (550–555 nm) so the λ-integrated lookup has a sharp first order.
    let lookup = narrow_band_lookup(&patch, TableParams { uv_resolution: 801, uv_power: 1.0 }, "test");
    for theta_i in [0.0, 30.0] {
        for m in [1.0, -1.0] {
            let expected = grating_angle(m, 552.5, d, theta_i);
            let (got, _) = peak(|a| lookup.xyz(light(theta_i), viewer(a)).y, expected - 3.0, expected + 3.0, 0.02);
            assert!((got - expected).abs() < 0.25, "lookup θi={theta_i} m={m}: {got:.3}° vs {expected:.3}°");
        }
    }
}

#[test]
fn flat_mirror_reflects_only_specularly() {
    // 12.8 µm patch, 8 µm coherence: the window falls to exp(−5) at the patch edges.
    let patch = Patch::from_row_major(256, 256, 50.0, 50.0, &vec![7.0; 256 * 256]).unwrap();
    let spectral = SpectralSetup::new(Illuminant::D65, Observer::Cie1931, 10.0).unwrap();
    let terms = Arc::new(TaylorTerms::compute(&patch, 2, 8000.0).unwrap());
    let reference = Reference { terms: terms.clone(), shading: Shading::default(), spectral: spectral.clone() };
    let truth = GroundTruth::new(&patch, 8000.0, Shading::default(), &spectral, 41).unwrap();
    let table = Arc::new(
        LookupTable::build(&terms, &spectral, TableParams { uv_resolution: 65, uv_power: 5.0 }, "flat", &|_| {})
            .unwrap(),
    );
    let lookup = Lookup::new(table, Shading::default(), Precision::F64).unwrap();
    let normal = [0.0, 0.0, 1.0];
    for e in [&reference as &dyn Evaluator, &truth, &lookup] {
        let y = e.xyz(normal, normal).y;
        assert!((y - 1.0).abs() < 1e-9, "{}: mirror Y = {y}", e.name());
        if let Some(rho) = e.reflectance(500.0, normal, normal) {
            assert!((rho - 1.0).abs() < 1e-12, "{}: ρ = {rho}", e.name());
        }
        // 20° off the mirror is > 5σ_f away at every visible λ: nothing but the truncated window's leakage.
        let off = e.xyz(normal, viewer(20.0)).y;
        assert!(off.abs() < 1e-6, "{}: off-specular Y = {off}", e.name());
    }
}

/// The width maps and screens are checked against (`spectral::lobe_sigma_uv`): a flat mirror's lobe, sampled
/// one σ off the mirror direction, has fallen to exp(−1/2) of its peak — the Gaussian window's law.
#[test]
fn a_mirror_lobe_is_as_wide_as_lobe_sigma_uv() {
    let coherence = 8000.0;
    let patch = Patch::from_row_major(64, 64, 50.0, 50.0, &vec![3.0; 64 * 64]).unwrap();
    let terms = Arc::new(TaylorTerms::compute(&patch, 2, coherence).unwrap());
    let spectral = SpectralSetup::new(Illuminant::D65, Observer::Cie1931, 10.0).unwrap();
    let reference = Reference { terms, shading: Shading::default(), spectral };
    let normal = [0.0, 0.0, 1.0];
    for lambda in [380.0, 550.0, 780.0] {
        let sigma = iridis_diffraction::spectral::lobe_sigma_uv(lambda, coherence);
        let at = |u: f64| reference.reflectance(lambda, normal, [u, 0.0, (1.0 - u * u).sqrt()]).unwrap();
        let ratio = at(sigma) / at(0.0);
        assert!((ratio - (-0.5f64).exp()).abs() < 1e-3, "λ {lambda}: σ {sigma}, ρ(σ)/ρ(0) = {ratio}");
    }
}

#[test]
fn blazed_grating_sends_light_to_the_side_its_facets_face() {
    // Facets rise towards +x with slope tan β, so their normals lean to −x (PHYSICS.md): under normal
    // incidence the brightest non-zero order is on the −x side (θ_r > 0 here) near θ_r = 2β.
    let d = 2500.0;
    let beta = (550.0f64 / d).asin() / 2.0; // blaze the first order at 550 nm
    let depth = d * beta.tan();
    let patch = grating(|t| depth * t, d, 50, 8, 4);
    let lambda = 550.0;
    let spectral = SpectralSetup::default();
    let n = terms_for_bound(patch.max_abs_height, 380.0, 1e-8).unwrap();
    let terms = Arc::new(TaylorTerms::compute(&patch, n, COHERENCE).unwrap());
    let reference = Reference { terms, shading: Shading::default(), spectral: spectral.clone() };
    let truth = GroundTruth::new(&patch, COHERENCE, Shading::default(), &spectral, 3).unwrap();
    for e in [&reference as &dyn Evaluator, &truth] {
        let order = |m: f64| {
            let a = grating_angle(m, lambda, d, 0.0);
            peak(|t| e.reflectance(lambda, light(0.0), viewer(t)).unwrap(), a - 0.5, a + 0.5, 0.02).1
        };
        let (plus, minus) = (order(-1.0), order(1.0)); // m = −1 → θ_r > 0 (−x side)
        assert!(plus > 5.0 * minus, "{}: −x side {plus:.4} vs +x side {minus:.4}", e.name());
        assert!(plus > order(0.0), "{}: the blazed order beats the mirror direction", e.name());
        assert!((grating_angle(-1.0, lambda, d, 0.0) - 2.0 * beta.to_degrees()).abs() < 0.01);
    }
}

#[test]
fn amplitude_is_reciprocal_and_methods_agree() {
    // A rough random patch: reference (Taylor + DFT) and ground truth agree closely when the window fits in
    // the patch, and the reference's BRDF is reciprocal. (|A|² alone depends on −ω_i − ω_r only, so it is
    // symmetric by construction; the test that can fail is the one through C, with its lone cos θ_r: ρ is the
    // BRDF times cos θ_i, so ρ(ω_i, ω_r)/cos θ_i = ρ(ω_r, ω_i)/cos θ_r.)
    // 48 × 48 samples 60 nm apart, heights uniform in ±30 nm.
    let patch = Patch::from_row_major(48, 48, 60.0, 60.0, &common::heights(48 * 48, 30.0, 7)).unwrap();
    let spectral = SpectralSetup::default();
    let n = terms_for_bound(patch.max_abs_height, 380.0, 1e-10).unwrap();
    let terms = Arc::new(TaylorTerms::compute(&patch, n, 2000.0).unwrap());
    let exact = Shading {
        fresnel: Arc::new(iridis_diffraction::Fresnel::Index { n: num_complex::Complex64::new(0.2, 3.4) }),
        ..Shading::default()
    };
    let reference = Reference { terms, shading: exact, spectral: spectral.clone() };
    let mut scratch = vec![num_complex::Complex64::new(0.0, 0.0); n + 1];
    for (wi, wr) in [(direction(0.5, 0.3), direction(0.2, 2.0)), (direction(1.1, 0.0), direction(0.3, 2.9))] {
        for lambda in [400.0, 550.0, 700.0] {
            let a = reference.reflectance(lambda, wi, wr).unwrap() / wi[2];
            let b = reference.reflectance(lambda, wr, wi).unwrap() / wr[2];
            assert!(a > 1e-8 && (a - b).abs() <= 1e-12 * a, "reciprocity at {lambda}: {a} vs {b}");
        }
    }
    // With the window (σ_s = 250 nm) well inside the 2.9 µm patch, the windowed DFT with Taylor terms equals
    // the direct windowed transform up to the 4σ_f cut-off of eq. 8 (a few 1e-3 of the amplitude).
    let small = 1000.0;
    let terms = Arc::new(TaylorTerms::compute(&patch, n, small).unwrap());
    let reference = Reference { terms, shading: Shading::default(), spectral: spectral.clone() };
    let truth = GroundTruth::new(&patch, small, Shading::default(), &spectral, 3).unwrap();
    let mut checked = 0;
    for (ti, pi, tr, pr) in [(0.0, 0.0, 0.3, 1.0), (0.5, 0.3, 0.2, 2.0), (0.9, 0.0, 0.6, 3.0), (0.2, 1.0, 1.2, 4.0)] {
        let (wi, wr) = (direction(ti, pi), direction(tr, pr));
        for lambda in [400.0, 550.0, 700.0] {
            let a = reference.amplitude(lambda, wi, wr, &mut scratch);
            let b = truth.amplitude(lambda, wi, wr);
            assert!((a - b).norm() < 5e-3 * a.norm().max(0.05), "{lambda} nm: reference {a} vs truth {b}");
            checked += 1;
        }
    }
    assert_eq!(checked, 12);
}

/// Angle (deg) between neighbouring nodes of the table's u grid at the view angle `theta_r_deg` (in the
/// light's plane, so `u = sin θ_r − sin θ_i`, `du = cos θ_r dθ_r`).
fn grid_step_deg(theta_i_deg: f64, theta_r_deg: f64, res: usize, power: f64) -> f64 {
    use iridis_diffraction::table::{grid_index, grid_value};
    let u = theta_r_deg.to_radians().sin() - theta_i_deg.to_radians().sin();
    let i = (grid_index(u, res, power).floor() as usize).min(res - 2);
    let du = grid_value(i + 1, res, power) - grid_value(i, res, power);
    (du / theta_r_deg.to_radians().cos()).to_degrees()
}

#[test]
fn lookup_on_the_power_5_grid_obeys_the_grating_equation_at_several_wavelengths() {
    // The paper's grid (a = 5, 501²) is fine near the specular direction and coarse far from it: a peak can
    // only be found to within half a grid step there (bilinear interpolation of a window ~2 steps wide).
    let (patch, d) = sine_patch();
    let n = terms_for_bound(patch.max_abs_height, 400.0, 1e-8).unwrap();
    let terms = TaylorTerms::compute(&patch, n, COHERENCE).unwrap();
    let (res, power) = (501, 5.0);
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for band in [420.0, 550.0, 680.0] {
        // One 5 nm band, so the λ-integrated table has sharp orders; its centre is the wavelength.
        let spectral = SpectralSetup::with_range(Illuminant::E, Observer::Cie1931, band, band + 5.0, 5.0).unwrap();
        let params = TableParams { uv_resolution: res, uv_power: power };
        let table = Arc::new(LookupTable::build(&terms, &spectral, params, "sine", &|_| {}).unwrap());
        let lookup = Lookup::new(table, Shading::default(), Precision::F64).unwrap();
        for theta_i in [0.0, 30.0] {
            for m in [1.0, -1.0, 2.0] {
                let expected = grating_angle(m, band + 2.5, d, theta_i);
                if !expected.is_finite() || expected.abs() > 80.0 {
                    continue;
                }
                let (got, _) = peak(|a| lookup.xyz(light(theta_i), viewer(a)).y, expected - 3.0, expected + 3.0, 0.01);
                let tol = 0.5 * grid_step_deg(theta_i, expected, res, power) + 0.05;
                worst = worst.max((got - expected).abs() / tol);
                checked += 1;
                eprintln!("λ={} θi={theta_i} m={m}: {got:.3}° vs {expected:.3}° (±{tol:.3}°)", band + 2.5);
                assert!(
                    (got - expected).abs() <= tol,
                    "λ={} θi={theta_i} m={m}: lookup peak at {got:.3}°, grating equation {expected:.3}° (±{tol:.3}°)",
                    band + 2.5
                );
            }
        }
    }
    eprintln!("power-5 lookup: worst |peak − grating equation| = {worst:.2} × tolerance");
    // Every order of every band and incidence lies within ±80° here: all 18 were checked, none skipped.
    assert_eq!(checked, 18);
}

#[test]
fn lookup_blazed_grating_prefers_the_side_its_facets_face() {
    // As for the other evaluators: facets facing −x, blaze order m = −1 (θ_r > 0) at 550 nm must be much
    // brighter than its mirror order m = +1, on the power-5 grid.
    let d = 2500.0;
    let beta = (550.0f64 / d).asin() / 2.0;
    let patch = grating(|t| d * beta.tan() * t, d, 50, 8, 4);
    let lookup = narrow_band_lookup(&patch, TableParams { uv_resolution: 501, uv_power: 5.0 }, "blazed");
    let order = |m: f64| {
        let a = grating_angle(m, 552.5, d, 0.0);
        peak(|t| lookup.xyz(light(0.0), viewer(t)).y, a - 1.0, a + 1.0, 0.01).1
    };
    let (blaze, mirror) = (order(-1.0), order(1.0));
    assert!(blaze > 5.0 * mirror, "blaze order {blaze:.4} vs its mirror order {mirror:.4}");
    assert!(blaze > order(0.0), "the blaze order beats the specular direction");
}

#[test]
fn ground_truth_is_reciprocal() {
    // Helmholtz reciprocity holds for the BRDF, F² G |P|² / (λ² A w²) with G = (1+ω_i·ω_r)²/(cos θ_i cos θ_r)
    // (paper eq. 2). iridis' ρ is that BRDF times cos θ_i (eq. 9: the light falls on the surface at θ_i), so
    // ρ(ω_i, ω_r)/cos θ_i must equal ρ(ω_r, ω_i)/cos θ_r — shading, shadowing and |A|² included.
    // 40 × 40 samples 60 nm apart, heights uniform in ±40 nm.
    let patch = Patch::from_row_major(40, 40, 60.0, 60.0, &common::heights(40 * 40, 40.0, 11)).unwrap();
    let spectral = SpectralSetup::default();
    let truth = GroundTruth::new(&patch, 1500.0, Shading::default(), &spectral, 3).unwrap();
    let pairs = [(0.0, 0.0, 0.3, 1.0), (0.5, 0.3, 0.2, 2.0), (1.1, 0.0, 0.6, 3.0), (0.2, 1.0, 1.3, 4.0)];
    for (ti, pi, tr, pr) in pairs {
        let (wi, wr) = (direction(ti, pi), direction(tr, pr));
        for lambda in [400.0, 550.0, 700.0] {
            let a = truth.reflectance(lambda, wi, wr).unwrap() / wi[2];
            let b = truth.reflectance(lambda, wr, wi).unwrap() / wr[2];
            assert!(a > 0.0 && (a - b).abs() <= 1e-10 * a, "{lambda} nm, {wi:?} ↔ {wr:?}: {a} vs {b}");
            // ρ itself is not symmetric unless θ_i = θ_r: the cos θ_i of eq. 9 is real.
            if (ti - tr).abs() > 0.1 {
                let (ra, rb) = (a * wi[2], b * wr[2]);
                assert!((ra - rb).abs() > 1e-3 * ra, "ρ symmetric where cos θ_i ≠ cos θ_r: {ra} {rb}");
            }
        }
    }
}

#[test]
fn ground_truth_window_cut_changes_nothing_measurable() {
    // A window much smaller than the patch (σ_s = 100 nm on 1.92 µm): the ground truth leaves out samples where
    // the window is below 1e-12 of its peak. Against the full sum written out here, A agrees to 1e-12.
    let (n, dx) = (32usize, 60.0);
    let h: Vec<f64> = (0..n * n).map(|k| 50.0 * ((k % n) as f64 * 0.9).sin() * ((k / n) as f64 * 0.4).cos()).collect();
    let patch = Patch::from_row_major(n, n, dx, dx, &h).unwrap();
    let coherence = 400.0;
    let truth = GroundTruth::new(&patch, coherence, Shading::default(), &SpectralSetup::default(), 3).unwrap();
    let sigma = coherence / 4.0;
    let c = (n - 1) as f64 * dx / 2.0;
    let (wi, wr) = (direction(0.4, 0.2), direction(0.7, 2.5));
    let [u, v, w] = iridis_diffraction::geometry::uvw(wi, wr);
    for lambda in [400.0, 550.0, 700.0] {
        let (mut acc, mut gs) = (num_complex::Complex64::new(0.0, 0.0), 0.0);
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (i as f64 * dx - c, j as f64 * dx - c);
                let g = (-(x * x + y * y) / (2.0 * sigma * sigma)).exp();
                let d = w * patch.heights[j * n + i] + u * x + v * y;
                acc += num_complex::Complex64::from_polar(g, std::f64::consts::TAU * d / lambda);
                gs += g;
            }
        }
        let full = acc / gs;
        let got = truth.amplitude(lambda, wi, wr);
        assert!((got - full).norm() < 1e-12, "{lambda} nm: {got} vs full sum {full}");
    }
}

/// The specular reflectance of a flat patch lit at `θ` (deg): the lobe of `ρ` around the mirror direction
/// integrated over projected solid angle (`dω cos θ_r = da db` for view directions `(a, b, ·)`), divided by the
/// light's `cos θ` (ρ is the BRDF times `cos θ_i`, eq. 9), at 500 nm.
fn flat_specular_reflectance(truth: &GroundTruth, theta_deg: f64) -> f64 {
    let wi = light(theta_deg);
    let (am, half, steps) = (-wi[0], 0.04, 121);
    let da = 2.0 * half / (steps - 1) as f64;
    let mut sum = 0.0;
    for j in 0..steps {
        for i in 0..steps {
            let (a, b) = (am - half + i as f64 * da, -half + j as f64 * da);
            let wr = [a, b, (1.0 - a * a - b * b).sqrt()];
            sum += truth.reflectance(500.0, wi, wr).unwrap() * da * da;
        }
    }
    sum / wi[2]
}

#[test]
fn flat_surface_reflects_the_exact_fresnel_ratio_once() {
    // Issue 14: Stam's F is the amplitude coefficient, so C carries the power reflectance R once. A flat
    // 51 µm patch with a 40 µm coherence window (σ_s = 10 µm, lobe ≈ 0.006 wide in direction cosines): the
    // specular reflectance at 60° relative to normal incidence must be the textbook R(60°)/R(0) of glass, not
    // its square (the paper's convention, kept as an option).
    let patch = Patch::from_row_major(64, 64, 800.0, 800.0, &vec![3.0; 64 * 64]).unwrap();
    let spectral = SpectralSetup::default();
    let n = 1.5f64;
    let fresnel = Arc::new(iridis_diffraction::Fresnel::Index { n: num_complex::Complex64::new(n, 0.0) });
    // Textbook Fresnel equations for a lossless dielectric in air (Hecht, Optics, eq. 4.42–4.43).
    let exact = |theta_deg: f64| {
        let ci = theta_deg.to_radians().cos();
        let st = theta_deg.to_radians().sin() / n;
        let ct = (1.0 - st * st).sqrt();
        let rs = (ci - n * ct) / (ci + n * ct);
        let rp = (n * ci - ct) / (n * ci + ct);
        0.5 * (rs * rs + rp * rp)
    };
    let want = exact(60.0) / exact(0.0);
    assert!((want - 2.2306).abs() < 1e-3, "textbook ratio {want}");
    for convention in [FresnelConvention::Physical, FresnelConvention::Paper] {
        let shading = Shading { fresnel: fresnel.clone(), shadowing: true, convention };
        let truth = GroundTruth::new(&patch, 40_000.0, shading, &spectral, 3).unwrap();
        let ratio = flat_specular_reflectance(&truth, 60.0) / flat_specular_reflectance(&truth, 0.0);
        let expected = match convention {
            FresnelConvention::Physical => want,
            FresnelConvention::Paper => want * want,
        };
        assert!((ratio / expected - 1.0).abs() < 2e-3, "{convention:?}: R(60°)/R(0) = {ratio}, expected {expected}");
    }
}

#[test]
fn a_film_fresnel_source_enters_the_spectrum_linearly() {
    // With a thin film as the Fresnel source, ρ_λ of a flat mirror at normal incidence is R_film(λ)/R̄₀: the
    // film's spectrum once, so ratios between wavelengths are the film's own ratios (the paper's F² squares them).
    let patch = Patch::from_row_major(32, 32, 100.0, 100.0, &vec![0.0; 32 * 32]).unwrap();
    let stack: iridis_thinfilm::Stack = "air | n=1.38 300nm | n=1.5".parse().unwrap();
    let film = Arc::new(iridis_diffraction::geometry::FilmFresnel::new(stack.clone()).unwrap());
    let normal = [0.0, 0.0, 1.0];
    for convention in [FresnelConvention::Physical, FresnelConvention::Paper] {
        let shading = Shading { fresnel: film.clone(), shadowing: true, convention };
        let truth = GroundTruth::new(&patch, 1000.0, shading, &SpectralSetup::default(), 3).unwrap();
        let (r450, r600) = (stack.evaluate(450.0, 0.0).unwrap().r(), stack.evaluate(600.0, 0.0).unwrap().r());
        let (p450, p600) =
            (truth.reflectance(450.0, normal, normal).unwrap(), truth.reflectance(600.0, normal, normal).unwrap());
        let film_ratio = r450 / r600;
        let expected = match convention {
            FresnelConvention::Physical => film_ratio,
            FresnelConvention::Paper => film_ratio * film_ratio,
        };
        assert!((film_ratio - 1.0).abs() > 0.2, "the film must colour the light: {film_ratio}");
        assert!((p450 / p600 / expected - 1.0).abs() < 1e-12, "{convention:?}: {} vs {expected}", p450 / p600);
    }
}

/// `∫ ρ cos θ_r dω_r / cos θ_i` over the hemisphere at 500 nm (ρ is the BRDF times cos θ_i): the reflected
/// power per unit incident power, relative to `R₀`.
fn hemispherical(truth: &GroundTruth, theta_deg: f64) -> f64 {
    let wi = light(theta_deg);
    common::projected_disk_sum(161, |wr| truth.reflectance(500.0, wi, wr).unwrap()) / wi[2]
}

#[test]
fn a_rough_patch_reflects_no_more_than_the_flat_one() {
    // Energy over the hemisphere. The paper's ρ is relative to the mirror's peak, so the hemispherical integral
    // of a flat patch is the window's Parseval sum, λ² Σg²/((Σg)² dx dy) (≈ λ²/(4πσ_s²) for an uncut Gaussian),
    // times R(θ)/R₀ (the flat-surface test above). With |exp(ikwh)| = 1 a
    // rough patch has the same total |A|² over all frequencies and roughness only moves power into other
    // directions (some of it below the horizon): its integral must not exceed the flat patch's.
    let (n, dx) = (32, 60.0);
    // Uniform in ±20 nm.
    let rough = common::heights(n * n, 20.0, 5);
    let metal = iridis_diffraction::Fresnel::Index { n: num_complex::Complex64::new(0.2, 3.4) };
    let shading = Shading { fresnel: Arc::new(metal), ..Shading::default() };
    let coherence = 1500.0;
    let make = |h: &[f64]| {
        let patch = Patch::from_row_major(n, n, dx, dx, h).unwrap();
        GroundTruth::new(&patch, coherence, shading.clone(), &SpectralSetup::default(), 3).unwrap()
    };
    let (flat, rough) = (make(&vec![0.0; n * n]), make(&rough));
    // Parseval on the sampled window as the ground truth holds it (centred, cut at the patch edge).
    let sigma_s: f64 = coherence / 4.0;
    let c = (n - 1) as f64 * dx / 2.0;
    let g: Vec<f64> = (0..n * n)
        .map(|k| {
            let (x, y) = ((k % n) as f64 * dx - c, (k / n) as f64 * dx - c);
            (-(x * x + y * y) / (2.0 * sigma_s * sigma_s)).exp()
        })
        .collect();
    let (sum, sum2) = (g.iter().sum::<f64>(), g.iter().map(|v| v * v).sum::<f64>());
    let parseval = 500.0f64.powi(2) * sum2 / (sum * sum * dx * dx);
    for theta in [0.0, 45.0] {
        let (f, r) = (hemispherical(&flat, theta), hemispherical(&rough, theta));
        eprintln!("θ_i = {theta}°: flat {f:.4} (Parseval at 0°: {parseval:.4}), rough {r:.4}");
        assert!(r <= f * 1.01 && r > 0.3 * f, "θ_i = {theta}°: flat {f}, rough {r}");
    }
    let f0 = hemispherical(&flat, 0.0);
    // C is 1 only at the mirror direction; across this wide lobe (≈ 0.15 in direction cosines) it grows like
    // 1/cos θ_r, a few per cent.
    assert!((f0 / parseval - 1.0).abs() < 0.05, "flat {f0} vs Parseval {parseval}");
}
