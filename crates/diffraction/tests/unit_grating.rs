//! The unit tests of src/grating.rs (unit cells' diffraction orders and energy-normalised lobes), moved here so that
//! `cargo test` compiles the library once.

use iridis_diffraction::geometry::{direction, Fresnel};
use iridis_diffraction::geometry::{dot, FresnelSource, Vec3};
use iridis_diffraction::grating::*;
use iridis_diffraction::taylor::terms_for_bound;
use iridis_diffraction::Patch;
use num_complex::Complex64;

/// A reflector that returns everything (`R = 1` for both polarisations).
#[derive(Debug)]
struct Perfect;
impl FresnelSource for Perfect {
    fn reflectance(&self, _: f64, _: f64) -> f64 {
        1.0
    }
    fn depends_on_wavelength(&self) -> bool {
        false
    }
    fn describe(&self) -> String {
        "perfect".into()
    }
}

/// `J_m(x)` by Bessel's integral `(1/π) ∫_0^π cos(mτ − x sin τ) dτ` (Abramowitz & Stegun 9.1.21): the
/// trapezoid rule on the periodic integrand converges geometrically, so 400 nodes give ~1e-15 up to x ≈ 100
/// (the power series loses digits to cancellation beyond x ≈ 10).
fn bessel_j(m: i64, x: f64) -> f64 {
    let nodes = 400;
    let h = std::f64::consts::PI / nodes as f64;
    let f = |t: f64| (m as f64 * t - x * t.sin()).cos();
    let inner: f64 = (1..nodes).map(|k| f(k as f64 * h)).sum();
    (inner + 0.5 * (f(0.0) + f(std::f64::consts::PI))) * h / std::f64::consts::PI
}

fn sine(period: f64, amplitude: f64, samples: usize) -> Patch {
    let h: Vec<f64> = (0..4 * samples)
        .map(|i| amplitude * (std::f64::consts::TAU * (i % samples) as f64 / samples as f64).sin())
        .collect();
    Patch::from_row_major(4, samples, period / samples as f64, 50.0, &h).unwrap()
}

#[test]
fn a_sine_gratings_orders_are_kirchhoffs_bessel_functions() {
    // exp(i k w a sin(2πx/Λ)) = Σ_m J_m(k w a) e^{2πi m x/Λ} (Jacobi–Anger): η_m = K R J_m(k w_m a)².
    let (period, a, lambda) = (1100.0, 60.0, 500.0);
    let cell = UnitCell::new(&sine(period, a, 256), 380.0).unwrap();
    assert_eq!(cell.lines(), Lines::AlongX);
    let wi = direction(30f64.to_radians(), 0.0);
    let ans = cell.efficiencies(wi, lambda, &Perfect, Normalisation::Kirchhoff).unwrap();
    assert_eq!(ans.orders.iter().map(|o| o.m).collect::<Vec<_>>(), vec![-1, 0, 1, 2, 3]);
    for o in &ans.orders {
        // Grating equation: sin θ_r = sin θ_i − m λ/Λ, θ_r positive on the specular side (φ = 180°).
        let s = 30f64.to_radians().sin() - o.m as f64 * lambda / period;
        let signed = if o.phi_deg > 90.0 && o.phi_deg < 270.0 { o.theta_deg } else { -o.theta_deg };
        assert!((signed.to_radians().sin() - s).abs() < 1e-12, "{o:?}");
        let wr = [-s, 0.0, (1.0 - s * s).sqrt()];
        let (ci, cr) = (wi[2], wr[2]);
        let k = (1.0 + dot(wi, wr)).powi(2) / (ci * cr * (ci + cr).powi(2));
        let j = bessel_j(o.m, std::f64::consts::TAU / lambda * (ci + cr) * a);
        let expect = k * j * j;
        assert!((o.efficiency.te - expect).abs() < 1e-9 * expect.max(1e-3), "{o:?} vs {expect}");
    }
}

