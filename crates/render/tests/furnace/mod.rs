//! White-furnace scenes shared by the CPU test (`white_furnace.rs`) and the GPU test
//! (`crates/gpu/tests/white_furnace_gpu.rs` includes this file by path): a unit sphere inside a uniform environment of
//! radiance 1, no lights, an orthographic camera. A material that reflects all the light it receives
//! (white albedo, no absorption) must show radiance 1 over the whole sphere, at every angle of view.

#![allow(dead_code)]

use iridis_render::{parse_scene, Image, Scene};

/// A lossless film (n = 1.3, 300 nm, on n = 1.5) as material `m` over the base material `b` given as its keys,
/// then any more keys of the film.
macro_rules! film_over {
    ($base:literal $(, $film:literal)?) => {
        concat!(
            "[materials.b]\n",
            $base,
            "\n[materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\""
            $(, $film)?
        )
    };
}

/// (name, the `[materials.m]` table(s), whether the material absorbs nothing in every channel or only in
/// luminance (films: their reflectance is coloured, the base takes the rest per channel)).
pub const MATERIALS: &[(&str, &str)] = &[
    ("lambert", "[materials.m]\nkind = \"lambert\"\ncolor = [1, 1, 1]"),
    ("dielectric r0", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.0\nior = 1.5"),
    ("dielectric r0.2", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.2\nior = 1.5"),
    ("dielectric r0.5", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.5\nior = 1.5"),
    ("dielectric r0.8", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.8\nior = 1.5"),
    ("dielectric r1", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 1.0\nior = 1.5"),
    ("dielectric n2.4 r0.3", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.3\nior = 2.4"),
    ("metal r0", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.0\nmetallic = 1.0"),
    ("metal r0.3", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.3\nmetallic = 1.0"),
    ("metal r0.7", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.7\nmetallic = 1.0"),
    ("metal r1", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 1.0\nmetallic = 1.0"),
    ("half metal r0.4", "[materials.m]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.4\nmetallic = 0.5"),
    ("film over lambert", film_over!("kind = \"lambert\"\ncolor = [1, 1, 1]")),
    ("film over dielectric r0", film_over!("kind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.0\nior = 1.5")),
    ("film over dielectric r0.5", film_over!("kind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.5\nior = 1.5")),
    (
        "film ×0.5 over dielectric r0.3",
        film_over!("kind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.3\nior = 1.5", "\nfactor = 0.5"),
    ),
    ("film over dielectric r1", film_over!("kind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 1.0\nior = 1.5")),
    ("soap bubble", "[materials.m]\nkind = \"thinfilm\"\nstack = \"air | water 400nm | air\"\ntransmission = true"),
    // A film over a white metal (F_0 = 1: the index (1 + √F_0)/(1 − √F_0) at its √F_0 ≤ 0.9999 cap, n ≈ 2·10⁴):
    // a lossless film over a near-perfect conductor reflects 1 − O(1/n) at every wavelength and angle.
    (
        "film over white metal r0",
        film_over!("kind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.0\nmetallic = 1.0"),
    ),
    (
        "film over white metal r0.6",
        film_over!("kind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.6\nmetallic = 1.0"),
    ),
    (
        "film over half metal r0.3",
        film_over!("kind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.3\nmetallic = 0.5"),
    ),
];

/// The furnace scene for a material table (the sphere uses material `m`), rendered at `scale`.
pub fn furnace_scene(materials: &str, scale: f64) -> Scene {
    let text = format!(
        "[output]\nmax_depth = 8\n\
         [camera]\nkind = \"orthographic\"\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nheight = 2.2\n\
         [environment]\nkind = \"uniform\"\ncolor = [1, 1, 1]\n\
         {materials}\n\
         [[object]]\nkind = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1.0\nmaterial = \"m\"\n"
    );
    let mut s = parse_scene(&text, "furnace.toml", std::path::Path::new(".")).unwrap();
    s.scale(scale);
    s
}

/// The largest deviation from radiance 1 of any channel over the pixels whose centre sees the sphere
/// (within 0.995 of its radius), and the number of such pixels. `size × size` image of [`furnace_scene`].
pub fn deviation(img: &Image) -> (f64, usize) {
    let size = img.width as f64;
    let (mut worst, mut n) = (0.0f64, 0);
    for row in 0..img.height {
        for col in 0..img.width {
            let x = (-1.0 + 2.0 * (col as f64 + 0.5) / size) * 1.1;
            let y = (1.0 - 2.0 * (row as f64 + 0.5) / size) * 1.1;
            if x * x + y * y > 0.995f64.powi(2) {
                continue;
            }
            n += 1;
            for c in img.data[(row * img.width + col) as usize] {
                worst = worst.max((c as f64 - 1.0).abs());
            }
        }
    }
    (worst, n)
}

/// Columns of [`furnace_grid`].
pub const GRID_COLS: usize = 6;

/// Every material of [`MATERIALS`] on its own unit sphere, in a grid of [`GRID_COLS`] columns 2.5 apart, inside
/// the furnace (the spheres see each other, which a furnace allows: what they reflect is radiance 1 too),
/// rendered at `scale`. One scene, so that the GPU compiles and uploads once.
pub fn furnace_grid(scale: f64) -> Scene {
    let rows = MATERIALS.len().div_ceil(GRID_COLS);
    let mut text = format!(
        "[output]\nmax_depth = 8\n\
         [camera]\nkind = \"orthographic\"\nposition = [0, 0, 10]\nlook_at = [0, 0, 0]\nheight = {}\n\
         [environment]\nkind = \"uniform\"\ncolor = [1, 1, 1]\n",
        2.5 * rows as f64
    );
    for (i, (_, mat)) in MATERIALS.iter().enumerate() {
        let (x, y) = grid_centre(i, rows);
        text.push_str(
            &mat.replace("[materials.m]", &format!("[materials.m{i}]"))
                .replace("[materials.b]", &format!("[materials.b{i}]"))
                .replace("base = \"b\"", &format!("base = \"b{i}\"")),
        );
        text.push_str(&format!(
            "\n[[object]]\nkind = \"sphere\"\ncenter = [{x}, {y}, 0]\nradius = 1.0\nmaterial = \"m{i}\"\n"
        ));
    }
    let mut s = parse_scene(&text, "furnace_grid.toml", std::path::Path::new(".")).unwrap();
    s.scale(scale);
    s
}

fn grid_centre(i: usize, rows: usize) -> (f64, f64) {
    let (c, r) = ((i % GRID_COLS) as f64, (i / GRID_COLS) as f64);
    (2.5 * (c - (GRID_COLS as f64 - 1.0) / 2.0), -2.5 * (r - (rows as f64 - 1.0) / 2.0))
}

/// Per material of [`furnace_grid`] (an image `GRID_COLS · k` × `rows · k` pixels): the largest deviation
/// from 1 over the pixels whose centre sees its sphere (within 0.98 of the radius), and their number.
pub fn grid_deviation(img: &Image) -> Vec<(f64, usize)> {
    let rows = MATERIALS.len().div_ceil(GRID_COLS);
    let (w, h) = (img.width as f64, img.height as f64);
    let half_h = 1.25 * rows as f64;
    let half_w = half_h * w / h;
    let mut out = vec![(0.0f64, 0usize); MATERIALS.len()];
    for row in 0..img.height {
        for col in 0..img.width {
            let x = (-1.0 + 2.0 * (col as f64 + 0.5) / w) * half_w;
            let y = (1.0 - 2.0 * (row as f64 + 0.5) / h) * half_h;
            for (i, o) in out.iter_mut().enumerate() {
                let (cx, cy) = grid_centre(i, rows);
                if (x - cx).powi(2) + (y - cy).powi(2) <= 0.98f64.powi(2) {
                    o.1 += 1;
                    for c in img.data[(row * img.width + col) as usize] {
                        o.0 = o.0.max((c as f64 - 1.0).abs());
                    }
                }
            }
        }
    }
    out
}

/// The energy-blend diffraction material of the furnace tests (issue 21): a radiometric table of a rough
/// nanostructure with a wide lobe (64² heights × 100 nm correlated over ~3 pixels, 60 nm scale, 3.2 µm
/// coherence, a 101² u-v table), a white texture under it, `w_diffuse` 0, Schlick with n = 1.5 (`R₀` = 0.04).
/// Returns the material and its lobe albedo. Built in a few seconds, identically on every call.
pub fn energy_diffraction() -> (iridis_render::material::Diffraction, iridis_render::lobe_albedo::LobeAlbedo) {
    use std::sync::Arc;

    use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
    use iridis_diffraction::taylor::terms_for_bound;
    use iridis_diffraction::{Patch, Shading, SpectralSetup, TaylorTerms};
    use iridis_render::lobe_albedo::LobeAlbedo;
    use iridis_render::material::{Blend, ColorSource, Diffraction, OrientRule, Orientation};

    let n = 64;
    let mut seed = 7u64;
    let mut rnd = move || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let noise: Vec<f64> = (0..n * n).map(|_| rnd()).collect();
    // Heights correlated over ~3 pixels (300 nm): light scattered over tens of degrees.
    let heights: Vec<f64> = (0..n * n)
        .map(|k| {
            let (r, c) = (k / n, k % n);
            (0..3)
                .flat_map(|dr| (0..3).map(move |dc| (dr, dc)))
                .map(|(dr, dc)| noise[((r + dr) % n) * n + (c + dc) % n])
                .sum::<f64>()
                * 60.0
        })
        .collect();
    let patch = Patch::from_row_major(n, n, 100.0, 100.0, &heights).unwrap();
    let coherence = 3200.0;
    let terms =
        TaylorTerms::compute(&patch, terms_for_bound(patch.max_abs_height, 380.0, 1e-6).unwrap(), coherence).unwrap();
    let spectral = SpectralSetup::default().radiometric(coherence).unwrap();
    let table =
        LookupTable::build(&terms, &spectral, TableParams { uv_resolution: 101, uv_power: 5.0 }, "rough", &|_| {})
            .unwrap();
    let lookup = Lookup::new(Arc::new(table), Shading::default(), Precision::F64).unwrap();
    let r0 = 0.04;
    let albedo = LobeAlbedo::compute(&lookup, r0).unwrap();
    let material = Diffraction {
        evaluator: Arc::new(lookup),
        orientation: Orientation { rule: OrientRule::Tangent, angle: 0.0 },
        scale_ru: std::f64::consts::PI * r0,
        w_diffuse: 0.0,
        texture: ColorSource::Const([1.0; 3]),
        ambient: 0.0,
        fresnel_n: 1.5,
        description: "rough".into(),
        blend: Blend::Energy(Arc::new(albedo.clone())),
        extended: Default::default(),
    };
    (material, albedo)
}

/// [`furnace_scene`] with the sphere made of `material` (built once by [`energy_diffraction`] and cloned per
/// scene: its table takes seconds), integrated by the fast path.
pub fn energy_diffraction_furnace(material: &iridis_render::material::Diffraction, scale: f64) -> Scene {
    let mut s = furnace_scene("[materials.m]\nkind = \"lambert\"\ncolor = [1, 1, 1]", scale);
    s.materials[0] = iridis_render::material::Material::Diffraction(Box::new(material.clone()));
    s
}

/// The scene integrated by Monte Carlo with `strategy` (the environment's sampler made for it).
pub fn monte_carlo(mut s: Scene, strategy: iridis_render::integrate::Strategy) -> Scene {
    s.integration = iridis_render::integrate::Integration::MonteCarlo(strategy);
    s.update_irradiance();
    s
}

/// A hit at the origin of the plane z = 0 (normal +z, no tangent): the frame of the material-level tests.
pub fn flat_hit() -> iridis_render::geometry::Hit {
    iridis_render::geometry::Hit {
        t: 1.0,
        p: [0.0; 3],
        n: [0.0, 0.0, 1.0],
        ng: [0.0, 0.0, 1.0],
        front: true,
        uv: [0.0; 2],
        tangent: None,
        tangent_sign: 1.0,
        along: None,
        material: 0,
    }
}

/// Mean and its standard error of independent samples.
pub fn mean_and_se(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    (mean, (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt())
}

/// The largest |L − 1| over the sphere's pixels whose normal is within `deg` of the view (the orthographic
/// camera looks down −z at the unit sphere: cos θ_o = √(1 − x² − y²)).
pub fn worst_within(img: &Image, deg: f64) -> f64 {
    let size = img.width as f64;
    let mut worst = 0.0f64;
    for row in 0..img.height {
        for col in 0..img.width {
            let x = (-1.0 + 2.0 * (col as f64 + 0.5) / size) * 1.1;
            let y = (1.0 - 2.0 * (row as f64 + 0.5) / size) * 1.1;
            let r2 = x * x + y * y;
            if r2 < 1.0 && (1.0 - r2).sqrt() >= deg.to_radians().cos() {
                for c in img.data[(row * img.width + col) as usize] {
                    worst = worst.max((c as f64 - 1.0).abs());
                }
            }
        }
    }
    worst
}

/// Pixels of a [`furnace_scene`] image whose centre sees the sphere (as [`deviation`] counts them).
pub fn sphere_pixels(img: &Image) -> impl Iterator<Item = [f32; 3]> + '_ {
    let size = img.width as f64;
    (0..img.height).flat_map(move |row| {
        (0..img.width).filter_map(move |col| {
            let x = (-1.0 + 2.0 * (col as f64 + 0.5) / size) * 1.1;
            let y = (1.0 - 2.0 * (row as f64 + 0.5) / size) * 1.1;
            (x * x + y * y <= 0.995f64.powi(2)).then(|| img.data[(row * img.width + col) as usize])
        })
    })
}

/// The fast path's bounds in the diffraction furnace, where the lobe's share of the light (0.03 at normal view,
/// 0.12 at 70°, more towards grazing) goes through the environment's 64-cell quadrature, whose cells near the
/// surface's horizon count whole or not at all: within 45° of the view, and over the whole sphere. Measured
/// 2026-11-26 (41² pixels): 9.1e-3 within 45° (4.2e-3 within 20°, 2.7e-2 within 60°, 8.3e-2 within 70°) and
/// 0.18 at the rim (docs/render.md, "White furnace"). Monte Carlo has no such error.
pub const FAST_DIFFRACTION_FURNACE: f64 = 0.012;
pub const FAST_DIFFRACTION_FURNACE_RIM: f64 = 0.2;

/// One material's furnace result `(largest |L − 1|, pixels on its sphere)`: the sphere must cover more than
/// `min_pixels`; a deviation above `tol` is noted in `failures` (the test lists them all before failing).
pub fn tally(failures: &mut Vec<String>, label: &str, (worst, n): (f64, usize), min_pixels: usize, tol: f64) {
    eprintln!("{label:<40} {n} pixels, largest |L − 1| = {worst:.2e}");
    assert!(n > min_pixels, "{label}: the sphere covers {n} pixels");
    if worst > tol {
        failures.push(format!("{label}: |L − 1| up to {worst:.4}"));
    }
}

/// Rough films for the furnace, (stack, σ, τ): a dielectric, an absorbing substrate and a metal.
pub const ROUGH_FILMS: [(&str, &str, &str); 3] = [
    ("air | water 348nm | Si", "25nm", "300nm"),
    ("air | n=2.0 80nm | n=0.2+3.4i", "25nm", "300nm"),
    ("air | TiO2 250nm | Al", "20nm", "400nm"),
];

/// The furnace scene of one of [`ROUGH_FILMS`], at unit scale.
pub fn rough_film_furnace(stack: &str, sigma: &str, tau: &str) -> Scene {
    furnace_scene(
        &format!(
            "[materials.m]\nkind = \"thinfilm\"\nstack = \"{stack}\"\nroughness = \"{sigma}\"\ncorrelation = \"{tau}\""
        ),
        1.0,
    )
}

/// Checks a 21 × 21 image of [`rough_film_furnace`] (rendered by `who`): at the centre of the sphere (normal
/// view) the luminance must be the film's reflected fraction `k_r + ∫ k_d cos θ dω` — by reciprocity the
/// directional albedo at normal incidence, which `RoughStack::albedo` integrates on a dense 60 × 120 grid,
/// weighted by D65 × ȳ — and no channel of a pixel whose centre sees the sphere may exceed radiance 1.01.
pub fn assert_rough_film_reflects_its_albedo(scene: &Scene, img: &Image, stack: &str, who: &str) {
    use iridis_color::{Illuminant, Observer};
    use iridis_render::material::Material;
    use iridis_thinfilm::color::FilmColorimeter;
    use iridis_thinfilm::rough::RoughStack;
    let Material::ThinFilm(f) = &scene.materials[0] else { panic!("{stack}: not a film") };
    let rough = RoughStack::new(f.stack.clone(), f.rough.expect("a rough film"));
    let grid = iridis_color::spectrum::uniform_grid(380.0, 780.0, 5.0).unwrap();
    let albedo: Vec<f64> = grid.iter().map(|&l| rough.albedo(l, 0.0, 60).unwrap().total()).collect();
    let expected = FilmColorimeter::new(&grid, Illuminant::D65, Observer::Cie1931).from_spectra(&albedo, &albedo);
    let y = |rgb: [f32; 3]| 0.2126 * rgb[0] as f64 + 0.7152 * rgb[1] as f64 + 0.0722 * rgb[2] as f64;
    let centre = y(img.data[10 * 21 + 10]);
    // Over the pixels whose centre sees the sphere (the others show the furnace's radiance 1).
    let mut brightest = 0.0f32;
    for row in 0..21u32 {
        for col in 0..21u32 {
            let (x, yy) =
                ((-1.0 + 2.0 * (col as f64 + 0.5) / 21.0) * 1.1, (1.0 - 2.0 * (row as f64 + 0.5) / 21.0) * 1.1);
            if x * x + yy * yy < 0.98 {
                brightest = img.data[(row * 21 + col) as usize].iter().fold(brightest, |a, &b| a.max(b));
            }
        }
    }
    eprintln!(
        "{stack}: {who} centre Y {centre:.4}, dense albedo Y {:.4}, brightest channel {brightest:.4}",
        expected.reflected.y
    );
    assert!(
        (centre - expected.reflected.y).abs() < 0.005,
        "{stack}: centre Y {centre} vs albedo {}",
        expected.reflected.y
    );
    assert!(brightest < 1.01, "{stack}: a channel reaches {brightest} in the furnace");
}
