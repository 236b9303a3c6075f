//! The unit tests of src/output.rs (outputs written together or not at all, formats, JSON layout), moved here so
//! that `cargo test` compiles the library once.

use iridis_api::output::*;
use std::path::Path;

/// The run's set: nothing appears before `commit`, everything after it; `discard` leaves no trace; a
/// second write of one path and two spellings of one path are refused; folders the run made go with it. (One
/// test: the set is global.)
#[test]
fn outputs_appear_together_or_not_at_all() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.png"), dir.path().join("b.csv"));
    let listing = || {
        let mut v: Vec<String> =
            std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        v.sort();
        v
    };
    assert_eq!(declare("-o", &a, &["png"]).unwrap(), "png");
    let same = dir.path().join(".").join("a.png");
    assert!(declare("--plot", &same, &["png"]).unwrap_err().to_string().contains("same file"));
    write_bytes(&a, b"first").unwrap();
    write_bytes(&b, b"second").unwrap();
    assert!(write_bytes(&b, b"again").unwrap_err().to_string().contains("twice"));
    // Written, not yet committed: only temporaries.
    assert!(listing().iter().all(|n| n.starts_with(".iridis-")), "{:?}", listing());
    discard();
    assert!(listing().is_empty(), "{:?}", listing());

    declare("-o", &a, &["png"]).unwrap();
    declare_opt("--csv", Some(b.as_path()), &["csv"]).unwrap();
    write_bytes(&a, b"first").unwrap();
    write_bytes(&b, b"second").unwrap();
    commit().unwrap();
    assert_eq!(listing(), ["a.png", "b.csv"]);
    assert_eq!(std::fs::read(&a).unwrap(), b"first");
    assert_eq!(std::fs::read(&b).unwrap(), b"second");
    // A declared output that is never written leaves nothing.
    declare("-o", &dir.path().join("c.png"), &["png"]).unwrap();
    commit().unwrap();
    assert_eq!(listing(), ["a.png", "b.csv"]);

    // Output folders the run creates are outputs too: a failed run removes them (and the parents it made,
    // with the temporaries inside), a folder that existed stays; a committed run keeps them.
    let (made, inner) = (dir.path().join("made"), dir.path().join("made").join("inner"));
    create_dir(&inner).unwrap();
    write_bytes(&inner.join("x.png"), b"x").unwrap();
    create_dir(dir.path()).unwrap();
    discard();
    assert!(!made.exists());
    assert_eq!(listing(), ["a.png", "b.csv"]);
    create_dir(&inner).unwrap();
    write_bytes(&inner.join("x.png"), b"x").unwrap();
    commit().unwrap();
    assert_eq!(std::fs::read(inner.join("x.png")).unwrap(), b"x");
    discard();
    assert!(inner.join("x.png").exists(), "a discard after a commit touched the committed run's folder");
}

#[test]
fn formats_follow_the_extension() {
    let p = Path::new("x.JPG");
    let e = format_of("-o", p, &["png", "exr"]).unwrap_err().to_string();
    assert_eq!(e, "-o x.JPG: cannot write .JPG files here; name it .png or .exr");
    assert_eq!(format_of("-o", Path::new("x.EXR"), &["png", "exr"]).unwrap(), "exr");
    assert!(format_of("", Path::new("noext"), &["png"]).unwrap_err().to_string().contains("no extension"));
}

#[test]
fn json_arrays_of_numbers_stay_on_one_line() {
    let v = serde_json::json!({"b": [1.5, 2, -3e-7], "a": {"m": [[1, 2], [3, 4]], "e": [], "o": {}}, "s": "x"});
    assert_eq!(
        json_string(&v),
        "{\n  \"a\": {\n    \"e\": [],\n    \"m\": [\n      [1, 2],\n      [3, 4]\n    ],\n    \"o\": {}\n  },\n  \
             \"b\": [1.5, 2, -3e-7],\n  \"s\": \"x\"\n}"
    );
    let back: serde_json::Value = serde_json::from_str(&json_string(&v)).unwrap();
    assert_eq!(back, v);
}
