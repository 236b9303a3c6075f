//! `iridis surface` end to end: generate → file → info finds the generated period; bad input exits
//! non-zero with a message and leaves no file behind.

use crate::common::{assert_fails, command as iridis, succeeds as ok, words};

#[test]
fn generate_then_info_recovers_the_period() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["gwy", "npy", "npz", "png", "txt"] {
        let out = dir.path().join(format!("g.{ext}"));
        let st = iridis()
            .args(["surface", "generate", "blazed", "--period", "1300nm", "--angle", "30deg", "--size", "16um"])
            .args(["--pixel", "40nm", "-o"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(st.status.success(), "{}", String::from_utf8_lossy(&st.stderr));
        let info = iridis().args(["surface", "info", "--json"]).arg(&out).output().unwrap();
        assert!(info.status.success(), "{ext}: {}", String::from_utf8_lossy(&info.stderr));
        let v: serde_json::Value = serde_json::from_slice(&info.stdout).unwrap();
        assert_eq!(v["rows"], 400);
        let p = &v["peaks"][0];
        assert!((p["period_nm"].as_f64().unwrap() / 1300.0 - 1.0).abs() < 0.005, "{ext}: {p}");
        assert!((p["orientation_deg"].as_f64().unwrap() - 30.0).abs() < 0.5, "{ext}: {p}");
        // The 16 µm patch is smaller than the 65 µm coherence area: the user is told once, in a note with its
        // practical consequence (λ/L = 550 nm / 16 µm: asin 0.0344 = 1.97°), not in a warning paragraph.
        let notes = v["notes"].to_string();
        assert!(notes.contains("coherence area") && notes.contains("λ/L = 2.0°"), "{notes}");
        assert!(
            !String::from_utf8_lossy(&info.stderr).contains("coherence"),
            "{}",
            String::from_utf8_lossy(&info.stderr)
        );
        // The period carries its uncertainty: refined off the grid, 10⁻³ of a DFT step along its direction,
        // d²·10⁻³/L = 1300² × 10⁻³ / 16 000 nm (the 16 µm square's extent along any direction).
        assert_eq!(p["read_off"], "refined", "{p}");
        let u = p["period_uncertainty_nm"].as_f64().unwrap();
        let d = p["period_nm"].as_f64().unwrap();
        assert!((u - d * d * 1e-3 / 16_000.0).abs() < 1e-9, "{ext}: {p}");
    }
    // Two cycles across the patch are too few to read a period from: no period is listed (rounding noise at a
    // share of 1e-32 was, "376 nm at 100°", and the test bench and report took it), and a note says why.
    let v = info_json(&["builtin:sine?size=4um&pixel=100nm&depth=100nm&period=2um"]);
    assert_eq!(v["peaks"], serde_json::json!([]));
    assert!(v["notes"].to_string().contains("100 % of the height variance lies in structure longer"), "{}", v["notes"]);
}

#[test]
fn bad_input_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.gwy");
    std::fs::write(&bad, b"GWYP\x00broken").unwrap();
    let o = iridis().args(["surface", "info"]).arg(&bad).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("Gwyddion"));
    let out = dir.path().join("never.gwy");
    let o = iridis().args(["surface", "convert"]).arg(&bad).arg(&out).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(!out.exists());
    let o = iridis().args(["surface", "generate", "sine", "--period", "1100", "-o"]).arg(&out).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no unit"));
    assert!(!out.exists());
    // A seed for a grating, which has no randomness, would change nothing: refused from every front.
    let npz = dir.path().join("never.npz");
    for args in [
        &["surface", "generate", "sine", "--seed", "3", "-o", out.to_str().unwrap()][..],
        &["surface", "info", "builtin:blazed", "--seed", "3"],
        &["precompute", "builtin:sine?seed=3", "-o", npz.to_str().unwrap()],
    ] {
        let o = iridis().args(args).output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.code() == Some(2) && stderr.contains("seed 3 would be ignored"), "{args:?}: {stderr}");
        assert!(stderr.contains("a seed shapes cd, gaussian, elaphe, xenopeltis"), "{stderr}");
    }
    assert!(!out.exists() && !npz.exists());
    // Leftover temporary files would start with ".iridis-".
    assert!(std::fs::read_dir(dir.path()).unwrap().all(|e| !e
        .unwrap()
        .file_name()
        .to_string_lossy()
        .starts_with(".iridis-")));
}

