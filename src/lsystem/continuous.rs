//! Continuous developmental time (differential L-systems): modules under a `solve` rule grow
//! by their ODEs, integrated together with `ode_solvers`' Dopri5; the moments at which a
//! module's first matching rule changes (events) are located by bisection on the solver's
//! dense output, and the string is rewritten there.

use std::cell::{Cell, RefCell};
use std::ops::Deref;
use std::sync::Arc;

use ode_solvers::dop_shared::IntegrationError;
use ode_solvers::{DVector, Dopri5, System};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::derive::{Failure, Pass, Workspace};
use super::expr::{EvalEnv, ExprError};
use super::open::exchange;
use super::string::ModuleString;
use super::{DeriveOptions, LSystem};
use crate::environment::Environment;
use crate::lang::ast::Timing;
use crate::lang::{Diagnostic, DiagnosticKind};

/// Relative tolerance of the ODE solver.
const RTOL: f64 = 1e-11;
/// Absolute tolerance of the ODE solver.
const ATOL: f64 = 1e-12;
/// An event this close after an observation time t (in time units, times max(1, |t|)) is taken
/// to belong to it, so that a guard flipping exactly at a frame — the final time included — is
/// seen at that frame whatever the round-off. Restarting the integrator at every frame adds
/// up round-off: about 1e-12 at t = 4 after 40,000 frames of dt = 1e-4, far inside this
/// window, which is in turn far below any meaningful time.
const EVENT_WINDOW: f64 = 1e-9;
/// A remainder of `time / dt` smaller than this is round-off: `time` is taken to be a whole
/// number of steps, and no extra short step is added before the final time.
const WHOLE_STEPS: f64 = 1e-6;
/// Most rewriting passes at one instant before settling is declared impossible.
pub const MAX_PASSES_PER_INSTANT: usize = 1000;
/// Most events within one observation step.
const MAX_EVENTS_PER_STEP: usize = 100_000;
const NO_RULE: u32 = u32::MAX;

/// A moment at which a module's first matching rule changed.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Event {
    /// When, in developmental time.
    pub t: f64,
    /// The module, written readably, as it was at that moment.
    pub module: String,
    /// The line of the rule that matches it from then on (`None`: no rule matches).
    pub rule_line: Option<usize>,
}

/// Development in continuous time: the string at the latest observation time.
///
/// It holds its grammar `G`: an `Arc<LSystem>` (the default: a development that owns its
/// grammar, made by [`Development::start`], which a physics loop can keep and step by any Δt
/// with [`advance_by`](Self::advance_by)), or a `&LSystem` while an L-system shows its own
/// frames ([`LSystem::development`]).
pub struct Development<G: Deref<Target = LSystem> = Arc<LSystem>> {
    lsys: G,
    string: ModuleString,
    scratch: ModuleString,
    env: Environment,
    t: f64,
    /// The time of frame 0.
    start: f64,
    /// How long development lasts: the last frame is at `start + duration`.
    duration: f64,
    frame: u64,
    frames: u64,
    dt: f64,
    timing: Timing,
    max_modules: usize,
    rng: ChaCha8Rng,
    /// Guards are evaluated many times while locating events: their random draws, if any,
    /// come from this stream so that they do not disturb the rewriting stream.
    classify_rng: ChaCha8Rng,
    ws: Workspace,
    /// The work of the rewriting passes so far, against [`DeriveOptions::max_work`].
    work: super::cut::WorkBudget,
    events: Vec<Event>,
    /// The first matching rule of every module, and the growing modules, as of the last
    /// change to the string; rebuilt after every rewrite (or every interval when guards can
    /// see other modules or the time).
    cache: Cache,
}

#[derive(Default)]
struct Cache {
    valid: bool,
    classes: Vec<u32>,
    growing: Vec<Growing>,
    offsets: Vec<u32>,
    state_len: usize,
}

/// A module growing by a `solve` rule during one integration.
struct Growing {
    module: usize,
    rule: u32,
    /// Where its parameters start in the state vector.
    offset: usize,
    /// Context modules bound by its rule: (first argument slot, module index).
    bound: Vec<(u32, u32)>,
}

