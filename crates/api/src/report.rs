//! How the facade talks to the person running the work, whatever the front end: notes and warnings (the CLI
//! prints them on stderr as `note: …` / `warning: …`, Python raises them as `warnings.warn`) and progress of
//! long steps (the CLI's bars; nothing in Python). The facade never prints: it says things to a [`Report`].

use std::sync::Mutex;

/// What kind of line a [`Report`] is told.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Something the person should know about a choice made for them (e.g. a fitted coherence length).
    Note,
    /// Something that may make the result wrong or misleading.
    Warning,
    /// What was done (sizes, terms, levelling): the CLI prints it as it is.
    Info,
}

/// Progress of one piece of work; called from many threads.
pub trait Progress: Sync {
    /// `done` of the work's steps are finished.
    fn set(&self, done: u64);
    /// The work has ended.
    fn finish(&self);
}

/// Where the facade's notes, warnings and progress go.
pub trait Report: Sync {
    /// One line for the person.
    fn say(&self, kind: Kind, text: &str);
    /// Work of `len` steps labelled `what`.
    fn progress(&self, len: u64, what: &str) -> Box<dyn Progress + '_>;
    /// A step that reports no progress of its own (loading or generating a height field).
    fn step(&self, what: &str) -> Box<dyn Progress + '_> {
        self.progress(1, what)
    }

    fn note(&self, text: &str) {
        self.say(Kind::Note, text)
    }
    fn warn(&self, text: &str) {
        self.say(Kind::Warning, text)
    }
    fn info(&self, text: &str) {
        self.say(Kind::Info, text)
    }
}

/// Runs `f` with a progress callback of `len` steps, finishing the progress after it.
pub fn with_progress<T>(report: &dyn Report, len: u64, what: &str, f: impl FnOnce(&(dyn Fn(usize) + Sync)) -> T) -> T {
    let p = report.progress(len, what);
    let out = f(&|d| p.set(d as u64));
    p.finish();
    out
}

/// Runs a step that reports no progress of its own under [`Report::step`].
pub fn with_step<T>(report: &dyn Report, what: &str, f: impl FnOnce() -> T) -> T {
    let p = report.step(what);
    let out = f();
    p.finish();
    out
}

struct NoProgress;

impl Progress for NoProgress {
    fn set(&self, _: u64) {}
    fn finish(&self) {}
}

/// A report that drops everything (tests, batch work that has its own logging).
#[derive(Debug, Clone, Copy, Default)]
pub struct Quiet;

impl Report for Quiet {
    fn say(&self, _: Kind, _: &str) {}
    fn progress(&self, _: u64, _: &str) -> Box<dyn Progress + '_> {
        Box::new(NoProgress)
    }
}

/// A report that keeps every line for the caller to show afterwards (Python: `warnings.warn` once the GIL is
/// taken again); no progress. A note or warning it holds already is not kept again, as the CLI says each once:
/// the library may reach the same check twice in one call (a wavelength step checked by the evaluator and again
/// by the point query).
#[derive(Debug, Default)]
pub struct Collect {
    lines: Mutex<Vec<(Kind, String)>>,
}

impl Collect {
    /// The lines said so far, in order, leaving none behind.
    pub fn take(&self) -> Vec<(Kind, String)> {
        std::mem::take(&mut *self.lines.lock().unwrap_or_else(|p| p.into_inner()))
    }
}

impl Report for Collect {
    fn say(&self, kind: Kind, text: &str) {
        let mut lines = self.lines.lock().unwrap_or_else(|p| p.into_inner());
        if kind == Kind::Info || !lines.iter().any(|(k, t)| *k == kind && t == text) {
            lines.push((kind, text.to_string()));
        }
    }
    fn progress(&self, _: u64, _: &str) -> Box<dyn Progress + '_> {
        Box::new(NoProgress)
    }
}
