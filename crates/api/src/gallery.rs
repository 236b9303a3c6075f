//! The demo gallery (`iridis demo`): one folder of images, captions and tables with an `index.html` that
//! opens in any browser. Each section is a list of library calls that writes its files through the run's
//! output set ([`crate::output`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;

/// A gallery being written: files go straight into the folder, `index.html` is written last.
pub struct Gallery {
    dir: PathBuf,
    html: String,
    /// Every figure added, in the page's order.
    figures: Vec<PathBuf>,
    /// Where "wrote FILE" progress lines go (the command line prints them; Python may drop them).
    log: Box<dyn FnMut(&str)>,
}

impl std::fmt::Debug for Gallery {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Gallery").field("dir", &self.dir).finish_non_exhaustive()
    }
}

impl Gallery {
    /// A gallery in `dir` (created if missing); `log` receives a line for each file written.
    pub fn new(dir: &Path, log: impl FnMut(&str) + 'static) -> Result<Self> {
        crate::output::create_dir(dir)?;
        Ok(Self { dir: dir.to_path_buf(), html: String::new(), figures: Vec::new(), log: Box::new(log) })
    }

    /// Sends a progress line to the gallery's log.
    pub fn log(&mut self, line: &str) {
        (self.log)(line);
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
        let path = self.path(file);
        (self.log)(&format!("  wrote {}", path.display()));
        self.figures.push(path);
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

    /// Writes `index.html` (after every section) and returns its path and every figure's, in the page's order.
    pub fn finish(self) -> Result<(PathBuf, Vec<PathBuf>)> {
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
        Ok((index, self.figures))
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}
