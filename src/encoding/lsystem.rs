//! Hornby & Pollack's generative encoding (2001, section "evolutionary algorithm"): a
//! parametric L-system whose productions each have a predecessor with parameters and a list
//! of condition–successor pairs. A condition compares one parameter with a constant; a
//! successor is a string of body and brain commands, `[` `]` branches and calls of
//! productions whose arguments are parameter expressions. Development derives a fixed number
//! of steps from the start production `P0` with its starting parameters, exactly as a
//! hand-written `.lsys` file is derived: [`LSystemGenome::develop`] prints the genome as text
//! and grows it through the language.
//!
//! Every operator keeps the genome within [`LSystemLimits`] by construction: it draws sizes
//! from what the limits leave free and never retries a draw.

use rand::RngExt;
use serde::{Deserialize, Serialize};

use super::command::{Argument, Command};
use super::{DevelopError, Genome, Rng};
use crate::creature::{Actuator, Creature, Role};
use crate::develop::{BuildOptions, build};
use crate::environment::Environment;
use crate::lang::ast::{BinaryOp, Expr, ModuleCall, Section, UnaryOp};
use crate::lang::{self, Source};
use crate::lsystem::{DeriveOptions, LSystem, ModuleString};

/// Random constants are rounded to this many parts of a unit, so printed genomes stay
/// readable (`0.731`, not `0.7312093857`); a rounded value prints and parses back exactly.
const GRID: f64 = 1000.0;

/// Range of starting parameters and of the constants conditions compare with.
const PARAM_RANGE: (f64, f64) = (0.0, 8.0);
/// Range of the constant in a `n + c` or `n * c` argument.
const OFFSET_RANGE: (f64, f64) = (-2.0, 2.0);
/// Longest run inserted or deleted by one mutation.
pub(crate) const MAX_RUN: usize = 3;

/// The limits of the L-system genome: every operator keeps a genome within them. They are
/// part of a run's configuration (`config.toml`); unknown keys are refused.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LSystemLimits {
    /// Most productions (`P0`, `P1`, ...). Hornby & Pollack's runs had a fixed number of
    /// productions (the digit is lost in our copy of the paper); 8 leaves room for a body
    /// plan, a limb and its joints, and a few brain motifs. At least 1 (the start
    /// production).
    pub max_productions: usize,
    /// Most condition–successor pairs per production (Hornby & Pollack: a few per
    /// production; 3 here). At least 1.
    pub max_pairs: usize,
    /// Parameters of every production (Hornby & Pollack: 2). All productions take the same
    /// number, so any call may name any production.
    pub params: usize,
    /// Most items in one successor (commands, brackets and production calls; Hornby &
    /// Pollack's successors had a maximum number of build commands, 15 here).
    pub max_successor: usize,
    /// The derivation length of random genomes, and the most a hand-written file may ask
    /// for (`derivation length:`). Hornby & Pollack derive a fixed number of steps; 6 lets a
    /// production nest calls six deep.
    pub derivation_length: u64,
    /// A derived string longer than this stops development with an error (the language's
    /// `--max-modules`): it cuts runaway growth so that a genome develops in a few
    /// milliseconds.
    pub max_modules: usize,
    /// A creature with more parts than this is invalid (the language's `--max-parts`).
    /// Hornby & Pollack capped their creatures' bars; 50 keeps evaluations fast.
    pub max_parts: usize,
}

impl Default for LSystemLimits {
    fn default() -> Self {
        LSystemLimits {
            max_productions: 8,
            max_pairs: 3,
            params: 2,
            max_successor: 15,
            derivation_length: 6,
            max_modules: 1_000,
            max_parts: 50,
        }
    }
}

impl LSystemLimits {
    /// Checks that the limits make sense; `Err` names the first that does not.
    pub fn validate(&self) -> Result<(), String> {
        if self.max_productions == 0 {
            return Err("max_productions must be at least 1 (the start production)".into());
        }
        if self.max_pairs == 0 {
            return Err("max_pairs must be at least 1".into());
        }
        if self.params > 8 {
            return Err(format!("params must be at most 8, not {}", self.params));
        }
        if self.derivation_length > 64 {
            return Err(format!(
                "derivation_length must be at most 64, not {}",
                self.derivation_length
            ));
        }
        if self.max_modules == 0 || self.max_parts == 0 {
            return Err("max_modules and max_parts must be at least 1".into());
        }
        Ok(())
    }

    /// The most productions, at least 1 (a genome always has its start production).
    fn productions(&self) -> usize {
        self.max_productions.max(1)
    }

    /// The most pairs per production, at least 1.
    fn pairs(&self) -> usize {
        self.max_pairs.max(1)
    }

    /// The parameter count, capped at 8.
    fn param_count(&self) -> usize {
        self.params.min(8)
    }
}

/// The range an argument's random constants are drawn from and perturbations stay in.
fn range(argument: Argument) -> (f64, f64) {
    match argument {
        Argument::None => (0.0, 0.0),
        Argument::Length => (0.2, 1.2),
        Argument::Size => (0.1, 0.5),
        Argument::Turn => (0.5, 1.0),
        Argument::Weight => (-2.0, 2.0),
        Argument::Index => (0.0, 3.0),
        Argument::Function => (0.0, 2.0),
        Argument::Bias => (-1.0, 1.0),
    }
}

/// The step between an argument's values: random values and perturbations stay on this grid
/// (turns are whole half-quarter turns, so that branches meet at 45° or 90°).
fn quantum(argument: Argument) -> f64 {
    match argument {
        Argument::Index | Argument::Function => 1.0,
        Argument::Turn => 0.5,
        _ => 1.0 / GRID,
    }
}

