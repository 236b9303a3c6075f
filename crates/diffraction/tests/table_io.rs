//! Lookup tables survive a round trip through `.npz`, and damaged or foreign files are refused clearly.

use std::io::Cursor;

use iridis_diffraction::table::{LookupTable, TableParams};
use iridis_diffraction::{Patch, SpectralSetup, TaylorTerms};

fn small_table() -> LookupTable {
    let h: Vec<f64> =
        (0..32 * 32).map(|k| 30.0 * ((k % 32) as f64 * 0.7).sin() + 10.0 * ((k / 32) as f64).cos()).collect();
    let patch = Patch::from_row_major(32, 32, 60.0, 60.0, &h).unwrap();
    let terms = TaylorTerms::compute(&patch, 6, 1000.0).unwrap();
    let spectral = SpectralSetup::new(iridis_color::Illuminant::D65, iridis_color::Observer::Cie1931, 20.0).unwrap();
    LookupTable::build(&terms, &spectral, TableParams { uv_resolution: 9, uv_power: 5.0 }, "test", &|_| {}).unwrap()
}

/// The table written as `.npz`, in memory.
fn npz_bytes(t: &LookupTable) -> Vec<u8> {
    let mut buf = Cursor::new(Vec::new());
    t.write_npz(&mut buf).unwrap();
    buf.into_inner()
}

/// The table written as `.npz` and read back as the file `name`.
fn reread(t: &LookupTable, name: &str) -> Result<LookupTable, iridis_diffraction::DiffractionError> {
    LookupTable::read_npz(Cursor::new(npz_bytes(t)), name)
}

/// `save` writes beside the destination and renames: the file is the in-memory `.npz` to the byte, readable by
/// others (not the temporary file's 0600), and nothing else is left in the folder; a folder that does not exist
/// is an error that leaves nothing behind.
#[test]
fn save_is_whole_and_leaves_no_temporary_file() {
    let t = small_table();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.npz");
    std::fs::write(&path, b"an older file").unwrap();
    t.save(&path).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), npz_bytes(&t));
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names, ["t.npz"]);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        assert_eq!(std::fs::metadata(&path).unwrap().permissions().mode() & 0o777, 0o644);
    }
    assert!(t.save(&dir.path().join("missing/t.npz")).is_err());
    assert!(!dir.path().join("missing").exists());
}

#[test]
fn round_trip_is_exact() {
    let t = small_table();
    let back = reread(&t, "mem").unwrap();
    assert_eq!(back.meta, t.meta);
    assert_eq!(back.data, t.data);
    assert_eq!(back.uv, t.uv);
    assert_eq!(back.wavelengths_nm, t.wavelengths_nm);
    assert_eq!(back.uv.len(), 9);
    assert!((back.uv[8] - 2.0).abs() < 1e-15 && (back.uv[0] + 2.0).abs() < 1e-15);
}

#[test]
fn damaged_and_foreign_files_are_refused() {
    let t = small_table();
    let bytes = npz_bytes(&t);

    let truncated = bytes[..bytes.len() / 2].to_vec();
    let e = LookupTable::read_npz(Cursor::new(truncated), "cut.npz").unwrap_err().to_string();
    assert!(e.contains("cut.npz"), "{e}");

    let e = LookupTable::read_npz(Cursor::new(b"not a zip at all".to_vec()), "x.npz").unwrap_err().to_string();
    assert!(e.contains("not an npz"), "{e}");

    let mut newer = t.clone();
    newer.meta.version = 99;
    let e = reread(&newer, "new.npz").unwrap_err().to_string();
    assert!(e.contains("version 99") && e.contains("precompute"), "{e}");

    let mut other = t.clone();
    other.meta.format = "something-else".into();
    assert!(reread(&other, "o.npz").unwrap_err().to_string().contains("something-else"));

    // An axis shorter than the metadata says, and a table holding NaN: both refused, not read into garbage.
    let mut short_axis = t.clone();
    short_axis.uv.pop();
    let e = reread(&short_axis, "s.npz").unwrap_err().to_string();
    assert!(e.contains("disagree"), "{e}");

    let mut poisoned = t.clone();
    poisoned.data[3] = f64::NAN;
    let e = reread(&poisoned, "n.npz").unwrap_err().to_string();
    assert!(e.contains("non-finite"), "{e}");

    // Finite in f64 but beyond f32 (the GPU's copy was NaN, said as "no light"), and lengths no table has.
    let mut huge = t.clone();
    huge.data[3] = 1e300;
    assert!(reread(&huge, "h.npz").unwrap_err().to_string().contains("beyond f32's range"));
    for forge in [
        |m: &mut iridis_diffraction::table::TableMeta| m.coherence_nm = -5.0,
        |m: &mut iridis_diffraction::table::TableMeta| m.dx_nm = 0.0,
        |m: &mut iridis_diffraction::table::TableMeta| m.wavelength_step_nm = 0.0,
        |m: &mut iridis_diffraction::table::TableMeta| m.wavelength_max_nm = 100.0,
        |m: &mut iridis_diffraction::table::TableMeta| m.max_abs_height_nm = 1e30,
    ] {
        let mut forged = t.clone();
        forge(&mut forged.meta);
        let e = reread(&forged, "f.npz").unwrap_err().to_string();
        assert!(e.contains("metadata out of range") && e.contains("not a table iridis wrote"), "{e}");
    }
}

