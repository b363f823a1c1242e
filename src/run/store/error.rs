//! Why a run store could not be created, opened, read or written ([`StoreError`]), and the
//! classification of SQLite's errors into those plain errors.

use std::path::{Path, PathBuf};

use rusqlite::ErrorCode;

use super::schema::{OLDEST_SCHEMA_VERSION, SCHEMA_VERSION};

/// Why a run store could not be created, opened, read or written. Every message names the file.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    /// `create` was given a path that exists.
    #[error("{} already exists; a new run needs a new file (nothing was changed)", path.display())]
    Exists {
        /// The database's path.
        path: PathBuf,
    },
    /// `open` was given a path that does not exist.
    #[error("{} does not exist", path.display())]
    Missing {
        /// The database's path.
        path: PathBuf,
    },
    /// The file is not an SQLite database, or a database but not a run store.
    #[error("{} is not a run database ({reason})", path.display())]
    NotARunStore {
        /// The database's path.
        path: PathBuf,
        /// What is wrong, in plain words.
        reason: String,
    },
    /// The file is a damaged database (truncated, overwritten).
    #[error("{} is corrupt: {detail}", path.display())]
    Corrupt {
        /// The database's path.
        path: PathBuf,
        /// What SQLite found.
        detail: String,
    },
    /// A record does not match the checksum stored with it, or a generation lacks some of
    /// its individuals: the file was damaged (a flipped bit, an edit) where SQLite's own
    /// checks do not look. Nothing of it is used.
    #[error(
        "{}: the record of {what} is damaged ({detail}); nothing was used or written: the run cannot go on from it (a copy made before the damage can)",
        path.display()
    )]
    Damaged {
        /// The database's path.
        path: PathBuf,
        /// Which record: "individual 3 of generation 1", "generation 1", "the run".
        what: String,
        /// What is wrong with it.
        detail: String,
    },
    /// The run store was written by a newer schema than this program reads.
    #[error(
        "{} was written by a newer schema (version {found}); this ontogeny reads version {SCHEMA_VERSION}: update ontogeny",
        path.display()
    )]
    NewerSchema {
        /// The database's path.
        path: PathBuf,
        /// The schema version found in the file.
        found: i64,
    },
    /// The run store was written by an older schema that this program cannot read.
    #[error(
        "{} was written by an older schema (version {found}) that this ontogeny (schema versions {OLDEST_SCHEMA_VERSION} to {SCHEMA_VERSION}) cannot read",
        path.display()
    )]
    OlderSchema {
        /// The database's path.
        path: PathBuf,
        /// The schema version found in the file.
        found: i64,
    },
    /// A record given to `write_generation` does not fit the store; nothing was written.
    #[error("{}: cannot write generation {generation} (nothing of it was stored): {reason}", path.display())]
    InvalidRecord {
        /// The database's path.
        path: PathBuf,
        /// The generation being written.
        generation: u32,
        /// What is wrong.
        reason: String,
    },
    /// A file-system error outside SQLite.
    #[error("{}: {action}: {source}", path.display())]
    Io {
        /// The database's path.
        path: PathBuf,
        /// What was being done.
        action: &'static str,
        /// The error.
        #[source]
        source: std::io::Error,
    },
    /// Any other SQLite error.
    #[error("{}: {action}: {source}", path.display())]
    Sqlite {
        /// The database's path.
        path: PathBuf,
        /// What was being done.
        action: String,
        /// SQLite's error.
        #[source]
        source: rusqlite::Error,
    },
}

impl StoreError {
    /// Whether the error is the input's: a file that is no run store, is damaged, is missing
    /// or already there, or of a schema this program does not read (the command line exits
    /// with 2). Otherwise it is ontogeny's own failure to create, read or write a store
    /// (exit code 1): the disk is full, SQLite refused, a record did not fit the schema.
    pub fn is_bad_input(&self) -> bool {
        match self {
            StoreError::Exists { .. }
            | StoreError::Missing { .. }
            | StoreError::NotARunStore { .. }
            | StoreError::Corrupt { .. }
            | StoreError::Damaged { .. }
            | StoreError::NewerSchema { .. }
            | StoreError::OlderSchema { .. } => true,
            StoreError::InvalidRecord { .. }
            | StoreError::Io { .. }
            | StoreError::Sqlite { .. } => false,
        }
    }
}

/// A file-system error of the store at `path` while it did `action` (e.g. "cannot read it").
pub(super) fn io_error(path: &Path, action: &'static str, source: std::io::Error) -> StoreError {
    StoreError::Io {
        path: path.into(),
        action,
        source,
    }
}

pub(super) fn sqlite(path: &Path, action: &str, source: rusqlite::Error) -> StoreError {
    StoreError::Sqlite {
        path: path.into(),
        action: action.into(),
        source,
    }
}

/// Turns SQLite's "not a database" and "malformed" codes into their plain errors.
pub(super) fn classify(path: &Path, action: &str, e: rusqlite::Error) -> StoreError {
    match e.sqlite_error_code() {
        Some(ErrorCode::NotADatabase) => StoreError::NotARunStore {
            path: path.into(),
            reason: "file is not a database".into(),
        },
        Some(ErrorCode::DatabaseCorrupt) => StoreError::Corrupt {
            path: path.into(),
            detail: e.to_string(),
        },
        _ => sqlite(path, action, e),
    }
}

pub(super) fn write_error(
    path: &Path,
    generation: u32,
    what: String,
    e: rusqlite::Error,
) -> StoreError {
    match e.sqlite_error_code() {
        Some(ErrorCode::ConstraintViolation) => StoreError::InvalidRecord {
            path: path.into(),
            generation,
            reason: format!("{what} breaks a rule of the schema ({e})"),
        },
        _ => match classify(path, "", e) {
            StoreError::Sqlite { source, .. } => StoreError::Sqlite {
                path: path.into(),
                action: format!(
                    "cannot write generation {generation} (nothing of it was stored): {what}"
                ),
                source,
            },
            other => other,
        },
    }
}
