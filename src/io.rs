//! Files in and out, safely.
//!
//! * Inputs ([`read_text`]) must be regular files (not a FIFO, a device or a directory) of at
//!   most [`MAX_INPUT_BYTES`], in UTF-8; a symlink is followed.
//! * Outputs go through an [`OutputSet`]: every file of a run is checked first — it must not be
//!   one of the run's inputs (compared by file identity, so `./a.yaml` and `a.yaml` and a link to
//!   it are the same file), not named twice, and, if it exists, a regular file (written through
//!   a symlink to its target; a FIFO, device or directory is refused) — then each is written to a
//!   temporary file beside it, and only when all were written are they renamed into place. A run
//!   with several outputs therefore writes all of them or none.

use std::io::Write;
use std::path::{Path, PathBuf};

/// Largest input file read \[bytes\] (task files, URDFs, strength tables, parameter files).
pub const MAX_INPUT_BYTES: u64 = 64 * 1024 * 1024;

/// Why a file could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    #[error("cannot read {path}: {message}")]
    Read { path: String, message: String },
    #[error("cannot write {path}: {message}")]
    Write { path: String, message: String },
}

fn read_err(path: &Path, message: impl Into<String>) -> IoError {
    IoError::Read {
        path: path.display().to_string(),
        message: message.into(),
    }
}

fn write_err(path: &Path, message: impl Into<String>) -> IoError {
    IoError::Write {
        path: path.display().to_string(),
        message: message.into(),
    }
}

/// What kind of thing a path is, in words, when it is not a regular file.
fn not_regular(meta: &std::fs::Metadata) -> Option<&'static str> {
    let ft = meta.file_type();
    if ft.is_file() {
        return None;
    }
    if ft.is_dir() {
        return Some("a directory");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if ft.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if ft.is_char_device() || ft.is_block_device() {
            return Some("a device");
        }
        if ft.is_socket() {
            return Some("a socket");
        }
    }
    Some("not a regular file")
}

/// Checks that `path` is a readable regular file within the size limit.
pub fn check_input(path: &Path) -> Result<std::fs::Metadata, IoError> {
    let meta = std::fs::metadata(path).map_err(|e| read_err(path, e.to_string()))?;
    if let Some(kind) = not_regular(&meta) {
        return Err(read_err(path, format!("is {kind}, not a regular file")));
    }
    if meta.len() > MAX_INPUT_BYTES {
        return Err(read_err(
            path,
            format!(
                "is {} bytes, more than the {} MiB an input may have",
                meta.len(),
                MAX_INPUT_BYTES / (1024 * 1024)
            ),
        ));
    }
    Ok(meta)
}

/// Reads a UTF-8 text input (see the module docs for what is refused).
pub fn read_text(path: &Path) -> Result<String, IoError> {
    check_input(path)?;
    let bytes = std::fs::read(path).map_err(|e| read_err(path, e.to_string()))?;
    String::from_utf8(bytes).map_err(|e| {
        let upto = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = upto.iter().filter(|&&b| b == b'\n').count() + 1;
        read_err(
            path,
            format!("is not UTF-8 text (invalid byte on line {line})"),
        )
    })
}

/// Identity of an existing file (device and inode on Unix; the canonical path elsewhere).
#[derive(Debug, Clone, PartialEq, Eq)]
struct FileId(#[cfg(unix)] (u64, u64), #[cfg(not(unix))] PathBuf);

fn file_id(path: &Path) -> Option<FileId> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        std::fs::metadata(path)
            .ok()
            .map(|m| FileId((m.dev(), m.ino())))
    }
    #[cfg(not(unix))]
    {
        std::fs::canonicalize(path).ok().map(FileId)
    }
}

/// Writes an output's content into its (temporary) file.
type WriteFn<'a> = Box<dyn FnOnce(&mut dyn Write) -> std::io::Result<()> + 'a>;

