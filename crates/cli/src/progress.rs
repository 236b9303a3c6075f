//! Progress for long work. On a terminal, an indicatif bar on stderr; when stderr is not a terminal (a log,
//! a pipe, CI) the bar is hidden, so a step that is still running after a second says so in one line, and
//! again when it ends: every step over ~1 s announces itself either way.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

/// Steps shorter than this stay silent in a log: 1 s, or `IRIDIS_PROGRESS_AFTER_MS` (0 announces every step).
fn announce_after() -> Duration {
    static AFTER: std::sync::OnceLock<Duration> = std::sync::OnceLock::new();
    *AFTER.get_or_init(|| {
        let ms = std::env::var("IRIDIS_PROGRESS_AFTER_MS").ok().and_then(|v| v.parse().ok()).unwrap_or(1000);
        Duration::from_millis(ms)
    })
}

/// A progress bar (or, without a terminal, its one-line announcements).
pub struct Bar {
    pb: ProgressBar,
    what: String,
    start: Instant,
    announced: AtomicBool,
}

impl Bar {
    pub fn set_position(&self, pos: u64) {
        self.pb.set_position(pos);
        self.announce();
    }

    /// Ends the bar; in a log, a step that was announced says how long it took.
    pub fn finish_and_clear(&self) {
        self.pb.finish_and_clear();
        if self.pb.is_hidden() && self.announced.load(Ordering::Relaxed) {
            eprintln!("{}: done in {:.1} s", self.what, self.start.elapsed().as_secs_f64());
        }
    }

    fn announce(&self) {
        if self.pb.is_hidden()
            && self.start.elapsed() >= announce_after()
            && !self.announced.swap(true, Ordering::Relaxed)
        {
            let len = self.pb.length().map(|l| format!("/{l}")).unwrap_or_default();
            eprintln!("{}: {}{len} after {:.1} s …", self.what, self.pb.position(), self.start.elapsed().as_secs_f64());
        }
    }
}

/// A bar of `len` steps labelled `what`.
pub fn bar(len: u64, what: &str) -> Bar {
    let pb = ProgressBar::new(len);
    pb.set_style(
        ProgressStyle::with_template("{msg:>18} [{bar:40.cyan/blue}] {pos}/{len} ({elapsed} elapsed, eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    pb.set_message(what.to_string());
    Bar { pb, what: what.to_string(), start: Instant::now(), announced: AtomicBool::new(false) }
}

/// A spinner with the elapsed time for a step that reports no progress of its own (loading and generating a
/// height field); in a log, a step over a second is reported when it ends.
pub struct Spinner {
    pb: ProgressBar,
    what: String,
    start: Instant,
}

impl Spinner {
    pub fn start(what: &str) -> Self {
        let pb = ProgressBar::new_spinner();
        pb.set_style(
            ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
                .unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        pb.set_message(what.to_string());
        pb.enable_steady_tick(Duration::from_millis(120));
        Self { pb, what: what.to_string(), start: Instant::now() }
    }

    pub fn finish(&self) {
        self.pb.finish_and_clear();
        if self.pb.is_hidden() && self.start.elapsed() >= announce_after() {
            eprintln!("{}: {:.1} s", self.what, self.start.elapsed().as_secs_f64());
        }
    }
}

/// The facade's notes, warnings and progress on the terminal: `note: …` and `warning: …` on stderr (each once a
/// run), the facade's other lines as they are, progress as [`bar`]s and spinners (`step`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Cli;

impl iridis_api::report::Progress for Bar {
    fn set(&self, done: u64) {
        self.set_position(done);
    }
    fn finish(&self) {
        self.finish_and_clear();
    }
}

impl iridis_api::report::Progress for Spinner {
    fn set(&self, _: u64) {}
    fn finish(&self) {
        Spinner::finish(self);
    }
}

/// The notes and warnings said so far in this run: the library may reach the same check twice in one command
/// (a wavelength step checked by the evaluator and again by the point query), and a line said again tells
/// nothing new.
fn first_time(kind: iridis_api::Kind, text: &str) -> bool {
    static SAID: std::sync::Mutex<Vec<(iridis_api::Kind, String)>> = std::sync::Mutex::new(Vec::new());
    let mut said = SAID.lock().unwrap_or_else(|e| e.into_inner());
    if said.iter().any(|(k, t)| *k == kind && t == text) {
        return false;
    }
    said.push((kind, text.to_string()));
    true
}

impl iridis_api::Report for Cli {
    fn say(&self, kind: iridis_api::Kind, text: &str) {
        if kind != iridis_api::Kind::Info && !first_time(kind, text) {
            return;
        }
        match kind {
            iridis_api::Kind::Note => eprintln!("note: {text}"),
            iridis_api::Kind::Warning => eprintln!("warning: {text}"),
            iridis_api::Kind::Info => eprintln!("{text}"),
        }
    }
    fn progress(&self, len: u64, what: &str) -> Box<dyn iridis_api::report::Progress + '_> {
        Box::new(bar(len, what))
    }
    fn step(&self, what: &str) -> Box<dyn iridis_api::report::Progress + '_> {
        Box::new(Spinner::start(what))
    }
}

/// A progress reporter for work a library announces as `(done, total, what)`: a bar per piece of work,
/// and one line on stderr when it starts, so that a log shows what the time went into too.
pub fn reporter() -> Box<iridis_render::tables::TableProgress> {
    let current: std::sync::Mutex<Option<Bar>> = std::sync::Mutex::new(None);
    Box::new(move |done, total, what| {
        let mut cur = current.lock().unwrap_or_else(|e| e.into_inner());
        let pb = cur.get_or_insert_with(|| {
            eprintln!("computing the {what} (cached for the next runs)");
            bar(total as u64, what)
        });
        pb.set_position(done as u64);
        if done >= total {
            pb.finish_and_clear();
            *cur = None;
        }
    })
}
