//! The unit tests of src/prep.rs, moved here so that `cargo test` compiles the library once.

#[test]
fn poly_and_median_lines_remove_what_they_model() {
    let (rows, cols) = (20, 30);
    let bump = |r: usize, c: usize| if (r, c) == (7, 9) { 50.0 } else { 0.0 };
    // A quadratic bow plus tilt plus one spike: the polynomial leaves the spike (less its share).
    let h: Vec<f64> = (0..rows * cols)
        .map(|i| {
            let (r, c) = ((i / cols) as f64, (i % cols) as f64);
            3.0 + 0.2 * c - 0.1 * r + 0.01 * c * c + 0.02 * r * c - 0.03 * r * r + bump(i / cols, i % cols)
        })
        .collect();
    let hf = HeightField::new(rows, cols, 10.0, 10.0, h).unwrap();
    let p = level_poly(&hf);
    let smooth = HeightField::new(
        rows,
        cols,
        10.0,
        10.0,
        hf.heights_nm.iter().enumerate().map(|(i, v)| v - bump(i / cols, i % cols)).collect(),
    )
    .unwrap();
    for v in &level_poly(&smooth).heights_nm {
        assert!(v.abs() < 1e-9, "{v}");
    }
    assert!(p.get(7, 9) > 45.0);
    // Line offsets plus a spike: the medians remove the offsets exactly, the spike stays whole.
    let lines: Vec<f64> = (0..rows * cols).map(|i| 5.0 * (i / cols) as f64 + bump(i / cols, i % cols)).collect();
    let l = level_lines_median(&HeightField::new(rows, cols, 10.0, 10.0, lines).unwrap());
    let off = l.get(0, 0);
    assert!((l.get(7, 9) - off - 50.0).abs() < 1e-9 && (l.get(19, 29) - off).abs() < 1e-9);
    assert!(level_by_name(&hf, "wobble").unwrap_err().to_string().contains("poly, lines"));
}

use iridis_surface::prep::*;
use iridis_surface::HeightField;

/// The levelling line says what was asked, once, and says "default" when nothing was (issue 32: "plane
/// (as asked (--level))" was printed when nothing had been asked).
#[test]
fn the_levelling_line_names_the_choice() {
    let hf = HeightField::new(3, 3, 1.0, 1.0, (0..9).map(f64::from).collect()).unwrap();
    let (_, asked) = level_for_model("scan.spm", hf.clone(), Some("lines")).unwrap();
    assert_eq!(asked, "levelling: lines (as asked: --level lines)");
    let (_, default) = level_for_model("scan.spm", hf.clone(), None).unwrap();
    assert_eq!(default, "levelling: plane (the default for files; --level none keeps the tilt)");
    let (_, builtin) = level_for_model("builtin:sine", hf, None).unwrap();
    assert_eq!(builtin, "levelling: none (built-ins are used as generated)");
}

fn field(rows: usize, cols: usize, f: impl Fn(usize, usize) -> f64) -> HeightField {
    let h = (0..rows * cols).map(|i| f(i / cols, i % cols)).collect();
    HeightField::new(rows, cols, 10.0, 20.0, h).unwrap()
}

#[test]
fn plane_levelling_removes_a_tilt_exactly() {
    // A tilt plus a zero-mean, tilt-free pattern (symmetric in x and y about the centre).
    let hf = field(9, 11, |r, c| 5.0 + 0.3 * c as f64 - 0.7 * r as f64 + if (r + c) % 2 == 0 { 1.0 } else { -1.0 });
    let l = level_plane(&hf);
    let pattern = field(9, 11, |r, c| if (r + c) % 2 == 0 { 1.0 } else { -1.0 });
    let pm = pattern.mean();
    for (a, b) in l.heights_nm.iter().zip(&pattern.heights_nm) {
        assert!((a - (b - pm)).abs() < 1e-9, "{a} vs {b}");
    }
}

#[test]
fn mean_and_rows() {
    let hf = field(4, 5, |r, c| (r * 10 + c) as f64);
    assert!(remove_mean(&hf).mean().abs() < 1e-12);
    let l = level_rows(&hf);
    for r in 0..4 {
        assert!(l.row(r).iter().sum::<f64>().abs() < 1e-12);
    }
}

#[test]
fn crop_tile_pad() {
    let hf = field(4, 5, |r, c| (r * 10 + c) as f64);
    let c = crop(&hf, 1, 2, 2, 3).unwrap();
    assert_eq!(c.heights_nm, vec![12.0, 13.0, 14.0, 22.0, 23.0, 24.0]);
    assert!(crop(&hf, 3, 0, 2, 2).is_err());
    let t = tile(&c, 2, 3).unwrap();
    assert_eq!((t.rows, t.cols), (4, 9));
    assert_eq!(t.get(3, 7), c.get(1, 1));
    let p = pad(&c, 4, 5).unwrap();
    assert_eq!(p.get(1, 1), 12.0);
    assert_eq!(p.get(0, 0), c.mean());
    assert!(pad(&c, 1, 5).is_err());
}

#[test]
fn resample_keeps_extent_and_linear_ramps() {
    let hf = field(40, 60, |_, c| c as f64 * 10.0); // h = x in nm at pixel centres (x = c·dx, dx = 10)
    let r = resample(&hf, 5.0, 20.0).unwrap();
    assert_eq!((r.rows, r.cols), (40, 120));
    assert_eq!(r.extent_nm(), hf.extent_nm());
    // Output pixel c covers [5c, 5c+5]: centre 5c + 2.5 → input pixel coordinate 0.5c − 0.25.
    for c in 2..110 {
        let expect = (c as f64 * 0.5 - 0.25) * 10.0;
        assert!((r.get(7, c) - expect).abs() < 1e-9, "col {c}: {} vs {expect}", r.get(7, c));
    }
    let coarse = resample(&hf, 40.0, 40.0).unwrap();
    assert_eq!((coarse.rows, coarse.cols), (20, 15));
    assert!(resample(&hf, 0.0, 1.0).is_err());
    assert!(resample(&hf, f64::NAN, 1.0).is_err());
}
