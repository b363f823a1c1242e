//! Reporting interpenetrating parts as problems of the creature: errors where physics needs
//! a valid creature, warnings in a picture.

use super::BuildOptions;
use crate::creature::{Creature, Problem, interpenetration_messages};

/// Adds a problem for the pairs of parts that interpenetrate other than at a joint (see
/// [`Creature::interpenetrating_pairs`]), a problem a pair or one for them all when there are
/// many ([`interpenetration_messages`]): errors, or warnings when `options` build for a
/// picture.
pub(super) fn report(creature: &mut Creature, t: Option<f64>, options: &BuildOptions) {
    let pairs = creature.interpenetrating_pairs();
    for message in interpenetration_messages(&pairs) {
        let (severity, message) = options.physics_problem(message);
        creature.problems.push(Problem {
            severity,
            message,
            module: None,
            t,
        });
    }
}
