//! A task specification: which task, its settings and the simulator's, as plain serialisable
//! data, so that an evaluation is a pure function of (creature, specification).

use serde::ser::{Serialize, SerializeStruct, Serializer};
use serde::{Deserialize, Deserializer};

use super::{
    Evaluation, FitnessExpression, GrowError, Growing, Habitat, Setup, Task, TaskOptions,
    TaskTables, Trials, Unit, Watch,
};
use crate::cancel::Interrupted;
use crate::creature::Creature;
use crate::develop::Seedling;
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

    /// What can be known of the task without its type ([`super::TASKS`]' row).
    pub fn info(self) -> &'static super::TaskInfo {
        &super::TASKS[self as usize]
    }

    /// The table of `[task]` the task reads ([`Task::TABLE`]).
    pub fn table(self) -> &'static str {
        crate::with_task!(self, T => T::TABLE)
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

/// Everything an evaluation depends on besides the creature: the simulator's settings and
/// the settings of the one task run. In a file it is the `[task]` table: `task = "NAME"`,
/// `[task.sim]` and the task's table (`[task.walker]`); the files of earlier releases, which
/// hold every task's table, read too ([`TaskTables`]), and keep the task's.
#[derive(Clone, Debug, Default)]
pub struct TaskSpec {
    /// The simulator's settings.
    pub sim: SimOptions,
    /// The world besides the creature (`[task.world]`): flat ground in air unless it says
    /// otherwise; a flat world is not written.
    pub world: WorldSpec,
    /// The habitats one evaluation spans (`[[task.habitats]]`); none: one, this
    /// specification's own world. Not written when there are none.
    pub habitats: Vec<Habitat>,
    /// The trials in each habitat (`[task.trials]`): one without noise unless it says
    /// otherwise; the default is not written.
    pub trials: Trials,
    /// The task and its settings.
    pub task: TaskOptions,
    /// When the creature develops (`develop`, `develop_rate`, `develop_t0`): before the
    /// evaluation unless it says otherwise; the default is not written.
    pub develop: super::Develop,
}

impl Serialize for TaskSpec {
    /// `task`, `sim`, `world` unless it is flat, `trials` unless they are the default,
    /// `habitats` unless there are none, and the task's one table.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let flat = self.world.is_flat();
        let plain_trials = self.trials.is_default();
        let during = self.develop.during();
        let fields = 3
            + usize::from(during) * (2 + usize::from(self.develop.t0.is_some()))
            + usize::from(!flat)
            + usize::from(!plain_trials)
            + usize::from(!self.habitats.is_empty());
        let mut out = serializer.serialize_struct("TaskSpec", fields)?;
        out.serialize_field("task", &self.kind())?;
        if during {
            out.serialize_field("develop", &self.develop.when)?;
            out.serialize_field("develop_rate", &self.develop.rate)?;
            if let Some(t0) = self.develop.t0 {
                out.serialize_field("develop_t0", &t0)?;
            }
        }
        out.serialize_field("sim", &self.sim)?;
        if !flat {
            out.serialize_field("world", &self.world)?;
        }
        if !plain_trials {
            out.serialize_field("trials", &self.trials)?;
        }
        if !self.habitats.is_empty() {
            out.serialize_field("habitats", &self.habitats)?;
        }
        crate::with_options!(&self.task, T, o => out.serialize_field(T::TABLE, o))?;
        out.end()
    }
}

impl<'de> Deserialize<'de> for TaskSpec {
    /// The `[task]` table of a file of this release or an earlier one: the task it names
    /// (the walker when it names none) and its table; the tables of other tasks are read,
    /// checked for unknown keys and dropped.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<TaskSpec, D::Error> {
        TaskTables::deserialize(deserializer).map(|tables| tables.spec(tables.kind()))
    }
}

impl TaskSpec {
    /// The default settings of `task`.
    pub fn new(task: TaskKind) -> TaskSpec {
        TaskSpec {
            sim: SimOptions::default(),
            world: WorldSpec::default(),
            habitats: Vec::new(),
            trials: Trials::default(),
            task: TaskOptions::default_of(task),
            develop: super::Develop::default(),
        }
    }

    /// The task run.
    pub fn kind(&self) -> TaskKind {
        self.task.kind()
    }

    /// The task and what its fitness measures, as every report names them:
    /// `"walker, distance (m)"`, `"walker, normalised (Chaumont eq. 1)"`,
    /// `"jump, height (m)"`, `"catapult, distance (m)"`, `"aim, distance − miss (m)"`,
    /// `"walker, D_w - 0.5 * drag"`.
    pub fn fitness_label(&self) -> String {
        format!("{}, {}", self.kind().name(), self.fitness_measure())
    }

