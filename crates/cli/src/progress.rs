//! Progress bars for long work (drawn on stderr, hidden when stderr is not a terminal).

use indicatif::{ProgressBar, ProgressStyle};

/// A bar of `len` steps labelled `what`.
pub fn bar(len: u64, what: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    pb.set_style(
        ProgressStyle::with_template("{msg:>18} [{bar:40.cyan/blue}] {pos}/{len} ({elapsed} elapsed, eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    pb.set_message(what.to_string());
    pb
}

/// A progress reporter for work a library announces as `(done, total, what)`: a bar per piece of work,
/// and one line on stderr when it starts, so that a log shows what the time went into too.
pub fn reporter() -> Box<dyn Fn(usize, usize, &str) + Send + Sync> {
    let current: std::sync::Mutex<Option<ProgressBar>> = std::sync::Mutex::new(None);
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