/// Mutated table files (bit flips, truncation, extreme size fields, splices: `iridis_surface::fuzz::mutate`)
/// are refused or read, never a panic. Seeded, so deterministic; the long run is
/// `cargo run --release -p iridis-diffraction --example fuzz_table -- 1000000 7`.
#[test]
fn mutated_tables_never_panic() {
    use iridis_surface::{fuzz::mutate, rng::Rng};
    let t = small_table();
    let good = npz_bytes(&t);
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut rng = Rng::new(5);
    let (mut panics, mut refused) = (Vec::new(), 0);
    for i in 0..3000 {
        let data = mutate(&mut rng, &good, &good);
        match std::panic::catch_unwind(|| LookupTable::read_npz(Cursor::new(data), "fuzz.npz")) {
            Ok(r) => refused += usize::from(r.is_err()),
            Err(_) => panics.push(i),
        }
    }
    std::panic::set_hook(hook);
    assert!(panics.is_empty(), "panics at iterations {panics:?}");
    assert!(refused > 300, "only {refused} of 3000 mutated tables refused: the mutations miss the reader");
}

/// Patch::warnings: each problem once (one pixel warning even when both axes are too coarse), with its
/// numbers; nothing for a fine, large patch. A table carries the warnings of its patch through the file, and a
/// table written before the field existed still reads (no warnings).
#[test]
fn patch_warnings_once_each_and_carried_by_tables() {
    let coarse = Patch::from_row_major(40, 50, 120.0, 110.0, &vec![0.0; 2000]).unwrap();
    let w = coarse.warnings();
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("pixel size 120.0 nm") && w[0].contains("≤ 95 nm"), "{w:?}");
    // A patch smaller than the window is no warning but the periodic model's unit cell, said in the note.
    let fine = Patch::from_row_major(100, 100, 65.0, 65.0, &vec![0.0; 10_000]).unwrap();
    assert!(fine.warnings().is_empty());
    let c = fine.coherence(None);
    assert_eq!(c.nm, 65_000.0, "the light's coherence, never fitted to the patch");
    assert!(
        c.note().contains("coherence 65 µm (the paper's default") && c.note().contains("one unit cell"),
        "{}",
        c.note()
    );
    let c = fine.coherence(Some(6_000.0));
    assert!(c.note() == "coherence 6 µm (as given)", "{}", c.note());

    // small_table(): 32 × 60 nm = 1.92 µm patch under a 1 µm window, pixels fine: no warning.
    assert!(small_table().meta.warnings.is_empty());
    let terms = TaylorTerms::compute(&coarse, 2, 65_000.0).unwrap();
    let spectral = SpectralSetup::new(iridis_color::Illuminant::D65, iridis_color::Observer::Cie1931, 20.0).unwrap();
    let t =
        LookupTable::build(&terms, &spectral, TableParams { uv_resolution: 5, uv_power: 5.0 }, "c", &|_| {}).unwrap();
    assert_eq!(t.meta.warnings, w);
    assert_eq!(reread(&t, "c.npz").unwrap().meta.warnings, w);
    let mut json = serde_json::to_value(&t.meta).unwrap();
    json.as_object_mut().unwrap().remove("warnings");
    let old: iridis_diffraction::table::TableMeta = serde_json::from_value(json).unwrap();
    assert!(old.warnings.is_empty());
}
