//! Stam's models against their own closed forms and against the measured-height-field methods; comparisons,
//! sweeps and the laser experiment against physical laws.

use crate::common;

use iridis_color::{Illuminant, Observer, Spectrum};
use iridis_diffraction::geometry::direction;
use iridis_diffraction::{Evaluator, Patch, Reference, Shading, SpectralSetup};
use iridis_lab::image::{render, Pixels};
use iridis_lab::methods::{Method, MethodConfig, Workbench};
use iridis_lab::stam::{Bump, Lattice, StamGaussian, StamPeriodic};

/// A lattice of bumps sampled on a grid: `cells` cells of `cx × cy` pixels, bump `ax × ay` pixels.
fn lattice_patch(
    bump: Bump,
    dx: f64,
    (cx, cy): (usize, usize),
    (ax, ay): (usize, usize),
    cells: (usize, usize),
    h: f64,
) -> Patch {
    let (cols, rows) = (cx * cells.0, cy * cells.1);
    let mut heights = vec![0.0; rows * cols];
    for r in 0..rows {
        for c in 0..cols {
            let (i, j) = (c % cx, r % cy);
            if i < ax && j < ay {
                heights[r * cols + c] = match bump {
                    Bump::Rectangular => h,
                    Bump::Triangular => {
                        // Tent across the bump's width, sampled at pixel centres.
                        let x = (i as f64 + 0.5) / ax as f64 - 0.5;
                        h * (1.0 - 2.0 * x.abs())
                    }
                };
            }
        }
    }
    Patch::from_row_major(rows, cols, dx, dx, &heights).unwrap()
}

/// The reference evaluator, its Taylor remainder below 1e-9.
fn reference(patch: &Patch, coherence: f64) -> Reference {
    common::reference(patch, coherence, 1e-9)
}

/// The view direction that sends light from `wi` into lattice order `(n, m)` at λ.
fn order_direction(wi: [f64; 3], n: f64, m: f64, px: f64, py: f64, lambda: f64) -> [f64; 3] {
    // f = (−u/λ, −v/λ) = (n/Δx, m/Δy) with (u, v) = −ω_i − ω_r.
    let (u, v) = (-n * lambda / px, -m * lambda / py);
    let (x, y) = (-wi[0] - u, -wi[1] - v);
    [x, y, (1.0 - x * x - y * y).sqrt()]
}

#[test]
fn stam_periodic_matches_the_perfect_lattice_it_assumes() {
    // 1200 × 800 nm cells, bumps half as wide and long, 80 nm high, 8 × 8 cells: the measured-height-field
    // method sees exactly Stam's lattice, so at each order's direction the two must agree.
    let dx = 20.0;
    for bump in [Bump::Rectangular, Bump::Triangular] {
        let patch = lattice_patch(bump, dx, (60, 40), (30, 20), (8, 8), 80.0);
        let e = reference(&patch, 1e9); // window ≪ one DFT bin: the patch is one period of an infinite lattice
        let lattice =
            Lattice { period_x: 1200.0, period_y: Some(800.0), width: 600.0, length: 400.0, height: 80.0, bump };
        let stam = StamPeriodic::new(lattice, 0.01, 1e9, Shading::default(), SpectralSetup::default()).unwrap();
        let wi = direction(30f64.to_radians(), 0.0);
        let mut checked = 0;
        for lambda in [450.0, 550.0, 650.0] {
            for (n, m) in [(1.0, 0.0), (-1.0, 0.0), (1.0, 1.0), (0.0, -1.0), (-2.0, 1.0), (0.0, 0.0)] {
                let wr = order_direction(wi, n, m, 1200.0, 800.0, lambda);
                if !wr[2].is_finite() || wr[2] < 0.05 {
                    continue;
                }
                let ours = e.reflectance(lambda, wi, wr).unwrap();
                let theirs = stam.reflectance(lambda, wi, wr).unwrap();
                // The sampled bump differs from the continuous one by (πn/60)²/6 ≈ 5e-4 in its coefficients.
                assert!(
                    (ours - theirs).abs() <= 5e-3 * theirs.max(1e-4),
                    "{bump:?} λ={lambda} order ({n},{m}): reference {ours:.6} vs Stam {theirs:.6}"
                );
                checked += 1;
            }
        }
        assert!(checked >= 12, "{checked}");
        // Off every order (0.3 of an order away) Stam's ε selection gives nothing.
        let wr = order_direction(wi, 1.3, 0.0, 1200.0, 800.0, 550.0);
        assert_eq!(stam.reflectance(550.0, wi, wr).unwrap(), 0.0);
    }
}

