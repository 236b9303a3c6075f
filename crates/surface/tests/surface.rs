//! Formats against independent writers (gwyfile, numpy: `tools/gen_surface_fixtures.py`), round trips through
//! every writable format, period analysis on generated gratings of known period, and bad input.

use std::path::{Path, PathBuf};

use iridis_surface::formats::channel::ChannelSel;
use iridis_surface::formats::{read_bytes, sidecar_path, write_bytes, Format};
use iridis_surface::generate::{Generator, Grid};
use iridis_surface::{find_peaks, load_surface, prep, HeightField, LoadOptions, PeakOptions};
use serde_json::Value;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(name)
}

fn expected() -> Value {
    serde_json::from_str(&std::fs::read_to_string(fixture("expected.json")).unwrap()).unwrap()
}

fn check_against_expected(hf: &HeightField, tol: f64) {
    let e = expected();
    assert_eq!(hf.rows as u64, e["rows"].as_u64().unwrap());
    assert_eq!(hf.cols as u64, e["cols"].as_u64().unwrap());
    assert!((hf.dx_nm - e["dx_nm"].as_f64().unwrap()).abs() < 1e-9, "dx {}", hf.dx_nm);
    assert!((hf.dy_nm - e["dy_nm"].as_f64().unwrap()).abs() < 1e-9, "dy {}", hf.dy_nm);
    for p in e["probe"].as_array().unwrap() {
        let (r, c, v) = (p[0].as_u64().unwrap() as usize, p[1].as_u64().unwrap() as usize, p[2].as_f64().unwrap());
        assert!((hf.get(r, c) - v).abs() <= tol * v.abs().max(1.0), "({r},{c}): {} vs {v}", hf.get(r, c));
    }
    let sum: f64 = hf.heights_nm.iter().sum();
    assert!((sum - e["sum_nm"].as_f64().unwrap()).abs() < 1e-3 + tol * 1e4, "sum {sum}");
}

#[test]
fn gwy_written_by_gwyfile() {
    let hf = load_surface(fixture("gwyfile_two_channels.gwy").to_str().unwrap(), &LoadOptions::default()).unwrap();
    check_against_expected(&hf, 1e-12);
    assert_eq!(hf.meta.z_unit, "m");
    assert!(hf.meta.notes.iter().any(|n| n.contains("'Height'")), "{:?}", hf.meta.notes);
    // Channel 1 is stored in µm, lateral and vertical: the units must be applied.
    let o = LoadOptions { channel: Some(ChannelSel::Index(1)), ..Default::default() };
    let c1 = load_surface(fixture("gwyfile_two_channels.gwy").to_str().unwrap(), &o).unwrap();
    assert!((c1.dx_nm - 100.0).abs() < 1e-9 && (c1.dy_nm - 80.0).abs() < 1e-9);
    for p in expected()["channel1_probe"].as_array().unwrap() {
        let (r, c, v) = (p[0].as_u64().unwrap() as usize, p[1].as_u64().unwrap() as usize, p[2].as_f64().unwrap());
        assert!((c1.get(r, c) - v).abs() < 1e-9, "({r},{c}) {} vs {v}", c1.get(r, c));
    }
    let e = load_surface(
        fixture("gwyfile_two_channels.gwy").to_str().unwrap(),
        &LoadOptions { channel: Some(ChannelSel::Index(7)), ..Default::default() },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("no channel 7") && e.contains("0: Height (m)"), "{e}");
    // No units in the file: metres assumed, and the user is told.
    let nu = load_surface(fixture("gwyfile_no_units.gwy").to_str().unwrap(), &LoadOptions::default()).unwrap();
    check_against_expected(&nu, 1e-12);
    assert!(nu.meta.warnings.iter().any(|w| w.contains("assumed metres")));
}

