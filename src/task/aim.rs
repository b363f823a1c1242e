//! The aiming catapult (Chaumont et al., equation 3): the catapult's protocol with a target,
//! scored by the distance thrown less the miss, D_p − D_t.

use super::catapult::{CatapultOptions, catapult_watched};
use super::registry::expression_fitness;
use super::{Bounds, Evaluation, Setup, Task};
use crate::cancel::Interrupted;
use crate::sim::SettingError;

/// Chaumont et al.'s aiming catapult, in the registry: it reads the catapult's settings,
/// target included (`[task.catapult] target`, which it needs).
pub struct AimTask;

impl Task for AimTask {
    const NAME: &'static str = "aim";
    const SUMMARY: &'static str = "Chaumont et al.'s aiming catapult: D_p − D_t (eq. 3)";
    const THROWS: bool = true;
    const TERMS: &'static [&'static str] = &[
        "D_p",
        "release_step",
        "release_time",
        "seconds",
        "projectile_x",
        "projectile_y",
        "projectile_z",
        "projectile_mass",
        "target_x",
        "target_y",
        "target_z",
        "D_t",
    ];
    const KEYWORDS: &'static [&'static str] = &["seconds", "fitness", "target"];
    const TABLE: &'static str = "catapult";
    type Options = CatapultOptions;

    expression_fitness!();

    fn measure(_options: &CatapultOptions) -> &'static str {
        "distance − miss (m)"
    }
    fn floor(_options: &CatapultOptions) -> Option<f64> {
        None
    }
    /// The catapult's table, its target included (the catapult task leaves the target
    /// alone).
    fn check_options(options: &CatapultOptions) -> Result<(), SettingError> {
        options.check().and_then(|()| options.check_target())
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
    /// The catapult's protocol, the target included.
    fn evaluate(setup: Setup<'_, '_, CatapultOptions>) -> Result<Evaluation, Interrupted> {
        catapult_watched(setup)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::task::CatapultTask;

    #[test]
    fn the_aim_task_checks_its_target_and_the_catapult_leaves_it_alone() {
        let mut options = CatapultOptions::default();
        assert_eq!(AimTask::check_options(&options), Ok(()));
        options.target = Some(nalgebra::Vector3::new(f64::NAN, 0.0, 0.0));
        assert_eq!(
            AimTask::check_options(&options).unwrap_err().to_string(),
            "target must be within 100000 m of the projectile, not [NaN, 0, 0]"
        );
        options.target = Some(nalgebra::Vector3::new(0.0, 3e5, -4e5));
        assert_eq!(
            AimTask::check_options(&options).unwrap_err().to_string(),
            "target must be within 100000 m of the projectile, not [0, 300000, -400000]"
        );
        assert_eq!(CatapultTask::check_options(&options), Ok(()));
        options.target = Some(nalgebra::Vector3::new(6e4, 0.0, 8e4));
        assert_eq!(AimTask::check_options(&options), Ok(()));
    }

    #[test]
    fn an_evolving_projectile_starts_within_its_range() {
        let mut options = CatapultOptions {
            evolve_projectile: true,
            projectile_size: nalgebra::Vector3::new(2.0, 0.2, 0.2),
            ..CatapultOptions::default()
        };
        let refusal = "projectile_size must be within [0.05, 1] m on every edge when the \
                       projectile evolves, not [2, 0.2, 0.2]";
        assert_eq!(
            CatapultTask::check_options(&options)
                .unwrap_err()
                .to_string(),
            refusal
        );
        assert_eq!(
            AimTask::check_options(&options).unwrap_err().to_string(),
            refusal
        );
        options.evolve_projectile = false;
        assert_eq!(CatapultTask::check_options(&options), Ok(()));
    }
}
