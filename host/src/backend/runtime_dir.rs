//! A usable `XDG_RUNTIME_DIR` for the Vulkan loader. Without a display session (ssh, CI, containers)
//! the variable is unset, and the window-system code that the Vulkan loader and Mesa's drivers bring
//! into every instance (libwayland-client) prints "error: XDG_RUNTIME_DIR is invalid or not set in
//! the environment." on stderr, though caustic opens no window. A private directory of caustic's own
//! silences it; nothing is written there.
use std::path::PathBuf;

/// Points `XDG_RUNTIME_DIR` at a private directory (`$TMPDIR/caustic-runtime-UID`, mode 0700) when it
/// is unset, empty, relative or not a directory; leaves a usable one alone. It changes the process
/// environment, which races with any thread reading it: call it at the start of `main`, before a
/// thread (rayon's pool, wgpu's) exists.
pub fn ensure_xdg_runtime_dir() {
    let usable = std::env::var_os("XDG_RUNTIME_DIR")
        .map(PathBuf::from)
        .is_some_and(|dir| dir.is_absolute() && dir.is_dir());
    if usable {
        return;
    }
    #[cfg(unix)]
    {
        if let Some(dir) = private_dir() {
            std::env::set_var("XDG_RUNTIME_DIR", dir);
        }
    }
}

/// The user's own directory in the temporary folder, created with mode 0700 on first use. One of that
/// name made by another user first (a shared /tmp), or a link there, is not used: `None`.
#[cfg(unix)]
fn private_dir() -> Option<PathBuf> {
    use std::os::unix::fs::{DirBuilderExt, MetadataExt};
    // SAFETY: getuid has no preconditions and cannot fail.
    let uid = unsafe { libc::getuid() };
    let dir = std::env::temp_dir().join(format!("caustic-runtime-{uid}"));
    if let Err(e) = std::fs::DirBuilder::new().mode(0o700).create(&dir) {
        if e.kind() != std::io::ErrorKind::AlreadyExists {
            return None;
        }
    }
    let meta = std::fs::symlink_metadata(&dir).ok()?;
    (meta.is_dir() && meta.uid() == uid && meta.mode() & 0o077 == 0).then_some(dir)
}
