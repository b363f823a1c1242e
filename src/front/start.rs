//! Starting a new run as `ontogeny evolve --out` and Python's `evolve` do: the settings
//! resolved from the config file and the flags over it ([`settings::new_run`]), the
//! notes on its seed told, and the run started in its directory.

use std::path::Path;

use super::settings::{self, RunFlags};
use crate::encoding::Genome;
use crate::lang::{Diagnostic, Source};
use crate::run::{Run, RunError};

/// What a new run starts from.
#[derive(Clone, Copy, Debug)]
pub struct NewRun<'a> {
    /// The run's directory (`--out`).
    pub out: &'a Path,
    /// The config file's text, if one is given.
    pub source: Option<&'a Source>,
    /// The flags over the config file.
    pub flags: &'a RunFlags,
    /// The grammar that seeds the first generation (`--init`), over the file's `init`.
    pub init: Option<&'a Path>,
    /// The master seed (`--seed`), over the file's.
    pub seed: Option<u64>,
    /// Whether each generation's best is re-walked at the fine reference.
    pub verify_best: bool,
    /// Whether identical creatures reuse an evaluation.
    pub cache: bool,
}

/// Why a new run did not start.
#[derive(Debug, thiserror::Error)]
pub enum StartError {
    /// Its settings or its seed are bad input.
    #[error(transparent)]
    Settings(#[from] Diagnostic),
    /// The run could not start in its directory.
    #[error(transparent)]
    Run(#[from] RunError),
}

/// Starts the run `new` describes, of genome `G`; `notes` is told the notes on its seed once
/// its settings hold, before the directory is claimed.
pub fn start_run<G: Genome>(
    new: &NewRun<'_>,
    notes: impl FnOnce(Vec<String>),
) -> Result<Run<G>, StartError> {
    let settings::ResolvedRun {
        config,
        init,
        notes: seed_notes,
    } = settings::new_run::<G>(
        new.source,
        new.flags,
        new.init,
        new.seed,
        new.verify_best,
        new.cache,
    )?;
    notes(seed_notes);
    let init_text = init.as_ref().map(|s| s.text());
    Ok(Run::<G>::start(new.out, config, init_text)?)
}
