//! A task specification: which task, its settings and the simulator's, as plain serialisable
//! data, so that an evaluation is a pure function of (creature, specification).

use serde::{Deserialize, Serialize};

use super::{CatapultOptions, Evaluation, JumpOptions, WalkerOptions};
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
        let fitness = match self.task {
            TaskKind::Walker => self.walker.fitness.label(),
            TaskKind::Jump => "height (m)",
            TaskKind::Catapult => "distance (m)",
            TaskKind::Aim => "distance − miss (m)",
        };
        format!("{}, {fitness}", self.task.name())
    }

    /// Evaluates `creature` on the task; `record` keeps every frame.
    pub fn evaluate(&self, creature: &Creature, record: bool) -> Evaluation {
        match self.task {
            TaskKind::Walker => super::walker(creature, &self.sim, &self.walker, record),
            TaskKind::Jump => super::jump(creature, &self.sim, &self.jump, record),
            TaskKind::Catapult => {
                let options = CatapultOptions {
                    target: None,
                    ..self.catapult.clone()
                };
                super::catapult(creature, &self.sim, &options, record)
            }
            TaskKind::Aim => super::catapult(creature, &self.sim, &self.catapult, record),
        }
    }
}
