//! L-systems: compiling a parsed file, and deriving module strings from it.
//!
//! ```
//! use ontogeny::lsystem::{DeriveOptions, LSystem};
//!
//! let lsys = LSystem::from_text("algae", "axiom: a\na --> ab\nb --> a\n").unwrap();
//! let mut derivation = lsys.derivation(&DeriveOptions::default()).unwrap();
//! for _ in 0..3 {
//!     derivation.step().unwrap();
//! }
//! assert_eq!(lsys.display(derivation.current()), "abaab");
//! ```

pub mod check;
mod compile;
mod continuous;
mod cut;
pub(crate) mod defines;
mod derive;
pub mod expr;
mod open;
pub mod print;
mod string;

pub use crate::lang::ast::Timing;
pub use continuous::{Development, Event, MAX_PASSES_PER_INSTANT};
pub use cut::DEFAULT_MAX_WORK;
pub use defines::{DefineOverride, Overrides, Slider, default_range};

use std::sync::Arc;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

pub use string::{Module, ModuleString, NamedModule, POP, PUSH, SymbolId, SymbolTable};

use crate::environment::Environment;
use crate::lang::{self, Diagnostic, DiagnosticKind, LsysFile, Source, Span};
use compile::RuleSet;
use cut::WorkBudget;
use derive::{Failure, Pass, Workspace};

/// The default limit on the length of a derived string.
pub const DEFAULT_MAX_MODULES: usize = 1_000_000;

/// A compiled L-system, ready to derive.
#[derive(Debug)]
pub struct LSystem {
    source: Arc<Source>,
    file: LsysFile,
    symbols: SymbolTable,
    constants: Vec<(String, f64, Span)>,
    axiom: ModuleString,
    axiom_span: Span,
    seed: u64,
    derivation_length: Option<u64>,
    productions: RuleSet,
    interpretation: RuleSet,
    ignored: Vec<bool>,
    /// The id of `?E`, if the system uses it.
    query: Option<SymbolId>,
    environment: Environment,
    time: Option<f64>,
    dt: Option<f64>,
    timing: Timing,
    turtle: TurtleHeaders,
}

/// The file's headers for the textbook turtle (`angle:`, `step:`, `heading:`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TurtleHeaders {
    /// `angle:`: the default angle of `+ - & ^ \ /`, in degrees.
    pub angle: Option<f64>,
    /// `step:`: the default length of `F` and `f`.
    pub step: Option<f64>,
    /// `heading:`: how the turtle starts.
    pub heading: crate::lang::ast::Heading,
}

/// Settings of one derivation. `None` fields fall back to the file's headers.
#[derive(Clone, Debug)]
pub struct DeriveOptions {
    /// Overrides the file's `seed:` for the derivation's draws (stochastic rules, random
    /// functions in rules). The draws made when the grammar was compiled (its defines, its
    /// headers) are the compiled seed's: give the same seed in [`Overrides::seed`] to have
    /// the file's `seed:` edited.
    pub seed: Option<u64>,
    /// A string longer than this is an error.
    pub max_modules: usize,
    /// Overrides initial environment values: (index, value).
    pub env: Vec<(usize, f64)>,
    /// Overrides the file's `time:` (continuous development from 0 to this).
    pub time: Option<f64>,
    /// Overrides the file's `dt:` (the observation step; default 1).
    pub dt: Option<f64>,
    /// Overrides the file's `timing:`.
    pub timing: Option<Timing>,
    /// The work budget: the most modules all rewriting passes may read together (about
    /// modules × steps); a derivation that would pass it stops with an error naming
    /// `--max-work`.
    pub max_work: u64,
}

impl Default for DeriveOptions {
    fn default() -> Self {
        DeriveOptions {
            seed: None,
            max_modules: DEFAULT_MAX_MODULES,
            env: Vec::new(),
            time: None,
            dt: None,
            timing: None,
            max_work: DEFAULT_MAX_WORK,
        }
    }
}

impl LSystem {
    /// Parses and compiles an L-system.
    pub fn parse(source: Arc<Source>) -> Result<LSystem, Diagnostic> {
        LSystem::parse_with(source, &Overrides::default())
    }

    /// Parses and compiles an L-system with `overrides` in place of the values of its
    /// defines and of its seed; a define that uses an overridden one is computed from the new
    /// value, and a seed given is as the file's `seed:` edited (the draws made in compiling
    /// follow it too). An override that names no define of the grammar is an error that lists
    /// its defines.
    pub fn parse_with(source: Arc<Source>, overrides: &Overrides) -> Result<LSystem, Diagnostic> {
        let file = lang::parse(&source)?;
        compile::compile(source, file, overrides)
    }

