//! How an individual is made: the operators, Chaumont's schedule of them over a
//! generation's children, and the count of children made by mutation because the encoding
//! lacks the scheduled operator.

use serde::{Deserialize, Serialize};

use super::settings::{GaSettings, Preset};

/// How an individual was made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Operator {
    /// A random genome of the first generation.
    Random,
    /// A mutant of a hand-written grammar (`--init`), in the first generation.
    Init,
    /// Kept unchanged from the previous generation.
    Elite,
    /// Mutation alone.
    Mutation,
    /// Crossover (then perhaps mutation).
    Crossover,
    /// Grafting (then perhaps mutation).
    Graft,
}

impl Operator {
    /// The name the run store uses.
    pub fn name(self) -> &'static str {
        match self {
            Operator::Random => "random",
            Operator::Init => "init",
            Operator::Elite => "elite",
            Operator::Mutation => "mutation",
            Operator::Crossover => "crossover",
            Operator::Graft => "graft",
        }
    }
}

/// Children made by mutation because the encoding lacks the scheduled operator.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Fallbacks {
    /// Instead of crossover.
    pub crossover: u64,
    /// Instead of grafting.
    pub graft: u64,
}

impl Fallbacks {
    /// Counts a child made by mutation instead of `op`.
    pub(super) fn count(&mut self, op: Operator) {
        match op {
            Operator::Crossover => self.crossover += 1,
            _ => self.graft += 1,
        }
    }

    /// Counts individual `index` of a generation after the first, stored as made by
    /// `operator` in a run with `settings`: a child made by mutation alone where the schedule
    /// asked for crossover or grafting is one the encoding could not mate. The schedule is a
    /// function of the index alone ([`schedule`]; Walking with Dinosaurs' always mates), so
    /// the count read back from a run store equals the one the run made.
    pub fn count_stored(&mut self, settings: &GaSettings, index: usize, operator: Operator) {
        let survivors = settings.survivors().min(settings.population);
        if index < survivors || operator != Operator::Mutation {
            return;
        }
        let scheduled = match settings.preset {
            Preset::Chaumont => schedule(
                index - survivors,
                settings.population - survivors,
                settings.asexual,
                settings.crossover,
            ),
            Preset::Wwd => Operator::Crossover,
        };
        if scheduled != Operator::Mutation {
            self.count(scheduled);
        }
    }
}

/// Chaumont's operator for child `k` of `children`: the first round(asexual × children) by
/// mutation, the next round(crossover × children) by crossover, the rest by grafting (exact
/// proportions rather than a draw per child, so every generation has the preset's mix).
pub fn schedule(k: usize, children: usize, asexual: f64, crossover: f64) -> Operator {
    let by_mutation = (asexual * children as f64).round() as usize;
    let by_crossover = (crossover * children as f64).round() as usize;
    if k < by_mutation {
        Operator::Mutation
    } else if k < by_mutation + by_crossover {
        Operator::Crossover
    } else {
        Operator::Graft
    }
}
