//! Where a run stands between two generations, and the steps of one: the state a run goes on
//! from (its last generation, the cache, the fine re-walk of its best, the fallbacks), a
//! generation bred and evaluated, and its best re-walked at the fine reference.

use rayon::prelude::*;

use super::{Run, RunError};
use crate::encoding::Genome;
use crate::evolve::evaluator_version::EVALUATOR_VERSION;
use crate::evolve::ga::{Algorithm, Fallbacks, Individual, Operator, ranking};
use crate::evolve::timing::GenerationTimes;
use crate::run::store::FineEvaluation;

/// Where a run stands between two generations.
pub(super) struct Progress<G> {
    /// The index of the generation to come.
    pub(super) next: u32,
    /// The last generation (none before the first).
    pub(super) population: Vec<Individual<G>>,
    /// Its best (the index) and that one's fine reference evaluation: an elite copy of it
    /// needs no second walk.
    pub(super) previous_best: Option<(u32, FineEvaluation)>,
    /// Children made by mutation so far because the encoding lacks an operator.
    pub(super) fallbacks: Fallbacks,
}

impl<G: Genome> Run<G> {
    /// Where the run stands before its next generation: the last stored generation read back
    /// (keyed again if it was stored before evaluation keys were), the evaluation cache
    /// rebuilt from the store, the fine re-walk of that generation's best, the fallbacks
    /// counted so far; and the derived files written, if they were not yet.
    pub(super) fn progress(&mut self) -> Result<Progress<G>, RunError> {
        let (mut population, next) = match self.store.last_generation()? {
            None => (Vec::new(), 0),
            Some(g) => (self.population(g)?, g + 1),
        };
        self.rebuild_cache()?;
        self.key_again(&mut population);
        let previous_best = self.stored_best_fine(&population, next)?;
        let fallbacks = self
            .fallbacks_by_generation()?
            .last()
            .cloned()
            .unwrap_or_default();
        if self.written.is_none() {
            self.write_derived_files()?;
        }
        Ok(Progress {
            next,
            population,
            previous_best,
            fallbacks,
        })
    }

    /// A generation stored before evaluation keys existed (a migrated store): its
    /// individuals are keyed again, so its elites carry their keys on, and join the cache.
    fn key_again(&mut self, population: &mut [Individual<G>]) {
        if population.iter().all(|i| i.key.is_some()) {
            return;
        }
        let evolution = &self.evolution;
        population
            .par_iter_mut()
            .filter(|i| i.key.is_none())
            .for_each(|i| i.key = evolution.key(&i.genome, i.develop_seed));
        for i in population.iter() {
            if let (Some(key), false) = (i.key, i.reused) {
                self.cache.insert(key, &i.evaluation);
            }
        }
    }

    /// The best of the last stored generation, `population` (its index), and its stored fine
    /// reference evaluation, when this program's evaluator made that generation; `next` is
    /// the index of the generation to come.
    fn stored_best_fine(
        &self,
        population: &[Individual<G>],
        next: u32,
    ) -> Result<Option<(u32, FineEvaluation)>, RunError> {
        if next > 0
            && self.store.evaluators()?.last().map(|&(_, v)| v) == Some(EVALUATOR_VERSION)
            && let Some(&best) = ranking(population).first()
            && let Some(stored) = self.store.generations()?.pop().and_then(|g| g.best_fine)
        {
            return Ok(Some((best as u32, stored)));
        }
        Ok(None)
    }

    /// Makes and evaluates generation `generation` (random, or bred from the progress's
    /// population, which it replaces); returns how many were evaluated. `times` gets where
    /// the time went.
    pub(super) fn breed(
        &mut self,
        progress: &mut Progress<G>,
        generation: u32,
        times: &mut GenerationTimes,
    ) -> Result<u64, RunError> {
        let (next, evaluations) = if generation == 0 {
            let first =
                self.evolution
                    .first_generation_timed(&mut self.cache, &self.cancel, times)?;
            let n = first.len() as u64;
            (first, n)
        } else {
            self.evolution.next_generation_timed(
                &progress.population,
                generation,
                &mut progress.fallbacks,
                &mut self.cache,
                &self.cancel,
                times,
            )?
        };
        progress.population = next;
        Ok(evaluations)
    }

    /// With `verify_best`, the fine reference re-walk of the population's best: the previous
    /// generation's when the best is its elite copy, the cache's when it holds one, else
    /// walked now (and cached), as an evaluation is a pure function of the genome, its
    /// development seed and the task. Remembered for the next generation.
    pub(super) fn verify_best(
        &mut self,
        progress: &mut Progress<G>,
    ) -> Result<Option<FineEvaluation>, RunError> {
        let best_fine = match self.fine_to_find(progress) {
            FineToFind::Unasked => None,
            FineToFind::Known(_, fine) => Some(fine),
            FineToFind::Walk(best) => {
                let b = &progress.population[best];
                let fine = self.fine_evaluation(b, &self.cancel)?;
                if let Some(key) = b.key {
                    self.cache.insert_fine(key, &fine);
                }
                Some(fine)
            }
        };
        let best = ranking(&progress.population).first().copied();
        progress.remember_best(best, best_fine.clone());
        Ok(best_fine)
    }

    /// Where the fine reference figure of the population's best comes from: none asked
    /// (`verify_best` off, or no population), one known already (the previous generation's
    /// best's when this is its elite copy, or the cache's), or a walk to make.
    pub(super) fn fine_to_find(&self, progress: &Progress<G>) -> FineToFind {
        let Some(best) = ranking(&progress.population).first().copied() else {
            return FineToFind::Unasked;
        };
        if !self.config.verify_best {
            return FineToFind::Unasked;
        }
        let steady = self.config.ga.algorithm == Algorithm::SteadyState;
        let b = &progress.population[best];
        match &progress.previous_best {
            // A steady-state run's best in the same slot, not replaced since
            // ([`Run::run_steady`] forgets it otherwise), is the same individual.
            Some((p, fine))
                if (b.operator == Operator::Elite && b.parents == [*p])
                    || (steady && best as u32 == *p) =>
            {
                FineToFind::Known(best, fine.clone())
            }
            _ => match b.key.and_then(|k| self.cache.fine(&k).cloned()) {
                Some(fine) => FineToFind::Known(best, fine),
                None => FineToFind::Walk(best),
            },
        }
    }
}

/// Where a generation's best's fine reference figure comes from ([`Run::fine_to_find`]).
pub(super) enum FineToFind {
    /// `verify_best` is off, or there is no population.
    Unasked,
    /// The best (its index) and its figure, known without a walk.
    Known(usize, FineEvaluation),
    /// The best (its index), to walk at the fine reference.
    Walk(usize),
}

impl<G> Progress<G> {
    /// Remembers the fine reference figure of the best of the generation just concluded
    /// (its index), for the next generation: an elite copy of it needs no second walk.
    pub(super) fn remember_best(&mut self, best: Option<usize>, fine: Option<FineEvaluation>) {
        self.previous_best = best.zip(fine).map(|(b, f)| (b as u32, f));
    }
}
