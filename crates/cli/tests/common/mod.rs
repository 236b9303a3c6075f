//! What every CLI test file needs: run the built `iridis` as a user would, read its JSON, and check that bad
//! input fails the way the project promises (exit code 2, one `error:` line, no panic).
#![allow(dead_code)] // each test file uses its own subset

use std::process::{Command, Output};

use iridis_color::integrate::white_point;
use iridis_color::{Illuminant, Lab, Observer, Xyz};
use iridis_thinfilm::accuracy::DeltaEStats;

/// A scratch folder, removed when the test ends (tests that leave files in the temp folder pile them up run
/// after run).
pub fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("a temporary folder")
}

/// The built binary as a command to add arguments, environment or pipes to, run from the repository root (so
/// `data/…` and `examples/…` paths work as in the README).
pub fn command() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_iridis"));
    c.current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    c
}

/// Runs `iridis ARGS` from the repository root.
pub fn iridis<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(args: &[S]) -> Output {
    command().args(args).output().expect("cannot run iridis")
}

/// Runs a command that must succeed.
pub fn succeeds<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(args: &[S]) -> Output {
    let out = iridis(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    out
}

/// Runs a command that must succeed; its stderr then its stdout, as text.
pub fn ok<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(args: &[S]) -> String {
    let out = succeeds(args);
    String::from_utf8_lossy(&out.stderr).to_string() + &String::from_utf8_lossy(&out.stdout)
}

/// Runs a command that must succeed and print JSON.
pub fn json_of<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(args: &[S]) -> serde_json::Value {
    let out = succeeds(args);
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e})"))
}

