//! The registry of tasks: the [`Task`] trait every task implements in its own file, and the
//! one list of them ([`for_each_task!`](crate::for_each_task)), from which the enum of task
//! names ([`TaskKind`](super::TaskKind)), the table of their names and summaries
//! ([`TASKS`]) and the dispatch from a kind to its type ([`with_task!`](crate::with_task))
//! derive. Adding a task is its file in `task/` and one line in
//! [`for_each_task!`](crate::for_each_task).

use serde::Serialize;

use super::{Evaluation, TaskSpec, Watch};
use crate::cancel::Interrupted;
use crate::creature::Creature;
use crate::sim::SettingError;

/// One task: its protocol and fitness formula, and what a run or a report needs to know of it.
pub trait Task {
    /// Its name, as the command line, configs and the run store spell it (`"walker"`).
    const NAME: &'static str;
    /// The task in a few words, for `--help` and Python's documentation.
    const SUMMARY: &'static str;
    /// The names of its fitness formulas (`--fitness`), the first the default; empty when it
    /// has one formula.
    const FITNESS_VARIANTS: &'static [&'static str];
    /// Whether it throws a projectile (the catapult's kind of body, not a walker's).
    const THROWS: bool;

    /// The settings it reads besides the simulator's: what the evaluation key hashes, so
    /// that a setting of another task never changes its keys.
    type Options: Serialize;

    /// Its settings in `spec`, as it reads them.
    fn options(spec: &TaskSpec) -> Self::Options;

    /// What its fitness measures and in which unit, as plots label their axis
    /// (`"height (m)"`).
    fn measure(spec: &TaskSpec) -> &'static str;

    /// The lowest fitness an evaluation that succeeds can score, when the formula has one.
    fn floor(spec: &TaskSpec) -> Option<f64>;

    /// The most control steps it can take (every phase at its longest).
    fn max_steps(spec: &TaskSpec) -> usize;

    /// The length of its measurement (s), which `--seconds` sets.
    fn seconds(spec: &mut TaskSpec) -> &mut f64;

    /// Checks the ranges of its own settings in `spec` (every task's are checked, run or
    /// not); the error names the key in its table, from inside `[task]` (`walker`).
    fn check_options(spec: &TaskSpec) -> Result<(), SettingError>;

    /// Checks what it needs of `spec` when it is the task run, beyond every table's ranges
    /// (the aim task's target); the error names the key as [`Task::check_options`] does.
    fn check(_spec: &TaskSpec) -> Result<(), SettingError> {
        Ok(())
    }

    /// Evaluates `creature` with `spec`, watched as `watch` says.
    fn evaluate(
        creature: &Creature,
        spec: &TaskSpec,
        watch: Watch<'_>,
    ) -> Result<Evaluation, Interrupted>;
}

/// What can be known of a task without its type: for the command line's lists and help, the
/// viewer's and Python's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TaskInfo {
    /// Its name ([`Task::NAME`]).
    pub name: &'static str,
    /// Its summary ([`Task::SUMMARY`]).
    pub summary: &'static str,
    /// Its fitness formulas ([`Task::FITNESS_VARIANTS`]).
    pub fitness_variants: &'static [&'static str],
    /// Whether it throws a projectile ([`Task::THROWS`]).
    pub throws: bool,
}

impl TaskInfo {
    /// The information of task type `T`.
    pub const fn of<T: Task>() -> TaskInfo {
        TaskInfo {
            name: T::NAME,
            summary: T::SUMMARY,
            fitness_variants: T::FITNESS_VARIANTS,
            throws: T::THROWS,
        }
    }
}

/// The registry: calls the macro `$callback` with its arguments, then `;` and every task,
/// one line each (its [`TaskKind`](super::TaskKind) variant and its type), in the order the
/// command line lists them. Keep the order: a task's place is part of the evaluation keys of
/// runs made before the keys had versions.
#[doc(hidden)]
#[macro_export]
macro_rules! for_each_task {
    ($callback:ident!($($args:tt)*)) => {
        $crate::$callback! {$($args)*;
            Walker => $crate::task::WalkerTask,
            Jump => $crate::task::JumpTask,
            Catapult => $crate::task::CatapultTask,
            Aim => $crate::task::AimTask,
            Stand => $crate::task::StandTask,
            Swim => $crate::task::SwimTask
        }
    };
}

/// Runs `$body` with `$T` standing for the task type of the [`TaskKind`](super::TaskKind)
/// `$kind`: `with_task!(spec.task, T => T::max_steps(spec))`.
#[macro_export]
macro_rules! with_task {
    ($kind:expr, $T:ident => $body:expr) => {
        $crate::for_each_task!(__with_task_arms!($kind, $T => $body))
    };
}

/// The arms of [`with_task!`](crate::with_task), one per task.
#[doc(hidden)]
#[macro_export]
macro_rules! __with_task_arms {
    ($kind:expr, $T:ident => $body:expr; $($variant:ident => $task:path),*) => {
        match $kind {
            $($crate::task::TaskKind::$variant => {
                type $T = $task;
                $body
            })*
        }
    };
}

/// The enum of task names, one variant per task of the registry.
#[doc(hidden)]
#[macro_export]
macro_rules! __task_kind {
    (; $($variant:ident => $task:path),*) => {
        /// The tasks of the registry ([`for_each_task!`](crate::for_each_task)), by name.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
        #[serde(rename_all = "kebab-case")]
        pub enum TaskKind {
            #[default]
            $(#[doc = concat!("The task `", stringify!($variant), "` of the registry.")] $variant,)*
        }

        impl TaskKind {
            /// Every task, in the order `--help` lists them.
            pub const ALL: &'static [TaskKind] = &[$(TaskKind::$variant),*];
        }
    };
}

/// The table of [`TASKS`], one row per task.
#[doc(hidden)]
#[macro_export]
macro_rules! __task_table {
    (; $($variant:ident => $task:path),*) => {
        [$($crate::task::TaskInfo::of::<$task>()),*]
    };
}

/// Every task, in the registry's order.
pub const TASKS: &[TaskInfo] = &crate::for_each_task!(__task_table!());

/// The task named `name`.
pub fn task_named(name: &str) -> Option<&'static TaskInfo> {
    TASKS.iter().find(|t| t.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::task::TaskKind;

    #[test]
    fn every_task_is_listed_once_and_dispatches_to_its_own_type() {
        let names: Vec<&str> = TASKS.iter().map(|t| t.name).collect();
        assert_eq!(
            names,
            ["walker", "jump", "catapult", "aim", "stand", "swim"]
        );
        for (&kind, info) in TaskKind::ALL.iter().zip(TASKS) {
            assert!(!info.summary.is_empty(), "{}", info.name);
            assert_eq!(crate::with_task!(kind, T => T::NAME), info.name);
            assert_eq!(serde_json::to_value(kind).unwrap(), info.name);
        }
        assert_eq!(task_named("aim").map(|t| t.throws), Some(true));
        assert_eq!(task_named("walk"), None);
    }
}