#[test]
fn a_relief_at_the_taylor_limit_keeps_bessels_orders_and_a_deeper_one_is_refused() {
    // The expansion's terms sum with about ε_f64 · e^x of rounding, x = 2k|h|max (docs/PHYSICS.md): a cell
    // accepts reliefs up to x = 26.8 at its shortest wavelength, 1e-4 of the amplitude. At 0.99 of that depth
    // and that wavelength (x = 26.5, the mirror order's k w a) Jacobi–Anger's orders still hold to it.
    let limit = 26.8 * 380.0 / (2.0 * std::f64::consts::TAU);
    let (period, lambda) = (2000.0, 380.0);
    let cell = UnitCell::new(&sine(period, 0.99 * limit, 256), lambda).unwrap();
    let wi = direction(0.0, 0.0);
    let ans = cell.efficiencies(wi, lambda, &Perfect, Normalisation::Kirchhoff).unwrap();
    assert_eq!(ans.orders.len(), 11, "orders −5..5 propagate at Λ/λ = 5.3");
    for o in &ans.orders {
        let s = -(o.m as f64) * lambda / period;
        let cr = (1.0 - s * s).sqrt();
        let k = (1.0 + cr).powi(2) / (cr * (1.0 + cr).powi(2));
        let j = bessel_j(o.m, std::f64::consts::TAU / lambda * (1.0 + cr) * 0.99 * limit);
        // An amplitude off by δ ≤ 1e-4 moves K|c|² by at most K (2|J| δ + δ²).
        let bound = k * (2.0 * j.abs() * 1e-4 + 1e-8);
        assert!((o.efficiency.te - k * j * j).abs() <= bound, "{o:?} vs {} (bound {bound:.1e})", k * j * j);
    }
    // Just deeper: refused with the limit named, where the sum used to print NaN (|h|^N overflowing) or noise.
    let e = UnitCell::new(&sine(period, 1.01 * limit, 256), lambda).unwrap_err().to_string();
    assert!(e.contains("too deep for the Taylor expansion") && e.contains("|h|max ≤ 811 nm"), "{e}");
    assert!(terms_for_bound(50.0, 10.0, 1e-10).is_err(), "a 50 nm relief at 10 nm: x = 63");
}

#[test]
fn energy_normalised_orders_of_a_perfect_reflector_return_all_light_at_every_incidence() {
    let cell = UnitCell::new(&sine(1100.0, 150.0, 128), 380.0).unwrap();
    for deg in [0.0, 30.0, 60.0, 75.0, 85.0, 89.0] {
        let wi = direction(f64::to_radians(deg), 0.3);
        for lambda in [400.0, 550.0, 700.0] {
            let e = cell.efficiencies(wi, lambda, &Perfect, Normalisation::Energy).unwrap();
            assert!((e.reflected_total.unpolarized - 1.0).abs() < 1e-12, "{deg}° {lambda}: {e:?}");
            let k = cell.efficiencies(wi, lambda, &Perfect, Normalisation::Kirchhoff).unwrap();
            assert!((k.kirchhoff_sum - k.reflected_total.unpolarized).abs() < 1e-12);
        }
    }
    // The printed obliquity creates energy at oblique light (the 2.08 at 75°, 150 nm amplitude).
    let k = cell.efficiencies(direction(75f64.to_radians(), 0.0), 550.0, &Perfect, Normalisation::Kirchhoff);
    assert!(k.unwrap().reflected_total.te > 1.5);
}

#[test]
fn energy_normalised_efficiencies_are_reciprocal() {
    // Light from ω_i into order G leaving along ω_r; the reverse light from ω_r leaves along ω_i in the same
    // order G (ω_i,xy = −ω_r,xy + G): the efficiencies agree (metal Fresnel included, symmetric in θ_h).
    let h: Vec<f64> = (0..96 * 96)
        .map(|i| {
            let (x, y) = ((i % 96) as f64 / 96.0, (i / 96) as f64 / 96.0);
            40.0 * (std::f64::consts::TAU * x).sin() + 25.0 * (std::f64::consts::TAU * (x + 2.0 * y)).cos().powi(3)
        })
        .collect();
    let patch = Patch::from_row_major(96, 96, 1400.0 / 96.0, 1700.0 / 96.0, &h).unwrap();
    let cell = UnitCell::new(&patch, 380.0).unwrap();
    assert_eq!(cell.lines(), Lines::Crossed);
    let metal = Fresnel::Index { n: Complex64::new(0.2, 3.4) };
    let wi = direction(50f64.to_radians(), 0.7);
    let ans = cell.efficiencies(wi, 600.0, &metal, Normalisation::Energy).unwrap();
    assert!(ans.orders.len() > 4);
    assert!(ans.reflected_total.unpolarized < 1.0);
    for o in &ans.orders {
        let wr = direction(o.theta_deg.to_radians(), o.phi_deg.to_radians());
        let back = cell.efficiencies(wr, 600.0, &metal, Normalisation::Energy).unwrap();
        let r = back.orders.iter().find(|b| (b.m, b.n) == (o.m, o.n)).expect("the reverse order");
        let there = direction(r.theta_deg.to_radians(), r.phi_deg.to_radians());
        assert!((0..3).all(|c| (there[c] - wi[c]).abs() < 1e-9), "{there:?} vs {wi:?}");
        for (x, y) in [(o.efficiency.te, r.efficiency.te), (o.efficiency.tm, r.efficiency.tm)] {
            assert!((x - y).abs() < 1e-11 * x.max(1e-6), "order {} {}: {x} vs {y}", o.m, o.n);
        }
    }
}

