//! Reporting interpenetrating parts as errors on the creature.

use crate::creature::{Creature, Problem, Severity};

/// Adds an error for every pair of parts that interpenetrate other than at a joint (see
/// [`Creature::interpenetrating_pairs`]).
pub(super) fn report(creature: &mut Creature, t: Option<f64>) {
    for (a, b) in creature.interpenetrating_pairs() {
        creature.problems.push(Problem {
            severity: Severity::Error,
            message: format!("parts {a} and {b} interpenetrate"),
            module: None,
            t,
        });
    }
}
