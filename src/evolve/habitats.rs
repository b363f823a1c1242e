//! An individual in its habitats: a genome developed in each habitat of a task (with the
//! habitat's chemical array, [`Genome::develop_in`]), the key of those creatures, and the
//! evaluation of one individual over every unit (habitat × trial) outside the genetic
//! algorithm's batches — the fine reference re-walk, the viewer, `eval` and `replay` — and one
//! walk of it recorded in a chosen habitat ([`recorded_walk`]). The genetic algorithm's batches
//! spread the same units over the evaluator (`ga`).

use super::evaluator::{Evaluator, Job};
use super::key::{EvaluationKey, KeyVersion};
use crate::cancel::{Cancel, Interrupted};
use crate::creature::Creature;
use crate::develop::Seedling;
use crate::encoding::{DevelopError, Genome};
use crate::environment::Environment;
use crate::sim::WorldSpec;
use crate::task::{Evaluation, Growing, TaskSpec, Watch};

/// The creatures `genome` develops into with `seed`, one per habitat of `task` (one for a
/// task without habitats): in a habitat with an array, [`Genome::develop_in`] it (an array
/// of another size than the genome's own is an error), and where the genome has no array of
/// its own, its creature's controller gets the habitat's in place of its own when the two
/// have the same length; in a habitat without one, [`Genome::develop`]. An error names the
/// habitat it arose in.
///
/// When `task` develops its creatures during their evaluation (`develop = "during"`), each is
/// the creature dropped: its seedling's ([`develop_with_seedlings`]) at t₀.
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
                    .and_then(|seedling| {
                        let growing = Growing::from_seedling(&seedling, &task.develop)
                            .map_err(|d| DevelopError(d.to_string()))?;
                        Ok((growing.creature().clone(), seedling))
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
            .map_err(|e| in_habitat(task, h, e))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok((creatures, Vec::new()))
}

/// `e`, arisen in habitat `h` of `task`, naming it (when it has a name).
fn in_habitat(task: &TaskSpec, h: usize, e: DevelopError) -> DevelopError {
    match task.habitat_name(h) {
        "" => e,
        name => DevelopError(format!("in habitat {name}: {}", e.0)),
    }
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
    evaluate_grown_in_habitats(task, creatures, &[], generation, only, evaluator, cancel)
}

/// [`evaluate_in_habitats`] for creatures that grow from `seedlings` during their evaluation
/// (one per habitat, [`develop_with_seedlings`]; none for creatures that do not grow): every
/// walk starts its habitat's seedling anew.
pub fn evaluate_grown_in_habitats(
    task: &TaskSpec,
    creatures: &[Creature],
    seedlings: &[Seedling],
    generation: u32,
    only: Option<usize>,
    evaluator: Evaluator,
    cancel: &Cancel,
) -> Result<Evaluation, Interrupted> {
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
    let key = EvaluationKey::of_habitats(creatures, task, KeyVersion::default());
    let units: Vec<_> = task
        .units(key.0, generation)
        .into_iter()
        .filter(|u| only.is_none_or(|h| u.habitat as usize == h))
        .collect();
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

/// [`evaluate_in_habitats`] for generation 0, on this process's threads, with nothing to stop
/// it: the evaluation `eval` and `replay` show.
pub fn evaluate_here(
    task: &TaskSpec,
    creatures: &[Creature],
    only: Option<usize>,
) -> Result<Evaluation, Interrupted> {
    evaluate_in_habitats(
        task,
        creatures,
        0,
        only,
        Evaluator::Local,
        &Cancel::default(),
    )
}

/// [`develop_in_habitats`] then [`evaluate_in_habitats`] on this process's threads: the
/// evaluation the genetic algorithm gives `genome` (of `seed`) in generation `generation`; a
/// genome that does not develop is `invalid`.
pub fn evaluate_genome<G: Genome>(
    genome: &G,
    limits: &G::Limits,
    seed: u64,
    task: &TaskSpec,
    generation: u32,
    cancel: &Cancel,
) -> Result<Evaluation, Interrupted> {
    match develop_with_seedlings(genome, limits, seed, task) {
        Ok((creatures, seedlings)) => evaluate_grown_in_habitats(
            task,
            &creatures,
            &seedlings,
            generation,
            None,
            Evaluator::Local,
            cancel,
        ),
        Err(e) => Ok(Evaluation::invalid(
            task.task.name(),
            format!("development: {e}"),
        )),
    }
}

/// One walk of an individual, recorded: the creature as it was placed, its evaluation (with a
/// recording) and the world it walked in.
pub struct RecordedWalk {
    /// The creature walked: developed in the habitat, placed by the trial's draw.
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
/// the viewer's `--habitat` play.
pub fn recorded_walk(task: &TaskSpec, creatures: &[Creature], habitat: usize) -> RecordedWalk {
    if task.is_plain() {
        let creature = creatures[0].clone();
        let evaluation = task.evaluate(&creature, true);
        return RecordedWalk {
            creature,
            evaluation,
            world: task.world.clone(),
        };
    }
    let key = EvaluationKey::of_habitats(creatures, task, KeyVersion::default());
    let unit = task
        .units(key.0, 0)
        .into_iter()
        .find(|u| u.habitat as usize == habitat)
        .expect("every habitat has a trial");
    let creature = unit.perturbation.place(&creatures[habitat]);
    let spec = task.unit_spec(&unit);
    let evaluation = spec.evaluate(&creature, true);
    RecordedWalk {
        creature,
        evaluation,
        world: spec.world,
    }
}
