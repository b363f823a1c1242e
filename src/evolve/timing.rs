//! Where a generation's time goes, as the genetic algorithm measures it: the wall time of its
//! steps (breeding, developing, keying, evaluating) and of every walk it simulated, with the
//! thread that ran it. Timings are reported, never used: no choice of the genetic algorithm
//! reads a clock, so a run is the same whether it is timed or not.

/// One walk the evaluator ran: whose it was, how long it took and where it ran.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WalkTime {
    /// The individual's index in its generation.
    pub individual: u32,
    /// Wall-clock seconds of the walk (building its world and stepping it).
    pub seconds: f64,
    /// The worker thread that ran it, from 0 (rayon's index in its pool).
    pub thread: u32,
    /// The MPI rank that ran it (0 without MPI).
    pub rank: u32,
    /// The parts of the creature it walked: what the longest-first order ranks walks by
    /// ([`crate::evolve::ga::WalkOrder::LongestFirst`]). 0 in a profile written before it
    /// was recorded.
    #[serde(default)]
    pub parts: u32,
}

/// Wall-clock seconds of the steps of one generation inside the genetic algorithm, and its
/// walks in the order the evaluator was handed them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GenerationTimes {
    /// Making the new genomes: ranking the previous generation, carrying the elite over and
    /// varying the rest (random genomes in the first generation).
    pub breeding: f64,
    /// Developing every new genome into its creatures (one per habitat).
    pub developing: f64,
    /// Computing the evaluation keys of the developed creatures.
    pub keying: f64,
    /// The evaluator's batch: every walk simulated, from the first handed out to the last
    /// back.
    pub evaluating: f64,
    /// The walks, in the order the evaluator was handed them. Empty when the batch went to MPI
    /// ranks, which do not report their walks' times.
    pub walks: Vec<WalkTime>,
}
