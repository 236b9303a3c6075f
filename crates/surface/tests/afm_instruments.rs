//! Real instrument files read as independent readers read them. The files (AFMReader 0.0.7's test
//! resources, GPL-free to fetch but not ours to commit) are fetched by `tools/fetch_afm_samples.sh` into
//! `$IRIDIS_AFM_SAMPLES` (default `target/afm-samples`); the reference numbers, made by
//! `tools/gen_afm_fixtures.py` with AFMReader / pySPM / igor2 / tifffile / gsffile, are committed in
//! `tests/fixtures/afm_reference.json`. Without the files these tests say so and pass without checking.

use std::path::PathBuf;

use iridis_surface::formats::channel::ChannelSel;
use iridis_surface::formats::{list_channels, read_bytes};
use iridis_surface::{HeightField, LoadOptions};
use serde_json::Value;

const REL: f64 = 1e-6;

fn samples_dir() -> PathBuf {
    std::env::var_os("IRIDIS_AFM_SAMPLES")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/afm-samples"))
}

fn reference() -> Value {
    let p = format!("{}/tests/fixtures/afm_reference.json", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

/// The file's bytes, or `None` (with a message) when the samples have not been fetched.
fn sample(name: &str) -> Option<Vec<u8>> {
    let p = samples_dir().join(name);
    match std::fs::read(&p) {
        Ok(b) => Some(b),
        Err(_) => {
            eprintln!(
                "SKIPPED: {} is absent; run tools/fetch_afm_samples.sh (pip, PyPI) to test the reader on real files",
                p.display()
            );
            None
        }
    }
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= REL * scale.max(b.abs())
}

fn load(bytes: &[u8], name: &str, channel: Option<&str>) -> HeightField {
    let o = LoadOptions { channel: channel.map(|c| c.parse::<ChannelSel>().unwrap()), ..Default::default() };
    read_bytes(bytes, name, None, &o).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Shape, pixel size, min/max/mean and the sampled values against the reference entry.
fn check(hf: &HeightField, r: &Value, what: &str) {
    assert_eq!((hf.rows as u64, hf.cols as u64), (r["rows"].as_u64().unwrap(), r["cols"].as_u64().unwrap()), "{what}");
    let px = r["pixel_nm"].as_f64().unwrap();
    assert!(close(hf.dx_nm, px, px) && close(hf.dy_nm, px, px), "{what}: pixel {} × {} vs {px}", hf.dx_nm, hf.dy_nm);
    let (lo, hi) = hf.min_max();
    let span = r["max_nm"].as_f64().unwrap() - r["min_nm"].as_f64().unwrap();
    for (k, v) in [("min_nm", lo), ("max_nm", hi), ("mean_nm", hf.mean())] {
        let want = r[k].as_f64().unwrap();
        assert!(close(v, want, span), "{what}: {k} {v} vs {want}");
    }
    for s in r["samples"].as_array().unwrap() {
        let (row, col, want) =
            (s[0].as_u64().unwrap() as usize, s[1].as_u64().unwrap() as usize, s[2].as_f64().unwrap());
        assert!(close(hf.get(row, col), want, span), "{what}: ({row}, {col}) {} vs {want}", hf.get(row, col));
    }
}

fn names(bytes: &[u8], name: &str, full: bool) -> Vec<String> {
    list_channels(bytes, name)
        .unwrap()
        .iter()
        .map(|c| match (full, c.alias.is_empty()) {
            (true, _) => c.full_name(),
            (false, true) => c.name.clone(),
            (false, false) => c.alias.clone(),
        })
        .collect()
}

/// `sample_0.KEY` (None where it is not fetched) read by channel name and checked against the reference:
/// heights, format and the channel list (names, or aliases where `full` is false); the file's bytes, its
/// reference and the channel.
fn read_as_reference(key: &str, channel: &str, format: &str, full: bool) -> Option<(Vec<u8>, Value, HeightField)> {
    let file = format!("sample_0.{key}");
    let b = sample(&file)?;
    let r = reference()[key].clone();
    let hf = load(&b, &file, Some(channel));
    check(&hf, &r, &format!("{key} {channel}"));
    assert_eq!(hf.meta.format, format);
    let want: Vec<String> = r["channels"].as_array().unwrap().iter().map(|v| v.as_str().unwrap().to_string()).collect();
    assert_eq!(names(&b, key, full), want);
    Some((b, r, hf))
}

#[test]
fn bruker_nanoscope_spm_as_afmreader_and_pyspm() {
    let Some((b, r, hf)) = read_as_reference("spm", "Height", "nanoscope", false) else { return };
    // By index: "Height" is the 8th image (index 7), and the default: AFMReader and TopoStats read "Height", not
    // the first height-like channel (Height Sensor, as before issue 32). The choice says why and how to change it.
    let by_index = load(&b, "sample_0.spm", Some("7"));
    assert_eq!(by_index.heights_nm, hf.heights_nm);
    let default = load(&b, "sample_0.spm", None);
    assert_eq!(default.heights_nm, hf.heights_nm, "default = the channel named Height");
    let c = default.meta.channel.as_ref().unwrap();
    assert_eq!((c.index, c.name.as_str(), c.of), (7, "Height", 8));
    let d = c.describe();
    assert!(d.contains("AFMReader") && d.contains("0: Height Sensor_retrace, 7: Height_trace"), "{d}");
    assert!(d.contains("--channel NAME"), "{d}");
    // Not a height: the message names the signal and the height channels.
    let e =
        read_bytes(&b, "s", None, &LoadOptions { channel: Some("DMTModulus".parse().unwrap()), ..Default::default() })
            .unwrap_err()
            .to_string();
    assert!(e.contains("records the modulus") && e.contains("7: Height_trace") && e.contains("--as-height"), "{e}");
    // The file's 0.494 nm pixels win over a contradicting --pixel-size 50nm (which made the 0.506 µm scan
    // 51 µm wide, silently), and its nm over --height-unit um; both are named in a warning. --override-units
    // gives the user's, saying what the file had.
    let flags = LoadOptions { pixel_size_nm: Some(50.0), height_unit: Some("um".into()), ..Default::default() };
    let kept = read_bytes(&b, "s", None, &flags).unwrap();
    assert!((kept.dx_nm - r["pixel_nm"].as_f64().unwrap()).abs() < 1e-9, "{}", kept.dx_nm);
    assert_eq!(kept.heights_nm, hf.heights_nm);
    let w = kept.meta.warnings.join("\n");
    assert!(w.contains("--pixel-size 50 nm ignored: the file gives 0.4940 × 0.4940 nm per pixel"), "{w}");
    assert!(w.contains("--height-unit um ignored: the file gives this channel's heights in nm"), "{w}");
    let forced = read_bytes(&b, "s", None, &LoadOptions { override_units: true, ..flags }).unwrap();
    assert_eq!(forced.dx_nm, 50.0);
    assert!((forced.heights_nm[0] - 1000.0 * hf.heights_nm[0]).abs() < 1e-9 * forced.heights_nm[0].abs());
    assert!(
        forced.meta.warnings.iter().any(|w| w.contains("replaces the file's own 0.4940")),
        "{:?}",
        forced.meta.warnings
    );
}

#[test]
fn asylum_ibw_as_afmreader_and_igor2() {
    let Some((b, _, hf)) = read_as_reference("ibw", "HeightTracee", "ibw", false) else { return };
    assert_eq!(load(&b, "sample_0.ibw", None).heights_nm, hf.heights_nm, "default = first height channel");
}

#[test]
fn jpk_as_afmreader_and_tifffile() {
    let Some((b, _, _)) = read_as_reference("jpk", "height_trace", "jpk", true) else { return };
    // The tapping amplitude is in metres but is not the topography: refused unless --as-height.
    let amp = |as_height| {
        read_bytes(
            &b,
            "s",
            None,
            &LoadOptions { channel: Some("amplitude".parse().unwrap()), as_height, ..Default::default() },
        )
    };
    let e = amp(false).unwrap_err().to_string();
    assert!(e.contains("records the amplitude") && e.contains("5: height_trace"), "{e}");
    assert!(amp(true).unwrap().meta.warnings.iter().any(|w| w.contains("--as-height")));
}

#[test]
fn gwyddion_gwy_as_afmreader() {
    let Some(b) = sample("sample_0.gwy") else { return };
    let hf = load(&b, "sample_0.gwy", Some("ZSensor"));
    check(&hf, &reference()["gwy"], "gwy ZSensor");
    // Channel 3, LogStiffness, has no unit: it was read as heights of 3.3e9–9.3e9 nm with only "assumed
    // metres"; its name says it is no height, so it is refused, naming the heights.
    let e = read_bytes(&b, "s", None, &LoadOptions { channel: Some(ChannelSel::Index(3)), ..Default::default() })
        .unwrap_err()
        .to_string();
    assert!(e.contains("'LogStiffness' (no unit) records the stiffness") && e.contains("0: ZSensor, 7: Height"), "{e}");
}

#[test]
fn wsxm_stp_and_top_as_afmreader_and_each_other() {
    let (Some(stp), Some(top)) = (sample("sample_0.stp"), sample("sample_0.top")) else { return };
    let r = reference();
    let s = load(&stp, "sample_0.stp", None);
    check(&s, &r["stp"], "stp");
    assert_eq!(s.meta.format, "wsxm");
    let t = load(&top, "sample_0.top", None);
    let rt = &r["top"];
    // The 16-bit twin reproduces WSxM's own double-precision export to half a code step.
    let half_step = rt["code_step_nm"].as_f64().unwrap() / 2.0;
    for smp in rt["stp_twin_samples"].as_array().unwrap() {
        let (row, col, v) =
            (smp[0].as_u64().unwrap() as usize, smp[1].as_u64().unwrap() as usize, smp[2].as_f64().unwrap());
        assert!((t.get(row, col) - v).abs() <= half_step, "top ({row}, {col}) {} vs stp {v}", t.get(row, col));
    }
    // AFMReader rescales the same codes to [0, int(Z amplitude)]; undo that and the values agree.
    let (lo, hi) = t.min_max();
    let k = rt["afmreader_z_amplitude_nm"].as_f64().unwrap() / (hi - lo);
    for smp in rt["samples"].as_array().unwrap() {
        let (row, col, v) =
            (smp[0].as_u64().unwrap() as usize, smp[1].as_u64().unwrap() as usize, smp[2].as_f64().unwrap());
        assert!(close((t.get(row, col) - lo) * k, v, 59.0), "top ({row}, {col})");
    }
    assert!(close(t.dx_nm, rt["pixel_nm"].as_f64().unwrap(), 1.0));
}

#[test]
fn gsf_written_by_gsffile() {
    let Some(b) = sample("sample_0.gsf") else { return };
    let hf = load(&b, "sample_0.gsf", None);
    check(&hf, &reference()["gsf"], "gsf");
    assert_eq!(hf.meta.format, "gsf");
}

#[test]
fn nanonis_sxm_as_pyspm() {
    // Synthetic (no real .sxm on PyPI; see tools/gen_afm_fixtures.py), committed: always runs.
    let b = std::fs::read(format!("{}/tests/fixtures/nanonis_synthetic.sxm", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let r = &reference()["sxm"];
    assert_eq!(names(&b, "sxm", true), ["Z_forward", "Z_backward", "Current_forward", "Current_backward"]);
    for dir in ["forward", "backward"] {
        let hf = load(&b, "nanonis_synthetic.sxm", Some(&format!("Z_{dir}")));
        let e = &r["channels"][format!("Z_{dir}")];
        let (rows, cols) = (hf.rows, hf.cols);
        assert_eq!((rows as u64, cols as u64), (e["rows"].as_u64().unwrap(), e["cols"].as_u64().unwrap()));
        assert!(close(hf.dx_nm, r["pixel_nm"].as_f64().unwrap(), 1.0));
        for s in e["stored_samples"].as_array().unwrap() {
            let (sr, sc, v) =
                (s[0].as_u64().unwrap() as usize, s[1].as_u64().unwrap() as usize, s[2].as_f64().unwrap());
            // Scan up: the first stored line is the bottom row; backward lines are stored right to left.
            let col = if dir == "backward" { cols - 1 - sc } else { sc };
            assert!(close(hf.get(rows - 1 - sr, col), v * 1e9, 10.0), "Z {dir} stored ({sr}, {sc})");
        }
    }
    let e =
        read_bytes(&b, "x.sxm", None, &LoadOptions { channel: Some("Current".parse().unwrap()), ..Default::default() })
            .unwrap_err()
            .to_string();
    assert!(e.contains("'Current_forward' (A) records the current") && e.contains("0: Z_forward"), "{e}");
}

use crate::common;

/// The synthetic files (always present): each format's orientation (row 0 on top) and scaling.
#[test]
fn synthetic_instrument_files_read_exactly() {
    use common::{code, COLS, ROWS};
    // (name, bytes, nm per code, offset nm, pixel nm)
    type Case = (&'static str, Vec<u8>, f64, f64, (f64, f64));
    let cases: [Case; 4] = [
        // (name, bytes, nm per code, offset nm, pixel nm)
        ("nanoscope", common::nanoscope(), 0.008, 0.0, (6.25, 6.25)),
        ("ibw", common::ibw(), 0.1, 0.0, (100.0, 100.0)),
        ("wsxm", common::wsxm_top(), 0.01, 0.0, (10.0, 10.0)),
        ("jpk", common::jpk(), 0.1, 2.0, (10.0, 10.0)),
    ];
    for (name, bytes, k, off, (dx, dy)) in cases {
        let hf = load(&bytes, name, None);
        assert_eq!((hf.rows, hf.cols), (ROWS, COLS), "{name}");
        assert_eq!(hf.meta.format, name);
        assert!(
            (hf.dx_nm - dx).abs() < 1e-9 && (hf.dy_nm - dy).abs() < 1e-9,
            "{name}: pixel {} × {}",
            hf.dx_nm,
            hf.dy_nm
        );
        for r in 0..ROWS {
            for c in 0..COLS {
                let want = f64::from(code(r, c)) * k + off;
                assert!(
                    (hf.get(r, c) - want).abs() < 1e-6 * want.abs().max(1.0),
                    "{name} ({r}, {c}) {} vs {want}",
                    hf.get(r, c)
                );
            }
        }
    }
    // The IBW's second layer is a phase (deg): by name, refused as a height with the list.
    let e = read_bytes(
        &common::ibw(),
        "x.ibw",
        None,
        &LoadOptions { channel: Some("phase".parse().unwrap()), ..Default::default() },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("'Phase' (deg) records the phase") && e.contains("0: HeightTrace_trace"), "{e}");
}

/// Roughness, ACF and correlation length of the real .gwy scan against numpy (tools/gen_afm_fixtures.py).
#[test]
fn roughness_of_the_real_gwy_scan_as_numpy() {
    let Some(b) = sample("sample_0.gwy") else { return };
    let r = &reference()["gwy"]["roughness"];
    let hf = iridis_surface::prep::level_plane(&load(&b, "sample_0.gwy", Some("ZSensor")));
    let got = iridis_surface::stats::roughness(&hf);
    for (k, v) in [
        ("sq_nm", got.sq_nm),
        ("sa_nm", got.sa_nm),
        ("skewness", got.skewness),
        ("excess_kurtosis", got.excess_kurtosis),
        ("sz_nm", got.sz_nm),
        ("correlation_length_nm", got.correlation_length_nm.unwrap()),
    ] {
        let want = r[k].as_f64().unwrap();
        assert!(close(v, want, want.abs()), "{k}: {v} vs numpy {want}");
    }
    let acf = iridis_surface::stats::acf(&hf);
    let (hr, hc) = (acf.rows / 2, acf.cols / 2);
    let g0 = r["acf_lags_px"][0][2].as_f64().unwrap();
    for l in r["acf_lags_px"].as_array().unwrap() {
        let (m, n, want) = (l[0].as_i64().unwrap(), l[1].as_i64().unwrap(), l[2].as_f64().unwrap());
        let v = acf.values[(hr as i64 + m) as usize * acf.cols + (hc as i64 + n) as usize];
        assert!(close(v, want, g0), "ACF ({m}, {n}): {v} vs numpy {want}");
    }
}
