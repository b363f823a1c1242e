//! Stand tall: after coming to rest, the controller runs for `seconds`, and the fitness is
//! the mean height of the creature's highest point over those seconds. A small task with no
//! terrain and one formula, the worked example of adding a task in `CONTRIBUTING.md`.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::protocol::{Bounds, Rest, Setup, evaluate, settle_steps, steps_in};
use super::recording::Phase;
use super::registry::expression_fitness;
use super::{Evaluation, FitnessExpression, Task};
use crate::cancel::Interrupted;
use crate::sim::SettingError;
use crate::sim::setting::check_real;

/// Settings of the stand task (`[task.stand]`).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StandOptions {
    /// Seconds with the controller on, after the creature has come to rest.
    pub seconds: f64,
    /// Creatures taller than this (m) are not simulated.
    pub max_height: f64,
    /// When the creature is at rest, before standing.
    pub rest: Rest,
    /// The fitness as an expression of the task's terms (`fitness = "height ^ 2"`); none:
    /// the mean height.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fitness: Option<FitnessExpression>,
}

impl Default for StandOptions {
    fn default() -> Self {
        StandOptions {
            seconds: 10.0,
            max_height: 15.0,
            rest: Rest::default(),
            fitness: None,
        }
    }
}

impl Bounds for StandOptions {
    fn limits(&self) -> (f64, f64) {
        (self.max_height, self.seconds)
    }
    fn max_steps(&self, dt: f64) -> usize {
        settle_steps(&self.rest, dt).saturating_add(steps_in(self.seconds, dt))
    }
    fn seconds(&mut self) -> &mut f64 {
        &mut self.seconds
    }
    /// Checks the settings: `seconds` in (0, [`super::MAX_SECONDS`]], the height limit finite
    /// and positive, and the rest criterion (in the `rest` table).
    fn check(&self) -> Result<(), SettingError> {
        super::check_duration("seconds", self.seconds)?;
        check_real("max_height", self.max_height, 0.0, true)?;
        self.rest.check().map_err(|e| e.within("rest"))
    }
}

/// Stand tall, in the registry.
pub struct StandTask;

impl Task for StandTask {
    const NAME: &'static str = "stand";
    const SUMMARY: &'static str = "Stand tall: mean height of the highest point while acting";
    const TERMS: &'static [&'static str] = &["height"];
    type Options = StandOptions;

    expression_fitness!();

    fn measure(_options: &StandOptions) -> &'static str {
        "mean height (m)"
    }
    fn evaluate(setup: Setup<'_, '_, StandOptions>) -> Result<Evaluation, Interrupted> {
        let Setup { sim, options, .. } = setup;
        evaluate(Self::NAME, setup, |run| {
            run.settle(&options.rest, 0.0, sim.control_step)?;
            run.check_height(options.max_height)?;
            run.phase = Phase::Measuring;
            let steps = steps_in(options.seconds, sim.control_step);
            let mut sum = 0.0;
            for _ in 0..steps {
                run.step(true)?;
                sum += run.world.highest_point().max(0.0);
            }
            let height = sum / steps as f64;
            Ok((height, BTreeMap::from([("height".to_string(), height)])))
        })
    }
}