/// Gaussian heights, uncorrelated from pixel to pixel (Box–Muller on a fixed LCG).
fn white_noise(rows: usize, cols: usize, sigma: f64, seed: u64) -> Vec<f64> {
    let mut s = seed;
    let mut u = || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((s >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    (0..rows * cols)
        .map(|_| {
            let (a, b) = (u(), u());
            sigma * (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
        })
        .collect()
}

#[test]
fn stam_gaussian_obeys_debye_waller_on_a_gaussian_surface() {
    // For Gaussian heights the coherent (mirror) reflection falls by e^{−g}, g = (k w σ_h)² (Stam 1999; Beckmann):
    // both Stam's correlation model and the measured-height-field reference must show it, and their diffuse
    // background must agree on average ((1 − e^{−g})/N per DFT bin for uncorrelated heights).
    let (rows, cols, dx) = (64, 64, 50.0);
    let h = white_noise(rows, cols, 20.0, 11);
    let patch = Patch::from_row_major(rows, cols, dx, dx, &h).unwrap();
    let coherence = 1e9;
    let stam = StamGaussian::new(&patch, coherence, Shading::default(), SpectralSetup::default()).unwrap();
    let e = reference(&patch, coherence);
    let normal = [0.0, 0.0, 1.0];
    let lambda = 500.0;
    let sigma = stam.sigma_h;
    let g = (std::f64::consts::TAU / lambda * 2.0 * sigma).powi(2);
    let debye_waller = (-g).exp();
    let s0 = stam.reflectance(lambda, normal, normal).unwrap();
    let r0 = e.reflectance(lambda, normal, normal).unwrap();
    assert!((s0 - debye_waller).abs() < 2e-3 * debye_waller, "Stam {s0} vs e^-g {debye_waller}");
    assert!((r0 - debye_waller).abs() < 0.05 * debye_waller, "reference {r0} vs e^-g {debye_waller}");
    // Diffuse: 16 bins around normal viewing, each against (1 − e^{−g})/N at its own w.
    let (lx, ly) = (cols as f64 * dx, rows as f64 * dx);
    let (mut sum_s, mut sum_r) = (0.0, 0.0);
    let mut expected = 0.0;
    let shading = Shading::default();
    for s in 1..=4 {
        for t in 1..=4 {
            let (fx, fy) = (s as f64 / lx, t as f64 / ly);
            let wr = [-fx * lambda, -fy * lambda, (1.0 - (fx * lambda).powi(2) - (fy * lambda).powi(2)).sqrt()];
            sum_s += stam.reflectance(lambda, normal, wr).unwrap();
            sum_r += e.reflectance(lambda, normal, wr).unwrap();
            let gb = (std::f64::consts::TAU / lambda * (1.0 + wr[2]) * sigma).powi(2);
            expected += shading.factor(lambda, normal, wr) * (1.0 - (-gb).exp()) / (rows * cols) as f64;
        }
    }
    let ratio = sum_r / sum_s;
    assert!((ratio - 1.0).abs() < 0.2, "diffuse power: reference/Stam = {ratio}");
    assert!((sum_s / expected - 1.0).abs() < 0.25, "Stam diffuse {sum_s} vs {expected}");
}

#[test]
fn comparison_and_terms_sweep_behave() {
    // A jittered lattice (a "biological" surface: periodic on average, irregular in detail).
    let (rows, cols, dx) = (48, 48, 50.0);
    let noise = white_noise(rows, cols, 1.0, 5);
    let h: Vec<f64> = (0..rows * cols)
        .map(|k| {
            let (r, c) = (k / cols, k % cols);
            let x = c as f64 * dx + 150.0 * noise[r * cols + (c / 8) * 8 % cols];
            60.0 * (std::f64::consts::TAU * x / 800.0).sin().max(0.0) + 5.0 * noise[k]
        })
        .collect();
    let patch = Patch::from_row_major(rows, cols, dx, dx, &h).unwrap();
    let config = MethodConfig {
        coherence_nm: 1000.0,
        spectral: SpectralSetup::new(Illuminant::D65, Observer::Cie1931, 10.0).unwrap(),
        ..MethodConfig::default()
    };
    let bench = Workbench::new(patch, config, "jittered").unwrap();
    let pixels = Pixels::brdf_map(0.3, 0.0, 25);
    let truth = render(bench.evaluator(Method::GroundTruth, &|_| {}).unwrap().as_ref(), &pixels, &|_| {});
    let mut mean = std::collections::BTreeMap::new();
    for m in [Method::Reference, Method::StamPeriodic(Bump::Rectangular), Method::StamGaussian] {
        let img = render(bench.evaluator(m, &|_| {}).unwrap().as_ref(), &pixels, &|_| {});
        let s = iridis_lab::compare::stats(&iridis_lab::compare::delta_e_map(&img, &truth, 1000.0));
        mean.insert(m.name(), s.mean);
    }
    eprintln!("mean ΔE at 1000 RU against the ground truth: {mean:?}");
    let ours = mean["reference"];
    assert!(ours < 2.0, "reference vs ground truth: mean ΔE {ours}");
    for stam in ["stam-periodic", "stam-gaussian"] {
        assert!(mean[stam] > 2.0 * ours, "{stam}: {} vs reference {ours}", mean[stam]);
    }
    // Convergence in the number of Taylor terms: 1 term is far off, the bound's count is close.
    let (_, points) = iridis_lab::sweep::run(
        &bench,
        Method::Reference,
        iridis_lab::sweep::Param::Terms,
        &[1.0, 4.0, 20.0],
        &pixels,
        &[1000.0],
        Method::GroundTruth,
        &|_| {},
    )
    .unwrap();
    let e: Vec<f64> = points.iter().map(|p| p.errors[0].1).collect();
    eprintln!("terms sweep 1, 4, 20: {e:?}");
    assert!(e[0] > e[1] && e[1] > e[2] && e[2] < 2.0, "{e:?}");
    // A parameter the method does not have is refused by name.
    let err = iridis_lab::sweep::run(
        &bench,
        Method::Reference,
        iridis_lab::sweep::Param::UvPower,
        &[2.0],
        &pixels,
        &[1.0],
        Method::Reference.model_truth(),
        &|_| {},
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("no parameter 'uv-power'") && err.contains("lookup"), "{err}");
}

#[test]
fn laser_spot_lands_where_the_grating_equation_puts_it() {
    // A 1000 nm sinusoidal grating under a green (530–535 nm) beam at 45°: the first order leaves at
    // sin θ_r = sin 45° − λ/d and hits the screen 100 mm away at a = D (ω_r·e₁)/(ω_r·s).
    let (d, px, periods) = (1000.0, 20, 12);
    let dx = d / px as f64;
    let h: Vec<f64> = (0..2 * px * periods)
        .map(|k| 40.0 * (std::f64::consts::TAU * (k % (px * periods)) as f64 * dx / d).sin())
        .collect();
    let patch = Patch::from_row_major(2, px * periods, dx, dx, &h).unwrap();
    let beam =
        Spectrum::new(vec![520.0, 529.0, 530.0, 535.0, 536.0, 545.0], vec![0.0, 0.0, 1.0, 1.0, 0.0, 0.0]).unwrap();
    let mut config = MethodConfig {
        coherence_nm: 5_000.0,
        spectral: SpectralSetup::with_range(Illuminant::E, Observer::Cie1931, 525.0, 540.0, 1.0).unwrap(),
        ..MethodConfig::default()
    };
    let gold = iridis_lab::laser::MetalFresnel::new(iridis_thinfilm::Material::builtin("gold").unwrap(), 525.0, 540.0)
        .unwrap();
    let scale =
        iridis_lab::laser::configure(&mut config, Method::Reference, &beam, Some(&gold), Observer::Cie1931).unwrap();
    assert!(scale > 0.5 && scale < 0.9, "gold mirror brightness under green light: {scale}");
    let bench = Workbench::new(patch, config, "sine").unwrap();
    let setup = iridis_lab::laser::LaserSetup {
        width_px: 101,
        height_px: 5,
        subsamples: 1,
        screen_height_nm: 15e6,
        ..Default::default()
    };
    let pixels = setup.pixels().unwrap();
    let img = render(bench.evaluator(Method::Reference, &|_| {}).unwrap().as_ref(), &pixels, &|_| {});
    // Brightest pixel of the middle row outside the mirror's spot.
    let row = 2;
    let (best, _) = (0..101)
        .filter(|c| (*c as i64 - 50).abs() > 5)
        .map(|c| (c, img[row * 101 + c].map(|x| x.y).unwrap_or(0.0)))
        .fold((0, f64::NEG_INFINITY), |b, x| if x.1 > b.1 { x } else { b });
    let theta = (45f64.to_radians().sin() - 532.5 / d).asin();
    let wr = [-theta.sin(), 0.0, theta.cos()];
    let (_, s, e1, _) = setup.frame();
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let a = setup.distance_nm * dot(wr, e1) / dot(wr, s);
    let expected_col = (a / setup.screen_width_nm + 0.5) * 101.0 - 0.5;
    assert!((best as f64 - expected_col).abs() <= 1.0, "spot at column {best}, grating equation {expected_col:.2}");
}

/// Stam's periodic model finds each order's wavelengths from its grating condition: for a 1-D grating
/// (d = 1500 nm) lit at 30°, the view where the grating equation `n λ / d = sin θ_i − sin θ_r` puts order 1 at
/// 550 nm sees order 1 at exactly 550 nm, inside its ε band `[a/(1+ε), a/(1−ε)]`, `a = d (sin θ_i − sin θ_r)`;
/// order 2 would need 275 nm, outside the visible range, and is absent.
#[test]
fn stam_periodic_orders_follow_the_grating_equation() {
    let (d, eps) = (1500.0, 0.01);
    let lattice =
        Lattice { period_x: d, period_y: None, width: 750.0, length: 0.0, height: 60.0, bump: Bump::Rectangular };
    let stam = StamPeriodic::new(lattice, eps, 20_000.0, Shading::default(), SpectralSetup::default()).unwrap();
    let ti = 30f64.to_radians();
    let wi = direction(ti, 0.0);
    let sin_r = ti.sin() - 550.0 / d;
    let wr = [-sin_r, 0.0, (1.0 - sin_r * sin_r).sqrt()];
    let orders = stam.orders(wi, wr, 380.0, 780.0);
    assert_eq!(orders.len(), 1, "{orders:?}");
    let o = orders[0];
    assert_eq!((o.n, o.m), (1, 0));
    let a = d * (ti.sin() - sin_r);
    assert!((o.wavelength_nm.unwrap() - 550.0).abs() < 1e-9, "{o:?}");
    assert!((o.band_nm.0 - a / (1.0 + eps)).abs() < 1e-9 && (o.band_nm.1 - a / (1.0 - eps)).abs() < 1e-9, "{o:?}");
    // Every order listed anywhere on the plane of incidence satisfies the grating equation at its wavelength.
    for k in 0..60 {
        let s = -0.95 + k as f64 * 0.032;
        let wr = [-s, 0.0, (1.0 - s * s).sqrt()];
        for o in stam.orders(wi, wr, 380.0, 780.0) {
            if let Some(l) = o.wavelength_nm {
                assert!((o.n as f64 * l / d - (ti.sin() - s)).abs() < 1e-12, "{o:?} at sin θr = {s}");
                assert!((380.0..=780.0).contains(&l) || o.band_nm.0 <= 380.0 || o.band_nm.1 >= 780.0, "{o:?}");
            }
        }
    }
}

/// The orders a map shows do not depend on the wavelength step: at Δλ = 5 nm and 1 nm the same pixels light
/// up and their colours agree. Testing ε at grid wavelengths instead (what `reflectance` answers per λ, summed
/// over the grid) loses orders whose ε band falls between two 5 nm samples — the control below.
#[test]
fn stam_periodic_maps_show_the_same_orders_at_5nm_and_1nm() {
    let lattice = Lattice {
        period_x: 1200.0,
        period_y: Some(900.0),
        width: 600.0,
        length: 450.0,
        height: 60.0,
        bump: Bump::Rectangular,
    };
    let setup = |step: f64| SpectralSetup::new(Illuminant::D65, Observer::Cie1931, step).unwrap();
    let model = |step: f64| StamPeriodic::new(lattice, 0.01, 20_000.0, Shading::default(), setup(step)).unwrap();
    let (coarse, fine) = (model(5.0), model(1.0));
    let pixels = Pixels::brdf_map(0.4, 0.0, 61);
    let (a, b) = (render(&coarse, &pixels, &|_| {}), render(&fine, &pixels, &|_| {}));
    let lit =
        |img: &[Option<iridis_color::Xyz>]| -> Vec<bool> { img.iter().map(|p| p.is_some_and(|x| x.y > 0.0)).collect() };
    let (la, lb) = (lit(&a), lit(&b));
    let shown = la.iter().filter(|&&l| l).count();
    assert!(shown > 40, "only {shown} pixels show an order");
    assert_eq!(la, lb, "the pixels that show an order differ between 5 nm and 1 nm");
    let s = iridis_lab::compare::stats(&iridis_lab::compare::delta_e_map(&a, &b, 1000.0));
    assert!(s.mean < 0.05 && s.max < 1.0, "5 nm vs 1 nm: {s:?}");
    // Control: the grid-sampled ε test at 5 nm misses orders that it finds at 1 nm.
    let grid = |m: &StamPeriodic| -> Vec<bool> {
        pixels
            .samples
            .iter()
            .map(|s| {
                s.iter().any(|&(wi, wr, _)| {
                    m.spectral.wavelengths().iter().any(|&l| m.reflectance(l, wi, wr).unwrap_or(0.0) > 0.0)
                })
            })
            .collect()
    };
    let (ga, gb) = (grid(&coarse), grid(&fine));
    let missed = ga.iter().zip(&gb).filter(|(a, b)| !**a && **b).count();
    assert!(missed > 0, "the control should show the grid-sampled test losing orders at 5 nm");
}

/// `compare`'s lookup builds its table only at the nodes the map reads (issue 32: a 64² crop spent 44 of 46 s
/// building a 501² table): the map is bit for bit the whole table's, from a small share of its nodes.
#[test]
fn the_lookup_of_a_map_builds_only_the_nodes_it_reads() {
    let patch = common::sine_along_x(32, 32, 50.0, 40.0, 400.0);
    let config = MethodConfig {
        coherence_nm: 800.0,
        spectral: SpectralSetup::new(Illuminant::D65, Observer::Cie1931, 20.0).unwrap(),
        table: iridis_diffraction::table::TableParams { uv_resolution: 101, uv_power: 5.0 },
        ..MethodConfig::default()
    };
    let bench = Workbench::new(patch, config, "sine").unwrap();
    let pixels = Pixels::brdf_map(0.3, 0.4, 16);
    let whole = render(bench.evaluator(Method::Lookup, &|_| {}).unwrap().as_ref(), &pixels, &|_| {});
    let sparse = render(bench.lookup_for(&pixels, &|_| {}).unwrap().as_ref(), &pixels, &|_| {});
    assert_eq!(whole, sparse);
    assert!(whole.iter().flatten().any(|x| x.y > 1e-6), "the map shows something");
    let dirs = pixels.samples.iter().flatten().map(|&(wi, wr, _)| (wi, wr));
    let nodes = iridis_diffraction::table::nodes_for(bench.config.table, dirs).iter().filter(|&&n| n).count();
    // At most four nodes per pixel, far fewer than the table's 101².
    assert!(nodes <= 4 * pixels.len() && nodes * 10 < 101 * 101, "{nodes} nodes");
}