/// The weight of a command in random successors: body commands that make parts and
/// joints, and `output`, which drives a joint, are the most likely, so that random genomes
/// often grow jointed, driven bodies.
fn draw_weight(command: Command) -> u32 {
    match command {
        Command::Forward => 12,
        Command::Revolute1 | Command::Revolute2 | Command::Twist90 | Command::Twist180 => 2,
        Command::Output => 6,
        Command::Left | Command::Right | Command::Up | Command::Down => 2,
        _ => 1,
    }
}

/// An argument: a constant or a parameter expression (Hornby & Pollack's "parameter
/// equation").
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Arg {
    /// A constant.
    Const(f64),
    /// Parameter `n<i>` plus a constant (`n0 + 1`, `n1 - 0.5`, `n0`).
    Plus(usize, f64),
    /// Parameter `n<i>` times a constant (`n1 * 0.5`).
    Times(usize, f64),
}

impl Arg {
    fn text(&self) -> String {
        match *self {
            Arg::Const(c) => format!("{c}"),
            Arg::Plus(i, 0.0) => format!("n{i}"),
            Arg::Plus(i, c) if c < 0.0 => format!("n{i} - {}", -c),
            Arg::Plus(i, c) => format!("n{i} + {c}"),
            Arg::Times(i, c) => format!("n{i} * {c}"),
        }
    }

    fn constant_mut(&mut self) -> &mut f64 {
        match self {
            Arg::Const(c) | Arg::Plus(_, c) | Arg::Times(_, c) => c,
        }
    }
}

/// A comparison in a condition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[allow(missing_docs)]
pub enum Compare {
    Less,
    LessEqual,
    Greater,
    GreaterEqual,
}

impl Compare {
    const ALL: [Compare; 4] = [
        Compare::Less,
        Compare::LessEqual,
        Compare::Greater,
        Compare::GreaterEqual,
    ];

    fn symbol(self) -> &'static str {
        match self {
            Compare::Less => "<",
            Compare::LessEqual => "<=",
            Compare::Greater => ">",
            Compare::GreaterEqual => ">=",
        }
    }

    /// The comparison with its sides swapped (`c < n` is `n > c`).
    fn flipped(self) -> Compare {
        match self {
            Compare::Less => Compare::Greater,
            Compare::LessEqual => Compare::GreaterEqual,
            Compare::Greater => Compare::Less,
            Compare::GreaterEqual => Compare::LessEqual,
        }
    }
}

/// A condition: parameter `n<param>` compared with a constant.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Condition {
    /// The parameter's index.
    pub param: usize,
    /// The comparison.
    pub compare: Compare,
    /// The constant.
    pub value: f64,
}

/// One item of a successor.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Item {
    /// `[`: push the construction state.
    Push,
    /// `]`: pop it.
    Pop,
    /// A building command, with its argument (`None`: written bare, the builder's default).
    Command(Command, Option<Arg>),
    /// A call of production `P<index>` with one argument per parameter.
    Call(usize, Vec<Arg>),
}

/// A condition–successor pair: the successor applies when the condition holds (always,
/// without one) and no earlier pair of the production applies.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pair {
    /// The condition.
    pub condition: Option<Condition>,
    /// The successor.
    pub successor: Vec<Item>,
}

/// A production `P<i>(n0, n1, ...)`: its condition–successor pairs, tried in order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Production {
    /// The pairs (at least one).
    pub pairs: Vec<Pair>,
}

/// Hornby & Pollack's L-system genome.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LSystemGenome {
    /// The starting parameters of `P0`, the axiom.
    pub start: Vec<f64>,
    /// The number of derivation steps.
    pub derivation_length: u64,
    /// The productions; `P0` is the start.
    pub productions: Vec<Production>,
}

// ---- random pieces -------------------------------------------------------------------

fn round(x: f64) -> f64 {
    (x * GRID).round() / GRID
}

fn uniform(rng: &mut Rng, (lo, hi): (f64, f64)) -> f64 {
    round(lo + rng.random::<f64>() * (hi - lo))
}

/// A small change of `x` within `range`: up to a tenth of the range either way, on the
/// grid of `quantum` (a coarse grid: one step either way).
fn perturb(x: f64, (lo, hi): (f64, f64), quantum: f64, rng: &mut Rng) -> f64 {
    let snap = |v: f64| ((v / quantum).round() * quantum).clamp(lo, hi);
    let steps = ((hi - lo) / quantum).round();
    if steps <= 20.0 {
        let step = if rng.random_bool(0.5) {
            quantum
        } else {
            -quantum
        };
        return snap(x + step);
    }
    let step = (hi - lo) * 0.1 * (2.0 * rng.random::<f64>() - 1.0);
    round(snap(x + step))
}

/// A random value of `range` on the grid of `quantum`.
fn random_constant(kind: Argument, rng: &mut Rng) -> f64 {
    let (lo, hi) = range(kind);
    let q = quantum(kind);
    let steps = ((hi - lo) / q).round() as u64;
    round(lo + rng.random_range(0..=steps) as f64 * q)
}

/// A random command drawn by [`draw_weight`], with a random constant argument when it takes
/// one.
pub(crate) fn random_command(rng: &mut Rng) -> Item {
    let total: u32 = Command::ALL.into_iter().map(draw_weight).sum();
    let mut draw = rng.random_range(0..total);
    let mut command = Command::Forward;
    for c in Command::ALL {
        if draw < draw_weight(c) {
            command = c;
            break;
        }
        draw -= draw_weight(c);
    }
    let kind = command.argument();
    let arg = (kind != Argument::None).then(|| Arg::Const(random_constant(kind, rng)));
    Item::Command(command, arg)
}

/// A random argument of a production call: mostly a parameter expression.
fn random_call_arg(params: usize, rng: &mut Rng) -> Arg {
    if params == 0 || rng.random_bool(0.25) {
        return Arg::Const(uniform(rng, PARAM_RANGE));
    }
    let i = rng.random_range(0..params);
    if rng.random_bool(0.75) {
        // Mostly counting down, so that recursion ends by a condition.
        Arg::Plus(i, round(rng.random_range(-2..=1) as f64))
    } else {
        Arg::Times(i, uniform(rng, (0.0, 1.5)))
    }
}

