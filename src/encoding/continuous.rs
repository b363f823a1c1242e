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

use super::command::{Argument, Command};
use super::{DevelopError, Genome, Rng};
use crate::creature::Creature;
use crate::develop::BuildOptions;
use crate::lang::ast::{BinaryOp, Expr, ModuleCall, UnaryOp};
use crate::lsystem::{DeriveOptions, LSystem, Timing};

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

/// The commands whose maturing twins (`mforward`, `mleft`, ..., `mrevolute1`, ...) can be
/// maturing symbols.
pub const MATURING: [Command; 11] = [
    Command::Forward,
    Command::Left,
    Command::Right,
    Command::Up,
    Command::Down,
    Command::Clockwise,
    Command::Counterclockwise,
    Command::Revolute1,
    Command::Revolute2,
    Command::Twist90,
    Command::Twist180,
];

/// The command a name stands for, among those this genome uses.
fn command_named(name: &str) -> Option<Command> {
    Command::from_name(name).filter(|c| CHOICES.iter().any(|&(d, _)| d == *c))
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
}

// ---- random draws --------------------------------------------------------------------

/// Most frames (time / dt) a genome may show: each costs a restart of the ODE solver.
const MAX_FRAMES: f64 = 1000.0;

/// Values are kept on a grid of 0.01 so that printed genomes stay readable.
const GRID: f64 = 100.0;

fn round_grid(v: f64) -> f64 {
    (v * GRID).round() / GRID
}

/// The largest grid value not above `v` (exact for values already on the grid).
fn floor_grid(v: f64) -> f64 {
    let mut q = ((v * GRID) + 1e-9).floor() / GRID;
    if q > v {
        q = ((v * GRID).floor() - 1.0) / GRID;
    }
    q
}

fn uniform(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    if hi > lo {
        rng.random_range(lo..=hi)
    } else {
        lo
    }
}

fn chance(rng: &mut Rng, p: f64) -> bool {
    rng.random_bool(p.clamp(0.0, 1.0))
}

/// An index drawn with chances proportional to `weights` (not all zero).
fn weighted(rng: &mut Rng, weights: &[f64]) -> usize {
    let total: f64 = weights.iter().sum();
    let mut u = rng.random_range(0.0..total);
    for (i, &w) in weights.iter().enumerate() {
        if u < w {
            return i;
        }
        u -= w;
    }
    weights.len() - 1
}

fn range_of(kind: Argument, limits: &ContinuousLimits) -> (f64, f64) {
    match kind {
        Argument::None => (0.0, 0.0),
        Argument::Length => (limits.min_threshold, limits.max_threshold),
        Argument::Size => (0.1, 1.0),
        Argument::Turn => (-1.0, 1.0),
        Argument::Weight | Argument::Bias => (-2.0, 2.0),
        Argument::Index => (0.0, 3.0),
        Argument::Function => (0.0, 2.0),
    }
}

fn integral(kind: Argument) -> bool {
    matches!(kind, Argument::Index | Argument::Function)
}

fn random_param(kind: Argument, limits: &ContinuousLimits, rng: &mut Rng) -> Option<f64> {
    if kind == Argument::None {
        return None;
    }
    let (lo, hi) = range_of(kind, limits);
    let v = uniform(rng, lo, hi);
    Some(if integral(kind) {
        v.round()
    } else {
        round_grid(v).clamp(lo, hi)
    })
}

/// A small change: ±1 for indices, else up to a quarter of the range (a triangular draw).
fn perturb(v: f64, kind: Argument, limits: &ContinuousLimits, rng: &mut Rng) -> f64 {
    let (lo, hi) = range_of(kind, limits);
    if integral(kind) {
        let step = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
        return (v + step).clamp(lo, hi);
    }
    let spread = 0.25 * (hi - lo);
    let d = (rng.random_range(0.0..1.0) + rng.random_range(0.0..1.0) - 1.0) * spread;
    round_grid(v + d).clamp(lo, hi)
}

/// A rate that makes a threshold take between `min_duration` (never less) and `max_duration`
/// to reach, on the grid when it can be.
fn fit_rate(rate: f64, threshold: f64, limits: &ContinuousLimits) -> f64 {
    let hi = threshold / limits.min_duration;
    let lo = threshold / limits.max_duration;
    let r = if rate.is_finite() { rate } else { lo };
    let q = floor_grid(r.clamp(lo, hi));
    if q > 0.0 && q <= hi { q } else { hi }
}

fn random_rate(threshold: f64, limits: &ContinuousLimits, rng: &mut Rng) -> f64 {
    let duration = uniform(rng, limits.min_duration, limits.max_duration);
    fit_rate(threshold / duration, threshold, limits)
}

