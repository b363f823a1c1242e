//! The jump (Walking with Dinosaurs 3.3.3): its settings and its protocol.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::protocol::{Rest, Setup, evaluate, on_flat_ground, settle_steps, steps_in};
use super::recording::Phase;
use super::registry::expression_fitness;
use super::{Evaluation, FitnessExpression, Task};
use crate::cancel::Interrupted;
use crate::creature::Creature;
use crate::sim::SimOptions;

/// Settings of the jump task.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct JumpOptions {
    /// Seconds with the controller on, after the creature has come to rest.
    pub seconds: f64,
    /// Creatures taller than this (m) are not simulated.
    pub max_height: f64,
    /// When the creature is at rest, before jumping.
    pub rest: Rest,
    /// The fitness as an expression of the task's terms (`fitness = "height - resting_lowest_point"`); none:
    /// the best height.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fitness: Option<FitnessExpression>,
}

impl Default for JumpOptions {
    fn default() -> Self {
        JumpOptions {
            seconds: 10.0,
            max_height: 15.0,
            rest: Rest::default(),
            fitness: None,
        }
    }
}

impl JumpOptions {
    /// The most control steps of `dt` the jump can take: the wait for rest at its time
    /// limit, then the jump.
    pub fn max_steps(&self, dt: f64) -> usize {
        settle_steps(&self.rest, dt).saturating_add(steps_in(self.seconds, dt))
    }
}

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
        let Setup { sim, options, .. } = setup;
        evaluate(Self::NAME, setup, |run| {
            run.settle(&options.rest, 0.0, sim.control_step)?;
            run.check_height(options.max_height)?;
            // Heights from the ground the creature was dropped on (0 on level ground).
            let ground = run.world.start_ground();
            let resting = (run.world.lowest_point() - ground).max(0.0);
            let mut best: f64 = 0.0;
            run.phase = Phase::Measuring;
            for _ in 0..steps_in(options.seconds, sim.control_step) {
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
