//! Reporting interpenetrating parts as problems of the creature: errors where physics needs
//! a valid creature, warnings in a picture.

use crate::creature::{Creature, Problem, Severity};

/// The most pairs named one by one: beyond them, one problem counts the pairs and names the
/// first few (a plant of thousands of parts has thousands of such pairs).
const NAMED_PAIRS: usize = 5;

/// Adds a problem of `severity` for every pair of parts that interpenetrate other than at a
/// joint (see [`Creature::interpenetrating_pairs`]), or one for them all when there are more
/// than [`NAMED_PAIRS`].
pub(super) fn report(creature: &mut Creature, t: Option<f64>, severity: Severity) {
    let pairs = creature.interpenetrating_pairs();
    if pairs.len() <= NAMED_PAIRS {
        for (a, b) in pairs {
            creature.problems.push(Problem {
                severity,
                message: format!("parts {a} and {b} interpenetrate"),
                module: None,
                t,
            });
        }
        return;
    }
    let named: Vec<String> = pairs[..NAMED_PAIRS]
        .iter()
        .map(|(a, b)| format!("{a} and {b}"))
        .collect();
    creature.problems.push(Problem {
        severity,
        message: format!(
            "{} pairs of parts interpenetrate (parts {}, ...)",
            pairs.len(),
            named.join(", ")
        ),
        module: None,
        t,
    });
}
