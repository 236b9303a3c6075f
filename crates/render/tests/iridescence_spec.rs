//! `KHR_materials_iridescence` in iridis against the specification's own approximation.
//!
//! iridis evaluates the film spectrally (81 wavelengths, the exact Airy/Abelès recurrence of
//! `iridis-thinfilm`); the glTF specification's reference implementation approximates it in RGB after Belcour
//! & Barla ("A Practical Extension to Microfacet Theory for the Modeling of Varying Iridescence", SIGGRAPH
//! 2017): Schlick Fresnel at both interfaces, the base's index from its `F_0`, and the spectral integral of
//! the interference terms replaced by Gaussian fits of the CIE sensitivities (eq. of their supplemental
//! material, as the glTF extension's appendix uses them). This test
//!
//! 1. checks iridis' film reflectance against the closed-form Airy formula of one layer (independent of the
//!    recurrence),
//! 2. checks the approximation's constants (its sensitivity is white at zero path difference) and that both
//!    agree where there is no film on a bright base (the base's Fresnel at normal incidence),
//! 3. prints the CIEDE2000 between the two on the parameter grids of Khronos' `IridescenceMetallicSpheres`
//!    and `IridescenceDielectricSpheres` sample models (rebuilt from their `.gltf` materials: roughness 0.1,
//!    factor 1, thickness = `iridescenceThicknessMaximum` 100–700 nm, film IOR 1.00–2.00 in sevenths; metallic
//!    spheres over grey base colours 0–1, dielectric spheres over base IOR 1.00–2.00 with base colour 0.8) —
//!    the table in docs/render.md.

use iridis_color::integrate::white_point;
use iridis_color::lab::delta_e_2000;
use iridis_color::{Illuminant, Lab, Observer, Xyz};
use iridis_render::gltf_io::metal_from_f0;
use iridis_render::material::ThinFilm;
use iridis_thinfilm::Stack;

const PI: f64 = std::f64::consts::PI;

fn schlick(f0: f64, c: f64) -> f64 {
    f0 + (1.0 - f0) * (1.0 - c).powi(5)
}

/// Belcour & Barla's spectral sensitivity of the interference term at optical path difference `opd` (nm) and
/// phase shift `shift`, as linear Rec.709 RGB (their Gaussian fits of the CIE 1931 XYZ functions).
fn sensitivity(opd: f64, shift: [f64; 3]) -> [f64; 3] {
    let phase = 2.0 * PI * opd * 1e-9;
    let val = [5.4856e-13, 4.4201e-13, 5.2481e-13];
    let pos = [1.6810e6, 1.7953e6, 2.2084e6];
    let var = [4.3278e9, 9.3046e9, 6.6121e9];
    let mut xyz = [0.0; 3];
    for k in 0..3 {
        xyz[k] =
            val[k] * (2.0 * PI * var[k]).sqrt() * (pos[k] * phase + shift[k]).cos() * (-phase * phase * var[k]).exp();
    }
    xyz[0] += 9.7470e-14
        * (2.0 * PI * 4.5282e9).sqrt()
        * (2.2399e6 * phase + shift[0]).cos()
        * (-4.5282e9 * phase * phase).exp();
    let x = Xyz::new(xyz[0] / 1.0685e-7, xyz[1] / 1.0685e-7, xyz[2] / 1.0685e-7);
    x.to_linear_srgb()
}

