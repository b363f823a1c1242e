//! A run's evaluation cache: every evaluation the run made, by the key of the creature and
//! task it evaluated ([`EvaluationKey`]), so an individual identical to one evaluated before
//! reuses that evaluation instead of simulating it again. The same holds for the fine
//! reference re-walk of a generation's best. A resumed run rebuilds the cache from its store.

use std::collections::HashMap;

use super::key::EvaluationKey;
use super::record::FineEvaluation;
use crate::task::Evaluation;

/// The evaluations of a run by key; an off cache (`--no-cache`) holds and finds nothing.
#[derive(Clone, Debug, Default)]
pub struct EvaluationCache {
    enabled: bool,
    evaluations: HashMap<EvaluationKey, Evaluation>,
    fine: HashMap<EvaluationKey, FineEvaluation>,
}

impl EvaluationCache {
    /// An empty cache, on or off.
    pub fn new(enabled: bool) -> EvaluationCache {
        EvaluationCache {
            enabled,
            ..EvaluationCache::default()
        }
    }

    /// Whether the cache is on.
    pub fn enabled(&self) -> bool {
        self.enabled
    }

    /// The evaluation of `key` made earlier in the run, if the cache is on and holds it.
    pub fn get(&self, key: &EvaluationKey) -> Option<&Evaluation> {
        self.evaluations.get(key)
    }

    /// Keeps `evaluation` as the evaluation of `key` (nothing when the cache is off; the
    /// first evaluation of a key stays).
    pub fn insert(&mut self, key: EvaluationKey, evaluation: &Evaluation) {
        if self.enabled {
            self.evaluations
                .entry(key)
                .or_insert_with(|| evaluation.clone());
        }
    }

    /// The fine reference re-walk of the creature of `key` (its key with the run's task),
    /// if the cache is on and holds it.
    pub fn fine(&self, key: &EvaluationKey) -> Option<&FineEvaluation> {
        self.fine.get(key)
    }

    /// Keeps `fine` as the fine reference re-walk of the creature of `key`.
    pub fn insert_fine(&mut self, key: EvaluationKey, fine: &FineEvaluation) {
        if self.enabled {
            self.fine.entry(key).or_insert_with(|| fine.clone());
        }
    }

    /// How many evaluations it holds.
    pub fn len(&self) -> usize {
        self.evaluations.len()
    }

    /// Whether it holds no evaluation.
    pub fn is_empty(&self) -> bool {
        self.evaluations.is_empty()
    }
}
