//! Growing while acting: a continuous development that goes on during an evaluation
//! ([`Growing`]). The creature dropped is the one at developmental time t₀; then, while the
//! protocol runs the controller (the walker's activation and walk), every control step of Δt
//! seconds develops the grammar by `rate` × Δt and applies what changed to the world
//! ([`World::apply_growth`]). While the protocol waits for the creature to come to rest,
//! development pauses: the rest tests measure the body, not its growth.
//!
//! The development and the controller share one environment array: at each control step the
//! development takes the world's array (what the controller's secreting neurons wrote), runs
//! its `?E` exchanges at once if the array changed, develops (exchanging at its events and at
//! the end, as any continuous development does) and writes the array back to the world,
//! whose chemical sensors read it at the next control step.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::creature::Creature;
use crate::develop::{BuildOptions, Growth, Seedling, build, growth_between};
use crate::lang::Diagnostic;
use crate::lsystem::{DeriveOptions, Development, Event, LSystem, ModuleString};
use crate::sim::{Grown, World};

/// When the creature develops: before the evaluation (today's protocol) or during it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DevelopWhen {
    /// Development runs to its end, then the finished creature is evaluated.
    #[default]
    Before,
    /// The creature at t₀ is evaluated, and development goes on during the evaluation.
    During,
}

/// The default `rate`: one unit of developmental time per second of physics.
pub const DEFAULT_RATE: f64 = 1.0;

/// When a creature develops, as `[task]` says: `develop = "before"` (the default, not
/// written) or `"during"`, with `develop_rate` (developmental time per second of physics)
/// and `develop_t0` (the developmental time of the creature dropped; default: the grammar's
/// first frame that builds a valid creature).
#[derive(Clone, Debug, PartialEq)]
pub struct Develop {
    /// Before or during the evaluation.
    pub when: DevelopWhen,
    /// Developmental time per second of physics.
    pub rate: f64,
    /// The developmental time of the creature dropped, if set.
    pub t0: Option<f64>,
}

impl Default for Develop {
    fn default() -> Self {
        Develop {
            when: DevelopWhen::Before,
            rate: DEFAULT_RATE,
            t0: None,
        }
    }
}

impl Develop {
    /// Whether development goes on during the evaluation.
    pub fn during(&self) -> bool {
        self.when == DevelopWhen::During
    }

    /// Checks the rate (finite, above 0) and t₀ (finite, 0 or more).
    pub fn check(&self) -> Result<(), crate::sim::SettingError> {
        crate::sim::check_real("develop_rate", self.rate, 0.0, true)?;
        match self.t0 {
            Some(t0) if !(t0.is_finite() && t0 >= 0.0) => Err(
                crate::sim::SettingError::out_of_range("develop_t0", "0 or more", t0),
            ),
            _ => Ok(()),
        }
    }
}

/// Why a creature cannot grow during an evaluation, or why its growing evaluation stopped.
#[derive(Debug, thiserror::Error)]
pub enum GrowError {
    /// The task does not grow its creature (only the walker does).
    #[error("develop = \"during\": the {0} task does not grow its creature; only the walker does")]
    Task(&'static str),
    /// The grammar develops in discrete steps, named by its source.
    #[error(
        "develop = \"during\": {0} develops in discrete steps; only continuous development (a \
         `time:` line, or --time) goes on during a walk"
    )]
    Discrete(String),
    /// Development failed, before the evaluation or during it.
    #[error(transparent)]
    Development(#[from] Diagnostic),
    /// The evaluation was interrupted.
    #[error(transparent)]
    Interrupted(#[from] crate::cancel::Interrupted),
}

/// Checks that `seedling` develops in continuous time, as a development that goes on during
/// an evaluation must; `source` names the grammar in the refusal.
pub fn check_continuous(seedling: &Seedling, source: &str) -> Result<(), GrowError> {
    match seedling.is_continuous() {
        true => Ok(()),
        false => Err(GrowError::Discrete(source.to_string())),
    }
}

/// How much a creature grew during an evaluation: Kriegman's measure of the development that
/// remains, body against brain.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GrowthTally {
    /// Parts added.
    pub parts: usize,
    /// Length gained (m): the sum of the parts' lengthening.
    pub length: f64,
    /// Neurons added.
    pub neurons: usize,
    /// Links added.
    pub links: usize,
    /// Steps at which some part stopped growing because it would have reached into
    /// something.
    pub stopped: usize,
}

/// A development that goes on while the creature acts: the grammar, the development at its
/// current time, and the creature it has built, its parts, joints and neurons at their ids.
pub struct Growing {
    lsys: Arc<LSystem>,
    development: Development,
    derive: DeriveOptions,
    build: BuildOptions,
    rate: f64,
    creature: Creature,
    tally: GrowthTally,
    events: Vec<Event>,
    /// The last interpreted string, the environment it was built with and the creature
    /// built from them: a step whose string and environment are the same builds the same
    /// creature (but for the time its problems carry), so it reuses this one.
    last_built: Option<(ModuleString, Vec<f64>, Creature)>,
}