/// An output's content: bytes made beforehand, or written as they are produced (a long timeline
/// need not sit in memory).
enum Content<'a> {
    Bytes(Vec<u8>),
    Stream(WriteFn<'a>),
}

impl std::fmt::Debug for Content<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Content::Bytes(b) => write!(f, "{} bytes", b.len()),
            Content::Stream(_) => f.write_str("streamed"),
        }
    }
}

/// The files one run reads and writes, written together at the end (all or none).
#[derive(Debug, Default)]
pub struct OutputSet<'a> {
    inputs: Vec<(PathBuf, FileId)>,
    outputs: Vec<(String, PathBuf, Content<'a>)>,
}

impl<'a> OutputSet<'a> {
    pub fn new() -> Self {
        Self::default()
    }

    /// Registers an input of the run (a task, robot, strength file or recording); outputs may
    /// not replace it. Paths that do not exist are ignored.
    pub fn input(&mut self, path: &Path) {
        if let Some(id) = file_id(path) {
            self.inputs.push((path.to_path_buf(), id));
        }
    }

    /// Adds an output, `what` naming it in messages (e.g. "--csv").
    pub fn add(&mut self, what: &str, path: &Path, bytes: Vec<u8>) {
        self.outputs
            .push((what.to_string(), path.to_path_buf(), Content::Bytes(bytes)));
    }

    /// Adds an output written by `write` into its temporary file when the set is written (after
    /// every check), so that it need not be held in memory; the rest as [`OutputSet::add`].
    pub fn add_stream(
        &mut self,
        what: &str,
        path: &Path,
        write: impl FnOnce(&mut dyn Write) -> std::io::Result<()> + 'a,
    ) {
        self.outputs.push((
            what.to_string(),
            path.to_path_buf(),
            Content::Stream(Box::new(write)),
        ));
    }

    /// Where a path really lands: through a symlink, at its target.
    fn target(path: &Path) -> Result<PathBuf, IoError> {
        match std::fs::symlink_metadata(path) {
            Ok(m) if m.file_type().is_symlink() => {
                std::fs::canonicalize(path).or_else(|_| {
                    // a dangling link: write its target path
                    let t = std::fs::read_link(path).map_err(|e| write_err(path, e.to_string()))?;
                    Ok(if t.is_absolute() {
                        t
                    } else {
                        path.parent().unwrap_or(Path::new(".")).join(t)
                    })
                })
            }
            _ => Ok(path.to_path_buf()),
        }
    }

    /// Checks every output (see the module docs) without writing anything.
    pub fn check(&self) -> Result<Vec<PathBuf>, IoError> {
        let mut targets: Vec<(PathBuf, Option<FileId>)> = Vec::new();
        for (what, path, _) in &self.outputs {
            let target = Self::target(path)?;
            let name = target
                .file_name()
                .ok_or_else(|| write_err(path, format!("{what}: not a file path")))?;
            if name.is_empty() {
                return Err(write_err(path, format!("{what}: not a file path")));
            }
            let dir = target
                .parent()
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or(Path::new("."));
            match std::fs::metadata(dir) {
                Ok(m) if m.is_dir() => {}
                _ => {
                    return Err(write_err(
                        path,
                        format!("{what}: directory {} does not exist", dir.display()),
                    ));
                }
            }
            if let Ok(meta) = std::fs::metadata(&target)
                && let Some(kind) = not_regular(&meta)
            {
                return Err(write_err(
                    path,
                    format!("{what}: is {kind}; only regular files are written"),
                ));
            }
            let id = file_id(&target);
            if let Some(id) = &id
                && let Some((input, _)) = self.inputs.iter().find(|(_, i)| i == id)
            {
                return Err(write_err(
                    path,
                    format!(
                        "{what}: is an input of this run ({}); choose another output file",
                        input.display()
                    ),
                ));
            }
            let canon_dir = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
            let key = canon_dir.join(name);
            if let Some(other) = self
                .outputs
                .iter()
                .zip(&targets)
                .find(|(_, (t, tid))| *t == key || (id.is_some() && *tid == id))
            {
                return Err(write_err(
                    path,
                    format!("{what}: is also the output of {}", other.0.0),
                ));
            }
            targets.push((key, id));
        }
        Ok(targets.into_iter().map(|(t, _)| t).collect())
    }

