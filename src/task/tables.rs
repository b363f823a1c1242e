//! The `[task]` table as a file holds it ([`TaskTables`]): the task's name when it gives one,
//! the simulator's settings and the tables of any number of tasks (`[task.walker]`,
//! `[task.jump]`, ...). A configuration may hold several and choose among them with `task =`
//! or `--task`; the files of earlier releases hold every task's. Once the task is known, its
//! one table makes the [`TaskSpec`] ([`TaskTables::spec`]).

use std::sync::LazyLock;

use serde::de::{self, Deserialize, Deserializer, MapAccess, Visitor};

use super::{Develop, Habitat, TASKS, TaskKind, TaskOptions, TaskSpec, Trials};
use crate::sim::{SettingError, SimOptions, WorldSpec};

/// A `[task]` table as read: what `task =` names, the simulator's settings and every task's
/// table it holds. Unknown keys are refused as a struct with `deny_unknown_fields` refuses
/// them, at their place in the file.
#[derive(Clone, Debug, Default)]
pub struct TaskTables {
    /// The task `task =` names, if it names one.
    pub task: Option<TaskKind>,
    /// The simulator's settings (`[task.sim]`).
    pub sim: SimOptions,
    /// The world (`[task.world]`).
    pub world: WorldSpec,
    /// The habitats (`[[task.habitats]]`).
    pub habitats: Vec<Habitat>,
    /// The trials in each habitat (`[task.trials]`).
    pub trials: Trials,
    /// When the creature develops (`develop`, `develop_rate`, `develop_t0`).
    pub develop: Develop,
    /// The tasks' tables it holds, in the order read, each as the settings of the first task
    /// of the registry that reads it.
    tables: Vec<TaskOptions>,
}

/// The keys of `[task]`: `task`, `develop`, `develop_rate`, `develop_t0`, `sim`, `world`, `trials`, `habitats` and each task's table,
/// in the registry's order.
fn fields() -> &'static [&'static str] {
    static FIELDS: LazyLock<Vec<&'static str>> = LazyLock::new(|| {
        let mut fields = vec![
            "task",
            "develop",
            "develop_rate",
            "develop_t0",
            "sim",
            "world",
            "trials",
            "habitats",
        ];
        for task in TASKS {
            if !fields.contains(&task.table) {
                fields.push(task.table);
            }
        }
        fields
    });
    &FIELDS
}

/// The first task of the registry that reads the table `name`.
fn reader_of(name: &str) -> Option<TaskKind> {
    TaskKind::ALL.iter().copied().find(|k| k.table() == name)
}

impl TaskTables {
    /// The task `task =` names; the walker when it names none.
    pub fn kind(&self) -> TaskKind {
        self.task.unwrap_or_default()
    }

    /// The specification of `kind`: the simulator's settings and its table, or its defaults
    /// when the file has no table for it.
    pub fn spec(&self, kind: TaskKind) -> TaskSpec {
        let task = self
            .tables
            .iter()
            .find(|t| t.table() == kind.table())
            .and_then(|t| TaskOptions::of_table(kind, t.as_any()))
            .unwrap_or_else(|| TaskOptions::default_of(kind));
        TaskSpec {
            sim: self.sim.clone(),
            world: self.world.clone(),
            habitats: self.habitats.clone(),
            trials: self.trials.clone(),
            task,
            develop: self.develop.clone(),
        }
    }

    /// The table of type `O` it holds (`WalkerOptions`, ...), if it holds one.
    pub fn get<O: 'static>(&self) -> Option<&O> {
        self.tables.iter().find_map(|t| t.get::<O>())
    }

    /// Checks the ranges of every table it holds but `table` (the table of the task run,
    /// which [`TaskSpec::check`] checks once flags have set it); the error names the key as
    /// a config file spells it (`[task.jump] seconds`).
    pub fn check_other_tables(&self, table: &str) -> Result<(), SettingError> {
        for options in self.tables.iter().filter(|t| t.table() != table) {
            // Checked as every task that reads it checks it (the aim task, the target); its
            // fitness expression, as the fitness of any one of them (the catapult's table may
            // read the aim task's D_t).
            let mut fitness = Vec::new();
            for &kind in TaskKind::ALL
                .iter()
                .filter(|k| k.table() == options.table())
            {
                if let Some(read) = TaskOptions::of_table(kind, options.as_any()) {
                    crate::with_options!(&read, T, o => <T as super::Task>::check_options(o))
                        .map_err(|e| e.within(options.table()).within("task"))?;
                    fitness.push(read.check_fitness());
                }
            }
            if !fitness.iter().any(Result::is_ok)
                && let Some(Err(e)) = fitness.into_iter().next()
            {
                return Err(e.within(options.table()).within("task"));
            }
        }
        Ok(())
    }
}

