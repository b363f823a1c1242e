//! The range check of every task setting, and the one limit on how long a task may run
//! ([`MAX_SECONDS`]): each options type checks its own values ([`Bounds::check`]: here the
//! walker's and the catapult's, with what else they bound) and
//! [`TaskSpec::check`] checks the task's with the simulator's, naming the key as a config
//! file spells it (`[task.walker] seconds`).

use super::protocol::bounds_of;
use super::{
    Bounds, CatapultOptions, MAX_TARGET_DISTANCE, Rest, TaskKind, TaskOptions, TaskSpec,
    WalkerOptions,
};
use crate::sim::setting::check_real;
use crate::sim::{Medium, SettingError};

/// The longest any duration of a task may be (s): an hour. A task's measurement (`seconds`,
/// the catapult's `max_seconds`), a wait for rest and every other phase must fit in it, so
/// that an evaluation ends in a bounded number of steps.
pub const MAX_SECONDS: f64 = 3600.0;

/// `seconds` is a task's duration: in (0, [`MAX_SECONDS`]]. The error names `key`.
pub fn check_duration(key: &'static str, seconds: f64) -> Result<(), SettingError> {
    if seconds > 0.0 && seconds <= MAX_SECONDS {
        Ok(())
    } else {
        Err(SettingError::out_of_range(
            key,
            &format!("in (0, {MAX_SECONDS}]"),
            seconds,
        ))
    }
}

/// `seconds` is a phase that may be empty: in [0, [`MAX_SECONDS`]]. The error names `key`.
fn check_phase(key: &'static str, seconds: f64) -> Result<(), SettingError> {
    if (0.0..=MAX_SECONDS).contains(&seconds) {
        Ok(())
    } else {
        Err(SettingError::out_of_range(
            key,
            &format!("in [0, {MAX_SECONDS}]"),
            seconds,
        ))
    }
}

impl Rest {
    /// Checks the rest criterion: thresholds finite and positive, the calm window in [0,
    /// [`MAX_SECONDS`]], the time limit in (0, [`MAX_SECONDS`]].
    pub fn check(&self) -> Result<(), SettingError> {
        check_real("distance", self.distance, 0.0, true)?;
        check_phase("duration", self.duration)?;
        check_real("drift", self.drift, 0.0, true)?;
        check_duration("limit", self.limit)
    }
}

impl Bounds for WalkerOptions {
    bounds_of!(max_height, seconds);
    /// Checks the walker's settings: `seconds` in (0, [`MAX_SECONDS`]], the activation and the
    /// second settling in [0, [`MAX_SECONDS`]], κ and the height limit finite and positive,
    /// and the rest criterion ([`Rest::check`], in the `rest` table).
    fn check(&self) -> Result<(), SettingError> {
        check_duration("seconds", self.seconds)?;
        check_real("kappa", self.kappa, 0.0, true)?;
        check_phase("activation", self.activation)?;
        check_phase("second_settle", self.second_settle)?;
        check_real("max_height", self.max_height, 0.0, true)?;
        self.rest.check().map_err(|e| e.within("rest"))
    }
}

impl Bounds for CatapultOptions {
    // `max_seconds`: the catapult's measurement lasts until the projectile is at rest.
    bounds_of!(max_height, max_seconds);
    /// Checks the catapult's settings: the projectile's size (every edge) and density finite
    /// and positive, `max_seconds` in (0, [`MAX_SECONDS`]], the release delay and the rest
    /// duration in [0, [`MAX_SECONDS`]], the rest speed and the height limit finite and
    /// positive; when the projectile evolves, its starting edges within
    /// [`PROJECTILE_EDGE`](crate::creature::PROJECTILE_EDGE). The target, which only the aim
    /// task reads, is [`CatapultOptions::check_target`]'s.
    fn check(&self) -> Result<(), SettingError> {
        for edge in self.projectile_size.iter() {
            check_real("projectile_size", *edge, 0.0, true)?;
        }
        check_real("projectile_density", self.projectile_density, 0.0, true)?;
        check_duration("max_seconds", self.max_seconds)?;
        check_phase("release_delay", self.release_delay)?;
        check_real("rest_speed", self.rest_speed, 0.0, true)?;
        check_phase("rest_duration", self.rest_duration)?;
        check_real("max_height", self.max_height, 0.0, true)?;
        let (lo, hi) = crate::creature::PROJECTILE_EDGE;
        if self.evolve_projectile && !self.projectile_size.iter().all(|e| (lo..=hi).contains(e)) {
            let s = self.projectile_size;
            return Err(SettingError::out_of_range(
                "projectile_size",
                &format!("within [{lo}, {hi}] m on every edge when the projectile evolves"),
                format!("[{}, {}, {}]", s.x, s.y, s.z),
            ));
        }
        Ok(())
    }
}

impl CatapultOptions {
    /// Checks the aim task's target, when there is one: finite and within
    /// [`MAX_TARGET_DISTANCE`] of the projectile.
    pub fn check_target(&self) -> Result<(), SettingError> {
        if let Some(target) = self.target
            && !(target.iter().all(|v| v.is_finite()) && target.norm() <= MAX_TARGET_DISTANCE)
        {
            return Err(SettingError::out_of_range(
                "target",
                &format!("within {MAX_TARGET_DISTANCE} m of the projectile"),
                format!("[{}, {}, {}]", target.x, target.y, target.z),
            ));
        }
        Ok(())
    }
}