/// A random call from a successor of production `home`: half the time of the next
/// production, so that random genomes use most of their productions.
fn random_call(home: usize, productions: usize, params: usize, rng: &mut Rng) -> Item {
    let target = if home + 1 < productions && rng.random_bool(0.5) {
        home + 1
    } else {
        rng.random_range(0..productions.max(1))
    };
    Item::Call(
        target,
        (0..params).map(|_| random_call_arg(params, rng)).collect(),
    )
}

fn random_condition(params: usize, rng: &mut Rng) -> Option<Condition> {
    (params > 0).then(|| Condition {
        param: rng.random_range(0..params),
        compare: Compare::ALL[rng.random_range(0..4)],
        value: uniform(rng, PARAM_RANGE),
    })
}

/// A random, well-nested run of exactly `len` items for a successor of production `home` of
/// a genome of `productions` productions; with `productions == 0` (the direct genome) a run
/// of commands and brackets only, where a call would have been a random command.
pub(crate) fn random_run(
    len: usize,
    home: usize,
    productions: usize,
    params: usize,
    rng: &mut Rng,
) -> Vec<Item> {
    let mut out = Vec::with_capacity(len);
    push_random_run(&mut out, len, home, productions, params, rng);
    out
}

fn push_random_run(
    out: &mut Vec<Item>,
    len: usize,
    home: usize,
    productions: usize,
    params: usize,
    rng: &mut Rng,
) {
    let mut left = len;
    while left > 0 {
        let draw = rng.random_range(0..100);
        if draw < 12 && left >= 3 {
            // A branch around a shorter run.
            let inner = rng.random_range(1..=(left - 2).min(6));
            out.push(Item::Push);
            push_random_run(out, inner, home, productions, params, rng);
            out.push(Item::Pop);
            left -= inner + 2;
        } else if draw < 24 {
            out.push(if productions == 0 {
                random_command(rng)
            } else {
                random_call(home, productions, params, rng)
            });
            left -= 1;
        } else if draw < 36 && left >= 3 {
            // A driven segment: a joint, the part it moves, and an output driving it.
            let joint = [
                Command::Revolute1,
                Command::Revolute2,
                Command::Twist90,
                Command::Twist180,
            ][rng.random_range(0..4)];
            out.push(Item::Command(joint, None));
            for c in [Command::Forward, Command::Output] {
                let kind = c.argument();
                out.push(Item::Command(
                    c,
                    Some(Arg::Const(random_constant(kind, rng))),
                ));
            }
            left -= 3;
        } else {
            out.push(random_command(rng));
            left -= 1;
        }
    }
}

/// Drops brackets that have no partner, so that a successor is well nested. Only removes
/// items, so it never breaks a limit.
pub(crate) fn balance(items: &mut Vec<Item>) {
    let mut open = Vec::new();
    let mut drop = vec![false; items.len()];
    for (k, item) in items.iter().enumerate() {
        match item {
            Item::Push => open.push(k),
            // The guard pops the partner when there is one; a `]` without one goes.
            Item::Pop if open.pop().is_none() => drop[k] = true,
            _ => {}
        }
    }
    for k in open {
        drop[k] = true;
    }
    let mut k = 0;
    items.retain(|_| {
        k += 1;
        !drop[k - 1]
    });
}

/// Whether every `[` of `items` has its `]` and every `]` its `[`.
pub(crate) fn is_balanced(items: &[Item]) -> bool {
    let mut depth = 0usize;
    for item in items {
        match item {
            Item::Push => depth += 1,
            Item::Pop if depth == 0 => return false,
            Item::Pop => depth -= 1,
            _ => {}
        }
    }
    depth == 0
}

// ---- the genome ----------------------------------------------------------------------

impl LSystemGenome {
    /// The number of items in the longest successor.
    pub fn longest_successor(&self) -> usize {
        self.successors().map(Vec::len).max().unwrap_or(0)
    }

    fn successors(&self) -> impl Iterator<Item = &Vec<Item>> {
        self.productions
            .iter()
            .flat_map(|p| p.pairs.iter().map(|pair| &pair.successor))
    }

    /// Whether the genome lies within `limits` and is well formed: every production has a
    /// pair, calls name existing productions with one argument per parameter, parameters
    /// named exist, and every successor's brackets are balanced. `Err` says what is wrong.
    pub fn check(&self, limits: &LSystemLimits) -> Result<(), String> {
        let params = limits.param_count();
        if self.productions.is_empty() || self.productions.len() > limits.productions() {
            return Err(format!(
                "{} productions, not 1 to {}",
                self.productions.len(),
                limits.productions()
            ));
        }
        if self.start.len() != params {
            return Err(format!(
                "{} starting parameters, not {params}",
                self.start.len()
            ));
        }
        if self.derivation_length > limits.derivation_length {
            return Err(format!(
                "derivation length {} is more than {}",
                self.derivation_length, limits.derivation_length
            ));
        }
        let arg_ok = |a: &Arg| match *a {
            Arg::Const(c) => c.is_finite(),
            Arg::Plus(i, c) | Arg::Times(i, c) => i < params && c.is_finite(),
        };
        for (i, p) in self.productions.iter().enumerate() {
            if p.pairs.is_empty() || p.pairs.len() > limits.pairs() {
                return Err(format!(
                    "P{i} has {} pairs, not 1 to {}",
                    p.pairs.len(),
                    limits.pairs()
                ));
            }
            for pair in &p.pairs {
                if let Some(c) = pair.condition
                    && !(c.param < params && c.value.is_finite())
                {
                    return Err(format!("P{i} has a condition on a missing parameter"));
                }
                if pair.successor.len() > limits.max_successor {
                    return Err(format!(
                        "a successor of P{i} has {} items, more than {}",
                        pair.successor.len(),
                        limits.max_successor
                    ));
                }
                if !is_balanced(&pair.successor) {
                    return Err(format!("a successor of P{i} has unbalanced brackets"));
                }
                for item in &pair.successor {
                    let ok = match item {
                        Item::Push | Item::Pop => true,
                        Item::Command(c, arg) => match arg {
                            None => true,
                            Some(a) => c.argument() != Argument::None && arg_ok(a),
                        },
                        Item::Call(target, args) => {
                            *target < self.productions.len()
                                && args.len() == params
                                && args.iter().all(arg_ok)
                        }
                    };
                    if !ok {
                        return Err(format!("a successor of P{i} has a malformed item {item:?}"));
                    }
                }
            }
        }
        Ok(())
    }