    /// Parses and compiles `text`, reported under `name`.
    pub fn from_text(name: &str, text: &str) -> Result<LSystem, Diagnostic> {
        LSystem::parse(Source::new(name, text))
    }

    /// Reads, parses and compiles a file; a file that is not a grammar (a MuJoCo model, a
    /// recording, ...) is refused with what it is ([`crate::lang::read_grammar`]).
    pub fn from_path(path: &std::path::Path) -> Result<LSystem, Diagnostic> {
        LSystem::from_path_with(path, &Overrides::default())
    }

    /// Like [`LSystem::from_path`], with `overrides` in place of the values of its defines
    /// and of its seed ([`LSystem::parse_with`]).
    pub fn from_path_with(
        path: &std::path::Path,
        overrides: &Overrides,
    ) -> Result<LSystem, Diagnostic> {
        LSystem::parse_with(crate::lang::read_grammar(path)?, overrides)
    }

    /// The grammar's defines as sliders, in file order: each one's value as compiled, and a
    /// range from its line's `# range A..B` comment, else around its value
    /// ([`default_range`]).
    pub fn sliders(&self) -> Vec<Slider> {
        self.constants
            .iter()
            .map(|(name, value, span)| {
                let (line, _) = self.source.line_col(span.start);
                defines::slider(name, *value, self.source.line_text(line))
            })
            .collect()
    }

    /// The source the system was read from.
    pub fn source(&self) -> &Source {
        &self.source
    }

    /// The syntax tree it was compiled from.
    pub fn file(&self) -> &LsysFile {
        &self.file
    }

    /// The module names.
    pub fn symbols(&self) -> &SymbolTable {
        &self.symbols
    }

    /// The starting string.
    pub fn axiom(&self) -> &ModuleString {
        &self.axiom
    }

    /// The seed it was compiled with: [`Overrides::seed`], else the file's `seed:`, else 0.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The file's `derivation length:`, if given.
    pub fn derivation_length(&self) -> Option<u64> {
        self.derivation_length
    }

    /// The file's headers for the textbook turtle.
    pub fn turtle(&self) -> TurtleHeaders {
        self.turtle
    }

    /// Named constants with their values.
    pub fn constants(&self) -> impl Iterator<Item = (&str, f64)> {
        self.constants.iter().map(|(n, v, _)| (n.as_str(), *v))
    }

    /// Whether the file has productions (rules that rewrite the string); a file of an axiom
    /// alone needs no derivation length.
    pub fn has_productions(&self) -> bool {
        !self.productions.rules.is_empty()
    }

    /// Whether the file has an `interpretation:` section.
    pub fn has_interpretation(&self) -> bool {
        !self.interpretation.rules.is_empty()
    }

    /// Whether the file develops in continuous time (it has `time:`).
    pub fn is_continuous(&self) -> bool {
        self.time.is_some()
    }

    /// The file's `time:`, if any.
    pub fn time(&self) -> Option<f64> {
        self.time
    }

    /// The file's `dt:` (1 if absent).
    pub fn dt(&self) -> f64 {
        self.dt.unwrap_or(1.0)
    }

    /// The file's `timing:` (exact if absent).
    pub fn timing(&self) -> Timing {
        self.timing
    }

    /// The initial environment the file declares.
    pub fn environment(&self) -> &Environment {
        &self.environment
    }

    /// The initial environment with `options.env` applied.
    pub fn initial_environment(&self, options: &DeriveOptions) -> Result<Environment, Diagnostic> {
        let mut env = self.environment.clone();
        for &(index, value) in &options.env {
            env.set(index, value).map_err(|e| {
                Diagnostic::without_location(
                    DiagnosticKind::Semantic,
                    format!("--env {index}={value}: {e} (the file's 'environment:' sets its size)"),
                )
            })?;
        }
        Ok(env)
    }

    /// Starts continuous development (dL-system) at t = 0. `options.time`, `dt` and `timing`
    /// override the file's headers; `time` must be given one way or the other.
    /// [`Development::start`] makes one that holds its grammar.
    pub fn development(&self, options: &DeriveOptions) -> Result<Development<&Self>, Diagnostic> {
        let env = self.initial_environment(options)?;
        self.development_from(self.axiom.clone(), 0.0, env, options)
    }

    /// Continues development from `start` (a string of this system's symbols) at time
    /// `start_time` in environment `env`, for the duration `options.time` (or the file's
    /// `time:`), with frames at `start_time + k·dt`.
    pub fn development_from(
        &self,
        start: ModuleString,
        start_time: f64,
        env: Environment,
        options: &DeriveOptions,
    ) -> Result<Development<&Self>, Diagnostic> {
        LSystem::develop_from(self, start, start_time, env, options)
    }

