//! `iridis demo`: the main job on built-in data. Each command group contributes a section to one gallery
//! (images, captions, numbers) with an `index.html` that opens in any browser.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args as ClapArgs;
use iridis_api::demo::SECTIONS;

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

pub fn run(args: Args) -> Result<()> {
    crate::outln!("iridis demo: writing the gallery to {}", args.out.display())?;
    // A progress line per file; the gallery is the product, so a closed standard output does not stop it.
    let (index, _) = iridis_api::demo::demo(&args.out, &args.only, |line| {
        let _ = crate::outln!("{line}");
    })?;
    crate::outln!("done: open {}", index.display())?;
    Ok(())
}