    /// Removes production `k`: calls of it disappear and later productions move down one.
    fn remove_production(&mut self, k: usize) {
        self.productions.remove(k);
        for p in &mut self.productions {
            for pair in &mut p.pairs {
                pair.successor
                    .retain(|item| !matches!(item, Item::Call(t, _) if *t == k));
                for item in &mut pair.successor {
                    if let Item::Call(t, _) = item
                        && *t > k
                    {
                        *t -= 1;
                    }
                }
                balance(&mut pair.successor);
            }
        }
    }

    /// A random production `P<home>` of a genome of `productions` productions.
    fn random_production(
        home: usize,
        productions: usize,
        limits: &LSystemLimits,
        rng: &mut Rng,
    ) -> Production {
        let params = limits.param_count();
        let count = rng.random_range(1..=limits.pairs());
        let pairs = (0..count)
            .map(|k| {
                let len = if limits.max_successor == 0 {
                    0
                } else {
                    rng.random_range(1..=limits.max_successor)
                };
                Pair {
                    // The last pair applies whatever the parameters: a production always
                    // rewrites.
                    condition: if k + 1 == count {
                        None
                    } else {
                        random_condition(params, rng)
                    },
                    successor: random_run(len, home, productions, params, rng),
                }
            })
            .collect();
        Production { pairs }
    }

    /// Mutates one successor in place (its items and runs).
    fn mutate_successor(
        successor: &mut Vec<Item>,
        home: usize,
        productions: usize,
        limits: &LSystemLimits,
        rate: f64,
        rng: &mut Rng,
    ) {
        let params = limits.param_count();
        for item in successor.iter_mut() {
            // Replace a command (or call) by another.
            if rng.random_bool(rate) && !matches!(item, Item::Push | Item::Pop) {
                *item = if rng.random_bool(0.8) {
                    random_command(rng)
                } else {
                    random_call(home, productions, params, rng)
                };
            }
            // Perturb a parameter.
            if rng.random_bool(rate) {
                match item {
                    Item::Command(c, Some(arg)) => perturb_argument(*c, arg, rng),
                    Item::Call(_, args) if !args.is_empty() => {
                        let k = rng.random_range(0..args.len());
                        let arg = &mut args[k];
                        let range = match arg {
                            Arg::Const(_) => PARAM_RANGE,
                            _ => OFFSET_RANGE,
                        };
                        let v = arg.constant_mut();
                        *v = perturb(*v, range, 1.0 / GRID, rng);
                    }
                    _ => {}
                }
            }
        }
        // Insert a run of commands.
        let room = limits.max_successor.saturating_sub(successor.len());
        if room > 0 && rng.random_bool(rate) {
            let len = rng.random_range(1..=room.min(MAX_RUN));
            let at = rng.random_range(0..=successor.len());
            let run = random_run(len, home, productions, params, rng);
            successor.splice(at..at, run);
        }
        // Delete a run.
        if !successor.is_empty() && rng.random_bool(rate) {
            let len = rng.random_range(1..=successor.len().min(MAX_RUN));
            let at = rng.random_range(0..=successor.len() - len);
            successor.drain(at..at + len);
        }
        balance(successor);
    }
}

/// Perturbs the argument of command `c`: a constant within the argument's range and on its
/// grid, the constant of a parameter expression within [`OFFSET_RANGE`].
pub(crate) fn perturb_argument(c: Command, arg: &mut Arg, rng: &mut Rng) {
    let kind = c.argument();
    let (range, quantum) = match arg {
        Arg::Const(_) => (range(kind), quantum(kind)),
        _ => (OFFSET_RANGE, 1.0 / GRID),
    };
    let v = arg.constant_mut();
    *v = perturb(*v, range, quantum, rng);
}

/// Keeps a mutation rate a probability.
pub(crate) fn clamp_rate(rate: f64) -> f64 {
    if rate.is_nan() {
        0.0
    } else {
        rate.clamp(0.0, 1.0)
    }
}

/// Picks a contiguous run of `items` of at most `max` items (possibly empty).
pub(crate) fn pick_run(items: &[Item], max: usize, rng: &mut Rng) -> std::ops::Range<usize> {
    if items.is_empty() || max == 0 {
        return 0..0;
    }
    let len = rng.random_range(1..=items.len().min(max));
    let at = rng.random_range(0..=items.len() - len);
    at..at + len
}

impl Genome for LSystemGenome {
    type Limits = LSystemLimits;

    const NAME: &'static str = "lsystem";

    fn random(limits: &LSystemLimits, rng: &mut Rng) -> Self {
        let count = rng.random_range(1..=limits.productions());
        let productions = (0..count)
            .map(|home| LSystemGenome::random_production(home, count, limits, rng))
            .collect();
        LSystemGenome {
            start: (0..limits.param_count())
                .map(|_| uniform(rng, PARAM_RANGE))
                .collect(),
            derivation_length: limits.derivation_length,
            productions,
        }
    }