fn fixture(name: &str) -> String {
    format!("{}/../surface/tests/fixtures/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn expected() -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(fixture("expected.json")).unwrap()).unwrap()
}

fn info_json(args: &[&str]) -> serde_json::Value {
    let mut a = vec!["surface", "info", "--json"];
    a.extend_from_slice(args);
    serde_json::from_slice(&ok(&a).stdout).unwrap()
}

fn load(path: &std::path::Path) -> iridis_surface::HeightField {
    iridis_surface::load_surface(path.to_str().unwrap(), &Default::default()).unwrap()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn info_json_has_the_documented_keys_and_the_numpy_values() {
    let e = expected();
    let v = info_json(&[&fixture("numpy_f64.npy")]);
    let keys: std::collections::BTreeSet<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    // The issue's keys, plus provenance (source, format, z unit, notes), mean and warnings.
    let documented =
        ["rows", "cols", "pixel_size_nm", "extent_nm", "height_min_nm", "height_max_nm", "rms_nm", "peaks"];
    let extra = [
        "source",
        "format",
        "mean_nm",
        "z_unit_in_file",
        "notes",
        "warnings",
        "roughness",
        "psdf_radial",
        "acf_radial",
        "inputs",
        "channel",
        "peaks_asked",
    ];
    assert_eq!(keys, documented.iter().chain(&extra).copied().collect(), "{v}");
    for p in v["peaks"].as_array().unwrap() {
        let pk: std::collections::BTreeSet<&str> = p.as_object().unwrap().keys().map(String::as_str).collect();
        assert_eq!(
            pk,
            ["orientation_deg", "period_nm", "period_uncertainty_nm", "power", "read_off"].into_iter().collect(),
            "{p}"
        );
    }
    // Values against numpy's (tools/gen_surface_fixtures.py).
    assert_eq!((v["rows"].as_u64(), v["cols"].as_u64()), (Some(48), Some(64)));
    assert_eq!(v["pixel_size_nm"], serde_json::json!([100.0, 80.0]));
    assert_eq!(v["extent_nm"], serde_json::json!([6400.0, 3840.0]));
    for k in ["height_min_nm", "height_max_nm", "rms_nm"] {
        assert!(close(v[k].as_f64().unwrap(), e[k].as_f64().unwrap(), 1e-9), "{k}: {} vs {}", v[k], e[k]);
    }
    let p0 = &v["peaks"][0];
    assert!(
        close(p0["period_nm"].as_f64().unwrap(), 800.0, 4.0) && p0["orientation_deg"].as_f64().unwrap() < 0.5,
        "{p0}"
    );
    assert_eq!(v["format"], "npy");
}

#[test]
fn info_image_writes_a_png() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("relief.png");
    ok(&["surface", "info", "builtin:sine?size=4um&pixel=50nm", "--image", png.to_str().unwrap()]);
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let img = image::load_from_memory(&bytes).unwrap();
    assert_eq!(img.width(), 900);
    assert!(img.height() >= 300);
}

#[test]
fn convert_crop_resample_tile_pad_level() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::path::PathBuf::from(fixture("numpy_f64.npy"));
    let orig = load(&src);
    let out = |n: &str| dir.path().join(n);
    let s = src.to_str().unwrap();

    ok(&["surface", "convert", s, out("crop.npy").to_str().unwrap(), "--crop", "4,8,20,30"]);
    let c = load(&out("crop.npy"));
    assert_eq!((c.rows, c.cols, c.dx_nm, c.dy_nm), (20, 30, 100.0, 80.0));
    for (r, col) in [(0, 0), (7, 11), (19, 29)] {
        assert_eq!(c.get(r, col), orig.get(r + 4, col + 8));
    }

    ok(&["surface", "convert", s, out("tile.gwy").to_str().unwrap(), "--tile", "2x3"]);
    let t = load(&out("tile.gwy"));
    assert_eq!((t.rows, t.cols), (96, 192));
    for (r, col) in [(0, 0), (5, 9), (47, 63)] {
        for (dr, dc) in [(0, 0), (48, 0), (0, 128), (48, 64)] {
            assert!(close(t.get(r + dr, col + dc), orig.get(r, col), 1e-9));
        }
    }

    ok(&["surface", "convert", s, out("pad.txt").to_str().unwrap(), "--pad", "60x80"]);
    let p = load(&out("pad.txt"));
    assert_eq!((p.rows, p.cols), (60, 80));
    assert!(close(p.get(0, 0), orig.mean(), 1e-9) && close(p.get(59, 79), orig.mean(), 1e-9));
    assert!(close(p.get(6, 8), orig.get(0, 0), 1e-9) && close(p.get(53, 71), orig.get(47, 63), 1e-9));

    // Resampling to 200 nm keeps the extent (6400 × 3840 nm) and the 800 nm period along x.
    ok(&["surface", "convert", s, out("res.npy").to_str().unwrap(), "--resample", "200nm"]);
    let r = load(&out("res.npy"));
    assert_eq!((r.rows, r.cols), (19, 32));
    assert!(close(r.dx_nm * 32.0, 6400.0, 1e-6) && close(r.dy_nm * 19.0, 3840.0, 1e-6));
    let v = info_json(&[out("res.npy").to_str().unwrap()]);
    assert!(close(v["peaks"][0]["period_nm"].as_f64().unwrap(), 800.0, 8.0), "{}", v["peaks"][0]);

    // Plane levelling removes the fixture's tilt of 0.01 nm per nm along y: mean 0, and no row-to-row trend.
    ok(&["surface", "convert", s, out("lev.npy").to_str().unwrap(), "--level", "plane"]);
    let l = load(&out("lev.npy"));
    assert!(l.mean().abs() < 1e-9);
    let row_mean = |h: &iridis_surface::HeightField, r: usize| h.row(r).iter().sum::<f64>() / h.cols as f64;
    assert!(close(row_mean(&orig, 0) - row_mean(&orig, 47), 0.01 * 47.0 * 80.0, 1e-6));
    assert!(close(row_mean(&l, 0), row_mean(&l, 47), 1e-6), "{} {}", row_mean(&l, 0), row_mean(&l, 47));

    // Bad step values: clear refusals, no file.
    for (opt, val, needle) in
        [("--crop", "1,2,3", "ROW,COL,ROWS,COLS"), ("--tile", "3", "3x3"), ("--level", "tilt", "unknown levelling")]
    {
        let o = iridis().args(["surface", "convert", s, out("bad.npy").to_str().unwrap(), opt, val]).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{opt}");
        assert!(String::from_utf8_lossy(&o.stderr).contains(needle), "{opt}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(!out("bad.npy").exists());
    }
}

#[test]
fn png_and_tiff_at_8_and_16_bit_with_pixel_size_and_max_height() {
    use image::{ImageBuffer, ImageFormat, Luma};
    let dir = tempfile::tempdir().unwrap();
    // A ramp along x: column c holds c·step grey levels; white stands for 300 nm, black for 0.
    let img8 = ImageBuffer::from_fn(16, 10, |x, _| Luma([(x * 17) as u8]));
    let img16 = ImageBuffer::from_fn(16, 10, |x, _| Luma([(x * 4369) as u16]));
    for (name, fmt, full) in [
        ("g8.png", ImageFormat::Png, 255.0),
        ("g16.png", ImageFormat::Png, 65535.0),
        ("g8.tif", ImageFormat::Tiff, 255.0),
        ("g16.tif", ImageFormat::Tiff, 65535.0),
    ] {
        let path = dir.path().join(name);
        if full == 255.0 {
            img8.save_with_format(&path, fmt).unwrap();
        } else {
            img16.save_with_format(&path, fmt).unwrap();
        }
        let p = path.to_str().unwrap();
        // Without --pixel-size: refused, saying what to give.
        let o = iridis().args(["surface", "info", p]).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{name}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("--pixel-size"), "{name}");
        let v = info_json(&[p, "--pixel-size", "50nm", "--max-height", "300nm"]);
        assert_eq!((v["rows"].as_u64(), v["cols"].as_u64()), (Some(10), Some(16)), "{name}");
        assert_eq!(v["pixel_size_nm"], serde_json::json!([50.0, 50.0]), "{name}");
        assert_eq!(v["height_min_nm"].as_f64(), Some(0.0), "{name}");
        assert!(close(v["height_max_nm"].as_f64().unwrap(), 300.0, 1e-9), "{name}: {}", v["height_max_nm"]);
        // Column 5: 85/255 or 21845/65535 of 300 nm = 100 nm, read back exactly through a .npy.
        let npy = dir.path().join(format!("{name}.npy"));
        ok(&["surface", "convert", p, npy.to_str().unwrap(), "--pixel-size", "50nm", "--max-height", "300nm"]);
        let h = load(&npy);
        let grey = if full == 255.0 { 85.0 } else { 21845.0 };
        let want = grey / full * 300.0; // both a third of full scale
        assert!(close(h.get(3, 5), want, 1e-9), "{name}: {} vs {want}", h.get(3, 5));
    }
}

