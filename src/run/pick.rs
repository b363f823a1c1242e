//! An individual of a run picked by generation and rank (`ontogeny replay RUN --gen G
//! --rank K`), with the refusals a person gets for a generation or rank the run lacks.

use std::path::Path;

use super::{Run, RunError};
use crate::encoding::Genome;
use crate::evolve::ga::{Individual, ranking};

/// Why an individual could not be picked.
#[derive(Debug, thiserror::Error)]
pub enum PickError {
    /// The run could not be read.
    #[error(transparent)]
    Run(#[from] RunError),
    /// No such generation or rank: the message says which there are.
    #[error("{0}")]
    Input(String),
}

/// Individual `rank` (1 = the best) of `generation` (default: the last complete one) of
/// `run`, whose directory is `dir`, with the generation it is of.
pub fn individual_by_rank<G: Genome>(
    run: &Run<G>,
    dir: &Path,
    generation: Option<u32>,
    rank: usize,
) -> Result<(u32, Individual<G>), PickError> {
    let last = run.last_generation()?.ok_or_else(|| {
        PickError::Input(format!("{}: no complete generation yet", dir.display()))
    })?;
    let generation = generation.unwrap_or(last);
    if generation > last {
        return Err(PickError::Input(format!(
            "--gen {generation}: {} has generations 0 to {last}",
            dir.display()
        )));
    }
    let mut population = run.population(generation)?;
    if rank == 0 || rank > population.len() {
        return Err(PickError::Input(format!(
            "--rank must be 1 to {}, not {rank}",
            population.len()
        )));
    }
    let order = ranking(&population);
    Ok((generation, population.swap_remove(order[rank - 1])))
}