    /// [`development_from`](Self::development_from) for a development holding `grammar`.
    pub(crate) fn develop_from<G: std::ops::Deref<Target = LSystem>>(
        grammar: G,
        start: ModuleString,
        start_time: f64,
        env: Environment,
        options: &DeriveOptions,
    ) -> Result<Development<G>, Diagnostic> {
        let (time, dt) = grammar.time_and_dt(options)?;
        let timing = options.timing.unwrap_or(grammar.timing);
        Development::new(grammar, options, start, start_time, env, time, dt, timing)
    }

    /// The duration and observation step of continuous development (`options` over the
    /// file's headers), checked: a positive dt, a time of 0 or more, at most 10^9
    /// observation steps.
    fn time_and_dt(&self, options: &DeriveOptions) -> Result<(f64, f64), Diagnostic> {
        let time = options.time.or(self.time).ok_or_else(|| {
            Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!(
                    "{}: continuous development needs 'time: T' in the file or --time",
                    self.source.name()
                ),
            )
        })?;
        let dt = options.dt.or(self.dt).unwrap_or(1.0);
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!("dt must be more than 0, not {dt}"),
            ));
        }
        if !(time >= 0.0 && time.is_finite()) {
            return Err(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!("time must be 0 or more, not {time}"),
            ));
        }
        if time / dt > 1e9 {
            return Err(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!("time / dt = {} observation steps is too many", time / dt),
            ));
        }
        Ok((time, dt))
    }

    /// The frames [`for_each_frame`](Self::for_each_frame) will show with these settings,
    /// known before deriving anything: their number and their times.
    pub fn frame_plan(
        &self,
        options: &DeriveOptions,
        steps: Option<u64>,
    ) -> Result<FramePlan, Diagnostic> {
        if options.time.is_some() || self.is_continuous() {
            let (time, dt) = self.time_and_dt(options)?;
            Ok(FramePlan {
                last_step: continuous::frame_count(time, dt),
                continuous: Some((time, dt)),
            })
        } else {
            Ok(FramePlan {
                last_step: steps.or(self.derivation_length).unwrap_or(0),
                continuous: None,
            })
        }
    }

    /// A string written readably (see [`ModuleString::display`]).
    pub fn display(&self, s: &ModuleString) -> String {
        s.display(&self.symbols)
    }

    /// Starts a discrete derivation at the axiom (its `?E` modules already processed).
    pub fn derivation(&self, options: &DeriveOptions) -> Result<Derivation<'_>, Diagnostic> {
        let env = self.initial_environment(options)?;
        let mut d = self.derivation_from(self.axiom.clone(), 0, options);
        d.env = env;
        d.exchange()?;
        Ok(d)
    }

    /// Starts a derivation at `start`, taken to be the string after `step` steps (its
    /// symbols must come from this system's [`symbols`](Self::symbols)). The random stream
    /// starts afresh from the seed.
    pub fn derivation_from(
        &self,
        start: ModuleString,
        step: u64,
        options: &DeriveOptions,
    ) -> Derivation<'_> {
        let mut rng = ChaCha8Rng::seed_from_u64(options.seed.unwrap_or(self.seed));
        rng.set_stream(0);
        Derivation {
            lsys: self,
            env: self.environment.clone(),
            current: start,
            next: ModuleString::new(),
            step,
            rng,
            workspace: Workspace::default(),
            max_modules: options.max_modules,
            work: WorkBudget::new(options),
            stepped: false,
        }
    }

    /// Applies the interpretation rules once (L-Py's homomorphism) for the builder and
    /// renderer; derivation never sees the result. Without an `interpretation:` section the
    /// string comes back unchanged. `t` is the time the string belongs to.
    pub fn interpret(
        &self,
        s: &ModuleString,
        t: f64,
        options: &DeriveOptions,
    ) -> Result<ModuleString, Diagnostic> {
        if self.interpretation.rules.is_empty() {
            return Ok(s.clone());
        }
        let mut rng = ChaCha8Rng::seed_from_u64(options.seed.unwrap_or(self.seed));
        rng.set_stream(1);
        let mut out = ModuleString::with_capacity(s.len(), s.params.len());
        let pass = Pass {
            rules: &self.interpretation,
            ignored: &self.ignored,
            t,
            max_modules: options.max_modules,
            continuous: false,
        };
        pass.rewrite(s, &mut out, &mut Workspace::default(), &mut rng)
            .map_err(|f| self.failure(f, &format!("interpreting the string at t = {t}")))?;
        Ok(out)
    }

    fn failure(&self, failure: Failure, when: &str) -> Diagnostic {
        let runtime =
            |span, message| Diagnostic::at(DiagnosticKind::Runtime, &self.source, span, message);
        match failure {
            Failure::Expr(e) => runtime(e.span, format!("{} while {when}", e.message)),
            Failure::TooLong { span, limit } => runtime(span.unwrap_or(self.axiom_span), format!("the string grew past {limit} modules while {when}"))
            .with_note("raise the limit with --max-modules, or check for a runaway rule"),
            Failure::SolveInDiscreteMode { span } => runtime(span, format!("a 'solve' rule matched while {when} in discrete steps"))
            .with_note("differential rules grow in continuous time: add 'time: T' to the file or pass --time"),
            Failure::Query { span, message } => runtime(span.unwrap_or(self.axiom_span), format!("{message} while {when}")),
            Failure::NoSettling { span, passes } => runtime(span.unwrap_or(self.axiom_span), format!("this rule keeps firing: more than {passes} rewriting passes at one instant while {when}"))
            .with_note("in continuous time a discrete rule must change its module so that it stops matching"),
        }
    }
}