impl From<&TaskSpec> for TaskTables {
    /// The tables of `spec`: its task and its one table.
    fn from(spec: &TaskSpec) -> TaskTables {
        TaskTables {
            task: Some(spec.kind()),
            sim: spec.sim.clone(),
            world: spec.world.clone(),
            habitats: spec.habitats.clone(),
            trials: spec.trials.clone(),
            develop: spec.develop.clone(),
            tables: vec![spec.task.clone()],
        }
    }
}

/// A key of `[task]`.
enum Key {
    Task,
    Develop,
    DevelopRate,
    DevelopT0,
    Sim,
    World,
    Trials,
    Habitats,
    Table(TaskKind),
}

impl<'de> Deserialize<'de> for Key {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Key, D::Error> {
        struct KeyVisitor;
        impl Visitor<'_> for KeyVisitor {
            type Value = Key;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a key of [task]")
            }
            fn visit_str<E: de::Error>(self, name: &str) -> Result<Key, E> {
                match name {
                    "task" => Ok(Key::Task),
                    "develop" => Ok(Key::Develop),
                    "develop_rate" => Ok(Key::DevelopRate),
                    "develop_t0" => Ok(Key::DevelopT0),
                    "sim" => Ok(Key::Sim),
                    "world" => Ok(Key::World),
                    "trials" => Ok(Key::Trials),
                    "habitats" => Ok(Key::Habitats),
                    _ => reader_of(name)
                        .map(Key::Table)
                        .ok_or_else(|| E::unknown_field(name, fields())),
                }
            }
        }
        deserializer.deserialize_str(KeyVisitor)
    }
}

/// Reads the value of the key `key` of `map` into `slot`, refusing the key when `slot`
/// holds a value already (the key given twice).
fn once<'de, T: Deserialize<'de>, A: MapAccess<'de>>(
    slot: &mut Option<T>,
    key: &'static str,
    map: &mut A,
) -> Result<(), A::Error> {
    if slot.is_some() {
        return Err(de::Error::duplicate_field(key));
    }
    *slot = Some(map.next_value()?);
    Ok(())
}

impl<'de> Deserialize<'de> for TaskTables {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<TaskTables, D::Error> {
        struct TablesVisitor;
        impl<'de> Visitor<'de> for TablesVisitor {
            type Value = TaskTables;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("struct TaskSpec")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<TaskTables, A::Error> {
                let (mut task, mut sim, mut world) = (None, None, None);
                let (mut trials, mut habitats) = (None, None);
                let (mut when, mut rate, mut t0) = (None, None, None);
                let mut tables: Vec<TaskOptions> = Vec::new();
                while let Some(key) = map.next_key::<Key>()? {
                    match key {
                        Key::Task => once(&mut task, "task", &mut map)?,
                        Key::Develop => once(&mut when, "develop", &mut map)?,
                        Key::DevelopRate => once(&mut rate, "develop_rate", &mut map)?,
                        Key::DevelopT0 => once(&mut t0, "develop_t0", &mut map)?,
                        Key::Sim => once(&mut sim, "sim", &mut map)?,
                        Key::World => once(&mut world, "world", &mut map)?,
                        Key::Trials => once(&mut trials, "trials", &mut map)?,
                        Key::Habitats => once(&mut habitats, "habitats", &mut map)?,
                        Key::Table(kind) if tables.iter().any(|t| t.kind() == kind) => {
                            return Err(de::Error::duplicate_field(kind.table()));
                        }
                        Key::Table(kind) => tables.push(TaskOptions::next_value(kind, &mut map)?),
                    }
                }
                Ok(TaskTables {
                    task,
                    sim: sim.unwrap_or_default(),
                    world: world.unwrap_or_default(),
                    habitats: habitats.unwrap_or_default(),
                    trials: trials.unwrap_or_default(),
                    develop: Develop {
                        when: when.unwrap_or_default(),
                        rate: rate.unwrap_or(super::DEFAULT_RATE),
                        t0,
                    },
                    tables,
                })
            }
        }
        deserializer.deserialize_map(TablesVisitor)
    }
}
