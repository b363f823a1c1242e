//! A genome file developed in each habitat of a configuration: what `ontogeny genome show
//! --habitats CONFIG FILE` and Python's `ontogeny.genome_habitats(config, genome)` share —
//! reading the configuration's `[[task.habitats]]`, reading the genome file and developing it
//! in each habitat's array ([`develop_in_habitat_arrays`]).

use std::path::Path;

use crate::encoding::{HabitatArray, HabitatPhenotypes, ShowError, develop_in_habitat_arrays};
use crate::lang::Diagnostic;

/// Why a genome could not be developed in a configuration's habitats.
#[derive(Debug, thiserror::Error)]
pub enum GenomeHabitatsError {
    /// The configuration or the genome's grammar is wrong (a diagnostic with its file, line
    /// and column).
    #[error("{0}")]
    Diagnostic(Diagnostic),
    /// Bad input: a configuration without habitats, a file that is no genome.
    #[error("{0}")]
    Input(String),
    /// The genome file cannot be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: std::path::PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
}

/// The genome file `genome` developed in each habitat of the configuration `config` (its
/// `[[task.habitats]]`, each with its array), with how the creatures of every pair differ.
/// `Err` for a configuration without habitats.
pub fn genome_in_habitats(
    config: &Path,
    genome: &Path,
) -> Result<HabitatPhenotypes, GenomeHabitatsError> {
    let spec =
        crate::run::config::read_task_config(config).map_err(GenomeHabitatsError::Diagnostic)?;
    if spec.habitats.is_empty() {
        return Err(GenomeHabitatsError::Input(format!(
            "{}: it has no [[task.habitats]] to develop the genome in",
            config.display()
        )));
    }
    let habitats: Vec<HabitatArray> = spec
        .habitats
        .iter()
        .map(|h| HabitatArray {
            name: h.name.clone(),
            environment: h.environment.clone(),
        })
        .collect();
    let text =
        crate::input::read_to_string(genome).map_err(|source| GenomeHabitatsError::Read {
            path: genome.to_path_buf(),
            source,
        })?;
    develop_in_habitat_arrays(genome, &text, &habitats).map_err(|e| match e {
        ShowError::Grammar(d) => GenomeHabitatsError::Diagnostic(d),
        ShowError::NotAGenome(m) => GenomeHabitatsError::Input(m),
    })
}
