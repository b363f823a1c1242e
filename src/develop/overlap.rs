//! Reporting interpenetrating parts as problems of the creature: errors where physics needs
//! a valid creature, warnings in a picture.

use super::BuildOptions;
use crate::creature::{Creature, Problem};

/// The most pairs named one by one: beyond them, one problem counts the pairs and names the
/// first few (a plant of thousands of parts has thousands of such pairs).
const NAMED_PAIRS: usize = 5;

/// Adds a problem for every pair of parts that interpenetrate other than at a joint (see
/// [`Creature::interpenetrating_pairs`]), or one for them all when there are more than
/// [`NAMED_PAIRS`]: errors, or warnings when `options` build for a picture.
pub(super) fn report(creature: &mut Creature, t: Option<f64>, options: &BuildOptions) {
    let pairs = creature.interpenetrating_pairs();
    if pairs.len() <= NAMED_PAIRS {
        for (a, b) in pairs {
            let (severity, message) =
                options.physics_problem(format!("parts {a} and {b} interpenetrate"));
            creature.problems.push(Problem {
                severity,
                message,
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
    let (severity, message) = options.physics_problem(format!(
        "{} pairs of parts interpenetrate (parts {}, ...)",
        pairs.len(),
        named.join(", ")
    ));
    creature.problems.push(Problem {
        severity,
        message,
        module: None,
        t,
    });
}
