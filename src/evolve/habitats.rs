//! An individual in its habitats: a genome developed in each habitat of a task (with the
//! habitat's chemical array, [`Genome::develop_in`]), the key of those creatures, and the
//! evaluation of one individual over every unit (habitat × trial) outside the genetic
//! algorithm's batches — the fine reference re-walk, the viewer, `eval` and `replay` — and one
//! walk of it recorded in a chosen habitat ([`recorded_walk`]); a grammar file that grows
//! during its walks, in each habitat ([`grammar_in_habitats`]). The genetic algorithm's batches
//! spread the same units over the evaluator (`ga`).

use super::evaluator::{Evaluator, Job};
use super::key::{EvaluationKey, KeyVersion};
use crate::cancel::{Cancel, Interrupted};
use crate::creature::Creature;
use crate::develop::Seedling;
use crate::encoding::{CheckedLimits, DevelopError, Genome};
use crate::environment::Environment;
use crate::sim::WorldSpec;
use crate::task::{Evaluation, Growing, TaskSpec, Unit, Watch};

/// The creatures `genome` develops into with `seed`, one per habitat of `task` (one for a
/// task without habitats): in a habitat with an array, [`Genome::develop_in`] it (an array
/// of another size than the genome's own is an error), and where the genome has no array of
/// its own, its creature's controller gets the habitat's in place of its own when the two
/// have the same length; in a habitat without one, [`Genome::develop`]. An error names the
/// habitat it arose in.
///
/// When `task` develops its creatures during their evaluation (`develop = "during"`), each is
/// the creature dropped: its seedling's ([`develop_with_seedlings`]) at t₀.
///
/// Every creature is held to the limits all encodings share ([`CheckedLimits::creature_limits`]:
/// `max_neurons`, `max_chain`): one past them gets an error-level problem that makes it
/// invalid, as a creature past `max_parts` is (a creature that grows during its evaluation
/// is held to them at t₀, and does not develop when it breaks one then).
pub fn develop_in_habitats<G: Genome>(
    genome: &G,
    limits: &G::Limits,
    seed: u64,
    task: &TaskSpec,
) -> Result<Vec<Creature>, DevelopError> {
    develop_with_seedlings(genome, limits, seed, task).map(|(creatures, _)| creatures)
}

