//! GPU against CPU: the lookup BRDF maps of the built-in surfaces and thin-film colours over angle ×
//! thickness frames must agree as displayed colours (issue 8: mean CIEDE2000 < 1, 99th percentile < 3).
//!
//! These tests need a Vulkan adapter; on a machine without a GPU install Mesa's software driver
//! (`apt-get install mesa-vulkan-drivers`, lavapipe). Without an adapter they fail, unless
//! `IRIDIS_SKIP_GPU=1` says to skip them.

use crate::common;

use std::sync::Arc;

use common::gpu;
use iridis_color::lab::delta_e_displayed;
use iridis_color::spectrum::uniform_grid;
use iridis_color::{Encoding, Illuminant, Observer, SpectralWeights, ToneMap, Xyz};
use iridis_diffraction::geometry::direction;
use iridis_diffraction::table::{Lookup, LookupTable, Precision, TableParams};
use iridis_diffraction::taylor::terms_for_bound;
use iridis_diffraction::{Fresnel, FresnelConvention, Patch, Shading, SpectralSetup, TaylorTerms};
use iridis_gpu::{FilmFrame, FilmPath, FilmPathUsed, GpuFilm, GpuLookup};
use iridis_thinfilm::accuracy::DeltaEStats;
use iridis_thinfilm::{Complex64, Stack};

/// CIEDE2000 between displayed colours (exposure, clipped to the sRGB cube), over the given pixels:
/// (mean, 99th percentile, max).
fn delta_e(a: &[Xyz], b: &[Xyz], exposure: f64, pixels: impl Iterator<Item = usize>) -> (f64, f64, f64) {
    let s = DeltaEStats::of(pixels.map(|i| delta_e_displayed(a[i], b[i], exposure)).collect());
    assert!(s.count > 0);
    (s.mean, s.p99, s.max)
}

/// A small lookup table of a built-in surface (16 µm patch at 50 nm, coherence = the patch, 121² grid).
fn small_table(name: &str) -> LookupTable {
    let spec = format!("builtin:{name}?size=16um&pixel=50nm");
    let hf = iridis_surface::load_surface(&spec, &Default::default()).unwrap();
    let patch = Patch::from_row_major(hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, &hf.heights_nm).unwrap();
    let n = terms_for_bound(patch.max_abs_height, 380.0, 1e-6).unwrap();
    let terms = TaylorTerms::compute(&patch, n, 16_000.0).unwrap();
    let params = TableParams { uv_resolution: 121, uv_power: 5.0 };
    LookupTable::build(&terms, &SpectralSetup::default(), params, &spec, &|_| {}).unwrap()
}

/// D65 and the CIE 1931 observer on 380–780 nm in 5 nm steps, the film tests' colorimetry.
fn d65_weights() -> SpectralWeights {
    SpectralWeights::new(&uniform_grid(380.0, 780.0, 5.0).unwrap(), Illuminant::D65, Observer::Cie1931)
}

