//! How every `--help` page is laid out, in one place: clap wraps the prose to the terminal, and the
//! examples stay one command per line so that they can be copied.
//!
//! Help texts are written in the source as `after_help` strings with hard line breaks for the reader of the
//! code. [`layout`] walks the command tree once, before parsing, and for each page
//! - joins each prose paragraph (unindented lines up to a blank line, an indented line or a line ending in
//!   `:`) into one line, which clap then wraps at the terminal's width (the `wrap_help` feature), and
//! - moves the `Examples:` block (the heading and the indented lines under it) into the page's help
//!   template, whose literal text clap prints as written, so an example is never split however narrow the
//!   terminal; the examples close the page.
//!
//! clap wraps greedily, which can leave the last word of a paragraph alone on a line; [`mend_widows`] moves
//! the word before it down to keep it company, on the page as rendered.

use clap::Command;

/// The heading that starts a page's examples.
pub const EXAMPLES: &str = "Examples:";

/// clap's default page (its `DEFAULT_TEMPLATE`), to which the examples are appended.
const PAGE: &str = "{before-help}{about-with-newline}\n{usage-heading} {usage}\n\n{all-args}{after-help}";

/// Lays out `cmd` and all its subcommands (see the module documentation).
pub fn layout(mut cmd: Command) -> Command {
    let names: Vec<String> = cmd.get_subcommands().map(|s| s.get_name().to_string()).collect();
    for name in names {
        cmd = cmd.mut_subcommand(name, layout);
    }
    let Some(after) = cmd.get_after_help().map(|s| s.to_string()) else { return cmd };
    let (prose, examples) = split_examples(&after);
    let heading = cmd.get_styles().get_header();
    let mut page = PAGE.to_string();
    if !examples.is_empty() {
        // `{` in an example (`{d}`) is not a template tag clap knows, so clap prints it unchanged.
        let (on, off) = (heading.render(), heading.render_reset());
        page.push_str(&format!("\n\n{on}{EXAMPLES}{off}\n{}", examples.join("\n")));
    }
    let prose = reflow(&prose);
    let cmd = if prose.is_empty() { cmd.after_help(clap::builder::Resettable::Reset) } else { cmd.after_help(prose) };
    cmd.help_template(page)
}

/// The width clap wraps help at (its own rule): the terminal's, else `COLUMNS`, else 100.
pub fn width() -> usize {
    terminal_size::terminal_size()
        .map(|(w, _)| usize::from(w.0))
        .or_else(|| std::env::var("COLUMNS").ok()?.parse().ok())
        .unwrap_or(100)
}

/// A line that holds one word and nothing else (not a heading, flag or value name of clap's lists).
pub fn is_lone(line: &str) -> bool {
    let t = line.trim();
    !t.is_empty()
        && !t.contains(' ')
        && !t.ends_with(':')
        && !t.starts_with('-')
        && !t.starts_with('<')
        && !t.starts_with('[')
}

/// Mends widows in a rendered help page of `width` columns: a lone last word of a wrapped paragraph or
/// argument help gets the word before it (when the line above keeps text of its own and the pair fits).
/// The examples are left as written.
pub fn mend_widows(page: &str, width: usize) -> String {
    let mut lines: Vec<String> = page.lines().map(str::to_string).collect();
    let end = lines.iter().position(|l| l.trim_end() == EXAMPLES).unwrap_or(lines.len());
    for i in 1..end {
        if !is_lone(&lines[i]) {
            continue;
        }
        let indent = lines[i].len() - lines[i].trim_start().len();
        let prev = &lines[i - 1];
        // The line above must run on into this one: text in the same column (clap's help column).
        if prev.trim().is_empty() || prev.len() <= indent || (indent > 0 && prev.as_bytes()[indent - 1] != b' ') {
            continue;
        }
        let Some(cut) = prev.rfind(' ') else { continue };
        let head = prev[..cut].trim_end();
        let moved = format!("{}{} {}", " ".repeat(indent), &prev[cut + 1..], lines[i].trim());
        if head.len() <= indent || is_lone(head) || moved.chars().count() > width {
            continue;
        }
        lines[i - 1] = head.to_string();
        lines[i] = moved;
    }
    let mut out = lines.join("\n");
    if page.ends_with('\n') {
        out.push('\n');
    }
    out
}

/// Splits an `after_help` text into its prose lines and its example lines (the indented lines under an
/// `Examples:` heading, kept verbatim).
pub fn split_examples(text: &str) -> (Vec<String>, Vec<String>) {
    let (mut prose, mut examples) = (Vec::new(), Vec::new());
    let mut in_examples = false;
    for line in text.lines() {
        if line.trim_end() == EXAMPLES {
            in_examples = true;
        } else if in_examples && line.starts_with(' ') && !line.trim().is_empty() {
            examples.push(line.trim_end().to_string());
        } else {
            in_examples = false;
            prose.push(line.to_string());
        }
    }
    (prose, examples)
}

/// Joins the lines of each prose paragraph into one line for clap to wrap. A paragraph ends at a blank line,
/// before an indented line (a table or list row, kept as written) and after its first line when that ends in
/// `:` (a heading for what follows).
pub fn reflow(lines: &[String]) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut open = false; // whether the last output line is a paragraph that may continue
    for line in lines {
        let t = line.trim_end();
        if t.is_empty() {
            if out.last().is_some_and(|l| !l.is_empty()) {
                out.push(String::new());
            }
            open = false;
        } else if t.starts_with(' ') {
            out.push(t.to_string());
            open = false;
        } else {
            match out.last_mut() {
                Some(last) if open => {
                    last.push(' ');
                    last.push_str(t);
                }
                // A paragraph whose first line ends in ':' is a heading for what follows ("Kinds:").
                _ => {
                    out.push(t.to_string());
                    open = !t.ends_with(':');
                    continue;
                }
            }
            open = true;
        }
    }
    while out.last().is_some_and(|l| l.is_empty()) {
        out.pop();
    }
    out.join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widows_get_company() {
        let page = "Options:\n      --x <X>  Some help that wraps\n               here\n\nA paragraph that ends\nalone.\nExamples:\n  iridis\n";
        assert_eq!(
            mend_widows(page, 40),
            "Options:\n      --x <X>  Some help that\n               wraps here\n\nA paragraph that\nends alone.\nExamples:\n  iridis\n"
        );
        // Too wide to join, or nothing above to take from: left alone.
        assert_eq!(mend_widows("abc defghij\nklmnop\n", 12), "abc defghij\nklmnop\n");
        assert_eq!(mend_widows("\nalone\n", 80), "\nalone\n");
    }

    #[test]
    fn paragraphs_join_and_examples_move_out() {
        let text = "First line\nof a paragraph, which says:\nthis.\n\nKinds:\n  sine   a table row\nCommon: x\n\nExamples:\n  iridis a --b \"c | d\"\n  iridis e   note\n\nAfter.";
        let (prose, examples) = split_examples(text);
        assert_eq!(examples, ["  iridis a --b \"c | d\"", "  iridis e   note"]);
        assert_eq!(
            reflow(&prose),
            "First line of a paragraph, which says: this.\n\nKinds:\n  sine   a table row\nCommon: x\n\nAfter."
        );
    }
}
