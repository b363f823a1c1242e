//! The fine reference re-walk of a generation's best, walked beside the run's next work: on a
//! thread of its own (with a one-thread pool of its own, so that it takes nothing from the
//! run's threads and never waits on them). A generation whose best needs the walk is set
//! aside ([`Pending`]) and stored when the next generation (or block of births) is evaluated,
//! once its figure is in, before that one is; one whose figure is known (an elite copy of
//! the previous best, the cache's, or none asked) is stored at once. Both algorithms use it: a generational run walks it beside the next
//! generation's breeding and walks, a steady-state run beside the next block's births.
//!
//! The fine figure only reports, and it is a pure function of the genome and the task, so the
//! run and its store are those of a run that re-walks each best before going on. A run
//! stopped (or killed) before a generation is stored makes that generation again when
//! resumed, the same.

use std::thread::{Scope, ScopedJoinHandle};
use std::time::{Duration, Instant};

use rayon::{ThreadPool, ThreadPoolBuilder};

use super::conclude::{Concluded, fine_walk};
use super::pool::message;
use super::progress::{FineToFind, Progress};
use super::{GenerationReport, Run, RunError};
use crate::cancel::Interrupted;
use crate::encoding::Genome;
use crate::evolve::ga::{Fallbacks, Individual};
use crate::evolve::timing::GenerationTimes;
use crate::run::store::FineEvaluation;

/// A generation bred and evaluated, waiting for its best's fine reference figure before it
/// is stored.
pub(super) struct Pending<'scope, G> {
    generation: u32,
    population: Vec<Individual<G>>,
    /// Children made by mutation so far because the encoding lacks an operator.
    fallbacks: Fallbacks,
    evaluations: u64,
    /// A steady-state block's births that reused an evaluation, kept or not.
    reused: Option<u64>,
    times: GenerationTimes,
    /// Seconds from its start to the end of its walks.
    evaluated: f64,
    /// Its best's index, if it has one.
    best: Option<usize>,
    fine: Fine<'scope>,
}

/// A generation's best's fine reference figure: known, or walking on its own thread (the
/// walk's result and its own duration).
enum Fine<'scope> {
    Known(Option<FineEvaluation>),
    Walking(ScopedJoinHandle<'scope, (Result<FineEvaluation, Interrupted>, Duration)>),
}

/// A generation just evaluated, to conclude: its number, its evaluations (and, for a
/// steady-state block, how many reused a stored evaluation), its steps' times, when it
/// started and the seconds from then to the end of its walks.
pub(super) struct Evaluated {
    pub(super) generation: u32,
    pub(super) evaluations: u64,
    pub(super) reused: Option<u64>,
    pub(super) times: GenerationTimes,
    pub(super) started: Instant,
    pub(super) evaluated: f64,
}

/// The one-thread pool the fine re-walks walk in; `None` when the system refused a thread
/// (each best is then re-walked before its generation is stored).
pub(super) fn fine_pool() -> Option<ThreadPool> {
    ThreadPoolBuilder::new()
        .num_threads(1)
        .thread_name(|_| "fine re-walk".to_string())
        .build()
        .ok()
}