#[test]
fn lookup_brdf_maps_match_the_cpu() {
    let Some(gpu) = gpu() else { return };
    let size = 96;
    let inside: Vec<usize> = (0..size * size)
        .filter(|&i| iridis_diffraction::map::view_direction(i % size, i / size, size).is_some())
        .collect();
    let paper = FresnelConvention::Paper;
    let cases: [(&str, Fresnel, bool, f64, f64, FresnelConvention); 6] = [
        ("blazed", Fresnel::Schlick { n: 1.5 }, true, 0.0, 0.0, FresnelConvention::Physical),
        ("cd", Fresnel::Schlick { n: 1.5 }, true, 0.0, 0.0, FresnelConvention::Physical),
        ("elaphe", Fresnel::Schlick { n: 1.5 }, true, 30.0, 40.0, FresnelConvention::Physical),
        ("xenopeltis", Fresnel::Schlick { n: 1.5 }, true, 20.0, 0.0, FresnelConvention::Physical),
        ("elaphe", Fresnel::Index { n: Complex64::new(0.2, 3.4) }, false, 45.0, 180.0, FresnelConvention::Physical),
        // The paper's R² (flag bit 3 of the shader) at oblique light, where R/R₀ is far from 1.
        ("elaphe", Fresnel::Schlick { n: 1.5 }, true, 60.0, 0.0, paper),
    ];
    let mut tables: Vec<(&str, Arc<LookupTable>)> = Vec::new();
    for (name, fresnel, shadowing, theta, phi, convention) in cases {
        let table = match tables.iter().find(|(n, _)| *n == name) {
            Some((_, t)) => t.clone(),
            None => {
                let t = Arc::new(small_table(name));
                tables.push((name, t.clone()));
                t
            }
        };
        let wi = direction(theta.to_radians(), phi.to_radians());
        let shading = Shading { fresnel: Arc::new(fresnel.clone()), shadowing, convention };
        let cpu = Lookup::new(table.clone(), shading, Precision::F64).unwrap();
        let cpu_map = iridis_diffraction::map::brdf_map(&cpu, wi, size, 1, &|_| {});
        let tone = ToneMap { exposure_ru: 1500.0, encoding: Encoding::Srgb };
        let g = GpuLookup::new(gpu, &table, fresnel.clone(), shadowing).unwrap().with_convention(convention);
        let out = g.render_map(wi, size, tone).unwrap();
        assert_eq!(out.xyz.len(), size * size);
        // Outside the disk the map is black on both.
        for i in (0..size * size).filter(|i| !inside.contains(i)) {
            assert_eq!(out.xyz[i], Xyz::default(), "pixel {i} outside the disk");
        }
        // The map is not trivially dark: the comparison below means something.
        let bright = inside.iter().filter(|&&i| cpu_map[i].y * 1500.0 > 0.05).count();
        assert!(bright > inside.len() / 50, "{name}: only {bright} lit pixels");
        for exposure in [1.0, 1500.0, 7500.0] {
            let (mean, p99, max) = delta_e(&out.xyz, &cpu_map, exposure, inside.iter().copied());
            eprintln!(
                "lookup {name} N={} θi={theta}° φi={phi}° {:?} shadowing={shadowing} {convention:?} at {exposure} \
                 RU: ΔE00 mean {mean:.5} p99 {p99:.5} max {max:.4}",
                table.meta.taylor_terms, fresnel
            );
            // Issue 14: measured on lavapipe, mean ≤ 1.2e-4 and p99 ≤ 1.1e-3; the bound leaves room for other
            // GPUs' f32 arithmetic while still failing on any real regression.
            assert!(mean < 0.01 && p99 < 0.1, "{name} at {exposure} RU: mean {mean}, p99 {p99}");
        }
        // The displayed pixels the shader writes are ToneMap::to_rgb8 of its own XYZ (±1 level for rounding).
        for (i, p) in out.xyz.iter().enumerate() {
            let want = tone.to_rgb8(*p);
            let got = &out.rgb8[3 * i..3 * i + 3];
            for c in 0..3 {
                assert!((want[c] as i32 - got[c] as i32).abs() <= 1, "pixel {i}: {got:?} vs {want:?}");
            }
        }
    }
}

#[test]
fn a_table_split_over_several_buffers_gives_the_same_map() {
    let Some(gpu) = gpu() else { return };
    let table = small_table("elaphe");
    let wi = direction(25f64.to_radians(), 60f64.to_radians());
    let tone = ToneMap::default();
    let whole = GpuLookup::new(gpu, &table, Fresnel::default(), true).unwrap();
    assert_eq!(whole.table_buffers(), 1);
    let reference = whole.render_map(wi, 64, tone).unwrap();
    let row = (table.meta.uv_resolution * 3 * table.powers() * 4) as u64;
    // 40 rows per buffer: 121 rows need 3 buffers (rows 0-40, 40-80, 80-120); 30 rows: 4 buffers.
    for (rows, buffers) in [(41u64, 3usize), (31, 4)] {
        let split = GpuLookup::with_binding_limit(gpu, &table, Fresnel::default(), true, rows * row).unwrap();
        assert_eq!(split.table_buffers(), buffers);
        let out = split.render_map(wi, 64, tone).unwrap();
        assert_eq!(out.xyz, reference.xyz, "{buffers} buffers");
    }
    // More than four buffers' worth is refused with advice.
    let e = GpuLookup::with_binding_limit(gpu, &table, Fresnel::default(), true, 20 * row).unwrap_err().to_string();
    assert!(e.contains("--uv-resolution"), "{e}");
}

/// A deterministic smooth grey texture in [0, 1] (sums of sines), as an SVT map.
fn svt_texture(width: usize, height: usize) -> Vec<f32> {
    let mut a = Vec::with_capacity(width * height);
    for r in 0..height {
        for c in 0..width {
            let (x, y) = (c as f64 / width as f64, r as f64 / height as f64);
            let v = 0.5 + 0.3 * (7.0 * x + 3.0 * y).sin() * (5.0 * y).cos() + 0.2 * (13.0 * x * y).sin();
            a.push(v.clamp(0.0, 1.0) as f32);
        }
    }
    a
}

