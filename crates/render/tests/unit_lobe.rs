//! The unit tests of src/lobe.rs, moved here so that `cargo test` compiles the library once.

use iridis_diffraction::table::{grid_value, Lookup, LookupTable, TableMeta};
use iridis_diffraction::Shading;
use iridis_render::lobe::*;
use iridis_render::math::*;
use std::sync::Arc;

/// A table with one power whose values are a known function of (u, v), on a coarse power grid.
fn table(res: usize, value: impl Fn(f64, f64) -> f64) -> Lookup {
    let uv: Vec<f64> = (0..res).map(|i| grid_value(i, res, 3.0)).collect();
    let mut data = vec![0.0; res * res * 3];
    for iv in 0..res {
        for iu in 0..res {
            for c in 0..3 {
                data[(iv * res + iu) * 3 + c] = value(uv[iu], uv[iv]) * (c + 1) as f64;
            }
        }
    }
    let meta = TableMeta {
        format: "test".into(),
        version: 0,
        surface: "test".into(),
        rows: 1,
        cols: 1,
        dx_nm: 1.0,
        dy_nm: 1.0,
        max_abs_height_nm: 0.0,
        taylor_terms: 0,
        coherence_nm: 1.0,
        uv_resolution: res,
        uv_power: 3.0,
        illuminant: "d65".into(),
        observer: "cie1931".into(),
        wavelength_step_nm: 5.0,
        wavelength_min_nm: 500.0,
        wavelength_max_nm: 500.0,
        layout: String::new(),
        warnings: Vec::new(),
        surface_fingerprint: None,
        light_spectrum: None,
        units: "relative".into(),
        built_on: None,
    };
    let t = LookupTable { meta, uv, wavelengths_nm: vec![500.0], data };
    Lookup::new(Arc::new(t), Shading::default(), iridis_diffraction::table::Precision::F64).unwrap()
}

#[test]
fn the_tables_integrate_a_bilinear_function_exactly() {
    // A bilinear function of u and v is its own interpolant: the box integral is the closed form, at any
    // box, in or across cells.
    let f = |u: f64, v: f64| 1.0 + 0.3 * u - 0.2 * v + 0.1 * u * v;
    let l = table(9, f);
    let p = Prefiltered::new(&l);
    let exact = |u0: f64, u1: f64, v0: f64, v1: f64| {
        let (a, b) = (u1 - u0, v1 - v0);
        let (su, sv) = (0.5 * (u1 * u1 - u0 * u0), 0.5 * (v1 * v1 - v0 * v0));
        a * b + 0.3 * su * b - 0.2 * a * sv + 0.1 * su * sv
    };
    for (u0, u1, v0, v1) in [(-1.9, 1.7, -1.2, 0.4), (0.01, 0.02, -0.015, -0.011), (-0.6, 0.3, 0.2, 1.95)] {
        let got = p.integral(&l.table.data, u0, u1, v0, v1, 0.0);
        for c in 0..3 {
            let want = exact(u0, u1, v0, v1) * (c + 1) as f64;
            assert!((got[c] - want).abs() < 1e-12 * want.abs().max(1.0), "{got:?} vs {want}");
        }
    }
}

#[test]
fn the_lobe_sampler_draws_its_pdf() {
    // A Gaussian lobe about (u, v) = (0.2, -0.1): sampled directions report the pdf of pdf(), the pdf
    // integrates to the fraction of (u, v) mass above the horizon, and E[g/pdf] = ∫ g dω for a test g.
    let l = table(41, |u, v| (-((u - 0.2).powi(2) + (v + 0.1).powi(2)) / 0.02).exp());
    let s = LobeSampler::new(&l);
    let lo = normalize([-0.25, 0.05, 0.9]);
    iridis_render::sampling::seed(4, 0);
    let n = 100_000;
    let (mut acc, mut acc2) = (0.0, 0.0);
    for _ in 0..n {
        let x = match s.sample(lo, iridis_render::sampling::next2()) {
            Some((li, pdf)) => {
                assert!((s.pdf(lo, li) - pdf).abs() < 1e-9 * pdf, "{} vs {pdf}", s.pdf(lo, li));
                // g = cos θ_i × a Gaussian in (u, v) narrower than the lobe (so that g / pdf stays bounded).
                let (u, v) = (-li[0] - lo[0], -li[1] - lo[1]);
                li[2] * (-((u - 0.2).powi(2) + (v + 0.1).powi(2)) / 0.01).exp() / pdf
            }
            None => 0.0,
        };
        acc += x;
        acc2 += x * x;
    }
    let mean = acc / n as f64;
    let se = ((acc2 / n as f64 - mean * mean) / n as f64).sqrt();
    // ∫ g dω = ∫ exp(−|x − x_0|² / 0.01) dA over the unit disk (dω = dA / cos θ): the Gaussian's π·0.01,
    // its centre (0.05, 0.05) lying 9 widths inside the disk.
    let want = std::f64::consts::PI * 0.01;
    assert!((mean - want).abs() < 4.0 * se, "{mean} ± {se} vs {want}");
}
