//! A task specification: which task, its settings and the simulator's, as plain serialisable
//! data, so that an evaluation is a pure function of (creature, specification).

use serde::{Deserialize, Serialize};

use super::{CatapultOptions, Evaluation, JumpOptions, WalkerOptions, Watch};
use crate::cancel::Interrupted;
use crate::creature::Creature;
use crate::sim::SimOptions;

/// The four tasks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TaskKind {
    /// Chaumont et al.'s walker (equation 1).
    #[default]
    Walker,
    /// Walking with Dinosaurs' jump.
    Jump,
    /// Chaumont et al.'s catapult (equation 2).
    Catapult,
    /// Chaumont et al.'s aiming catapult (equation 3): needs `catapult.target`.
    Aim,
}

impl TaskKind {
    /// Every task, in the order `--help` lists them.
    pub const ALL: [TaskKind; 4] = [
        TaskKind::Walker,
        TaskKind::Jump,
        TaskKind::Catapult,
        TaskKind::Aim,
    ];

    /// The task in a few words, for `--help`.
    pub fn summary(self) -> &'static str {
        match self {
            TaskKind::Walker => {
                "Chaumont et al.'s walker: distance of the root part, normalised by size (eq. 1)"
            }
            TaskKind::Jump => "Walking with Dinosaurs' jump: best height of the lowest point",
            TaskKind::Catapult => {
                "Chaumont et al.'s catapult: distance the projectile travels (eq. 2)"
            }
            TaskKind::Aim => "Chaumont et al.'s aiming catapult: D_p − D_t (eq. 3)",
        }
    }

    /// The task's name as the CLI and the run store spell it.
    pub fn name(self) -> &'static str {
        match self {
            TaskKind::Walker => "walker",
            TaskKind::Jump => "jump",
            TaskKind::Catapult => "catapult",
            TaskKind::Aim => "aim",
        }
    }
}

impl std::str::FromStr for TaskKind {
    type Err = String;

    /// The task named `name` ([`TaskKind::name`]).
    fn from_str(name: &str) -> Result<TaskKind, String> {
        TaskKind::ALL
            .into_iter()
            .find(|t| t.name() == name)
            .ok_or_else(|| format!("unknown task '{name}'"))
    }
}

/// Everything an evaluation depends on besides the creature.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskSpec {
    /// The task.
    #[serde(default)]
    pub task: TaskKind,
    /// The simulator's settings.
    #[serde(default)]
    pub sim: SimOptions,
    /// The walker's settings (used by `walker`).
    #[serde(default)]
    pub walker: WalkerOptions,
    /// The jump's settings (used by `jump`).
    #[serde(default)]
    pub jump: JumpOptions,
    /// The catapult's settings (used by `catapult` and `aim`; `aim` needs its target).
    #[serde(default)]
    pub catapult: CatapultOptions,
}

impl TaskSpec {
    /// The default settings of `task`.
    pub fn new(task: TaskKind) -> TaskSpec {
        TaskSpec {
            task,
            sim: SimOptions::default(),
            walker: WalkerOptions::default(),
            jump: JumpOptions::default(),
            catapult: CatapultOptions::default(),
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
        match self.task {
            TaskKind::Walker => self.walker.fitness.label(),
            TaskKind::Jump => "height (m)",
            TaskKind::Catapult => "distance (m)",
            TaskKind::Aim => "distance − miss (m)",
        }
    }

    /// The lowest fitness an evaluation that succeeds can score, when the formula has one:
    /// 0 for distances and heights (the walker's formulas but Hornby & Pollack's, the jump,
    /// the catapult); none for the aim task (D_p − D_t) and Hornby & Pollack's walker, which
    /// can be negative.
    pub fn fitness_floor(&self) -> Option<f64> {
        match self.task {
            TaskKind::Walker => self.walker.fitness.floor(),
            TaskKind::Jump | TaskKind::Catapult => Some(0.0),
            TaskKind::Aim => None,
        }
    }

    /// Evaluates `creature` on the task; `record` keeps a recording (every step's sample, or
    /// evenly spaced ones for a long run: see [`super::recording_interval`]).
    pub fn evaluate(&self, creature: &Creature, record: bool) -> Evaluation {
        self.evaluate_with_progress(creature, record, &mut |_| {})
    }

    /// [`TaskSpec::evaluate`], telling `progress` the fraction done, as
    /// [`super::walker_with_progress`] does.
    pub fn evaluate_with_progress(
        &self,
        creature: &Creature,
        record: bool,
        progress: &mut dyn FnMut(f64),
    ) -> Evaluation {
        let watch = Watch {
            record,
            progress,
            cancel: None,
        };
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
        match self.task {
            TaskKind::Walker => {
                super::walker::walker_watched(creature, &self.sim, &self.walker, watch)
            }
            TaskKind::Jump => super::jump::jump_watched(creature, &self.sim, &self.jump, watch),
            TaskKind::Catapult => {
                let options = CatapultOptions {
                    target: None,
                    ..self.catapult.clone()
                };
                super::catapult::catapult_watched(creature, &self.sim, &options, watch)
            }
            TaskKind::Aim => {
                super::catapult::catapult_watched(creature, &self.sim, &self.catapult, watch)
            }
        }
    }

    /// The most control steps the task can take (every phase at its longest), which sets how
    /// densely a recording keeps samples ([`super::recording_interval`]).
    pub fn max_steps(&self) -> usize {
        let dt = self.sim.control_step;
        match self.task {
            TaskKind::Walker => self.walker.max_steps(dt),
            TaskKind::Jump => self.jump.max_steps(dt),
            TaskKind::Catapult | TaskKind::Aim => self.catapult.max_steps(dt),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::TaskKind;

    #[test]
    fn task_names_are_the_ones_configs_spell_and_read_back() {
        for task in TaskKind::ALL {
            assert_eq!(serde_json::to_value(task).unwrap(), task.name());
            assert_eq!(task.name().parse::<TaskKind>(), Ok(task));
        }
        assert!("walk".parse::<TaskKind>().is_err());
    }
}
