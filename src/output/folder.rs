//! Output folders: which folder a verb may write into, so that no file of the user's is ever
//! replaced.
//!
//! A verb that writes a folder (`evolve --out`, `compare --out`, `grow --out`, `eval
//! --record`, a run's `replay`) uses it only when it does not exist (it is then made, with its
//! parents), when it is empty, or when Ontogeny made it for the same kind of output. Ontogeny
//! knows its own folders by a mark: a small file named after the kind of output
//! ([`FolderKind::mark`], e.g. `.ontogeny-growth`), written into the folder when the folder is
//! first used. Anything else (a folder of the user's files, `.`, `/`) is refused before any
//! work is done, and left as it is.
//!
//! What this module does not own: whether a run or comparison already fills a folder (the run
//! store and the comparison's plan say so), or the files written inside (see the parent
//! module, which writes each whole).

use std::io::{self, Write};
use std::path::{Path, PathBuf};

use super::OutputError;

/// What a folder of outputs holds, and so which verb may write into it again.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FolderKind {
    /// A run directory (`evolve --out`, and each replicate of a comparison).
    Run,
    /// A comparison directory (`compare --out`).
    Comparison,
    /// A growth (`grow --out`).
    Growth,
    /// A recording (`eval --record`).
    Recording,
    /// An individual of a run replayed (`replay RUN`), inside the run directory.
    Replay,
}

impl FolderKind {
    /// The name of the file that marks a folder as Ontogeny's, for this kind of output.
    pub fn mark(self) -> &'static str {
        match self {
            FolderKind::Run => ".ontogeny-run",
            FolderKind::Comparison => ".ontogeny-comparison",
            FolderKind::Growth => ".ontogeny-growth",
            FolderKind::Recording => ".ontogeny-recording",
            FolderKind::Replay => ".ontogeny-replay",
        }
    }

    /// The command that writes this kind of folder, in words.
    pub fn verb(self) -> &'static str {
        match self {
            FolderKind::Run => "`ontogeny evolve`",
            FolderKind::Comparison => "`ontogeny compare`",
            FolderKind::Growth => "`ontogeny grow --out`",
            FolderKind::Recording => "`ontogeny eval --record`",
            FolderKind::Replay => "`ontogeny replay`",
        }
    }

    /// What to do instead of writing into a folder that is not this kind's (`path`).
    fn advice(self, path: &Path) -> String {
        match self {
            FolderKind::Run => format!(
                "choose a new or empty folder (or, if it holds a run, go on with it: `ontogeny \
                 evolve --resume {}`)",
                path.display()
            ),
            FolderKind::Comparison => format!(
                "choose a new or empty folder (or, if it holds a comparison, complete it: \
                 `ontogeny compare --resume {}`)",
                path.display()
            ),
            _ => "choose a new or empty folder".to_string(),
        }
    }

    /// The error for the folder `path` that holds `found` and no mark of this kind.
    pub fn refusal(self, path: &Path, found: impl Into<String>) -> OutputError {
        OutputError::NotOurFolder {
            path: path.into(),
            found: found.into(),
            verb: self.verb(),
            advice: self.advice(path),
        }
    }
}

/// Whether `path` is a folder that Ontogeny marked as one of `kind`.
pub fn is_marked(path: &Path, kind: FolderKind) -> bool {
    std::fs::symlink_metadata(path.join(kind.mark())).is_ok_and(|m| m.is_file())
}

/// Says whether `path` may be used as a folder of `kind` ([`prepare_folder`] would use it),
/// changing nothing: a path that does not exist, an empty folder, or a folder marked as
/// `kind`'s. A symbolic link to a folder counts as that folder.
pub fn check_folder(path: &Path, kind: FolderKind) -> Result<(), OutputError> {
    let io_error = |source| OutputError::Io {
        path: path.into(),
        cause: source,
    };
    let metadata = match std::fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            // Nothing there, or a link that points nowhere.
            return match std::fs::read_link(path) {
                Ok(target) => Err(OutputError::DanglingLink {
                    path: path.into(),
                    target,
                }),
                Err(_) => Ok(()),
            };
        }
        Err(e) => return Err(io_error(e)),
    };
    if !metadata.is_dir() {
        return Err(OutputError::NotAFolder { path: path.into() });
    }
    if is_marked(path, kind) {
        return Ok(());
    }
    let mut entries = std::fs::read_dir(path).map_err(io_error)?;
    match entries.next() {
        None => Ok(()),
        Some(entry) => {
            let name = entry.map_err(io_error)?.file_name();
            let name = name.to_string_lossy();
            let found = match entries.count() {
                0 => name.into_owned(),
                more => format!("{name} and {more} more"),
            };
            Err(kind.refusal(path, found))
        }
    }
}