fn random_threshold(limits: &ContinuousLimits, rng: &mut Rng) -> f64 {
    random_param(Argument::Length, limits, rng).unwrap_or(limits.min_threshold)
}

/// A random maturing symbol: mostly (4 in 5) one the genome has a rule for, when it has any.
fn random_grower(limits: &ContinuousLimits, active: &[Grower], rng: &mut Rng) -> Grower {
    if !active.is_empty() && rng.random_bool(0.8) {
        return active[rng.random_range(0..active.len())];
    }
    let all = limits.growers();
    let weights: Vec<f64> = all.iter().map(|g| g.weight()).collect();
    all[weighted(rng, &weights)]
}

/// A random non-bracket token; a maturing token only when `grower_ok`. Maturing tokens
/// together weigh as much as `forward`.
fn random_token(
    limits: &ContinuousLimits,
    active: &[Grower],
    grower_ok: bool,
    rng: &mut Rng,
) -> Token {
    let mut weights: Vec<f64> = CHOICES.iter().map(|&(_, w)| w).collect();
    if grower_ok {
        weights.push(CHOICES[0].1);
    }
    let i = weighted(rng, &weights);
    if i < CHOICES.len() {
        let c = CHOICES[i].0;
        Token::Command(c, random_param(c.argument(), limits, rng))
    } else {
        Token::Grower(random_grower(limits, active, rng))
    }
}

/// A random joint command: `revolute2` (the freest) twice as often as each other one.
fn random_joint(rng: &mut Rng) -> Token {
    let joints = [
        (Command::Revolute1, 1.0),
        (Command::Revolute2, 2.0),
        (Command::Twist90, 1.0),
        (Command::Twist180, 1.0),
    ];
    let weights: Vec<f64> = joints.iter().map(|&(_, w)| w).collect();
    Token::Command(joints[weighted(rng, &weights)].0, None)
}

/// A random turn of 45° to 90° either way: smaller turns make branches that overlap.
fn random_turn(rng: &mut Rng) -> Token {
    let turns = [
        Command::Left,
        Command::Right,
        Command::Up,
        Command::Down,
        Command::Clockwise,
        Command::Counterclockwise,
    ];
    let c = turns[rng.random_range(0..turns.len())];
    Token::Command(c, Some(round_grid(rng.random_range(0.5..=1.0))))
}

/// A limb: a part (`forward(l)`, or the maturing token `part` born at 0), with, 7 times in
/// 10 when there is room, a joint command before it and an `output` driving that joint after
/// it. At most `room` tokens.
fn limb(part: Token, room: usize, limits: &ContinuousLimits, rng: &mut Rng) -> Vec<Token> {
    if room >= 3 && rng.random_bool(0.7) {
        let output = Token::Command(Command::Output, random_param(Argument::Weight, limits, rng));
        vec![random_joint(rng), part, output]
    } else {
        vec![part]
    }
}

/// A maturing token; `mforward(0)` has a joint command before it 7 times in 10 (the output
/// that drives that joint comes at the start of `mforward`'s successor, see [`random_rule`]).
fn grower_motif(
    limits: &ContinuousLimits,
    active: &[Grower],
    room: usize,
    rng: &mut Rng,
) -> Vec<Token> {
    match random_grower(limits, active, rng) {
        g @ Grower::Maturing(Command::Forward) if room >= 2 && rng.random_bool(0.7) => {
            vec![random_joint(rng), Token::Grower(g)]
        }
        g => vec![Token::Grower(g)],
    }
}

/// A random motif of at most `room` (≥ 1) tokens: a limb (4), a limb that grows (3, while
/// `growers` allows a maturing token), a branch `[ turn ... ]` (2), a turn (1) or any single
/// token (2). Branches nest at most 3 deep.
fn random_motif(
    limits: &ContinuousLimits,
    active: &[Grower],
    growers: &mut usize,
    room: usize,
    depth: usize,
    rng: &mut Rng,
) -> Vec<Token> {
    let can_grow = *growers > 0;
    let can_branch = room >= 4 && depth < 3;
    let weights = [
        4.0,
        if can_grow { 3.0 } else { 0.0 },
        if can_branch { 2.0 } else { 0.0 },
        1.0,
        2.0,
    ];
    match weighted(rng, &weights) {
        0 => {
            let part = Token::Command(
                Command::Forward,
                random_param(Argument::Length, limits, rng),
            );
            limb(part, room, limits, rng)
        }
        1 => {
            *growers -= 1;
            grower_motif(limits, active, room, rng)
        }
        2 => {
            let inner_len = rng.random_range(2..=(room - 2).min(6));
            let mut v = vec![Token::Push, random_turn(rng)];
            let inner = random_sequence(
                inner_len - 1,
                inner_len - 1,
                growers,
                depth + 1,
                limits,
                active,
                rng,
            );
            v.extend(inner);
            v.push(Token::Pop);
            v
        }
        3 => vec![random_turn(rng)],
        _ => {
            let t = random_token(limits, active, can_grow, rng);
            if t.is_grower() {
                *growers -= 1;
            }
            vec![t]
        }
    }
}

