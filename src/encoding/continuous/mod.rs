//! The `lsystem-continuous` genome: Matos & Arita's evolvable differential L-systems
//! (section 3.2, Figure 2).
//!
//! A genome is an axiom and a set of rules that are all instances of one **viable template**:
//! a maturing symbol grows linearly (`solve dx/dt = r`) while its parameter is below a
//! threshold, and is then replaced by its matured twin plus further tokens:
//!
//! ```text
//! mforward(x) : x < 0.8 --> solve dx/dt = 0.4
//! mforward(x) : x >= 0.8 --> forward(x) [ right(1) revolute2 mforward(0) ] output(1)
//! ```
//!
//! The maturing symbols are the maturing twins of the body commands (`mforward`, the turns,
//! the joints) and the control tokens `A`, `B`, ..., which build nothing and have no twin.
//! Every maturing token is born at 0 and every threshold and rate is positive, so a token
//! always grows before it matures: development cannot loop at one instant, and the number of
//! generations is bounded by `time / min_duration`.
//!
//! The genome develops through its text ([`ContinuousGenome::to_text`]), exactly as
//! `ontogeny grow` develops the printed file.

use rand::RngExt;
use serde::{Deserialize, Serialize};

use super::{DevelopError, Genome, Rng, array_read, grammar_shown_with_reads, neurons_written};
use crate::creature::Creature;
use crate::develop::BuildOptions;
use crate::environment::Environment;
use crate::lang::ast::{BinaryOp, Expr, ModuleCall};
use crate::lang::commands::{Argument, Command};
use crate::lsystem::{DeriveOptions, LSystem, Timing};

mod develop;
mod mirror;
mod operators;
mod text;

use operators::*;
use text::*;

/// The limits and settings of the `lsystem-continuous` genome (a run's `config.toml`).
///
/// Operators keep every genome within them by construction. [`ContinuousLimits::check`]
/// reports limits that make no sense; operators given such limits use the nearest sensible
/// ones rather than panic.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ContinuousLimits {
    /// Most rules (one per maturing symbol; each is the template's pair of productions).
    /// Default 6: a few kinds of organ, as in Matos & Arita's evolved creature.
    pub max_rules: usize,
    /// Number of control tokens `A`, `B`, ... available to rules (at most 26). Default 3.
    pub control_tokens: usize,
    /// Most tokens in the axiom (brackets count). Default 12.
    pub max_axiom: usize,
    /// Most tokens in a rule's successor after the matured twin (brackets count). Default 12.
    pub max_successor: usize,
    /// Most maturing tokens (`mforward(0)`, `A(0)`, ...) in the axiom and in one successor:
    /// the branching factor of development. Default 2.
    pub max_growers: usize,
    /// Developmental time: the printed `time:` (development runs from 0 to it). Default 4.
    pub time: f64,
    /// Observation step: the printed `dt:`. Only the frames shown by `ontogeny grow` depend on
    /// it, not the creature (exact timing). Default 0.25.
    pub dt: f64,
    /// Smallest threshold; also the shortest `forward`. Default 0.2.
    pub min_threshold: f64,
    /// Largest threshold; also the longest `forward` (so a grown `mforward` is at most this
    /// long). Default 1.
    pub max_threshold: f64,
    /// Shortest time a maturing token takes to mature (threshold / rate): with `time` it bounds
    /// the number of generations, hence the work of development. Default 1.
    pub min_duration: f64,
    /// Longest time a random or mutated rule takes to mature. Default 3.
    pub max_duration: f64,
    /// More parts than this makes the creature invalid (`BuildOptions::max_parts`). Default 50.
    pub max_parts: usize,
    /// A string longer than this stops development with an error
    /// (`DeriveOptions::max_modules`); a safety net, far above what the other limits allow
    /// (about 2,000 modules). Default 5,000.
    pub max_modules: usize,
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
    /// The chance that operators make, change or remove an environment read (the `[ga]` key
    /// `environment_reads`, set by [`Genome::allow_environment_reads`]; not a key of the
    /// limits). 0, the default, draws exactly as a genome without reads always has.
    #[serde(skip)]
    pub environment_reads: f64,
    /// The projectile newborns carry when the run evolves it (set by
    /// [`Genome::evolve_projectile`]; not a key of the limits). None: no genome carries one.
    #[serde(skip)]
    pub projectile: Option<[f64; 3]>,
}