#[test]
fn gwy_fixture_periods_along_x_and_y() {
    // Channel 0: 800 nm along x (orientation 0°); channel 1: 640 nm along y (90°), non-square pixels.
    let p = fixture("gwyfile_two_channels.gwy");
    let c0 = load_surface(p.to_str().unwrap(), &LoadOptions::default()).unwrap();
    let pk = &find_peaks(&c0, &PeakOptions::default())[0];
    assert!((pk.period_nm - 800.0).abs() < 4.0 && pk.orientation_deg.min(180.0 - pk.orientation_deg) < 0.5, "{pk:?}");
    let c1 =
        load_surface(p.to_str().unwrap(), &LoadOptions { channel: Some(ChannelSel::Index(1)), ..Default::default() })
            .unwrap();
    let pk = &find_peaks(&c1, &PeakOptions::default())[0];
    assert!((pk.period_nm - 640.0).abs() < 3.2 && (pk.orientation_deg - 90.0).abs() < 0.5, "{pk:?}");
}

#[test]
fn npy_written_by_numpy() {
    // Sidecar beside numpy_f64.npy gives non-square pixels; the others get the pixel from the options
    // (dx = dy there) and warn that heights are assumed in nm.
    let hf = load_surface(fixture("numpy_f64.npy").to_str().unwrap(), &LoadOptions::default()).unwrap();
    check_against_expected(&hf, 0.0);
    assert!(hf.meta.warnings.is_empty());
    for (name, tol) in [("numpy_f32_fortran.npy", 1e-6), ("numpy_f64_bigendian.npy", 0.0)] {
        let o = LoadOptions { pixel_size_nm: Some(100.0), ..Default::default() };
        let mut h = load_surface(fixture(name).to_str().unwrap(), &o).unwrap();
        h.dy_nm = 80.0; // the options give one pixel size for both axes
        check_against_expected(&h, tol);
        assert!(h.meta.warnings.iter().any(|w| w.contains("nm")), "{name}");
    }
}

