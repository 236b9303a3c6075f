//! The exact derivatives of `iridis_thinfilm::jet` against a closed form (the Airy formula of one layer)
//! and against high-accuracy finite differences (Richardson-extrapolated central differences, error
//! O(h⁴), ~1e-11 here) on coherent, absorbing, oblique and mixed (`inc:`) stacks, for R, T, ψ and Δ.

use iridis_thinfilm::jet::{Jet, Tangent};
use iridis_thinfilm::{Complex64, Material, Stack};

/// `Stack` from (index, thickness) of every medium (the ends' thickness ignored) and coherency flags.
fn build(media: &[(Complex64, f64, bool)]) -> Stack {
    let mut s = Stack::parse(&format!("air |{} air", " air 1nm |".repeat(media.len() - 2))).unwrap();
    let m = |z: Complex64| Material::constant(format!("n={z}"), z).unwrap();
    s.incident = m(media[0].0);
    s.substrate = m(media[media.len() - 1].0);
    for (l, x) in s.layers.iter_mut().zip(&media[1..media.len() - 1]) {
        l.material = m(x.0);
        l.thickness_nm = x.1;
        l.incoherent = x.2;
    }
    s
}

/// A parameter: the thickness of layer `j` (1-based medium index), or the real / imaginary part of the
/// index of medium `j`.
#[derive(Clone, Copy, Debug)]
enum P {
    D(usize),
    N(usize),
    K(usize),
}

fn perturbed(media: &[(Complex64, f64, bool)], p: P, h: f64) -> Stack {
    let mut m = media.to_vec();
    match p {
        P::D(j) => m[j].1 += h,
        P::N(j) => m[j].0.re += h,
        P::K(j) => m[j].0.im += h,
    }
    build(&m)
}

/// (value, derivatives) of the four quantities R, T (unpolarised), ψ, Δ (ψ, Δ only for coherent stacks).
fn jets(media: &[(Complex64, f64, bool)], ps: &[P; 3], w: f64, th: f64) -> Vec<Jet<3>> {
    let s = build(media);
    let mut tan = Tangent::<3>::zero(s.layers.len());
    for (k, p) in ps.iter().enumerate() {
        match *p {
            P::D(j) => tan.thickness[j - 1][k] = 1.0,
            P::N(j) => tan.index[j][k] = Complex64::new(1.0, 0.0),
            P::K(j) => tan.index[j][k] = Complex64::new(0.0, 1.0),
        }
    }
    let x = s.evaluate_jet(w, th, &tan).unwrap();
    let mut out = vec![x.r(), x.t()];
    if !s.has_incoherent() {
        let (psi, delta) = s.ellipsometry_jet(w, th, &tan).unwrap();
        out.extend([psi, delta]);
    }
    out
}

fn values(s: &Stack, w: f64, th: f64) -> Vec<f64> {
    let x = s.evaluate(w, th).unwrap();
    let mut out = vec![x.r(), x.t()];
    if !s.has_incoherent() {
        let (psi, delta) = s.ellipsometry(w, th).unwrap();
        out.extend([psi, delta]);
    }
    out
}