#[test]
fn thin_film_colours_match_the_cpu() {
    let Some(gpu) = gpu() else { return };
    let weights = d65_weights();
    let mirror: String = {
        let mut s = String::from("air");
        for _ in 0..10 {
            s.push_str(" | n=2.35 58.5nm | n=1.38 99.6nm");
        }
        s + " | glass"
    };
    let mirror_offset = if std::env::var("IRIDIS_EXHAUSTIVE").as_deref() == Ok("1") { 40.0 } else { 10.0 };
    let (w, h) = (90, 64);
    let cases: Vec<(&str, String, (f64, f64), bool)> = vec![
        ("soap film 0–1500 nm", "air | water 750nm | air".into(), (-750.0, 750.0), false),
        ("soap film with SVT", "air | water 400nm | air".into(), (-200.0, 200.0), true),
        ("oil slick", "air | gasoline 216nm | water 220nm | asphalt".into(), (-200.0, 200.0), true),
        ("Si on glass (measured n, κ)", "air | Si 108nm | glass".into(), (-100.0, 100.0), false),
        ("film on gold-like metal", "air | n=1.38 100nm | n=0.2+3.4i".into(), (-100.0, 300.0), false),
        ("gold film (measured)", "air | Au 30nm | glass".into(), (-25.0, 25.0), false),
        // ±10 nm of offset, as thinfilm's own table test (crates/thinfilm/tests/film_tables.rs): the table's grid
        // follows the fastest fringe, and over ±40 nm this mirror's was 724 cos θ × 755 offset nodes (10 s on
        // lavapipe, 20 CPU-s) to shade this 90 × 64 frame. The full range with `IRIDIS_EXHAUSTIVE=1` (README).
        ("20-layer mirror", mirror, (-mirror_offset, mirror_offset), false),
    ];
    for (name, spec, offsets, svt) in cases {
        let stack: Stack = spec.parse().unwrap();
        let frame = FilmFrame {
            width: w,
            height: h,
            angle_rad: (0.0, 89f64.to_radians()),
            offset_nm: offsets,
            svt: svt.then(|| (150.0, svt_texture(w, h))),
        };
        let all: Vec<usize> = (0..w * h).collect();
        let cpu = iridis_gpu::film::cpu_reference(&stack, &weights, &frame, &all).unwrap();
        let (cr, ct): (Vec<Xyz>, Vec<Xyz>) = cpu.into_iter().unzip();
        // Both paths: the direct evaluation (f32 rounding only: mean 0.01, p99 0.1) and the colour table
        // (issue 17's fast path: its interpolation error too, which the thin-film library's own test,
        // `tables_meet_the_colour_bound`, holds to mean 0.02, p99 0.35 in f64 over 0°–89.5°).
        for path in [FilmPath::Direct, FilmPath::Table] {
            let (mean_max, p99_max) = if path == FilmPath::Direct { (0.01, 0.1) } else { (0.02, 0.35) };
            let film = GpuFilm::new(gpu, &stack, &weights).unwrap().with_path(path);
            let run = film.frame(&frame, ToneMap::default()).unwrap();
            assert_eq!(matches!(run.path(), FilmPathUsed::Table { .. }), path == FilmPath::Table, "{name}");
            run.run().unwrap();
            let out = run.read().unwrap();
            // Reflected colour exposed so that the brightest pixel reaches Y = 1 (as `iridis thinfilm chart`).
            let ymax = cr.iter().map(|x| x.y).fold(0.0f64, f64::max);
            assert!(ymax > 0.01, "{name}: the film reflects almost nothing ({ymax})");
            let (mean, p99, max) = delta_e(&out.reflected, &cr, 1.0 / ymax, 0..w * h);
            eprintln!(
                "film {name} ({path:?}): reflected at {:.2} RU: ΔE00 mean {mean:.5} p99 {p99:.5} max {max:.4}",
                1.0 / ymax
            );
            assert!(mean < mean_max && p99 < p99_max, "{name} {path:?} reflected: mean {mean}, p99 {p99}");
            let tmax = ct.iter().map(|x| x.y).fold(0.0f64, f64::max);
            if tmax > 0.01 {
                let (mean, p99, max) = delta_e(&out.transmitted, &ct, 1.0 / tmax, 0..w * h);
                eprintln!("film {name} ({path:?}): transmitted: ΔE00 mean {mean:.5} p99 {p99:.5} max {max:.4}");
                assert!(mean < mean_max && p99 < p99_max, "{name} {path:?} transmitted: mean {mean}, p99 {p99}");
            } else {
                // An opaque substrate: the shader must transmit nothing too.
                assert!(out.transmitted.iter().all(|x| x.y.abs() < 1e-6), "{name}: light through an absorber");
            }
            // Energy: R + T ≤ 1 (Y of a white reflector is 1), up to f32 rounding.
            for (r, t) in out.reflected.iter().zip(&out.transmitted) {
                assert!(r.y + t.y <= 1.0 + 1e-4 && r.y >= 0.0 && t.y >= 0.0, "{name}: R {} T {}", r.y, t.y);
            }
        }
    }
}