/// Makes `path` ready to hold outputs of `kind`: refuses it as [`check_folder`] does,
/// otherwise creates it (with its parents) if it is missing and marks it as `kind`'s.
pub fn prepare_folder(path: &Path, kind: FolderKind) -> Result<(), OutputError> {
    check_folder(path, kind)?;
    std::fs::create_dir_all(path).map_err(|source| OutputError::Io {
        path: path.into(),
        cause: source,
    })?;
    if is_marked(path, kind) {
        return Ok(());
    }
    mark(path, kind)
}

/// Marks the existing folder `path` as `kind`'s, for a verb that has recognised it as its own
/// otherwise (a folder an older version made, which carries no mark).
pub fn mark(path: &Path, kind: FolderKind) -> Result<(), OutputError> {
    let io_error = |path: PathBuf| {
        move |source| OutputError::Io {
            path,
            cause: source,
        }
    };
    let mark = path.join(kind.mark());
    let mut file = std::fs::File::create(&mark).map_err(io_error(mark.clone()))?;
    writeln!(
        file,
        "Made by {}: Ontogeny may write into this folder again (and into no folder of \
         files it did not make).",
        kind.verb()
    )
    .map_err(io_error(mark))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_folder_is_made_with_its_parents_and_marked() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("a").join("b");
        prepare_folder(&out, FolderKind::Growth).unwrap();
        assert!(is_marked(&out, FolderKind::Growth));
        assert!(!is_marked(&out, FolderKind::Recording));
        // Used again: it is the growth's own.
        std::fs::write(out.join("creature.json"), "{}").unwrap();
        prepare_folder(&out, FolderKind::Growth).unwrap();
    }

    #[test]
    fn an_empty_folder_is_used_and_a_folder_of_the_users_is_refused_untouched() {
        let dir = tempfile::tempdir().unwrap();
        prepare_folder(dir.path(), FolderKind::Recording).unwrap();
        assert!(is_marked(dir.path(), FolderKind::Recording));
        let users = dir.path().join("mine");
        std::fs::create_dir(&users).unwrap();
        std::fs::write(users.join("log.txt"), "mine").unwrap();
        let error = prepare_folder(&users, FolderKind::Run).unwrap_err();
        let more = dir.path().join("more");
        std::fs::create_dir(&more).unwrap();
        for name in ["a", "b", "c"] {
            std::fs::write(more.join(name), name).unwrap();
        }
        let said = check_folder(&more, FolderKind::Growth)
            .unwrap_err()
            .to_string();
        assert!(said.contains(" and 2 more); refusing"), "{said}");
        assert_eq!(
            error.to_string(),
            format!(
                "{0} already holds files that `ontogeny evolve` did not write there (log.txt); \
                 refusing to write into it: choose a new or empty folder (or, if it holds a \
                 run, go on with it: `ontogeny evolve --resume {0}`)",
                users.display()
            )
        );
        assert_eq!(std::fs::read_dir(&users).unwrap().count(), 1);
    }

    #[test]
    fn another_verbs_folder_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        prepare_folder(dir.path(), FolderKind::Growth).unwrap();
        let error = check_folder(dir.path(), FolderKind::Recording).unwrap_err();
        assert!(matches!(error, OutputError::NotOurFolder { .. }));
        assert!(error.to_string().contains("(.ontogeny-growth)"), "{error}");
    }

    #[test]
    fn a_file_is_not_a_folder() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("file");
        std::fs::write(&file, "mine").unwrap();
        assert_eq!(
            check_folder(&file, FolderKind::Growth)
                .unwrap_err()
                .to_string(),
            format!(
                "{} exists and is not a folder; refusing to write into it: choose a new or \
                 empty folder",
                file.display()
            )
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_dangling_link_is_refused_in_words_and_a_link_to_a_folder_is_followed() {
        let dir = tempfile::tempdir().unwrap();
        let link = crate::input::dangling_link(dir.path(), "link", "nowhere");
        assert_eq!(
            prepare_folder(&link, FolderKind::Growth)
                .unwrap_err()
                .to_string(),
            format!(
                "{} is a symbolic link to nowhere, which does not exist; refusing to write \
                 through it: remove the link, or choose another path",
                link.display()
            )
        );
        assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
        std::fs::create_dir(dir.path().join("nowhere")).unwrap();
        prepare_folder(&link, FolderKind::Growth).unwrap();
        assert!(is_marked(&dir.path().join("nowhere"), FolderKind::Growth));
    }
}
