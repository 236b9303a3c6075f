//! The unit tests of src/rigorous_brdf.rs (the rigorous BRDF's lobes, reciprocity and peak), moved here so that
//! `cargo test` compiles the library once.

use iridis_api::grating::{material_fresnel, RigorousCell};
use iridis_api::rigorous_brdf::*;
use iridis_api::surface::{Source, SurfaceOptions};
use iridis_api::ModelOptions;
use iridis_diffraction::geometry::direction;
use iridis_diffraction::geometry::Vec3;
use iridis_diffraction::grating::Lines;
use iridis_diffraction::{Evaluator, Patch};

/// One period (1100 nm) of a sine of `amplitude` nm, 4 identical rows: a 1-D grating along x.
fn sine_cell(amplitude: f64) -> CellChoice {
    let cols = 110;
    let row: Vec<f64> = (0..cols).map(|i| amplitude * (std::f64::consts::TAU * i as f64 / cols as f64).sin()).collect();
    let heights: Vec<f64> = (0..4).flat_map(|_| row.clone()).collect();
    let patch = Patch::from_row_major(4, cols, 10.0, 10.0, &heights).unwrap();
    CellChoice { patch, averaged: None, scan_extent_nm: 1100.0 }
}

/// A window of 5 µm (lobes ~0.06 wide in direction cosines, resolved by a fine grid) and a 20 nm grid.
fn model() -> ModelOptions {
    ModelOptions { coherence_nm: Some(5000.0), step_nm: Some(20.0), ..Default::default() }
}

/// `f_r` (sr⁻¹, unpolarised) of the rigorous BRDF.
fn brdf(e: &RigorousBrdf, lambda: f64, wi: Vec3, wr: Vec3) -> f64 {
    let rho = e.reflectance(lambda, wi, wr).unwrap();
    e.shading().unwrap().fresnel.normal_reflectance() * rho * e.radiometric_gain(lambda).unwrap() / wi[2]
}

#[test]
fn the_lobes_return_maxwells_hemispherical_reflectance() {
    // ∬ f_r cos θ_r dω_r = ∬ f_r du dv over the unit disk: the lobes together carry the rigorous reflected
    // total (gold: absorbing, so the total is below 1 and the check is not energy conservation by accident).
    let cell = sine_cell(60.0);
    let e = RigorousBrdf::new(cell.clone(), Some("gold"), &model(), &iridis_api::Quiet).unwrap();
    let (lambda, wi) = (500.0, direction(20f64.to_radians(), 0.0));
    let n = 500;
    let du = 2.0 / n as f64;
    let mut sum = 0.0;
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (-1.0 + (i as f64 + 0.5) * du, -1.0 + (j as f64 + 0.5) * du);
            if x * x + y * y < 1.0 {
                sum += brdf(&e, lambda, wi, [x, y, (1.0 - x * x - y * y).sqrt()]) * du * du;
            }
        }
    }
    let metal = material_fresnel("gold", 380.0, 780.0).unwrap();
    let solved = RigorousCell::new(&cell.patch, Lines::AlongX, &iridis_api::Quiet)
        .solve(lambda, wi, metal.index(lambda))
        .unwrap();
    let total = solved.reflected_total.unpolarized;
    eprintln!("lobes {sum:.5}, rigorous total {total:.5}, orders {}", solved.orders.len());
    assert!(solved.orders.len() >= 3 && total < 0.9, "{total}");
    // The lobe-versus-order accuracy of a 5 µm window (measured 0.48 %: the obliquity and Fresnel factors
    // vary across the lobe, which the order's factor takes at its centre).
    assert!((sum / total - 1.0).abs() < 1e-2, "lobes {sum} vs Maxwell {total}");
}

#[test]
fn the_rigorous_brdf_is_reciprocal_at_its_orders() {
    // Light from ω_i into order 1 along ω_r, and back: rigorous efficiencies obey reciprocity (TE and TM
    // apart in the classical mount), so f_r(ω_i, ω_r) = f_r(ω_r, ω_i) to the solver's tolerance (1e-3).
    let e = RigorousBrdf::new(sine_cell(80.0), Some("n=1.5"), &model(), &iridis_api::Quiet).unwrap();
    let lambda = 540.0;
    let wi = direction(25f64.to_radians(), 0.0);
    // m λ/Λ = sin θ_i − sin θ_r (θ_r on the specular side).
    let s = wi[0] - lambda / 1100.0;
    let wr = [-s, 0.0, (1.0 - s * s).sqrt()];
    let (a, b) = (brdf(&e, lambda, wi, wr), brdf(&e, lambda, wr, wi));
    eprintln!("f_r(ω_i, ω_r) = {a:.6} sr⁻¹, f_r(ω_r, ω_i) = {b:.6} sr⁻¹");
    assert!(a > 1e-3, "{a}");
    assert!((a / b - 1.0).abs() < 2e-3, "{a} vs {b}");
    for k in 0..2 {
        let (pa, pb) = (e.polarisation(lambda, wi, wr).unwrap()[k], e.polarisation(lambda, wr, wi).unwrap()[k]);
        assert!((pa * a / (pb * b) - 1.0).abs() < 3e-3, "polarisation {k}: {pa} vs {pb}");
    }
}

#[test]
fn the_first_orders_lobe_peaks_at_the_grating_equations_angle() {
    // The light's 65 µm window: lobes ~0.006 wide in direction cosines, so the smooth factors across the
    // lobe (cos θ_r, the obliquity) move its peak by far less than the 0.002° steps of the scan (with a
    // 5 µm window they move it by 0.06°).
    let narrow = ModelOptions { step_nm: Some(20.0), ..Default::default() };
    let e = RigorousBrdf::new(sine_cell(40.0), None, &narrow, &iridis_api::Quiet).unwrap();
    let (lambda, ti) = (620.0, 10f64.to_radians());
    let wi = direction(ti, 0.0);
    let expect = (ti.sin() - lambda / 1100.0).asin();
    // Scan the plane of incidence ±1° around it at 0.002°.
    let (mut best, mut at) = (0.0, 0.0);
    for k in 0..1000 {
        let t = expect + (k as f64 * 0.002 - 1.0).to_radians();
        let wr = [-t.sin(), 0.0, t.cos()];
        let f = brdf(&e, lambda, wi, wr);
        if f > best {
            (best, at) = (f, t);
        }
    }
    assert!(best > 1.0, "{best}");
    let (got, want) = (at.to_degrees(), expect.to_degrees());
    assert!((got - want).abs() < 0.005, "peak at {got:.4}°, grating equation {want:.4}°");
}

#[test]
fn a_scan_too_long_to_be_one_period_is_refused_naming_unit_cell_auto() {
    let row: Vec<f64> = (0..2000).map(|i| 50.0 * (i as f64 * 0.057).sin()).collect();
    let heights: Vec<f64> = (0..2).flat_map(|_| row.clone()).collect();
    let patch = Patch::from_row_major(2, 2000, 10.0, 10.0, &heights).unwrap();
    let source = Source::Patch { patch, name: "scan".into() };
    let err = unit_cell(&source, &SurfaceOptions::default(), false, 380.0, &iridis_api::Quiet).unwrap_err();
    assert!(format!("{err:#}").contains("--unit-cell auto"), "{err:#}");
}