impl Default for ContinuousLimits {
    fn default() -> Self {
        ContinuousLimits {
            max_rules: 6,
            control_tokens: 3,
            max_axiom: 12,
            max_successor: 12,
            max_growers: 2,
            time: 4.0,
            dt: 0.25,
            min_threshold: 0.2,
            max_threshold: 1.0,
            min_duration: 1.0,
            max_duration: 3.0,
            max_parts: 50,
            max_modules: 5000,
            max_neurons: None,
            max_chain: None,
            environment_reads: 0.0,
            projectile: None,
        }
    }
}

impl ContinuousLimits {
    /// `Err` naming the first limit that makes no sense.
    pub fn check(&self) -> Result<(), String> {
        let pos = |v: f64| v.is_finite() && v > 0.0;
        if self.max_rules == 0 {
            return Err("max_rules must be at least 1".into());
        }
        if self.control_tokens > 26 {
            return Err("control_tokens must be at most 26 (A to Z)".into());
        }
        if self.max_axiom == 0 {
            return Err("max_axiom must be at least 1".into());
        }
        if !pos(self.time) || !pos(self.dt) {
            return Err("time and dt must be positive and finite".into());
        }
        if !pos(self.min_threshold)
            || self.max_threshold.is_nan()
            || self.max_threshold < self.min_threshold
        {
            return Err("thresholds need 0 < min_threshold <= max_threshold".into());
        }
        if !self.max_threshold.is_finite() {
            return Err("max_threshold must be finite".into());
        }
        if !pos(self.min_duration)
            || self.max_duration.is_nan()
            || self.max_duration < self.min_duration
            || !self.max_duration.is_finite()
        {
            return Err("durations need 0 < min_duration <= max_duration".into());
        }
        if self.max_parts < 2 {
            return Err("max_parts must be at least 2".into());
        }
        if self.max_modules < self.max_axiom {
            return Err("max_modules must be at least max_axiom".into());
        }
        Ok(())
    }

    /// The nearest sensible limits: these when [`check`](Self::check) passes.
    fn sane(&self) -> ContinuousLimits {
        let d = ContinuousLimits::default();
        let pos = |v: f64, default: f64| if v.is_finite() && v > 0.0 { v } else { default };
        let min_threshold = pos(self.min_threshold, d.min_threshold);
        let max_threshold = pos(self.max_threshold, d.max_threshold).max(min_threshold);
        let min_duration = pos(self.min_duration, d.min_duration);
        let max_duration = pos(self.max_duration, d.max_duration).max(min_duration);
        ContinuousLimits {
            max_rules: self.max_rules.max(1),
            control_tokens: self.control_tokens.min(26),
            max_axiom: self.max_axiom.max(1),
            max_successor: self.max_successor,
            max_growers: self.max_growers,
            time: pos(self.time, d.time),
            dt: pos(self.dt, d.dt),
            min_threshold,
            max_threshold,
            min_duration,
            max_duration,
            max_parts: self.max_parts.max(2),
            max_modules: self.max_modules.max(self.max_axiom.max(1)),
            max_neurons: self.max_neurons,
            max_chain: self.max_chain,
            environment_reads: if self.environment_reads.is_finite() {
                self.environment_reads.clamp(0.0, 1.0)
            } else {
                0.0
            },
            projectile: self.projectile,
        }
    }

    /// Every maturing symbol these limits allow, in alphabetical order of their names (the
    /// order crossover cuts in).
    pub fn growers(&self) -> Vec<Grower> {
        let mut all: Vec<Grower> = (0..self.control_tokens.min(26) as u8)
            .map(Grower::Control)
            .chain(MATURING.iter().map(|&c| Grower::Maturing(c)))
            .collect();
        all.sort_by_key(|g| g.name());
        all
    }
}

