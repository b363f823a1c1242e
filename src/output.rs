//! Writing outputs: files whole or not at all, never over something that is not a file, and
//! folders only when they are new, empty or Ontogeny's own.
//!
//! Every file Ontogeny writes for its user (pictures, animations, plots, recordings, exported
//! models, reports) goes through [`write`](fn@write) or [`write_with`]: the content goes to a fresh
//! temporary file in the target's own directory, which is then renamed over the target. A
//! reader sees the old file or the new one, never half of one, and a failure leaves the old one
//! as it was. A target that exists and is not a regular file (a directory, a device such as
//! `/dev/null`, a fifo, a socket, or a symbolic link, which is refused rather than followed or
//! replaced) is refused before anything is written. The one exception, [`replace_tail`],
//! grows a log in place, for a file that can be written anew from a record of truth.
//!
//! Every folder a verb writes its outputs into is first made ready by
//! [`prepare_folder`] ([`folder`]): it must be missing, empty, or marked as Ontogeny's for the
//! same kind of output, so that no file of the user's is replaced.
//!
//! What this module does not own: deciding where outputs go.

pub mod folder;

pub use folder::{FolderKind, check_folder, prepare_folder};

use std::fs::File;
use std::io::{self, BufWriter, Seek, Write};
use std::path::{Path, PathBuf};

/// Why an output file was not written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The target exists and is not a regular file (nor a link to one: links are refused).
    #[error("{} exists and is not a regular file; refusing to replace it", path.display())]
    NotARegularFile {
        /// The target.
        path: PathBuf,
    },
    /// The target is a symbolic link to nothing: neither followed nor replaced.
    #[error(
        "{} is a symbolic link to {}, which does not exist; refusing to write through it: \
         remove the link, or choose another path",
        path.display(),
        target.display()
    )]
    DanglingLink {
        /// The target.
        path: PathBuf,
        /// Where the link points.
        target: PathBuf,
    },
    /// An output folder exists and holds files Ontogeny did not write there for this kind of
    /// output ([`folder`]).
    #[error(
        "{} already holds files that {verb} did not write there ({found}); refusing to write \
         into it: {advice}",
        path.display()
    )]
    NotOurFolder {
        /// The folder.
        path: PathBuf,
        /// One of the files found in it.
        found: String,
        /// The command that writes this kind of folder.
        verb: &'static str,
        /// What to do instead.
        advice: String,
    },
    /// An output folder's path is taken by something that is not a folder.
    #[error(
        "{} exists and is not a folder; refusing to write into it: choose a new or empty folder",
        path.display()
    )]
    NotAFolder {
        /// The path.
        path: PathBuf,
    },
    /// The file could not be written (or its temporary file made, or renamed into place).
    #[error("cannot write {}: {cause}", path.display())]
    Io {
        /// The target.
        path: PathBuf,
        /// What went wrong: part of the message, and so not a `source` that a chain of causes
        /// would print a second time.
        cause: io::Error,
    },
}

/// Refuses a target that exists and is not a regular file; a missing target, or a regular
/// file (which [`write`](fn@write) replaces), passes. A symbolic link is refused whatever it points to,
/// since replacing it would cut the link and following it would write somewhere else; one that
/// points nowhere is refused as such ([`OutputError::DanglingLink`]).
pub fn check_target(path: &Path) -> Result<(), OutputError> {
    match std::fs::symlink_metadata(path) {
        Ok(metadata) if metadata.file_type().is_file() => Ok(()),
        Ok(metadata) if metadata.is_symlink() && !path.exists() => Err(OutputError::DanglingLink {
            path: path.into(),
            target: std::fs::read_link(path).unwrap_or_default(),
        }),
        Ok(_) => Err(OutputError::NotARegularFile { path: path.into() }),
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
        Err(source) => Err(OutputError::Io {
            path: path.into(),
            cause: source,
        }),
    }
}

/// Writes `bytes` to `path`, whole or not at all (see the module's documentation).
pub fn write(path: &Path, bytes: impl AsRef<[u8]>) -> Result<(), OutputError> {
    write_with(path, |out| {
        out.write_all(bytes.as_ref())
            .map_err(|source| OutputError::Io {
                path: path.into(),
                cause: source,
            })
    })
}