impl Development {
    /// Starts continuous development of `lsys` at t = 0, holding the grammar: as
    /// [`LSystem::development`] does, `options.time`, `dt` and `timing` over the file's headers.
    pub fn start(lsys: Arc<LSystem>, options: &DeriveOptions) -> Result<Self, Diagnostic> {
        let env = lsys.initial_environment(options)?;
        let axiom = lsys.axiom.clone();
        LSystem::develop_from(lsys, axiom, 0.0, env, options)
    }
}

impl<G: Deref<Target = LSystem>> Development<G> {
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        lsys: G,
        options: &DeriveOptions,
        start_string: ModuleString,
        start: f64,
        env: Environment,
        time: f64,
        dt: f64,
        timing: Timing,
    ) -> Result<Self, Diagnostic> {
        let seed = options.seed.unwrap_or(lsys.seed);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(0);
        let mut classify_rng = ChaCha8Rng::seed_from_u64(seed);
        classify_rng.set_stream(4);
        let frames = frame_count(time, dt);
        let mut dev = Development {
            lsys,
            string: start_string,
            scratch: ModuleString::new(),
            env,
            t: start,
            start,
            duration: time,
            frame: 0,
            frames,
            dt,
            timing,
            max_modules: options.max_modules,
            rng,
            classify_rng,
            ws: Workspace::default(),
            work: super::cut::WorkBudget::new(options),
            events: Vec::new(),
            cache: Cache::default(),
        };
        match timing {
            Timing::Exact => dev.settle()?,
            Timing::Iterative => {
                dev.exchange()?;
            }
        }
        Ok(dev)
    }

    /// The string at the current observation time.
    pub fn current(&self) -> &ModuleString {
        &self.string
    }

    /// The environment at the current observation time.
    pub fn environment(&self) -> &Environment {
        &self.env
    }

    /// Takes `values` as the environment array (the array a creature's controller reads and
    /// writes while the development goes on during its walk; the same length as this one) and,
    /// if that changed it, processes the `?E` modules at the current instant, as at an event:
    /// with exact timing the exchanges and rewriting passes until nothing changes, with
    /// iterative timing one exchange. Returns whether the array differed.
    ///
    /// # Errors
    ///
    /// A bad `?E` module, or an instant that does not settle.
    pub fn share_environment(&mut self, values: &[f64]) -> Result<bool, Diagnostic> {
        if self.env.values() == values {
            return Ok(false);
        }
        self.env = Environment::new(values.to_vec());
        self.cache.valid = false;
        match self.timing {
            Timing::Exact => self.settle()?,
            Timing::Iterative => {
                self.exchange()?;
            }
        }
        Ok(true)
    }

    /// The index of the current observation (0 for t = 0).
    pub fn frame_number(&self) -> u64 {
        self.frame
    }

    /// The current observation time: `start + frame_number() * dt`, except the last frame,
    /// which is at the final time `start + time` (see [`frame_count`](Self::frame_count)).
    pub fn time(&self) -> f64 {
        self.frame_time(self.frame)
    }

    /// The time of frame `k`.
    fn frame_time(&self, k: u64) -> f64 {
        if k >= self.frames {
            self.start + self.duration
        } else {
            self.start + k as f64 * self.dt
        }
    }

    /// How many observation steps development takes: `time / dt` when dt divides the time
    /// (up to round-off, a remainder below 1e-6 steps), else `ceil(time / dt)`, the last step
    /// being shorter. Either way the last frame is at the final time.
    pub fn frame_count(&self) -> u64 {
        self.frames
    }

    /// Events since the last call, in time order.
    pub fn take_events(&mut self) -> Vec<Event> {
        std::mem::take(&mut self.events)
    }

    /// The developmental time reached: the current observation time, or wherever
    /// [`advance_by`](Self::advance_by) has taken development since.
    pub fn now(&self) -> f64 {
        self.t
    }

    /// Develops by `dt` (any length, 0 or more) from [`now`](Self::now), whatever the
    /// observation step, and past the final time if asked: the physics loop's way to grow a
    /// creature as it walks. With exact timing the string reached does not depend on how the
    /// time is cut into steps (up to the ODE solver's tolerance in growing parameters); with
    /// iterative timing each call is one rewriting pass, as an observation step is. It does
    /// not count observation frames: use it or [`advance`](Self::advance), not both.
    pub fn advance_by(&mut self, dt: f64) -> Result<(), Diagnostic> {
        if !(dt >= 0.0 && dt.is_finite()) {
            return Err(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!("a development step must be 0 or more, not {dt}"),
            ));
        }
        let target = self.t + dt;
        if self.timing == Timing::Iterative {
            self.pass()?;
            self.exchange()?;
        }
        self.integrate_within(target, EVENT_WINDOW * target.abs().max(1.0))?;
        match self.timing {
            Timing::Exact => self.settle(),
            Timing::Iterative => self.exchange().map(|_| ()),
        }
    }

    /// Develops to the next observation time. Returns false when development is over.
    pub fn advance(&mut self) -> Result<bool, Diagnostic> {
        if self.frame >= self.frames {
            return Ok(false);
        }
        let target = self.frame_time(self.frame + 1);
        if self.timing == Timing::Iterative {
            self.pass()?;
            self.exchange()?;
        }
        self.integrate_to(target)?;
        match self.timing {
            Timing::Exact => self.settle()?,
            Timing::Iterative => {
                self.exchange()?;
            }
        }
        self.frame += 1;
        Ok(true)
    }

    fn fail(&self, failure: Failure) -> Diagnostic {
        self.lsys
            .failure(failure, &format!("developing at t = {}", self.t))
    }

    /// One parallel pass: modules whose first matching rule is discrete are rewritten.
    /// Returns how many were.
    fn pass(&mut self) -> Result<super::derive::PassStats, Diagnostic> {
        let when = format!("at t = {} with {} modules", self.t, self.string.len());
        self.work.spend(self.string.len(), &when)?;
        let pass = pass_rules(&self.lsys, self.t, self.max_modules);
        let stats = pass
            .rewrite(&self.string, &mut self.scratch, &mut self.ws, &mut self.rng)
            .map_err(|f| self.fail(f))?;
        if stats.rewritten > 0 {
            std::mem::swap(&mut self.string, &mut self.scratch);
            self.cache.valid = false;
        }
        Ok(stats)
    }

    /// Processes the environment and rewrites at this instant, again and again, until an
    /// exchange changes nothing and a pass rewrites nothing.
    fn settle(&mut self) -> Result<(), Diagnostic> {
        let mut last_rule = None;
        for _ in 0..=MAX_PASSES_PER_INSTANT {
            let changed = self.exchange()?;
            let stats = self.pass()?;
            if stats.rewritten == 0 && !changed {
                return Ok(());
            }
            last_rule = stats.last_rule.or(last_rule);
        }
        Err(self.fail(Failure::NoSettling {
            span: last_rule,
            passes: MAX_PASSES_PER_INSTANT,
        }))
    }

    /// Processes the `?E` modules (after a pass, at events and at frames); returns whether
    /// anything changed.
    fn exchange(&mut self) -> Result<bool, Diagnostic> {
        let Some(query) = self.lsys.query else {
            return Ok(false);
        };
        let changed = exchange(
            &mut self.string,
            query,
            &mut self.env,
            &self.ws.query_origins,
        )
        .map_err(|f| self.fail(f))?;
        if changed {
            self.cache.valid = false;
        }
        Ok(changed)
    }

    /// The first matching rule of every module of the string at time `t`.
    fn classify(&mut self, t: f64, out: &mut Vec<u32>) -> Result<(), Failure> {
        let pass = pass_rules(&self.lsys, t, self.max_modules);
        let string = &self.string;
        pass.prepare(string, &mut self.ws);
        out.clear();
        for i in 0..string.len() {
            let rule = pass.first_match(string, i, &mut self.ws, &mut self.classify_rng)?;
            out.push(rule.unwrap_or(NO_RULE));
        }
        Ok(())
    }

    /// Rebuilds the classification and the list of growing modules if the string changed
    /// (or always, when guards can see other modules or the time).
    fn refresh(&mut self) -> Result<(), Diagnostic> {
        if self.cache.valid && !self.lsys.productions.guards_see_outside {
            return Ok(());
        }
        let mut cache = std::mem::take(&mut self.cache);
        let t = self.t;
        self.classify(t, &mut cache.classes)
            .map_err(|f| self.fail(f))?;
        let rules = &self.lsys.productions.rules;
        cache.growing.clear();
        cache.offsets.clear();
        cache.offsets.resize(self.string.len(), u32::MAX);
        let mut offset = 1; // y[0] is time itself, so the state is never empty
        let pass = pass_rules(&self.lsys, self.t, self.max_modules);
        pass.prepare(&self.string, &mut self.ws);
        for (m, &r) in cache.classes.iter().enumerate() {
            if r != NO_RULE && rules[r as usize].solve.is_some() {
                let rule = &rules[r as usize];
                let bound = if rule.left.is_empty() && rule.right.is_empty() {
                    Vec::new()
                } else {
                    // Bind again to learn which context modules the rule reads.
                    pass.first_match(&self.string, m, &mut self.ws, &mut self.classify_rng)
                        .map_err(|f| self.fail(f))?;
                    self.ws.bound.clone()
                };
                cache.offsets[m] = offset as u32;
                cache.growing.push(Growing {
                    module: m,
                    rule: r,
                    offset,
                    bound,
                });
                offset += self.string.params(m).len();
            }
        }
        cache.state_len = offset;
        cache.valid = true;
        self.cache = cache;
        Ok(())
    }

    /// Integrates the growing modules up to `target`, handling every event on the way.
    fn integrate_to(&mut self, target: f64) -> Result<(), Diagnostic> {
        // The window ends less than half-way to the next frame; after the last frame, nothing
        // follows.
        let next = self.frame_time(self.frame + 2);
        let mut window = EVENT_WINDOW * target.abs().max(1.0);
        if self.frame + 1 < self.frames {
            window = window.min(0.5 * (next - target));
        }
        self.integrate_within(target, window)
    }

    /// Integrates the growing modules up to `target`, handling every event on the way; an
    /// event less than `window` after `target` counts as at `target`.
    fn integrate_within(&mut self, target: f64, window: f64) -> Result<(), Diagnostic> {
        let mut events = 0;
        let mut probe = Vec::new();
        while self.t < target {
            let t0 = self.t;
            self.refresh()?;
            let cache = std::mem::take(&mut self.cache);
            let result = self.integrate_once(t0, target, window, &cache, &mut probe);
            let event = match result {
                Ok(event) => event,
                Err(e) => {
                    self.cache = cache;
                    return Err(e);
                }
            };
            self.cache = cache;
            if !event {
                continue;
            }
            // Even when nothing is rewritten, some module's rule changed.
            self.cache.valid = false;
            match self.timing {
                Timing::Exact => self.settle()?,
                Timing::Iterative => {
                    self.pass()?;
                    self.exchange()?;
                }
            }
            events += 1;
            if events > MAX_EVENTS_PER_STEP {
                let rules = &self.lsys.productions.rules;
                let span = self
                    .cache
                    .growing
                    .first()
                    .map(|g| rules[g.rule as usize].span);
                return Err(self.fail(Failure::Expr(ExprError {
                    span: span.unwrap_or_default(),
                    message: format!(
                        "more than {MAX_EVENTS_PER_STEP} events in one observation step (do guards flip back and forth?)"
                    ),
                })));
            }
        }
        Ok(())
    }

    /// Integrates from `t0` towards `target`; stops at the first event. Returns whether one
    /// happened (the string then holds the state at the event, not yet rewritten).
    fn integrate_once(
        &mut self,
        t0: f64,
        target: f64,
        window: f64,
        cache: &Cache,
        probe: &mut Vec<u32>,
    ) -> Result<bool, Diagnostic> {
        let growing = &cache.growing;
        let baseline = &cache.classes;
        let offsets = &cache.offsets;
        let offset = cache.state_len;
        let end = target + window;
        if end - t0 <= 1e-13 * t0.abs().max(1.0) {
            self.t = target;
            return Ok(false);
        }
        let mut y0 = DVector::zeros(offset);
        y0[0] = t0;
        for g in growing {
            let p = self.string.params(g.module);
            y0.rows_mut(g.offset, p.len()).copy_from_slice(p);
        }

        let system = GrowthSystem {
            dev: RefCell::new(self),
            growing,
            offsets,
            baseline,
            last_same: Cell::new(t0),
            stop: Cell::new(None),
            error: RefCell::new(None),
            probe: RefCell::new(std::mem::take(probe)),
        };
        let mut model = ode_solvers::continuous_output_model::ContinuousOutputModel::default();
        let outcome = {
            let mut solver = Dopri5::new(&system, t0, end, 0.0, y0.clone(), RTOL, ATOL);
            solver.integrate_with_continuous_output_model(&mut model)
        };
        let stop = system.stop.get();
        let error = system.error.borrow_mut().take();
        *probe = system.probe.take();
        drop(system);

        if let Some(e) = error {
            return Err(self.runtime_error(e));
        }
        if let Err(e) = outcome {
            return Err(self.integration_error(e, growing));
        }
        let state_at = |t: f64| model.evaluate(t).unwrap_or_else(|| y0.clone());
        match stop {
            None => {
                let y = state_at(target);
                self.write_state(growing, &y);
                self.t = target;
                Ok(false)
            }
            Some((mut lo, mut hi)) => {
                // Bisection: the first matching rules are as at t0 at `lo`, not at `hi`.
                // Located to a few units of round-off, far inside EVENT_WINDOW.
                while hi - lo > 4.0 * f64::EPSILON * hi.abs().max(1.0) {
                    let mid = 0.5 * (lo + hi);
                    let y = state_at(mid);
                    if self
                        .differs(growing, &y, mid, baseline, probe)
                        .map_err(|f| self.fail(f))?
                    {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                let y = state_at(hi);
                self.write_state(growing, &y);
                self.t = hi;
                self.record_events(baseline, probe)?;
                Ok(true)
            }
        }
    }

    /// Copies the growing parameters of state `y` into the string.
    fn write_state(&mut self, growing: &[Growing], y: &DVector<f64>) {
        for g in growing {
            let start = self.string.bounds[g.module] as usize;
            let n = self.string.params(g.module).len();
            for k in 0..n {
                self.string.params[start + k] = y[g.offset + k];
            }
        }
    }

    /// Whether, at state `y` and time `t`, some module's first matching rule differs from
    /// `baseline`. Leaves state `y` in the string.
    fn differs(
        &mut self,
        growing: &[Growing],
        y: &DVector<f64>,
        t: f64,
        baseline: &[u32],
        probe: &mut Vec<u32>,
    ) -> Result<bool, Failure> {
        self.write_state(growing, y);
        if self.lsys.productions.guards_see_outside {
            self.classify(t, probe)?;
            return Ok(probe.as_slice() != baseline);
        }
        // Guards read only their own module's parameters: only growing modules can change.
        let pass = pass_rules(&self.lsys, t, self.max_modules);
        for g in growing {
            let rule =
                pass.first_match(&self.string, g.module, &mut self.ws, &mut self.classify_rng)?;
            if rule.unwrap_or(NO_RULE) != baseline[g.module] {
                return Ok(true);
            }
        }
        Ok(false)
    }

    fn record_events(&mut self, baseline: &[u32], probe: &mut Vec<u32>) -> Result<(), Diagnostic> {
        let t = self.t;
        self.classify(t, probe).map_err(|f| self.fail(f))?;
        let rules = &self.lsys.productions.rules;
        for (m, (&before, &after)) in baseline.iter().zip(probe.iter()).enumerate() {
            if before != after {
                let mut one = ModuleString::new();
                one.push_from(&self.string, m);
                self.events.push(Event {
                    t,
                    module: self.lsys.display(&one),
                    rule_line: (after != NO_RULE).then(|| {
                        self.lsys
                            .source
                            .line_col(rules[after as usize].span.start)
                            .0
                    }),
                });
            }
        }
        Ok(())
    }

    fn runtime_error(&self, (t, e): (f64, ExprError)) -> Diagnostic {
        Diagnostic::at(
            DiagnosticKind::Runtime,
            &self.lsys.source,
            e.span,
            format!("{} in an ODE at t = {t}", e.message),
        )
    }

    fn integration_error(&self, e: IntegrationError, growing: &[Growing]) -> Diagnostic {
        let message = format!("the ODEs could not be integrated: {e}");
        match growing.first() {
            Some(g) => Diagnostic::at(
                DiagnosticKind::Runtime,
                &self.lsys.source,
                self.lsys.productions.rules[g.rule as usize].span,
                message,
            ),
            None => Diagnostic::without_location(DiagnosticKind::Runtime, message),
        }
    }
}

/// The rewriting pass of continuous development at time `t`.
fn pass_rules(lsys: &LSystem, t: f64, max_modules: usize) -> Pass<'_> {
    Pass {
        rules: &lsys.productions,
        ignored: &lsys.ignored,
        t,
        max_modules,
        continuous: true,
    }
}

