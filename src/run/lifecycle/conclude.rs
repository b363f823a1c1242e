//! The end of a generation: its best re-walked at the fine reference (or that figure taken
//! from where it is known), the generation stored in one transaction, the derived files
//! advanced, its profile line written and the observer told.

use std::time::Instant;

use super::progress::Progress;
use super::{GenerationReport, Run, RunError, status_name, status_text};
use crate::cancel::{Cancel, Interrupted};
use crate::encoding::Genome;
use crate::evolve::evaluator::Evaluator;
use crate::evolve::ga::{Fallbacks, Individual};
use crate::evolve::timing::GenerationTimes;
use crate::run::profile::GenerationProfile;
use crate::run::store::{FineEvaluation, GenerationRecord, IndividualRecord};
use crate::task::TaskSpec;

impl<G: Genome> Run<G> {
    /// The end of generation `generation`, bred and evaluated since `started` (`evaluations`
    /// made, and how many of them reused a stored evaluation where its members do not say,
    /// as a steady-state block's births that reused one and were not kept, for the report
    /// to `observer` only; its steps' `times`): its best re-walked at the fine reference,
    /// stored, the derived files advanced, `observer` told.
    pub(super) fn conclude(
        &mut self,
        progress: &mut Progress<G>,
        generation: u32,
        (evaluations, reused): (u64, Option<u64>),
        times: GenerationTimes,
        started: Instant,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError> {
        let evaluated = started.elapsed().as_secs_f64();
        let fine_started = Instant::now();
        let best_fine = self.verify_best(progress)?;
        let fine = fine_started.elapsed().as_secs_f64();
        self.store_generation(
            Concluded {
                generation,
                population: &progress.population,
                fallbacks: &progress.fallbacks,
                evaluations,
                reused,
                times,
                evaluated,
                best_fine,
                fine,
                fine_walk: None,
            },
            observer,
        )
    }

    /// Stores a generation whose best's fine reference figure is known, advances the derived
    /// files, writes its profile line and tells `observer`.
    pub(super) fn store_generation(
        &mut self,
        concluded: Concluded<'_, G>,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError> {
        let Concluded {
            generation,
            population,
            fallbacks,
            evaluations,
            reused,
            times,
            evaluated,
            best_fine,
            fine,
            fine_walk,
        } = concluded;
        let mut stats = GenerationRecord {
            index: generation,
            best_fine,
            ..GenerationRecord::of(population, evaluations)
        };
        let writing_started = Instant::now();
        let until_written = |writing: f64| evaluated + fine + writing;
        self.record(population, &mut stats, &until_written)?;
        self.advance_derived_files(population, &stats, fallbacks)?;
        let writing = writing_started.elapsed().as_secs_f64();
        let wall_seconds = until_written(writing);
        if let Some(profile) = &mut self.profile {
            let line = GenerationProfile {
                fine_walk,
                ..GenerationProfile::new(
                    generation,
                    rayon::current_num_threads() as u32,
                    Evaluator::current().ranks(),
                    evaluations,
                    times,
                    fine,
                    writing,
                    wall_seconds,
                )
            };
            profile.add(&line)?;
        }
        // The store counts the reused among the members; the report, every evaluation
        // reused this generation where the members do not say (a birth not kept).
        if let Some(reused) = reused {
            stats.reused = reused;
        }
        observer(&GenerationReport {
            generation,
            stats,
            wall_seconds,
            evaluation_seconds: evaluated + fine,
            fallbacks: fallbacks.clone(),
        });
        Ok(())
    }

    /// The task specification of the fine reference check: the run's, with the simulator at
    /// its fine reference setting.
    pub fn fine_task(&self) -> TaskSpec {
        TaskSpec {
            sim: self.config.task.sim.fine_reference(),
            ..self.config.task.clone()
        }
    }

    /// `individual` developed again (same limits and development seed as in the run) and
    /// evaluated with [`Run::fine_task`]: a pure function of the genome and the task;
    /// `Interrupted` once `cancel` is set.
    pub fn fine_evaluation(
        &self,
        individual: &Individual<G>,
        cancel: &Cancel,
    ) -> Result<FineEvaluation, Interrupted> {
        fine_walk(
            &individual.genome,
            &self.evolution.limits,
            individual.develop_seed,
            &self.fine_task(),
            cancel,
        )
    }

    /// Stores a generation (one transaction); `stats` gets its timings first: its wall
    /// seconds are `wall(seconds spent writing so far)`.
    pub(super) fn record(
        &mut self,
        population: &[Individual<G>],
        stats: &mut GenerationRecord,
        wall: &dyn Fn(f64) -> f64,
    ) -> Result<(), RunError> {
        let writing_started = Instant::now();
        let generation = stats.index;
        let individuals = population
            .iter()
            .enumerate()
            .map(|(index, i)| {
                Ok(IndividualRecord {
                    generation,
                    index: index as u32,
                    parents: i.parents.clone(),
                    operator: i.operator.name().to_string(),
                    genome_text: i.genome.to_text(),
                    genome_json: serde_json::to_string(i)
                        .map_err(|e| RunError::Corrupt(e.to_string()))?,
                    fitness: i.evaluation.fitness,
                    status: status_name(i),
                    terms_json: serde_json::to_string(&i.evaluation.terms)
                        .map_err(|e| RunError::Corrupt(e.to_string()))?,
                    parts: i.size.0,
                    joints: i.size.1,
                    neurons: i.size.2,
                    reused: i.reused,
                    evaluation_key: i.key.map(|k| k.to_hex()),
                    parents_generation: i.parents_generation,
                })
            })
            .collect::<Result<Vec<_>, RunError>>()?;
        stats.wall_seconds = wall(writing_started.elapsed().as_secs_f64());
        stats.evaluations_per_second = stats.evaluations as f64 / stats.wall_seconds.max(1e-9);
        self.store.write_generation(stats, &individuals)?;
        Ok(())
    }
}

/// A generation bred and evaluated, with its best's fine reference figure: what
/// [`Run::store_generation`] stores.
pub(super) struct Concluded<'a, G> {
    pub(super) generation: u32,
    pub(super) population: &'a [Individual<G>],
    /// Children made by mutation so far because the encoding lacks an operator.
    pub(super) fallbacks: &'a Fallbacks,
    pub(super) evaluations: u64,
    /// A steady-state block's births that reused an evaluation, kept or not.
    pub(super) reused: Option<u64>,
    pub(super) times: GenerationTimes,
    /// Seconds from its start to the end of its walks.
    pub(super) evaluated: f64,
    pub(super) best_fine: Option<FineEvaluation>,
    /// Seconds the run waited for the fine re-walk.
    pub(super) fine: f64,
    /// The fine re-walk's own seconds when it walked beside the next generation (0 when its
    /// figure was known); `None` when `fine` is the walk itself.
    pub(super) fine_walk: Option<f64>,
}

/// `genome` developed with `limits` and its development seed and evaluated with the fine
/// reference `task` (generation 0's trials, so that every generation's best sees the same
/// draws of its creature): the figure stored beside a generation's best.
pub(super) fn fine_walk<G: Genome>(
    genome: &G,
    limits: &G::Limits,
    develop_seed: u64,
    task: &TaskSpec,
    cancel: &Cancel,
) -> Result<FineEvaluation, Interrupted> {
    let evaluation =
        crate::evolve::habitats::evaluate_genome(genome, limits, develop_seed, task, 0, cancel)?;
    Ok(FineEvaluation {
        fitness: evaluation.fitness,
        status: status_text(&evaluation),
    })
}
