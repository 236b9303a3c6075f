//! Printing results: the command's JSON answer with its `"inputs"`, and standard output that a closed pipe
//! does not turn into a panic. Files are written through the library's run-wide output set
//! ([`iridis_api::output`], re-exported here).

use std::io::Write;

use anyhow::Result;

pub use iridis_api::output::*;

// ----------------------------------------------------------------------------------------------------------
// JSON

static INPUTS: std::sync::OnceLock<serde_json::Value> = std::sync::OnceLock::new();

/// The options of the command line, for the `"inputs"` object of every JSON answer (set once by `main`):
/// each option of the command that ran, under its long name with `_` for `-`, as typed or its default
/// (`null` when absent and without a default); flags as booleans.
pub fn set_inputs(cli: &clap::Command, matches: &clap::ArgMatches) {
    let _ = INPUTS.set(inputs_of(cli, matches));
}

/// The `"inputs"` object of a command line parsed by `cli` (see [`set_inputs`]).
pub fn inputs_of(cli: &clap::Command, matches: &clap::ArgMatches) -> serde_json::Value {
    let (mut cmd, mut m) = (cli, matches);
    while let Some((name, sub)) = m.subcommand() {
        match cmd.find_subcommand(name) {
            Some(c) => (cmd, m) = (c, sub),
            None => break,
        }
    }
    let mut inputs = serde_json::Map::new();
    for arg in cmd.get_arguments() {
        let id = arg.get_id().as_str();
        if matches!(id, "help" | "version" | "json") || arg.is_hide_set() {
            continue;
        }
        let key = arg.get_long().unwrap_or(id).replace('-', "_");
        // A flag is a boolean, whether it was given: a SetFalse flag (`--no-shadowing`) stores false when it is,
        // one of no values that fills an `Option` (`--percent`) stores nothing when it is not.
        let flag = matches!(arg.get_action(), clap::ArgAction::SetTrue | clap::ArgAction::SetFalse)
            || arg.get_num_args().is_some_and(|n| !n.takes_values());
        let value = match arg.get_action() {
            _ if flag => (m.value_source(id) == Some(clap::parser::ValueSource::CommandLine)).into(),
            clap::ArgAction::Count => {
                m.try_get_one::<u8>(id).ok().flatten().map_or(serde_json::Value::Null, |n| (*n).into())
            }
            _ => match m.try_get_raw(id).ok().flatten() {
                None => serde_json::Value::Null,
                Some(raw) => {
                    let v: Vec<serde_json::Value> =
                        raw.map(|s| serde_json::Value::String(s.to_string_lossy().into_owned())).collect();
                    match (v.len(), arg.get_num_args().is_some_and(|n| n.max_values() > 1)) {
                        (1, false) => v.into_iter().next().unwrap_or_default(),
                        _ => serde_json::Value::Array(v),
                    }
                }
            },
        };
        inputs.insert(key, value);
    }
    serde_json::Value::Object(inputs)
}

/// A command's JSON answer with the `"inputs"` it answers: the command line's options (see [`set_inputs`]),
/// completed by what the command resolved itself (its own `"inputs"` object, which wins on a shared key).
pub fn with_inputs(value: &serde_json::Value) -> serde_json::Value {
    let mut v = value.clone();
    if let Some(obj) = v.as_object_mut() {
        let mut inputs = INPUTS.get().and_then(|i| i.as_object().cloned()).unwrap_or_default();
        if let Some(own) = obj.get("inputs").and_then(|i| i.as_object()) {
            inputs.extend(own.clone());
        }
        obj.insert("inputs".into(), serde_json::Value::Object(inputs));
    }
    v
}

/// Prints a command's JSON answer, with its `"inputs"`, on stdout (see [`write_stdout`] for a closed pipe).
pub fn print_json(value: &serde_json::Value) -> Result<()> {
    write_stdout(format_args!("{}\n", json_string(&with_inputs(value))))
}
/// Prints a command's answer: its JSON (see [`print_json`]) when `json`, else its text, ending in one newline.
pub fn print_answer(
    json: bool,
    value: impl FnOnce() -> Result<serde_json::Value>,
    text: impl FnOnce() -> String,
) -> Result<()> {
    if json {
        print_json(&value()?)
    } else {
        write_stdout(format_args!("{}\n", text().trim_end_matches('\n')))
    }
}

/// Writes to standard output through the locked handle and flushes. Unlike `println!`, a failed write is
/// an error, not a panic; when the reader has gone away (`iridis … --json | head -c 10`) the error is an
/// `io::Error` of kind `BrokenPipe`, which `main` turns into a clean exit (see [`is_broken_pipe`]).
pub fn write_stdout(args: std::fmt::Arguments<'_>) -> Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_fmt(args)?;
    out.flush()?;
    Ok(())
}

/// Writes raw bytes to standard output, like [`write_stdout`].
pub fn write_stdout_bytes(bytes: &[u8]) -> Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)?;
    out.flush()?;
    Ok(())
}

/// True when an error comes from writing to a pipe whose reader has closed it.
pub fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| c.downcast_ref::<std::io::Error>().is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe))
}

/// `println!` that returns a `Result` instead of panicking when standard output is closed:
/// `outln!("x = {x}")?;`.
#[macro_export]
macro_rules! outln {
    () => { $crate::output::write_stdout(format_args!("\n")) };
    ($($arg:tt)*) => { $crate::output::write_stdout(format_args!("{}\n", format_args!($($arg)*))) };
}
