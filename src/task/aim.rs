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
    /// The target, its one setting of its own (the catapult task checks the rest of the
    /// table they share).
    fn check_options(spec: &TaskSpec) -> Result<(), SettingError> {
        spec.catapult
            .check_target()
            .map_err(|e| e.within("catapult"))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::task::{CatapultTask, TaskKind};

    #[test]
    fn the_aim_task_checks_its_target_and_the_catapult_leaves_it_alone() {
        let mut spec = TaskSpec::new(TaskKind::Aim);
        assert_eq!(AimTask::check_options(&spec), Ok(()));
        spec.catapult.target = Some(nalgebra::Vector3::new(f64::NAN, 0.0, 0.0));
        assert_eq!(
            AimTask::check_options(&spec).unwrap_err().to_string(),
            "[catapult] target must be within 100000 m of the projectile, not [NaN, 0, 0]"
        );
        spec.catapult.target = Some(nalgebra::Vector3::new(0.0, 3e5, -4e5));
        assert_eq!(
            AimTask::check_options(&spec).unwrap_err().to_string(),
            "[catapult] target must be within 100000 m of the projectile, not [0, 300000, -400000]"
        );
        assert_eq!(CatapultTask::check_options(&spec), Ok(()));
        spec.catapult.target = Some(nalgebra::Vector3::new(6e4, 0.0, 8e4));
        assert_eq!(AimTask::check_options(&spec), Ok(()));
    }
}
