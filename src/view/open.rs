//! What opening a page involves beyond its data: a run's individuals developed and their walks
//! played on request, in one of the run's habitats when asked ([`run_developer`]), and the
//! warnings for the flags that do nothing for
//! the page ([`ignored_flags`]).

use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use super::{Kind, Target, ViewError};
use crate::creature::Creature;
use crate::encoding::Genome;
use crate::evolve::habitats::{Growth, develop_in_habitats, develop_with_seedlings, recorded_walk};
use crate::run::Run;
use crate::run::pick::{PickError, individual_by_rank};
use crate::task::Recording;

/// What the server asks of a run's individuals, which only code that knows the run's encoding
/// can answer ([`run_developer`] makes one for an encoding).
pub struct Developer {
    /// The habitat the individuals are shown in, by name (`None`: the run has no habitats, or
    /// none was asked for, and its first is used).
    pub habitat: Option<String>,
    /// Develops individual `(generation, index)` into a creature (in the habitat's chemical
    /// array, [`crate::evolve::habitats::develop_in_habitats`]), or says why not.
    pub develop: Box<dyn Fn(u32, u32) -> Result<Creature, String> + Send + Sync>,
    /// Re-evaluates the individual of rank `(generation, rank)` (rank 1 the best, in the order
    /// `ontogeny replay --rank` uses) with a recording, and returns the page's data for it:
    /// the shape [`super::recording_data`] gives a recording directory, with `generation`,
    /// `rank`, `stored_fitness` (the fitness the run stored for it: with habitats, the
    /// aggregate of every habitat and trial) and `habitat` (the habitat's name, null for a run
    /// without habitats). With habitats, the walk is the habitat's first trial
    /// ([`crate::evolve::habitats::recorded_walk`]). It takes as long as an evaluation does.
    pub walk: Box<dyn Fn(u32, u32) -> Result<Value, ViewError> + Send + Sync>,
}

/// The flags of `ontogeny view` that may do nothing for a page.
#[derive(Clone, Debug, Default)]
pub struct PageFlags {
    /// The growth flags given (`--steps`, `--seed`, ...), by name.
    pub growth: Vec<&'static str>,
    /// Whether `--size` was given.
    pub size: bool,
    /// Whether `--snapshot` was given.
    pub snapshot: bool,
    /// `--frame`.
    pub frame: Option<i64>,
    /// `--habitat NAME`.
    pub habitat: Option<String>,
}

/// What `flags` do not do for the page of `target` (of `frames` frames, when known), one
/// warning each: growth flags with a directory (its creatures are already grown), `--size`
/// without `--snapshot`, `--frame` on a run page or past the page's frames, `--habitat` on a
/// page that is no run's.
pub fn ignored_flags(flags: &PageFlags, target: &Target, frames: Option<usize>) -> Vec<String> {
    let mut warnings = Vec::new();
    if target.kind != Kind::Lsys && !flags.growth.is_empty() {
        warnings.push(format!(
            "{} {} a creature from a grammar; {} is not an .lsys file: ignored",
            flags.growth.join(", "),
            if flags.growth.len() == 1 {
                "grows"
            } else {
                "grow"
            },
            target.path.display()
        ));
    }
    if let Some(name) = &flags.habitat
        && target.kind != Kind::Run
    {
        warnings.push(format!(
            "--habitat {name} shows a run's individuals in one of its habitats; {} is not a \
             run directory: ignored",
            target.path.display()
        ));
    }
    if flags.size && !flags.snapshot {
        warnings.push("--size sets the size of a --snapshot picture: ignored".to_string());
    }
    if let Some(k) = flags.frame {
        if target.kind == Kind::Run {
            warnings.push(format!(
                "--frame {k}: a run page has no frames (open an individual with ?gen=G&index=I \
                 in its address): ignored"
            ));
        } else if target.kind == Kind::Comparison {
            warnings.push(format!(
                "--frame {k}: a comparison page has no frames: ignored"
            ));
        } else if let Some(n) = frames {
            let n = n as i64;
            if n == 0 {
                warnings.push(format!("--frame {k}: the recording has no frames: ignored"));
            } else if k >= n || k < -n {
                warnings.push(format!(
                    "--frame {k}: there are {n} frames (0 to {}, or -{n} to -1): showing the {}",
                    n - 1,
                    if k >= n { "last" } else { "first" }
                ));
            }
        }
    }
    warnings
}

