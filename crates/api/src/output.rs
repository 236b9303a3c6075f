//! Writing results. A run's outputs form one set ("output plan"): a command declares each output path before
//! it computes anything ([`declare`]: the folder exists, the extension names a format the option writes, no
//! path is used twice), every write goes to a temporary file beside its destination, and the front end renames all
//! of them into place only when the whole command has succeeded ([`commit`]); on an error they are deleted
//! ([`discard`]). A failed run therefore leaves no output at all, not some of them, nor a folder it made for
//! them ([`create_dir`]).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use anyhow::{bail, Context, Result};
use image::ImageEncoder;

/// One output of the run: where it goes and the temporary file that holds it until [`commit`].
struct Staged {
    /// The destination as the user wrote it.
    path: PathBuf,
    /// The destination with its folder made absolute, to tell two spellings of one file apart.
    key: PathBuf,
    /// The option that named it (`-o`, `--raw`, …), for messages; empty for files a command names itself.
    flag: String,
    /// The written content, created at the first write (not at the declaration: a run interrupted while it
    /// computes leaves no temporary file behind).
    tmp: Option<tempfile::NamedTempFile>,
}

static RUN: Mutex<Vec<Staged>> = Mutex::new(Vec::new());

/// The folders this run created for its outputs ([`create_dir`]), outermost first: a failed run removes them.
static CREATED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn created() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    CREATED.lock().unwrap_or_else(|e| e.into_inner())
}

/// Creates an output folder of this run (`-o DIR`, `--maps DIR`) and its missing parents. Those it creates
/// belong to the run's outputs: a failed run ([`discard`]) removes them again, so it leaves no empty folder
/// either; a folder that existed is left as it was.
pub fn create_dir(dir: &Path) -> Result<()> {
    if dir.is_file() {
        bail!(
            "cannot create {}: it is a file, and this output is a folder: give a folder's name (new or existing)",
            dir.display()
        );
    }
    let missing: Vec<PathBuf> =
        dir.ancestors().take_while(|d| !d.as_os_str().is_empty() && !d.exists()).map(Path::to_path_buf).collect();
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    created().extend(missing.into_iter().rev());
    Ok(())
}

/// A file being written: [`write_atomic`]'s writer.
pub trait WriteSeek: Write + std::io::Seek {}
impl<T: Write + std::io::Seek> WriteSeek for T {}

fn run() -> std::sync::MutexGuard<'static, Vec<Staged>> {
    RUN.lock().unwrap_or_else(|e| e.into_inner())
}

fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// The destination with its (existing) folder resolved, so `m.png` and `./m.png` are one file.
fn key_of(path: &Path) -> Result<PathBuf> {
    let dir = folder_of(path);
    if !dir.is_dir() {
        // An I/O error in the chain: Python raises OSError for it, as `open` would.
        let missing = format!("cannot write {}: folder {} does not exist", path.display(), dir.display());
        return Err(std::io::Error::new(std::io::ErrorKind::NotFound, missing).into());
    }
    let name = path.file_name().with_context(|| format!("{} names no file", path.display()))?;
    let dir = dir.canonicalize().with_context(|| format!("cannot open folder {}", dir.display()))?;
    Ok(dir.join(name))
}

/// The lower-case extension of `path` if it is one of `supported`; otherwise an error that lists them.
/// The one rule for every output: the format follows the extension, or the output is refused.
pub fn format_of(flag: &str, path: &Path, supported: &[&str]) -> Result<String> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext {
        Some(e) if supported.contains(&e.as_str()) => Ok(e),
        _ => {
            let list = match supported.split_last() {
                Some((last, [])) => format!(".{last}"),
                Some((last, rest)) => {
                    format!("{} or .{last}", rest.iter().map(|e| format!(".{e}")).collect::<Vec<_>>().join(", "))
                }
                None => String::new(),
            };
            let what = match path.extension().and_then(|e| e.to_str()) {
                Some(e) => format!("cannot write .{e} files"),
                None => "the file name has no extension to tell the format".to_string(),
            };
            let flag = if flag.is_empty() { String::new() } else { format!("{flag} ") };
            bail!("{flag}{}: {what} here; name it {list}", path.display())
        }
    }
}

fn stage(flag: &str, path: &Path, run: &mut Vec<Staged>) -> Result<usize> {
    let key = key_of(path)?;
    if let Some(other) = run.iter().find(|s| s.key == key) {
        let by = |f: &str| if f.is_empty() { String::new() } else { format!(" ({f})") };
        bail!(
            "{}{} and {}{} are the same file: give each output its own path",
            other.path.display(),
            by(&other.flag),
            path.display(),
            by(flag)
        );
    }
    // Creating (and at once deleting) a file proves the folder writable before the work starts.
    temporary(path)?;
    run.push(Staged { path: path.to_path_buf(), key, flag: flag.to_string(), tmp: None });
    Ok(run.len() - 1)
}

fn temporary(path: &Path) -> Result<tempfile::NamedTempFile> {
    let dir = folder_of(path);
    tempfile::Builder::new()
        .prefix(".iridis-")
        .suffix(".tmp")
        .tempfile_in(dir)
        .with_context(|| format!("cannot write {}: cannot create a file in {}", path.display(), dir.display()))
}

