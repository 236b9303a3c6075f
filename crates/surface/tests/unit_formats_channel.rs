//! The unit tests of src/formats/channel.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::channel::*;
use iridis_surface::formats::LoadOptions;

fn ch(index: u32, name: &str, unit: &str, dir: &str) -> ChannelInfo {
    ChannelInfo {
        index,
        name: name.into(),
        rows: 4,
        cols: 4,
        z_unit: unit.into(),
        direction: dir.into(),
        alias: String::new(),
    }
}

#[test]
fn selection_by_index_name_and_default() {
    let l = vec![
        ch(0, "Amplitude", "m", "trace"),
        ch(1, "Phase", "deg", "trace"),
        ch(2, "Height", "m", "trace"),
        ch(3, "Height", "m", "retrace"),
    ];
    assert_eq!(pick(&l, None).unwrap(), 2);
    assert_eq!(pick(&l, Some(&"1".parse().unwrap())).unwrap(), 1);
    assert_eq!(pick(&l, Some(&"height".parse().unwrap())).unwrap(), 2);
    assert_eq!(pick(&l, Some(&"height_retrace".parse().unwrap())).unwrap(), 3);
    let e = pick(&l, Some(&"Friction".parse().unwrap())).unwrap_err().to_string();
    assert!(e.contains("'Friction'") && e.contains("1: Phase (deg, trace)"), "{e}");
    let e = pick(&l, Some(&ChannelSel::Index(9))).unwrap_err().to_string();
    assert!(e.contains("no channel 9") && e.contains("3: Height (m, retrace)"), "{e}");
    let o = LoadOptions::default();
    let um = LoadOptions { height_unit: Some("um".into()), ..Default::default() };
    assert!(z_scale(&l, &l[1], &o, None, None).unwrap_err().to_string().contains("records the phase"));
    assert_eq!(z_scale(&l, &l[2], &o, None, None).unwrap().nm_per_unit, 1e9);
    let nounit = ch(0, "Z", "", "");
    assert!(z_scale(&l, &nounit, &o, None, None).unwrap_err().to_string().contains("--height-unit"));
    assert_eq!(z_scale(&l, &nounit, &um, None, None).unwrap().nm_per_unit, 1e3);
}

/// Bruker's channel list (sample_0.spm): AFMReader and TopoStats read "Height", not the first height-like
/// channel "Height Sensor"; the choice says why and lists the heights.
#[test]
fn the_default_is_the_channel_named_height() {
    let l = vec![
        ch(0, "Height Sensor", "nm", "trace"),
        ch(1, "Peak Force Error", "nm", "trace"),
        ch(2, "DMTModulus", "MPa", "trace"),
        ch(3, "Deformation", "nm", "trace"),
        ch(4, "Height", "nm", "trace"),
    ];
    assert_eq!(pick(&l, None).unwrap(), 4);
    let c = ChannelChoice::new(&l, 4, None);
    let d = c.describe();
    assert!(d.contains("channel 4 'Height' (trace) of 5") && d.contains("AFMReader"), "{d}");
    assert!(d.contains("height channels: 0: Height Sensor_trace, 4: Height_trace") && d.contains("--channel"), "{d}");
    // Without a "Height", the first channel named like one; error and deformation are not heights.
    assert_eq!(pick(&l[..4], None).unwrap(), 0);
    assert!(!l[1].is_height() && !l[3].is_height() && !l[2].is_height() && l[0].is_height());
    let asked = ChannelChoice::new(&l, 0, Some(&ChannelSel::Index(0)));
    assert!(asked.describe().contains("as asked (--channel 0)"), "{}", asked.describe());
}

/// A tapping amplitude is in metres but is not a height: refused, naming the heights, unless forced.
#[test]
fn other_signals_are_refused_as_heights_unless_forced() {
    let l = vec![ch(0, "height", "m", "trace"), ch(1, "amplitude", "m", "trace"), ch(2, "phase", "deg", "trace")];
    let e = z_scale(&l, &l[1], &LoadOptions::default(), None, None).unwrap_err().to_string();
    assert!(e.contains("records the amplitude") && e.contains("0: height_trace") && e.contains("--as-height"), "{e}");
    let forced = LoadOptions { as_height: true, ..Default::default() };
    let z = z_scale(&l, &l[1], &forced, None, None).unwrap();
    assert_eq!(z.nm_per_unit, 1e9);
    assert!(z.warnings[0].contains("--as-height"), "{:?}", z.warnings);
    // A phase in degrees needs a height unit even when forced.
    assert!(z_scale(&l, &l[2], &forced, None, None).unwrap_err().to_string().contains("--height-unit"));
    let forced_nm = LoadOptions { as_height: true, height_unit: Some("nm".into()), ..Default::default() };
    assert_eq!(z_scale(&l, &l[2], &forced_nm, None, None).unwrap().nm_per_unit, 1.0);
    // The height channel itself needs no forcing: --as-height there would change nothing, and says so.
    let e = z_scale(&l, &l[0], &forced, None, None).unwrap_err().to_string();
    assert!(e.contains("--as-height would be ignored: channel 0 'height_trace' is a height already (in m)"), "{e}");
}

/// The file's unit wins over a contradicting --height-unit, with a warning naming both, unless
/// --override-units; a --height-unit that agrees says nothing.
#[test]
fn the_files_height_unit_wins_unless_overridden() {
    let l = vec![ch(0, "Height", "nm", "")];
    let um = LoadOptions { height_unit: Some("um".into()), ..Default::default() };
    let z = z_scale(&l, &l[0], &um, None, None).unwrap();
    assert_eq!((z.nm_per_unit, z.unit.as_str()), (1.0, "nm"));
    assert!(z.warnings[0].contains("--height-unit um ignored") && z.warnings[0].contains("in nm"), "{:?}", z.warnings);
    let forced = LoadOptions { override_units: true, ..um };
    let z = z_scale(&l, &l[0], &forced, None, None).unwrap();
    assert_eq!(z.nm_per_unit, 1e3);
    assert!(z.warnings[0].contains("--override-units"), "{:?}", z.warnings);
    let same = LoadOptions { height_unit: Some("nm".into()), ..Default::default() };
    assert!(z_scale(&l, &l[0], &same, None, None).unwrap().warnings.is_empty());
}