#[test]
fn energy_and_reciprocity_hold_on_a_cell_with_hundreds_of_channels() {
    // A rough 2.4 µm cell at 400 nm: ~110 channels, whose scaling takes Sinkhorn's over-relaxed steps (the
    // small cells above converge in a few plain ones). Rows (energy) and columns (reciprocity) both hold.
    let n = 64;
    let h: Vec<f64> = (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64 / n as f64, (i / n) as f64 / n as f64);
            let t = std::f64::consts::TAU;
            60.0 * (t * (3.0 * x + y)).sin() + 45.0 * (t * (x - 4.0 * y)).cos() + 30.0 * (t * 7.0 * x).sin().powi(3)
        })
        .collect();
    let patch = Patch::from_row_major(n, n, 2400.0 / n as f64, 2400.0 / n as f64, &h).unwrap();
    let cell = UnitCell::new(&patch, 380.0).unwrap();
    let wi = direction(20f64.to_radians(), 0.4);
    let row = cell.row(wi, 400.0, Normalisation::Energy).unwrap();
    assert!(row.raw.len() > 100 && row.applied == "energy", "{} channels", row.raw.len());
    assert!(row.residual < 1e-13, "{:e}", row.residual);
    let ans = cell.efficiencies(wi, 400.0, &Perfect, Normalisation::Energy).unwrap();
    assert!((ans.reflected_total.unpolarized - 1.0).abs() < 1e-12, "{}", ans.reflected_total.unpolarized);
    for o in ans.orders.iter().filter(|o| o.efficiency.te > 1e-3).take(4) {
        let wr = direction(o.theta_deg.to_radians(), o.phi_deg.to_radians());
        let back = cell.efficiencies(wr, 400.0, &Perfect, Normalisation::Energy).unwrap();
        let r = back.orders.iter().find(|b| (b.m, b.n) == (o.m, o.n)).expect("the reverse order");
        assert!((o.efficiency.te - r.efficiency.te).abs() < 1e-11 * o.efficiency.te, "order {} {}", o.m, o.n);
    }
}

/// `∬ f_r cos θ_r dω_r = ∬ f_r du dv` of a continuous evaluator for light at `wi`, one wavelength, on a
/// grid over the unit disk.
fn hemispherical(e: &dyn iridis_diffraction::Evaluator, wi: Vec3, lambda: f64, n: usize) -> f64 {
    let f_r_per_rho = e.shading().unwrap().fresnel.normal_reflectance() * e.radiometric_gain(lambda).unwrap() / wi[2];
    crate::common::projected_disk_sum(n, |wr| e.reflectance(lambda, wi, wr).unwrap()) * f_r_per_rho
}

