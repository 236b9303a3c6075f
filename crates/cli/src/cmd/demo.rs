//! `iridis demo`: the main job on built-in data. Each command group contributes a section to one gallery
//! (images, captions, numbers) with an `index.html` that opens in any browser.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args as ClapArgs;

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
    ("snakes", super::render::figures_demo),
    ("color", super::color::demo),
    ("surface", super::surface::demo),
    ("thinfilm", super::thinfilm::demo),
    ("brdf", super::brdf::demo),
    ("lab", super::lab::demo),
    ("render", super::render::demo),
];

/// A gallery being written: files go straight into the folder, `index.html` is written last.
#[derive(Debug)]
pub struct Gallery {
    dir: PathBuf,
    html: String,
}

impl Gallery {
    pub fn new(dir: &Path) -> Result<Self> {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        Ok(Self { dir: dir.to_path_buf(), html: String::new() })
    }

    /// Path of a file inside the gallery.
    pub fn path(&self, file: &str) -> PathBuf {
        self.dir.join(file)
    }

    pub fn section(&mut self, title: &str, text: &str) {
        let _ = write!(self.html, "<h2>{}</h2>\n<p>{}</p>\n", escape(title), escape(text));
    }

    /// Adds an image already written to `file` with a caption.
    pub fn image(&mut self, file: &str, caption: &str) {
        // A progress line; the gallery is the product, so a closed standard output does not stop it.
        let _ = crate::outln!("  wrote {}", self.path(file).display());
        let _ = writeln!(
            self.html,
            "<figure><a href=\"{f}\"><img src=\"{f}\" alt=\"{c}\"></a><figcaption>{c}</figcaption></figure>",
            f = escape(file),
            c = escape(caption)
        );
    }

    /// Adds a table: a header row and rows of cells.
    pub fn table(&mut self, header: &[&str], rows: &[Vec<String>]) {
        self.html.push_str("<table><tr>");
        for h in header {
            let _ = write!(self.html, "<th>{}</th>", escape(h));
        }
        self.html.push_str("</tr>\n");
        for r in rows {
            self.html.push_str("<tr>");
            for c in r {
                if let Some(hex) = c.strip_prefix("swatch:") {
                    let _ = write!(
                        self.html,
                        "<td><span class=\"sw\" style=\"background:{0}\"></span> {0}</td>",
                        escape(hex)
                    );
                } else {
                    let _ = write!(self.html, "<td>{}</td>", escape(c));
                }
            }
            self.html.push_str("</tr>\n");
        }
        self.html.push_str("</table>\n");
    }

    fn finish(self) -> Result<PathBuf> {
        let page = format!(
            "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>iridis demo</title><style>\
body{{font-family:sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;color:#222}}\
figure{{display:inline-block;margin:0 1em 1em 0;vertical-align:top;max-width:560px}}\
img{{max-width:560px;border:1px solid #ccc}}figcaption{{font-size:90%;color:#444}}\
table{{border-collapse:collapse;margin:1em 0}}td,th{{border:1px solid #ccc;padding:3px 8px;font-size:90%}}\
.sw{{display:inline-block;width:2.5em;height:1em;border:1px solid #888;vertical-align:middle}}\
</style></head><body>\n<h1>iridis demo gallery</h1>\n<p>Made by <code>iridis demo</code> (iridis {}) from built-in \
data only. Every image below can be regenerated with the command named in its caption.</p>\n{}</body></html>\n",
            env!("CARGO_PKG_VERSION"),
            self.html
        );
        let index = self.dir.join("index.html");
        crate::output::write_bytes(&index, page.as_bytes())?;
        Ok(index)
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

pub fn run(args: Args) -> Result<()> {
    crate::outln!("iridis demo: writing the gallery to {}", args.out.display())?;
    let mut gallery = Gallery::new(&args.out)?;
    for (name, section) in SECTIONS {
        if args.only.is_empty() || args.only.iter().any(|o| o == name) {
            section(&mut gallery)?;
        }
    }
    let index = gallery.finish()?;
    crate::outln!("done: open {}", index.display())?;
    Ok(())
}