impl TaskSpec {
    /// Checks every setting of the specification — the simulator's
    /// ([`crate::sim::SimOptions::check`]) and the task's ([`super::Task::check_options`]) — and
    /// what the task run needs ([`super::Task::check`]: the aim task's target). The error names the
    /// key in its table as a config file spells it (`[task.sim] substeps`).
    pub fn check(&self) -> Result<(), SettingError> {
        self.check_tables().map_err(|e| e.within("task"))?;
        self.check_habitats()
    }

    /// [`TaskSpec::check`], the key's table named from inside `[task]` (`sim`).
    fn check_tables(&self) -> Result<(), SettingError> {
        self.develop.check()?;
        self.sim.check().map_err(|e| e.within("sim"))?;
        if let Medium::Water { .. } = self.world.medium
            && self.kind() != TaskKind::Swim
        {
            return Err(SettingError::out_of_range(
                "medium",
                &format!(
                    "air for the {} task (water is the swim task's)",
                    self.task.name()
                ),
                "water",
            )
            .within("world"));
        }
        self.world.check().map_err(|e| e.within("world"))?;
        crate::with_options!(&self.task, T, o => {
            <T as super::Task>::check_options(o)
                .and_then(|()| <T as super::Task>::check(o))
        })
        .and_then(|()| self.task.check_fitness())
        .map_err(|e| e.within(self.task.table()))
    }
}

impl TaskOptions {
    /// Checks the task's fitness expression, when it has one, as the fitness of this task
    /// ([`FitnessExpression::check`](super::FitnessExpression::check)): its syntax, and that
    /// it reads only the task's terms ([`Task::TERMS`](super::Task::TERMS)), which needs no
    /// simulation. The error names the key, `fitness`.
    pub fn check_fitness(&self) -> Result<(), SettingError> {
        let problem = crate::with_options!(self, T, o => {
            use super::Task;
            match T::expression(o) {
                Some(expression) => expression
                    .check(T::NAME, T::TERMS, T::FITNESS_VARIANTS)
                    .map_err(|problem| {
                        // Another task's formula (`distance` for the jump) is no expression.
                        let owner = super::TASKS
                            .iter()
                            .find(|t| t.fitness_variants.contains(&expression.source()));
                        match owner {
                            Some(owner) => format!(
                                "\"{}\" is a formula of the {} task, not of the {} task, whose \
                                 fitness may be an expression of its terms: {}",
                                expression.source(),
                                owner.name,
                                T::NAME,
                                T::TERMS
                                    .iter()
                                    .chain(super::PROTOCOL_TERMS)
                                    .copied()
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ),
                            None => problem,
                        }
                    }),
                None => Ok(()),
            }
        });
        problem.map_err(|problem| SettingError {
            table: String::new(),
            key: "fitness",
            problem,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::SimOptions;
    use crate::task::TaskKind;

    #[test]
    fn every_task_passes_its_defaults() {
        for &task in TaskKind::ALL.iter().filter(|&&t| t != TaskKind::Aim) {
            assert_eq!(TaskSpec::new(task).check(), Ok(()));
        }
    }

    #[test]
    fn the_check_names_the_key_in_its_table() {
        let mut spec = TaskSpec::new(TaskKind::Walker);
        spec.sim = SimOptions {
            substeps: 0,
            ..SimOptions::default()
        };
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[task.sim] substeps must be 1 to 64, not 0"
        );
        let mut spec = TaskSpec::new(TaskKind::Walker);
        spec.task.get_mut::<WalkerOptions>().unwrap().rest.limit = 1e12;
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[task.walker.rest] limit must be in (0, 3600], not 1000000000000"
        );
        let mut spec = TaskSpec::new(TaskKind::Catapult);
        spec.task.get_mut::<CatapultOptions>().unwrap().max_seconds = 3600.5;
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[task.catapult] max_seconds must be in (0, 3600], not 3600.5"
        );
        let spec = TaskSpec::new(TaskKind::Aim);
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[task.catapult] target is needed by the aim task: target = [x, y, z] (metres from the projectile)"
        );
        let mut spec = TaskSpec::new(TaskKind::Aim);
        spec.task.get_mut::<CatapultOptions>().unwrap().target =
            Some(nalgebra::Vector3::new(2.0 * MAX_TARGET_DISTANCE, 0.0, 0.0));
        let e = spec.check().unwrap_err();
        assert_eq!((e.table.as_str(), e.key), ("task.catapult", "target"));
    }

    #[test]
    fn a_duration_is_checked_against_the_one_limit() {
        assert_eq!(check_duration("seconds", MAX_SECONDS), Ok(()));
        for bad in [0.0, -1.0, MAX_SECONDS + 1.0, f64::NAN, f64::INFINITY] {
            assert!(check_duration("seconds", bad).is_err(), "{bad}");
        }
    }
}