/// How many observation steps develop `time` in steps of `dt` (the last one possibly shorter).
pub(super) fn frame_count(time: f64, dt: f64) -> u64 {
    let steps = time / dt;
    let whole = steps.round();
    if (steps - whole).abs() < WHOLE_STEPS {
        whole as u64
    } else {
        steps.ceil() as u64
    }
}

/// The ODE system of one integration, as `ode_solvers` sees it.
struct GrowthSystem<'a, 'd, G: Deref<Target = LSystem>> {
    dev: RefCell<&'d mut Development<G>>,
    growing: &'a [Growing],
    offsets: &'a [u32],
    baseline: &'a [u32],
    /// The last solver time at which every module's first matching rule was as at the start.
    last_same: Cell<f64>,
    /// Set when an event is bracketed: (last time without it, first time with it).
    stop: Cell<Option<(f64, f64)>>,
    error: RefCell<Option<(f64, ExprError)>>,
    probe: RefCell<Vec<u32>>,
}

impl<G: Deref<Target = LSystem>> System<f64, DVector<f64>> for &GrowthSystem<'_, '_, G> {
    fn system(&self, t: f64, y: &DVector<f64>, dy: &mut DVector<f64>) {
        dy.fill(0.0);
        dy[0] = 1.0;
        if self.error.borrow().is_some() {
            return;
        }
        let mut dev = self.dev.borrow_mut();
        let dev = &mut **dev;
        let rules = &dev.lsys.productions.rules;
        let string = &dev.string;
        let args = &mut dev.ws.scratch_args;
        for g in self.growing {
            let rule = &rules[g.rule as usize];
            args.clear();
            args.resize(rule.slots, 0.0);
            args[..rule.arity].copy_from_slice(y.rows(g.offset, rule.arity).as_slice());
            for &(slot, m) in &g.bound {
                let (slot, m) = (slot as usize, m as usize);
                let n = string.params(m).len();
                let at = self.offsets[m];
                if at == u32::MAX {
                    args[slot..slot + n].copy_from_slice(string.params(m));
                } else {
                    args[slot..slot + n].copy_from_slice(y.rows(at as usize, n).as_slice());
                }
            }
            let mut env = EvalEnv {
                args,
                t,
                rng: &mut dev.classify_rng,
            };
            for (index, rate) in rule.solve.as_ref().expect("growing rules solve") {
                match rate.eval(&mut env) {
                    Ok(v) => dy[g.offset + index] = v,
                    Err(e) => {
                        *self.error.borrow_mut() = Some((t, e));
                        return;
                    }
                }
            }
        }
    }

    fn solout(&mut self, t: f64, y: &DVector<f64>, _dy: &DVector<f64>) -> bool {
        if self.error.borrow().is_some() {
            return true;
        }
        let mut dev = self.dev.borrow_mut();
        let mut probe = self.probe.borrow_mut();
        match dev.differs(self.growing, y, t, self.baseline, &mut probe) {
            Ok(false) => {
                self.last_same.set(t);
                false
            }
            Ok(true) => {
                self.stop.set(Some((self.last_same.get(), t)));
                true
            }
            Err(Failure::Expr(e)) => {
                *self.error.borrow_mut() = Some((t, e));
                true
            }
            Err(_) => true,
        }
    }
}