/// Richardson-extrapolated central difference of every quantity with respect to `p`.
fn fd(media: &[(Complex64, f64, bool)], p: P, h: f64, w: f64, th: f64) -> Vec<f64> {
    let central = |h: f64| -> Vec<f64> {
        let (a, b) = (values(&perturbed(media, p, -h), w, th), values(&perturbed(media, p, h), w, th));
        a.iter()
            .zip(&b)
            .enumerate()
            .map(|(i, (a, b))| {
                let mut diff = b - a;
                if i == 3 {
                    // Δ is an angle: the difference on the circle.
                    diff = (diff + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
                }
                diff / (2.0 * h)
            })
            .collect()
    };
    let (c1, c2) = (central(h), central(h / 2.0));
    c1.iter().zip(&c2).map(|(a, b)| (4.0 * b - a) / 3.0).collect()
}

fn c(re: f64, im: f64) -> Complex64 {
    Complex64::new(re, im)
}

fn check(name: &str, media: &[(Complex64, f64, bool)], ps: [P; 3], w: f64, th_deg: f64) {
    let th = th_deg.to_radians();
    let j = jets(media, &ps, w, th);
    let v = values(&build(media), w, th);
    for (q, jq) in j.iter().enumerate() {
        assert!((jq.v.re - v[q]).abs() < 1e-12, "{name}: value {q}: {} vs {}", jq.v.re, v[q]);
    }
    for (k, p) in ps.iter().enumerate() {
        let h = match *p {
            P::D(_) => 1e-2,
            P::N(_) => 1e-5,
            // A step below κ keeps κ ≥ 0.
            P::K(j) => 1e-5f64.min(0.25 * media[j].0.im),
        };
        let f = fd(media, *p, h, w, th);
        for (q, jq) in j.iter().enumerate() {
            let exact = jq.d[k].re;
            // Absolute error against the derivative's own scale (a thickness derivative is ~1e-2 per nm).
            let tol = 1e-8 * exact.abs().max(if matches!(p, P::D(_)) { 1e-2 } else { 1.0 });
            assert!(
                (exact - f[q]).abs() < tol,
                "{name}, θ = {th_deg}°, ∂[{}]/∂{p:?}: jet {exact:e}, finite differences {:e}",
                ["R", "T", "ψ", "Δ"][q],
                f[q]
            );
            assert!(jq.d[k].im == 0.0, "a real quantity has a real derivative");
        }
    }
}

#[test]
fn one_layer_matches_the_derivative_of_the_airy_formula() {
    // Lossless layer n₁ on n₂ at normal incidence (Born & Wolf §7.6.1):
    // R = (r₀₁² + r₁₂² + 2 r₀₁ r₁₂ cos 2β) / (1 + r₀₁² r₁₂² + 2 r₀₁ r₁₂ cos 2β), β = 2π n₁ d / λ, so
    // dR/dd = b (e − a) / D² · (−sin 2β) · 4π n₁/λ with a = r₀₁² + r₁₂², e = 1 + r₀₁² r₁₂², b = 2 r₀₁ r₁₂.
    let (n0, n1, n2): (f64, f64, f64) = (1.0, 1.38, 1.52);
    let (r01, r12) = ((n0 - n1) / (n0 + n1), (n1 - n2) / (n1 + n2));
    let (a, e, b) = (r01 * r01 + r12 * r12, 1.0 + (r01 * r12).powi(2), 2.0 * r01 * r12);
    for (d, w) in [(100.0, 550.0), (237.0, 433.0), (1234.5, 700.0)] {
        let beta = 2.0 * std::f64::consts::PI * n1 * d / w;
        let den = e + b * (2.0 * beta).cos();
        let r = (a + b * (2.0 * beta).cos()) / den;
        let drdd = b * (e - a) / (den * den) * (-(2.0 * beta).sin()) * 4.0 * std::f64::consts::PI * n1 / w;
        let s = Stack::parse(&format!("air | n={n1} {d}nm | n={n2}")).unwrap();
        let mut tan = Tangent::<1>::zero(1);
        tan.thickness[0][0] = 1.0;
        let x = s.evaluate_jet(w, 0.0, &tan).unwrap();
        assert!((x.r().v.re - r).abs() < 1e-15, "{} vs {r}", x.r().v.re);
        assert!((x.r().d[0].re - drdd).abs() < 1e-15, "d = {d}: {} vs {drdd}", x.r().d[0].re);
        // Lossless: T = 1 − R, so ∂T = −∂R.
        assert!((x.t().d[0].re + drdd).abs() < 1e-15);
    }
}

#[test]
fn coherent_dielectric_stacks_at_several_angles() {
    let m = [
        (c(1.0, 0.0), 0.0, false),
        (c(1.38, 0.0), 97.0, false),
        (c(2.3, 0.0), 61.0, false),
        (c(1.52, 0.0), 0.0, false),
    ];
    for th in [0.0, 30.0, 65.0, 85.0] {
        check("MgF2/TiO2 on glass", &m, [P::D(1), P::N(2), P::N(3)], 520.0, th);
        check("MgF2/TiO2 on glass", &m, [P::D(2), P::N(1), P::N(0)], 610.0, th);
    }
}

#[test]
fn absorbing_layers_and_substrates() {
    // Gold-like metal film on an absorbing (silicon-like) substrate; a water incident medium.
    let m = [
        (c(1.33, 0.0), 0.0, false),
        (c(0.2, 3.4), 31.0, false),
        (c(1.46, 0.0), 180.0, false),
        (c(3.9, 0.02), 0.0, false),
    ];
    for th in [0.0, 20.0, 55.0, 75.0] {
        check("metal/oxide on Si", &m, [P::D(1), P::K(1), P::N(1)], 480.0, th);
        check("metal/oxide on Si", &m, [P::D(2), P::K(3), P::N(3)], 700.0, th);
    }
    // Oxide on silicon at the ellipsometer's 70°.
    let m = [(c(1.0, 0.0), 0.0, false), (c(1.458, 0.0), 187.0, false), (c(4.1, 0.05), 0.0, false)];
    check("SiO2 on Si", &m, [P::D(1), P::N(1), P::N(2)], 500.0, 70.0);
}

#[test]
fn beyond_the_critical_angle() {
    // Light from glass onto a thin low-index gap and glass again (frustrated total internal reflection).
    let m = [(c(1.52, 0.0), 0.0, false), (c(1.0, 0.0), 150.0, false), (c(1.52, 0.0), 0.0, false)];
    check("FTIR gap", &m, [P::D(1), P::N(1), P::N(0)], 600.0, 50.0);
}

#[test]
fn mixed_stacks_with_incoherent_layers() {
    // A coated slide (incoherent, weakly absorbing so its thickness matters) with a film on each side.
    let m = [
        (c(1.0, 0.0), 0.0, false),
        (c(2.1, 0.0), 212.0, false),
        (c(1.52, 2e-6), 1e6, true),
        (c(1.38, 0.001), 95.0, false),
        (c(1.0, 0.0), 0.0, false),
    ];
    for th in [0.0, 35.0, 60.0] {
        check("film | inc slide | film", &m, [P::D(1), P::D(2), P::D(3)], 550.0, th);
        check("film | inc slide | film", &m, [P::N(1), P::K(2), P::N(3)], 650.0, th);
    }
    // Two incoherent layers in a row, on an absorbing substrate.
    let m = [
        (c(1.0, 0.0), 0.0, false),
        (c(1.5, 1e-5), 5e4, true),
        (c(1.7, 0.0), 3e5, true),
        (c(2.0, 0.0), 120.0, false),
        (c(3.9, 0.1), 0.0, false),
    ];
    check("inc | inc | film on absorber", &m, [P::D(1), P::K(1), P::D(3)], 500.0, 40.0);
}

#[test]
fn dispersion_gradients_are_the_derivatives_of_the_formulas() {
    // ∂n/∂c against central differences of the formulas themselves.
    let n = |sell: bool, c: &[f64], w: f64| {
        let m = if sell { Material::sellmeier("s", c) } else { Material::cauchy("c", c) }.unwrap();
        m.index_at(w).unwrap().re
    };
    for (sell, coefs) in [(false, vec![1.45, 0.0042, 1.1e-4]), (true, vec![1.04, 0.006, 0.23, 0.02, 1.01, 103.6])] {
        for w in [400.0, 633.0, 1000.0] {
            let g = if sell { Material::sellmeier_gradient(&coefs, w) } else { Material::cauchy_gradient(&coefs, w) };
            assert_eq!(g.len(), coefs.len());
            for i in 0..coefs.len() {
                let h = 1e-6 * coefs[i].abs().max(1e-3);
                let (mut a, mut b) = (coefs.clone(), coefs.clone());
                a[i] -= h;
                b[i] += h;
                let f = (n(sell, &b, w) - n(sell, &a, w)) / (2.0 * h);
                assert!(
                    (g[i] - f).abs() < 1e-7 * g[i].abs().max(1.0),
                    "sellmeier {sell}, c{i} at {w}: {} vs {f}",
                    g[i]
                );
            }
        }
    }
}
