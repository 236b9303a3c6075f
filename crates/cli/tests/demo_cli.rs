//! `iridis demo` as a user runs it: a gallery folder with an `index.html` whose every image exists.

use crate::common;
use common::{assert_fails, iridis};

/// The `src="…"` of every `<img>` in a page.
fn image_sources(html: &str) -> Vec<String> {
    html.split("<img src=\"").skip(1).map(|rest| rest.split('"').next().unwrap_or("").to_string()).collect()
}

/// Runs the demo into a fresh folder and checks the page: every image it names is a PNG in the folder, and
/// no temporary file is left behind.
fn check_gallery(args: &[&str], min_images: usize) -> String {
    let dir = std::env::temp_dir().join(format!("iridis-demo-cli-{}-{}", std::process::id(), args.len()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut all = vec!["demo", "--out", dir.to_str().unwrap()];
    all.extend_from_slice(args);
    let out = iridis(&all);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let html = std::fs::read_to_string(dir.join("index.html")).expect("index.html written");
    assert!(html.starts_with("<!doctype html>") && html.trim_end().ends_with("</html>"));
    let images = image_sources(&html);
    assert!(images.len() >= min_images, "{} images: {images:?}", images.len());
    for src in &images {
        let bytes = std::fs::read(dir.join(src)).unwrap_or_else(|e| panic!("{src} named in index.html: {e}"));
        assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n") && bytes.len() > 200, "{src} is not a PNG");
    }
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().to_string();
        assert!(!name.ends_with(".tmp"), "temporary file left: {name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    html
}

#[test]
fn demo_sections_write_an_index_whose_images_exist() {
    let html = check_gallery(&["--only", "color,surface,thinfilm"], 8);
    // Only the sections asked for, in the gallery's order.
    let at = |needle: &str| html.find(needle).unwrap_or_else(|| panic!("{needle} missing"));
    assert!(
        at("cie1931_locus.png") < at("surface_elaphe.png") && at("surface_elaphe.png") < at("thinfilm_soap_chart.png")
    );
    assert!(!html.contains("brdf_") && !html.contains("render_"), "sections not asked for");
}

#[test]
fn demo_refuses_an_unknown_section() {
    let out = iridis(&["demo", "--only", "colour", "--out", "/nonexistent/never-created"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("'colour'") && stderr.contains("color"), "{stderr}");
    assert!(!std::path::Path::new("/nonexistent/never-created").exists());
}

/// The whole gallery (about 80 s on a shared 2-core machine): `cargo test -p iridis --test integration demo_cli:: -- --ignored`.
#[test]
#[ignore = "slow: the full gallery takes over a minute"]
fn full_demo_gallery() {
    check_gallery(&[], 30);
}

#[test]
fn demo_into_a_file_fails_cleanly() {
    let file = std::env::temp_dir().join(format!("iridis-demo-file-{}", std::process::id()));
    std::fs::write(&file, "x").unwrap();
    assert_fails(&["demo", "--only", "color", "--out", file.to_str().unwrap()], &["cannot create"]);
    let _ = std::fs::remove_file(&file);
}
