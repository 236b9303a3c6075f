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

#[test]
fn round_trip_is_exact() {
    let t = small_table();
    let mut buf = Cursor::new(Vec::new());
    t.write_npz(&mut buf).unwrap();
    buf.set_position(0);
    let back = LookupTable::read_npz(buf, "mem").unwrap();
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
    let mut buf = Cursor::new(Vec::new());
    t.write_npz(&mut buf).unwrap();
    let bytes = buf.into_inner();

    let truncated = bytes[..bytes.len() / 2].to_vec();
    let e = LookupTable::read_npz(Cursor::new(truncated), "cut.npz").unwrap_err().to_string();
    assert!(e.contains("cut.npz"), "{e}");

    let e = LookupTable::read_npz(Cursor::new(b"not a zip at all".to_vec()), "x.npz").unwrap_err().to_string();
    assert!(e.contains("not an npz"), "{e}");

    let mut newer = t.clone();
    newer.meta.version = 99;
    let mut buf = Cursor::new(Vec::new());
    newer.write_npz(&mut buf).unwrap();
    buf.set_position(0);
    let e = LookupTable::read_npz(buf, "new.npz").unwrap_err().to_string();
    assert!(e.contains("version 99") && e.contains("precompute"), "{e}");

    let mut other = t.clone();
    other.meta.format = "something-else".into();
    let mut buf = Cursor::new(Vec::new());
    other.write_npz(&mut buf).unwrap();
    buf.set_position(0);
    assert!(LookupTable::read_npz(buf, "o.npz").unwrap_err().to_string().contains("something-else"));

    // An axis shorter than the metadata says, and a table holding NaN: both refused, not read into garbage.
    let mut short_axis = t.clone();
    short_axis.uv.pop();
    let mut buf = Cursor::new(Vec::new());
    short_axis.write_npz(&mut buf).unwrap();
    buf.set_position(0);
    let e = LookupTable::read_npz(buf, "s.npz").unwrap_err().to_string();
    assert!(e.contains("disagree"), "{e}");

    let mut poisoned = t.clone();
    poisoned.data[3] = f64::NAN;
    let mut buf = Cursor::new(Vec::new());
    poisoned.write_npz(&mut buf).unwrap();
    buf.set_position(0);
    let e = LookupTable::read_npz(buf, "n.npz").unwrap_err().to_string();
    assert!(e.contains("non-finite"), "{e}");
}