/// One observation of a derivation or development, as [`LSystem::for_each_frame`] shows it.
pub struct Frame<'a> {
    /// The step (discrete) or observation index (continuous).
    pub step: u64,
    /// Developmental time: the step number in discrete mode, `step · dt` in continuous mode
    /// (the last frame is at the final time, even when dt does not divide it).
    pub t: f64,
    /// The string.
    pub string: &'a ModuleString,
    /// The environment.
    pub env: &'a Environment,
    /// Events since the previous frame (continuous mode).
    pub events: Vec<Event>,
    /// Whether this is the last frame.
    pub last: bool,
    /// On a last frame reached by a shortcut: the step since which the string has not
    /// changed (a fixed point, see [`LSystem::steps_are_pure`]); the frames between it and
    /// this one, all the same, were not derived.
    pub fixed_since: Option<u64>,
    /// The step of the last frame: `step / final_step` is the fraction of the frames shown
    /// so far (see [`Frame::fraction`]).
    pub final_step: u64,
}

impl Frame<'_> {
    /// The fraction of the frames shown so far, 0 at the first frame and 1 at the last: a
    /// derivation's progress, for a progress bar.
    pub fn fraction(&self) -> f64 {
        if self.final_step == 0 {
            1.0
        } else {
            self.step as f64 / self.final_step as f64
        }
    }
}

/// The frames a run shows, known before it starts (see [`LSystem::frame_plan`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FramePlan {
    /// The step of the last frame: frames are numbered 0 to this.
    last_step: u64,
    /// Continuous development's duration and observation step.
    continuous: Option<(f64, f64)>,
}

impl FramePlan {
    /// The step of the last frame (frames are numbered from 0).
    pub fn last_step(&self) -> u64 {
        self.last_step
    }

    /// How many frames: one more than [`last_step`](Self::last_step) (saturating).
    pub fn frame_count(&self) -> u64 {
        self.last_step.saturating_add(1)
    }

    /// The developmental time of frame `step`, as [`Frame::t`] will give it: the step in
    /// discrete mode; `step · dt` in continuous mode, the last frame at the final time.
    pub fn time(&self, step: u64) -> f64 {
        match self.continuous {
            None => step as f64,
            Some((time, _)) if step >= self.last_step => time,
            Some((_, dt)) => step as f64 * dt,
        }
    }
}