#[test]
fn npz_written_by_numpy_savez_and_savez_compressed() {
    let e = expected();
    // np.savez: the one 2-D array ("heights") beside a 1-D axis; units from the sidecar, exact values.
    let hf = load_surface(fixture("numpy_savez.npz").to_str().unwrap(), &LoadOptions::default()).unwrap();
    check_against_expected(&hf, 0.0);
    assert_eq!(hf.meta.format, "npz");
    assert!(hf.meta.warnings.is_empty(), "{:?}", hf.meta.warnings);
    assert!(hf.meta.notes.iter().any(|n| n.contains("'heights'")), "{:?}", hf.meta.notes);
    assert_eq!(e["npz_2d_arrays"]["numpy_savez.npz"][0], "heights");

    // np.savez_compressed (deflated) with two 2-D arrays: without --channel the one named height, as `surface
    // channels` says (an archive with none named height is refused, listing them: unit_formats_npz).
    let path = fixture("numpy_savez_compressed.npz");
    let p = path.to_str().unwrap();
    let o = |channel| LoadOptions { pixel_size_nm: Some(100.0), channel, ..Default::default() };
    let names: Vec<&str> = e["npz_2d_arrays"]["numpy_savez_compressed.npz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(names, ["amplitude", "height"]);
    let by_default = load_surface(p, &o(None)).unwrap();
    assert!(by_default.meta.notes.iter().any(|n| n.contains("array 'height' of the archive's 2 2-D arrays")));
    assert_eq!(by_default.heights_nm, load_surface(p, &o(Some(ChannelSel::Index(1)))).unwrap().heights_nm);
    // --channel 1 is "height": the same field as the .npy fixtures (dy from the options is dx here).
    let mut h = load_surface(p, &o(Some(ChannelSel::Index(1)))).unwrap();
    h.dy_nm = 80.0;
    check_against_expected(&h, 0.0);
    // --channel 0 is "amplitude": the second grating, stored as float32.
    let a = load_surface(p, &o(Some(ChannelSel::Index(0)))).unwrap();
    for q in e["channel1_probe"].as_array().unwrap() {
        let (r, c, v) = (q[0].as_u64().unwrap() as usize, q[1].as_u64().unwrap() as usize, q[2].as_f64().unwrap());
        assert!((a.get(r, c) - v).abs() <= 4e-6 * v.abs().max(1.0), "({r},{c}) {} vs {v}", a.get(r, c));
    }
    let err = load_surface(p, &o(Some(ChannelSel::Index(2)))).unwrap_err().to_string();
    assert!(err.contains("--channel 2") && err.contains("0: amplitude") && err.contains("1: height"), "{err}");
    // By name, as numpy saved it.
    let by_name = load_surface(p, &o(Some(ChannelSel::Name("height".into())))).unwrap();
    assert_eq!(by_name.heights_nm, load_surface(p, &o(Some(ChannelSel::Index(1)))).unwrap().heights_nm);
    let err = load_surface(p, &o(Some(ChannelSel::Name("phase".into())))).unwrap_err().to_string();
    assert!(err.contains("no such array") && err.contains("1: height"), "{err}");
}

/// Builds a zip archive holding `members` (name, bytes), stored.
fn zip_of(members: &[(&str, Vec<u8>)]) -> Vec<u8> {
    use std::io::Write;
    let mut zw = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    for (name, data) in members {
        zw.start_file(*name, zip::write::SimpleFileOptions::default()).unwrap();
        zw.write_all(data).unwrap();
    }
    zw.finish().unwrap().into_inner()
}

fn npy_header(descr: &str, shape: &str, version: u8) -> Vec<u8> {
    let header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    let mut b = b"\x93NUMPY".to_vec();
    b.extend_from_slice(&[version, 0]);
    let pre = if version == 1 { 10 } else { 12 };
    let text = format!("{header}{}\n", " ".repeat(64 - (pre + header.len() + 1) % 64));
    if version == 1 {
        b.extend_from_slice(&(text.len() as u16).to_le_bytes());
    } else {
        b.extend_from_slice(&(text.len() as u32).to_le_bytes());
    }
    b.extend_from_slice(text.as_bytes());
    b
}

#[test]
fn npz_sizes_are_not_trusted() {
    let o = LoadOptions { pixel_size_nm: Some(10.0), ..Default::default() };
    // A member whose header claims a 60000 × 60000 float64 array (28.8 GB) is refused before reading data.
    let z = zip_of(&[("big.npy", npy_header("<f8", "(60000, 60000)", 1))]);
    let e = read_bytes(&z, "big.npz", None, &o).unwrap_err().to_string();
    assert!(e.contains("too large") && e.contains("big"), "{e}");
    // A version-2 header that declares 4 GiB of header text: refused without sizing a buffer from it.
    let mut lying = npy_header("<f8", "(4, 4)", 2);
    lying[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
    let e = read_bytes(&zip_of(&[("h.npy", lying)]), "lying.npz", None, &o).unwrap_err().to_string();
    assert!(e.contains("header"), "{e}");
    // A header promising more data than the member holds: truncated, said so.
    let mut short = npy_header("<f8", "(4, 4)", 1);
    short.extend_from_slice(&[0u8; 40]);
    let e = read_bytes(&zip_of(&[("h.npy", short)]), "short.npz", None, &o).unwrap_err().to_string();
    assert!(e.contains("truncated"), "{e}");
    // No 2-D array at all: the message lists what is there.
    let z = zip_of(&[("x.npy", npy_header("<f8", "(3,)", 1).into_iter().chain([0u8; 24]).collect())]);
    let e = read_bytes(&z, "axes.npz", None, &o).unwrap_err().to_string();
    assert!(e.contains("no 2-D array") && e.contains("x (3 <f8)"), "{e}");
    // The numpy fixture cut anywhere: an error, never a panic.
    let good = std::fs::read(fixture("numpy_savez_compressed.npz")).unwrap();
    for n in [0, 4, 30, 100, good.len() / 2, good.len() - 22, good.len() - 1] {
        assert!(read_bytes(&good[..n], "cut.npz", None, &o).is_err(), "cut at {n}");
    }
}

fn gen(g: Generator, grid: &Grid) -> HeightField {
    g.generate(grid).unwrap()
}

#[test]
fn round_trips_through_every_writable_format() {
    let grid = Grid { size_x_nm: 6_400.0, size_y_nm: 4_000.0, pixel_nm: 40.0, angle_rad: 0.3, seed: 5 };
    let hf = gen(Generator::Elaphe { spacing_nm: 1100.0, finger_nm: 3000.0, rms_nm: 60.0 }, &grid);
    let dir = tempfile::tempdir().unwrap();
    let (lo, hi) = hf.min_max();
    for (ext, fmt, tol) in [
        ("gwy", Format::Gwy, 1e-9),
        ("npy", Format::Npy, 0.0),
        ("npz", Format::Npz, 0.0),
        ("txt", Format::Text, 0.0),
        ("png", Format::Png, (hi - lo) / 65535.0 / 2.0 + 1e-9),
    ] {
        let path = dir.path().join(format!("f.{ext}"));
        let (bytes, side) = write_bytes(&hf, fmt).unwrap();
        std::fs::write(&path, bytes).unwrap();
        if let Some(s) = side {
            std::fs::write(sidecar_path(&path), s).unwrap();
        }
        let back = load_surface(path.to_str().unwrap(), &LoadOptions::default()).unwrap();
        assert_eq!((back.rows, back.cols), (hf.rows, hf.cols), "{ext}");
        assert!((back.dx_nm - hf.dx_nm).abs() < 1e-9 && (back.dy_nm - hf.dy_nm).abs() < 1e-9, "{ext}");
        let worst = back.heights_nm.iter().zip(&hf.heights_nm).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(worst <= tol, "{ext}: worst height error {worst} nm > {tol}");
        assert!(back.meta.warnings.is_empty(), "{ext}: {:?}", back.meta.warnings);
    }
    assert!(write_bytes(&hf, Format::Tiff).is_err());
}

/// The analysis must recover a generated grating's period within 0.5 % and its orientation within 0.5°.
#[test]
fn periods_and_orientations_of_generated_gratings() {
    let cases = [
        (Generator::Sine { period_nm: 1100.0, depth_nm: 100.0 }, 0.0),
        (Generator::Sine { period_nm: 1234.5, depth_nm: 80.0 }, 17.0),
        (Generator::Sine { period_nm: 800.0, depth_nm: 50.0 }, 101.3),
        (Generator::Blazed { period_nm: 2500.0, depth_nm: 262.76 }, 0.0),
        (Generator::Blazed { period_nm: 2500.0, depth_nm: 262.76 }, 33.3),
        (Generator::Blazed { period_nm: 1700.0, depth_nm: 150.0 }, 135.0),
        (Generator::Blazed { period_nm: 2500.0, depth_nm: 262.76 }, 90.0),
    ];
    for (g, deg) in cases {
        let grid =
            Grid { size_x_nm: 24_000.0, size_y_nm: 20_000.0, pixel_nm: 40.0, angle_rad: f64::to_radians(deg), seed: 1 };
        let hf = gen(g.clone(), &grid);
        let pk = find_peaks(&hf, &PeakOptions::default());
        let p = &pk[0];
        let period = match g {
            Generator::Sine { period_nm, .. } | Generator::Blazed { period_nm, .. } => period_nm,
            _ => unreachable!(),
        };
        let dang = (p.orientation_deg - deg.rem_euclid(180.0)).abs();
        let dang = dang.min(180.0 - dang);
        assert!((p.period_nm / period - 1.0).abs() < 0.005, "{g:?} at {deg}°: period {}", p.period_nm);
        assert!(dang < 0.5, "{g:?} at {deg}°: orientation {}", p.orientation_deg);
    }
}

/// A grating along x turned by a thousandth of a degree either way reads 0.00°, not 180.00° (the fold into
/// [0°, 180°) left 179.999° for a vector a hair below the x axis: one file said 0.00°, another 180.00°).
#[test]
fn a_grating_along_x_reads_zero_degrees_from_either_side() {
    for deg in [-0.001, 0.001] {
        let grid =
            Grid { size_x_nm: 24_000.0, size_y_nm: 20_000.0, pixel_nm: 40.0, angle_rad: f64::to_radians(deg), seed: 1 };
        let hf = gen(Generator::Sine { period_nm: 1100.0, depth_nm: 100.0 }, &grid);
        let p = &find_peaks(&hf, &PeakOptions::default())[0];
        assert!(p.orientation_deg < 0.005, "turned by {deg}°: orientation {}", p.orientation_deg);
    }
}

#[test]
fn snake_and_cd_periods_match_their_construction() {
    let grid = Grid { size_x_nm: 30_000.0, size_y_nm: 30_000.0, pixel_nm: 50.0, angle_rad: 0.0, seed: 2 };
    // Elaphe: rows 1100 nm apart along y → 90°.
    let e = &find_peaks(
        &gen(Generator::Elaphe { spacing_nm: 1100.0, finger_nm: 4000.0, rms_nm: 60.0 }, &grid),
        &PeakOptions::default(),
    )[0];
    assert!((e.period_nm / 1100.0 - 1.0).abs() < 0.02 && (e.orientation_deg - 90.0).abs() < 1.0, "{e:?}");
    // CD: tracks 1600 nm apart along y.
    let cd = Generator::Cd { pitch_nm: 1600.0, bit_nm: 231.0, pit_width_nm: 500.0, depth_nm: 110.0 };
    let c = &find_peaks(&gen(cd, &grid), &PeakOptions::default())[0];
    assert!((c.period_nm / 1600.0 - 1.0).abs() < 0.005 && (c.orientation_deg - 90.0).abs() < 0.5, "{c:?}");
    // Xenopeltis: a period within ±10 % of 1500 nm along the fingers (near 0°) among the peaks, and one
    // across them within ±15 % of 550 nm (near 90°); grains differ on purpose.
    let x = find_peaks(
        &gen(
            Generator::Xenopeltis { along_nm: 1500.0, across_nm: 550.0, depth_nm: 120.0 },
            &Grid { size_x_nm: 65_000.0, size_y_nm: 65_000.0, pixel_nm: 65.0, ..grid },
        ),
        &PeakOptions { max_peaks: 8, ..PeakOptions::default() },
    );
    let near = |deg: f64, p: &iridis_surface::Peak| {
        let d = (p.orientation_deg - deg).abs();
        d.min(180.0 - d) < 25.0
    };
    assert!(x.iter().any(|p| near(0.0, p) && (p.period_nm / 1500.0 - 1.0).abs() < 0.10), "{x:?}");
    assert!(x.iter().any(|p| near(90.0, p) && (p.period_nm / 550.0 - 1.0).abs() < 0.15), "{x:?}");
}

#[test]
fn gaussian_surface_has_its_correlation_length() {
    // Correlation exp(−r²/ℓ²): at lag ℓ it is 1/e of the variance. Averaged along x over the whole field.
    let grid = Grid { size_x_nm: 40_000.0, size_y_nm: 40_000.0, pixel_nm: 50.0, angle_rad: 0.0, seed: 11 };
    let hf = gen(Generator::Gaussian { rms_nm: 20.0, corr_nm: 500.0 }, &grid);
    let lag = 10; // 500 nm
    let (mut s, mut n) = (0.0, 0.0);
    for r in 0..hf.rows {
        for c in 0..hf.cols {
            s += hf.get(r, c) * hf.get(r, (c + lag) % hf.cols);
            n += 1.0;
        }
    }
    let rho = s / n / (20.0 * 20.0);
    assert!((rho - (-1f64).exp()).abs() < 0.05, "correlation at ℓ: {rho}");
}

#[test]
fn levelling_then_analysis_of_a_tilted_scan() {
    let p = fixture("numpy_f64.npy");
    let hf = load_surface(p.to_str().unwrap(), &LoadOptions::default()).unwrap();
    let l = prep::level_plane(&hf);
    assert!(l.mean().abs() < 1e-9);
    // The tilt 0.01·y is gone; what is left is the 25 nm sine minus its own least-squares slope along x
    // (8 whole periods on 64 samples still correlate with x), computed here by hand for one row.
    let xs: Vec<f64> = (0..64).map(|c| c as f64 * 100.0).collect();
    let ss: Vec<f64> = xs.iter().map(|x| 25.0 * (std::f64::consts::TAU * x / 800.0).sin()).collect();
    let (xm, sm) = (xs.iter().sum::<f64>() / 64.0, ss.iter().sum::<f64>() / 64.0);
    let b = xs.iter().zip(&ss).map(|(x, s)| (x - xm) * (s - sm)).sum::<f64>()
        / xs.iter().map(|x| (x - xm) * (x - xm)).sum::<f64>();
    let res: Vec<f64> = xs.iter().zip(&ss).map(|(x, s)| s - sm - b * (x - xm)).collect();
    let rms = (res.iter().map(|r| r * r).sum::<f64>() / 64.0).sqrt();
    assert!((l.rms() - rms).abs() < 1e-9, "rms {} vs {rms}", l.rms());
    for c in 0..64 {
        assert!((l.get(10, c) - res[c]).abs() < 1e-9);
    }
}

#[test]
fn bad_input_is_refused_with_reasons() {
    let o = LoadOptions::default();
    let good = std::fs::read(fixture("gwyfile_two_channels.gwy")).unwrap();
    for n in [0usize, 5, 40, good.len() / 3, good.len() - 3] {
        assert!(read_bytes(&good[..n], "t.gwy", None, &o).is_err(), "truncated gwy {n}");
    }
    let npy = std::fs::read(fixture("numpy_f64.npy")).unwrap();
    let e = read_bytes(&npy[..npy.len() - 100], "t.npy", None, &LoadOptions { pixel_size_nm: Some(1.0), ..o.clone() })
        .unwrap_err()
        .to_string();
    assert!(e.contains("truncated"), "{e}");
    // Pixel sizes.
    for p in [0.0, -5.0, f64::NAN, f64::INFINITY] {
        assert!(HeightField::new(2, 2, p, 1.0, vec![0.0; 4]).is_err());
        let e = read_bytes(&npy, "t.npy", None, &LoadOptions { pixel_size_nm: Some(p), ..o.clone() }).unwrap_err();
        assert!(e.to_string().contains("positive"), "{e}");
    }
    // Non-finite heights, 1×N, length mismatch.
    assert!(HeightField::new(2, 2, 1.0, 1.0, vec![0.0, f64::NAN, 0.0, 0.0])
        .unwrap_err()
        .to_string()
        .contains("row 0, column 1"));
    assert!(HeightField::new(1, 5, 1.0, 1.0, vec![0.0; 5]).unwrap_err().to_string().contains("2×2"));
    assert!(HeightField::new(2, 3, 1.0, 1.0, vec![0.0; 5]).is_err());
    // A 1×N numpy array.
    let mut one_row = Vec::new();
    {
        use npyz::WriterBuilder;
        let mut w = npyz::WriteOptions::new().default_dtype().shape(&[1, 6]).writer(&mut one_row).begin_nd().unwrap();
        w.extend([1.0f64, 2.0, 3.0, 4.0, 5.0, 6.0]).unwrap();
        w.finish().unwrap();
    }
    let e = read_bytes(&one_row, "row.npy", None, &LoadOptions { pixel_size_nm: Some(1.0), ..o.clone() }).unwrap_err();
    assert!(e.to_string().contains("2-D"), "{e}");
    // Absurd sizes refused before allocating: a .gwy header claiming 2³¹ × 2³¹ and a .npy claiming 10⁶ × 10⁶.
    let mut gwy = good.clone();
    let pos = gwy.windows(5).position(|w| w == b"xres\0").unwrap() + 6;
    gwy[pos..pos + 4].copy_from_slice(&i32::MAX.to_le_bytes());
    let e = read_bytes(&gwy, "big.gwy", None, &o).unwrap_err().to_string();
    assert!(e.contains("too large"), "{e}");
    let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (1000000, 1000000), }";
    let mut big = b"\x93NUMPY\x01\x00".to_vec();
    let pad = 64 - (10 + header.len() + 1) % 64;
    let text = format!("{header}{}\n", " ".repeat(pad));
    big.extend_from_slice(&(text.len() as u16).to_le_bytes());
    big.extend_from_slice(text.as_bytes());
    let e = read_bytes(&big, "big.npy", None, &LoadOptions { pixel_size_nm: Some(1.0), ..o.clone() }).unwrap_err();
    assert!(e.to_string().contains("too large"), "{e}");
}

#[test]
fn colour_images_become_luminance_with_a_warning() {
    use image::{ImageBuffer, Rgb};
    let img = ImageBuffer::from_fn(8, 6, |x, y| Rgb([(x * 30) as u8, (y * 40) as u8, 200u8]));
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png).unwrap();
    let o = LoadOptions { pixel_size_nm: Some(50.0), max_height_nm: Some(255.0), ..Default::default() };
    let hf = read_bytes(bytes.get_ref(), "c.png", None, &o).unwrap();
    assert!(hf.meta.warnings.iter().any(|w| w.contains("luma")), "{:?}", hf.meta.warnings);
    // Rec. 709 luma of (60, 80, 200) with white = 255 nm is the luma value itself in nm.
    let expect = 0.2126 * 60.0 + 0.7152 * 80.0 + 0.0722 * 200.0;
    assert!((hf.get(2, 2) - expect).abs() < 1e-3, "{} vs {expect}", hf.get(2, 2));
    // An 8-bit grey TIFF: relative heights, black 0, white = --max-height.
    let grey = ImageBuffer::from_fn(5, 4, |x, _| image::Luma([(x * 50) as u8]));
    let mut t = std::io::Cursor::new(Vec::new());
    grey.write_to(&mut t, image::ImageFormat::Tiff).unwrap();
    let hf = read_bytes(t.get_ref(), "g.tif", None, &o).unwrap();
    assert_eq!(hf.meta.format, "tiff");
    assert!((hf.get(1, 4) - 200.0).abs() < 1e-9 && hf.meta.warnings.is_empty());
}

#[test]
fn physics_warnings_carry_numbers() {
    let hf = HeightField::new(100, 100, 120.0, 120.0, vec![0.0; 10_000]).unwrap();
    let w = hf.physics_warnings(65_000.0);
    assert!(w.iter().any(|m| m.contains("120.0 nm") && m.contains("95")), "{w:?}");
    assert_eq!(w.len(), 1, "the patch size is a note, not a warning: {w:?}");
    // λ/L at 550 nm over 12 µm: asin(0.0458) = 2.63°.
    let n = hf.coherence_note(65_000.0).unwrap();
    assert!(n.contains("12.0 × 12.0 µm") && n.contains("65.0 µm") && n.contains("2.6°"), "{n}");
    assert!(n.chars().count() < 400, "two sentences, not a paragraph: {} characters", n.chars().count());
    let fine = HeightField::new(1000, 1000, 65.0, 65.0, vec![0.0; 1_000_000]).unwrap();
    assert!(fine.physics_warnings(65_000.0).is_empty() && fine.coherence_note(65_000.0).is_none());
}