/// Replaces what follows the first `at` bytes of the regular file `path` with `bytes`, in
/// place: for a file that grows at its end (a log), at a cost that does not grow with the
/// file. Unlike [`write`](fn@write), a process killed meanwhile may leave the file cut short
/// or half written: use it only for a file that can be written anew from a record of truth. A
/// target that is missing or not a regular file is refused ([`check_target`]; a missing one as
/// [`OutputError::Io`]).
pub fn replace_tail(path: &Path, at: u64, bytes: impl AsRef<[u8]>) -> Result<(), OutputError> {
    check_target(path)?;
    let io_error = |source| OutputError::Io {
        path: path.into(),
        cause: source,
    };
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .open(path)
        .map_err(io_error)?;
    file.set_len(at).map_err(io_error)?;
    file.seek(io::SeekFrom::Start(at)).map_err(io_error)?;
    file.write_all(bytes.as_ref()).map_err(io_error)
}

/// Writes to `path` what `fill` writes, whole or not at all: `fill` writes to a temporary file
/// beside `path`, which replaces `path` only if `fill` succeeds. An error of `fill` is returned
/// as it is; the temporary file is removed.
pub fn write_with<E: From<OutputError>>(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<File>) -> Result<(), E>,
) -> Result<(), E> {
    check_target(path)?;
    let io_error = |source| OutputError::Io {
        path: path.into(),
        cause: source,
    };
    let directory = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .ok_or_else(|| io_error(io::Error::other("the path names no file")))?;
    let mut prefix = std::ffi::OsString::from(".");
    prefix.push(name);
    prefix.push(".");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    // The permissions of a file made by `std::fs::write` (read and write for all, less the
    // process's umask), not the private ones of a temporary file.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    if !directory.is_dir() {
        let what = if directory.exists() {
            "is not a folder"
        } else {
            "does not exist"
        };
        let cause = io::Error::new(
            io::ErrorKind::NotFound,
            format!("{} {what}", directory.display()),
        );
        return Err(io_error(cause).into());
    }
    // tempfile's errors name the temporary file, which the user never asked for: keep the
    // system's words alone.
    let temporary = builder
        .tempfile_in(directory)
        .map_err(|e| io_error(e.raw_os_error().map_or(e, io::Error::from_raw_os_error)))?;
    let mut out = BufWriter::new(temporary.reopen().map_err(io_error)?);
    fill(&mut out)?;
    out.into_inner()
        .map_err(|e| io_error(e.into_error()))?
        .sync_all()
        .map_err(io_error)?;
    // Checked again just before the rename, so that a target that became something else while
    // the content was written is not replaced.
    check_target(path)?;
    temporary.persist(path).map_err(|e| io_error(e.error))?;
    Ok(())
}

/// The line that tells the user which files a command wrote (a message, for standard
/// error): `wrote A`, `wrote A and B`, `wrote A, B and C`.
pub fn wrote<P: AsRef<Path>>(paths: &[P]) -> String {
    let names: Vec<String> = paths
        .iter()
        .map(|p| p.as_ref().display().to_string())
        .collect();
    match names.split_last() {
        None => "wrote nothing".to_string(),
        Some((last, [])) => format!("wrote {last}"),
        Some((last, rest)) => format!("wrote {} and {last}", rest.join(", ")),
    }
}