impl LSystem {
    /// Runs the system and shows every frame to `visit`: every derivation step in discrete
    /// mode (`steps`, else the file's derivation length, else 0), every observation time in
    /// continuous mode (a file with `time:`, or `options.time`). Past a fixed point of a
    /// discrete derivation ([`LSystem::steps_are_pure`]) the frames show the same string,
    /// derived no more.
    pub fn for_each_frame<E: From<Diagnostic>>(
        &self,
        options: &DeriveOptions,
        steps: Option<u64>,
        mut visit: impl FnMut(Frame<'_>) -> Result<(), E>,
    ) -> Result<(), E> {
        self.frames(options, steps, false, |frame| visit(frame).map(|()| true))
    }

    /// [`for_each_frame`](Self::for_each_frame) cut short where the result is decided: a
    /// discrete derivation that reaches a fixed point shows the frames to it, then at once
    /// the last frame (with [`Frame::fixed_since`]); and the frames stop as soon as `visit`
    /// returns false.
    pub fn for_each_frame_until<E: From<Diagnostic>>(
        &self,
        options: &DeriveOptions,
        steps: Option<u64>,
        visit: impl FnMut(Frame<'_>) -> Result<bool, E>,
    ) -> Result<(), E> {
        self.frames(options, steps, true, visit)
    }

    /// The frames, `jump`ing from a fixed point to the last frame or not.
    fn frames<E: From<Diagnostic>>(
        &self,
        options: &DeriveOptions,
        steps: Option<u64>,
        jump: bool,
        mut visit: impl FnMut(Frame<'_>) -> Result<bool, E>,
    ) -> Result<(), E> {
        if options.time.is_some() || self.is_continuous() {
            let mut dev = self.development(options)?;
            loop {
                let go_on = visit(Frame {
                    step: dev.frame_number(),
                    t: dev.time(),
                    events: dev.take_events(),
                    string: dev.current(),
                    env: dev.environment(),
                    last: dev.frame_number() == dev.frame_count(),
                    fixed_since: None,
                    final_step: dev.frame_count(),
                })?;
                if !go_on || !dev.advance()? {
                    return Ok(());
                }
            }
        }
        let steps = steps.or(self.derivation_length).unwrap_or(0);
        let pure = self.steps_are_pure();
        let mut d = self.derivation(options)?;
        let mut fixed = false;
        for step in 0..=steps {
            if step > 0 && !fixed {
                d.step()?;
                // A fixed point: every later frame is this one.
                fixed = pure && d.unchanged();
            }
            let go_on = visit(Frame {
                step,
                t: step as f64,
                string: d.current(),
                env: d.environment(),
                events: Vec::new(),
                last: step == steps,
                fixed_since: None,
                final_step: steps,
            })?;
            if !go_on {
                return Ok(());
            }
            if jump && fixed && step < steps {
                visit(Frame {
                    step: steps,
                    t: steps as f64,
                    string: d.current(),
                    env: d.environment(),
                    events: Vec::new(),
                    last: true,
                    fixed_since: Some(step),
                    final_step: steps,
                })?;
                return Ok(());
            }
        }
        Ok(())
    }
}

/// A derivation in progress: the current string and the means to rewrite it.
pub struct Derivation<'l> {
    lsys: &'l LSystem,
    env: Environment,
    current: ModuleString,
    next: ModuleString,
    step: u64,
    rng: ChaCha8Rng,
    workspace: Workspace,
    max_modules: usize,
    work: WorkBudget,
    /// Whether a step was taken (then `next` holds the string before it).
    stepped: bool,
}

impl Derivation<'_> {
    /// The string after [`step_number`](Self::step_number) steps.
    pub fn current(&self) -> &ModuleString {
        &self.current
    }

    /// The environment after the current step's `?E` modules were processed.
    pub fn environment(&self) -> &Environment {
        &self.env
    }

    fn exchange(&mut self) -> Result<(), Diagnostic> {
        let Some(query) = self.lsys.query else {
            return Ok(());
        };
        open::exchange(
            &mut self.current,
            query,
            &mut self.env,
            &self.workspace.query_origins,
        )
        .map(|_| ())
        .map_err(|f| {
            let when = format!("processing ?E after step {}", self.step);
            self.lsys.failure(f, &when)
        })
    }

    /// How many steps have been taken.
    pub fn step_number(&self) -> u64 {
        self.step
    }

    /// Whether the last step left the string as it was, bit for bit (false before any
    /// step).
    pub fn unchanged(&self) -> bool {
        self.stepped && self.current.same_bits(&self.next)
    }

    /// Rewrites the current string once, in parallel (refused when it would pass the work
    /// budget, [`DeriveOptions::max_work`]).
    pub fn step(&mut self) -> Result<&ModuleString, Diagnostic> {
        self.work.spend(
            self.current.len(),
            &format!(
                "at step {} (a string of {} modules)",
                self.step + 1,
                self.current.len()
            ),
        )?;
        let pass = Pass {
            rules: &self.lsys.productions,
            ignored: &self.lsys.ignored,
            t: self.step as f64,
            max_modules: self.max_modules,
            continuous: false,
        };
        if let Err(f) = pass.rewrite(
            &self.current,
            &mut self.next,
            &mut self.workspace,
            &mut self.rng,
        ) {
            let when = format!("deriving step {}", self.step + 1);
            return Err(self.lsys.failure(f, &when));
        }
        std::mem::swap(&mut self.current, &mut self.next);
        self.stepped = true;
        self.step += 1;
        self.exchange()?;
        Ok(&self.current)
    }
}