/// The commands a genome uses (all but Hornby's `increase`/`decrease`, which `weight`
/// covers), with the weight of drawing each as a random token: body commands, joints and
/// `output` are favoured so that random creatures often have driven joints.
const CHOICES: [(Command, f64); 28] = [
    (Command::Forward, 5.0),
    (Command::Backward, 0.3),
    (Command::Left, 1.0),
    (Command::Right, 1.0),
    (Command::Up, 0.7),
    (Command::Down, 0.7),
    (Command::Clockwise, 0.4),
    (Command::Counterclockwise, 0.4),
    (Command::Revolute1, 1.0),
    (Command::Revolute2, 2.0),
    (Command::Twist90, 1.0),
    (Command::Twist180, 1.0),
    (Command::Width, 0.4),
    (Command::Thickness, 0.4),
    (Command::Split, 0.8),
    (Command::Duplicate, 0.3),
    (Command::Loop, 0.3),
    (Command::Merge, 0.2),
    (Command::Next, 0.2),
    (Command::Parent, 0.2),
    (Command::Output, 4.0),
    (Command::Reverse, 0.2),
    (Command::Setfunc, 0.3),
    (Command::Bias, 0.3),
    (Command::Cut, 0.1),
    (Command::Weight, 0.4),
    (Command::Touch, 0.4),
    (Command::Angle, 0.4),
];

/// The commands a genome with an environment may also use: the `chem` sensor and the
/// `secrete` effector neurons, which read and write the chemical array. Operators draw them
/// only when environment reads are allowed, with these weights.
pub const ENVIRONMENT_CHOICES: [(Command, f64); 2] =
    [(Command::Chem, 1.0), (Command::Secrete, 1.0)];

/// The commands whose maturing twins (`mforward`, `mleft`, ..., `mrevolute1`, ...) can be
/// maturing symbols.
pub const MATURING: [Command; Command::GROWING.len()] = Command::GROWING;

/// The command a name stands for, among those this genome uses.
fn command_named(name: &str) -> Option<Command> {
    Command::from_name(name).filter(|c| {
        CHOICES
            .iter()
            .chain(&ENVIRONMENT_CHOICES)
            .any(|&(d, _)| d == *c)
    })
}

/// Whether a command reads or writes the chemical array (its parameter is a slot).
fn is_environment_command(c: Command) -> bool {
    ENVIRONMENT_CHOICES.iter().any(|&(d, _)| d == c)
}

/// A maturing symbol: the predecessor of a rule, and a token born at 0 in an axiom or
/// successor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Grower {
    /// A control token: 0 is `A`, 1 is `B`, ... It builds nothing and has no matured twin.
    Control(u8),
    /// The maturing twin of a command (`mforward` for `Forward`), which builds what the
    /// command builds, marked as growing.
    Maturing(Command),
}

impl Grower {
    /// Its name in a module string (`A`, `mforward`).
    pub fn name(self) -> String {
        match self {
            Grower::Control(i) => ((b'A' + i.min(25)) as char).to_string(),
            Grower::Maturing(c) => format!("m{}", c.name()),
        }
    }

    /// The symbol a name stands for, if the limits allow it.
    fn from_name(name: &str, limits: &ContinuousLimits) -> Option<Grower> {
        limits.growers().into_iter().find(|g| g.name() == name)
    }

    /// The weight of choosing it for a random rule: `mforward` (limbs that lengthen) and the
    /// control tokens are favoured.
    fn weight(self) -> f64 {
        match self {
            Grower::Control(_) => 1.5,
            Grower::Maturing(Command::Forward) => 4.0,
            Grower::Maturing(_) => 0.3,
        }
    }
}

/// One token of an axiom or successor.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Token {
    /// `[`
    Push,
    /// `]`
    Pop,
    /// A stable command and its parameter (`None` for commands without one).
    Command(Command, Option<f64>),
    /// A maturing token, born at 0: `mforward(0)`, `A(0)`.
    Grower(Grower),
}

impl Token {
    fn text(&self) -> String {
        match self {
            Token::Push => "[".into(),
            Token::Pop => "]".into(),
            Token::Command(c, Some(v)) => format!("{}({v})", c.name()),
            Token::Command(c, None) => c.name().into(),
            Token::Grower(g) => format!("{}(0)", g.name()),
        }
    }

    fn is_grower(&self) -> bool {
        matches!(self, Token::Grower(_))
    }