#[test]
fn energy_normalised_lobes_of_a_deep_sine_return_the_light_where_kirchhoffs_create_it() {
    // A 150 nm-amplitude sine of period 1100 nm (4 periods, window as wide as the cell) on a near-perfect
    // reflector, light at 75°: Kirchhoff's lobes return ~2× the light (the orders' 2.08), normalised ~1.
    let row: Vec<f64> = (0..256).map(|i| 150.0 * (std::f64::consts::TAU * (i % 64) as f64 / 64.0).sin()).collect();
    let heights: Vec<f64> = (0..64).flat_map(|_| row.clone()).collect();
    let patch = Patch::from_row_major(64, 256, 4400.0 / 256.0, 4400.0 / 64.0, &heights).unwrap();
    let terms = std::sync::Arc::new(
        iridis_diffraction::TaylorTerms::compute(&patch, terms_for_bound(150.0, 500.0, 1e-8).unwrap(), 4400.0).unwrap(),
    );
    let mirror = Fresnel::Index { n: Complex64::new(1e-4, 30.0) };
    let shading =
        iridis_diffraction::Shading { fresnel: std::sync::Arc::new(mirror), shadowing: false, ..Default::default() };
    let spectral = iridis_diffraction::SpectralSetup::default();
    let raw = iridis_diffraction::Reference { terms, shading, spectral: spectral.clone() };
    let wi = direction(75f64.to_radians(), 0.0);
    let before = hemispherical(&raw, wi, 500.0, 400);
    let e = LobeScaled::energy_normalised(Box::new(raw), &patch, spectral).unwrap();
    let after = hemispherical(&e, wi, 500.0, 400);
    eprintln!("75°, 500 nm: Kirchhoff's lobes return {before:.4}, normalised {after:.4}");
    assert!(before > 1.5, "{before}");
    assert!((after - 1.0).abs() < 0.03, "{after}");
    // Reciprocity at an order's direction: light from ω_r sees ω_i in the same order (same factor product).
    let wr = [-(wi[0] - 500.0 / 1100.0), 0.0, (1.0 - (wi[0] - 500.0 / 1100.0).powi(2)).sqrt()];
    use iridis_diffraction::Evaluator;
    let (a, b) = (e.reflectance(500.0, wi, wr).unwrap() / wi[2], e.reflectance(500.0, wr, wi).unwrap() / wr[2]);
    assert!((a / b - 1.0).abs() < 1e-9, "{a} vs {b}");
}

/// Below the colour grid (an animal's ultraviolet) more orders couple: lobes asked there are scaled by a cell
/// made for that wavelength, whether or not the caller said so up front (`down_to`), and a cell refuses rows
/// shorter than it serves rather than missing those orders.
#[test]
fn lobes_below_the_grid_are_scaled_by_a_cell_made_for_their_wavelength() {
    use iridis_diffraction::Evaluator;
    // A 1100 nm sine, 150 nm amplitude, 4 periods, light at 40°: 8 orders propagate at 300 nm, 6 at 380 nm
    // (|sin 40° + m λ/Λ| < 1). A cell made for 380 nm scaled the 300 nm lobes by 0.14 % less (before this test).
    let row: Vec<f64> = (0..256).map(|i| 150.0 * (std::f64::consts::TAU * (i % 64) as f64 / 64.0).sin()).collect();
    let heights: Vec<f64> = (0..64).flat_map(|_| row.clone()).collect();
    let patch = Patch::from_row_major(64, 256, 4400.0 / 256.0, 4400.0 / 64.0, &heights).unwrap();
    let spectral = iridis_diffraction::SpectralSetup::default();
    let reference = || {
        let terms =
            iridis_diffraction::TaylorTerms::compute(&patch, terms_for_bound(150.0, 300.0, 1e-8).unwrap(), 4400.0);
        let shading = iridis_diffraction::Shading::default();
        Box::new(iridis_diffraction::Reference { terms: terms.unwrap().into(), shading, spectral: spectral.clone() })
    };
    let on_the_grid = LobeScaled::energy_normalised(reference(), &patch, spectral.clone()).unwrap();
    assert_eq!(on_the_grid.cell().lambda_min_nm(), spectral.wavelengths()[0]);
    let made_for_300 =
        LobeScaled::down_to(reference(), &patch, spectral.clone(), std::sync::Arc::new(SinkhornEnergy), 300.0).unwrap();
    let wi = direction(40f64.to_radians(), 0.0);
    // Towards the first order at 300 nm (sin θ_r = sin 40° − 300/1100, on the specular side) and the mirror.
    let s1 = 40f64.to_radians().sin() - 300.0 / 1100.0;
    for wr in [[-s1, 0.0, (1.0 - s1 * s1).sqrt()], [-wi[0], 0.0, wi[2]]] {
        let (a, b) =
            (on_the_grid.reflectance(300.0, wi, wr).unwrap(), made_for_300.reflectance(300.0, wi, wr).unwrap());
        assert!(a > 0.0 && (a / b - 1.0).abs() < 1e-12, "{a} vs {b}");
        // On the grid both give what a cell made for 380 nm gives.
        let (a, b) =
            (on_the_grid.reflectance(500.0, wi, wr).unwrap(), made_for_300.reflectance(500.0, wi, wr).unwrap());
        assert!((a / b - 1.0).abs() < 1e-9, "{a} vs {b}");
    }
    assert_eq!(on_the_grid.cell().lambda_min_nm(), 300.0);
    let e = UnitCell::new(&patch, 380.0).unwrap().row(wi, 300.0, Normalisation::Energy).unwrap_err().to_string();
    assert!(e.contains("serves 380 nm and longer"), "{e}");
}