/// Asserts a clean failure: exit code 2, a single `error:` line that contains every needle, no panic.
pub fn assert_fails<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(args: &[S], needles: &[&str]) {
    let out = iridis(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{args:?}: {stderr}");
    for n in needles {
        assert!(errors[0].contains(n), "{args:?}: '{}' lacks '{n}'", errors[0]);
    }
}

/// Splits a command line as a shell would: words, '…' and "…" quoting. Tests write a command as a user types
/// it: `json_of(&words("thinfilm color --stack 'air | water 348nm | air' --json"))`.
pub fn words(command: &str) -> Vec<String> {
    let (mut words, mut cur, mut quote, mut any) = (Vec::new(), String::new(), None, false);
    for c in command.chars() {
        match (quote, c) {
            (None, '\'' | '"') => (quote, any) = (Some(c), true),
            (Some(q), c) if c == q => quote = None,
            (None, ' ') => {
                if any {
                    words.push(std::mem::take(&mut cur));
                }
                any = false;
            }
            (_, c) => {
                cur.push(c);
                any = true;
            }
        }
    }
    if any {
        words.push(cur);
    }
    words
}

/// Writes `text` to `dir/name`; returns the path as text, for a command line.
pub fn write_file(dir: &std::path::Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// A path as one quoted word of a command line for [`words`].
pub fn quoted(path: &std::path::Path) -> String {
    format!("'{}'", path.display())
}

/// The rough film of Sussenbach's Listing 3.6 (water 348 nm on Si, σ 25 nm, τ 300 nm) as `thinfilm` options.
pub const ROUGH_FILM: &str = "--stack 'air | water 348nm | Si' --roughness 25nm --correlation 300nm";

/// Displayed colours of an 8-bit sRGB PNG as CIELAB (white: D65, CIE 1931 observer).
pub fn png_lab(path: &std::path::Path) -> Vec<Lab> {
    let img = image::open(path).unwrap().to_rgb8();
    let white = white_point(Illuminant::D65, Observer::Cie1931);
    img.pixels()
        .map(|p| {
            let lin = p.0.map(|v| iridis_color::convert::srgb_decode(v as f64 / 255.0));
            Lab::from_xyz(Xyz::from_linear_srgb(lin), white)
        })
        .collect()
}

/// CIEDE2000 between two images pixel for pixel (same size), as the library's ΔE statistics: mean, 99th
/// percentile, largest.
pub fn delta_e_between(a: &[Lab], b: &[Lab]) -> DeltaEStats {
    assert_eq!(a.len(), b.len(), "images of different sizes");
    DeltaEStats::of(a.iter().zip(b).map(|(p, q)| iridis_color::lab::delta_e_2000(*p, *q)).collect())
}

/// docs/json.md, the one place where the JSON keys of every command are documented, read as the test reads
/// it: a `## ` section per command with the command line in backticks and a table of keys.
pub mod json_doc {
    use std::collections::BTreeSet;

    pub struct Section {
        pub title: String,
        pub command: String,
        /// "Needs a GPU."
        pub gpu: bool,
        /// "… a display …": run only under xvfb by the viewer test.
        pub display: bool,
        /// (key path, meaning)
        pub keys: Vec<(String, String)>,
    }

    pub fn read() -> (Vec<Section>, Vec<Section>) {
        let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/json.md")).unwrap();
        let (mut shapes, mut commands) = (Vec::new(), Vec::new());
        let mut cur: Option<Section> = None;
        let flush = |cur: Option<Section>, shapes: &mut Vec<Section>, commands: &mut Vec<Section>| {
            if let Some(s) = cur {
                if s.title.starts_with("Shape: ") {
                    shapes.push(s)
                } else {
                    commands.push(s)
                }
            }
        };
        for line in text.lines() {
            if let Some(t) = line.strip_prefix("## ") {
                flush(cur.take(), &mut shapes, &mut commands);
                cur = Some(Section {
                    title: t.to_string(),
                    command: String::new(),
                    gpu: false,
                    display: false,
                    keys: Vec::new(),
                });
            } else if let Some(s) = cur.as_mut() {
                if s.command.is_empty() && line.starts_with("`iridis ") && line.ends_with('`') {
                    s.command = line.trim_matches('`').to_string();
                } else if line.starts_with("Needs a GPU") {
                    s.gpu = true;
                    s.display = line.contains("display");
                } else if let Some(row) = line.strip_prefix("| `") {
                    let (key, rest) = row.split_once('`').unwrap();
                    let meaning = rest.trim_start_matches(" |").trim_end_matches('|').trim().to_string();
                    s.keys.push((key.to_string(), meaning));
                }
            }
        }
        flush(cur, &mut shapes, &mut commands);
        (shapes, commands)
    }

    /// Splits a documented command line as a shell would ([`super::words`]).
    pub fn split(command: &str) -> Vec<String> {
        super::words(command)
    }

    /// The key paths of an answer as the page writes them (`a.b`, `list[].key`), not descending into
    /// `inputs` or into values documented with a shape (`(shape: NAME)`, whose keys are checked against it).
    fn paths(v: &serde_json::Value, prefix: &str, shaped: &BTreeSet<String>, out: &mut BTreeSet<String>) {
        match v {
            serde_json::Value::Object(m) => {
                for (k, x) in m {
                    let p = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                    out.insert(p.clone());
                    let echo = prefix.is_empty() && k == "inputs";
                    if !echo && !shaped.contains(&p) {
                        paths(x, &p, shaped, out);
                    }
                }
            }
            serde_json::Value::Array(items) => {
                for x in items.iter().filter(|x| x.is_object()) {
                    paths(x, &format!("{prefix}[]"), shaped, out);
                }
            }
            _ => {}
        }
    }

    /// Checks one answer against its section: the documented keys are exactly the keys printed (a
    /// documented key of an array's elements is excused when the array is empty), values with a shape have
    /// the shape's keys, and `inputs` is there.
    pub fn check(section: &Section, shapes: &[Section], v: &serde_json::Value) -> Vec<String> {
        let mut problems = Vec::new();
        let shape_of = |meaning: &str| {
            shapes.iter().find(|s| meaning.contains(&format!("(shape: {})", s.title.trim_start_matches("Shape: "))))
        };
        let shaped: BTreeSet<String> =
            section.keys.iter().filter(|(_, m)| shape_of(m).is_some()).map(|(k, _)| k.clone()).collect();
        let mut printed = BTreeSet::new();
        paths(v, "", &shaped, &mut printed);
        let documented: BTreeSet<String> = section.keys.iter().map(|(k, _)| k.clone()).collect();
        let title = &section.title;
        for k in printed.difference(&documented) {
            problems.push(format!("{title}: `{k}` is printed but not documented"));
        }
        for k in documented.difference(&printed) {
            // `a[].b` cannot be seen when the array `a` is empty.
            let empty_array = k.split_once("[]").is_some_and(|(a, _)| {
                a.split('.').try_fold(v, |x, part| x.get(part)).and_then(|x| x.as_array()).is_some_and(|x| x.is_empty())
            });
            if !empty_array {
                problems.push(format!("{title}: `{k}` is documented but not printed"));
            }
        }
        for (k, m) in &section.keys {
            let Some(shape) = shape_of(m) else { continue };
            // `a[].b`: the shape holds for `b` of every element of the array `a`.
            let values: Vec<Option<&serde_json::Value>> = match k.split_once("[].") {
                Some((a, rest)) => match a.split('.').try_fold(v, |x, part| x.get(part)).and_then(|x| x.as_array()) {
                    Some(items) => items.iter().map(|it| rest.split('.').try_fold(it, |x, part| x.get(part))).collect(),
                    None => vec![None],
                },
                None => vec![k.split('.').try_fold(v, |x, part| x.get(part))],
            };
            for value in values {
                match value {
                    Some(serde_json::Value::Object(o)) => {
                        let got: BTreeSet<&String> = o.keys().collect();
                        let want: BTreeSet<&String> = shape.keys.iter().map(|(k, _)| k).collect();
                        if got != want {
                            problems.push(format!("{title}: `{k}` has keys {got:?}, its shape {want:?}"));
                        }
                    }
                    Some(serde_json::Value::Null) if m.contains("`null`") => {}
                    other => problems.push(format!("{title}: `{k}` should be a {} object, is {other:?}", shape.title)),
                }
            }
        }
        if !v["inputs"].is_object() {
            problems.push(format!("{title}: no `inputs` object"));
        }
        problems
    }
}
