//! Every file the process reads as input and every file it writes, so that no output can destroy
//! an input and no failed write can destroy an earlier output.
//!
//! Inputs are read through `read`, `read_to_string` or `open`: only regular files (a link to
//! `/dev/zero` or a FIFO is refused rather than read until memory runs out), each remembered by its
//! device and inode. Outputs are written through `write`: refused when the path is, through any
//! symbolic or hard link, a file this process has read (naming both), and otherwise written to a
//! temporary file beside the target, flushed to disk and renamed over it only when complete, so that
//! a full disk or a file-size limit leaves the previous file as it was. `check_output` runs the same
//! refusal before a render starts, so that a user learns of it before waiting for the image.
use anyhow::{bail, Context, Result};
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// An input read so far: its path as given, and its identity.
struct Input {
    path: PathBuf,
    id: FileId,
}

/// A file's identity, the same through every link to it.
#[derive(Clone, Copy, PartialEq, Eq)]
struct FileId {
    device: u64,
    inode: u64,
}

static INPUTS: Mutex<Vec<Input>> = Mutex::new(Vec::new());

#[cfg(unix)]
fn id_of(metadata: &std::fs::Metadata) -> Option<FileId> {
    use std::os::unix::fs::MetadataExt;
    Some(FileId { device: metadata.dev(), inode: metadata.ino() })
}

#[cfg(not(unix))]
fn id_of(_: &std::fs::Metadata) -> Option<FileId> {
    None
}

/// Refuses anything but a regular file (following links), naming `what` and the path.
fn regular(path: &Path, what: &str) -> Result<std::fs::Metadata> {
    let metadata =
        std::fs::metadata(path).with_context(|| format!("cannot read {what} {}", path.display()))?;
    if !metadata.is_file() {
        bail!("cannot read {what} {}: not a regular file", path.display());
    }
    Ok(metadata)
}

/// Remembers `path` as an input of this process (`write` will not overwrite it).
pub fn note_input(path: &Path) {
    let Ok(metadata) = std::fs::metadata(path) else { return };
    if let Some(id) = id_of(&metadata) {
        let mut inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
        if !inputs.iter().any(|i| i.id == id && i.path == path) {
            inputs.push(Input { path: path.to_path_buf(), id });
        }
    }
}

/// Opens input `path` (`what` names it in errors: "PLY mesh", "texture", ...), a regular file.
pub fn open(path: &Path, what: &str) -> Result<File> {
    regular(path, what)?;
    let file = File::open(path).with_context(|| format!("cannot open {what} {}", path.display()))?;
    note_input(path);
    Ok(file)
}

/// The bytes of input `path`, a regular file.
pub fn read(path: &Path, what: &str) -> Result<Vec<u8>> {
    regular(path, what)?;
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {what} {}", path.display()))?;
    note_input(path);
    Ok(bytes)
}

/// The bytes of `path`, a regular file that this process also writes (a checkpoint it resumes
/// from and then replaces): not recorded as an input.
pub fn read_own(path: &Path, what: &str) -> Result<Vec<u8>> {
    regular(path, what)?;
    std::fs::read(path).with_context(|| format!("cannot read {what} {}", path.display()))
}

/// The text of input `path`, a regular file.
pub fn read_to_string(path: &Path, what: &str) -> Result<String> {
    let bytes = read(path, what)?;
    String::from_utf8(bytes).with_context(|| format!("cannot read {what} {}: not UTF-8 text", path.display()))
}

/// The input that `path` is (through any link), if it is one. An input counts only while its own
/// path still leads to the file it read: once it is deleted, its inode number may be given to a new
/// file, which is no input.
fn input_at(path: &Path) -> Option<PathBuf> {
    let id = id_of(&std::fs::metadata(path).ok()?)?;
    let still = |i: &&Input| std::fs::metadata(&i.path).ok().and_then(|m| id_of(&m)) == Some(id);
    let inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
    inputs.iter().filter(|i| i.id == id).find(still).map(|i| i.path.clone())
}

/// Refuses output `path` if it is a file this process has read.
pub fn check_output(path: &Path) -> Result<()> {
    if let Some(input) = input_at(path) {
        if input == path {
            bail!("refusing to write {}: it is one of this command's inputs", path.display());
        }
        bail!(
            "refusing to write {}: it is the same file as {}, one of this command's inputs",
            path.display(),
            input.display()
        );
    }
    Ok(())
}

