//! The registry of tasks: the [`Task`] trait every task implements in its own file, and the
//! one list of them ([`for_each_task!`](crate::for_each_task)), from which the enum of task
//! names ([`TaskKind`](super::TaskKind)), the table of their names and summaries
//! ([`TASKS`]) and the dispatch from a kind to its type ([`with_task!`](crate::with_task))
//! derive, as do the one value holding a task's settings
//! ([`TaskOptions`](super::TaskOptions)) and the dispatch from it to its task
//! ([`with_options!`](crate::with_options)). Adding a task is its file in `task/` and one
//! line in [`for_each_task!`](crate::for_each_task).

use serde::{Serialize, de::DeserializeOwned};

use super::protocol::{Bounds, Setup};
use super::{Evaluation, FitnessExpression};
use crate::cancel::Interrupted;
use crate::sim::{SettingError, SimOptions};

/// One task: its protocol and fitness formula, and what a run or a report needs to know of it.
pub trait Task {
    /// Its name, as the command line, configs and the run store spell it (`"walker"`).
    const NAME: &'static str;
    /// The task in a few words, for `--help` and Python's documentation.
    const SUMMARY: &'static str;
    /// The names of its fitness formulas (`--fitness`), the first the default; empty (the
    /// default) when it has one formula.
    const FITNESS_VARIANTS: &'static [&'static str] = &[];
    /// Whether it throws a projectile (the catapult's kind of body, not a walker's); by
    /// default not.
    const THROWS: bool = false;
    /// The terms its evaluations give (`D_w`, `height`, ...), besides the protocol's
    /// ([`PROTOCOL_TERMS`](super::PROTOCOL_TERMS)): what an expression of its fitness may
    /// read, checked when a config is read, without a simulation.
    const TERMS: &'static [&'static str];

    /// The task settings it reads that a run's flags and Python's keyword arguments set, by
    /// their keyword names (`--seconds`, `seconds=`): what another task does not read is
    /// refused.
    const KEYWORDS: &'static [&'static str] = &["seconds", "fitness"];

    /// The table of `[task]` its settings are read from and written to (`[task.walker]`):
    /// its name, unless it reads another task's table (the aim task reads the catapult's).
    /// Tasks that share a table share their [`Task::Options`] type.
    const TABLE: &'static str = Self::NAME;

    /// Its settings besides the simulator's: its `[task.TABLE]` table, with its [`Bounds`].
    type Options: Bounds
        + Clone
        + std::fmt::Debug
        + Default
        + Serialize
        + DeserializeOwned
        + Send
        + Sync
        + 'static;

    /// What it reads of `options`: what the evaluation key hashes, so that a setting it
    /// ignores (the catapult's target) or a setting of another task never changes its keys.
    fn reads(options: &Self::Options) -> Self::Options {
        options.clone()
    }

    /// Its fitness expression, when its table's `fitness` is one (`fitness = "D_w - 0.5 *
    /// drag"`): the fitness of each of its evaluations that succeeds is then the expression's
    /// value over its terms ([`FitnessExpression::score`]).
    fn expression(options: &Self::Options) -> Option<&FitnessExpression>;

    /// Sets its `fitness` to `text` (`--fitness`, Python's `fitness=`): the formula of that
    /// name ([`Task::FITNESS_VARIANTS`]), else `text` as an expression of its terms, which
    /// [`TaskSpec::check`](super::TaskSpec::check) checks.
    fn set_fitness(options: &mut Self::Options, text: &str);

    /// What its fitness measures and in which unit, as plots label their axis
    /// (`"height (m)"`).
    fn measure(options: &Self::Options) -> &'static str;

    /// The lowest fitness an evaluation that succeeds can score, when the formula has one;
    /// by default 0 (a distance or a height).
    fn floor(_options: &Self::Options) -> Option<f64> {
        Some(0.0)
    }

    /// The most control steps it can take (every phase at its longest): its settings'
    /// [`Bounds::max_steps`] at the simulator's control step.
    fn max_steps(sim: &SimOptions, options: &Self::Options) -> usize {
        options.max_steps(sim.control_step)
    }

    /// The length of its measurement (s), which `--seconds` sets ([`Bounds::seconds`]).
    fn seconds(options: &mut Self::Options) -> &mut f64 {
        options.seconds()
    }

    /// Checks the ranges of `options`, its table (every table a config holds is checked, run
    /// or not); the error names the key in the table, from inside `[task]` (`walker`). By
    /// default the table's own check, [`Bounds::check`].
    fn check_options(options: &Self::Options) -> Result<(), SettingError> {
        options.check()
    }

    /// Checks what it needs of `options` when it is the task run, beyond the table's ranges
    /// (the aim task's target); the error names the key as [`Task::check_options`] does.
    fn check(_options: &Self::Options) -> Result<(), SettingError> {
        Ok(())
    }

    /// Evaluates the creature of `setup` with its simulator's settings, in its world, with its
    /// own settings, watched as `setup` says.
    fn evaluate(setup: Setup<'_, '_, Self::Options>) -> Result<Evaluation, Interrupted>;
}

/// [`Task::expression`] and [`Task::set_fitness`] for a task whose `fitness` setting is an
/// expression of its terms or none (an `Option<FitnessExpression>`), as every task's is but
/// the walker's, whose formulas have names: `expression_fitness!();` in its `impl Task`.
macro_rules! expression_fitness {
    () => {
        fn expression(options: &Self::Options) -> Option<&$crate::task::FitnessExpression> {
            options.fitness.as_ref()
        }
        fn set_fitness(options: &mut Self::Options, text: &str) {
            options.fitness = Some($crate::task::FitnessExpression::new(text));
        }
    };
}
pub(crate) use expression_fitness;

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
    /// The terms its evaluations give ([`Task::TERMS`]).
    pub terms: &'static [&'static str],
    /// The table of `[task]` it reads ([`Task::TABLE`]).
    pub table: &'static str,
    /// The keywords of its settings ([`Task::KEYWORDS`]).
    pub keywords: &'static [&'static str],
}