    fn mutate(&self, limits: &LSystemLimits, rate: f64, rng: &mut Rng) -> Self {
        let rate = clamp_rate(rate);
        let params = limits.param_count();
        let mut g = self.clone();
        for v in &mut g.start {
            if rng.random_bool(rate) {
                *v = perturb(*v, PARAM_RANGE, 1.0 / GRID, rng);
            }
        }
        // Delete a production (never the start), then perhaps add one.
        if g.productions.len() > 1 && rng.random_bool(rate) {
            let k = rng.random_range(1..g.productions.len());
            g.remove_production(k);
        }
        if g.productions.len() < limits.productions() && rng.random_bool(rate) {
            let n = g.productions.len() + 1;
            let p = LSystemGenome::random_production(n - 1, n, limits, rng);
            g.productions.push(p);
        }
        let n = g.productions.len();
        for (home, p) in g.productions.iter_mut().enumerate() {
            // Delete a pair, or add one before the last (the last often has no condition).
            if p.pairs.len() > 1 && rng.random_bool(rate) {
                let k = rng.random_range(0..p.pairs.len());
                p.pairs.remove(k);
            }
            if p.pairs.len() < limits.pairs() && rng.random_bool(rate) {
                let len = rng.random_range(0..=limits.max_successor);
                let pair = Pair {
                    condition: random_condition(params, rng),
                    successor: random_run(len, home, n, params, rng),
                };
                let at = rng.random_range(0..p.pairs.len());
                p.pairs.insert(at, pair);
            }
            for pair in &mut p.pairs {
                // Change a condition: perturb its constant, or draw a new one (or none).
                if rng.random_bool(rate) {
                    pair.condition = match pair.condition {
                        Some(mut c) if rng.random_bool(0.5) => {
                            c.value = perturb(c.value, PARAM_RANGE, 1.0 / GRID, rng);
                            Some(c)
                        }
                        _ if rng.random_bool(0.2) => None,
                        _ => random_condition(params, rng),
                    };
                }
                LSystemGenome::mutate_successor(&mut pair.successor, home, n, limits, rate, rng);
            }
        }
        g
    }

    fn crossover(&self, other: &Self, limits: &LSystemLimits, rng: &mut Rng) -> Option<Self> {
        let mut child = self.clone();
        let n = child.productions.len();
        let params = limits.param_count();
        // The donor: one successor of the other parent.
        let donor: Vec<&Vec<Item>> = other.successors().collect();
        let receivers: Vec<(usize, usize)> = child
            .productions
            .iter()
            .enumerate()
            .flat_map(|(i, p)| (0..p.pairs.len()).map(move |j| (i, j)))
            .collect();
        if donor.is_empty() || receivers.is_empty() {
            return Some(child);
        }
        let from = donor[rng.random_range(0..donor.len())];
        let (i, j) = receivers[rng.random_range(0..receivers.len())];
        let target = &mut child.productions[i].pairs[j].successor;
        // Calls into productions the child lacks wrap round; arguments fit the child's
        // parameter count.
        let adapt = |item: &Item| match item {
            Item::Call(t, args) => {
                let mut args = args.clone();
                args.resize(params, Arg::Const(0.0));
                for a in &mut args {
                    if let Arg::Plus(k, _) | Arg::Times(k, _) = a
                        && *k >= params
                    {
                        *a = Arg::Const(0.0);
                    }
                }
                Item::Call(t % n, args)
            }
            other => other.clone(),
        };
        match rng.random_range(0..3) {
            0 => {
                // Replace the whole successor.
                *target = from.iter().take(limits.max_successor).map(adapt).collect();
            }
            1 => {
                // Insert a run of the donor.
                let room = limits.max_successor.saturating_sub(target.len());
                let run = pick_run(from, room.min(limits.max_successor), rng);
                let at = rng.random_range(0..=target.len());
                let piece: Vec<Item> = from[run].iter().map(adapt).collect();
                target.splice(at..at, piece);
            }
            _ => {
                // Replace a run with a run of the donor.
                let out = pick_run(target, target.len(), rng);
                let room = limits
                    .max_successor
                    .saturating_sub(target.len() - out.len());
                let run = pick_run(from, room, rng);
                let piece: Vec<Item> = from[run].iter().map(adapt).collect();
                target.splice(out, piece);
            }
        }
        balance(target);
        Some(child)
    }

    fn develop(&self, limits: &LSystemLimits, seed: u64) -> Result<Creature, DevelopError> {
        develop_text(&self.to_text(), limits.max_modules, limits.max_parts, seed)
    }

    fn to_text(&self) -> String {
        let params: Vec<String> = (0..self.start.len()).map(|i| format!("n{i}")).collect();
        let formal = if params.is_empty() {
            String::new()
        } else {
            format!("({})", params.join(", "))
        };
        let mut out = String::new();
        out.push_str(&format!(
            "# An L-system genome (Hornby & Pollack 2001): {} production(s) of {} parameter(s).\n",
            self.productions.len(),
            self.start.len()
        ));
        out.push_str(&format!("derivation length: {}\n", self.derivation_length));
        let start: Vec<String> = self.start.iter().map(|v| format!("{v}")).collect();
        if start.is_empty() {
            out.push_str("axiom: P0\n\n");
        } else {
            out.push_str(&format!("axiom: P0({})\n\n", start.join(", ")));
        }
        for (i, p) in self.productions.iter().enumerate() {
            for pair in &p.pairs {
                out.push_str(&format!("P{i}{formal}"));
                if let Some(c) = pair.condition {
                    out.push_str(&format!(
                        " : n{} {} {}",
                        c.param,
                        c.compare.symbol(),
                        c.value
                    ));
                }
                out.push_str(" -->");
                for item in &pair.successor {
                    out.push(' ');
                    push_item_text(item, &mut out);
                }
                out.push('\n');
            }
        }
        out
    }

    fn from_lsys(text: &str, limits: &LSystemLimits) -> Result<Self, DevelopError> {
        from_lsys(text, limits)
    }
}

