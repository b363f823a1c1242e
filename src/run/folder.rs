//! A run's directory: the names of its files, and which folders a new run may claim (a new,
//! empty or marked one; see [`crate::output::folder`]).

use std::path::Path;

use super::lock::LOCK_FILE;
use super::store::RunStore;
use crate::output;

/// The run's settings as it was started or last extended (TOML).
pub const CONFIG_FILE: &str = "config.toml";
/// The run store, the record of truth.
pub const STORE_FILE: &str = "run.sqlite";
/// One line per generation, derived from the store.
pub const LOG_FILE: &str = "log.txt";
/// The fitness plot, derived from the store.
pub const PLOT_FILE: &str = "fitness.svg";

/// What [`claim_folder`] found.
#[derive(Debug, PartialEq, Eq)]
pub enum Claim {
    /// The folder is ready for the run.
    Ready,
    /// The folder holds a run that an older version made (it carries no mark): `--resume` it.
    HoldsARun,
}

/// Makes `dir` ready for a new run ([`output::prepare_folder`]): missing, empty, or a run's
/// folder (one this version marked, or one an older version's killed start left, holding only
/// the lock and the store's temporary file). A run an older version made, which carries no
/// mark, is found as a run ([`Claim::HoldsARun`]); a folder of the user's files is refused as
/// theirs.
pub fn claim_folder(dir: &Path) -> Result<Claim, output::OutputError> {
    let kind = output::FolderKind::Run;
    if output::folder::is_marked(dir, kind) {
        return Ok(Claim::Ready);
    }
    if dir.join(CONFIG_FILE).exists() || !RunStore::is_vacant(&dir.join(STORE_FILE)) {
        return Ok(Claim::HoldsARun);
    }
    let partial = format!("{STORE_FILE}.partial");
    let left_by_a_start = |name: &str| name == LOCK_FILE || name.starts_with(&partial);
    let entries = std::fs::read_dir(dir).map(|entries| {
        entries
            .map(|e| e.map(|e| e.file_name().to_string_lossy().into_owned()))
            .collect::<Result<Vec<_>, _>>()
    });
    if let Ok(Ok(names)) = entries
        && !names.is_empty()
        && names.iter().all(|n| left_by_a_start(n))
    {
        output::folder::mark(dir, kind)?;
    }
    output::prepare_folder(dir, kind)?;
    Ok(Claim::Ready)
}
