//! Writing results: every file is written to a temporary file beside its destination and renamed into
//! place, so a failed run never leaves a half-written output.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result};

/// Writes `path` atomically with the bytes that `write` produces.
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        anyhow::bail!("cannot write {}: folder {} does not exist", path.display(), dir.display());
    }
    let mut tmp = tempfile::Builder::new()
        .prefix(".iridis-")
        .suffix(".tmp")
        .tempfile_in(dir)
        .with_context(|| format!("cannot create a file in {}", dir.display()))?;
    {
        let mut buffered = std::io::BufWriter::new(tmp.as_file_mut());
        write(&mut buffered)?;
        buffered.flush().with_context(|| format!("cannot write {}", path.display()))?;
    }
    // Temporary files are created private (0600); a result is an ordinary file that others may read.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file().set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    tmp.persist(path).map_err(|e| e.error).with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

/// Writes bytes atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic(path, |w| Ok(w.write_all(bytes)?))
}

/// Writes an 8-bit RGB image as PNG, atomically.
pub fn write_png_rgb8(path: &Path, width: u32, height: u32, rgb: &[u8]) -> Result<()> {
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(rgb, width, height, image::ExtendedColorType::Rgb8)
        .map_err(|e| anyhow::anyhow!("cannot encode PNG: {e}"))?;
    write_bytes(path, &bytes)
}

use image::ImageEncoder;

/// Prints a value as pretty JSON on stdout (see [`write_stdout`] for a closed pipe).
pub fn print_json(value: &serde_json::Value) -> Result<()> {
    write_stdout(format_args!("{}\n", serde_json::to_string_pretty(value)?))
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