impl<G: Genome> Run<G> {
    /// Concludes the generation `pending` holds, if any (waiting for its figure), then sets
    /// `evaluated` (the population `progress` holds) aside with its best's fine reference
    /// figure walking on a thread of `scope` in `pool`, or stores it at once when its figure
    /// is known, or, without a pool, after walking it here.
    pub(super) fn hand_over<'scope>(
        &mut self,
        scope: &'scope Scope<'scope, '_>,
        pool: Option<&'scope ThreadPool>,
        progress: &mut Progress<G>,
        pending: &mut Option<Pending<'scope, G>>,
        evaluated: Evaluated,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError>
    where
        G: 'scope,
        G::Limits: 'scope,
    {
        if let Some(previous) = pending.take() {
            self.conclude_pending(progress, previous, observer)?;
        }
        // Told to stop (by the observer, say): nothing more is stored.
        self.cancel.check()?;
        let Evaluated {
            generation,
            evaluations,
            reused,
            times,
            started,
            evaluated,
        } = evaluated;
        let Some(pool) = pool else {
            let counts = (evaluations, reused);
            return self.conclude(progress, generation, counts, times, started, observer);
        };
        let (best, fine) = match self.fine_to_find(progress) {
            FineToFind::Unasked => (None, Fine::Known(None)),
            FineToFind::Known(best, fine) => (Some(best), Fine::Known(Some(fine))),
            FineToFind::Walk(best) => {
                let individual = &progress.population[best];
                let genome = individual.genome.clone();
                let develop_seed = individual.develop_seed;
                let limits = self.evolution.limits.clone();
                let task = self.fine_task();
                let cancel = self.cancel.clone();
                let spawned = std::thread::Builder::new()
                    .name("fine re-walk".to_string())
                    .spawn_scoped(scope, move || {
                        let started = Instant::now();
                        let fine = pool
                            .install(|| fine_walk(&genome, &limits, develop_seed, &task, &cancel));
                        (fine, started.elapsed())
                    });
                let Ok(walking) = spawned else {
                    // The system refused a thread: walked here, before it is stored.
                    let counts = (evaluations, reused);
                    return self.conclude(progress, generation, counts, times, started, observer);
                };
                (Some(best), Fine::Walking(walking))
            }
        };
        let set_aside = Pending {
            generation,
            population: progress.population.clone(),
            fallbacks: progress.fallbacks.clone(),
            evaluations,
            reused,
            times,
            evaluated,
            best,
            fine,
        };
        match set_aside.fine {
            Fine::Known(_) => self.conclude_pending(progress, set_aside, observer),
            Fine::Walking(_) => {
                *pending = Some(set_aside);
                Ok(())
            }
        }
    }

    /// The end of a run loop that handed its generations over ([`Run::hand_over`]): after
    /// `outcome`, the generation still pending is stored, or, after an error, its walk is
    /// stopped and waited for.
    pub(super) fn finish_beside(
        &mut self,
        progress: &mut Progress<G>,
        mut pending: Option<Pending<'_, G>>,
        mut outcome: Result<(), RunError>,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError> {
        if outcome.is_ok()
            && let Some(last) = pending.take()
        {
            outcome = self.conclude_pending(progress, last, observer);
        }
        if outcome.is_err() {
            // A fine re-walk still walking stops at its next control step.
            self.cancel.cancel();
            if let Some(Pending {
                fine: Fine::Walking(walking),
                ..
            }) = pending.take()
            {
                let _ = walking.join();
            }
        }
        outcome
    }

    /// Waits for `pending`'s fine reference figure, then stores it and tells `observer`.
    pub(super) fn conclude_pending(
        &mut self,
        progress: &mut Progress<G>,
        pending: Pending<'_, G>,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError> {
        let waited = Instant::now();
        let (best_fine, walk) = match pending.fine {
            Fine::Known(fine) => (fine, 0.0),
            Fine::Walking(walking) => {
                let (fine, walk) = walking
                    .join()
                    .map_err(|panic| RunError::Panicked(message(panic.as_ref())))?;
                let fine = fine?;
                let key = pending.best.and_then(|b| pending.population[b].key);
                if let Some(key) = key {
                    self.cache.insert_fine(key, &fine);
                }
                (Some(fine), walk.as_secs_f64())
            }
        };
        let fine = waited.elapsed().as_secs_f64();
        progress.remember_best(pending.best, best_fine.clone());
        self.store_generation(
            Concluded {
                generation: pending.generation,
                population: &pending.population,
                fallbacks: &pending.fallbacks,
                evaluations: pending.evaluations,
                reused: pending.reused,
                times: pending.times,
                evaluated: pending.evaluated,
                best_fine,
                fine,
                fine_walk: Some(walk),
            },
            observer,
        )
    }
}
