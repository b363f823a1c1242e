//! The limits every encoding shares on the creature its genome develops into, whatever made
//! it: `[limits] max_neurons` (the brain's neurons, sensors and actuators included, counted as
//! the run store's `neurons` column counts them) and `[limits] max_chain` (the parts of the
//! body's longest sequence joined end to end, Hornby & Pollack's "bars in a row";
//! [`Creature::longest_chain`]). Both are absent unless a run sets them; a developed creature
//! past one is invalid, with an error-level problem that says which, as a creature with more
//! parts than `max_parts` is.

use crate::creature::{Creature, Problem, Severity};

/// The `[limits]` keys every encoding has, as one encoding's limits hold them
/// ([`CheckedLimits::creature_limits`](super::CheckedLimits::creature_limits)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CreatureLimits {
    /// Most neurons ([`Creature::neuron_count`]); `None`: no limit.
    pub max_neurons: Option<usize>,
    /// Most parts in a row ([`Creature::longest_chain`]); `None`: no limit.
    pub max_chain: Option<usize>,
}

impl CreatureLimits {
    /// What `creature` breaks of these limits, a message each (none when it keeps them).
    pub fn broken(&self, creature: &Creature) -> Vec<String> {
        let mut broken = Vec::new();
        if let Some(most) = self.max_neurons {
            let neurons = creature.neuron_count();
            if neurons > most {
                broken.push(format!(
                    "{neurons} neurons, more than limits.max_neurons = {most}"
                ));
            }
        }
        if let Some(most) = self.max_chain {
            let chain = creature.longest_chain();
            if chain > most {
                broken.push(format!(
                    "a chain of {chain} parts in a row, more than limits.max_chain = {most}"
                ));
            }
        }
        broken
    }

    /// `creature` with an error-level problem for each limit it breaks ([`Self::broken`]),
    /// which makes it invalid; unchanged when it keeps them, or when no limit is set.
    pub fn apply(&self, creature: &mut Creature) {
        for message in self.broken(creature) {
            creature.problems.push(Problem {
                severity: Severity::Error,
                message,
                module: None,
                t: None,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::develop::creature_from_commands;

    #[test]
    fn a_creature_past_a_limit_gets_an_error_that_names_the_key() {
        // Three parts in a row; the brain's first oscillator and one output neuron for the
        // hinge: 2 neurons.
        let grown =
            creature_from_commands("forward(1) revolute2 forward(1) output(1) forward(1)").unwrap();
        assert_eq!((grown.neuron_count(), grown.longest_chain()), (2, 3));
        assert!(grown.is_valid());
        let at = |max_neurons, max_chain| CreatureLimits {
            max_neurons,
            max_chain,
        };
        for (limits, errors) in [
            (CreatureLimits::default(), vec![]),
            (at(Some(2), Some(3)), vec![]),
            (
                at(None, Some(2)),
                vec!["a chain of 3 parts in a row, more than limits.max_chain = 2"],
            ),
            (
                at(Some(1), None),
                vec!["2 neurons, more than limits.max_neurons = 1"],
            ),
            (
                at(Some(1), Some(1)),
                vec![
                    "2 neurons, more than limits.max_neurons = 1",
                    "a chain of 3 parts in a row, more than limits.max_chain = 1",
                ],
            ),
        ] {
            let mut c = grown.clone();
            limits.apply(&mut c);
            let said: Vec<&str> = c.problems[grown.problems.len()..]
                .iter()
                .map(|p| p.message.as_str())
                .collect();
            assert_eq!(said, errors, "{limits:?}");
            assert_eq!(c.is_valid(), errors.is_empty(), "{limits:?}");
        }
    }
}