impl TaskInfo {
    /// The information of task type `T`.
    pub const fn of<T: Task>() -> TaskInfo {
        TaskInfo {
            name: T::NAME,
            summary: T::SUMMARY,
            fitness_variants: T::FITNESS_VARIANTS,
            throws: T::THROWS,
            terms: T::TERMS,
            table: T::TABLE,
            keywords: T::KEYWORDS,
        }
    }

    /// Whether it reads the setting of the keyword `keyword` ([`Task::KEYWORDS`]).
    pub fn reads(&self, keyword: &str) -> bool {
        self.keywords.contains(&keyword)
    }
}

/// The tasks that read the setting of `keyword`, as messages name them: `"the walker task"`,
/// `"the catapult and aim tasks"`.
pub fn tasks_reading(keyword: &str) -> String {
    let names: Vec<&str> = TASKS
        .iter()
        .filter(|t| t.reads(keyword))
        .map(|t| t.name)
        .collect();
    match names.as_slice() {
        [one] => format!("the {one} task"),
        [most @ .., last] => format!("the {} and {last} tasks", most.join(", ")),
        [] => "no task".to_string(),
    }
}

/// The refusal of the keyword `keyword` (spelt `spelt`: `--fitness`, `fitness=`) for `task`,
/// when it does not read it: `"--fitness is for the walker task only, and the task is
/// jump"`.
pub fn keyword_refusal(keyword: &str, spelt: &str, task: &TaskInfo) -> Option<String> {
    (!task.reads(keyword)).then(|| {
        format!(
            "{spelt} is for {} only, and the task is {}",
            tasks_reading(keyword),
            task.name
        )
    })
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

/// Runs `$body` with `$T` standing for the task type of the
/// [`TaskOptions`](super::TaskOptions) `$options` and `$o` for its options (a reference, as
/// `$options` is one): `with_options!(&spec.task, T, o => T::measure(o))`.
#[macro_export]
macro_rules! with_options {
    ($options:expr, $T:ident, $o:ident => $body:expr) => {
        $crate::for_each_task!(__with_options_arms!($options, $T, $o => $body))
    };
}

/// The arms of [`with_options!`](crate::with_options), one per task.
#[doc(hidden)]
#[macro_export]
macro_rules! __with_options_arms {
    ($options:expr, $T:ident, $o:ident => $body:expr; $($variant:ident => $task:path),*) => {
        match $options {
            $($crate::task::TaskOptions::$variant($o) => {
                #[allow(dead_code)]
                type $T = $task;
                $body
            })*
        }
    };
}

/// The enum of one task's settings, one variant per task of the registry.
#[doc(hidden)]
#[macro_export]
macro_rules! __task_options {
    (; $($variant:ident => $task:path),*) => {
        /// One task's settings: the variant of the task run, holding its
        /// [`Task::Options`](crate::task::Task::Options) (its `[task.TABLE]` table).
        #[derive(Clone, Debug)]
        pub enum TaskOptions {
            $(#[doc = concat!("The settings of the task `", stringify!($variant), "`.")]
            $variant(<$task as $crate::task::Task>::Options),)*
        }

        impl TaskOptions {
            /// The task whose settings these are.
            pub fn kind(&self) -> $crate::task::TaskKind {
                match self {
                    $(TaskOptions::$variant(_) => $crate::task::TaskKind::$variant,)*
                }
            }

            /// The default settings of `kind`.
            pub fn default_of(kind: $crate::task::TaskKind) -> TaskOptions {
                match kind {
                    $($crate::task::TaskKind::$variant => TaskOptions::$variant(Default::default()),)*
                }
            }

            /// The settings of `kind` read from `table`, a table of its type (the settings
            /// of a task that shares its table); `None` when `table` is of another type.
            pub fn of_table(kind: $crate::task::TaskKind, table: &dyn std::any::Any) -> Option<TaskOptions> {
                match kind {
                    $($crate::task::TaskKind::$variant => table
                        .downcast_ref::<<$task as $crate::task::Task>::Options>()
                        .cloned()
                        .map(TaskOptions::$variant),)*
                }
            }

            /// The settings of `kind`, the next value of `map` (a `[task.TABLE]` table).
            pub(crate) fn next_value<'de, A: serde::de::MapAccess<'de>>(
                kind: $crate::task::TaskKind,
                map: &mut A,
            ) -> Result<TaskOptions, A::Error> {
                match kind {
                    $($crate::task::TaskKind::$variant => map.next_value().map(TaskOptions::$variant),)*
                }
            }
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
        assert_eq!(task_named("aim").map(|t| t.table), Some("catapult"));
        assert_eq!(
            tasks_reading("fitness"),
            "the walker, jump, catapult, aim, stand and swim tasks"
        );
        assert_eq!(
            tasks_reading("seconds"),
            "the walker, jump, catapult, aim, stand and swim tasks"
        );
        assert_eq!(
            keyword_refusal("target", "--target", task_named("catapult").unwrap()).as_deref(),
            Some("--target is for the aim task only, and the task is catapult")
        );
        assert_eq!(keyword_refusal("seconds", "--seconds", &TASKS[1]), None);
    }
}
