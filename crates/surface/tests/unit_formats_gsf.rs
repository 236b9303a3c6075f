//! The unit tests of src/formats/gsf.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::gsf::*;
use iridis_surface::formats::LoadOptions;

/// A file without lateral units asks for --pixel-size; NaN lines are reported and filled with the mean.
#[test]
fn no_units_and_nan_lines() {
    let mut head = String::from_utf8_lossy(MAGIC).into_owned();
    head += "XRes = 4\nYRes = 3\nXReal = 2\nYReal = 1.5\n";
    let mut b = head.into_bytes();
    let pad = 4 - b.len() % 4;
    b.resize(b.len() + pad, 0);
    let vals = [1.0f32, 2.0, 3.0, 4.0, f32::NAN, f32::NAN, f32::NAN, f32::NAN, 5.0, 6.0, 7.0, 8.0];
    for v in vals {
        b.extend_from_slice(&v.to_le_bytes());
    }
    let e = read(&b, None, &LoadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("--height-unit"), "{e}");
    let o = LoadOptions { height_unit: Some("nm".into()), ..Default::default() };
    let e = read(&b, None, &o).unwrap_err().to_string();
    assert!(e.contains("without XYUnits has no pixel size") && e.contains("--pixel-size"), "{e}");
    let o = LoadOptions { height_unit: Some("nm".into()), pixel_size_nm: Some(5.0), ..Default::default() };
    let hf = read(&b, None, &o).unwrap();
    assert_eq!(hf.get(1, 2), 4.5);
    let w = hf.meta.warnings.join(" ");
    assert!(w.contains("4 of 12 samples are not numbers") && w.contains("1 of 3 rows"), "{w}");
}

/// Two lines clipped at the top of the z range (60 samples at the maximum, in runs of 30) are reported and
/// filled with the mean of the other samples; a run of equal values below the extreme, and a short run at
/// the extreme, are heights and stay.
#[test]
fn saturated_lines_are_reported_and_filled() {
    let (rows, cols) = (12usize, 40usize);
    let mut vals: Vec<f32> = (0..rows * cols)
        .map(|i| (i / cols) as f32 * 0.1 + (i % cols) as f32 * 0.01 + (i as f32).sin() * 1e-3)
        .collect();
    for r in [5, 6] {
        for c in 0..30 {
            vals[r * cols + c] = 100.0;
        }
    }
    // Row 2: eight equal values mid-range (a flat terrace, not saturation); row 9: a 4-long run at the max.
    for c in 10..18 {
        vals[2 * cols + c] = 0.5;
    }
    for c in 0..4 {
        vals[9 * cols + c] = 100.0;
    }
    let mut head = String::from_utf8_lossy(MAGIC).into_owned();
    head += &format!("XRes = {cols}\nYRes = {rows}\nXReal = 4e-6\nYReal = 1.2e-6\nXYUnits = m\nZUnits = nm\n");
    let mut b = head.into_bytes();
    let pad = 4 - b.len() % 4;
    b.resize(b.len() + pad, 0);
    for v in &vals {
        b.extend_from_slice(&v.to_le_bytes());
    }
    let hf = read(&b, None, &LoadOptions::default()).unwrap();
    let w = hf.meta.warnings.join(" ");
    assert!(w.contains("60 samples in 2 of 12 rows (first row 5, last row 6)") && w.contains("saturated"), "{w}");
    let kept: Vec<f64> = (0..rows * cols)
        .filter(|i| !(i / cols == 5 || i / cols == 6) || i % cols >= 30)
        .map(|i| vals[i] as f64)
        .collect();
    let mean = kept.iter().sum::<f64>() / kept.len() as f64;
    assert!((hf.get(5, 0) - mean).abs() < 1e-9 && (hf.get(6, 29) - mean).abs() < 1e-9, "{}", hf.get(5, 0));
    assert_eq!(hf.get(2, 12), 0.5, "a mid-range terrace is a height");
    assert_eq!(hf.get(9, 0), 100.0, "a short run at the maximum is a height");
}

#[test]
fn round_trip_to_f32_precision() {
    let hf = crate::unit_formats::sample_field();
    let bytes = write(&hf);
    assert_eq!((bytes.len() - hf.heights_nm.len() * 4) % 4, 0);
    let back = read(&bytes, None, &LoadOptions::default()).unwrap();
    assert_eq!((back.rows, back.cols), (hf.rows, hf.cols));
    assert!((back.dx_nm - hf.dx_nm).abs() < 1e-9 * hf.dx_nm);
    for (a, b) in back.heights_nm.iter().zip(&hf.heights_nm) {
        assert!((a - b).abs() <= 1e-6 * b.abs().max(1.0), "{a} vs {b}");
    }
}