/// [`develop_in_habitats`], with the seedlings the creatures grow from during their
/// evaluation, one per habitat, when `task` develops them during it (`develop = "during"`;
/// none otherwise): each habitat's seedling develops in the habitat's array
/// ([`Genome::seedling`]; a genome that does not develop in continuous time is an error), and
/// its creature is the one it holds at t₀.
pub fn develop_with_seedlings<G: Genome>(
    genome: &G,
    limits: &G::Limits,
    seed: u64,
    task: &TaskSpec,
) -> Result<(Vec<Creature>, Vec<Seedling>), DevelopError> {
    let shared = limits.creature_limits();
    if task.develop.during() {
        let seedlings = (0..task.habitat_count())
            .map(|h| {
                let env = task
                    .habitat_environment(h)
                    .map(|values| Environment::new(values.to_vec()));
                genome
                    .seedling(limits, env.as_ref())
                    .unwrap_or_else(|| {
                        Err(DevelopError(format!(
                            "the {} genome does not develop during an evaluation",
                            G::NAME
                        )))
                    })
                    .and_then(|seedling| dropped(task, seedling))
                    .and_then(|(creature, seedling)| {
                        // The walk grows its creature anew from the seedling: a creature
                        // past a limit at t₀ does not develop.
                        match shared.broken(&creature) {
                            broken if broken.is_empty() => Ok((creature, seedling)),
                            broken => Err(DevelopError(broken.join("; "))),
                        }
                    })
                    .map_err(|e| in_habitat(task, h, e))
            })
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(seedlings.into_iter().unzip());
    }
    let creatures = (0..task.habitat_count())
        .map(|h| {
            match task.habitat_environment(h) {
                Some(values) => genome
                    .develop_in(limits, seed, &Environment::new(values.to_vec()))
                    .map(|mut creature| {
                        if genome.environment().is_empty()
                            && creature.environment.len() == values.len()
                        {
                            creature.environment = values.to_vec();
                        }
                        creature
                    }),
                None => genome.develop(limits, seed),
            }
            .map(|mut creature| {
                shared.apply(&mut creature);
                creature
            })
            .map_err(|e| in_habitat(task, h, e))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok((creatures, Vec::new()))
}

/// The creature `seedling` holds at t₀ (`task`'s `develop_t0`), with the seedling.
fn dropped(task: &TaskSpec, seedling: Seedling) -> Result<(Creature, Seedling), DevelopError> {
    let growing = Growing::from_seedling(&seedling, &task.develop)
        .map_err(|d| DevelopError(d.to_string()))?;
    Ok((growing.creature().clone(), seedling))
}

/// A grammar file's [`develop_with_seedlings`]: `seedling` (a grammar read from a file, with
/// its options) in each habitat of `task` (one for a task without habitats), and the creature
/// each holds at t₀. In a habitat whose array has as many slots as the grammar's
/// `environment:`, its development starts from the habitat's values (the seedling's own
/// initial values, such as `--env`'s, still apply over them), as the grammar's last frame
/// grows there ([`crate::encoding::load::LoadOptions::habitat_environment`]); another
/// habitat leaves the grammar's own array. An error names the habitat it arose in.
pub fn grammar_in_habitats(
    task: &TaskSpec,
    seedling: &Seedling,
) -> Result<(Vec<Creature>, Vec<Seedling>), DevelopError> {
    let slots = seedling.lsys.environment().len();
    let grown = (0..task.habitat_count())
        .map(|h| {
            let mut here = seedling.clone();
            if let Some(values) = task.habitat_environment(h).filter(|v| v.len() == slots) {
                here.derive.env = values
                    .iter()
                    .copied()
                    .enumerate()
                    .chain(seedling.derive.env.iter().copied())
                    .collect();
            }
            dropped(task, here).map_err(|e| in_habitat(task, h, e))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(grown.into_iter().unzip())
}

/// `e`, arisen in habitat `h` of `task`, naming it (when it has a name).
fn in_habitat(task: &TaskSpec, h: usize, e: DevelopError) -> DevelopError {
    match task.habitat_name(h) {
        "" => e,
        name => DevelopError(format!("in habitat {name}: {}", e.0)),
    }
}

/// What an individual's creatures grow from during their walks (`develop = "during"`): a
/// seedling per habitat ([`develop_with_seedlings`], [`grammar_in_habitats`]), and the text
/// of its genome (or of its grammar file, without a champion's record), which keys the draws
/// of its trials with the development's settings as the genetic algorithm keys them
/// ([`EvaluationKey::growing_text`]).
#[derive(Clone, Copy, Debug)]
pub struct Growth<'a> {
    /// The seedling of each habitat, in order.
    pub seedlings: &'a [Seedling],
    /// The genome's text ([`Genome::to_text`]), or the grammar file's.
    pub text: &'a str,
}

impl<'a> Growth<'a> {
    /// The growth of creatures that grow from `seedlings` (one per habitat) and whose text is
    /// `text`; `None` when there are no seedlings (creatures that do not grow).
    pub fn of(seedlings: &'a [Seedling], text: &'a str) -> Option<Growth<'a>> {
        (!seedlings.is_empty()).then_some(Growth { seedlings, text })
    }
}

/// The units of an individual developed into `creatures` (growing from `growth`, when it
/// grows during its walks) on `task`, drawn for generation `generation`: those of habitat
/// `only`, when given.
fn units_of(
    task: &TaskSpec,
    creatures: &[Creature],
    growth: Option<Growth<'_>>,
    generation: u32,
    only: Option<usize>,
) -> Vec<Unit> {
    let mut key = EvaluationKey::of_habitats(creatures, task, KeyVersion::default());
    if let Some(growth) = growth {
        key = key.growing_text(task, growth.text);
    }
    task.units(key.0, generation)
        .into_iter()
        .filter(|u| only.is_none_or(|h| u.habitat as usize == h))
        .collect()
}

/// The evaluation of an individual developed into `creatures` (one per habitat of `task`,
/// [`develop_in_habitats`]), whose units are drawn for generation `generation`: a plain task
/// walks its one creature; otherwise every unit is walked, in parallel on `evaluator`, and
/// [`TaskSpec::combine`]d. `only` keeps the units of one habitat (by index) and combines
/// those alone. `Interrupted` once `cancel` is set.
pub fn evaluate_in_habitats(
    task: &TaskSpec,
    creatures: &[Creature],
    generation: u32,
    only: Option<usize>,
    evaluator: Evaluator,
    cancel: &Cancel,
) -> Result<Evaluation, Interrupted> {
    evaluate_grown_in_habitats(task, creatures, None, generation, only, evaluator, cancel)
}

/// [`evaluate_in_habitats`] for creatures that grow during their evaluation as `growth` says
/// (`None` for creatures that do not grow): every walk starts its habitat's seedling anew,
/// on the draws the genetic algorithm gives the individual.
pub fn evaluate_grown_in_habitats(
    task: &TaskSpec,
    creatures: &[Creature],
    growth: Option<Growth<'_>>,
    generation: u32,
    only: Option<usize>,
    evaluator: Evaluator,
    cancel: &Cancel,
) -> Result<Evaluation, Interrupted> {
    let seedlings = growth.map_or(&[][..], |g| g.seedlings);
    if task.is_plain() {
        let watch = Watch {
            record: false,
            progress: &mut |_| {},
            cancel: Some(cancel),
        };
        return Job {
            creature: &creatures[0],
            unit: None,
            seedling: seedlings.first(),
        }
        .evaluate(task, watch);
    }
    let units = units_of(task, creatures, growth, generation, only);
    let jobs: Vec<Job<'_>> = units
        .iter()
        .map(|u| Job {
            creature: &creatures[u.habitat as usize],
            unit: Some(*u),
            seedling: seedlings.get(u.habitat as usize),
        })
        .collect();
    let evaluations = evaluator.evaluate(task, &jobs, cancel)?;
    Ok(task.combine(&units, evaluations, creatures))
}

/// [`evaluate_grown_in_habitats`] for generation 0, on this process's threads, with nothing
/// to stop it: the evaluation `eval` and `replay` show.
pub fn evaluate_here(
    task: &TaskSpec,
    creatures: &[Creature],
    growth: Option<Growth<'_>>,
    only: Option<usize>,
) -> Result<Evaluation, Interrupted> {
    evaluate_grown_in_habitats(
        task,
        creatures,
        growth,
        0,
        only,
        Evaluator::Local,
        &Cancel::default(),
    )
}

/// [`develop_with_seedlings`] then [`evaluate_grown_in_habitats`] on this process's threads:
/// the evaluation the genetic algorithm gives `genome` (of `seed`) in generation
/// `generation`; a genome that does not develop is `invalid`.
pub fn evaluate_genome<G: Genome>(
    genome: &G,
    limits: &G::Limits,
    seed: u64,
    task: &TaskSpec,
    generation: u32,
    cancel: &Cancel,
) -> Result<Evaluation, Interrupted> {
    // Rank 0 of an MPI job counts this walk's CPU time as its own walks' (the fine re-walk).
    #[cfg(feature = "mpi")]
    let _own = super::mpi::OwnWalk::start();
    match develop_with_seedlings(genome, limits, seed, task) {
        Ok((creatures, seedlings)) => {
            let text = genome.to_text();
            evaluate_grown_in_habitats(
                task,
                &creatures,
                Growth::of(&seedlings, &text),
                generation,
                None,
                Evaluator::Local,
                cancel,
            )
        }
        Err(e) => Ok(Evaluation::invalid(
            task.task.name(),
            format!("development: {e}"),
        )),
    }
}

/// One walk of an individual, recorded: the creature as it was placed, its evaluation (with a
/// recording) and the world it walked in.
pub struct RecordedWalk {
    /// The creature walked: developed in the habitat, placed by the trial's draw (for one
    /// that grows during the walk, the creature dropped; the recording holds its growth).
    pub creature: Creature,
    /// The walk's evaluation, with a recording.
    pub evaluation: Evaluation,
    /// The world it walked in (the habitat's, its roughness scaled by the draw).
    pub world: WorldSpec,
}

/// The walk of an individual developed into `creatures` (one per habitat of `task`,
/// [`develop_in_habitats`]) recorded in habitat `habitat` (by index): for a plain task its one
/// walk; otherwise that habitat's first trial as drawn for generation 0 (the draws of a run
/// whose trials are not fresh), placed and scaled by its draw — what `replay --habitat` and
/// the viewer's `--habitat` play. A creature that grows during its walk grows as `growth`
/// says (`None` for one that does not), as in its evaluation.
pub fn recorded_walk(
    task: &TaskSpec,
    creatures: &[Creature],
    growth: Option<Growth<'_>>,
    habitat: usize,
) -> Result<RecordedWalk, Interrupted> {
    let unit = if task.is_plain() {
        None
    } else {
        units_of(task, creatures, growth, 0, Some(habitat))
            .first()
            .copied()
    };
    let evaluation = Job {
        creature: &creatures[habitat],
        unit,
        seedling: growth.and_then(|g| g.seedlings.get(habitat)),
    }
    .evaluate(task, Watch::uncancelled(true, &mut |_| {}))?;
    Ok(match unit {
        None => RecordedWalk {
            creature: creatures[habitat].clone(),
            evaluation,
            world: task.world.clone(),
        },
        Some(unit) => RecordedWalk {
            creature: unit.perturbation.place(&creatures[habitat]),
            evaluation,
            world: task.unit_spec(&unit).world,
        },
    })
}