/// A random balanced sequence of `min_len` to `max_len` tokens made of motifs, with at most
/// `growers` maturing tokens (it decreases as they are used).
fn random_sequence(
    min_len: usize,
    max_len: usize,
    growers: &mut usize,
    depth: usize,
    limits: &ContinuousLimits,
    active: &[Grower],
    rng: &mut Rng,
) -> Vec<Token> {
    let len = if max_len > min_len {
        rng.random_range(min_len..=max_len)
    } else {
        max_len
    };
    let mut out = Vec::with_capacity(len);
    while out.len() < len {
        let room = len - out.len();
        out.extend(random_motif(limits, active, growers, room, depth, rng));
    }
    out
}

/// A random rule for `grower`; `active` are the symbols the genome has rules for.
fn random_rule(
    grower: Grower,
    limits: &ContinuousLimits,
    active: &[Grower],
    rng: &mut Rng,
) -> Rule {
    let threshold = random_threshold(limits, rng);
    let mut growers = limits.max_growers;
    let max = limits.max_successor.min(8);
    let forward = grower == Grower::Maturing(Command::Forward);
    let len = rng.random_range(usize::from(forward).min(max)..=max);
    // A grown limb drives the joint it was born with, 9 times in 10.
    let mut successor = Vec::with_capacity(len);
    if forward && len > 0 && rng.random_bool(0.9) {
        successor.push(Token::Command(
            Command::Output,
            random_param(Argument::Weight, limits, rng),
        ));
    }
    let rest = len - successor.len();
    successor.extend(random_sequence(
        rest,
        rest,
        &mut growers,
        0,
        limits,
        active,
        rng,
    ));
    Rule {
        grower,
        threshold,
        rate: random_rate(threshold, limits, rng),
        successor,
    }
}

/// A random axiom: a first part (`forward`), a maturing token one of the rules rewrites (when
/// the limits allow one), and random motifs, at most `max_axiom` tokens in all.
fn random_axiom(limits: &ContinuousLimits, active: &[Grower], rng: &mut Rng) -> Vec<Token> {
    let max = limits.max_axiom;
    let len = rng.random_range(max.min(3)..=max.min(8));
    let mut axiom = vec![Token::Command(
        Command::Forward,
        random_param(Argument::Length, limits, rng),
    )];
    let mut growers = limits.max_growers;
    if growers > 0 && axiom.len() < len && !active.is_empty() {
        growers -= 1;
        let room = len - axiom.len();
        axiom.extend(grower_motif(limits, active, room, rng));
    }
    let rest = len - axiom.len();
    axiom.extend(random_sequence(
        rest,
        rest,
        &mut growers,
        0,
        limits,
        active,
        rng,
    ));
    axiom
}

// ---- mutation ------------------------------------------------------------------------

/// The index of the bracket matching the one at `i`.
fn matching_bracket(seq: &[Token], i: usize) -> Option<usize> {
    let mut depth = 0i64;
    if seq[i] == Token::Push {
        for (k, t) in seq.iter().enumerate().skip(i) {
            match t {
                Token::Push => depth += 1,
                Token::Pop => {
                    depth -= 1;
                    if depth == 0 {
                        return Some(k);
                    }
                }
                _ => {}
            }
        }
    } else if seq[i] == Token::Pop {
        for k in (0..=i).rev() {
            match seq[k] {
                Token::Pop => depth += 1,
                Token::Push => {
                    depth -= 1;
                    if depth == 0 {
                        return Some(k);
                    }
                }
                _ => {}
            }
        }
    }
    None
}

/// Mutates a sequence in place, keeping it balanced, between `min_len` and `max_len` tokens
/// long and with at most `max_growers` maturing tokens. Sites: every token (replaced by a
/// random one), every parameter (changed a little), one insertion and one deletion.
fn mutate_sequence(
    seq: &mut Vec<Token>,
    min_len: usize,
    max_len: usize,
    limits: &ContinuousLimits,
    active: &[Grower],
    rate: f64,
    rng: &mut Rng,
) {
    let count = |s: &[Token]| s.iter().filter(|t| t.is_grower()).count();
    for i in 0..seq.len() {
        if seq[i].is_bracket() {
            continue;
        }
        if chance(rng, rate) {
            let others = count(seq) - usize::from(seq[i].is_grower());
            seq[i] = random_token(limits, active, others < limits.max_growers, rng);
        }
        if let Token::Command(c, Some(v)) = &mut seq[i]
            && chance(rng, rate)
        {
            *v = perturb(*v, c.argument(), limits, rng);
        }
    }
    if seq.len() < max_len && chance(rng, rate) {
        let at = rng.random_range(0..=seq.len());
        let token = random_token(limits, active, count(seq) < limits.max_growers, rng);
        if seq.len() + 3 <= max_len && rng.random_bool(0.25) {
            seq.splice(at..at, [Token::Push, token, Token::Pop]);
        } else {
            seq.insert(at, token);
        }
    }
    if seq.len() > min_len && chance(rng, rate) {
        let at = rng.random_range(0..seq.len());
        match matching_bracket(seq, at) {
            Some(other) if seq.len() >= min_len + 2 => {
                let (a, b) = (at.min(other), at.max(other));
                seq.remove(b);
                seq.remove(a);
            }
            Some(_) => {}
            None => {
                seq.remove(at);
            }
        }
    }
}

