//! Extended light by Monte Carlo (issue 19): the white furnace under Monte Carlo environment light, area lights
//! that shrink to the directional light they approach, and the multiple-importance-sampling estimator against
//! its two single-technique estimators. Every bound is a multiple of a standard error measured from the
//! samples themselves, plus, where stated, a known deterministic tolerance.

use crate::furnace;

use furnace::{furnace_scene, monte_carlo};
use iridis_render::integrate::{Integration, Strategy};
use iridis_render::material::Material;
use iridis_render::math::*;
use iridis_render::{parse_scene, Scene};

/// Mean and standard error per channel of `n` independent samples of the radiance along one camera ray.
fn estimate(scene: &Scene, o: V3, d: V3, n: u64, stream: u64) -> ([f64; 3], [f64; 3]) {
    let (mut s, mut s2) = ([0.0; 3], [0.0; 3]);
    for k in 0..n {
        iridis_render::sampling::seed(stream, k);
        let x = scene.primary(o, d);
        for c in 0..3 {
            s[c] += x[c];
            s2[c] += x[c] * x[c];
        }
    }
    let nf = n as f64;
    let mean = s.map(|v| v / nf);
    let se = [0, 1, 2].map(|c| ((s2[c] / nf - mean[c] * mean[c]).max(0.0) / nf).sqrt());
    (mean, se)
}

/// The furnace's camera ray through the point `(x, y)` of the unit sphere's disk (orthographic, looking −z).
fn furnace_ray(x: f64, y: f64) -> (V3, V3) {
    ([x, y, 5.0], [0.0, 0.0, -1.0])
}

/// Points of the sphere's disk seen at cos θ_o = 1, 0.8, 0.5, 0.2.
const VIEWS: [f64; 4] = [1.0, 0.8, 0.5, 0.2];