/// Appends an item as the language writes it (`[`, `forward(0.5)`, `P1(n0 - 1, 2)`).
pub(crate) fn push_item_text(item: &Item, out: &mut String) {
    match item {
        Item::Push => out.push('['),
        Item::Pop => out.push(']'),
        Item::Command(c, None) => out.push_str(c.name()),
        Item::Command(c, Some(a)) => out.push_str(&format!("{}({})", c.name(), a.text())),
        Item::Call(t, args) if args.is_empty() => out.push_str(&format!("P{t}")),
        Item::Call(t, args) => {
            let args: Vec<String> = args.iter().map(Arg::text).collect();
            out.push_str(&format!("P{t}({})", args.join(", ")));
        }
    }
}

/// Grows `text` as `ontogeny grow --max-modules M --max-parts P` does, building only the
/// last frame (`develop::grow` builds every frame the same way, so its last creature is this
/// one); `seed` drives stochastic rules.
pub(crate) fn develop_text(
    text: &str,
    max_modules: usize,
    max_parts: usize,
    seed: u64,
) -> Result<Creature, DevelopError> {
    let lsys = LSystem::from_text("genome.lsys", text)
        .map_err(|d| DevelopError(format!("the genome does not compile: {d}")))?;
    let options = DeriveOptions {
        seed: Some(seed),
        max_modules,
        ..DeriveOptions::default()
    };
    let build_options = BuildOptions {
        max_parts,
        ..BuildOptions::default()
    };
    last_frame(&lsys, &options, |shown, env, t| {
        build(shown, lsys.symbols(), env, Some(t), &build_options)
    })
    .map_err(|d| DevelopError(d.to_string()))
}

/// Runs `lsys` to its last frame, as `ontogeny grow` does, and gives `visit` that frame's
/// string after the interpretation rules (what the builder sees), its environment and time.
pub(crate) fn last_frame<T>(
    lsys: &LSystem,
    options: &DeriveOptions,
    visit: impl FnOnce(&ModuleString, &Environment, f64) -> T,
) -> Result<T, lang::Diagnostic> {
    let mut visit = Some(visit);
    let mut out = None;
    lsys.for_each_frame(options, None, |frame| {
        if frame.last
            && let Some(visit) = visit.take()
        {
            let shown = lsys.interpret(frame.string, frame.t, options)?;
            out = Some(visit(&shown, frame.env, frame.t));
        }
        Ok::<(), lang::Diagnostic>(())
    })?;
    out.ok_or_else(|| {
        lang::Diagnostic::without_location(
            lang::DiagnosticKind::Runtime,
            "development produced no frame".to_string(),
        )
    })
}

// ---- reading hand-written files ------------------------------------------------------

fn refuse(message: impl Into<String>) -> DevelopError {
    DevelopError(format!(
        "this file does not fit the lsystem genome: {}",
        message.into()
    ))
}

/// A number, or minus a number.
fn number(e: &Expr) -> Option<f64> {
    match e {
        Expr::Number(v, _) => Some(*v),
        Expr::Unary {
            op: UnaryOp::Neg,
            operand,
            ..
        } => match operand.as_ref() {
            Expr::Number(v, _) => Some(-v),
            _ => None,
        },
        _ => None,
    }
}