// ---- the genome ----------------------------------------------------------------------

impl ContinuousGenome {
    /// `Err` naming the first way the genome exceeds `limits` (or is malformed: unbalanced
    /// brackets, rules out of order, a parameter outside its range, ...).
    pub fn check_limits(&self, limits: &ContinuousLimits) -> Result<(), String> {
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
        check_sequence("the axiom", &self.axiom, limits.max_axiom, limits)?;
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
                limits,
            )?;
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

fn sequence_text(seq: &[Token]) -> String {
    seq.iter().map(Token::text).collect::<Vec<_>>().join(" ")
}

impl Genome for ContinuousGenome {
    type Limits = ContinuousLimits;

    const NAME: &'static str = "lsystem-continuous";

    fn random(limits: &ContinuousLimits, rng: &mut Rng) -> Self {
        let limits = limits.sane();
        // Always a rule for mforward (limbs that lengthen, Figure 2), and others at random.
        let mut candidates = limits.growers();
        let n_rules = rng.random_range(1..=limits.max_rules.min(candidates.len()));
        let mut active = Vec::with_capacity(n_rules);
        let mforward = Grower::Maturing(Command::Forward);
        candidates.retain(|&g| g != mforward);
        active.push(mforward);
        while active.len() < n_rules {
            let weights: Vec<f64> = candidates.iter().map(|g| g.weight()).collect();
            active.push(candidates.remove(weighted(rng, &weights)));
        }
        let mut genome = ContinuousGenome {
            time: limits.time,
            dt: limits.dt,
            axiom: Vec::new(),
            rules: Vec::new(),
        };
        for &g in &active {
            genome.insert_rule(random_rule(g, &limits, &active, rng));
        }
        genome.axiom = random_axiom(&limits, &active, rng);
        genome
    }

    fn mutate(&self, limits: &ContinuousLimits, rate: f64, rng: &mut Rng) -> Self {
        let limits = limits.sane();
        let rate = if rate.is_finite() { rate } else { 0.0 };
        let mut g = self.clone();
        let active: Vec<Grower> = g.rules.iter().map(|r| r.grower).collect();
        mutate_sequence(
            &mut g.axiom,
            1,
            limits.max_axiom,
            &limits,
            &active,
            rate,
            rng,
        );
        for rule in &mut g.rules {
            if chance(rng, rate) {
                rule.threshold = perturb(rule.threshold, Argument::Length, &limits, rng);
                rule.rate = fit_rate(rule.rate, rule.threshold, &limits);
            }
            if chance(rng, rate) {
                let (lo, hi) = (
                    rule.threshold / limits.max_duration,
                    rule.threshold / limits.min_duration,
                );
                let d = (rng.random_range(0.0..1.0) + rng.random_range(0.0..1.0) - 1.0)
                    * 0.25
                    * (hi - lo);
                rule.rate = fit_rate(rule.rate + d, rule.threshold, &limits);
            }
            mutate_sequence(
                &mut rule.successor,
                0,
                limits.max_successor,
                &limits,
                &active,
                rate,
                rng,
            );
        }
        if !g.rules.is_empty() && chance(rng, rate) {
            let at = rng.random_range(0..g.rules.len());
            g.rules.remove(at);
        }
        if g.rules.len() < limits.max_rules && chance(rng, rate) {
            let unused: Vec<Grower> = limits
                .growers()
                .into_iter()
                .filter(|x| g.rule(*x).is_none())
                .collect();
            if !unused.is_empty() {
                let weights: Vec<f64> = unused.iter().map(|x| x.weight()).collect();
                let grower = unused[weighted(rng, &weights)];
                g.insert_rule(random_rule(grower, &limits, &active, rng));
            }
        }
        g
    }

