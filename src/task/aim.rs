//! The aiming catapult (Chaumont et al., equation 3): the catapult's protocol with a target,
//! scored by the distance thrown less the miss, D_p − D_t.

use super::catapult::{CatapultOptions, catapult_watched};
use super::{Evaluation, Task, Watch};
use crate::cancel::Interrupted;
use crate::creature::Creature;
use crate::sim::{SettingError, SimOptions};

/// Chaumont et al.'s aiming catapult, in the registry: it reads the catapult's settings,
/// target included (`[task.catapult] target`, which it needs).
pub struct AimTask;

impl Task for AimTask {
    const NAME: &'static str = "aim";
    const SUMMARY: &'static str = "Chaumont et al.'s aiming catapult: D_p − D_t (eq. 3)";
    const FITNESS_VARIANTS: &'static [&'static str] = &[];
    const THROWS: bool = true;
    const KEYWORDS: &'static [&'static str] = &["seconds", "target"];
    const TABLE: &'static str = "catapult";
    type Options = CatapultOptions;

    fn measure(_options: &CatapultOptions) -> &'static str {
        "distance − miss (m)"
    }
    fn floor(_options: &CatapultOptions) -> Option<f64> {
        None
    }
    fn max_steps(sim: &SimOptions, options: &CatapultOptions) -> usize {
        options.max_steps(sim.control_step)
    }
    fn seconds(options: &mut CatapultOptions) -> &mut f64 {
        &mut options.max_seconds
    }
    fn check_options(options: &CatapultOptions) -> Result<(), SettingError> {
        options.check()
    }
    fn check(options: &CatapultOptions) -> Result<(), SettingError> {
        if options.target.is_none() {
            return Err(SettingError {
                table: String::new(),
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
        sim: &SimOptions,
        options: &CatapultOptions,
        watch: Watch<'_>,
    ) -> Result<Evaluation, Interrupted> {
        catapult_watched(creature, sim, options, watch)
    }
}
