//! Swim (Sims 1994): in water, with no ground and no gravity, the controller runs for
//! `seconds` from the start, and the fitness is the distance (in 3D: water has no up) the
//! creature's centre of mass moves. There is no wait for rest: in still water with the
//! controller off nothing moves, so the creature is at rest from its first step.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::protocol::{Bounds, Setup, evaluate, steps_in};
use super::recording::Phase;
use super::registry::expression_fitness;
use super::walker::centre_of_mass;
use super::{Evaluation, FitnessExpression, Task};
use crate::cancel::Interrupted;
use crate::sim::{DEFAULT_VISCOSITY, Medium, SettingError, WorldSpec};

/// Settings of the swim task (`[task.swim]`).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SwimOptions {
    /// Seconds of swimming with the controller on, measured from the start.
    pub seconds: f64,
    /// The fitness as an expression of the task's terms (`fitness = "distance / mass"`); none:
    /// the distance swum.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fitness: Option<FitnessExpression>,
}

impl Default for SwimOptions {
    fn default() -> Self {
        SwimOptions {
            seconds: 20.0,
            fitness: None,
        }
    }
}

impl Bounds for SwimOptions {
    fn limits(&self) -> (f64, f64) {
        // Water has no up: no height test.
        (f64::INFINITY, self.seconds)
    }
    fn max_steps(&self, dt: f64) -> usize {
        steps_in(self.seconds, dt)
    }
    fn seconds(&mut self) -> &mut f64 {
        &mut self.seconds
    }
    /// Checks the settings: `seconds` in (0, [`super::MAX_SECONDS`]].
    fn check(&self) -> Result<(), SettingError> {
        super::check_duration("seconds", self.seconds)
    }
}

/// The viscosity the swim task swims in, in `world`: its water's, or [`DEFAULT_VISCOSITY`]
/// when the world's medium is air (the default).
pub fn swim_viscosity(world: &WorldSpec) -> f64 {
    match world.medium {
        Medium::Water { viscosity } => viscosity,
        Medium::Air => DEFAULT_VISCOSITY,
    }
}

/// Swim, in the registry.
pub struct SwimTask;

impl Task for SwimTask {
    const NAME: &'static str = "swim";
    const SUMMARY: &'static str = "Swim (Sims): distance of the centre of mass in water";
    const TERMS: &'static [&'static str] = &["distance", "viscosity", "mass", "N"];
    type Options = SwimOptions;

    expression_fitness!();

    fn measure(_options: &SwimOptions) -> &'static str {
        "distance (m)"
    }
    fn evaluate(setup: Setup<'_, '_, SwimOptions>) -> Result<Evaluation, Interrupted> {
        let Setup {
            creature,
            sim,
            world,
            options,
            ..
        } = setup;
        let viscosity = swim_viscosity(world);
        let water = WorldSpec {
            medium: Medium::Water { viscosity },
            ..world.clone()
        };
        let setup = Setup {
            world: &water,
            ..setup
        };
        evaluate(Self::NAME, setup, |run| {
            run.phase = Phase::Measuring;
            let from = centre_of_mass(&run.world, creature);
            run.run_for(options.seconds, true, sim.control_step)?;
            let distance = (centre_of_mass(&run.world, creature) - from).norm();
            Ok((
                distance,
                BTreeMap::from([
                    ("distance".to_string(), distance),
                    ("viscosity".to_string(), viscosity),
                    ("mass".to_string(), creature.mass()),
                    ("N".to_string(), creature.parts.len() as f64),
                ]),
            ))
        })
    }
}
