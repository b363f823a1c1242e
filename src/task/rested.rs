//! A task that acts after coming to rest: its settings ([`RestedOptions`]: how long it acts,
//! the height limit, the wait for rest before it and its fitness expression) and the protocol's
//! first steps (the wait for rest, the height test again). The jump and the stand task are
//! such tasks, each reading its own table.

use std::collections::BTreeMap;
use std::marker::PhantomData;

use serde::{Deserialize, Serialize};

use super::protocol::{Bounds, Rest, Run, Setup, bounds_of, evaluate, settle_steps, steps_in};
use super::recording::Phase;
use super::{Evaluation, FitnessExpression};
use crate::cancel::Interrupted;
use crate::sim::SettingError;
use crate::sim::setting::check_real;

/// Settings of a task `T` that acts after coming to rest (`[task.jump]`, `[task.stand]`):
/// [`JumpOptions`](super::JumpOptions), [`StandOptions`](super::StandOptions). Each task has
/// its own type, so that a task's table is never read as another's.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RestedOptions<T> {
    /// Seconds with the controller on, after the creature has come to rest.
    pub seconds: f64,
    /// Creatures taller than this (m) are not simulated.
    pub max_height: f64,
    /// When the creature is at rest, before acting.
    pub rest: Rest,
    /// The fitness as an expression of the task's terms; none: the task's own formula.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fitness: Option<FitnessExpression>,
    /// The task that reads them (no setting).
    #[serde(skip)]
    pub task: PhantomData<T>,
}

impl<T> Default for RestedOptions<T> {
    fn default() -> Self {
        RestedOptions {
            seconds: 10.0,
            max_height: 15.0,
            rest: Rest::default(),
            fitness: None,
            task: PhantomData,
        }
    }
}

impl<T> RestedOptions<T> {
    /// The most control steps of `dt` the task can take: the wait for rest at its time
    /// limit, then the action.
    pub fn max_steps(&self, dt: f64) -> usize {
        settle_steps(&self.rest, dt).saturating_add(steps_in(self.seconds, dt))
    }
}

impl<T> Bounds for RestedOptions<T> {
    bounds_of!(max_height, seconds);
    /// Checks the settings: `seconds` in (0, [`super::MAX_SECONDS`]], the height limit finite
    /// and positive, and the rest criterion ([`Rest::check`], in the `rest` table).
    fn check(&self) -> Result<(), SettingError> {
        super::check_duration("seconds", self.seconds)?;
        check_real("max_height", self.max_height, 0.0, true)?;
        self.rest.check().map_err(|e| e.within("rest"))
    }
}

/// Evaluates the creature of `setup` for the task `task`: it comes to rest and passes the
/// height test again, then `act` runs the measurement, given the number of control steps its
/// `seconds` last, and returns the fitness and its terms.
pub(super) fn evaluate_after_rest<T>(
    task: &'static str,
    setup: Setup<'_, '_, RestedOptions<T>>,
    act: impl FnOnce(&mut Run<'_>, usize) -> Result<(f64, BTreeMap<String, f64>), Evaluation>,
) -> Result<Evaluation, Interrupted> {
    let Setup { sim, options, .. } = setup;
    evaluate(task, setup, |run| {
        run.settle(&options.rest, 0.0, sim.control_step)?;
        run.check_height(options.max_height)?;
        run.phase = Phase::Measuring;
        act(run, steps_in(options.seconds, sim.control_step))
    })
}