/// Moves the file `source` (written by another program, e.g. a browser's screenshot) to
/// `target` as [`write`](fn@write) would write it; `source` is left in place for its owner to remove.
pub fn copy_into_place(source: &Path, target: &Path) -> Result<(), OutputError> {
    let bytes = crate::input::read(source).map_err(|e| OutputError::Io {
        path: source.into(),
        cause: e,
    })?;
    write(target, bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_in_a_missing_folder_is_refused_in_words_that_name_the_folder_once() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("nodir").join("x.xml");
        let error = write(&path, "x").unwrap_err();
        assert_eq!(
            error.to_string(),
            format!(
                "cannot write {}: {} does not exist",
                path.display(),
                dir.path().join("nodir").display()
            )
        );
        assert!(
            std::error::Error::source(&error).is_none(),
            "no cause printed twice"
        );
    }

    #[test]
    fn the_files_written_are_listed_in_one_line() {
        assert_eq!(wrote(&["a"]), "wrote a");
        assert_eq!(wrote(&["a", "b"]), "wrote a and b");
        assert_eq!(wrote(&["d/a", "d/b", "d/c"]), "wrote d/a, d/b and d/c");
    }

    #[test]
    fn a_new_file_is_written_and_nothing_else_is_left_beside_it() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        write(&path, "hello").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "hello");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1);
    }

    #[test]
    fn a_regular_file_is_replaced_whole() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        std::fs::write(&path, "an old and longer content").unwrap();
        write(&path, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
    }

    #[test]
    fn a_tail_is_replaced_in_place_after_the_head_kept() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("log.txt");
        std::fs::write(&path, "line 0\nnote: old\n").unwrap();
        replace_tail(&path, 7, "line 1\nnote: new\n").unwrap();
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            "line 0\nline 1\nnote: new\n"
        );
        // A missing file is not created, and a link is not followed.
        let missing = dir.path().join("missing.txt");
        let error = replace_tail(&missing, 0, "x").unwrap_err();
        assert!(matches!(error, OutputError::Io { .. }), "{error:?}");
        assert!(!missing.exists());
        #[cfg(unix)]
        {
            let link = dir.path().join("link.txt");
            std::os::unix::fs::symlink(&path, &link).unwrap();
            let error = replace_tail(&link, 0, "x").unwrap_err();
            assert!(
                matches!(error, OutputError::NotARegularFile { .. }),
                "{error:?}"
            );
            assert_eq!(
                std::fs::read_to_string(&path).unwrap(),
                "line 0\nline 1\nnote: new\n"
            );
        }
    }

    #[test]
    fn a_failed_fill_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        std::fs::write(&path, "old").unwrap();
        let result = write_with(&path, |out| {
            out.write_all(b"half").map_err(|source| OutputError::Io {
                path: path.clone(),
                cause: source,
            })?;
            Err(OutputError::Io {
                path: path.clone(),
                cause: io::Error::other("the encoder failed"),
            })
        });
        assert!(result.is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_directory_is_refused_and_left_intact() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("taken");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("inside"), "kept").unwrap();
        let error = write(&target, "x").unwrap_err();
        assert!(matches!(error, OutputError::NotARegularFile { .. }));
        assert_eq!(
            error.to_string(),
            format!(
                "{} exists and is not a regular file; refusing to replace it",
                target.display()
            )
        );
        assert_eq!(
            std::fs::read_to_string(target.join("inside")).unwrap(),
            "kept"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_device_a_socket_and_a_link_are_refused() {
        use std::os::unix::fs::FileTypeExt;
        let dir = tempfile::tempdir().unwrap();
        let socket = dir.path().join("socket");
        let _listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
        let file = dir.path().join("file");
        std::fs::write(&file, "kept").unwrap();
        let link = dir.path().join("link");
        std::os::unix::fs::symlink(&file, &link).unwrap();
        for target in [Path::new("/dev/null"), &socket, &link] {
            assert!(
                matches!(write(target, "x"), Err(OutputError::NotARegularFile { .. })),
                "{}",
                target.display()
            );
        }
        assert!(
            std::fs::symlink_metadata(&socket)
                .unwrap()
                .file_type()
                .is_socket()
        );
        assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "kept");
    }

    #[cfg(unix)]
    #[test]
    fn a_dangling_link_is_refused_in_words_and_left_as_it_is() {
        let dir = tempfile::tempdir().unwrap();
        let link = crate::input::dangling_link(dir.path(), "out.mjcf", "missing/model.xml");
        assert_eq!(
            write(&link, "x").unwrap_err().to_string(),
            format!(
                "{} is a symbolic link to missing/model.xml, which does not exist; refusing to \
                 write through it: remove the link, or choose another path",
                link.display()
            )
        );
        assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[cfg(unix)]
    #[test]
    fn a_new_file_gets_the_permissions_of_an_ordinary_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let ours = dir.path().join("ours");
        let ordinary = dir.path().join("ordinary");
        write(&ours, "x").unwrap();
        std::fs::write(&ordinary, "x").unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode();
        assert_eq!(mode(&ours), mode(&ordinary));
    }
}