#[test]
fn a_layer_at_its_critical_angle() {
    // An air gap in glass: at θ = asin(1/1.5) the gap's cosine is 0 and eq. 3.1 is 0/0. The CPU averages two
    // shifted evaluations there (recurrence::grazing_variants); the f32 shader evaluates directly — its cosine
    // is never exactly 0 — and must still agree.
    let Some(gpu) = gpu() else { return };
    let weights = d65_weights();
    let stack: Stack = "n=1.5 | n=1.0 300nm | n=1.5".parse().unwrap();
    let crit = (1.0f64 / 1.5).asin();
    let (w, h) = (201, 8);
    let frame =
        FilmFrame { width: w, height: h, angle_rad: (crit - 0.01, crit + 0.01), offset_nm: (-100.0, 100.0), svt: None };
    assert!((frame.pixel(100, 0).0 - crit).abs() < 1e-15);
    // No colour table follows the kink at the critical angle: the fast path evaluates directly and says why.
    let film = GpuFilm::new(gpu, &stack, &weights).unwrap();
    assert_eq!(film.path(), FilmPath::Table);
    let run = film.frame(&frame, ToneMap::default()).unwrap();
    match run.path() {
        FilmPathUsed::Direct { why: Some(w) } => assert!(w.contains("critical angle"), "{w}"),
        other => panic!("expected the direct path, got {other:?}"),
    }
    run.run().unwrap();
    let out = run.read().unwrap();
    let all: Vec<usize> = (0..w * h).collect();
    let cpu = iridis_gpu::film::cpu_reference(&stack, &weights, &frame, &all).unwrap();
    let worst = all.iter().map(|&i| (cpu[i].0.y - out.reflected[i].y).abs()).fold(0.0, f64::max);
    let (cr, _): (Vec<Xyz>, Vec<Xyz>) = cpu.into_iter().unzip();
    let (mean, p99, max) = delta_e(&out.reflected, &cr, 1.0, 0..w * h);
    eprintln!("film at the critical angle ±0.57°: max |ΔY| {worst:.2e}, ΔE00 mean {mean:.5} p99 {p99:.5} max {max:.4}");
    assert!(worst < 1e-4 && mean < 0.01 && p99 < 0.1, "|ΔY| {worst}, mean {mean}, p99 {p99}");
}

#[test]
fn thin_film_frame_rejects_bad_input() {
    let Some(gpu) = gpu() else { return };
    let weights = d65_weights();
    // Rutile has no data below 430 nm: an error that names the material, not a silent extrapolation.
    let stack: Stack = "air | rutile 100nm | glass".parse().unwrap();
    let e = GpuFilm::new(gpu, &stack, &weights).unwrap_err().to_string();
    assert!(e.contains("rutile") && e.contains("380"), "{e}");
    let stack: Stack = "air | water 300nm | air".parse().unwrap();
    let film = GpuFilm::new(gpu, &stack, &weights).unwrap();
    let bad = FilmFrame { width: 4, height: 4, angle_rad: (0.0, 2.0), offset_nm: (0.0, 0.0), svt: None };
    assert!(film.render(&bad, ToneMap::default()).unwrap_err().to_string().contains("0°–90°"));
    let bad = FilmFrame { angle_rad: (0.0, 1.0), svt: Some((10.0, vec![0.5; 3])), ..bad };
    assert!(film.render(&bad, ToneMap::default()).unwrap_err().to_string().contains("SVT texture"));
}