    /// Checks, then writes every output: all to temporary files first, then renamed into place.
    pub fn write_all(self) -> Result<(), IoError> {
        let targets = self.check()?;
        let mut staged: Vec<(PathBuf, PathBuf, PathBuf)> = Vec::new();
        let cleanup = |staged: &[(PathBuf, PathBuf, PathBuf)]| {
            for (tmp, _, _) in staged {
                let _ = std::fs::remove_file(tmp);
            }
        };
        for ((_, path, content), target) in self.outputs.into_iter().zip(&targets) {
            let dir = target.parent().unwrap_or(Path::new("."));
            let name = target.file_name().unwrap_or_default().to_string_lossy();
            let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
            let r = (|| {
                let f = std::fs::File::create(&tmp)?;
                let f = match content {
                    Content::Bytes(bytes) => {
                        let mut f = f;
                        f.write_all(&bytes)?;
                        f
                    }
                    Content::Stream(write) => {
                        let mut w = std::io::BufWriter::with_capacity(1 << 16, f);
                        write(&mut w)?;
                        w.into_inner().map_err(|e| e.into_error())?
                    }
                };
                f.sync_all()
            })();
            if let Err(e) = r {
                let _ = std::fs::remove_file(&tmp);
                cleanup(&staged);
                return Err(write_err(&path, e.to_string()));
            }
            staged.push((tmp, target.clone(), path));
        }
        for (i, (tmp, target, path)) in staged.iter().enumerate() {
            if let Err(e) = std::fs::rename(tmp, target) {
                cleanup(&staged[i..]);
                return Err(write_err(path, e.to_string()));
            }
        }
        Ok(())
    }
}

/// Writes one file atomically (an [`OutputSet`] of one, with `inputs` protected).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    let mut set = OutputSet::new();
    set.add("output", path, bytes.to_vec());
    set.write_all()
}

/// A large output written as it is produced: to a temporary file beside the target, renamed
/// into place by [`TempOutput::commit`] (dropped without commit: removed). Check the target with
/// an [`OutputSet`] first.
pub struct TempOutput {
    tmp: PathBuf,
    target: PathBuf,
    path: PathBuf,
    file: Option<std::io::BufWriter<std::fs::File>>,
}

impl TempOutput {
    /// Opens the temporary file for `path` (through a symlink, at its target).
    pub fn beside(path: &Path) -> Result<Self, IoError> {
        let target = OutputSet::target(path)?;
        let dir = target
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let name = target
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .to_string();
        let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
        let f = std::fs::File::create(&tmp).map_err(|e| write_err(path, e.to_string()))?;
        Ok(TempOutput {
            tmp,
            target: target.clone(),
            path: path.to_path_buf(),
            file: Some(std::io::BufWriter::with_capacity(1 << 16, f)),
        })
    }

    /// Where to write.
    pub fn writer(&mut self) -> &mut dyn Write {
        self.file.as_mut().expect("open until commit")
    }

    /// Flushes and renames the file into place.
    pub fn commit(mut self) -> Result<(), IoError> {
        let f = self.file.take().expect("open until commit");
        let r = f
            .into_inner()
            .map_err(|e| e.into_error())
            .and_then(|f| f.sync_all())
            .and_then(|_| std::fs::rename(&self.tmp, &self.target));
        if r.is_err() {
            let _ = std::fs::remove_file(&self.tmp);
        }
        r.map_err(|e| write_err(&self.path, e.to_string()))
    }
}

impl Drop for TempOutput {
    fn drop(&mut self) {
        if self.file.is_some() {
            self.file = None;
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}