/// The [`Developer`] of the run in `dir`, whose genomes are `G`s, showing its individuals in
/// habitat `habitat` (by index into the run's `[[task.habitats]]`; `None`: the first, or the
/// run's one world) named `name`.
pub fn run_developer<G: Genome + 'static>(
    dir: PathBuf,
    habitat: Option<(usize, String)>,
) -> Developer {
    let walk_dir = dir.clone();
    let index = habitat.as_ref().map_or(0, |(i, _)| *i);
    Developer {
        habitat: habitat.map(|(_, name)| name),
        develop: Box::new(move |generation, at| {
            // Read-only: the viewer never changes a run's files.
            let run = Run::<G>::open_read_only(&dir).map_err(|e| e.to_string())?;
            let population = run.population(generation).map_err(|e| e.to_string())?;
            let individual = population.get(at as usize).ok_or_else(|| {
                format!(
                    "generation {generation} has {} individual(s); there is no individual {at}",
                    population.len()
                )
            })?;
            develop_in_habitats(
                &individual.genome,
                &run.config().limits,
                individual.develop_seed,
                &run.config().task,
            )
            .map(|mut creatures| creatures.swap_remove(index.min(creatures.len() - 1)))
            .map_err(|e| format!("the genome does not develop: {e}"))
        }),
        walk: Box::new(move |generation, rank| walk::<G>(&walk_dir, generation, rank, index)),
    }
}

/// The individual of rank `rank` of `generation` of the run in `dir`, re-evaluated with a
/// recording in habitat `habitat` (by index) as `ontogeny replay DIR --gen G --rank R` does:
/// the page's data (see [`Developer::walk`]). A generation or rank the run lacks is refused,
/// saying which it has.
fn walk<G: Genome>(
    dir: &Path,
    generation: u32,
    rank: u32,
    habitat: usize,
) -> Result<Value, ViewError> {
    let unreadable = |e: &dyn std::fmt::Display| ViewError::BadFile(e.to_string());
    if rank == 0 {
        return Err(ViewError::BadRequest(
            "rank=0: ranks start at 1, the best".to_string(),
        ));
    }
    // Read-only: the viewer never changes a run's files.
    let run = Run::<G>::open_read_only(dir).map_err(|e| unreadable(&e))?;
    match run.last_generation().map_err(|e| unreadable(&e))? {
        None => {
            return Err(ViewError::NotFound(
                "the run has no complete generation yet".to_string(),
            ));
        }
        Some(last) if generation > last => {
            return Err(ViewError::NotFound(format!(
                "there is no generation {generation}: the run has generations 0 to {last}"
            )));
        }
        Some(_) => {}
    }
    let count = super::run_population_size(dir, generation)?;
    if rank as usize > count {
        return Err(ViewError::NotFound(format!(
            "generation {generation} has {count} individual(s); there is no rank {rank}"
        )));
    }
    let (_, individual) =
        individual_by_rank(&run, dir, Some(generation), rank as usize).map_err(|e| match e {
            PickError::Run(e) => unreadable(&e),
            PickError::Input(message) => ViewError::NotFound(message),
        })?;
    let title = format!("generation {generation}, rank {rank}");
    let task = &run.config().task;
    let (creatures, seedlings) = develop_with_seedlings(
        &individual.genome,
        &run.config().limits,
        individual.develop_seed,
        task,
    )
    .map_err(|e| ViewError::BadFile(format!("{title}: the genome does not develop: {e}")))?;
    let text = individual.genome.to_text();
    let walked = recorded_walk(task, &creatures, Growth::of(&seedlings, &text), habitat)
        .map_err(|e| ViewError::BadFile(format!("{title}: {e}")))?;
    let recording = Recording::of(&walked.creature, &walked.evaluation).in_world(&walked.world);
    let mut value = super::recording_value(&recording, &title)
        .map_err(|e| ViewError::BadFile(format!("{title}: {e}")))?;
    value["generation"] = json!(generation);
    value["rank"] = json!(rank);
    value["stored_fitness"] = super::finite(individual.evaluation.fitness);
    value["habitat"] = match task.habitat_name(habitat) {
        "" => Value::Null,
        name => json!(name),
    };
    Ok(value)
}