fn from_lsys(text: &str, limits: &LSystemLimits) -> Result<LSystemGenome, DevelopError> {
    // The language's own checks first: a file that does not compile gets its located error.
    let lsys = LSystem::from_text("file.lsys", text).map_err(|d| DevelopError(d.to_string()))?;
    let source = Source::new("file.lsys", text);
    let file = lang::parse(&source).map_err(|d| DevelopError(d.to_string()))?;
    let snippet = |span: lang::Span| text.get(span.start..span.end).unwrap_or("?").to_string();
    let line = |span: lang::Span| source.line_col(span.start).0;

    if lsys.is_continuous() || file.environment.is_some() {
        return Err(refuse(
            "it develops in continuous time or has an environment; the genome derives discrete steps",
        ));
    }
    if !file.defines.is_empty() {
        return Err(refuse(
            "it defines named constants; write their values in the rules",
        ));
    }
    let derivation_length = lsys.derivation_length().unwrap_or(0);
    if derivation_length > limits.derivation_length {
        return Err(refuse(format!(
            "its derivation length {derivation_length} is more than the limit, {}",
            limits.derivation_length
        )));
    }
    let Some((axiom, axiom_span)) = &file.axiom else {
        return Err(refuse("it has no axiom"));
    };
    let [start] = axiom.as_slice() else {
        return Err(refuse(format!(
            "its axiom must be one production with constant parameters, not '{}'",
            snippet(*axiom_span)
        )));
    };

    // Productions, the axiom's first, then in order of first appearance.
    let mut names: Vec<String> = vec![start.name.clone()];
    for rule in &file.rules {
        if !names.contains(&rule.predecessor.name) {
            names.push(rule.predecessor.name.clone());
        }
    }
    let params = limits.param_count();
    if names.len() > limits.productions() {
        return Err(refuse(format!(
            "it has {} productions, more than the limit, {}",
            names.len(),
            limits.productions()
        )));
    }
    let mut arity = vec![None; names.len()];
    let mut productions: Vec<Production> = vec![Production { pairs: Vec::new() }; names.len()];
    for rule in &file.rules {
        let at = line(rule.span);
        if rule.section == Section::Interpretation {
            return Err(refuse(format!(
                "line {at}: interpretation rules are not part of the genome"
            )));
        }
        if !rule.left.is_empty() || !rule.right.is_empty() {
            return Err(refuse(format!(
                "line {at}: context-sensitive rules are not part of the genome"
            )));
        }
        if rule.probability.is_some() || rule.solve.is_some() {
            return Err(refuse(format!(
                "line {at}: stochastic and differential rules are not part of the genome"
            )));
        }
        let name = &rule.predecessor.name;
        if Command::from_name(name).is_some() || lang::is_builtin_command(name) {
            return Err(refuse(format!(
                "line {at}: a rule rewrites the building command '{name}'; productions must be control symbols"
            )));
        }
        let k = names.iter().position(|n| n == name).expect("collected");
        let formals = &rule.predecessor.params;
        if formals.len() > params {
            return Err(refuse(format!(
                "line {at}: {name} has {} parameters, more than the limit, {params}",
                formals.len()
            )));
        }
        if let Some((f, _)) = formals
            .iter()
            .find(|(f, _)| lang::ast::is_constant_formal(f))
        {
            return Err(refuse(format!(
                "line {at}: the predecessor matches the number {f}; write a condition instead"
            )));
        }
        arity[k] = Some(formals.len());
        let param_of = |n: &str| formals.iter().position(|(f, _)| f == n);
        let arg = |e: &Expr| -> Result<Arg, DevelopError> {
            if let Some(v) = number(e) {
                return Ok(Arg::Const(v));
            }
            let bad = || {
                refuse(format!(
                    "line {at}: the argument '{}' is not a number, a parameter, or a parameter plus, minus or times a number",
                    snippet(e.span())
                ))
            };
            match e {
                Expr::Name(n, _) => param_of(n).map(|i| Arg::Plus(i, 0.0)).ok_or_else(bad),
                Expr::Binary { op, lhs, rhs, .. } => {
                    let (n, c, swapped) = match (lhs.as_ref(), number(rhs), number(lhs)) {
                        (Expr::Name(n, _), Some(c), _) => (n, c, false),
                        (_, _, Some(c)) => match rhs.as_ref() {
                            Expr::Name(n, _) => (n, c, true),
                            _ => return Err(bad()),
                        },
                        _ => return Err(bad()),
                    };
                    let i = param_of(n).ok_or_else(bad)?;
                    match op {
                        BinaryOp::Add => Ok(Arg::Plus(i, c)),
                        BinaryOp::Sub if !swapped => Ok(Arg::Plus(i, -c)),
                        BinaryOp::Mul => Ok(Arg::Times(i, c)),
                        _ => Err(bad()),
                    }
                }
                _ => Err(bad()),
            }
        };
        let condition = match &rule.guard {
            None => None,
            Some(g) => {
                let bad = || {
                    refuse(format!(
                        "line {at}: the condition '{}' is not a parameter compared with a number",
                        snippet(g.span())
                    ))
                };
                let Expr::Binary { op, lhs, rhs, .. } = g else {
                    return Err(bad());
                };
                let compare = match op {
                    BinaryOp::Lt => Compare::Less,
                    BinaryOp::Le => Compare::LessEqual,
                    BinaryOp::Gt => Compare::Greater,
                    BinaryOp::Ge => Compare::GreaterEqual,
                    _ => return Err(bad()),
                };
                let (n, value, compare) = match (lhs.as_ref(), number(rhs), number(lhs)) {
                    (Expr::Name(n, _), Some(c), _) => (n, c, compare),
                    (_, _, Some(c)) => match rhs.as_ref() {
                        Expr::Name(n, _) => (n, c, compare.flipped()),
                        _ => return Err(bad()),
                    },
                    _ => return Err(bad()),
                };
                let param = param_of(n).ok_or_else(bad)?;
                Some(Condition {
                    param,
                    compare,
                    value,
                })
            }
        };
        let mut successor = Vec::new();
        for call in &rule.successor {
            successor.push(item(call, &names, params, at, &arg)?);
        }
        if successor.len() > limits.max_successor {
            return Err(refuse(format!(
                "line {at}: the successor has {} items, more than the limit, {}",
                successor.len(),
                limits.max_successor
            )));
        }
        if !is_balanced(&successor) {
            return Err(refuse(format!(
                "line {at}: the successor's brackets are not balanced"
            )));
        }
        productions[k].pairs.push(Pair {
            condition,
            successor,
        });
        if productions[k].pairs.len() > limits.pairs() {
            return Err(refuse(format!(
                "{name} has more than {} condition-successor pairs",
                limits.pairs()
            )));
        }
    }
    if productions[0].pairs.is_empty() {
        return Err(refuse(format!(
            "the axiom's module {} has no rule",
            names[0]
        )));
    }
    let mut start_values = Vec::new();
    for a in &start.args {
        start_values.push(number(a).ok_or_else(|| {
            refuse(format!(
                "the axiom's parameter '{}' is not a number",
                snippet(a.span())
            ))
        })?);
    }
    if arity[0].is_some_and(|a| a != start_values.len()) {
        return Err(refuse(
            "the axiom's parameter count differs from its rule's",
        ));
    }
    start_values.resize(params, 0.0);
    let genome = LSystemGenome {
        start: start_values,
        derivation_length,
        productions,
    };
    genome.check(limits).map_err(refuse)?;
    Ok(genome)
}

/// One successor module as an item.
fn item(
    call: &ModuleCall,
    names: &[String],
    params: usize,
    at: usize,
    arg: &dyn Fn(&Expr) -> Result<Arg, DevelopError>,
) -> Result<Item, DevelopError> {
    match call.name.as_str() {
        "[" => return Ok(Item::Push),
        "]" => return Ok(Item::Pop),
        _ => {}
    }
    if let Some(c) = Command::from_name(&call.name) {
        return match call.args.as_slice() {
            [] => Ok(Item::Command(c, None)),
            [a] if c.argument() != Argument::None => Ok(Item::Command(c, Some(arg(a)?))),
            _ => Err(refuse(format!(
                "line {at}: '{}' takes {} argument",
                c.name(),
                if c.argument() == Argument::None {
                    "no"
                } else {
                    "at most one"
                }
            ))),
        };
    }
    if let Some(k) = names.iter().position(|n| *n == call.name) {
        let mut args = call.args.iter().map(arg).collect::<Result<Vec<_>, _>>()?;
        args.resize(params, Arg::Const(0.0));
        return Ok(Item::Call(k, args));
    }
    Err(refuse(format!(
        "line {at}: '{}' is neither a production nor a building command the genome uses \
         (not used: repeat blocks, maturing m-commands, chem, secrete, target, release)",
        call.name
    )))
}

