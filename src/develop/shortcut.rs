//! Growing only the last frame, cut short as soon as its creature is decided: at a fixed
//! point of the derivation (the string no longer changes, so the last frame is this one), or
//! when the settled start of the string ([`LSystem::settled_prefix`], the modules no later
//! step can change) already makes more parts than the limit (the builder reads a string left
//! to right and stops at the limit, so the last creature is invalid, and is exactly the one
//! this start builds). Either way the steps after it are not derived, and the last frame is
//! the one the whole derivation would have built.

use std::fmt;

use super::{Action, BuildOptions, GrowthFrame, build, build_frame, command_of};
use crate::creature::Creature;
use crate::environment::Environment;
use crate::lang::Diagnostic;
use crate::lsystem::{DeriveOptions, LSystem, ModuleString};

/// Why growing stopped before deriving every step: the last creature was decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shortcut {
    /// The string did not change at this step: every later step gives it again.
    FixedPoint {
        /// The step that changed nothing.
        step: u64,
    },
    /// At this step the modules no later step can change already made more parts than the
    /// limit: the last creature is invalid whatever follows.
    PartLimit {
        /// The step (or, in continuous time, the observation) at which it was seen.
        step: u64,
        /// The part limit.
        limit: usize,
    },
}

impl fmt::Display for Shortcut {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Shortcut::FixedPoint { step } => write!(
                f,
                "fixed point at step {step}: later steps give the same string, so they were \
                 not derived"
            ),
            Shortcut::PartLimit { step, limit } => write!(
                f,
                "more than {limit} parts (--max-parts) at step {step}, which no later step can \
                 undo: the creature is invalid, and later steps were not derived"
            ),
        }
    }
}

/// The last frame of a growth, and the shortcut that reached it, if any.
#[derive(Clone, Debug)]
pub struct LastFrame {
    /// The last frame, as deriving every step would have built it.
    pub frame: GrowthFrame,
    /// How it was reached before deriving every step.
    pub shortcut: Option<Shortcut>,
}

/// Grows `lsys` to its last frame, building only that one, cut short where it is decided
/// (see the module's comment); `progress` is told the fraction of the frames done.
pub fn grow_last(
    lsys: &LSystem,
    options: &DeriveOptions,
    steps: Option<u64>,
    build_options: &BuildOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<LastFrame, Diagnostic> {
    let plan = lsys.frame_plan(options, steps)?;
    let (last_step, last_t) = (plan.last_step(), plan.time(plan.last_step()));
    let build_options = &build_options.with_headers(lsys);
    let mut watch = PartWatch::new(lsys, build_options);
    let mut last = None;
    lsys.for_each_frame_until(options, steps, |frame| {
        build_options.cancel.check().map_err(Diagnostic::from)?;
        progress(frame.fraction());
        if frame.last {
            let creature = build_frame(lsys, &frame, options, build_options)?;
            let shortcut = frame.fixed_since.map(|step| Shortcut::FixedPoint { step });
            last = Some((frame.step, frame.t, creature, shortcut));
            return Ok(false);
        }
        // Every frame's string is interpreted, as growing every frame does: an error at any
        // frame before the result is decided is an error.
        lsys.interpret(frame.string, frame.t, options)?;
        if let Some(watch) = &mut watch
            && let Some(creature) = watch.passed(frame.string, frame.env, last_t)
        {
            let shortcut = Shortcut::PartLimit {
                step: frame.step,
                limit: build_options.max_parts,
            };
            last = Some((last_step, last_t, creature, Some(shortcut)));
            return Ok(false);
        }
        Ok::<bool, Diagnostic>(true)
    })?;
    progress(1.0);
    let (step, t, creature, shortcut) = last.ok_or_else(|| {
        Diagnostic::without_location(
            crate::lang::DiagnosticKind::Runtime,
            "development produced no frame".to_string(),
        )
    })?;
    Ok(LastFrame {
        frame: GrowthFrame { step, t, creature },
        shortcut,
    })
}

/// Watches the settled start of each frame's string for the part limit.
struct PartWatch<'a> {
    lsys: &'a LSystem,
    options: &'a BuildOptions,
    /// For each symbol, what it does in the builder.
    actions: Vec<Option<Action>>,
    /// The length of the settled start built last (0: none yet).
    built: usize,
}

impl<'a> PartWatch<'a> {
    /// A watch, or `None` when the system has `?E`: its environment, which the creature
    /// keeps, can change until the last frame.
    fn new(lsys: &'a LSystem, options: &'a BuildOptions) -> Option<PartWatch<'a>> {
        let symbols = lsys.symbols();
        (!lsys.queries_environment()).then(|| PartWatch {
            lsys,
            options,
            actions: (0..symbols.len() as u32)
                .map(|id| command_of(symbols.name(id)))
                .collect(),
            built: 0,
        })
    }

    /// The last creature (built at time `t` in `env`), when the settled start of `string`
    /// already passes the part limit. The start is built only when it could (more `forward`
    /// commands than the limit, or a repeat block) and has grown by an eighth since the last
    /// build, so the watch costs a few builds, not one per step.
    fn passed(&mut self, string: &ModuleString, env: &Environment, t: f64) -> Option<Creature> {
        let settled = self.settled(string);
        if settled == 0 || settled < self.built + (self.built / 8).max(1) {
            return None;
        }
        let (forwards, repeats) = (0..settled).fold((0usize, false), |(n, r), i| {
            match self.actions[string.sym(i) as usize] {
                Some(Action::Forward { .. }) => (n + 1, r),
                Some(Action::RepeatStart) => (n, true),
                _ => (n, r),
            }
        });
        if forwards <= self.options.max_parts && !repeats {
            return None;
        }
        self.built = settled;
        let creature = build(
            &string.prefix(settled),
            self.lsys.symbols(),
            env,
            Some(t),
            self.options,
        );
        (creature.parts.len() > self.options.max_parts).then_some(creature)
    }

    /// The settled start of `string`, ended before a repeat block that it does not close
    /// (the builder pairs a `{` with its `}`, which may lie beyond).
    fn settled(&self, string: &ModuleString) -> usize {
        let settled = self.lsys.settled_prefix(string);
        let mut open = Vec::new();
        for i in 0..settled {
            match self.actions[string.sym(i) as usize] {
                Some(Action::RepeatStart) => open.push(i),
                Some(Action::RepeatEnd) => {
                    open.pop();
                }
                _ => {}
            }
        }
        open.first().copied().unwrap_or(settled)
    }
}
