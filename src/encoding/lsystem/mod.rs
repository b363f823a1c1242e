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
//!
//! A genome may also read a chemical array (`environment:`): a production that reads
//! ([`Production::read`]) is called with the read `?E(1, SLOT, 0)` right before every call,
//! and its rules take the value read as `c` through their left context, so that a condition
//! may test it as it tests a parameter (`?E(1, 0, c) < P1(n0, n1) : c > 0.5 --> ...`). The
//! array is read before every derivation step, so the value tested is the array's where the
//! call stands. The `chem` and `secrete` neurons read and write the array from the
//! controller.

use rand::RngExt;
use serde::{Deserialize, Serialize};

use super::{DevelopError, Genome, Rng, array_read, grammar_shown_with_reads};
use crate::creature::{Actuator, Creature, Role};
use crate::develop::{BuildOptions, build, build_frame};
use crate::environment::Environment;
use crate::lang::ast::{BinaryOp, Expr, ModuleCall, Section};
use crate::lang::commands::{Argument, Command};
use crate::lang::{self, Source};
use crate::lsystem::{DeriveOptions, LSystem, ModuleString};

mod develop;
mod mirror;
mod operators;
mod reads;
mod seed;
mod text;

pub use develop::is_driven_walker;
pub(crate) use develop::{develop_text, grown_size, last_frame};
pub(crate) use mirror::ITEMS;
pub(crate) use operators::{
    balance, is_balanced, perturb_argument, pick_run, random_command, random_run,
};
pub(crate) use text::push_item_text;

/// Random constants are rounded to this many parts of a unit, so printed genomes stay
/// readable (`0.731`, not `0.7312093857`); a rounded value prints and parses back exactly.
const GRID: f64 = 1000.0;

/// Range of starting parameters and of the constants conditions compare with.
const PARAM_RANGE: (f64, f64) = (0.0, 8.0);
/// Range of the constant in a `n + c` or `n * c` argument.
const OFFSET_RANGE: (f64, f64) = (-2.0, 2.0);
/// Longest run inserted or deleted by one mutation.
pub(crate) const MAX_RUN: usize = 3;

/// The largest `max_repeat` any run may set: the builder's own cap on one block's count
/// ([`BuildOptions::max_repeat`]'s default).
pub(crate) const MOST_REPEAT: usize = 100;

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
    /// The largest count of a repeat block `{ ... }(n)` the genome may write (Hornby &
    /// Pollack's "repeat the enclosed block of build commands n times"): random successors
    /// and mutation make blocks with counts of 2 to this. 0, the default, makes none, and
    /// the operators draw exactly as they did before the genome had repeat blocks. However
    /// blocks nest, development interprets at most `max_modules` modules in all. Not
    /// written when 0, so that a run's stored configuration stays as it was.
    #[serde(skip_serializing_if = "is_zero")]
    pub max_repeat: usize,
    /// A creature with more neurons than this (sensors and actuators included, as the run
    /// store's `neurons` column counts them) is invalid. Absent (the default): no limit. Not
    /// written when absent, so that a run's stored configuration stays as it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_neurons: Option<usize>,
    /// A creature whose body has a longer unbranched row of parts than this
    /// ([`Creature::longest_chain`](crate::creature::Creature::longest_chain); Hornby &
    /// Pollack's bars in a row) is invalid. Absent (the default): no limit. Not written when
    /// absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_chain: Option<usize>,
    /// The chance that operators make, change or remove an environment read or a `chem` or
    /// `secrete` neuron (the `[ga]` key `environment_reads`, set by
    /// [`Genome::allow_environment_reads`]; not a key of the limits). 0, the default, draws
    /// exactly as a genome without reads always has.
    #[serde(skip)]
    pub environment_reads: f64,
    /// The projectile newborns carry when the run evolves it (set by
    /// [`Genome::evolve_projectile`]; not a key of the limits). None: no genome carries one.
    #[serde(skip)]
    pub projectile: Option<[f64; 3]>,
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
            max_repeat: 0,
            max_neurons: None,
            max_chain: None,
            environment_reads: 0.0,
            projectile: None,
        }
    }
}