#[test]
fn bump_lattices_and_blazed_refusal() {
    let dir = tempfile::tempdir().unwrap();
    for kind in ["rect-bumps", "tri-bumps"] {
        let out = dir.path().join(format!("{kind}.npy"));
        let o = ok(&[
            "surface",
            "generate",
            kind,
            "--period",
            "1000nm",
            "--depth",
            "80nm",
            "--fill",
            "0.5",
            "--size",
            "20um",
            "--pixel",
            "25nm",
            "-o",
            out.to_str().unwrap(),
            "--json",
        ]);
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        // Peak-to-valley is the depth; a pyramid's apex may fall between samples, at most half a pixel
        // (12.5 nm) from the nearest one on each axis, which lowers it by depth · 12.5/250 (half-width 250 nm).
        let pv = v["height_max_nm"].as_f64().unwrap() - v["height_min_nm"].as_f64().unwrap();
        let lowest = if kind == "rect-bumps" { 80.0 } else { 80.0 * (1.0 - 12.5 / 250.0) };
        assert!(pv <= 80.0 + 1e-9 && pv >= lowest - 1e-9, "{kind}: peak-to-valley {pv}");
        // A square lattice: the 1000 nm period along x (0°) and along y (90°) are the two strongest peaks.
        let peaks = v["peaks"].as_array().unwrap();
        for deg in [0.0, 90.0] {
            assert!(
                peaks[..2].iter().any(|p| close(p["period_nm"].as_f64().unwrap(), 1000.0, 5.0)
                    && close(p["orientation_deg"].as_f64().unwrap(), deg, 0.5)),
                "{kind}: no 1000 nm peak at {deg}°: {peaks:?}"
            );
        }
        // Boxes of fill 0.5 cover a quarter of the area at full height, pyramids on the same footprint
        // hold a third of the boxes' volume: mean heights depth/4 and depth/12 above the floor.
        let mean_above_floor = load(&out).mean() - v["height_min_nm"].as_f64().unwrap();
        let want = if kind == "rect-bumps" { 80.0 / 4.0 } else { 80.0 / 12.0 };
        assert!(close(mean_above_floor, want, 0.02 * want), "{kind}: mean above floor {mean_above_floor}, want {want}");
    }
    let out = dir.path().join("never.npy");
    let o = iridis()
        .args(["surface", "generate", "blazed", "--blaze", "6deg", "--depth", "200nm", "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("either blaze=ANGLE or depth=LENGTH") && !err.contains("panicked"), "{err}");
    assert!(!out.exists());
}

#[test]
fn z_unit_round_trip_through_the_sidecar() {
    let dir = tempfile::tempdir().unwrap();
    // Heights stored in micrometres, as the sidecar says.
    let src = dir.path().join("um.npy");
    let values: Vec<f64> = (0..24).map(|k| 0.001 * (k as f64 - 10.0) * 3.5).collect();
    {
        use npyz::WriterBuilder;
        let mut f = std::fs::File::create(&src).unwrap();
        let mut w = npyz::WriteOptions::new().default_dtype().shape(&[4, 6]).writer(&mut f).begin_nd().unwrap();
        w.extend(values.iter().copied()).unwrap();
        w.finish().unwrap();
    }
    std::fs::write(dir.path().join("um.npy.json"), r#"{"pixel_size_nm": 40, "height_unit": "um"}"#).unwrap();
    let v = info_json(&[src.to_str().unwrap()]);
    assert_eq!(v["z_unit_in_file"], "um");
    assert!(
        close(v["height_min_nm"].as_f64().unwrap(), -35.0, 1e-9)
            && close(v["height_max_nm"].as_f64().unwrap(), 45.5, 1e-9)
    );
    // Converted: the heights are written in nm and the new sidecar says so; reading it back gives the same nm.
    for ext in ["npy", "npz", "png", "gwy", "txt"] {
        let out = dir.path().join(format!("nm.{ext}"));
        ok(&["surface", "convert", src.to_str().unwrap(), out.to_str().unwrap()]);
        if matches!(ext, "npy" | "npz") {
            let side: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(dir.path().join(format!("nm.{ext}.json"))).unwrap())
                    .unwrap();
            assert_eq!(side["height_unit"], "nm", "{ext}");
            assert_eq!(side["pixel_size_nm"], 40.0, "{ext}");
        }
        let back = load(&out);
        let tol = if ext == "png" { 80.5 / 65535.0 / 2.0 + 1e-9 } else { 1e-9 };
        for (k, &um) in values.iter().enumerate() {
            assert!(
                close(back.heights_nm[k], um * 1000.0, tol),
                "{ext} [{k}]: {} vs {}",
                back.heights_nm[k],
                um * 1000.0
            );
        }
        assert!(close(back.dx_nm, 40.0, 1e-9), "{ext}");
    }
}

fn samples(name: &str) -> Option<String> {
    let p = std::env::var_os("IRIDIS_AFM_SAMPLES")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/afm-samples"))
        .join(name);
    if p.exists() {
        Some(p.to_str().unwrap().to_string())
    } else {
        eprintln!("SKIPPED: {} absent; run tools/fetch_afm_samples.sh", p.display());
        None
    }
}

fn fails(args: &[&str]) -> String {
    let o = iridis().args(args).output().unwrap();
    assert_eq!(o.status.code(), Some(2), "{args:?} should fail: {}", String::from_utf8_lossy(&o.stdout));
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A flag that contradicts what an instrument file states is not applied silently (issue 32: `--pixel-size
/// 50nm` made a 0.506 µm scan 51 µm wide; `--height-unit um` was ignored without a word): the file's value
/// wins and a warning names both, or `--override-units` applies the flag and names the file's value.
#[test]
fn an_instrument_files_own_units_win_over_flags_unless_overridden() {
    let sxm = fixture("nanonis_synthetic.sxm");
    let plain = info_json(&[&sxm]);
    let v = info_json(&[&sxm, "--pixel-size", "50nm", "--height-unit", "um"]);
    assert_eq!(v["pixel_size_nm"], plain["pixel_size_nm"], "{v}");
    assert_eq!(v["height_max_nm"], plain["height_max_nm"]);
    let w = v["warnings"].to_string();
    assert!(w.contains("--pixel-size 50 nm ignored: the file gives 10.00 × 10.00 nm per pixel"), "{w}");
    assert!(w.contains("--override-units"), "{w}");
    assert!(w.contains("--height-unit um ignored: the file gives this channel's heights in m"), "{w}");
    let o = info_json(&[&sxm, "--pixel-size", "50nm", "--height-unit", "um", "--override-units"]);
    assert!(close(o["pixel_size_nm"][0].as_f64().unwrap(), 50.0, 1e-12), "{o}");
    // Stored in m, read as µm: a millionth of the heights.
    let ratio = o["height_max_nm"].as_f64().unwrap() / plain["height_max_nm"].as_f64().unwrap();
    assert!(close(ratio, 1e-6, 1e-9), "{ratio}");
    assert!(o["warnings"].to_string().contains("replaces the file's own 10.00 × 10.00 nm"), "{o}");
    // A channel that is not a height is read with --as-height (and a height unit where its own is not a length).
    let e = fails(&["surface", "info", &sxm, "--channel", "Current", "--as-height"]);
    assert!(e.contains("give --height-unit"), "{e}");
    let f = info_json(&[&sxm, "--channel", "Current", "--as-height", "--height-unit", "nm"]);
    assert!(f["warnings"].to_string().contains("--as-height"), "{f}");
}

#[test]
fn channels_are_listed_and_picked_by_name_or_index() {
    let sxm = fixture("nanonis_synthetic.sxm");
    let out = String::from_utf8(ok(&["surface", "channels", &sxm]).stdout).unwrap();
    for needle in ["4 channels", "Z", "Current", "backward", "40×24", "(not a height)"] {
        assert!(out.contains(needle), "'{needle}' missing in:\n{out}");
    }
    let v: serde_json::Value = serde_json::from_slice(&ok(&["surface", "channels", &sxm, "--json"]).stdout).unwrap();
    assert_eq!(v["format"], "sxm");
    assert_eq!(v["channels"][1]["name"], "Z");
    assert_eq!(v["channels"][1]["direction"], "backward");
    assert_eq!(v["channels"][2]["z_unit"], "A");
    // By name and by index: the same image.
    let a = info_json(&[&sxm, "--channel", "z_backward"]);
    let b = info_json(&[&sxm, "--channel", "1"]);
    assert_eq!(a["height_min_nm"], b["height_min_nm"]);
    for k in 0..2 {
        assert!(close(a["pixel_size_nm"][k].as_f64().unwrap(), 10.0, 1e-9), "{a}");
    }
    // An unknown channel and a channel that is not a height: exit 2 and the list.
    let e = fails(&["surface", "info", &sxm, "--channel", "Friction"]);
    assert!(e.contains("no channel named 'Friction'") && e.contains("2: Current (A, forward)"), "{e}");
    let e = fails(&["surface", "info", &sxm, "--channel", "Current"]);
    assert!(e.contains("records the current") && e.contains("0: Z_forward, 1: Z_backward"), "{e}");
    // The channel taken, why, and how to pick another, in the text and in --json.
    let v = info_json(&[&sxm]);
    assert_eq!((v["channel"]["index"].as_u64(), v["channel"]["of"].as_u64()), (Some(0), Some(4)), "{v}");
    assert!(v["channel"]["reason"].as_str().unwrap().starts_with("the default"), "{v}");
    assert_eq!(v["channel"]["heights"], serde_json::json!(["0: Z_forward", "1: Z_backward"]));
    let text = String::from_utf8(ok(&["surface", "info", &sxm]).stdout).unwrap();
    assert!(text.contains("channel 0 'Z' (forward) of 4, the default") && text.contains("--channel NAME"), "{text}");
    // Every model command says it too (on stderr, as a note).
    let e = String::from_utf8(
        ok(&["brdf", "eval", &sxm, "--light", "0deg", "--view", "10deg", "--coherence", "0.1um"]).stderr,
    )
    .unwrap();
    assert!(e.contains("note: ") && e.contains("channel 0 'Z' (forward) of 4, the default"), "{e}");
    // brdf-map takes --channel too, and works on the instrument file.
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("m.png");
    ok(&[
        "brdf-map",
        &sxm,
        "--channel",
        "Z_forward",
        "--method",
        "reference",
        "--size",
        "16",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(png.exists());
}

#[test]
fn height_unit_and_metres_warning() {
    let dir = tempfile::tempdir().unwrap();
    let npy = dir.path().join("m.npy");
    // Heights in metres (a 50 nm sine): taken as nm the relief would be sub-picometre.
    let hf = iridis_surface::load_surface("builtin:sine?size=4um&pixel=50nm&depth=50nm", &Default::default()).unwrap();
    let metres: Vec<f64> = hf.heights_nm.iter().map(|h| h * 1e-9).collect();
    let m = iridis_surface::HeightField::new(hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, metres).unwrap();
    // The .npy alone, without the sidecar that would give its unit.
    let (bytes, _sidecar) = iridis_surface::formats::write_bytes(&m, iridis_surface::Format::Npy).unwrap();
    std::fs::write(&npy, bytes).unwrap();
    let p = npy.to_str().unwrap();
    let o = ok(&["surface", "info", p, "--pixel-size", "50nm"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("look like metres"), "{}", String::from_utf8_lossy(&o.stderr));
    let v = info_json(&[p, "--pixel-size", "50nm", "--height-unit", "m"]);
    assert!(close(v["height_max_nm"].as_f64().unwrap(), 25.0, 0.01), "{v}");
    assert!(v["warnings"].as_array().unwrap().iter().all(|w| !w.as_str().unwrap().contains("metres")), "{v}");
    let e = fails(&["surface", "info", p, "--pixel-size", "50nm", "--height-unit", "kg"]);
    assert!(e.contains("not a length unit"), "{e}");
}

#[test]
fn psdf_and_acf_images_and_roughness_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let (psd, acf_png) = (dir.path().join("psdf.png"), dir.path().join("acf.png"));
    let v = info_json(&[
        "builtin:sine?size=8um&pixel=50nm&period=800nm&depth=20nm",
        "--psdf",
        psd.to_str().unwrap(),
        "--acf",
        acf_png.to_str().unwrap(),
    ]);
    // A sine of amplitude 10 nm: Sq = 10/√2 nm (the plane fit takes < 1 %). Its radial ACF is
    // (A²/2) J0(2π r / period), which falls to 1/e at r = 1.75199 · 800 nm / 2π = 223.07 nm (scipy).
    let ro = &v["roughness"];
    assert!(close(ro["sq_nm"].as_f64().unwrap(), 10.0 / 2f64.sqrt(), 0.01 * 7.07), "{v}");
    assert!(close(ro["correlation_length_nm"].as_f64().unwrap(), 223.07, 0.03 * 223.07), "{v}");
    // The radial PSDF peaks at the grating's frequency 1/800 nm (bin 10 of 1/8000 nm steps); the radial ACF starts
    // at Sq² = 50 nm² and crosses zero where J0 does, r = 2.40483 · 800 nm / 2π = 306.19 nm.
    let psdf = &v["psdf_radial"];
    let step = psdf["frequency_step_per_nm"].as_f64().unwrap();
    assert!(close(step, 1.0 / 8000.0, 1e-12), "{step}");
    let vals: Vec<f64> = psdf["values_nm4"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    let peak = (0..vals.len()).max_by(|&a, &b| vals[a].total_cmp(&vals[b])).unwrap();
    assert_eq!(peak, 10, "radial PSDF peak at bin {peak}");
    let acf = &v["acf_radial"];
    let lag = acf["lag_step_nm"].as_f64().unwrap();
    let a: Vec<f64> = acf["values_nm2"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert!(close(a[0], 50.0, 0.01 * 50.0), "ACF(0) {}", a[0]);
    let zero = (1..a.len()).find(|&i| a[i] <= 0.0).unwrap();
    let r0 = lag * ((zero - 1) as f64 + a[zero - 1] / (a[zero - 1] - a[zero]));
    assert!(close(r0, 306.19, 0.03 * 306.19), "first zero of the radial ACF at {r0} nm");
    for p in [&psd, &acf_png] {
        assert_eq!(&std::fs::read(p).unwrap()[..8], b"\x89PNG\r\n\x1a\n");
    }
}

#[test]
fn real_instrument_files_through_the_cli() {
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(fixture("afm_reference.json")).unwrap()).unwrap();
    for (key, file, channel) in [
        ("spm", "sample_0.spm", "Height"),
        ("ibw", "sample_0.ibw", "HeightTracee"),
        ("jpk", "sample_0.jpk", "height_trace"),
        ("stp", "sample_0.stp", "0"),
        ("gsf", "sample_0.gsf", "0"),
    ] {
        let Some(path) = samples(file) else { return };
        let v = info_json(&[&path, "--channel", channel]);
        let r = &reference[key];
        assert_eq!(v["rows"], r["rows"], "{file}");
        let lo = r["min_nm"].as_f64().unwrap();
        assert!((v["height_min_nm"].as_f64().unwrap() - lo).abs() <= 1e-6 * lo.abs().max(1.0), "{file}: {v}");
        let px = r["pixel_nm"].as_f64().unwrap();
        assert!((v["pixel_size_nm"][0].as_f64().unwrap() - px).abs() <= 1e-6 * px, "{file}");
    }
}

/// A tilted scan (128 nm across) puts a false streak into a BRDF map; files are plane-levelled by default,
/// so the tilted and the flat grating give the same map, and `--level none` shows the difference.
#[test]
fn files_are_plane_levelled_by_default_before_the_model() {
    use iridis_surface::{formats, Format, HeightField};
    let dir = tempfile::tempdir().unwrap();
    let flat = iridis_surface::load_surface(
        "builtin:sine?size=6400nm&pixel=50nm&period=800nm&depth=60nm",
        &Default::default(),
    )
    .unwrap();
    let (rows, cols) = (flat.rows, flat.cols);
    let tilted: Vec<f64> =
        flat.heights_nm.iter().enumerate().map(|(i, h)| h + 128.0 * (i % cols) as f64 / (cols - 1) as f64).collect();
    let t = HeightField::new(rows, cols, flat.dx_nm, flat.dy_nm, tilted).unwrap();
    let write = |hf: &HeightField, name: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, formats::write_bytes(hf, Format::Gwy).unwrap().0).unwrap();
        p.to_str().unwrap().to_string()
    };
    let (f, tl) = (write(&flat, "flat.gwy"), write(&t, "tilted.gwy"));
    // Linear XYZ of the map (--raw), compared as numbers.
    let map = |input: &str, extra: &[&str], name: &str| {
        let (png, raw) = (dir.path().join(format!("{name}.png")), dir.path().join(format!("{name}.npy")));
        // A coherence that fits the 6.4 µm patch (the default 65 µm leaves a patch this small dark).
        let mut args = vec!["brdf-map", input, "--method", "reference", "--size", "24", "--coherence", "2um"];
        args.extend_from_slice(&["-o", png.to_str().unwrap()]);
        args.extend_from_slice(&["--raw", raw.to_str().unwrap()]);
        args.extend_from_slice(extra);
        let o = ok(&args);
        let xyz: Vec<f64> = npyz::NpyFile::new(&std::fs::read(&raw).unwrap()[..]).unwrap().into_vec().unwrap();
        (xyz, String::from_utf8_lossy(&o.stderr).into_owned())
    };
    let (a, msg) = map(&f, &[], "flat");
    assert!(msg.contains("levelling: plane (the default for files"), "{msg}");
    let (b, _) = map(&tl, &[], "tilted");
    let (c, msg) = map(&tl, &["--level", "none"], "tilted_raw");
    assert!(msg.contains("levelling: none (as asked"), "{msg}");
    // Directions outside the hemisphere are NaN in all three maps alike.
    let peak = a.iter().filter(|v| v.is_finite()).fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = |x: &[f64], y: &[f64]| {
        x.iter().zip(y).fold(0.0f64, |m, (p, q)| match (p.is_finite(), q.is_finite()) {
            (true, true) => m.max((p - q).abs()),
            (false, false) => m,
            _ => f64::INFINITY,
        }) / peak
    };
    assert!(worst(&a, &b) < 1e-6, "levelled tilted map differs from the flat one by {}", worst(&a, &b));
    assert!(worst(&a, &c) > 0.01, "the tilt should change the unlevelled map: {}", worst(&a, &c));
}

/// `iridis report` on an instrument file: index.html and report.json with the figures and the commands.
#[test]
fn report_on_an_instrument_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rep");
    let sxm = fixture("nanonis_synthetic.sxm");
    // Every step announced in the log (threshold 0): the labels whole, not cut at 18 characters ("Levelled
    // relief, r: 1/4").
    let run = iridis()
        .args(["report", &sxm, "--channel", "Z_forward", "--size", "16", "-o", out.to_str().unwrap()])
        .env("IRIDIS_PROGRESS_AFTER_MS", "0")
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let log = String::from_utf8_lossy(&run.stderr);
    assert!(log.contains("Levelled relief, roughness, periods, PSDF and ACF"), "{log}");
    assert!(!log.contains("Levelled relief, r:"), "{log}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    // The synthetic scan is 5 nm · sin(2π x / 10 px) + 0.3 nm · y over 40 × 24 px of 10 nm; numpy's
    // least-squares plane leaves Sq = 3.4721342 nm.
    assert_eq!((r["info"]["cols"].as_u64(), r["info"]["rows"].as_u64()), (Some(40), Some(24)));
    let sq = r["info"]["roughness"]["sq_nm"].as_f64().unwrap();
    assert!(close(sq, 3.472_134_206_7, 1e-4), "{sq}");
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    for f in ["relief.png", "psdf.png", "acf.png"] {
        assert!(out.join(f).exists(), "{f}");
        assert!(html.contains(f), "{f} not in the page");
    }
    assert!(html.contains("iridis grating") && html.contains("--channel Z_forward"), "commands missing");
    // Its 100 nm period cannot diffract visible light (a first order needs d > λ/2 ≥ 190 nm): said in words,
    // with the mirror colour instead of a map.
    assert_eq!(r["diffracts_visible_light"], false, "{r}");
    let verdict = r["verdict"].as_str().unwrap();
    assert!(verdict.contains("diffracts no visible light") && verdict.contains("100 nm"), "{verdict}");
    assert!(!out.join("brdf_0deg.png").exists() && !html.contains("brdf_0deg"), "no map of nothing");
    // The map's and the animal's options go unused, and the verdict says so.
    assert!(verdict.contains("(--size, --visual unused)") && !out.join("vision.png").exists(), "{verdict}");
    // No --level was given: the model steps get none, and say "the default for files", not "as asked".
    for c in
        r["commands"].as_array().unwrap().iter().filter(|c| !c["command"].as_str().unwrap().contains("surface info"))
    {
        assert!(!c["command"].as_str().unwrap().contains("--level"), "{c}");
    }
    assert!(!log.contains("as asked (--level)"), "{log}");
    // 0.4 µm is far below the 65 µm coherence area: the surface's note says what that means, once.
    assert!(r["info"]["notes"].to_string().contains("coherence area"), "{r}");
    assert!(!r["warnings"].to_string().contains("coherence area"), "{r}");
}

/// The issue's small scan: a 1000 nm sine on a 6.4 µm patch (6.4 periods). The coherence is the light's 65 µm,
/// the patch the periodic model's unit cell, so the bench reads a DFT grid value (6400/6 = 1066.7 nm) and says
/// it is known to ± half a DFT step, d²/(2L) — within which it agrees with surface info. A window inside the
/// patch (`--coherence 3.2um`) reads between the grid values, to the window's resolution d²σ_f.
#[test]
fn report_states_the_quantisation_of_a_small_patch() {
    let dir = tempfile::tempdir().unwrap();
    let g = dir.path().join("s.gwy");
    let gs = g.to_str().unwrap();
    ok(&["surface", "generate", "sine", "--size", "6400nm", "--pixel", "50nm", "--period", "1000nm", "-o", gs]);
    let report = |extra: &[&str], name: &str| -> serde_json::Value {
        let out = dir.path().join(name);
        let mut args = vec!["report", gs, "--size", "16", "-o", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        ok(&args);
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap()
    };
    let r = report(&[], "light");
    assert_eq!(r["diffracts_visible_light"], true);
    assert!(r["verdict"].as_str().unwrap().starts_with("The scan diffracts visible light"), "{}", r["verdict"]);
    let html = std::fs::read_to_string(dir.path().join("light").join("index.html")).unwrap();
    // One title, the file's name without its folders; the maps with axes, each once under its step.
    let title = html.lines().find(|l| l.starts_with("<h1>")).unwrap();
    assert_eq!(title, "<h1>iridis report: s.gwy</h1>");
    assert_eq!(html.matches("<h1>").count(), 1);
    for f in ["brdf_0deg_plot.png", "brdf_45deg_plot.png", "testbench.png"] {
        assert_eq!(html.matches(&format!("src=\"{f}\"")).count(), 1, "{f}");
    }
    assert_eq!(html.matches("<h2>Levelled relief").count(), 1, "one heading for the relief, PSDF and ACF");
    let tb = &r["testbench"];
    let d = tb["periodicity_nm"]["mean"].as_f64().unwrap();
    let q = tb["periodicity_nm"]["uncertainty"].as_f64().unwrap();
    assert!(close(d, 6400.0 / 6.0, 0.05), "the DFT grid value L/6: {d}");
    assert!(close(q, d * d / 12_800.0, 1e-6), "uncertainty {q} is d²/(2L)");
    assert!(close(tb["coherence_nm"].as_f64().unwrap(), 65_000.0, 1e-9), "the light's coherence");
    assert_eq!(tb["periodicity_nm"]["quantised"], true);
    let info = r["info"]["peaks"][0]["period_nm"].as_f64().unwrap();
    assert!(close(info, 1000.0, 0.5), "surface info {info}");
    assert!((d - info).abs() <= q && (d - 1000.0).abs() <= q, "test bench {d} ± {q} vs surface info {info}");
    let r = report(&["--coherence", "3.2um"], "window");
    let tb = &r["testbench"]["periodicity_nm"];
    let (d, q) = (tb["mean"].as_f64().unwrap(), tb["uncertainty"].as_f64().unwrap());
    assert_eq!(tb["quantised"], false);
    // σ_f = 1/(2π σ_s), σ_s = 800 nm.
    assert!(close(q, d * d / (std::f64::consts::TAU * 800.0), 1e-6), "the window's resolution: {q}");
    assert!((d - 1000.0).abs() < 10.0 && (d - info).abs() <= q, "{d} ± {q}");
}

/// A 64² grey PNG of a sine along x, 16 pixels a period (4 periods), constant along y; its grey levels per column.
fn grey_sine_png(dir: &std::path::Path) -> (std::path::PathBuf, Vec<u8>) {
    let png = dir.join("grey.png");
    let grey: Vec<u8> =
        (0..64).map(|x| (127.5 + 127.5 * (std::f64::consts::TAU * x as f64 / 16.0).sin()) as u8).collect();
    image::GrayImage::from_fn(64, 64, |x, _| image::Luma([grey[x as usize]])).save(&png).unwrap();
    (png, grey)
}

/// A grey PNG holds relative heights: the report asks for --max-height, takes it (it had no such option, and its
/// error told the user to give one), passes it to every step's command line, and the heights are grey / 255 ×
/// max-height: the rms is that of the grey levels scaled, the period 16 pixels of 50 nm.
#[test]
fn report_of_a_grey_image_takes_its_max_height() {
    let dir = tempfile::tempdir().unwrap();
    let (png, grey) = grey_sine_png(dir.path());
    let (p, out) = (png.to_str().unwrap(), dir.path().join("report"));
    let mut args = vec!["report", p, "-o", out.to_str().unwrap(), "--size", "16", "--no-testbench"];
    args.extend(["--pixel-size", "50nm", "--level", "mean"]);
    let refused = iridis().args(&args).output().unwrap();
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("give --max-height"));
    args.extend(["--max-height", "100nm"]);
    ok(&args);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let mean = grey.iter().map(|&g| g as f64).sum::<f64>() / 64.0;
    let rms = (grey.iter().map(|&g| (g as f64 - mean).powi(2)).sum::<f64>() / 64.0).sqrt() * 100.0 / 255.0;
    assert!(close(r["info"]["rms_nm"].as_f64().unwrap(), rms, 1e-9), "{} against {rms}", r["info"]["rms_nm"]);
    assert!(close(r["info"]["peaks"][0]["period_nm"].as_f64().unwrap(), 800.0, 1.0), "{}", r["info"]["peaks"][0]);
    for c in r["commands"].as_array().unwrap() {
        assert!(c["command"].as_str().unwrap().contains("--max-height 100nm"), "{c}");
    }
}

/// A reader's warning (a colour PNG's heights from its luma) is said by every step that loads the scan; the
/// report lists it once, with the file's name, and the terminal shows it once.
#[test]
fn report_says_a_readers_warning_once() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("colour.png");
    image::RgbImage::from_fn(64, 64, |x, _| {
        let g = (127.5 + 127.5 * (std::f64::consts::TAU * x as f64 / 16.0).sin()) as u8;
        image::Rgb([g, g / 2, 255 - g])
    })
    .save(&png)
    .unwrap();
    let (p, out) = (png.to_str().unwrap(), dir.path().join("report"));
    let args = ["report", p, "-o", out.to_str().unwrap(), "--size", "16", "--no-testbench", "--pixel-size", "50nm"];
    let run = iridis().args(args).args(["--max-height", "100nm"]).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let log = String::from_utf8_lossy(&run.stderr);
    assert_eq!(log.matches("Rec. 709 luma").count(), 1, "{log}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let luma: Vec<&str> =
        r["warnings"].as_array().unwrap().iter().filter_map(|w| w.as_str()).filter(|w| w.contains("luma")).collect();
    assert!(luma.len() == 1 && luma[0].starts_with(&format!("{p}: colour image")), "{luma:?}");
}

/// The accuracy bench reads a scan as every command does (it took built-in names and files that state their units
/// only): the grey PNG with --max-height gives the numbers of the same heights as .npy (`surface convert`), and
/// its default coherence (a quarter of the patch) keeps the window inside the patch, where the periodic and the
/// finite ground truths agree (ΔE00 of their difference below 1e-6).
#[test]
fn accuracy_bench_reads_a_grey_image_with_its_max_height() {
    let dir = tempfile::tempdir().unwrap();
    let (png, _) = grey_sine_png(dir.path());
    let npy = dir.path().join("grey.npy");
    let (png, npy) = (png.to_str().unwrap(), npy.to_str().unwrap());
    ok(&["surface", "convert", png, npy, "--pixel-size", "50nm", "--max-height", "100nm"]);
    let bench = |surface: &str, read: &[&str]| -> serde_json::Value {
        let mut args = vec!["bench", "diffraction-accuracy", "--surface", surface, "--pixel-size", "50nm"];
        args.extend(read);
        args.extend(["--level", "mean", "--map-size", "8", "--uv-resolution", "31", "--json"]);
        let mut v: serde_json::Value = serde_json::from_slice(&ok(&args).stdout).unwrap();
        for row in v["results"].as_array_mut().unwrap() {
            row.as_object_mut().unwrap().remove("surface");
        }
        v["results"].take()
    };
    let from_png = bench(png, &["--max-height", "100nm"]);
    assert_eq!(from_png, bench(npy, &["--height-unit", "nm"]));
    let rows = from_png.as_array().unwrap();
    assert_eq!(rows.len(), 15, "{from_png}");
    for r in rows.iter().filter(|r| r["method"] == "periodic-extension") {
        assert!(r["mean"].as_f64().unwrap() < 1e-6 && r["p95"].as_f64().unwrap() < 1e-6, "{r}");
    }
    // Maps have brdf-map's sizes: a 1² map (the normal alone) printed ΔE 0.0000 at 1000 RU, two clipped whites.
    crate::common::assert_fails(
        &["bench", "diffraction-accuracy", "--surface", npy, "--pixel-size", "50nm", "--map-size", "1"],
        &["--map-size 1 must be between 8 and 8192 pixels"],
    );
}

/// The report of an Elaphe-like scan (issue 28, 30): how far the scalar model is from the rigorous solver on
/// the scan's own averaged profile, with numbers (the scalar model is tens of percent off at these depths), and
/// how a blue tit sees the colours across directions; the test bench along the rows (90°), not along x.
#[test]
fn report_of_a_snake_scan_states_the_scalar_models_error_and_a_birds_view() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("elaphe");
    ok(&["report", "builtin:elaphe?size=10um&pixel=50nm&seed=3", "--size", "16", "-o", out.to_str().unwrap()]);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(r["diffracts_visible_light"], true);
    let e = &r["scalar_model_error"];
    let worst = e["worst_relative_error"]["unpolarized"].as_f64().unwrap();
    let period = e["unit_cell"]["period_x_nm"].as_f64().unwrap();
    assert!((period - 1100.0).abs() < 60.0, "the averaged cell's period {period}");
    assert!(worst > 0.1 && e["rigorous_converged"] == true, "{e}");
    assert!(e["delta_e00_diffracted"].as_f64().is_some(), "{e}");
    let sentence = r["scalar_model_sentence"].as_str().unwrap();
    assert!(sentence.contains(&format!("{:.1} %", 100.0 * worst)), "{sentence}");
    let v = &r["vision"]["vision"];
    assert_eq!(v["receptors"].as_array().unwrap().len(), 4, "a blue tit's four cones");
    assert!(r["vision_sentence"].as_str().unwrap().contains("JND"));
    assert!(out.join("vision.png").exists());
    let az = r["testbench"]["azimuth_deg"].as_f64().unwrap();
    assert!((az - 90.0).abs() < 1.0, "the bench along the rows: {az}");
}

/// A relief too deep for the Taylor expansion (a 4 µm-deep sine, |h|max 2 µm: 2k|h|max = 66 at 380 nm) printed
/// NaN efficiencies with exit 0: `grating` refuses it, naming the limit and the methods without it, and the
/// report keeps the relief's own figures, says what to run for its colours and draws no (black) mirror swatch.
#[test]
fn a_relief_too_deep_for_the_taylor_expansion_is_said_so() {
    let deep = "builtin:sine?size=4um&pixel=100nm&depth=4000nm&period=2um";
    let grating = ["grating", deep, "--light", "0deg", "--from", "400nm", "--to", "400nm"];
    crate::common::assert_fails(&grating, &["too deep for the Taylor expansion", "2k|h|max ≤ 26.8", "rigorous"]);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("deep");
    ok(&["report", deep, "--size", "16", "-o", out.to_str().unwrap()]);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(r["diffracts_visible_light"], serde_json::Value::Null);
    assert!(r["too_deep_for_scalar_model"].as_str().unwrap().contains("|h|max ≤ 811 nm"), "{r}");
    assert!(r["verdict"].as_str().unwrap().contains("--method rigorous --unit-cell auto"), "{}", r["verdict"]);
    assert_eq!(r["figures"], serde_json::json!(["relief.png", "psdf.png", "acf.png"]));
    assert_eq!(r["commands"].as_array().unwrap().len(), 1, "the relief's step only");
    assert!(!std::fs::read_to_string(out.join("index.html")).unwrap().contains("mirror colour"));
}

/// `iridis report` on every real instrument file (small maps), when the samples have been fetched.
#[test]
fn report_on_each_real_instrument_file() {
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(fixture("afm_reference.json")).unwrap()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for (key, file) in [
        ("spm", "sample_0.spm"),
        ("ibw", "sample_0.ibw"),
        ("jpk", "sample_0.jpk"),
        ("stp", "sample_0.stp"),
        ("gsf", "sample_0.gsf"),
        ("gwy", "sample_0.gwy"),
    ] {
        let Some(path) = samples(file) else { return };
        let out = dir.path().join(key);
        let mut args = vec!["report", &path, "--size", "16", "-o", out.to_str().unwrap()];
        if key == "gwy" {
            // The channel of the numpy reference (the default is the file's "Height", as AFMReader's).
            args.extend(["--channel", "ZSensor"]);
        }
        ok(&args);
        let r: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
        assert_eq!(r["info"]["rows"], reference[key]["rows"], "{file}");
        // The report's heights are plane-levelled; the pixel size is the file's.
        let px = reference[key]["pixel_nm"].as_f64().unwrap();
        assert!((r["info"]["pixel_size_nm"][0].as_f64().unwrap() - px).abs() <= 1e-6 * px, "{file}");
        if key == "gwy" {
            // numpy's Sq of the plane-levelled scan (tools/gen_afm_fixtures.py).
            let sq = reference["gwy"]["roughness"]["sq_nm"].as_f64().unwrap();
            assert!((r["info"]["roughness"]["sq_nm"].as_f64().unwrap() - sq).abs() <= 1e-6 * sq, "{file}");
        }
        for f in ["index.html", "relief.png", "psdf.png"] {
            assert!(out.join(f).exists(), "{file}: {f}");
        }
        // 0.4–0.5 µm scans of molecules (periods 30–130 nm): nothing visible is diffracted. Said in words with
        // the mirror colour, never a saturated map (the report's maps were white disks), no test bench.
        assert_eq!(r["diffracts_visible_light"], false, "{file}");
        assert!(r["verdict"].as_str().unwrap().contains("diffracts no visible light"), "{file}: {}", r["verdict"]);
        // What the scan as a unit cell sends out of the mirror direction comes from its edges: under 1 %.
        for share in r["unit_cell"].as_array().unwrap().iter().map(|u| u["diffracted_share"].as_f64().unwrap()) {
            assert!(share < 1e-2, "{file}: diffracted share {share}");
        }
        assert!(!out.join("brdf_0deg.png").exists() && r["testbench"].is_null(), "{file}");
        // Sub-micrometre scans: the coherence note with its consequence, in the surface's notes.
        assert!(r["info"]["notes"].to_string().contains("coherence area"), "{file}");
    }
}

/// What a later step of the report would refuse is refused before that step's work: the maps' size and the
/// animal before any step, a coherence window narrower than the scan's pixels right after the first step has
/// read them. One `error:` line, the option's (a failed step adds a line naming the step). Nothing is written,
/// not even the folder.
#[test]
fn report_refuses_what_its_steps_would_before_they_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r");
    let o = out.to_str().unwrap();
    let report = |option: &'static str, value: &'static str| {
        ["report", "builtin:sine?size=4um&pixel=100nm", "-o", o, option, value]
    };
    crate::common::assert_fails(&report("--size", "0"), &["--size 0 must be between 8 and 8192 pixels"]);
    crate::common::assert_fails(&report("--visual", "cat"), &["--visual", "unknown visual system 'cat'"]);
    // A scan that is not there: said as such, before any step (it was the first step's failure, its command
    // line and then the reason).
    crate::common::assert_fails(&["report", "no/such.gwy", "-o", o], &["cannot read no/such.gwy: no such file"]);
    let short = ["--coherence: a coherence length of 300 nm", "give at least 400 nm"];
    crate::common::assert_fails(&report("--coherence", "300nm"), &short);
    // The folder the run created is an output too: removed with the rest; one that existed stays, empty.
    assert!(!out.exists(), "a refused report left its folder");
    std::fs::create_dir(&out).unwrap();
    crate::common::assert_fails(&report("--coherence", "300nm"), &short);
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 0, "a refused report left files in the folder");
}

/// `surface convert` onto the file it reads (or its sidecar) is refused and leaves the scan as it was: the
/// rename over it replaced a two-channel .gwy with one channel, and a .npy's raw heights with levelled ones.
#[test]
fn convert_refuses_to_overwrite_its_input() {
    let dir = tempfile::tempdir().unwrap();
    let gwy = dir.path().join("scan.gwy");
    std::fs::copy(fixture("gwyfile_two_channels.gwy"), &gwy).unwrap();
    let before = std::fs::read(&gwy).unwrap();
    let g = gwy.to_str().unwrap();
    crate::common::assert_fails(&["surface", "convert", g, g], &["would overwrite the scan being read"]);
    // Another spelling of the same file.
    let dotted = dir.path().join(".").join("scan.gwy");
    crate::common::assert_fails(&["surface", "convert", g, dotted.to_str().unwrap()], &["would overwrite"]);
    assert_eq!(std::fs::read(&gwy).unwrap(), before);
    // A .npy and its own sidecar: the same.
    let npy = dir.path().join("h.npy");
    let said = ok(&["surface", "convert", g, npy.to_str().unwrap()]);
    // Sizes x before y, as channels, info and the report give them (it printed rows × cols beside dx × dy).
    let said = String::from_utf8_lossy(&said.stdout);
    assert!(said.contains("64 × 48 samples (x × y) at 100.0000 × 80.0000 nm/pixel (x × y)"), "{said}");
    let n = npy.to_str().unwrap();
    crate::common::assert_fails(&["surface", "convert", n, n, "--level", "plane"], &["would overwrite"]);
    // Another name is fine.
    ok(&["surface", "convert", n, dir.path().join("h2.npy").to_str().unwrap()]);
}

/// Units that give a field no microscope makes are said: a Gwyddion file in metres read with `--height-unit nm`
/// (the tool's own hint for a file without units) is a relief of 6e-8 nm, all-zero heights that a report called
/// "too shallow to diffract"; `--pixel-size 100mm` for 100 nm made a 6.4 m scan; and `--height-unit` replacing
/// a sidecar's unit is said as a file's own unit is.
#[test]
fn implausible_units_are_said() {
    let warned = |args: &[&str]| String::from_utf8_lossy(&ok(args).stderr).into_owned();
    let err = warned(&["surface", "info", &fixture("gwyfile_no_units.gwy"), "--height-unit", "nm"]);
    assert!(err.contains("the relief is below a picometre (largest |height| 6.260e-8 nm as read)"), "{err}");
    let err = warned(&["surface", "info", &fixture("numpy_f32_fortran.npy"), "--pixel-size", "100mm"]);
    assert!(err.contains("pixels of 100000 µm as read"), "{err}");
    let err = warned(&["surface", "info", &fixture("numpy_f32_fortran.npy"), "--pixel-size", "1e-30nm"]);
    assert!(err.contains("pixels of 1.000e-30 nm as read: finer than an atom's spacing"), "{err}");
    let err = warned(&["surface", "info", &fixture("numpy_f64.npy"), "--height-unit", "um"]);
    assert!(err.contains("--height-unit um replaces the sidecar's height unit 'nm'"), "{err}");
    // The right units say none of it.
    let err = warned(&["surface", "info", &fixture("numpy_f64.npy")]);
    assert!(!err.contains("picometre") && !err.contains("replaces") && !err.contains("pixels of"), "{err}");
}

/// A random surface's strongest peak holds about 1 % of the height variance: a note says it has no dominant
/// period (five "periods" were listed without a word), and the ± of the listed periods says what it is.
#[test]
fn a_random_surface_has_no_dominant_period() {
    let out = ok(&["surface", "info", "builtin:gaussian?size=20um&pixel=50nm"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("note         no dominant period: the strongest peak holds"), "{text}");
    assert!(text.contains("(± the peak's resolution on the spectrum, not an accuracy"), "{text}");
    // Nor is that peak a grating's unit cell: `grating --unit-cell auto` printed its orders as one's.
    assert_fails(
        &["grating", "builtin:gaussian?size=20um&pixel=50nm", "--unit-cell", "auto"],
        &[
            "has no dominant period to take as the unit cell: its strongest spectral peak",
            "the peaks of a random surface (a period holds at least 10 %, or 1.5 × the next)",
        ],
    );
    // Nor does `brdf eval` state the scalar model's error on it (it did, from that peak's averaged profile).
    let v = crate::common::json_of(&words(
        "brdf eval builtin:gaussian?size=20um&pixel=50nm --light 0deg --view 10deg --step 20nm --json",
    ));
    assert!(v["scalar_error"].is_null(), "{}", v["scalar_error"]);
    let out = ok(&["surface", "info", "builtin:elaphe?size=20um&pixel=50nm"]);
    assert!(!String::from_utf8_lossy(&out.stdout).contains("no dominant period"));
    // --peaks 0 looks for none: said so, not "none found" (a statement about the surface).
    let out = ok(&["surface", "info", "builtin:elaphe?size=20um&pixel=50nm", "--peaks", "0"]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("periods      not looked for (--peaks 0)"));
}

/// A .npy's heights in an assumed or given unit are a height channel to `surface channels`, as every command reads
/// them ("nm (assumed)" was not recognised as a length, and the listing said "(not a height)").
#[test]
fn channels_of_a_npy_list_a_height() {
    let out = ok(&["surface", "channels", &fixture("numpy_f32_fortran.npy"), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["channels"][0]["height"], true, "{v}");
    let out = ok(&["surface", "channels", &fixture("numpy_f32_fortran.npy")]);
    assert!(!String::from_utf8_lossy(&out.stdout).contains("not a height"));
}

/// The report's verdict rests on what its numbers can show (an audit's three cases):
/// - a 300 nm patch with no period holds too little of the surface to judge: its shares are given, no verdict
///   (it said "diffracts" from 1.2 % at 45° into the orders of its own extent);
/// - a 200 nm sine has no visible first order at the report's 0° and 45° (λ < d (1 + sin 45°) needs d > 223 nm
///   at 380 nm): the 10 % that plane levelling's tilt sends out of the mirror direction is said to be that, and
///   the reason is not "too shallow" (its relief is 200 nm deep);
/// - a spike's spectral peaks are no periods: "no dominant period", not "its periods (27, 24, … nm)".
#[test]
fn the_reports_verdict_rests_on_what_its_numbers_show() {
    let dir = tempfile::tempdir().unwrap();
    let report = |surface: &str, extra: &[&str], name: &str| -> serde_json::Value {
        let out = dir.path().join(name);
        let mut args = vec!["report", surface, "--no-testbench", "--size", "16", "-o", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        ok(&args);
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap()
    };
    let r = report("builtin:gaussian?size=300nm&pixel=100nm", &[], "small");
    assert_eq!(r["diffracts_visible_light"], serde_json::Value::Null, "{r}");
    let verdict = r["verdict"].as_str().unwrap();
    assert!(verdict.starts_with("The scan is too small to tell whether the surface diffracts"), "{verdict}");
    assert!(verdict.contains("at 300 × 300 nm (3 × 3 samples)"), "{verdict}");
    // Its coherence note gives its sides in nm (a 20 nm side read "0.0 µm").
    assert!(r["info"]["notes"].to_string().contains("patch 300 × 300 nm is smaller than"), "{r}");
    let r = report("builtin:sine?size=2um&pixel=10nm&period=200nm&depth=200nm", &["--level", "plane"], "sine200");
    assert_eq!(r["diffracts_visible_light"], false, "{r}");
    let verdict = r["verdict"].as_str().unwrap();
    assert!(verdict.contains("its longest period (200 nm) is too short for a visible first order"), "{verdict}");
    assert!(verdict.contains("= 223 nm at 380 nm") && verdict.contains("plane levelling"), "{verdict}");
    assert!(!verdict.contains("shallow"), "{verdict}");
    // The tilt is there: more than the 0.1 % a diffracting scan needs leaves the mirror direction.
    assert!(r["unit_cell"][0]["diffracted_share"].as_f64().unwrap() > 0.05, "{r}");
    // Its mirror colour is the scalar model's, which Maxwell's equations put far off on a relief as deep as its
    // period (Y 3.6 % against 0.3 %): measured although it does not diffract, and warned.
    assert!(r["scalar_model_error"]["total_relative_error"].as_f64().unwrap() > 1.0, "{r}");
    assert!(
        r["warnings"].to_string().contains("the scalar (Kirchhoff) model behind the mirror colour is off by"),
        "{r}"
    );
    let dir2 = tempfile::tempdir().unwrap();
    let spike = dir2.path().join("spike.gwy");
    let mut heights = vec![0.0f64; 64 * 64];
    heights[32 * 64 + 32] = 500.0;
    let hf = iridis_surface::HeightField::new(64, 64, 10.0, 10.0, heights).unwrap();
    std::fs::write(&spike, iridis_surface::formats::gwy::write(&hf)).unwrap();
    let r = report(spike.to_str().unwrap(), &[], "spike");
    let verdict = r["verdict"].as_str().unwrap();
    assert!(verdict.contains("diffracts no visible light: it has no dominant period"), "{verdict}");
}

/// The report's animal's view is measured against a flat mirror of the scan's size under the same window (whose
/// lobe widens with λ, so it changes colour with direction too), among directions that get at least 1 % of the
/// brightest one's light: a 1000 nm sine on a 4 µm patch exceeds the flat's, and is said to be the structure's.
#[test]
fn the_reports_animal_view_is_measured_against_the_windows_own() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rep");
    let sine = "builtin:sine?size=4um&pixel=50nm&period=1000nm&depth=100nm";
    ok(&["report", sine, "--no-testbench", "--size", "16", "-o", out.to_str().unwrap()]);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    // The flat mirror changes colour with direction too (its window's lobe widens with λ), but the direction of the
    // scan's largest change is one it leaves dark.
    assert!(r["vision"]["flat_mirror_delta_s_jnd"].as_f64().unwrap() > 1.0, "{r}");
    let sentence = r["vision_sentence"].as_str().unwrap();
    assert!(sentence.contains("at least 1 % of the brightest one's light"), "{sentence}");
    assert!(
        sentence
            .contains("a flat mirror of the scan's size under the same coherence window leaves that direction dark"),
        "{sentence}"
    );
    assert!(sentence.contains("so the iridescence is the structure's"), "{sentence}");
    // Under the light's 65 µm the orders of a 20 µm Xenopeltis-like scan fall between the 10° views: said, with no
    // verdict on the window (it said "0.0 JND … the window's own colours").
    let out2 = dir.path().join("xeno");
    ok(&["report", "builtin:xenopeltis", "--no-testbench", "--size", "16", "-o", out2.to_str().unwrap()]);
    let x: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out2.join("report.json")).unwrap()).unwrap();
    let sentence = x["vision_sentence"].as_str().unwrap();
    assert!(sentence.contains("no direction sampled") && !sentence.contains("window's own colours"), "{sentence}");
    // Each step's reflector, said in one place (JSON and under the verdict).
    let reflectors = &r["reflectors"];
    assert_eq!(
        (reflectors["unit_cell"].as_str(), reflectors["scalar_model_error"].as_str()),
        (Some("n=1.5"), Some("keratin"))
    );
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("Reflectors: the unit cell's orders and the mirror colour are computed over n = 1.5"));
}