#[test]
fn lambert_and_microfacets_pass_the_white_furnace_under_monte_carlo_light() {
    // Lambert exactly; the microfacets to the energy table's accuracy (their ∫ f cos is 1 within 0.015 by a
    // brute-force quadrature in material.rs; the Monte Carlo estimate converges to that integral).
    let cases = [
        ("lambert", "[materials.m]\nkind = \"lambert\"\ncolor = [1, 1, 1]", 0.0),
        (
            "dielectric r0.2",
            "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.2\nior = 1.5",
            0.015,
        ),
        (
            "dielectric r0.6",
            "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.6\nior = 1.5",
            0.015,
        ),
        ("dielectric r1", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 1.0\nior = 1.5", 0.015),
        (
            "metal r0.3",
            "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.3\nmetallic = 1.0",
            0.015,
        ),
        ("metal r1", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 1.0\nmetallic = 1.0", 0.015),
        (
            "half metal r0.4",
            "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.4\nmetallic = 0.5",
            0.015,
        ),
    ];
    let mut failures = Vec::new();
    for (name, mat, tol) in cases {
        let scene = monte_carlo(furnace_scene(mat, 1.0), Strategy::Mis);
        for (k, c) in VIEWS.iter().enumerate() {
            let x = (1.0 - c * c).sqrt();
            let (o, d) = furnace_ray(x, 0.0);
            let (mean, se) = estimate(&scene, o, d, 4000, k as u64);
            eprintln!("{name:<18} cos θ_o {c}: {mean:.4?} ± {se:.4?}");
            for ch in 0..3 {
                if (mean[ch] - 1.0).abs() > 4.0 * se[ch] + tol {
                    failures.push(format!("{name} at cos θ_o {c}: {} ± {}", mean[ch], se[ch]));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn films_in_the_monte_carlo_furnace() {
    use iridis_render::light::Rgb;
    // A soap bubble (reflection + transmission along its mirror and straight through: no lobe to sample)
    // returns R + T = 1 up to the XYZ → sRGB rounding of D65 white (5.9e-4, docs/render.md).
    let bubble = monte_carlo(
        furnace_scene(
            "[materials.m]\nkind = \"thinfilm\"\nstack = \"air | water 400nm | air\"\ntransmission = true",
            1.0,
        ),
        Strategy::Mis,
    );
    for c in VIEWS {
        let (o, d) = furnace_ray((1.0 - c * c).sqrt(), 0.0);
        let (mean, se) = estimate(&bubble, o, d, 4, 0);
        assert!(mean.iter().all(|m| (m - 1.0).abs() < 1e-3) && se.iter().all(|s| *s < 1e-9), "{mean:?} {se:?}");
    }
    // A film over a base: the Monte Carlo estimate converges to ∫ f cos θ_i dω / π of the BRDF the lights see
    // (the glTF iridescence BRDF, `ThinFilm::over_base_light`, mixed with the base by the factor), computed
    // here by a deterministic quadrature; that BRDF is not energy-conserving (its GGX lobe is single
    // scattering and its diffuse split uses R(v·h), as the glTF BRDF's `mix(diffuse, specular, F(v·h))` does), so
    // the furnace shows its albedo, not 1. Where the specular lobe sees a larger R than the diffuse directions'
    // half vectors do, the albedo exceeds 1: measured 1.056 (green) over a dielectric at roughness 0.3 seen at
    // 60° (docs/render.md); the environment's fast path splits by R(cos θ_o) instead and gives 1. Bounded
    // here at the measured excess, so that a change of the model shows.
    for (name, base, factor) in [
        ("film over lambert", "[materials.b]\nkind = \"lambert\"\ncolor = [1, 1, 1]", 1.0),
        (
            "film over dielectric r0.3",
            "[materials.b]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.3\nior = 1.5",
            1.0,
        ),
        (
            "film ×0.5 over dielectric r0.6",
            "[materials.b]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.6\nior = 1.5",
            0.5,
        ),
    ] {
        let mat = format!(
            "{base}\n[materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\"\nfactor = {factor}"
        );
        let scene = monte_carlo(furnace_scene(&mat, 1.0), Strategy::Mis);
        let Material::ThinFilm(f) = &scene.materials.iter().find(|m| matches!(m, Material::ThinFilm(_))).unwrap()
        else {
            unreachable!()
        };
        let b = f.base.expect("a base");
        for c in [1.0f64, 0.5] {
            let (o, d) = furnace_ray((1.0 - c * c).sqrt(), 0.0);
            let (mean, se) = estimate(&scene, o, d, 3000, 7);
            // The quadrature in the hit's frame: n = (x, 0, c), ω_o = +z.
            let n = [(1.0 - c * c).sqrt(), 0.0, c];
            let wo = [0.0, 0.0, 1.0];
            let (nt, np) = (400, 200);
            let mut want: Rgb = [0.0; 3];
            let (t1, t2) = iridis_render::sampling::frame(n);
            for i in 0..nt {
                let th = std::f64::consts::FRAC_PI_2 * (i as f64 + 0.5) / nt as f64;
                let dw = th.sin() * std::f64::consts::FRAC_PI_2 / nt as f64 * std::f64::consts::TAU / np as f64;
                for j in 0..np {
                    let ph = std::f64::consts::TAU * (j as f64 + 0.5) / np as f64;
                    let wi = iridis_render::sampling::from_local(
                        t1,
                        t2,
                        n,
                        [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()],
                    );
                    let film = f.over_base_light(&b, [1.0; 3], n, wi, wo, 0.0);
                    let base = b.reflect(n, wi, wo, [1.0; 3]);
                    for k in 0..3 {
                        want[k] += (factor * film[k] + (1.0 - factor) * base[k]) * dw / std::f64::consts::PI;
                    }
                }
            }
            eprintln!("{name:<30} cos θ_o {c}: {mean:.4?} ± {se:.4?}, quadrature {want:.4?}");
            for k in 0..3 {
                assert!(
                    (mean[k] - want[k]).abs() < 4.0 * se[k] + 2e-3 * want[k],
                    "{name} at cos θ_o {c}: {} ± {} vs {}",
                    mean[k],
                    se[k],
                    want[k]
                );
                assert!(want[k] < 1.06, "{name}: the film's albedo {} exceeds 1.06", want[k]);
            }
        }
    }
}

#[test]
fn a_rough_film_reflects_its_albedo_under_monte_carlo_light() {
    use iridis_color::{Illuminant, Observer};
    use iridis_thinfilm::color::FilmColorimeter;
    use iridis_thinfilm::rough::RoughStack;
    // Normal view: k_r + ∫ k_d cos θ dω, the albedo that RoughStack integrates on a dense grid (the fast
    // path's test in white_furnace.rs, here with the diffuse lobe sampled instead of tabulated).
    let mat = "[materials.m]\nkind = \"thinfilm\"\nstack = \"air | water 348nm | Si\"\nroughness = \"25nm\"\ncorrelation = \"300nm\"";
    let scene = monte_carlo(furnace_scene(mat, 1.0), Strategy::Mis);
    let Material::ThinFilm(f) = &scene.materials[0] else { panic!("not a film") };
    let rough = RoughStack::new(f.stack.clone(), f.rough.expect("a rough film"));
    let grid = iridis_color::spectrum::uniform_grid(380.0, 780.0, 5.0).unwrap();
    let albedo: Vec<f64> = grid.iter().map(|&l| rough.albedo(l, 0.0, 60).unwrap().total()).collect();
    let want = FilmColorimeter::new(&grid, Illuminant::D65, Observer::Cie1931).from_spectra(&albedo, &albedo).reflected;
    let (o, d) = furnace_ray(0.0, 0.0);
    let (mean, se) = estimate(&scene, o, d, 400, 3);
    let y = 0.2126 * mean[0] + 0.7152 * mean[1] + 0.0722 * mean[2];
    let se_y = 0.2126 * se[0] + 0.7152 * se[1] + 0.0722 * se[2];
    eprintln!("rough film: Y {y:.4} ± {se_y:.4}, dense albedo {:.4}", want.y);
    assert!((y - want.y).abs() < 4.0 * se_y + 1e-3, "{y} ± {se_y} vs {}", want.y);
}

/// A plane at the origin (normal +z) under a sphere light of angular radius `alpha` in direction `dir`, of
/// radiance chosen so that its irradiance is `e` RU — or, with `alpha = 0`, the directional light itself.
fn plane_under(material: &str, dir: V3, alpha_deg: f64, e: f64, integration: &str) -> Scene {
    let light = if alpha_deg == 0.0 {
        format!("[[light]]\nkind = \"directional\"\ndirection = {dir:?}\nintensity = {e}\n")
    } else {
        let a = alpha_deg.to_radians();
        let dist = 10.0;
        let r = dist * a.sin();
        let p = mul(normalize(dir), dist);
        format!(
            "[[light]]\nkind = \"sphere\"\nposition = {p:?}\nradius = {r}\nintensity = {}\nvisible = false\n",
            e / (a.sin() * a.sin())
        )
    };
    let text = format!(
        "[output]\nintegration = \"{integration}\"\n\
         [camera]\nkind = \"hemisphere\"\ntarget = [0, 0, 0]\nnormal = [0, 0, 1]\nup = [0, 1, 0]\n\
         {light}{material}\n\
         [[object]]\nkind = \"plane\"\nnormal = [0, 0, 1]\ntangent = [1, 0, 0]\nmaterial = \"m\"\n"
    );
    parse_scene(&text, "plane.toml", std::path::Path::new(".")).unwrap()
}

#[test]
fn a_sphere_light_lights_a_lambertian_exactly_as_its_directional_light() {
    // A sphere light wholly above the horizon gives E = π L sin²α cos θ: the directional light of L sin²α RU,
    // at any size. The Monte Carlo estimate must agree within its standard error at every α.
    let dir = normalize([0.3, -0.2, 0.8]);
    let mat = "[materials.m]\nkind = \"lambert\"\ncolor = [0.8, 0.5, 0.3]";
    let want = mul([0.8, 0.5, 0.3], dir[2]);
    for alpha in [20.0, 5.0, 1.0] {
        let scene = plane_under(mat, dir, alpha, 1.0, "monte-carlo");
        let (mean, se) = estimate(&scene, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0], 2000, 1);
        eprintln!("α {alpha}°: {mean:.5?} ± {se:.5?} vs {want:.5?}");
        for k in 0..3 {
            assert!((mean[k] - want[k]).abs() < 4.0 * se[k] + 1e-9, "α {alpha}°: {mean:?} ± {se:?} vs {want:?}");
        }
        // The fast path's representative light is exact here.
        let fast = plane_under(mat, dir, alpha, 1.0, "fast").primary([0.0, 0.0, 10.0], [0.0, 0.0, -1.0]);
        for k in 0..3 {
            assert!((fast[k] - want[k]).abs() < 1e-12, "fast, α {alpha}°: {fast:?} vs {want:?}");
        }
    }
}

/// Relative RMS difference of two images' luminance over the pixels where `b` is lit.
fn relative_rms(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    let y = |p: &[f32; 3]| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64;
    let (mut num, mut den) = (0.0, 0.0);
    for (p, q) in a.iter().zip(b) {
        num += (y(p) - y(q)).powi(2);
        den += y(q).powi(2);
    }
    (num / den.max(1e-300)).sqrt()
}

#[test]
fn shrinking_area_lights_converge_to_the_directional_light() {
    // A glossy microfacet and a diffraction grating (hemisphere camera: each pixel a view direction, the BRDF
    // map of the plane) under a sphere light of irradiance 1 RU whose angular radius shrinks: the converged
    // image approaches the directional light's, on both paths (Monte Carlo and the prefiltered fast path).
    let dir = normalize([0.35, 0.35, 0.866]);
    for (name, mat) in [
        ("glossy microfacet", "[materials.m]\nkind = \"microfacet\"\ncolor = [0.2, 0.2, 0.2]\nroughness = 0.35\nmetallic = 1.0"),
        (
            "diffraction",
            "[materials.m]\nkind = \"diffraction\"\ntable = \"builtin:blazed\"\nuv_resolution = 65\nscale_ru = 1\ncolor = [0, 0, 0]",
        ),
    ] {
        let size = 24;
        // The same samples per pixel everywhere, so that the pixels on the rim of the hemisphere's disk are
        // covered alike.
        let spp = 64;
        let reference = iridis_render::render(&plane_under(mat, dir, 0.0, 1.0, "fast"), size, size, spp, &|_| {});
        let mut last = (f64::INFINITY, f64::INFINITY);
        // The diffraction lobe's orders are about λ / coherence length ≈ 0.5° wide: the light must become
        // much smaller than that before it is a directional light.
        for alpha in [2.0, 0.5, 0.1, 0.02] {
            let mc = iridis_render::render(&plane_under(mat, dir, alpha, 1.0, "monte-carlo"), size, size, spp, &|_| {});
            let fast = iridis_render::render(&plane_under(mat, dir, alpha, 1.0, "fast"), size, size, spp, &|_| {});
            let (e_mc, e_fast) = (relative_rms(&mc.data, &reference.data), relative_rms(&fast.data, &reference.data));
            eprintln!("{name}, α {alpha}°: relative RMS to the directional light: Monte Carlo {e_mc:.4}, fast {e_fast:.4}");
            // Down to the Monte Carlo noise of 64 samples (about 0.005 here).
            assert!(
                e_mc < last.0 + 0.003 && e_fast <= last.1 + 1e-9,
                "{name}: the difference must shrink with the light ({e_mc}, {e_fast} after {last:?})"
            );
            last = (e_mc, e_fast);
        }
        assert!(last.0 < 0.02 && last.1 < 0.02, "{name}: at α = 0.02° still {last:?} from the directional light");
    }
}

#[test]
fn multiple_importance_sampling_agrees_with_each_technique_alone() {
    // The same pixels estimated with light samples only, BRDF samples only and both weighted by the power
    // heuristic: three unbiased estimators of one integral must agree within their standard errors. A sky
    // with a small bright sun (an equirectangular map), a disk light and a rectangle light, over a glossy
    // metal, a Lambertian and a diffraction grating.
    use iridis_render::light::{equirect_dir, equirect_mean, Environment};
    use iridis_render::texture::{TexKind, Texture};
    let (w, h) = (64usize, 32usize);
    let sun = normalize([0.4, 0.8, 0.3]);
    let mut data = Vec::with_capacity(w * h * 3);
    for r in 0..h {
        for c in 0..w {
            let d = equirect_dir((c as f64 + 0.5) / w as f64, (r as f64 + 0.5) / h as f64, 0.0);
            let s = if dot(d, sun) > 0.995 { 40.0 } else { 0.0 };
            let sky = if d[1] > 0.0 { 0.3 + 0.5 * d[1] } else { 0.1 };
            data.extend([sky + s, sky + 0.9 * s, sky * 1.2 + 0.7 * s].map(|x| x as f32));
        }
    }
    let texture = Texture::Image { width: w, height: h, channels: 3, data, kind: TexKind::Color, name: "sun".into() };
    let mean = equirect_mean(&texture, 1.0);
    for mat in [
        "[materials.m]\nkind = \"microfacet\"\ncolor = [0.9, 0.6, 0.3]\nroughness = 0.3\nmetallic = 1.0",
        "[materials.m]\nkind = \"lambert\"\ncolor = [0.7, 0.7, 0.7]",
        "[materials.m]\nkind = \"diffraction\"\ntable = \"builtin:blazed\"\nuv_resolution = 65\nscale_ru = 1\ncolor = [0.2, 0.2, 0.2]\nw_diffuse = 0.3",
    ] {
        let text = format!(
            "[output]\nintegration = \"monte-carlo\"\n\
             [camera]\nkind = \"hemisphere\"\ntarget = [0, 0, 0]\nnormal = [0, 0, 1]\nup = [0, 1, 0]\n\
             [[light]]\nkind = \"disk\"\nposition = [1, 1, 3]\nlook_at = [0, 0, 0]\nradius = 0.5\nintensity = 3\n\
             [[light]]\nkind = \"rectangle\"\nposition = [-2, 0.5, 2]\nlook_at = [0, 0, 0]\nsize = [1, 0.4]\nintensity = 2\ncolor = [1, 0.8, 0.6]\n\
             {mat}\n\
             [[object]]\nkind = \"plane\"\nnormal = [0, 0, 1]\ntangent = [1, 0, 0]\nmaterial = \"m\"\n"
        );
        let mut scene = parse_scene(&text, "mis.toml", std::path::Path::new(".")).unwrap();
        scene.environment =
            Environment::Map { texture: Box::new(texture.clone()), rotation: 0.0, intensity: 1.0, mean };
        let mut worst = 0.0f64;
        for (k, (x, y)) in [(0.0, 0.0), (-0.3, -0.3), (0.4, -0.2), (-0.5, 0.5)].into_iter().enumerate() {
            let view = [x, y, (1.0f64 - x * x - y * y).sqrt()];
            let o = mul(view, 10.0);
            let d = mul(view, -1.0);
            let mut est = Vec::new();
            for strategy in [Strategy::Mis, Strategy::Light, Strategy::Brdf] {
                scene.integration = Integration::MonteCarlo(strategy);
                scene.update_irradiance();
                est.push(estimate(&scene, o, d, 20_000, k as u64));
            }
            let (m, s) = est[0];
            for (name, (m2, s2)) in ["light", "brdf"].iter().zip(&est[1..]) {
                for c in 0..3 {
                    let z = (m[c] - m2[c]).abs() / (s[c] * s[c] + s2[c] * s2[c]).sqrt().max(1e-300);
                    worst = worst.max(z);
                    assert!(z < 4.5, "MIS {} ± {} vs {name}-only {} ± {} (z = {z:.2})", m[c], s[c], m2[c], s2[c]);
                }
            }
            eprintln!("view {view:.2?}: MIS {:.4?} ± {:.4?}, light {:.4?} ± {:.4?}, BRDF {:.4?} ± {:.4?}", est[0].0, est[0].1, est[1].0, est[1].1, est[2].0, est[2].1);
            // MIS is never much worse than the better of the two.
            for c in 0..3 {
                assert!(s[c] <= 1.5 * est[1].1[c].min(est[2].1[c]) + 1e-12, "MIS noisier than a single technique");
            }
        }
        eprintln!("largest |z| {worst:.2}");
    }
}

#[test]
fn the_diffraction_brdf_is_reciprocal_and_reflects_at_most_what_it_receives() {
    // Algorithm 4 without its texture terms (w_diffuse 0, black texture) at scale_ru 1 is the paper's BRDF:
    // `π f cos θ_i = C Σ_p w^p I_p` with `C ∝ (1 + ω_i·ω_o)² / ((cos θ_i + cos θ_o)² cos θ_o)` — so `f` is
    // symmetric. Its albedo `∫ π f cos θ_i dω / π` is summed over the table's own cells in the u-v plane
    // (dω = dA / cos θ_i), which resolve the specular spike.
    for table in ["builtin:blazed", "builtin:elaphe"] {
        let mat = format!(
            "[materials.m]\nkind = \"diffraction\"\ntable = \"{table}\"\nuv_resolution = 65\nscale_ru = 1\ncolor = [0, 0, 0]"
        );
        let s = plane_under(&mat, [0.0, 0.0, 1.0], 0.0, 1.0, "fast");
        let Material::Diffraction(df) = &s.materials[0] else { panic!("not diffraction") };
        let l = df.evaluator.as_lookup().unwrap();
        let y = |li: V3, lo: V3| df.evaluator.xyz(li, lo).y;
        let dir = |t: f64, p: f64| [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()];
        let mut worst = 0.0f64;
        for (ti, pi, to, po) in
            [(0.2, 0.0, 0.3, 2.8), (0.5, 0.5, 0.4, 3.5), (0.9, 1.0, 0.75, 4.2), (0.3, 0.1, 0.31, 3.2)]
        {
            let (wi, wo) = (dir(ti, pi), dir(to, po));
            let (a, b) = (y(wi, wo) / wi[2], y(wo, wi) / wo[2]);
            if a > 1e-12 {
                worst = worst.max((a - b).abs() / a);
            }
        }
        assert!(worst < 1e-9, "{table}: f(ω_i, ω_o) vs f(ω_o, ω_i): relative {worst}");
        let uv = &l.table.uv;
        let n = uv.len();
        for theta_o in [0.0f64, 30.0, 60.0] {
            let lo = dir(theta_o.to_radians(), 0.7);
            let mut albedo = 0.0;
            for iv in 0..n - 1 {
                for iu in 0..n - 1 {
                    let (u, v) = (0.5 * (uv[iu] + uv[iu + 1]), 0.5 * (uv[iv] + uv[iv + 1]));
                    let (x, z) = (-u - lo[0], -v - lo[1]);
                    let s2 = x * x + z * z;
                    if s2 >= 1.0 {
                        continue;
                    }
                    let li = [x, z, (1.0 - s2).sqrt()];
                    albedo += y(li, lo) / li[2] * (uv[iu + 1] - uv[iu]) * (uv[iv + 1] - uv[iv]) / std::f64::consts::PI;
                }
            }
            eprintln!(
                "{table}: albedo at θ_o = {theta_o}°: {albedo:.4e} (scale_ru up to {:.0} keeps it ≤ 1)",
                1.0 / albedo
            );
            // The table is normalised to a mirror's peak (Y = 1 at the specular direction), so its albedo is
            // the spike's small solid angle; `scale_ru` multiplies it: the examples' 3000 must stay ≤ 1.
            assert!(3000.0 * albedo <= 1.0, "{table}: albedo {albedo} × 3000 at θ_o = {theta_o}°");
        }
    }
}
