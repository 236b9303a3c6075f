//! The unit tests of src/formats/npy.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::npy::*;
use iridis_surface::formats::{LoadOptions, Sidecar};

#[test]
fn round_trip_with_sidecar() {
    let hf = crate::unit_formats::sample_field();
    let bytes = write(&hf).unwrap();
    let side = Sidecar::for_field(&hf, false);
    let back = read(&bytes, Some(&side), &LoadOptions::default()).unwrap();
    assert_eq!(back.heights_nm, hf.heights_nm);
    assert_eq!((back.dx_nm, back.dy_nm), (hf.dx_nm, hf.dy_nm));
    assert!(back.meta.warnings.is_empty());
    // Without units it refuses, saying how to give them.
    let e = read(&bytes, None, &LoadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("--pixel-size"), "{e}");
}

/// NaN lines in a .npy (an aborted scan saved by a script) are filled with the mean and said, as a .gsf's and an
/// instrument file's are (the .npy was refused, and `surface convert --crop`, the remedy offered, could not read
/// it either); an array of nothing but NaN is refused.
#[test]
fn nan_lines_are_filled_and_said() {
    let mut hf = crate::unit_formats::sample_field();
    let cols = hf.cols;
    let good_mean = {
        let row1: Vec<f64> = hf.heights_nm.iter().enumerate().filter(|(i, _)| i / cols != 1).map(|(_, v)| *v).collect();
        row1.iter().sum::<f64>() / row1.len() as f64
    };
    for c in 0..cols {
        hf.heights_nm[cols + c] = 0.0;
    }
    let mut bytes = write(&hf).unwrap();
    // Row 1 as NaN in the f64 data at the end of the file.
    let n = bytes.len();
    let data_start = n - hf.rows * cols * 8;
    for c in 0..cols {
        let at = data_start + (cols + c) * 8;
        bytes[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    }
    let side = Sidecar::for_field(&hf, false);
    let back = read(&bytes, Some(&side), &LoadOptions::default()).unwrap();
    let w = back.meta.warnings.join(" ");
    assert!(
        w.contains(&format!("{cols} of {} samples are not numbers", hf.rows * cols)) && w.contains("first row 1"),
        "{w}"
    );
    assert!((back.heights_nm[cols] - good_mean).abs() < 1e-9 * good_mean.abs().max(1.0));
    let all: Vec<u8> = {
        let mut b = bytes.clone();
        for k in 0..hf.rows * cols {
            let at = data_start + k * 8;
            b[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
        }
        b
    };
    let e = read(&all, Some(&side), &LoadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("holds no finite value"), "{e}");
    // All but row 0: more than half are not numbers, refused (filled, the statistics were the filling's).
    assert!(hf.rows >= 3);
    let most: Vec<u8> = {
        let mut b = bytes.clone();
        for k in (0..hf.rows * cols).filter(|k| k / cols != 0) {
            let at = data_start + k * 8;
            b[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
        }
        b
    };
    let e = read(&most, Some(&side), &LoadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("more than half: filled, the field would describe the filling"), "{e}");
}