    fn is_bracket(&self) -> bool {
        matches!(self, Token::Push | Token::Pop)
    }
}

/// One rule: the template's two productions for one maturing symbol.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rule {
    /// The maturing symbol it rewrites.
    pub grower: Grower,
    /// The parameter grows while below this, and matures on reaching it.
    pub threshold: f64,
    /// The growth rate: `solve dx/dt = rate` (linear growth).
    pub rate: f64,
    /// The tokens after the matured twin (`forward(x)` for `mforward`; none for a control
    /// token).
    pub successor: Vec<Token>,
    /// A plastic rule's other branch: where the chemical it reads is high when the token
    /// matures, the token matures into its twin and this branch's successor instead.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plastic: Option<Plastic>,
}

/// The branch of a plastic rule. The genome's text writes the read `?E(1, slot, 0)` right
/// before every maturing token of the rule's symbol, and the branch as a rule whose left
/// context is that read:
///
/// ```text
/// ?E(1, 0, c) < mforward(x) : x >= 0.8 && c > 0.5 --> forward(x) [ left(1) mforward(0) ]
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Plastic {
    /// The slot of the chemical array read.
    pub slot: usize,
    /// The branch is taken where the value read is above this.
    pub above: f64,
    /// The tokens after the matured twin on this branch.
    pub successor: Vec<Token>,
}

/// A genome of the `lsystem-continuous` encoding: an axiom and template rules, sorted by the
/// name of their maturing symbol, at most one rule per symbol.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContinuousGenome {
    /// Developmental time (the printed `time:`).
    pub time: f64,
    /// Observation step (the printed `dt:`).
    pub dt: f64,
    /// The starting string.
    pub axiom: Vec<Token>,
    /// The rules.
    pub rules: Vec<Rule>,
    /// The chemical array's initial values (the printed `environment:`); empty when the
    /// genome has none. Its length is the array's size.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub environment: Vec<f64>,
    /// The edge lengths (m) of the projectile it throws, when its run evolves the projectile
    /// (the printed `# projectile:` line; see [`Genome::evolve_projectile`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub projectile: Option<[f64; 3]>,
}

/// Most frames (time / dt) a genome may show: each costs a restart of the ODE solver.
const MAX_FRAMES: f64 = 1000.0;

/// Values are kept on a grid of 0.01 so that printed genomes stay readable.
const GRID: f64 = 100.0;

// ---- the genome ----------------------------------------------------------------------

impl ContinuousGenome {
    /// `Err` naming the first way the genome exceeds `limits` (or is malformed: unbalanced
    /// brackets, rules out of order, a parameter outside its range, ...).
    pub fn check_limits(&self, limits: &ContinuousLimits) -> Result<(), String> {
        super::projectile::check(self.projectile)?;
        if !(self.time > 0.0 && self.time <= limits.time) {
            return Err(format!(
                "its time, {}, is not in (0, {}] (the limit 'time')",
                self.time, limits.time
            ));
        }
        if !(self.dt.is_finite() && self.dt > 0.0 && self.time / self.dt <= MAX_FRAMES) {
            return Err(format!(
                "its dt, {}, is not positive or makes more than {MAX_FRAMES} frames",
                self.dt
            ));
        }
        if self.axiom.is_empty() {
            return Err("its axiom is empty".into());
        }
        super::check_environment_values(&self.environment)?;
        let slots = self.environment.len();
        check_sequence("the axiom", &self.axiom, limits.max_axiom, slots, limits)?;
        if self.rules.len() > limits.max_rules {
            return Err(format!(
                "it has {} rules, more than max_rules = {}",
                self.rules.len(),
                limits.max_rules
            ));
        }
        for pair in self.rules.windows(2) {
            if pair[0].grower.name() >= pair[1].grower.name() {
                return Err(format!(
                    "its rules are not in alphabetical order, one per symbol ({} before {})",
                    pair[0].grower.name(),
                    pair[1].grower.name()
                ));
            }
        }
        for rule in &self.rules {
            let name = rule.grower.name();
            check_grower(rule.grower, limits)?;
            let t = rule.threshold;
            if !(t >= limits.min_threshold && t <= limits.max_threshold) {
                return Err(format!(
                    "the rule for {name} has threshold {t}, outside [{}, {}]",
                    limits.min_threshold, limits.max_threshold
                ));
            }
            if !(rule.rate > 0.0 && t / rule.rate >= limits.min_duration * (1.0 - 1e-12)) {
                return Err(format!(
                    "the rule for {name} has rate {}: it must be positive and take at least \
                     min_duration = {} to reach its threshold",
                    rule.rate, limits.min_duration
                ));
            }
            check_sequence(
                &format!("the successor of {name}"),
                &rule.successor,
                limits.max_successor,
                slots,
                limits,
            )?;
            if let Some(branch) = &rule.plastic {
                if branch.slot >= slots {
                    return Err(format!(
                        "the rule for {name} reads slot {} of an environment of {slots} slot(s)",
                        branch.slot
                    ));
                }
                if !branch.above.is_finite() {
                    return Err(format!(
                        "the rule for {name} compares the value read with {}, not a finite \
                         number",
                        branch.above
                    ));
                }
                check_sequence(
                    &format!("the plastic successor of {name}"),
                    &branch.successor,
                    limits.max_successor,
                    slots,
                    limits,
                )?;
            }
        }
        Ok(())
    }