/// Whether a count is 0 (so that it is not written).
fn is_zero(v: &usize) -> bool {
    *v == 0
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
        if self.max_repeat == 1 || self.max_repeat > MOST_REPEAT {
            return Err(format!(
                "max_repeat must be 0 (no repeat blocks) or 2 to {MOST_REPEAT}, not {}",
                self.max_repeat
            ));
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

    /// The chance of making or removing a read, within [0, 1] (0 when not a number).
    fn read_chance(&self) -> f64 {
        if self.environment_reads.is_finite() {
            self.environment_reads.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
}

/// The name a reading production's rules give the value read (`?E(1, SLOT, c) < P1(...)`).
pub(crate) const READ_VALUE: &str = "c";

/// Range of the constants conditions on the value read compare with.
const READ_RANGE: (f64, f64) = (0.0, 1.0);

/// The commands that read or write the chemical array from the controller (the `chem`
/// sensor and the `secrete` effector neurons): their argument is a slot of the array.
pub const ENVIRONMENT_COMMANDS: [Command; 2] = [Command::Chem, Command::Secrete];

/// Whether a command reads or writes the chemical array.
fn is_environment_command(c: Command) -> bool {
    ENVIRONMENT_COMMANDS.contains(&c)
}

/// The range an argument's random constants are drawn from and perturbations stay in.
fn range(argument: Argument) -> (f64, f64) {
    match argument {
        Argument::None => (0.0, 0.0),
        Argument::Length => (0.2, 1.2),
        Argument::Size => (0.1, 0.5),
        Argument::Turn => (0.5, 1.0),
        // The textbook's turns, which genomes do not write.
        Argument::Degrees => (45.0, 90.0),
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

/// A condition: parameter `n<param>`, or the value read, compared with a constant.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Condition {
    /// The parameter's index (0, and not used, when the condition tests the value read).
    pub param: usize,
    /// The comparison.
    pub compare: Compare,
    /// The constant.
    pub value: f64,
    /// Whether the condition tests the value its production reads from the chemical array
    /// (`c`), not a parameter: only in a production that reads.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub read: bool,
}

impl Condition {
    /// The condition as a rule's guard writes it (`n0 < 2`, `c > 0.5`).
    pub(crate) fn text(&self) -> String {
        let subject = if self.read {
            READ_VALUE.to_string()
        } else {
            format!("n{}", self.param)
        };
        format!("{subject} {} {}", self.compare.symbol(), self.value)
    }
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
    /// `{`: opens a repeat block (L-system genome only).
    RepeatOpen,
    /// `}(n)`: closes a repeat block, whose items the builder interprets `n` times (a whole
    /// number of 2 to the limits' `max_repeat`).
    RepeatClose(usize),
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
    /// The slot of the chemical array the production reads, if it reads one: every call of
    /// it is written with the read `?E(1, SLOT, 0)` right before it, and its conditions may
    /// test the value read.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub read: Option<usize>,
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
    /// The chemical array's initial values (the printed `environment:`); empty when the
    /// genome has none. Its length is the array's size.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub environment: Vec<f64>,
    /// The edge lengths (m) of the projectile it throws, when its run evolves the projectile
    /// (the printed `# projectile:` line; see [`Genome::evolve_projectile`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub projectile: Option<[f64; 3]>,
}

// ---- the genome ----------------------------------------------------------------------

impl LSystemGenome {
    /// `creature`, developed from this genome, with the projectile the genome carries.
    fn throwing(&self, creature: Creature) -> Creature {
        Creature {
            projectile: self.projectile,
            ..creature
        }
    }

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
    /// named exist, every successor's brackets and repeat blocks are balanced, and every
    /// block's count is within `max_repeat`. `Err` says what is wrong.
    pub fn check(&self, limits: &LSystemLimits) -> Result<(), String> {
        super::projectile::check(self.projectile)?;
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
        super::check_environment_values(&self.environment)?;
        let slots = self.environment.len();
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
            if let Some(slot) = p.read
                && slot >= slots
            {
                return Err(format!(
                    "P{i} reads slot {slot} of an environment of {slots} slot(s)"
                ));
            }
            for pair in &p.pairs {
                if let Some(c) = pair.condition {
                    if !c.value.is_finite() {
                        return Err(format!("P{i} has a condition on {}", c.value));
                    }
                    if c.read && p.read.is_none() {
                        return Err(format!(
                            "P{i} has a condition on the value read, and reads nothing"
                        ));
                    }
                    if !c.read && c.param >= params {
                        return Err(format!("P{i} has a condition on a missing parameter"));
                    }
                }
                if pair.successor.len() > limits.max_successor {
                    return Err(format!(
                        "a successor of P{i} has {} items, more than {}",
                        pair.successor.len(),
                        limits.max_successor
                    ));
                }
                if !is_balanced(&pair.successor) {
                    return Err(format!(
                        "a successor of P{i} has unbalanced brackets or repeat blocks"
                    ));
                }
                for item in &pair.successor {
                    if let Item::Command(c, arg) = item
                        && is_environment_command(*c)
                    {
                        match arg {
                            Some(Arg::Const(v))
                                if *v >= 0.0 && v.fract() == 0.0 && *v < slots as f64 => {}
                            _ if slots == 0 => {
                                return Err(format!(
                                    "a successor of P{i} has {}, which needs an environment \
                                     ('environment:'), and the genome has none",
                                    c.name()
                                ));
                            }
                            _ => {
                                return Err(format!(
                                    "a successor of P{i} has {} without a slot of the \
                                     environment, 0 to {}, as its argument",
                                    c.name(),
                                    slots - 1
                                ));
                            }
                        }
                        continue;
                    }
                    if let Item::RepeatClose(n) = item
                        && !(2..=limits.max_repeat).contains(n)
                    {
                        return Err(match limits.max_repeat {
                            0 => format!(
                                "a successor of P{i} has a repeat block, and the limits allow \
                                 none (max_repeat 0)"
                            ),
                            most => format!(
                                "a successor of P{i} repeats a block {n} times, not 2 to {most} \
                                 (max_repeat)"
                            ),
                        });
                    }
                    let ok = match item {
                        Item::Push | Item::Pop | Item::RepeatOpen | Item::RepeatClose(_) => true,
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
}

impl Genome for LSystemGenome {
    type Limits = LSystemLimits;

    const NAME: &'static str = "lsystem";

    const DESCRIPTION: &'static str = "Hornby & Pollack's parametric L-system";

    fn random(limits: &LSystemLimits, rng: &mut Rng) -> Self {
        LSystemGenome::random_genome(limits, rng)
    }

    fn mutate(&self, limits: &LSystemLimits, rate: f64, rng: &mut Rng) -> Self {
        self.mutant(limits, rate, rng)
    }

    fn crossover(&self, other: &Self, limits: &LSystemLimits, rng: &mut Rng) -> Option<Self> {
        self.child(other, limits, rng)
    }

    /// A part of one of `other`'s successors, half turned (`left(2)`), replaces a part of one
    /// of `self`'s (see `LSystemGenome::mirrored_child`).
    fn mirroring_crossover(
        &self,
        other: &Self,
        limits: &LSystemLimits,
        rng: &mut Rng,
    ) -> Option<Self> {
        self.mirrored_child(other, limits, rng)
    }

    fn allow_environment_reads(limits: &mut LSystemLimits, probability: f64) {
        limits.environment_reads = probability;
    }

    fn evolve_projectile(limits: &mut LSystemLimits, start: [f64; 3]) {
        limits.projectile = Some(start);
    }

    fn projectile(&self) -> Option<[f64; 3]> {
        self.projectile
    }

    fn develop(&self, limits: &LSystemLimits, seed: u64) -> Result<Creature, DevelopError> {
        develop_text(
            &self.to_text(),
            limits.max_modules,
            limits.max_parts,
            seed,
            None,
        )
        .map(|c| self.throwing(c))
    }

    fn environment_values(&self) -> &[f64] {
        &self.environment
    }

    fn develop_in(
        &self,
        limits: &LSystemLimits,
        seed: u64,
        env: &Environment,
    ) -> Result<Creature, DevelopError> {
        develop_text(
            &self.to_text(),
            limits.max_modules,
            limits.max_parts,
            seed,
            array_read(&self.environment, env)?,
        )
        .map(|c| self.throwing(c))
    }

    fn show(&self) -> String {
        grammar_shown_with_reads(&self.to_text(), &self.environment_reads())
    }

    fn to_text(&self) -> String {
        self.text()
    }

    fn from_lsys(text: &str, limits: &LSystemLimits) -> Result<Self, DevelopError> {
        seed::seed_from_lsys("file.lsys", text, limits, false).map(|s| s.genome)
    }

    /// A genome file as this genome writes it: its productions as they stand, nothing
    /// rewritten (unlike a run's seed, [`Genome::from_lsys`]), within `limits`.
    fn read_text(text: &str, limits: &LSystemLimits) -> Result<Self, DevelopError> {
        seed::genome_as_written(text, limits)
    }

    fn seed_from_lsys(
        name: &str,
        text: &str,
        limits: &LSystemLimits,
    ) -> Result<super::Seed<Self>, DevelopError> {
        seed::seed_from_lsys(name, text, limits, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

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