/// The glTF iridescence Fresnel (Belcour & Barla) from air at `cos1`, film index `eta2`, thickness `d` nm,
/// base `F_0` per channel: linear RGB reflectance.
fn belcour_barla(eta2_in: f64, cos1: f64, d: f64, f0: [f64; 3]) -> [f64; 3] {
    let t = (d / 0.03).clamp(0.0, 1.0);
    let eta2 = 1.0 + (eta2_in - 1.0) * t * t * (3.0 - 2.0 * t);
    let cos2sq = 1.0 - (1.0 / eta2).powi(2) * (1.0 - cos1 * cos1);
    if cos2sq < 0.0 {
        return [1.0; 3];
    }
    let cos2 = cos2sq.sqrt();
    let r12 = schlick(((eta2 - 1.0) / (eta2 + 1.0)).powi(2), cos1);
    let t121 = 1.0 - r12;
    let phi12 = if eta2 < 1.0 { PI } else { 0.0 };
    let phi21 = PI - phi12;
    let mut out = [0.0; 3];
    let mut r23 = [0.0; 3];
    let mut phi = [0.0; 3];
    for k in 0..3 {
        let s = f0[k].clamp(0.0, 0.9999).sqrt();
        let base = (1.0 + s) / (1.0 - s);
        r23[k] = schlick(((base - eta2) / (base + eta2)).powi(2), cos2);
        phi[k] = phi21 + if base < eta2 { PI } else { 0.0 };
    }
    let opd = 2.0 * eta2 * d * cos2;
    let s1 = sensitivity(opd, phi);
    let s2 = sensitivity(2.0 * opd, phi.map(|p| 2.0 * p));
    for k in 0..3 {
        let r123 = (r12 * r23[k]).clamp(1e-5, 0.9999);
        let sr = r123.sqrt();
        let rs = t121 * t121 * r23[k] / (1.0 - r123);
        let mut i = r12 + rs;
        let mut cm = rs - t121;
        for s in [s1[k], s2[k]] {
            cm *= sr;
            i += cm * 2.0 * s;
        }
        out[k] = i.max(0.0);
    }
    out
}

fn lab(x: Xyz) -> Lab {
    Lab::from_xyz(x, white_point(Illuminant::D65, Observer::Cie1931))
}

/// iridis' film reflectance colour (XYZ, D65, `R = 1` → `Y = 1`) for a stack at `cos θ`.
fn iridis(stack: Stack, cos: f64) -> Xyz {
    ThinFilm::new(stack, None, false).unwrap().colors(cos, 0.0).0
}

fn stack(film: f64, d: f64, substrate: &str) -> Stack {
    format!("air | n={film} {d}nm | {substrate}").parse().unwrap()
}

#[test]
fn iridis_film_reflectance_is_the_airy_formula() {
    // One layer n2 = 1.33, d = 350 nm on n3 = 1.5, normal incidence:
    // R = (r12² + r23² + 2 r12 r23 cos 2δ) / (1 + r12² r23² + 2 r12 r23 cos 2δ), δ = 2π n2 d / λ.
    let s = stack(1.33, 350.0, "n=1.5");
    for l in [400.0, 500.0, 650.0] {
        let (r12, r23) = ((1.0 - 1.33) / (1.0 + 1.33), (1.33 - 1.5) / (1.33 + 1.5));
        let c = (2.0 * 2.0 * PI * 1.33 * 350.0 / l).cos();
        let want = (r12 * r12 + r23 * r23 + 2.0 * r12 * r23 * c) / (1.0 + r12 * r12 * r23 * r23 + 2.0 * r12 * r23 * c);
        let got = s.evaluate(l, 0.0).unwrap().r();
        assert!((got - want).abs() < 1e-12, "{l} nm: {got} vs {want}");
    }
}