    /// The rule for a maturing symbol, if the genome has one.
    pub fn rule(&self, grower: Grower) -> Option<&Rule> {
        self.rules.iter().find(|r| r.grower == grower)
    }

    fn insert_rule(&mut self, rule: Rule) {
        let at = self
            .rules
            .partition_point(|r| r.grower.name() < rule.grower.name());
        self.rules.insert(at, rule);
    }
}

fn check_grower(g: Grower, limits: &ContinuousLimits) -> Result<(), String> {
    match g {
        Grower::Control(i) if usize::from(i) >= limits.control_tokens.min(26) => Err(format!(
            "control token {} is beyond the {} allowed (control_tokens)",
            g.name(),
            limits.control_tokens
        )),
        Grower::Maturing(c) if !MATURING.contains(&c) => Err(format!(
            "m{} is not a maturing symbol (they are the maturing twins of forward, the turns \
             and the joints, and the control tokens)",
            c.name()
        )),
        _ => Ok(()),
    }
}

fn check_sequence(
    what: &str,
    seq: &[Token],
    max_len: usize,
    slots: usize,
    limits: &ContinuousLimits,
) -> Result<(), String> {
    if seq.len() > max_len {
        return Err(format!(
            "{what} has {} tokens, more than the {max_len} allowed",
            seq.len()
        ));
    }
    let growers = seq.iter().filter(|t| t.is_grower()).count();
    if growers > limits.max_growers {
        return Err(format!(
            "{what} has {growers} maturing tokens, more than max_growers = {}",
            limits.max_growers
        ));
    }
    let mut depth = 0usize;
    for t in seq {
        match t {
            Token::Push => depth += 1,
            Token::Pop => {
                depth = depth
                    .checked_sub(1)
                    .ok_or_else(|| format!("{what} has a ']' without its '['"))?;
            }
            Token::Command(c, p) if is_environment_command(*c) => match p {
                Some(v) if *v >= 0.0 && v.fract() == 0.0 && *v < slots as f64 => {}
                _ if slots == 0 => {
                    return Err(format!(
                        "{what}: {} needs an environment ('environment:'), and the genome has \
                         none",
                        c.name()
                    ));
                }
                _ => {
                    return Err(format!(
                        "{what}: {} needs a slot of the environment, 0 to {}",
                        c.name(),
                        slots - 1
                    ));
                }
            },
            Token::Command(c, p) => {
                let kind = c.argument();
                match (kind, p) {
                    (Argument::None, None) => {}
                    (Argument::None, Some(_)) => {
                        return Err(format!("{what}: {} takes no parameter", c.name()));
                    }
                    (_, None) => {
                        return Err(format!("{what}: {} needs its parameter", c.name()));
                    }
                    (kind, Some(v)) => {
                        let (lo, hi) = range_of(kind, limits);
                        if !(*v >= lo && *v <= hi) || (integral(kind) && v.fract() != 0.0) {
                            return Err(format!(
                                "{what}: {}({v}) is outside its range, {}[{lo}, {hi}]",
                                c.name(),
                                if integral(kind) {
                                    "whole numbers in "
                                } else {
                                    ""
                                }
                            ));
                        }
                    }
                }
            }
            Token::Grower(g) => check_grower(*g, limits).map_err(|e| format!("{what}: {e}"))?,
        }
    }
    if depth != 0 {
        return Err(format!("{what} has a '[' without its ']'"));
    }
    Ok(())
}

