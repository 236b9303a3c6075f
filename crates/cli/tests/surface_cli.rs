//! `iridis surface` end to end: generate → file → info finds the generated period; bad input exits
//! non-zero with a message and leaves no file behind.

use std::process::Command;

fn iridis() -> Command {
    Command::new(env!("CARGO_BIN_EXE_iridis"))
}

#[test]
fn generate_then_info_recovers_the_period() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["gwy", "npy", "png", "txt"] {
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
        // The 16 µm patch is smaller than the 65 µm coherence area: the user is told.
        assert!(String::from_utf8_lossy(&info.stderr).contains("coherence area"));
    }
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
    // Leftover temporary files would start with ".iridis-".
    assert!(std::fs::read_dir(dir.path()).unwrap().all(|e| !e
        .unwrap()
        .file_name()
        .to_string_lossy()
        .starts_with(".iridis-")));
}
