//! The jump (Walking with Dinosaurs 3.3.3): its settings and its protocol.

use std::collections::BTreeMap;

use super::protocol::{Setup, on_flat_ground};
use super::registry::expression_fitness;
use super::rested::{RestedOptions, evaluate_after_rest};
use super::{Evaluation, Task};
use crate::cancel::Interrupted;
use crate::creature::Creature;
use crate::sim::SimOptions;

/// Settings of the jump task (`[task.jump]`): `seconds` of jumping after coming to rest.
/// Its fitness may be an expression of its terms (`fitness = "height - resting_lowest_point"`);
/// none: the best height.
pub type JumpOptions = RestedOptions<JumpTask>;

/// Jump (Walking with Dinosaurs 3.3.3): after coming to rest (and passing the height test
/// again), the controller runs for `seconds`; the fitness is the best height of the
/// creature's lowest point above the ground.
pub fn jump(
    creature: &Creature,
    sim: &SimOptions,
    options: &JumpOptions,
    record: bool,
) -> Evaluation {
    on_flat_ground(creature, sim, options, record, JumpTask::evaluate)
}

/// Walking with Dinosaurs' jump, in the registry ([`super::Task`]).
#[derive(Clone, Copy, Debug)]
pub struct JumpTask;

impl Task for JumpTask {
    const NAME: &'static str = "jump";
    const SUMMARY: &'static str = "Walking with Dinosaurs' jump: best height of the lowest point";
    const TERMS: &'static [&'static str] = &["height", "resting_lowest_point"];
    type Options = JumpOptions;

    expression_fitness!();

    fn measure(_options: &JumpOptions) -> &'static str {
        "height (m)"
    }
    fn evaluate(setup: Setup<'_, '_, JumpOptions>) -> Result<Evaluation, Interrupted> {
        evaluate_after_rest(Self::NAME, setup, |run, steps| {
            // Heights from the ground the creature was dropped on (0 on level ground).
            let ground = run.world.start_ground();
            let resting = (run.world.lowest_point() - ground).max(0.0);
            let mut best: f64 = 0.0;
            for _ in 0..steps {
                run.step(true)?;
                best = best.max(run.world.lowest_point() - ground);
            }
            let terms = BTreeMap::from([
                ("height".to_string(), best),
                ("resting_lowest_point".to_string(), resting),
            ]);
            Ok((best, terms))
        })
    }
}
