//! White-furnace scenes shared by the CPU test (`white_furnace.rs`) and the GPU test
//! (`crates/gpu/tests/white_furnace_gpu.rs` includes this file by path): a unit sphere inside a uniform environment of
//! radiance 1, no lights, an orthographic camera. A material that reflects all the light it receives
//! (white albedo, no absorption) must show radiance 1 over the whole sphere, at every angle of view.

#![allow(dead_code)]

use iridis_render::{parse_scene, Image, Scene};

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
    (
        "film over lambert",
        "[materials.b]\nkind = \"lambert\"\ncolor = [1, 1, 1]\n\
         [materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\"",
    ),
    (
        "film over dielectric r0",
        "[materials.b]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.0\nior = 1.5\n\
         [materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\"",
    ),
    (
        "film over dielectric r0.5",
        "[materials.b]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.5\nior = 1.5\n\
         [materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\"",
    ),
    (
        "film ×0.5 over dielectric r0.3",
        "[materials.b]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.3\nior = 1.5\n\
         [materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\"\nfactor = 0.5",
    ),
    (
        "film over dielectric r1",
        "[materials.b]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 1.0\nior = 1.5\n\
         [materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\"",
    ),
    ("soap bubble", "[materials.m]\nkind = \"thinfilm\"\nstack = \"air | water 400nm | air\"\ntransmission = true"),
    // A film over a white metal (F_0 = 1: the index (1 + √F_0)/(1 − √F_0) at its √F_0 ≤ 0.9999 cap, n ≈ 2·10⁴):
    // a lossless film over a near-perfect conductor reflects 1 − O(1/n) at every wavelength and angle.
    (
        "film over white metal r0",
        "[materials.b]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.0\nmetallic = 1.0\n\
         [materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\"",
    ),
    (
        "film over white metal r0.6",
        "[materials.b]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.6\nmetallic = 1.0\n\
         [materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\"",
    ),
    (
        "film over half metal r0.3",
        "[materials.b]\nkind = \"microfacet\"\ncolor = [1, 1, 1]\nroughness = 0.3\nmetallic = 0.5\n\
         [materials.m]\nkind = \"thinfilm\"\nstack = \"air | n=1.3 300nm | n=1.5\"\nbase = \"b\"",
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
