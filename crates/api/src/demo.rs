//! The main job on built-in data (`iridis demo`, Python's `iridis.demo`): each command group contributes a
//! section to one gallery (images, captions, numbers) with an `index.html` that opens in any browser.

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};

use crate::gallery::Gallery;

/// A section: library calls that add their figures and tables to the gallery.
pub type Section = fn(&mut Gallery) -> Result<()>;

/// The gallery's sections, in the order a newcomer should read them; each command group adds its own.
pub const SECTIONS: [(&str, Section); 7] = [
    ("snakes", crate::scene::figures_section),
    ("color", crate::color::demo_section),
    ("surface", crate::surface_info::demo_section),
    ("thinfilm", crate::film_chart::demo_section),
    ("brdf", crate::brdf_map::demo_section),
    ("lab", crate::lab_run::demo_section),
    ("render", crate::scene::demo_section),
];

/// Writes the gallery into `dir` (created if missing): every section, or those named in `only` (in the
/// gallery's order); `log` receives a line for each file written. Returns the path of `index.html` and of every
/// figure, in the page's order.
pub fn demo(dir: &Path, only: &[String], log: impl FnMut(&str) + 'static) -> Result<(PathBuf, Vec<PathBuf>)> {
    if let Some(unknown) = only.iter().find(|o| !SECTIONS.iter().any(|s| s.0 == o.as_str())) {
        let names: Vec<&str> = SECTIONS.iter().map(|s| s.0).collect();
        bail!("no demo section '{unknown}'; the sections: {}", names.join(", "));
    }
    let mut gallery = Gallery::new(dir, log)?;
    for (name, section) in SECTIONS {
        if only.is_empty() || only.iter().any(|o| o == name) {
            section(&mut gallery)?;
        }
    }
    gallery.finish()
}