    /// What the fitness measures and in which unit, as plots label their axis:
    /// `"distance (m)"`, `"normalised (Chaumont eq. 1)"`, `"distance − miss (m)"`; a fitness
    /// expression as written (`"D_w - 0.5 * drag"`).
    pub fn fitness_measure(&self) -> String {
        crate::with_options!(&self.task, T, o => match T::expression(o) {
            Some(expression) => expression.source().to_string(),
            None => T::measure(o).to_string(),
        })
    }

    /// The lowest fitness an evaluation that succeeds can score, when the formula has one:
    /// 0 for distances and heights (the walker's formulas but Hornby & Pollack's, the jump,
    /// the catapult); none for the aim task (D_p − D_t), Hornby & Pollack's walker, which
    /// can be negative, and a fitness expression.
    pub fn fitness_floor(&self) -> Option<f64> {
        crate::with_options!(&self.task, T, o => match T::expression(o) {
            Some(_) => None,
            None => T::floor(o),
        })
    }

    /// The fitness expression of the task run, when its `fitness` is one.
    pub fn fitness_expression(&self) -> Option<&FitnessExpression> {
        crate::with_options!(&self.task, T, o => T::expression(o))
    }

    /// Sets the task's `fitness` to `text` (`--fitness`, `fitness=`): the formula of that
    /// name, else an expression of its terms ([`Task::set_fitness`]); [`TaskSpec::check`]
    /// checks it.
    pub fn set_fitness(&mut self, text: &str) {
        crate::with_options!(&mut self.task, T, o => T::set_fitness(o, text))
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
    /// interrupted evaluation has no result: nothing of it is kept). With a fitness
    /// expression, the fitness of an evaluation that succeeds is its value
    /// ([`FitnessExpression::score`]).
    pub fn evaluate_watched(
        &self,
        creature: &Creature,
        watch: Watch<'_>,
    ) -> Result<Evaluation, Interrupted> {
        self.evaluate_growing(creature, watch, None)
    }

    /// [`TaskSpec::evaluate_watched`], the creature growing as `growing` develops during the
    /// evaluation (`develop = "during"`): `creature` is `growing`'s creature at its start.
    pub fn evaluate_growing<'w>(
        &self,
        creature: &Creature,
        watch: Watch<'w>,
        growing: Option<&'w mut super::Growing>,
    ) -> Result<Evaluation, Interrupted> {
        crate::with_options!(&self.task, T, options => {
            let evaluation = T::evaluate(Setup {
                creature,
                sim: &self.sim,
                world: &self.world,
                options,
                watch,
                growing,
            })?;
            Ok(match T::expression(options) {
                Some(expression) => expression.score(evaluation),
                None => evaluation,
            })
        })
    }

    /// Checks that this task grows its creature during an evaluation: only the walker does.
    pub fn check_growing(&self) -> Result<(), GrowError> {
        match self.kind() {
            TaskKind::Walker => Ok(()),
            kind => Err(GrowError::Task(kind.name())),
        }
    }

    /// The evaluation of the creature `seedling` grows into, developing during the
    /// evaluation as [`TaskSpec::develop`] says ([`Growing`]): the creature at t₀ walks `unit`
    /// (placed by its draw, with [`TaskSpec::unit_spec`]) or, for none, the one walk of this
    /// specification. `eval` and the genetic algorithm's evaluator both evaluate a growing
    /// creature through it.
    ///
    /// # Errors
    ///
    /// What development reports, before the walk or during it; [`GrowError::Interrupted`]
    /// once `watch`'s token is set.
    pub fn evaluate_grown_job(
        &self,
        seedling: &Seedling,
        unit: Option<&Unit>,
        watch: Watch<'_>,
    ) -> Result<Evaluation, GrowError> {
        let mut growing = Growing::from_seedling(seedling, &self.develop)?;
        let (spec, creature) = match unit {
            Some(unit) => (
                std::borrow::Cow::Owned(self.unit_spec(unit)),
                unit.perturbation.place(growing.creature()),
            ),
            None => (std::borrow::Cow::Borrowed(self), growing.creature().clone()),
        };
        let watch = Watch {
            record: watch.record,
            progress: &mut *watch.progress,
            cancel: watch.cancel,
        };
        Ok(spec.evaluate_growing(&creature, watch, Some(&mut growing))?)
    }

    /// The most control steps the task can take (every phase at its longest), which sets how
    /// densely a recording keeps samples ([`super::recording_interval`]).
    pub fn max_steps(&self) -> usize {
        crate::with_options!(&self.task, T, o => T::max_steps(&self.sim, o))
    }

    /// The length of the task's measurement (s), which `--seconds` sets ([`Task::seconds`]).
    pub fn seconds_mut(&mut self) -> &mut f64 {
        crate::with_options!(&mut self.task, T, o => T::seconds(o))
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
