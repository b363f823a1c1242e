//! A generation's record as the genetic algorithm computes it: its fitness statistics and
//! the fine re-walk of its best ([`FineEvaluation`]), which the run store keeps.

/// The evaluation of a generation's best individual at the fine reference setting
/// ([`crate::sim::SimOptions::fine_reference`]): a check that its fitness is not an artefact
/// of the evaluator's coarse stepping.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FineEvaluation {
    /// Its fitness at the fine reference (NaN if the evaluation gave none).
    pub fitness: f64,
    /// The evaluation's status, e.g. `ok` or the reason it failed.
    pub status: String,
}

/// One generation's statistics, as the genetic algorithm computes them
/// ([`GenerationRecord::of`](crate::evolve::ga)) and the run store keeps them. Statistics of an
/// empty sample (no valid individual) are NaN (`null` in JSON).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct GenerationRecord {
    /// The generation's index, from 0.
    #[serde(rename = "generation")]
    pub index: u32,
    /// The best fitness.
    pub best: f64,
    /// The mean fitness (the GA computes it over valid individuals).
    pub mean: f64,
    /// The median fitness (the GA computes it over valid individuals).
    pub median: f64,
    /// The standard deviation of fitness (over valid individuals).
    pub sd: f64,
    /// The fraction of individuals whose evaluation succeeded, in [0, 1].
    pub valid_fraction: f64,
    /// How many evaluations the generation ran (the elite is not evaluated again).
    pub evaluations: u64,
    /// Of which reused from an identical creature evaluated earlier in the run (the others
    /// were simulated). Not a column of its own: the store counts its individuals' `reused`
    /// flags (0 in a store older than schema version 3), and
    /// [`RunStore::write_generation`](crate::run::store::RunStore::write_generation) does not read it.
    pub reused: u64,
    /// Wall-clock seconds the generation took until it was stored (NaN before).
    pub wall_seconds: f64,
    /// `evaluations / wall_seconds` (NaN before the generation is stored).
    pub evaluations_per_second: f64,
    /// The best individual (rank 1) re-walked at the fine reference setting; `None` when it
    /// was not (the run's `verify_best` is off, or the generation predates schema version 2).
    pub best_fine: Option<FineEvaluation>,
}
