//! A task specification: which task, its settings and the simulator's, as plain serialisable
//! data, so that an evaluation is a pure function of (creature, specification).

use serde::{Deserialize, Serialize};

use super::{
    CatapultOptions, Evaluation, JumpOptions, StandOptions, SwimOptions, Task, WalkerOptions, Watch,
};
use crate::cancel::Interrupted;
use crate::creature::Creature;
use crate::sim::{SimOptions, WorldSpec};

crate::for_each_task!(__task_kind!());

impl TaskKind {
    /// The task in a few words, for `--help` ([`Task::SUMMARY`]).
    pub fn summary(self) -> &'static str {
        crate::with_task!(self, T => T::SUMMARY)
    }

    /// The task's name as the CLI and the run store spell it ([`Task::NAME`]).
    pub fn name(self) -> &'static str {
        crate::with_task!(self, T => T::NAME)
    }

    /// Whether the task throws a projectile ([`Task::THROWS`]).
    pub fn throws(self) -> bool {
        crate::with_task!(self, T => T::THROWS)
    }
}

impl std::str::FromStr for TaskKind {
    type Err = String;

    /// The task named `name` ([`TaskKind::name`]).
    fn from_str(name: &str) -> Result<TaskKind, String> {
        TaskKind::ALL
            .iter()
            .copied()
            .find(|t| t.name() == name)
            .ok_or_else(|| format!("unknown task '{name}'"))
    }
}

/// Everything an evaluation depends on besides the creature.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskSpec {
    /// The task.
    #[serde(default)]
    pub task: TaskKind,
    /// The simulator's settings.
    #[serde(default)]
    pub sim: SimOptions,
    /// The world besides the creature (`[task.world]`): flat ground in air unless it says
    /// otherwise; a flat world is not written.
    #[serde(default, skip_serializing_if = "WorldSpec::is_flat")]
    pub world: WorldSpec,
    /// The walker's settings (used by `walker`).
    #[serde(default)]
    pub walker: WalkerOptions,
    /// The jump's settings (used by `jump`).
    #[serde(default)]
    pub jump: JumpOptions,
    /// The catapult's settings (used by `catapult` and `aim`; `aim` needs its target).
    #[serde(default)]
    pub catapult: CatapultOptions,
    /// The stand task's settings (used by `stand`).
    #[serde(default)]
    pub stand: StandOptions,
    /// The swim task's settings (used by `swim`).
    #[serde(default)]
    pub swim: SwimOptions,
}

impl TaskSpec {
    /// The default settings of `task`.
    pub fn new(task: TaskKind) -> TaskSpec {
        TaskSpec {
            task,
            ..TaskSpec::default()
        }
    }

    /// The task and what its fitness measures, as every report names them:
    /// `"walker, distance (m)"`, `"walker, normalised (Chaumont eq. 1)"`,
    /// `"jump, height (m)"`, `"catapult, distance (m)"`, `"aim, distance − miss (m)"`.
    pub fn fitness_label(&self) -> String {
        format!("{}, {}", self.task.name(), self.fitness_measure())
    }

    /// What the fitness measures and in which unit, as plots label their axis:
    /// `"distance (m)"`, `"normalised (Chaumont eq. 1)"`, `"distance − miss (m)"`.
    pub fn fitness_measure(&self) -> &'static str {
        crate::with_task!(self.task, T => T::measure(self))
    }

    /// The lowest fitness an evaluation that succeeds can score, when the formula has one:
    /// 0 for distances and heights (the walker's formulas but Hornby & Pollack's, the jump,
    /// the catapult); none for the aim task (D_p − D_t) and Hornby & Pollack's walker, which
    /// can be negative.
    pub fn fitness_floor(&self) -> Option<f64> {
        crate::with_task!(self.task, T => T::floor(self))
    }

    /// Evaluates `creature` on the task; `record` keeps a recording (every step's sample, or
    /// evenly spaced ones for a long run: see [`super::recording_interval`]).
    pub fn evaluate(&self, creature: &Creature, record: bool) -> Evaluation {
        self.evaluate_with_progress(creature, record, &mut |_| {})
    }

    /// [`TaskSpec::evaluate`], telling `progress` the fraction done, as
    /// [`Watch::progress`] says.
    pub fn evaluate_with_progress(
        &self,
        creature: &Creature,
        record: bool,
        progress: &mut dyn FnMut(f64),
    ) -> Evaluation {
        let watch = Watch::uncancelled(record, progress);
        super::protocol::uninterrupted(self.evaluate_watched(creature, watch))
    }

    /// [`TaskSpec::evaluate`], watched as `watch` says: recorded, told its progress, and
    /// stopped before its next control step with [`Interrupted`] once its token is set (an
    /// interrupted evaluation has no result: nothing of it is kept).
    pub fn evaluate_watched(
        &self,
        creature: &Creature,
        watch: Watch<'_>,
    ) -> Result<Evaluation, Interrupted> {
        crate::with_task!(self.task, T => T::evaluate(creature, self, watch))
    }

    /// The most control steps the task can take (every phase at its longest), which sets how
    /// densely a recording keeps samples ([`super::recording_interval`]).
    pub fn max_steps(&self) -> usize {
        crate::with_task!(self.task, T => T::max_steps(self))
    }
}

#[cfg(test)]
mod tests {
    use super::TaskKind;

    #[test]
    fn task_names_are_the_ones_configs_spell_and_read_back() {
        for &task in TaskKind::ALL {
            assert_eq!(serde_json::to_value(task).unwrap(), task.name());
            assert_eq!(task.name().parse::<TaskKind>(), Ok(task));
        }
        assert!("walk".parse::<TaskKind>().is_err());
    }
}