    fn crossover(&self, other: &Self, limits: &ContinuousLimits, rng: &mut Rng) -> Option<Self> {
        let limits = limits.sane();
        let alphabet = limits.growers();
        let cut = alphabet[rng.random_range(0..alphabet.len())].name();
        let mut child = self.clone();
        child.rules = self
            .rules
            .iter()
            .filter(|r| r.grower.name() < cut)
            .chain(other.rules.iter().filter(|r| r.grower.name() >= cut))
            .take(limits.max_rules)
            .cloned()
            .collect();
        Some(child)
    }

    fn develop(&self, limits: &ContinuousLimits, _seed: u64) -> Result<Creature, DevelopError> {
        let limits = limits.sane();
        // A genome from elsewhere (a store, a hand-edited file) may not fit: its time and
        // frames would be unbounded.
        self.check_limits(&limits)
            .map_err(|e| DevelopError(format!("the genome exceeds its limits: {e}")))?;
        let lsys = LSystem::from_text(Self::NAME, &self.to_text())
            .map_err(|d| DevelopError(d.to_string()))?;
        let options = DeriveOptions {
            max_modules: limits.max_modules,
            ..DeriveOptions::default()
        };
        let build_options = BuildOptions {
            max_parts: limits.max_parts,
            ..BuildOptions::default()
        };
        // What `develop::grow` does, building only the last frame.
        let mut last = None;
        lsys.for_each_frame(&options, None, |frame| {
            if frame.last {
                let shown = lsys.interpret(frame.string, frame.t, &options)?;
                last = Some(crate::develop::build(
                    &shown,
                    lsys.symbols(),
                    frame.env,
                    Some(frame.t),
                    &build_options,
                ));
            }
            Ok::<(), crate::lang::Diagnostic>(())
        })
        .map_err(|d| DevelopError(d.to_string()))?;
        last.ok_or_else(|| DevelopError("development showed no last frame".into()))
    }

    fn to_text(&self) -> String {
        let mut s = String::new();
        s.push_str("# An lsystem-continuous genome (Matos & Arita, section 3.2): every rule\n");
        s.push_str("# grows a maturing token linearly until its threshold, then matures it.\n");
        s.push_str(&format!("time: {}\n", self.time));
        s.push_str(&format!("dt: {}\n", self.dt));
        s.push_str("timing: exact\n");
        s.push_str(&format!("axiom: {}\n", sequence_text(&self.axiom)));
        for rule in &self.rules {
            let name = rule.grower.name();
            let t = rule.threshold;
            s.push('\n');
            s.push_str(&format!(
                "{name}(x) : x < {t} --> solve dx/dt = {}\n",
                rule.rate
            ));
            let twin = match rule.grower {
                Grower::Control(_) => None,
                Grower::Maturing(c) if c.has_argument() => Some(format!("{}(x)", c.name())),
                Grower::Maturing(c) => Some(c.name().to_string()),
            };
            let tail = sequence_text(&rule.successor);
            let successor = match (twin, tail.is_empty()) {
                (Some(twin), true) => twin,
                (Some(twin), false) => format!("{twin} {tail}"),
                (None, _) => tail,
            };
            let line = format!("{name}(x) : x >= {t} --> {successor}");
            s.push_str(line.trim_end());
            s.push('\n');
        }
        s
    }

