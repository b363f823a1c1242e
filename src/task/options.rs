//! One task's settings as one value ([`TaskOptions`], made from the registry): the variant of
//! the task run, holding its [`Task::Options`](super::Task::Options), with typed access for
//! the settings a flag sets (the walker's fitness, the catapult's target).

use std::any::Any;

use super::TaskKind;

crate::for_each_task!(__task_options!());

impl TaskOptions {
    /// The settings, as a value of their own type ([`TaskOptions::get`] reads them so).
    pub fn as_any(&self) -> &dyn Any {
        crate::with_options!(self, T, o => o as &dyn Any)
    }

    /// [`TaskOptions::as_any`], to change them.
    pub fn as_any_mut(&mut self) -> &mut dyn Any {
        crate::with_options!(self, T, o => o as &mut dyn Any)
    }

    /// The settings as `O` (`WalkerOptions`, `CatapultOptions`, ...), when the task run
    /// reads a table of that type: `spec.task.get::<CatapultOptions>()` is the catapult's
    /// table for the catapult and aim tasks, and `None` for the others.
    pub fn get<O: 'static>(&self) -> Option<&O> {
        self.as_any().downcast_ref()
    }

    /// [`TaskOptions::get`], to change them.
    pub fn get_mut<O: 'static>(&mut self) -> Option<&mut O> {
        self.as_any_mut().downcast_mut()
    }

    /// The task's name ([`TaskKind::name`]).
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }

    /// Whether the task throws a projectile ([`TaskKind::throws`]).
    pub fn throws(&self) -> bool {
        self.kind().throws()
    }

    /// The table of `[task]` they are read from and written to ([`super::Task::TABLE`]).
    pub fn table(&self) -> &'static str {
        self.kind().table()
    }
}

impl Default for TaskOptions {
    /// The walker's default settings.
    fn default() -> Self {
        TaskOptions::default_of(TaskKind::default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::task::{CatapultOptions, WalkerOptions};

    #[test]
    fn a_task_reads_its_own_table_and_aim_the_catapults() {
        for &kind in TaskKind::ALL {
            let options = TaskOptions::default_of(kind);
            assert_eq!(options.kind(), kind);
            assert_eq!(
                options.get::<WalkerOptions>().is_some(),
                kind == TaskKind::Walker
            );
            assert_eq!(
                options.get::<CatapultOptions>().is_some(),
                matches!(kind, TaskKind::Catapult | TaskKind::Aim)
            );
        }
        let catapult = TaskOptions::default_of(TaskKind::Catapult);
        let aim = TaskOptions::of_table(TaskKind::Aim, catapult.as_any()).unwrap();
        assert_eq!(aim.kind(), TaskKind::Aim);
        assert_eq!(aim.table(), "catapult");
        assert!(TaskOptions::of_table(TaskKind::Jump, catapult.as_any()).is_none());
    }
}
