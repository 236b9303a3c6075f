//! `iridis demo`: the main job on built-in data. Each command group contributes a section to one gallery
//! (images, captions, numbers) with an `index.html` that opens in any browser.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args as ClapArgs;
use iridis_api::gallery::Gallery;

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
The gallery opens on snake skin rendered like the paper's figures (section snakes: nine 1024-px renders,
about 40 s of CPU time on 2 cores). The whole gallery takes a few minutes on a shared 2-core machine, most
of it in the snakes, brdf, lab and render sections; --only writes some sections (an index page with just
those).

Examples:
  iridis demo                      writes ./iridis-demo/index.html and its images
  iridis demo --out gallery
  iridis demo --only color,thinfilm --out films    two sections only (seconds)")]
pub struct Args {
    /// Folder for the gallery (created if missing).
    #[arg(long, default_value = "iridis-demo")]
    pub out: PathBuf,
    /// Only these sections, comma-separated, in the gallery's order (see below).
    #[arg(long, value_delimiter = ',', value_parser = clap::builder::PossibleValuesParser::new(SECTIONS.map(|s| s.0)))]
    pub only: Vec<String>,
}

type Section = fn(&mut Gallery) -> Result<()>;

/// The gallery's sections, in the order a newcomer should read them; each command group adds its own.
const SECTIONS: [(&str, Section); 7] = [
    ("snakes", iridis_api::scene::figures_section),
    ("color", iridis_api::color::demo_section),
    ("surface", iridis_api::surface_info::demo_section),
    ("thinfilm", iridis_api::film_chart::demo_section),
    ("brdf", iridis_api::brdf_map::demo_section),
    ("lab", iridis_api::lab_run::demo_section),
    ("render", iridis_api::scene::demo_section),
];

pub fn run(args: Args) -> Result<()> {
    crate::outln!("iridis demo: writing the gallery to {}", args.out.display())?;
    // A progress line per file; the gallery is the product, so a closed standard output does not stop it.
    let mut gallery = Gallery::new(&args.out, |line| {
        let _ = crate::outln!("{line}");
    })?;
    for (name, section) in SECTIONS {
        if args.only.is_empty() || args.only.iter().any(|o| o == name) {
            section(&mut gallery)?;
        }
    }
    let index = gallery.finish()?;
    crate::outln!("done: open {}", index.display())?;
    Ok(())
}