#[test]
fn a_cell_for_one_light_gives_the_same_bits_and_refuses_other_light() {
    // 8 µm crossed cell: > 600 channels at 400 and 500 nm (rows normalised alone), so `for_light` keeps
    // only the bins within 1/λ of ω_i,xy/λ; its orders are those of the cell for every light, bit for bit.
    let h: Vec<f64> = (0..80 * 80)
        .map(|i| {
            let (x, y) = ((i % 80) as f64 / 80.0, (i / 80) as f64 / 80.0);
            45.0 * (std::f64::consts::TAU * 7.0 * x).sin() + 20.0 * (std::f64::consts::TAU * (3.0 * x + 5.0 * y)).cos()
        })
        .collect();
    let patch = Patch::from_row_major(80, 80, 100.0, 100.0, &h).unwrap();
    let wi = direction(40f64.to_radians(), 1.1);
    let glass = Fresnel::Index { n: Complex64::new(1.5, 0.0) };
    let all = UnitCell::new(&patch, 400.0).unwrap();
    let one = UnitCell::for_light(&patch, wi, &[400.0, 500.0]).unwrap();
    assert!(
        one.terms.memory_bytes() * 3 < all.terms.memory_bytes(),
        "{} vs {}",
        one.terms.memory_bytes(),
        all.terms.memory_bytes()
    );
    for lambda in [400.0, 500.0] {
        for norm in [Normalisation::Energy, Normalisation::Kirchhoff] {
            let a = all.efficiencies(wi, lambda, &glass, norm).unwrap();
            assert_eq!(a.normalisation, if norm == Normalisation::Energy { "energy-row" } else { "kirchhoff" });
            assert_eq!(one.efficiencies(wi, lambda, &glass, norm).unwrap(), a);
        }
    }
    assert!(one.efficiencies(direction(0.3, 0.0), 500.0, &glass, Normalisation::Energy).is_err());
    assert!(one.efficiencies(wi, 390.0, &glass, Normalisation::Energy).is_err());
    // Few channels (the full scaling reads every direction's bins): the cell for every light.
    let small = UnitCell::for_light(&patch, wi, &[400.0, 5000.0]).unwrap();
    assert_eq!(small.terms.memory_bytes(), all.terms.memory_bytes());
}

#[test]
fn a_flat_cell_is_a_mirror_with_fresnels_reflectance() {
    let patch = Patch::from_row_major(8, 8, 100.0, 100.0, &[5.0; 64]).unwrap();
    let cell = UnitCell::new(&patch, 380.0).unwrap();
    let glass = Fresnel::Index { n: Complex64::new(1.5, 0.0) };
    let wi = direction(60f64.to_radians(), 0.0);
    let ans = cell.efficiencies(wi, 500.0, &glass, Normalisation::Energy).unwrap();
    let [rs, rp] = iridis_diffraction::geometry::fresnel_sp(Complex64::new(1.5, 0.0), 0.5);
    for o in &ans.orders {
        let want = if (o.m, o.n) == (0, 0) { [rs, rp] } else { [0.0, 0.0] };
        assert!((o.efficiency.te - want[0]).abs() < 1e-14 && (o.efficiency.tm - want[1]).abs() < 1e-14, "{o:?}");
    }
}

/// Rows the same but for plane levelling's rounding (1e-14 nm on a 200 nm relief) make a 1-D grating: exact
/// equality made a tiled sine crossed along one axis and 1-D along the other, and sent the crossed one to the
/// 2-D solver's order limit. A row that differs by a picometre is a crossed grating.
#[test]
fn rows_equal_but_for_rounding_are_a_1d_grating() {
    let (rows, cols) = (4, 16);
    let sine: Vec<f64> = (0..cols).map(|i| 100.0 * (std::f64::consts::TAU * i as f64 / 16.0).sin()).collect();
    let field = |shift: f64| -> Patch {
        let h: Vec<f64> = (0..rows).flat_map(|j| sine.iter().map(move |v| v + shift * j as f64)).collect();
        Patch::from_row_major(rows, cols, 10.0, 10.0, &h).unwrap()
    };
    assert_eq!(Lines::of(&field(1e-14)), Lines::AlongX);
    assert_eq!(Lines::of(&field(1e-3)), Lines::Crossed);
}
