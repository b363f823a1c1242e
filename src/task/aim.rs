//! The aiming catapult (Chaumont et al., equation 3): the catapult's protocol with a target,
//! scored by the distance thrown less the miss, D_p − D_t.

use super::catapult::{CatapultOptions, catapult_watched};
use super::{Evaluation, Task, TaskSpec, Watch};
use crate::cancel::Interrupted;
use crate::creature::Creature;
use crate::sim::SettingError;

/// Chaumont et al.'s aiming catapult, in the registry: it reads the catapult's settings,
/// target included (`[task.catapult] target`, which it needs).
pub struct AimTask;

impl Task for AimTask {
    const NAME: &'static str = "aim";
    const SUMMARY: &'static str = "Chaumont et al.'s aiming catapult: D_p − D_t (eq. 3)";
    const FITNESS_VARIANTS: &'static [&'static str] = &[];
    const THROWS: bool = true;
    type Options = CatapultOptions;

    fn options(spec: &TaskSpec) -> CatapultOptions {
        spec.catapult.clone()
    }
    fn measure(_spec: &TaskSpec) -> &'static str {
        "distance − miss (m)"
    }
    fn floor(_spec: &TaskSpec) -> Option<f64> {
        None
    }
    fn max_steps(spec: &TaskSpec) -> usize {
        spec.catapult.max_steps(spec.sim.control_step)
    }
    fn seconds(spec: &mut TaskSpec) -> &mut f64 {
        &mut spec.catapult.max_seconds
    }
    fn check_options(_spec: &TaskSpec) -> Result<(), SettingError> {
        // The catapult's table, which the catapult task checks.
        Ok(())
    }
    fn check(spec: &TaskSpec) -> Result<(), SettingError> {
        if spec.catapult.target.is_none() {
            return Err(SettingError {
                table: "catapult".to_string(),
                key: "target",
                problem:
                    "is needed by the aim task: target = [x, y, z] (metres from the projectile)"
                        .to_string(),
            });
        }
        Ok(())
    }
    fn evaluate(
        creature: &Creature,
        spec: &TaskSpec,
        watch: Watch<'_>,
    ) -> Result<Evaluation, Interrupted> {
        catapult_watched(creature, (&spec.sim, &spec.world), &spec.catapult, watch)
    }
}
