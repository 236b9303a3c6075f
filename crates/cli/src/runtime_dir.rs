//! A private `XDG_RUNTIME_DIR` for processes started without a valid one (a service, `sudo`, a container,
//! `env -i`). Graphics drivers look for their sockets there, and libwayland-client prints
//! "error: XDG_RUNTIME_DIR is invalid or not set in the environment." when it is missing — on every `--gpu`
//! run, although nothing is wrong. An empty folder of our own (mode 0700, as the XDG Base Directory
//! specification asks of this folder) answers the drivers and is removed when the process ends.

/// Sets `XDG_RUNTIME_DIR` to a fresh private folder when it is unset or does not name an existing absolute
/// folder; returns the folder's guard (the folder is deleted when it is dropped). Call it first in `main`,
/// before any thread starts: changing the environment is only sound while the process has one thread.
pub fn ensure() -> Option<tempfile::TempDir> {
    let valid = std::env::var_os("XDG_RUNTIME_DIR")
        .map(std::path::PathBuf::from)
        .is_some_and(|p| p.is_absolute() && p.is_dir());
    if valid {
        return None;
    }
    let dir = tempfile::Builder::new().prefix("iridis-runtime-").tempdir().ok()?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o700)).ok()?;
    }
    std::env::set_var("XDG_RUNTIME_DIR", dir.path());
    Some(dir)
}
