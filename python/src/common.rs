//! What every binding shares: errors as Python exceptions, warnings, names parsed from
//! strings, the worker thread pool.

use std::ffi::CString;
use std::path::Path;

use crate::interrupt::interrupted_error;
use ontogeny::encoding::LoadError;
use ontogeny::lang::Diagnostic;
use ontogeny::run::RunError;
use ontogeny::sim::StepSetting;
use ontogeny::task::TaskKind;
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyUserWarning, PyValueError};
use pyo3::prelude::*;

/// The most worker threads `threads=` may ask for, as `--threads` on the command line.
pub(crate) const MAX_THREADS: usize = 1024;

/// A bad-input error: `ValueError` with the command line's message.
pub(crate) fn value_error(message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// A library's diagnostic (a grammar's names its file, line and column) as `ValueError`.
pub(crate) fn diagnostic_error(d: Diagnostic) -> PyErr {
    value_error(d)
}

/// A failure to load a creature as Python sees it.
pub(crate) fn load_error(e: LoadError) -> PyErr {
    match e {
        LoadError::Read { path, source } => {
            let message = format!("cannot read {}: {source}", path.display());
            match source.kind() {
                std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
                _ => PyOSError::new_err(message),
            }
        }
        LoadError::Bad(d) => diagnostic_error(d),
    }
}

/// A run's failure as Python sees it: a file that cannot be read or written is an `OSError`,
/// an interrupted run `KeyboardInterrupt`, anything else (a bad configuration, a run already
/// there, a locked run) a `ValueError`.
pub(crate) fn run_error(e: RunError) -> PyErr {
    match e {
        RunError::Io { path, source } => {
            PyOSError::new_err(format!("{}: {source}", path.display()))
        }
        RunError::Interrupted(e) => interrupted_error(e),
        other => value_error(other),
    }
}

/// Refuses a path that does not exist with `FileNotFoundError`, as Python's `open` does.
pub(crate) fn require_exists(path: &Path) -> PyResult<()> {
    if path.exists() {
        Ok(())
    } else {
        Err(PyFileNotFoundError::new_err(format!(
            "{}: no such file or directory",
            path.display()
        )))
    }
}

/// Issues each of `messages` as a Python `UserWarning`.
pub(crate) fn warn_all(py: Python<'_>, messages: &[String]) -> PyResult<()> {
    let category = py.get_type::<PyUserWarning>();
    for message in messages {
        let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, category.as_any(), &text, 1)?;
    }
    Ok(())
}

/// A local pool of `threads` worker threads (default: one per core), 1 to 1024.
pub(crate) fn thread_pool(threads: Option<usize>) -> PyResult<rayon::ThreadPool> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if !(1..=MAX_THREADS).contains(&n) {
            return Err(value_error(format!(
                "threads must be 1 to {MAX_THREADS}, not {n}"
            )));
        }
        builder = builder.num_threads(n);
    }
    builder
        .build()
        .map_err(|e| PyOSError::new_err(format!("cannot start the worker threads: {e}")))
}

/// A name of one of the library's vocabularies, or `ValueError` listing the names.
pub(crate) fn parse_name<T: std::str::FromStr>(
    what: &str,
    name: &str,
    all: impl IntoIterator<Item = T>,
    spell: fn(T) -> &'static str,
) -> PyResult<T> {
    name.parse::<T>().map_err(|_| {
        let names: Vec<&str> = all.into_iter().map(spell).collect();
        value_error(format!(
            "unknown {what} '{name}' (one of: {})",
            names.join(", ")
        ))
    })
}

pub(crate) fn task_named(name: &str) -> PyResult<TaskKind> {
    parse_name("task", name, TaskKind::ALL.iter().copied(), TaskKind::name)
}

pub(crate) fn setting_named(name: &str) -> PyResult<StepSetting> {
    parse_name("setting", name, StepSetting::ALL, StepSetting::name)
}