/// Writes `bytes` to `path` whole or not at all: refused where `path` is an input (`check_output`);
/// written to a temporary file in the target's directory, flushed to disk and renamed over the
/// target, so that a failed write leaves any earlier file at `path` unchanged. A symbolic link at
/// `path` is written through (its target is replaced, the link kept); a new file gets the
/// permissions `File::create` would give it, a replaced one keeps its own.
pub fn write(path: &Path, bytes: &[u8]) -> Result<()> {
    check_output(path)?;
    let target = match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => {
            std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
        }
        _ => path.to_path_buf(),
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let mut temporary = tempfile::Builder::new()
        .prefix(&format!(".{name}."))
        .suffix(".partial")
        .tempfile_in(&dir)
        .with_context(|| {
            format!("cannot write {}: cannot create a file in {}", path.display(), dir.display())
        })?;
    // Through the `File`: tempfile's own `Write` names the temporary path in its errors.
    let file = temporary.as_file_mut();
    let written = file.write_all(bytes).and_then(|_| file.sync_all());
    written.with_context(|| format!("cannot write {}", path.display()))?;
    set_permissions(temporary.as_file(), &target);
    temporary
        .persist(&target)
        .map_err(|e| e.error)
        .with_context(|| format!("cannot move the finished file into place at {}", path.display()))?;
    Ok(())
}

/// Makes a write past the process's file-size limit (`ulimit -f`) fail with an error that the
/// writer reports, instead of killing the process (SIGXFSZ's default) with a temporary file left
/// behind and nothing said.
pub fn write_errors_are_errors() {
    // SAFETY: setting a signal's disposition to "ignore" touches no memory of this process.
    #[cfg(unix)]
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
}

/// Gives the temporary file the permissions of the file it replaces, or of a newly created one.
#[cfg(unix)]
fn set_permissions(file: &File, target: &Path) {
    use std::os::unix::fs::PermissionsExt;
    let mode = match std::fs::metadata(target) {
        Ok(m) => m.permissions().mode() & 0o7777,
        Err(_) => 0o666 & !umask(),
    };
    let _ = file.set_permissions(std::fs::Permissions::from_mode(mode));
}

#[cfg(not(unix))]
fn set_permissions(_: &File, _: &Path) {}

/// The process's file-creation mask (read from /proc; 022 where it cannot be read).
#[cfg(unix)]
fn umask() -> u32 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("Umask:"))
                .and_then(|v| u32::from_str_radix(v.trim(), 8).ok())
        })
        .unwrap_or(0o022)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("caustic-files-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn an_input_is_never_overwritten_through_any_link() {
        let dir = scratch("links");
        let scene = dir.join("scene.xml");
        std::fs::write(&scene, "<scene/>").unwrap();
        read(&scene, "scene").unwrap();
        let hard = dir.join("hard.exr");
        std::fs::hard_link(&scene, &hard).unwrap();
        let soft = dir.join("soft.exr");
        std::os::unix::fs::symlink(&scene, &soft).unwrap();
        for out in [&scene, &hard, &soft] {
            let e = write(out, b"image").unwrap_err().to_string();
            assert!(e.contains("refusing") && e.contains(&out.display().to_string()), "{e}");
        }
        let e = write(&hard, b"image").unwrap_err().to_string();
        assert!(e.contains("scene.xml"), "names the input: {e}");
        assert_eq!(std::fs::read_to_string(&scene).unwrap(), "<scene/>");
        // Another file is written, and a link to a non-input is written through.
        let other = dir.join("other.exr");
        write(&other, b"one").unwrap();
        let link = dir.join("link.exr");
        std::os::unix::fs::symlink(&other, &link).unwrap();
        write(&link, b"two").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read(&other).unwrap(), b"two");
    }

    #[test]
    fn a_deleted_input_protects_nothing() {
        let dir = scratch("deleted");
        let texture = dir.join("texture.png");
        std::fs::write(&texture, "texels").unwrap();
        read(&texture, "texture").unwrap();
        std::fs::remove_file(&texture).unwrap();
        // A new file (which may be given the deleted one's inode) and the same name again.
        let out = dir.join("out.png");
        std::fs::write(&out, "x").unwrap();
        write(&out, b"image").unwrap();
        write(&texture, b"image").unwrap();
    }

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let dir = scratch("failed");
        let out = dir.join("image.png");
        write(&out, b"old").unwrap();
        // A directory that cannot take the temporary file stands in for a full disk.
        let missing = dir.join("gone").join("image.png");
        assert!(write(&missing, b"new").is_err());
        assert_eq!(std::fs::read(&out).unwrap(), b"old");
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, vec![std::ffi::OsString::from("image.png")], "no temporary left");
    }

    #[test]
    fn only_regular_files_are_read() {
        let e = read(Path::new("/dev/zero"), "mesh").unwrap_err().to_string();
        assert!(e.contains("not a regular file") && e.contains("/dev/zero"), "{e}");
        let dir = scratch("dir");
        let e = read_to_string(&dir, "scene").unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{e}");
    }

    #[test]
    fn a_new_file_gets_the_usual_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch("mode");
        let out = dir.join("a.ppm");
        write(&out, b"P6").unwrap();
        let mode = std::fs::metadata(&out).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o666 & !umask());
    }
}