impl ContinuousGenome {
    /// A sequence as text, with the read of a plastic rule right before each of its maturing
    /// tokens.
    fn sequence_text(&self, seq: &[Token]) -> String {
        let mut words = Vec::with_capacity(seq.len());
        for t in seq {
            if let Token::Grower(g) = t
                && let Some(branch) = self.rule(*g).and_then(|r| r.plastic.as_ref())
            {
                words.push(read_text(branch.slot));
            }
            words.push(t.text());
        }
        words.join(" ")
    }
}

impl ContinuousGenome {
    /// Where its text writes reads in `seq`: (index of the maturing token read for, slot),
    /// one before each maturing token whose rule is plastic.
    pub(super) fn reads_in(&self, seq: &[Token]) -> Vec<(usize, usize)> {
        seq.iter()
            .enumerate()
            .filter_map(|(i, t)| match t {
                Token::Grower(g) => self
                    .rule(*g)
                    .and_then(|r| r.plastic.as_ref())
                    .map(|b| (i, b.slot)),
                _ => None,
            })
            .collect()
    }

    /// The genome's environment reads for people (`ontogeny genome show`): a line per
    /// plastic rule saying which maturing token reads which slot, and what its rule branches
    /// on; then the `chem` and `secrete` neurons. Empty when it reads nothing.
    pub fn environment_reads(&self) -> Vec<String> {
        let mut lines = Vec::new();
        for rule in &self.rules {
            let Some(b) = &rule.plastic else { continue };
            let name = rule.grower.name();
            let count = std::iter::once(&self.axiom)
                .chain(self.rules.iter().flat_map(|r| {
                    std::iter::once(&r.successor).chain(r.plastic.iter().map(|b| &b.successor))
                }))
                .map(|seq| {
                    self.reads_in(seq)
                        .iter()
                        .filter(|(i, _)| seq[*i] == Token::Grower(rule.grower))
                        .count()
                })
                .sum::<usize>();
            lines.push(format!(
                "{name} reads slot {} ({count} read(s) written): on maturing, where the value \
                 read is above {}, it becomes {}; elsewhere {}",
                b.slot,
                b.above,
                self.matured_text(rule, &b.successor),
                self.matured_text(rule, &rule.successor),
            ));
        }
        let every = std::iter::once(&self.axiom).chain(self.rules.iter().flat_map(|r| {
            std::iter::once(&r.successor).chain(r.plastic.iter().map(|b| &b.successor))
        }));
        lines.extend(neurons_written(every.flatten().filter_map(|t| match t {
            Token::Command(c, Some(v)) if is_environment_command(*c) => Some((*c, *v)),
            _ => None,
        })));
        lines
    }

    /// What a rule's token matures into with `successor`: its twin and the tokens, as text.
    fn matured_text(&self, rule: &Rule, successor: &[Token]) -> String {
        let twin = match rule.grower {
            Grower::Control(_) => None,
            Grower::Maturing(c) if c.has_argument() => Some(format!("{}(x)", c.name())),
            Grower::Maturing(c) => Some(c.name().to_string()),
        };
        let tail = self.sequence_text(successor);
        match (twin, tail.is_empty()) {
            (Some(twin), true) => twin,
            (Some(twin), false) => format!("{twin} {tail}"),
            (None, true) => "nothing".into(),
            (None, false) => tail,
        }
    }
}

/// The read of `slot`, as a genome's text writes it before a maturing token.
fn read_text(slot: usize) -> String {
    format!("?E(1, {slot}, 0)")
}
impl Genome for ContinuousGenome {
    type Limits = ContinuousLimits;

    const NAME: &'static str = "lsystem-continuous";