/// Whether a creature can walk: valid, at least 2 parts, and a movable joint that an
/// actuator neuron with an input drives.
pub fn is_driven_walker(creature: &Creature) -> bool {
    let driven = creature.brain.neurons.iter().enumerate().any(|(k, n)| {
        matches!(
            n.role,
            Role::Actuator {
                actuator: Actuator::Joint { .. }
            }
        ) && creature
            .brain
            .links
            .iter()
            .any(|l| l.to == k && l.weight != 0.0)
    });
    creature.is_valid() && creature.parts.len() >= 2 && driven
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn fwd(l: f64) -> Item {
        Item::Command(Command::Forward, Some(Arg::Const(l)))
    }

    #[test]
    fn balance_drops_only_unpartnered_brackets() {
        let mut items = vec![
            Item::Pop,
            Item::Push,
            fwd(1.0),
            Item::Push,
            Item::Pop,
            Item::Push,
        ];
        assert!(!is_balanced(&items));
        balance(&mut items);
        // `]` first has nothing to close; the `[` before `f` and the last are never closed.
        assert_eq!(items, vec![fwd(1.0), Item::Push, Item::Pop]);
        assert!(is_balanced(&items));
        let kept = items.clone();
        balance(&mut items);
        assert_eq!(items, kept);
    }

    #[test]
    fn arguments_print_as_the_language_reads_them() {
        assert_eq!(Arg::Const(-1.5).text(), "-1.5");
        assert_eq!(Arg::Plus(0, 0.0).text(), "n0");
        assert_eq!(Arg::Plus(1, -2.0).text(), "n1 - 2");
        assert_eq!(Arg::Plus(1, 0.25).text(), "n1 + 0.25");
        assert_eq!(Arg::Times(0, -1.0).text(), "n0 * -1");
    }

    #[test]
    fn perturbation_stays_in_range_and_on_the_grid() {
        let mut rng = Rng::seed_from_u64(3);
        let mut turn = 1.0;
        let mut length = 0.2;
        for _ in 0..1000 {
            turn = perturb(
                turn,
                range(Argument::Turn),
                quantum(Argument::Turn),
                &mut rng,
            );
            assert!(turn == 0.5 || turn == 1.0, "{turn}");
            let before = length;
            length = perturb(length, range(Argument::Length), 1.0 / GRID, &mut rng);
            assert!((0.2..=1.2).contains(&length));
            // A tenth of the range at most, plus rounding.
            assert!((length - before).abs() <= 0.1 + 1e-9);
            assert_eq!(length, round(length));
            assert_eq!(format!("{length}").parse::<f64>().unwrap(), length);
        }
        let index = perturb(0.0, range(Argument::Index), 1.0, &mut rng);
        assert!(index == 0.0 || index == 1.0);
    }

    #[test]
    fn random_constants_cover_their_grid() {
        let mut rng = Rng::seed_from_u64(1);
        let mut seen = [false; 3];
        for _ in 0..200 {
            let f = random_constant(Argument::Function, &mut rng);
            assert_eq!(f, f.round());
            seen[f as usize] = true;
        }
        assert_eq!(seen, [true; 3]);
    }

    #[test]
    fn removing_a_production_drops_its_calls_and_renumbers_the_rest() {
        let call = |t| Item::Call(t, vec![]);
        let production = |successor| Production {
            pairs: vec![Pair {
                condition: None,
                successor,
            }],
        };
        let mut g = LSystemGenome {
            start: vec![],
            derivation_length: 2,
            productions: vec![
                production(vec![call(1), Item::Push, call(2), Item::Pop, call(0)]),
                production(vec![fwd(1.0)]),
                production(vec![call(1)]),
            ],
        };
        g.remove_production(1);
        assert_eq!(
            g.productions[0].pairs[0].successor,
            vec![Item::Push, call(1), Item::Pop, call(0)]
        );
        assert!(g.productions[1].pairs[0].successor.is_empty());
        let limits = LSystemLimits {
            params: 0,
            ..LSystemLimits::default()
        };
        assert_eq!(g.check(&limits), Ok(()));
        assert_eq!(
            g.to_text().lines().skip(1).collect::<Vec<_>>(),
            [
                "derivation length: 2",
                "axiom: P0",
                "",
                "P0 --> [ P1 ] P0",
                "P1 -->",
            ]
        );
    }

    #[test]
    fn check_names_what_breaks_the_limits() {
        let limits = LSystemLimits::default();
        let mut rng = Rng::seed_from_u64(5);
        let g = LSystemGenome::random(&limits, &mut rng);
        let tight = LSystemLimits {
            max_successor: 0,
            ..LSystemLimits::default()
        };
        assert!(g.check(&tight).unwrap_err().contains("items, more than 0"));
        let mut bad = g.clone();
        bad.productions[0].pairs[0]
            .successor
            .push(Item::Call(99, vec![Arg::Const(0.0); 2]));
        assert!(bad.check(&limits).unwrap_err().contains("malformed"));
        assert!(
            LSystemLimits {
                max_productions: 0,
                ..LSystemLimits::default()
            }
            .validate()
            .is_err()
        );
        assert_eq!(limits.validate(), Ok(()));
    }

    #[test]
    fn limits_read_from_toml_like_json_refuse_unknown_keys() {
        let l: LSystemLimits = serde_json::from_str(r#"{"max_parts": 20}"#).unwrap();
        assert_eq!(l.max_parts, 20);
        assert_eq!(l.max_productions, LSystemLimits::default().max_productions);
        assert!(serde_json::from_str::<LSystemLimits>(r#"{"max_part": 20}"#).is_err());
    }
}
