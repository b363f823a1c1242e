//! The lock that makes a run or comparison directory one process's at a time.
//!
//! `evolve --out`, `evolve --resume`, `compare` and `compare --resume` hold an exclusive
//! advisory lock (`flock`, through the standard library's [`std::fs::File::try_lock`]) on the
//! file `.lock` in the directory for as long as they write it. A second process is refused at
//! once with a message naming the holder (its process id and command line, which the holder
//! writes into the file). The operating system drops the lock when the holder ends, however
//! it ends (`kill -9` included), so a stale `.lock` file never blocks anyone. Readers (the
//! viewer, `runs show`, `replay`, `compare --merge`) do not take it.

use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};

/// The lock file's name inside a locked directory.
pub const LOCK_FILE: &str = ".lock";

/// Why a directory could not be locked.
#[derive(Debug, thiserror::Error)]
pub enum LockError {
    /// Another process holds the lock.
    #[error(
        "{} is in use by another ontogeny process ({holder}); wait for it to finish, or stop it",
        dir.display()
    )]
    Held {
        /// The directory.
        dir: PathBuf,
        /// Who holds it, as the holder wrote it (or "holder unknown").
        holder: String,
    },
    /// The lock file could not be made or locked.
    #[error("{}: cannot lock it: {source}", path.display())]
    Io {
        /// The lock file.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
}

/// An exclusive lock on a directory, held until it is dropped.
#[derive(Debug)]
pub struct DirectoryLock {
    // Holding the open file holds the lock; closing it (drop) releases it.
    _file: File,
}

impl DirectoryLock {
    /// Locks `dir` (which must exist), or says who holds it. Never waits.
    pub fn acquire(dir: &Path) -> Result<DirectoryLock, LockError> {
        let path = dir.join(LOCK_FILE);
        let io = |source| LockError::Io {
            path: path.clone(),
            source,
        };
        // Not truncated on open: the holder's description stays readable to the refused.
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(io)?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                let mut holder = String::new();
                // The holder writes a line; a file grown past that is not read on.
                let _ = (&mut file).take(4096).read_to_string(&mut holder);
                let holder = holder.trim();
                return Err(LockError::Held {
                    dir: dir.to_path_buf(),
                    holder: if holder.is_empty() {
                        "holder unknown".to_string()
                    } else {
                        holder.to_string()
                    },
                });
            }
            Err(TryLockError::Error(e)) => return Err(io(e)),
        }
        let command: Vec<String> = std::env::args().collect();
        let description = format!("pid {}: {}", std::process::id(), command.join(" "));
        file.set_len(0)
            .and_then(|()| file.rewind())
            .and_then(|()| file.write_all(description.as_bytes()))
            .map_err(io)?;
        Ok(DirectoryLock { _file: file })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_lock_on_a_directory_is_refused_naming_the_holder_until_the_first_is_dropped() {
        let scratch = tempfile::tempdir().unwrap();
        let dir = scratch.path();
        let first = DirectoryLock::acquire(dir).unwrap();
        let refused = DirectoryLock::acquire(dir).unwrap_err();
        let message = refused.to_string();
        assert!(matches!(refused, LockError::Held { .. }), "{message}");
        assert!(
            message.contains(&format!("pid {}", std::process::id())),
            "{message}"
        );
        drop(first);
        DirectoryLock::acquire(dir).unwrap();
    }
}
