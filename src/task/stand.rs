//! Stand tall: after coming to rest, the controller runs for `seconds`, and the fitness is
//! the mean height of the creature's highest point over those seconds. A small task with no
//! terrain and one formula, the worked example of adding a task in `CONTRIBUTING.md`.

use std::collections::BTreeMap;

use super::protocol::Setup;
use super::registry::expression_fitness;
use super::rested::{RestedOptions, evaluate_after_rest};
use super::{Evaluation, Task};
use crate::cancel::Interrupted;

/// Settings of the stand task (`[task.stand]`): `seconds` of standing after coming to rest.
/// Its fitness may be an expression of its terms (`fitness = "height ^ 2"`); none: the mean
/// height.
pub type StandOptions = RestedOptions<StandTask>;

/// Stand tall, in the registry.
#[derive(Clone, Copy, Debug)]
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
        evaluate_after_rest(Self::NAME, setup, |run, steps| {
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
