//! The spread of a generation's best individual over its habitats and trials: the lowest and
//! highest fitness of its walks, around the fitness they combine into (the aggregate). The
//! fitness plot and the viewer's run page draw it as a band around the best; a run without
//! habitats or trials has none.

use super::store::{RunStore, StoreError};
use crate::evolve::ga::ranking_by;
use crate::task::{Evaluation, FAILURE_FITNESS};

/// The lowest and highest fitness of one generation's best individual's walks (one per
/// habitat and trial).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    /// The generation's index.
    pub generation: u32,
    /// The lowest fitness of its walks.
    pub low: f64,
    /// The highest.
    pub high: f64,
}

impl Spread {
    /// The spread of `fitnesses` (a walk's each) in `generation`, of the walks that did not
    /// fail (a failed walk scores the failure floor, which says nothing of the spread);
    /// `None` when no walk is left.
    pub fn of_walks(generation: u32, fitnesses: impl IntoIterator<Item = f64>) -> Option<Spread> {
        let (low, high) = fitnesses
            .into_iter()
            .filter(|f| f.is_finite() && *f > FAILURE_FITNESS)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), f| {
                (lo.min(f), hi.max(f))
            });
        (low <= high).then_some(Spread {
            generation,
            low,
            high,
        })
    }

    /// The spread of `evaluation`'s walks ([`Evaluation::units`]) in `generation`; `None` for
    /// an evaluation without habitats or trials.
    pub fn of(generation: u32, evaluation: &Evaluation) -> Option<Spread> {
        Spread::of_walks(generation, evaluation.units().iter().map(|u| u.fitness))
    }
}

/// The spread of each stored generation's best individual (rank 1), in generation order; a
/// generation whose best has no walks of its own (a run without habitats or trials) has none.
/// Reads every individual of the store: call it for a run with habitats or trials only.
pub fn stored_spreads(store: &RunStore) -> Result<Vec<Spread>, StoreError> {
    let mut spreads = Vec::new();
    for g in store.generations()? {
        let individuals = store.individuals(g.index)?;
        let Some(&best) = ranking_by(&individuals, |i| i.fitness).first() else {
            continue;
        };
        // The individual's JSON holds its evaluation, with a result per walk.
        let json: serde_json::Value =
            serde_json::from_str(&individuals[best].genome_json).unwrap_or_default();
        let walks: Vec<f64> = json["evaluation"]["habitats"]
            .as_array()
            .map(|units| units.iter().filter_map(|u| u["fitness"].as_f64()).collect())
            .unwrap_or_default();
        spreads.extend(Spread::of_walks(g.index, walks));
    }
    Ok(spreads)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_spread_leaves_out_failed_walks_and_is_none_without_walks() {
        let spread = Spread::of_walks(4, [1.5, FAILURE_FITNESS, -0.25, 3.0, f64::NAN]);
        assert_eq!(
            spread,
            Some(Spread {
                generation: 4,
                low: -0.25,
                high: 3.0
            })
        );
        assert_eq!(Spread::of_walks(4, []), None);
        assert_eq!(Spread::of_walks(4, [FAILURE_FITNESS]), None);
    }
}
