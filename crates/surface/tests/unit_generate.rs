//! The unit tests of src/generate.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::generate::*;

fn small() -> Grid {
    Grid { size_x_nm: 8000.0, size_y_nm: 6000.0, pixel_nm: 50.0, angle_rad: 0.0, seed: 3 }
}

#[test]
fn grid_dimensions_follow_size_and_pixel() {
    let g = small();
    assert_eq!(g.dims().unwrap(), (120, 160));
    assert_eq!(Grid::default().dims().unwrap(), (1000, 1000));
    let bad = Grid { pixel_nm: 0.0, ..small() };
    assert!(bad.dims().is_err());
    let huge = Grid { pixel_nm: 0.001, ..Grid::default() };
    assert!(huge.dims().unwrap_err().to_string().contains("too large"));
}

#[test]
fn blazed_facets_face_minus_x() {
    // Height rises with x inside a period: the facet normal (−dh/dx, 0, 1) leans towards −x.
    let hf = Generator::Blazed { period_nm: 2500.0, depth_nm: 262.0 }.generate(&small()).unwrap();
    let row = hf.row(10);
    let rising = row.windows(2).filter(|w| w[1] > w[0]).count();
    let falling = row.windows(2).filter(|w| w[1] < w[0]).count();
    assert!(rising > 10 * falling, "rising {rising}, falling {falling}");
    let (lo, hi) = hf.min_max();
    assert!(lo >= 0.0 && hi < 262.0 && hi > 262.0 * (1.0 - 50.0 / 2500.0) - 1e-9);
}

#[test]
fn seeds_reproduce_and_differ() {
    for gen in [
        Generator::Gaussian { rms_nm: 20.0, corr_nm: 300.0 },
        Generator::Elaphe { spacing_nm: 1100.0, finger_nm: 4000.0, rms_nm: 60.0 },
        Generator::Xenopeltis { along_nm: 1500.0, across_nm: 550.0, depth_nm: 120.0 },
        Generator::Cd { pitch_nm: 1600.0, bit_nm: 231.0, pit_width_nm: 500.0, depth_nm: 110.0 },
    ] {
        let a = gen.generate(&small()).unwrap();
        let b = gen.generate(&small()).unwrap();
        let c = gen.generate(&Grid { seed: 4, ..small() }).unwrap();
        assert_eq!(a.heights_nm, b.heights_nm, "{}", gen.kind());
        assert_ne!(a.heights_nm, c.heights_nm, "{}", gen.kind());
    }
}

#[test]
fn rms_targets_are_met() {
    let g = Generator::Gaussian { rms_nm: 20.0, corr_nm: 300.0 }.generate(&small()).unwrap();
    assert!((g.rms() - 20.0).abs() < 1e-9 && g.mean().abs() < 1e-9);
    let e = Generator::Elaphe { spacing_nm: 1100.0, finger_nm: 4000.0, rms_nm: 60.0 }.generate(&small()).unwrap();
    assert!((e.rms() - 60.0).abs() < 1e-9);
}

#[test]
fn cd_pits_have_efm_lengths() {
    // Along a track centre (angle 0, track j = 0 at v = 0, the middle row), pit lengths are 3T..11T.
    let grid = Grid { size_x_nm: 60_000.0, size_y_nm: 1_000.0, pixel_nm: 10.0, angle_rad: 0.0, seed: 9 };
    let bit = 231.0;
    let hf =
        Generator::Cd { pitch_nm: 1600.0, bit_nm: bit, pit_width_nm: 500.0, depth_nm: 110.0 }.generate(&grid).unwrap();
    let mid = hf.row(hf.rows / 2);
    let mut runs = Vec::new();
    let mut start = None;
    for (i, &h) in mid.iter().enumerate() {
        match (h < -55.0, start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                runs.push((i - s) as f64 * 10.0);
                start = None
            }
            _ => {}
        }
    }
    let inner = &runs[1..runs.len() - 1];
    assert!(inner.len() > 10);
    for &len in inner {
        let t = len / bit;
        assert!((2.9..=11.1).contains(&t), "pit of {len} nm = {t} T");
    }
}
