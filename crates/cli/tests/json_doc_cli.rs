//! docs/json.md against the real output: every command documented there is run as written (at the small
//! sizes the page uses), and its keys must be exactly the documented ones. The GPU commands are checked in
//! gpu_cli.rs.

use crate::common;

use common::{iridis, json_doc};

#[test]
fn every_documented_key_is_printed_and_every_printed_key_is_documented() {
    let (shapes, sections) = json_doc::read();
    assert!(shapes.len() >= 2 && sections.len() >= 25, "{} shapes, {} sections", shapes.len(), sections.len());
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().display().to_string();
    let mut problems = Vec::new();
    let mut ran = 0;
    for s in &sections {
        assert!(s.command.starts_with("iridis ") && s.command.contains("--json"), "{}: no command", s.title);
        assert!(!s.keys.is_empty(), "{}: no keys", s.title);
        for (k, m) in &s.keys {
            assert!(!m.is_empty(), "{}: `{k}` has no meaning", s.title);
        }
        if s.gpu {
            continue;
        }
        let words = json_doc::split(&s.command.replace("OUT/", &format!("{out_dir}/")));
        let args: Vec<&str> = words[1..].iter().map(String::as_str).collect();
        let out = iridis(&args);
        assert!(out.status.success(), "{}: {}", s.command, String::from_utf8_lossy(&out.stderr));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{}: {e}", s.command));
        problems.extend(json_doc::check(s, &shapes, &v));
        ran += 1;
    }
    assert!(ran >= 22, "ran {ran} commands");
    assert!(problems.is_empty(), "docs/json.md disagrees with the output:\n{}", problems.join("\n"));
}

/// Every JSON subcommand of the CLI has a section: the page covers them all.
#[test]
fn every_command_with_json_is_documented() {
    let (_, sections) = json_doc::read();
    let documented: Vec<String> = sections
        .iter()
        .map(|s| {
            json_doc::split(&s.command)
                .iter()
                .take_while(|w| !w.starts_with('-') && !w.contains(['/', ':', '.', ',']))
                .cloned()
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    // Every page of `--help` that lists `--json`.
    let mut missing = Vec::new();
    let mut stack = vec![vec!["iridis".to_string()]];
    while let Some(path) = stack.pop() {
        let args: Vec<&str> = path[1..].iter().map(String::as_str).chain(["--help"]).collect();
        let help = String::from_utf8_lossy(&iridis(&args).stdout).into_owned();
        let has_json = help.lines().any(|l| l.trim_start().starts_with("--json"));
        if has_json && !documented.iter().any(|d| d.starts_with(&path.join(" "))) {
            missing.push(path.join(" "));
        }
        if let Some(list) = help.split("Commands:\n").nth(1) {
            for line in list.lines().take_while(|l| l.starts_with("  ")) {
                let name = line.split_whitespace().next().unwrap_or("");
                if !name.is_empty() && name != "help" && line.starts_with("  ") && !line.starts_with("   ") {
                    let mut p = path.clone();
                    p.push(name.to_string());
                    stack.push(p);
                }
            }
        }
    }
    assert!(missing.is_empty(), "commands with --json but no section in docs/json.md: {missing:?}");
}