#[test]
fn the_approximation_is_implemented_as_published() {
    // Belcour & Barla normalise their Gaussian fits so that at zero optical path difference the sensitivity
    // is the XYZ of an equal-energy white, (1, 1, 1): a check of the constants above.
    let rgb = sensitivity(0.0, [0.0; 3]);
    let xyz = Xyz::from_linear_srgb(rgb);
    for (c, v) in [("X", xyz.x), ("Y", xyz.y), ("Z", xyz.z)] {
        assert!((v - 1.0).abs() < 2e-3, "{c} = {v}");
    }
    // Without a film (film index 1) on a bright metal, at normal incidence, both give the base's F_0: iridis
    // through the exact Fresnel of the substrate index made from F_0, the approximation through Schlick. (On
    // dark bases they part: the approximation keeps interference terms of amplitude √1e-5 from its clamp of
    // R12·R23, visible where F_0 is small.)
    for f0 in [0.3, 0.5, 0.9] {
        let mut s = stack(1.0, 300.0, "n=1.5");
        s.substrate = metal_from_f0([f0; 3]).unwrap();
        let a = lab(iridis(s, 1.0));
        let b = lab(Xyz::from_linear_srgb(belcour_barla(1.0, 1.0, 300.0, [f0; 3])));
        let d = delta_e_2000(a, b);
        assert!(d < 1.0, "F_0 {f0}: ΔE00 {d}");
    }
}

/// ΔE00 between iridis and the glTF approximation for one sphere, averaged over cos θ = 1, 0.7, 0.4.
fn sphere_delta_e(film: f64, d: f64, substrate: Stack, f0: [f64; 3]) -> f64 {
    [1.0, 0.7, 0.4]
        .iter()
        .map(|&c| {
            let a = lab(iridis(substrate.clone(), c));
            let b = lab(Xyz::from_linear_srgb(belcour_barla(film, c, d, f0)));
            delta_e_2000(a, b)
        })
        .sum::<f64>()
        / 3.0
}

#[test]
fn delta_e_against_the_gltf_approximation_on_the_khronos_sphere_grids() {
    let iors: Vec<f64> = (0..7).map(|i| 1.0 + i as f64 / 6.0).collect();
    let thick: Vec<f64> = (1..=7).map(|i| 100.0 * i as f64).collect();
    let mut all = Vec::new();
    for metallic in [true, false] {
        let mut table = vec![vec![0.0; thick.len()]; iors.len()];
        for (i, &film) in iors.iter().enumerate() {
            for (j, &d) in thick.iter().enumerate() {
                let mut sum = 0.0;
                for k in 0..7 {
                    let x = k as f64 / 6.0;
                    let (s, f0) = if metallic {
                        let mut s = stack(film, d, "n=1.5");
                        s.substrate = metal_from_f0([x; 3]).unwrap();
                        (s, [x; 3])
                    } else {
                        let base = 1.0 + x;
                        (stack(film, d, &format!("n={base}")), [((base - 1.0) / (base + 1.0)).powi(2); 3])
                    };
                    sum += sphere_delta_e(film, d, s, f0);
                }
                table[i][j] = sum / 7.0;
                all.push(sum / 7.0);
            }
        }
        let name = if metallic { "IridescenceMetallicSpheres" } else { "IridescenceDielectricSpheres" };
        eprintln!(
            "\n{name}: mean ΔE00 over the 7 {} × cos θ ∈ {{1, 0.7, 0.4}}",
            if metallic { "base colours" } else { "base IORs" }
        );
        eprintln!("| film IOR | {} |", thick.iter().map(|d| format!("{d:.0} nm")).collect::<Vec<_>>().join(" | "));
        eprintln!("|---|{}", "---|".repeat(thick.len()));
        for (i, row) in table.iter().enumerate() {
            eprintln!("| {:.2} | {} |", iors[i], row.iter().map(|v| format!("{v:.1}")).collect::<Vec<_>>().join(" | "));
        }
        let flat: Vec<f64> = table.iter().flatten().copied().collect();
        let mean = flat.iter().sum::<f64>() / flat.len() as f64;
        let max = flat.iter().fold(0.0f64, |a, &b| a.max(b));
        eprintln!("mean {mean:.2}, largest cell {max:.2}");
    }
    // The approximation is close enough for real-time use, not to the spectral film: a few ΔE00 on average.
    let mean = all.iter().sum::<f64>() / all.len() as f64;
    assert!(all.iter().all(|v| v.is_finite()) && mean < 8.0, "mean ΔE00 {mean}");
}
