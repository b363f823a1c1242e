//! The run loop of a generational run: each generation bred and evaluated while the fine
//! reference re-walk of the previous generation's best walks beside it, on a thread of its
//! own (with a one-thread pool of its own, so that it takes nothing from the run's threads and
//! never waits on them), so that the run's threads do not wait for that one long walk between
//! two generations. A generation whose best needs the walk is stored once its figure is in:
//! after the next generation's walks; one whose figure is known (an elite copy of the previous
//! best, the cache's, or none asked) is stored at once.
//!
//! The fine figure only reports, and it is a pure function of the genome and the task, so the
//! run and its store are those of a run that re-walks each best before going on. A run
//! stopped (or killed) before a generation is stored makes that generation again when
//! resumed, the same: it loses at most the work of the two generations it was between.

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
struct Pending<'scope, G> {
    generation: u32,
    population: Vec<Individual<G>>,
    /// Children made by mutation so far because the encoding lacks an operator.
    fallbacks: Fallbacks,
    evaluations: u64,
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

impl<G: Genome> Run<G> {
    /// Runs a generational run's remaining generations, calling `observer` after each is
    /// stored (one generation after its walks, with the last one's at the end).
    pub(super) fn run_generational(
        &mut self,
        progress: &mut Progress<G>,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError> {
        let generations = self.config.ga.generations as u32;
        // Without a pool of its own (the system refused a thread), each best is re-walked
        // before its generation is stored, as a steady-state run does.
        let fine_pool = ThreadPoolBuilder::new()
            .num_threads(1)
            .thread_name(|_| "fine re-walk".to_string())
            .build()
            .ok();
        std::thread::scope(|scope| {
            let mut pending: Option<Pending<'_, G>> = None;
            let mut outcome = (|| -> Result<(), RunError> {
                for generation in progress.next..generations {
                    self.cancel.check()?;
                    let started = Instant::now();
                    let mut times = GenerationTimes::default();
                    let evaluations = self.breed(progress, generation, &mut times)?;
                    let evaluated = started.elapsed().as_secs_f64();
                    if let Some(previous) = pending.take() {
                        self.conclude_pending(progress, previous, observer)?;
                    }
                    // Told to stop (by the observer, say): nothing more is stored.
                    self.cancel.check()?;
                    let Some(pool) = &fine_pool else {
                        let counts = (evaluations, None);
                        self.conclude(progress, generation, counts, times, started, observer)?;
                        continue;
                    };
                    let this = (evaluations, times, evaluated);
                    let set_aside = self.begin_fine(scope, pool, progress, generation, this);
                    match set_aside.fine {
                        Fine::Known(_) => self.conclude_pending(progress, set_aside, observer)?,
                        Fine::Walking(_) => pending = Some(set_aside),
                    }
                }
                Ok(())
            })();
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
        })
    }

    /// Generation `generation`, just evaluated (`evaluations` made in `evaluated` seconds,
    /// its steps' `times`), set aside with its best's fine reference figure known or being
    /// walked on a thread of `scope` in `pool`.
    fn begin_fine<'scope>(
        &self,
        scope: &'scope Scope<'scope, '_>,
        pool: &'scope ThreadPool,
        progress: &Progress<G>,
        generation: u32,
        (evaluations, times, evaluated): (u64, GenerationTimes, f64),
    ) -> Pending<'scope, G>
    where
        G: 'scope,
        G::Limits: 'scope,
    {
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
                let walking = scope.spawn(move || {
                    let started = Instant::now();
                    let fine =
                        pool.install(|| fine_walk(&genome, &limits, develop_seed, &task, &cancel));
                    (fine, started.elapsed())
                });
                (Some(best), Fine::Walking(walking))
            }
        };
        Pending {
            generation,
            population: progress.population.clone(),
            fallbacks: progress.fallbacks.clone(),
            evaluations,
            times,
            evaluated,
            best,
            fine,
        }
    }

    /// Waits for `pending`'s fine reference figure, then stores it and tells `observer`.
    fn conclude_pending(
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
                reused: None,
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
