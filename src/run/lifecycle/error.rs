//! Why a run could not start, resume or go on: [`RunError`].

use std::path::{Path, PathBuf};

use crate::cancel::Interrupted;
use crate::lang::Diagnostic;
use crate::run::lock::LockError;
use crate::run::store::StoreError;

/// Why a run could not start, resume or go on.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// `--out` names a run that exists.
    #[error(
        "{0} already holds a run: resume it with `ontogeny evolve --resume {0}`, or choose another --out"
    )]
    Exists(PathBuf),
    /// A directory that is not a run.
    #[error(
        "{0} holds no run (no run.sqlite with a run in it): start one with `ontogeny evolve --out {0}`"
    )]
    NotARun(PathBuf),
    /// Another process is writing the run.
    #[error(transparent)]
    Locked(#[from] LockError),
    /// `config.toml` was edited since the run started: resuming would mix two settings in
    /// one store.
    #[error(
        "{}: {} differ{} from the settings the run was started with (kept in run.sqlite); a resumed run must go on as it began: undo the edit, or start a new run with --out",
        path.display(),
        keys.join(", "),
        if keys.len() == 1 { "s" } else { "" }
    )]
    ConfigChanged {
        /// The run's `config.toml`.
        path: PathBuf,
        /// The settings that differ, as dotted TOML keys.
        keys: Vec<String>,
    },
    /// The run's last generation was evaluated by another evaluator than this program's:
    /// going on would mix two evaluators' results in one run.
    #[error(
        "{}: its last generation ({generation}) was evaluated by evaluator version {stored}, and this ontogeny evaluates with version {current}: going on would mix the evaluations of two evaluators in one run. Resume it with an ontogeny of evaluator version {stored}, start a new run with --out, or pass --allow-evaluator-change to go on with version {current} (the store records the generation where the version changes)",
        dir.display()
    )]
    EvaluatorChanged {
        /// The run directory.
        dir: PathBuf,
        /// The run's last stored generation.
        generation: u32,
        /// The evaluator version that made it.
        stored: u32,
        /// This program's ([`crate::evolve::evaluator_version::EVALUATOR_VERSION`]).
        current: u32,
    },
    /// A bad configuration.
    #[error("{0}")]
    Config(Diagnostic),
    /// The database refused.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// A stored individual does not read back (a database written by another encoding or
    /// version).
    #[error("{0}")]
    Corrupt(String),
    /// A run cannot be extended to the generations asked for.
    #[error("{0}")]
    Extend(String),
    /// The plot could not be drawn.
    #[error("{0}")]
    Plot(String),
    /// A file of the run could not be written, or its target is not a regular file.
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// A thread evaluating a steady-state birth, or re-walking a generation's best at the
    /// fine reference, panicked (a fault of this program): the run stopped, and resumes after
    /// its last stored generation.
    #[error(
        "a thread of the run panicked ({0}): the run stopped after its last stored generation (resume it with `ontogeny evolve --resume`); this is a fault of ontogeny, please report it"
    )]
    Panicked(String),
    /// The run's cancellation token was set ([`crate::run::Run::set_cancel`]): the generations
    /// not yet stored were dropped, and the run resumes after its last stored generation.
    #[error(transparent)]
    Interrupted(#[from] Interrupted),
}

/// A mapper of an I/O error on `path` to [`RunError::Io`].
pub(super) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> RunError + '_ {
    move |source| RunError::Io {
        path: path.to_path_buf(),
        source,
    }
}
