//! Comparing encodings, or conditions, on equal terms (`ontogeny compare`): a comparison
//! directory holds one full run directory per replicate of every encoding (all with the same
//! genetic algorithm and task) or of every condition (each a whole run config of its own),
//! all on the same budget of walks, and a report of statistics over their champions that
//! states the effect it can detect.
//!
//! ```text
//! runs/NAME/compare.toml             the comparison: encodings or conditions, replicates, budget, seed
//! runs/NAME/evolve.toml              encodings: the shared settings ([ga] and [task]), an evolve config
//! runs/NAME/<condition>/evolve.toml  conditions: each one's settings, an evolve config
//! runs/NAME/<name>/rep-<k>/          replicate k (1-based) of an encoding or condition: an ordinary run directory
//! runs/NAME/report.md, summary.csv, fitness.svg, parts.svg
//! ```
//!
//! This module knows no encoding by name: everything that depends on one is generic over
//! [`Genome`](crate::encoding::Genome).
//!
//! The comparison's directory and plan are in `plan`, reading a finished replicate in
//! `replicate`, the pairwise tests and the power in `pairs`, the statistics and the files of
//! the report in [`report`], where a comparison stands in [`survey`].

mod pairs;
mod plan;
mod replicate;
mod report;
mod survey;

pub use pairs::{LARGE_A12, Pair, Power, is_primary, pairwise, planned_power, power_note};
pub use plan::{
    Arm, BUDGET_TOLERANCE, ConditionFile, MAX_CONDITION_NAME, MAX_REPLICATES, Manifest, Shared,
    check_budgets, check_condition_name, condition_file, create, duplicate_condition,
    encoding_arms, evaluated_per_generation, evaluations_of, fitness_labels, generations_for, lock,
    open, replicate_config, replicate_dir, replicate_seed, walks_per_individual,
};
pub use replicate::{Champion, Replicate, ReplicateState, read_replicate};
pub use report::{
    ArmSummary, MIN_REPLICATES_FOR_STATISTICS, Report, fine_sample, report, too_few_note,
    write_report,
};
pub use survey::{Survey, gather, replicate_state, survey};

use std::path::{Path, PathBuf};

use crate::run::plot;

/// Why a comparison could not be planned, run or reported.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// Bad input: a budget below one generation, a replicate whose settings differ, ...
    #[error("{0}")]
    Input(String),
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// An output file was refused or could not be written (see [`crate::output`]).
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// Anything else (a database or a plot that fails).
    #[error("{0}")]
    Other(String),
}

impl From<plot::PlotError> for CompareError {
    fn from(e: plot::PlotError) -> Self {
        match e {
            plot::PlotError::Output(e) => CompareError::Output(e),
            other => CompareError::Other(other.to_string()),
        }
    }
}

pub(crate) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> CompareError + '_ {
    move |source| CompareError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Test settings: the Chaumont preset with `population` and `generations`.
#[cfg(test)]
fn chaumont_ga(population: usize, generations: usize) -> crate::evolve::ga::GaSettings {
    crate::evolve::ga::GaSettings {
        population,
        generations,
        ..crate::evolve::ga::GaSettings::preset(crate::evolve::ga::Preset::Chaumont)
    }
}