    const DESCRIPTION: &'static str = "Matos & Arita's continuous (dL) L-system";

    fn random(limits: &ContinuousLimits, rng: &mut Rng) -> Self {
        ContinuousGenome::random_genome(limits, rng)
    }

    fn mutate(&self, limits: &ContinuousLimits, rate: f64, rng: &mut Rng) -> Self {
        self.mutant(limits, rate, rng)
    }

    fn crossover(&self, other: &Self, limits: &ContinuousLimits, rng: &mut Rng) -> Option<Self> {
        Some(self.child(other, limits, rng))
    }

    /// A part of `other`'s axiom or successors, half turned (`left(1) left(1)`), replaces a
    /// part of `self`'s (see `ContinuousGenome::mirrored_child`).
    fn mirroring_crossover(
        &self,
        other: &Self,
        limits: &ContinuousLimits,
        rng: &mut Rng,
    ) -> Option<Self> {
        self.mirrored_child(other, limits, rng)
    }

    fn allow_environment_reads(limits: &mut ContinuousLimits, probability: f64) {
        limits.environment_reads = probability;
    }

    fn evolve_projectile(limits: &mut ContinuousLimits, start: [f64; 3]) {
        limits.projectile = Some(start);
    }

    fn projectile(&self) -> Option<[f64; 3]> {
        self.projectile
    }

    fn develop(&self, limits: &ContinuousLimits, _seed: u64) -> Result<Creature, DevelopError> {
        self.creature(limits, None)
    }

    fn environment_values(&self) -> &[f64] {
        &self.environment
    }

    fn develop_in(
        &self,
        limits: &ContinuousLimits,
        _seed: u64,
        env: &Environment,
    ) -> Result<Creature, DevelopError> {
        self.creature(limits, array_read(&self.environment, env)?)
    }

    fn seedling(
        &self,
        limits: &ContinuousLimits,
        env: Option<&Environment>,
    ) -> Option<Result<crate::develop::Seedling, DevelopError>> {
        let env = match env {
            Some(env) => match array_read(&self.environment, env) {
                Ok(env) => env,
                Err(e) => return Some(Err(e)),
            },
            None => None,
        };
        Some(self.seedling_in(limits, env))
    }

    fn show(&self) -> String {
        grammar_shown_with_reads(&self.to_text(), &self.environment_reads())
    }

    fn to_text(&self) -> String {
        self.text()
    }

    fn from_lsys(text: &str, limits: &ContinuousLimits) -> Result<Self, DevelopError> {
        let lsys =
            LSystem::from_text("init.lsys", text).map_err(|d| DevelopError(d.to_string()))?;
        let projectile = super::projectile::read_line(text)?;
        let genome = from_file(&lsys, limits).map_err(|e| {
            DevelopError(format!(
                "this file does not fit the {} genome: {e}",
                Self::NAME
            ))
        })?;
        Ok(ContinuousGenome {
            projectile,
            ..genome
        })
    }
}

#[cfg(test)]
impl ContinuousGenome {
    /// For tests: a genome of `time` time units observed every unit, with no environment,
    /// whose axiom is a 0.5 m forward part followed by `growers`.
    fn on_a_forward_part(time: f64, growers: &[Grower], rules: Vec<Rule>) -> ContinuousGenome {
        let mut axiom = vec![Token::Command(Command::Forward, Some(0.5))];
        axiom.extend(growers.iter().map(|&g| Token::Grower(g)));
        ContinuousGenome {
            time,
            dt: 1.0,
            environment: Vec::new(),
            axiom,
            rules,
            projectile: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_read_from_config_fill_defaults_and_refuse_unknown_keys() {
        let l: ContinuousLimits = serde_json::from_str("{}").unwrap();
        assert_eq!(l, ContinuousLimits::default());
        let l: ContinuousLimits = serde_json::from_str(r#"{"max_rules": 2}"#).unwrap();
        assert_eq!((l.max_rules, l.max_axiom), (2, 12));
        let e = serde_json::from_str::<ContinuousLimits>(r#"{"max_rule": 2}"#).unwrap_err();
        assert!(e.to_string().contains("unknown field"), "{e}");
    }
}