/// Declares an output of this run before any computing: checks that the extension is one of `supported`
/// (returned in lower case), that the folder exists and is writable, and that no other output of the run has
/// the same path. `flag` names the option in messages (`-o`, `--raw`).
pub fn declare(flag: &str, path: &Path, supported: &[&str]) -> Result<String> {
    let ext = format_of(flag, path, supported)?;
    stage(flag, path, &mut run())?;
    Ok(ext)
}

/// [`declare`] for an optional output.
pub fn declare_opt(flag: &str, path: Option<&Path>, supported: &[&str]) -> Result<Option<String>> {
    path.map(|p| declare(flag, p, supported)).transpose()
}

/// Writes `path` as part of this run's outputs: into its temporary file, renamed into place by [`commit`]
/// once the command has succeeded. A path that was not declared is declared now (a command's own files, such
/// as a gallery's pages); one path written twice is an error. The writer seeks, so a zip archive (`.npz`) streams
/// into the file rather than being built in memory first.
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn WriteSeek) -> Result<()>) -> Result<()> {
    let key = key_of(path)?;
    let i = {
        let mut run = run();
        match run.iter().position(|s| s.key == key) {
            Some(i) if run[i].tmp.is_some() => bail!("{} is written twice in one run", path.display()),
            Some(i) => i,
            None => stage("", path, &mut run)?,
        }
    };
    // Written without the lock (entries are only ever appended, so `i` stays this output's index).
    let mut tmp = temporary(path)?;
    {
        let mut buffered = std::io::BufWriter::new(tmp.as_file_mut());
        write(&mut buffered)?;
        buffered.flush().with_context(|| format!("cannot write {}", path.display()))?;
    }
    let mut run = run();
    if run[i].tmp.is_some() {
        bail!("{} is written twice in one run", path.display());
    }
    run[i].tmp = Some(tmp);
    Ok(())
}

/// Renames every written output of the run into place (called by `main` when the command succeeded);
/// declared outputs that were never written leave nothing behind.
pub fn commit() -> Result<()> {
    created().clear();
    for s in std::mem::take(&mut *run()) {
        let Some(tmp) = s.tmp else { continue };
        // Temporary files are created private (0600); a result is an ordinary file that others may read.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            tmp.as_file().set_permissions(std::fs::Permissions::from_mode(0o644))?;
        }
        tmp.persist(&s.path).map_err(|e| e.error).with_context(|| format!("cannot write {}", s.path.display()))?;
    }
    Ok(())
}

/// Deletes the run's temporary files (called by `main` when the command failed): no output appears.
pub fn discard() {
    run().clear();
    // Innermost first; a folder that holds anything else (a user's file put there meanwhile) stays.
    for dir in std::mem::take(&mut *created()).iter().rev() {
        let _ = std::fs::remove_dir(dir);
    }
}

/// Writes a file at once, atomically, outside the run's set: for files the run reads back itself (the
/// example scenes a benchmark renders).
pub fn write_now(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = folder_of(path);
    let mut tmp = tempfile::Builder::new()
        .prefix(".iridis-")
        .suffix(".tmp")
        .tempfile_in(dir)
        .with_context(|| format!("cannot create a file in {}", dir.display()))?;
    tmp.write_all(bytes).with_context(|| format!("cannot write {}", path.display()))?;
    tmp.persist(path).map_err(|e| e.error).with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

/// Writes bytes as part of the run's outputs.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic(path, |w| Ok(w.write_all(bytes)?))
}

/// Writes an 8-bit RGB image as PNG, as part of the run's outputs.
pub fn write_png_rgb8(path: &Path, width: u32, height: u32, rgb: &[u8]) -> Result<()> {
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(rgb, width, height, image::ExtendedColorType::Rgb8)
        .map_err(|e| anyhow::anyhow!("cannot encode PNG: {e}"))?;
    write_bytes(path, &bytes)
}

/// JSON text for people and files alike: objects indented one key a line, arrays of numbers (and other
/// scalars) on one line, so an 80 001-point spectrum is one line per quantity instead of one per number.
pub fn json_string(value: &serde_json::Value) -> String {
    let mut out = String::new();
    write_json(value, 0, &mut out);
    out
}

fn write_json(v: &serde_json::Value, indent: usize, out: &mut String) {
    use serde_json::Value;
    let pad = |n: usize, out: &mut String| out.extend(std::iter::repeat_n(' ', n));
    match v {
        Value::Object(map) if !map.is_empty() => {
            out.push_str("{\n");
            for (i, (k, x)) in map.iter().enumerate() {
                pad(indent + 2, out);
                out.push_str(&Value::String(k.clone()).to_string());
                out.push_str(": ");
                write_json(x, indent + 2, out);
                out.push_str(if i + 1 < map.len() { ",\n" } else { "\n" });
            }
            pad(indent, out);
            out.push('}');
        }
        Value::Array(items) if items.iter().any(|x| x.is_array() || x.is_object()) => {
            out.push_str("[\n");
            for (i, x) in items.iter().enumerate() {
                pad(indent + 2, out);
                write_json(x, indent + 2, out);
                out.push_str(if i + 1 < items.len() { ",\n" } else { "\n" });
            }
            pad(indent, out);
            out.push(']');
        }
        Value::Array(items) => {
            out.push('[');
            for (i, x) in items.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                out.push_str(&x.to_string());
            }
            out.push(']');
        }
        scalar => out.push_str(&scalar.to_string()),
    }
}