    fn from_lsys(text: &str, limits: &ContinuousLimits) -> Result<Self, DevelopError> {
        let lsys =
            LSystem::from_text("init.lsys", text).map_err(|d| DevelopError(d.to_string()))?;
        from_file(&lsys, limits).map_err(|e| {
            DevelopError(format!(
                "this file does not fit the {} genome: {e}",
                Self::NAME
            ))
        })
    }
}

// ---- reading a hand-written file -----------------------------------------------------

/// A constant number written as such (`0.5`, `-1`).
fn number(e: &Expr) -> Option<f64> {
    match e {
        Expr::Number(v, _) => Some(*v),
        Expr::Unary {
            op: UnaryOp::Neg,
            operand,
            ..
        } => number(operand).map(|v| -v),
        _ => None,
    }
}

/// `name OP number`.
fn comparison(e: &Expr, want: BinaryOp, param: &str) -> Option<f64> {
    match e {
        Expr::Binary { op, lhs, rhs, .. } if *op == want => match lhs.as_ref() {
            Expr::Name(n, _) if n == param => number(rhs),
            _ => None,
        },
        _ => None,
    }
}

fn token_of(call: &ModuleCall, limits: &ContinuousLimits) -> Result<Token, String> {
    let name = call.name.as_str();
    match name {
        "[" | "]" if call.args.is_empty() => {
            return Ok(if name == "[" { Token::Push } else { Token::Pop });
        }
        _ => {}
    }
    if let Some(c) = command_named(name) {
        return match (c.has_argument(), call.args.as_slice()) {
            (false, []) => Ok(Token::Command(c, None)),
            (true, [arg]) => number(arg)
                .map(|v| Token::Command(c, Some(v)))
                .ok_or_else(|| format!("{name}'s parameter must be a number")),
            (true, _) => Err(format!("write {name} with one number, as {name}(1)")),
            (false, _) => Err(format!("{name} takes no parameter here")),
        };
    }
    if let Some(g) = Grower::from_name(name, limits) {
        return match call.args.as_slice() {
            [arg] if number(arg) == Some(0.0) => Ok(Token::Grower(g)),
            _ => Err(format!(
                "the maturing token {name} must be written {name}(0)"
            )),
        };
    }
    let controls = match limits.control_tokens.min(26) {
        0 => "no control tokens".to_string(),
        n => format!(
            "control tokens A to {}",
            Grower::Control(n as u8 - 1).name()
        ),
    };
    Err(format!(
        "'{name}' is not a token of the genome (the commands but chem, target, secrete, \
         release, increase and decrease; the maturing twins of forward, the turns and the \
         joints; {controls})"
    ))
}

fn from_file(lsys: &LSystem, limits: &ContinuousLimits) -> Result<ContinuousGenome, String> {
    let file = lsys.file();
    let Some(time) = lsys.time() else {
        return Err("it has no 'time:' (the genome develops in continuous time)".into());
    };
    if lsys.timing() != Timing::Exact {
        return Err("it uses 'timing: iterative'; the genome uses exact timing".into());
    }
    if file.environment.is_some() {
        return Err("it has an environment ('environment:'); the genome has none".into());
    }
    if !file.defines.is_empty() {
        return Err("it defines constants; write numbers instead".into());
    }
    if !file.ignore.is_empty() {
        return Err("it has an 'ignore:' line; the genome's rules use no context".into());
    }
    let axiom = file
        .axiom
        .as_ref()
        .map(|(calls, _)| calls.iter().map(|c| token_of(c, limits)).collect())
        .transpose()
        .map_err(|e| format!("in the axiom: {e}"))?
        .unwrap_or_default();
    let mut rules: Vec<Rule> = Vec::new();
    let mut done: Vec<String> = Vec::new();
    for rule in &file.rules {
        let name = rule.predecessor.name.clone();
        if done.contains(&name) {
            continue;
        }
        let line = format!("the rules for {name}");
        if rule.section != crate::lang::ast::Section::Productions {
            return Err("it has interpretation rules".into());
        }
        let Some(grower) = Grower::from_name(&name, limits) else {
            return Err(format!(
                "{name} is not a maturing symbol (the maturing twins of forward, the turns \
                 and the joints, and the control tokens A, B, ... that the limits allow)"
            ));
        };
        let pair: Vec<_> = file
            .rules
            .iter()
            .filter(|r| r.predecessor.name == name)
            .collect();
        let template = "they must be the template's two rules, \
                        'P(x) : x < T --> solve dx/dt = R' and 'P(x) : x >= T --> ...'";
        if pair.len() != 2 {
            return Err(format!("{line}: {template}"));
        }
        let mut grow = None;
        let mut mature = None;
        for r in pair {
            if !r.left.is_empty() || !r.right.is_empty() || r.probability.is_some() {
                return Err(format!("{line}: no context and no probabilities, please"));
            }
            let [(param, _)] = r.predecessor.params.as_slice() else {
                return Err(format!("{line}: {name} must have one parameter"));
            };
            let guard = r
                .guard
                .as_ref()
                .ok_or_else(|| format!("{line}: {template}"))?;
            match &r.solve {
                Some(ode) => {
                    let threshold = comparison(guard, BinaryOp::Lt, param)
                        .ok_or_else(|| format!("{line}: {template}"))?;
                    let rate = match ode.as_slice() {
                        [d] if d.param == *param => number(&d.rhs),
                        _ => None,
                    }
                    .ok_or_else(|| {
                        format!(
                            "{line}: the growth must be 'solve d{param}/dt = R' with a number R"
                        )
                    })?;
                    grow = Some((threshold, rate));
                }
                None => {
                    let threshold = comparison(guard, BinaryOp::Ge, param)
                        .ok_or_else(|| format!("{line}: {template}"))?;
                    let mut calls = r.successor.as_slice();
                    if let Grower::Maturing(c) = grower {
                        let twin_ok = calls.first().is_some_and(|first| {
                            first.name == c.name()
                                && match first.args.as_slice() {
                                    [] => !c.has_argument(),
                                    [Expr::Name(n, _)] => c.has_argument() && n == param,
                                    _ => false,
                                }
                        });
                        if !twin_ok {
                            let twin = if c.has_argument() {
                                format!("{}({param})", c.name())
                            } else {
                                c.name().to_string()
                            };
                            return Err(format!(
                                "{line}: the matured successor must start with the twin, {twin}"
                            ));
                        }
                        calls = &calls[1..];
                    }
                    let successor = calls
                        .iter()
                        .map(|c| token_of(c, limits))
                        .collect::<Result<Vec<_>, _>>()
                        .map_err(|e| format!("{line}: {e}"))?;
                    mature = Some((threshold, successor));
                }
            }
        }
        let (Some((t1, rate)), Some((t2, successor))) = (grow, mature) else {
            return Err(format!("{line}: {template}"));
        };
        if t1 != t2 {
            return Err(format!(
                "{line}: the two guards must use the same threshold ({t1} and {t2})"
            ));
        }
        rules.push(Rule {
            grower,
            threshold: t1,
            rate,
            successor,
        });
        done.push(name);
    }
    let mut genome = ContinuousGenome {
        time,
        dt: lsys.dt(),
        axiom,
        rules: Vec::new(),
    };
    for rule in rules {
        genome.insert_rule(rule);
    }
    genome.check_limits(limits)?;
    Ok(genome)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn rng(seed: u64) -> Rng {
        Rng::seed_from_u64(seed)
    }

    #[test]
    fn grid_floor_is_exact_on_grid_values_and_never_above() {
        assert_eq!(floor_grid(0.29), 0.29);
        assert_eq!(floor_grid(0.299), 0.29);
        assert_eq!(floor_grid(1.0), 1.0);
        for k in 0..1000 {
            let v = k as f64 / 997.0;
            assert!(floor_grid(v) <= v, "{v}");
            assert!(v - floor_grid(v) < 0.0100001, "{v}");
        }
    }

    #[test]
    fn fit_rate_never_matures_faster_than_min_duration() {
        let l = ContinuousLimits::default();
        // 0.8 with min_duration 1: at most 0.8 per time unit.
        assert_eq!(fit_rate(5.0, 0.8, &l), 0.8);
        // at least 0.8 / 3, floored to the grid below 0.8 / 3 = 0.2666 -> but within bounds
        let slow = fit_rate(0.0, 0.8, &l);
        assert!(slow > 0.0 && 0.8 / slow >= 1.0);
        assert_eq!(fit_rate(0.5, 0.8, &l), 0.5);
        // A threshold too small for the grid keeps the exact bound.
        let tiny = ContinuousLimits {
            min_duration: 1000.0,
            max_duration: 2000.0,
            ..l
        };
        assert_eq!(fit_rate(1.0, 0.5, &tiny), 0.5 / 1000.0);
    }

    #[test]
    fn the_printed_rule_is_the_papers_template() {
        let g = ContinuousGenome {
            time: 4.0,
            dt: 0.5,
            axiom: vec![Token::Grower(Grower::Maturing(Command::Forward))],
            rules: vec![Rule {
                grower: Grower::Maturing(Command::Forward),
                threshold: 2.0,
                rate: 1.0,
                successor: vec![
                    Token::Push,
                    Token::Command(Command::Right, Some(-1.0)),
                    Token::Grower(Grower::Maturing(Command::Forward)),
                ],
            }],
        };
        let text = g.to_text();
        assert!(text.contains("time: 4\ndt: 0.5\ntiming: exact\naxiom: mforward(0)\n"));
        assert!(text.contains("mforward(x) : x < 2 --> solve dx/dt = 1\n"));
        // Figure 2, with its unclosed push (allowed in a hand-written rule, not by the genome).
        assert!(text.contains("mforward(x) : x >= 2 --> forward(x) [ right(-1) mforward(0)\n"));
        assert!(g.check_limits(&ContinuousLimits::default()).is_err());
    }

    #[test]
    fn a_control_token_has_no_twin_and_may_vanish() {
        let g = ContinuousGenome {
            time: 2.0,
            dt: 1.0,
            axiom: vec![
                Token::Command(Command::Forward, Some(0.5)),
                Token::Grower(Grower::Control(0)),
            ],
            rules: vec![Rule {
                grower: Grower::Control(0),
                threshold: 0.5,
                rate: 0.5,
                successor: vec![],
            }],
        };
        let text = g.to_text();
        assert!(text.contains("A(x) : x >= 0.5 -->\n"), "{text}");
        // A(0) grows for one time unit, then is deleted: the string is forward(0.5) alone.
        let lsys = LSystem::from_text("t", &text).unwrap();
        let mut dev = lsys.development(&DeriveOptions::default()).unwrap();
        while dev.advance().unwrap() {}
        assert_eq!(lsys.display(dev.current()), "forward(0.5)");
    }

    #[test]
    fn mutation_and_crossover_keep_rules_sorted_and_unique() {
        let l = ContinuousLimits::default();
        let mut r = rng(3);
        let mut a = ContinuousGenome::random(&l, &mut r);
        let b = ContinuousGenome::random(&l, &mut r);
        for _ in 0..50 {
            a = a.mutate(&l, 0.3, &mut r);
            a = a.crossover(&b, &l, &mut r).unwrap();
            a.check_limits(&l).unwrap();
        }
    }

    #[test]
    fn crossover_takes_rules_before_the_cut_from_self_and_the_rest_from_other() {
        let l = ContinuousLimits::default();
        let rule = |g, t: f64| Rule {
            grower: g,
            threshold: t,
            rate: 0.1,
            successor: vec![],
        };
        let mk = |t: f64| ContinuousGenome {
            time: 4.0,
            dt: 1.0,
            axiom: vec![Token::Command(Command::Forward, Some(t))],
            rules: vec![
                rule(Grower::Control(0), t),
                rule(Grower::Maturing(Command::Forward), t),
                rule(Grower::Maturing(Command::Twist90), t),
            ],
        };
        let (a, b) = (mk(0.3), mk(0.6));
        let alphabet: Vec<String> = l.growers().iter().map(|g| g.name()).collect();
        assert_eq!(alphabet[0], "A");
        assert_eq!(alphabet[3], "mclockwise");
        let mut seen = std::collections::BTreeSet::new();
        let mut r = rng(11);
        for _ in 0..200 {
            let c = a.crossover(&b, &l, &mut r).unwrap();
            assert_eq!(c.axiom, a.axiom);
            let from: Vec<bool> = c.rules.iter().map(|x| x.threshold == 0.3).collect();
            assert_eq!(c.rules.len(), 3);
            // Once the child takes from `other`, it never goes back.
            assert!(from.windows(2).all(|w| w[0] || !w[1]), "{from:?}");
            seen.insert(from);
        }
        // Cuts at A, between A and mforward, between mforward and mtwist90, and after.
        assert_eq!(seen.len(), 4);
    }

    #[test]
    fn limits_read_from_config_fill_defaults_and_refuse_unknown_keys() {
        let l: ContinuousLimits = serde_json::from_str("{}").unwrap();
        assert_eq!(l, ContinuousLimits::default());
        let l: ContinuousLimits = serde_json::from_str(r#"{"max_rules": 2}"#).unwrap();
        assert_eq!((l.max_rules, l.max_axiom), (2, 12));
        let e = serde_json::from_str::<ContinuousLimits>(r#"{"max_rule": 2}"#).unwrap_err();
        assert!(e.to_string().contains("unknown field"), "{e}");
    }

    #[test]
    fn growth_doubles_once_per_min_duration_and_no_more() {
        // Two limbs that each branch into two every time unit (threshold 0.2, rate 0.2), over
        // 4 time units: generations born at t = 0, 1, 2, 3, 4 hold 2, 4, 8, 16, 32 tokens;
        // the first four matured into 30 parts, the last is just born.
        let mf = Grower::Maturing(Command::Forward);
        let g = ContinuousGenome {
            time: 4.0,
            dt: 1.0,
            axiom: vec![
                Token::Command(Command::Forward, Some(0.5)),
                Token::Grower(mf),
                Token::Grower(mf),
            ],
            rules: vec![Rule {
                grower: mf,
                threshold: 0.2,
                rate: 0.2,
                successor: vec![
                    Token::Push,
                    Token::Command(Command::Left, Some(1.0)),
                    Token::Grower(mf),
                    Token::Pop,
                    Token::Grower(mf),
                ],
            }],
        };
        let l = ContinuousLimits::default();
        g.check_limits(&l).unwrap();
        let lsys = LSystem::from_text("t", &g.to_text()).unwrap();
        let mut dev = lsys.development(&DeriveOptions::default()).unwrap();
        while dev.advance().unwrap() {}
        let s = lsys.display(dev.current());
        assert_eq!(s.matches("mforward").count(), 32, "{s}");
        assert_eq!(s.matches("forward").count() - 32, 31, "{s}");
        // A rate that would mature faster than min_duration is refused.
        let mut fast = g.clone();
        fast.rules[0].rate = 0.4;
        assert!(fast.check_limits(&l).unwrap_err().contains("min_duration"));
    }

    #[test]
    fn bad_limits_are_reported_and_operators_still_work() {
        let bad = ContinuousLimits {
            max_rules: 0,
            time: f64::NAN,
            min_threshold: -1.0,
            max_duration: 0.0,
            ..ContinuousLimits::default()
        };
        assert!(bad.check().is_err());
        assert!(ContinuousLimits::default().check().is_ok());
        let mut r = rng(1);
        let g = ContinuousGenome::random(&bad, &mut r);
        let _ = g.mutate(&bad, f64::NAN, &mut r).develop(&bad, 0);
        let _ = g.mutate(&bad, 7.0, &mut r);
    }
}