impl Growing {
    /// Starts the development of `lsys` and takes it to `t0`, or, with none, to its first
    /// observation frame that builds a valid creature (the last frame if none does); `rate`
    /// is developmental time per second of physics.
    ///
    /// # Errors
    ///
    /// What development reports (a diagnostic of the grammar).
    pub fn start(
        lsys: Arc<LSystem>,
        derive: &DeriveOptions,
        build_options: &BuildOptions,
        rate: f64,
        t0: Option<f64>,
    ) -> Result<Growing, Diagnostic> {
        let build_options = build_options.with_headers(&lsys);
        let mut development = Development::start(Arc::clone(&lsys), derive)?;
        let built = |development: &Development| -> Result<Creature, Diagnostic> {
            let t = development.now();
            let shown = lsys.interpret(development.current(), t, derive)?;
            Ok(build(
                &shown,
                lsys.symbols(),
                development.environment(),
                Some(t),
                &build_options,
            ))
        };
        let creature = match t0 {
            Some(t0) => {
                development.advance_by(t0)?;
                built(&development)?
            }
            None => loop {
                let creature = built(&development)?;
                if creature.is_valid() || !development.advance()? {
                    break creature;
                }
            },
        };
        // The events that led to t₀ are not the evaluation's.
        development.take_events();
        Ok(Growing {
            lsys,
            development,
            derive: derive.clone(),
            build: build_options,
            rate,
            creature,
            tally: GrowthTally::default(),
            events: Vec::new(),
            last_built: None,
        })
    }

    /// [`Growing::start`] from `seedling` as `develop` says (its rate and t₀).
    ///
    /// # Errors
    ///
    /// What development reports.
    pub fn from_seedling(seedling: &Seedling, develop: &Develop) -> Result<Growing, Diagnostic> {
        Growing::start(
            Arc::clone(&seedling.lsys),
            &seedling.derive,
            &seedling.build,
            develop.rate,
            develop.t0,
        )
    }

    /// The creature as it is now, its parts, joints and neurons at their ids.
    pub fn creature(&self) -> &Creature {
        &self.creature
    }

    /// The developmental time reached.
    pub fn now(&self) -> f64 {
        self.development.now()
    }

    /// The development's events (a bud maturing, a guard turning) since it started, in
    /// order, each at the developmental time the dL-system located it at: exactly, whatever
    /// the control step. Their growth reaches the world at the end of the control step they
    /// fall in.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// How much it has grown since it started.
    pub fn tally(&self) -> &GrowthTally {
        &self.tally
    }

    /// Develops by `rate` × `seconds` and applies the growth to `world`, which must hold this
    /// creature.
    ///
    /// # Errors
    ///
    /// What development reports.
    pub fn step(&mut self, world: &mut World, seconds: f64) -> Result<Grown, Diagnostic> {
        // One environment array: the development takes the world's (what the controller
        // secreted this step), exchanges at once if it changed, develops, and gives it back
        // for the controller's next step.
        self.development.share_environment(world.environment())?;
        self.development.advance_by(self.rate * seconds)?;
        world.set_environment(self.development.environment().values());
        self.creature.environment = self.development.environment().values().to_vec();
        self.events.extend(self.development.take_events());
        let t = self.development.now();
        let shown = self
            .lsys
            .interpret(self.development.current(), t, &self.derive)?;
        let environment = self.development.environment().values();
        let after = match &self.last_built {
            Some((string, values, built))
                if same_bits(&string.params, &shown.params)
                    && string.syms == shown.syms
                    && string.bounds == shown.bounds
                    && same_bits(values, environment) =>
            {
                let mut after = built.clone();
                for problem in &mut after.problems {
                    problem.t = Some(t);
                }
                after
            }
            _ => {
                let after = build(
                    &shown,
                    self.lsys.symbols(),
                    self.development.environment(),
                    Some(t),
                    &self.build,
                );
                self.last_built = Some((shown, environment.to_vec(), after.clone()));
                after
            }
        };
        let mut growth: Growth = growth_between(&self.creature, &after, self.build.max_parts);
        if growth.is_empty() {
            return Ok(Grown::default());
        }
        let lengths: f64 = self.creature.parts.iter().map(|p| p.size.x).sum();
        let grown = world.apply_growth(&mut growth);
        self.creature = growth.creature;
        let now: f64 = self.creature.parts.iter().map(|p| p.size.x).sum();
        self.tally.parts += grown.added;
        self.tally.neurons += grown.neurons;
        self.tally.links += grown.links;
        self.tally.stopped += usize::from(!grown.stopped.is_empty());
        // Length gained by the parts there were and brought by the new ones.
        self.tally.length += now - lengths;
        Ok(grown)
    }
}

/// Whether `a` and `b` hold the same numbers, bit for bit (so 0 and −0 differ).
fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}
