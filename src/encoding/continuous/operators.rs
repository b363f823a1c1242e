//! The continuous genome's operators: random genomes drawn within the limits, mutation of
//! sequences, thresholds and rates, and crossover of the rules cut at a maturing symbol.

use super::*;
use crate::encoding::draw::on_grid;

// ---- random draws --------------------------------------------------------------------

/// The largest grid value not above `v` (exact for values already on the grid).
pub(super) fn floor_grid(v: f64) -> f64 {
    let mut q = ((v * GRID) + 1e-9).floor() / GRID;
    if q > v {
        q = ((v * GRID).floor() - 1.0) / GRID;
    }
    q
}

/// A value drawn uniformly from `[lo, hi]` (both ends included; `lo` when the range is
/// empty), off the grid.
pub(super) fn uniform_inclusive(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    if hi > lo {
        rng.random_range(lo..=hi)
    } else {
        lo
    }
}

pub(super) fn chance(rng: &mut Rng, p: f64) -> bool {
    rng.random_bool(p.clamp(0.0, 1.0))
}

/// An index drawn with chances proportional to `weights` (not all zero).
pub(super) fn weighted(rng: &mut Rng, weights: &[f64]) -> usize {
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

pub(super) fn range_of(kind: Argument, limits: &ContinuousLimits) -> (f64, f64) {
    match kind {
        Argument::None => (0.0, 0.0),
        Argument::Length => (limits.min_threshold, limits.max_threshold),
        Argument::Size => (0.1, 1.0),
        Argument::Turn => (-1.0, 1.0),
        // The textbook's turns, which genomes do not write.
        Argument::Degrees => (-90.0, 90.0),
        Argument::Weight | Argument::Bias => (-2.0, 2.0),
        Argument::Index => (0.0, 3.0),
        Argument::Function => (0.0, 2.0),
    }
}

pub(super) fn integral(kind: Argument) -> bool {
    matches!(kind, Argument::Index | Argument::Function)
}

pub(super) fn random_param(
    kind: Argument,
    limits: &ContinuousLimits,
    rng: &mut Rng,
) -> Option<f64> {
    if kind == Argument::None {
        return None;
    }
    let (lo, hi) = range_of(kind, limits);
    let v = uniform_inclusive(rng, lo, hi);
    Some(if integral(kind) {
        v.round()
    } else {
        on_grid(v, GRID).clamp(lo, hi)
    })
}

/// A small change: ±1 for indices, else up to a quarter of the range (a triangular draw,
/// unlike the other genomes' steps in `encoding::draw`).
pub(super) fn perturb_triangular(
    v: f64,
    kind: Argument,
    limits: &ContinuousLimits,
    rng: &mut Rng,
) -> f64 {
    let (lo, hi) = range_of(kind, limits);
    if integral(kind) {
        let step = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
        return (v + step).clamp(lo, hi);
    }
    let spread = 0.25 * (hi - lo);
    let d = (rng.random_range(0.0..1.0) + rng.random_range(0.0..1.0) - 1.0) * spread;
    on_grid(v + d, GRID).clamp(lo, hi)
}

/// A rate that makes a threshold take between `min_duration` (never less) and `max_duration`
/// to reach, on the grid when it can be.
pub(super) fn fit_rate(rate: f64, threshold: f64, limits: &ContinuousLimits) -> f64 {
    let hi = threshold / limits.min_duration;
    let lo = threshold / limits.max_duration;
    let r = if rate.is_finite() { rate } else { lo };
    let q = floor_grid(r.clamp(lo, hi));
    if q > 0.0 && q <= hi { q } else { hi }
}

pub(super) fn random_rate(threshold: f64, limits: &ContinuousLimits, rng: &mut Rng) -> f64 {
    let duration = uniform_inclusive(rng, limits.min_duration, limits.max_duration);
    fit_rate(threshold / duration, threshold, limits)
}

pub(super) fn random_threshold(limits: &ContinuousLimits, rng: &mut Rng) -> f64 {
    random_param(Argument::Length, limits, rng).unwrap_or(limits.min_threshold)
}

/// A random maturing symbol: mostly (4 in 5) one the genome has a rule for, when it has any.
pub(super) fn random_grower(limits: &ContinuousLimits, active: &[Grower], rng: &mut Rng) -> Grower {
    if !active.is_empty() && rng.random_bool(0.8) {
        return active[rng.random_range(0..active.len())];
    }
    let all = limits.growers();
    let weights: Vec<f64> = all.iter().map(|g| g.weight()).collect();
    all[weighted(rng, &weights)]
}

/// A random non-bracket token; a maturing token only when `grower_ok`. Maturing tokens
/// together weigh as much as `forward`.
pub(super) fn random_token(
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
pub(super) fn random_joint(rng: &mut Rng) -> Token {
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
pub(super) fn random_turn(rng: &mut Rng) -> Token {
    let turns = [
        Command::Left,
        Command::Right,
        Command::Up,
        Command::Down,
        Command::Clockwise,
        Command::Counterclockwise,
    ];
    let c = turns[rng.random_range(0..turns.len())];
    Token::Command(c, Some(on_grid(rng.random_range(0.5..=1.0), GRID)))
}

/// A limb: a part (`forward(l)`, or the maturing token `part` born at 0), with, 7 times in
/// 10 when there is room, a joint command before it and an `output` driving that joint after
/// it. At most `room` tokens.
pub(super) fn limb(
    part: Token,
    room: usize,
    limits: &ContinuousLimits,
    rng: &mut Rng,
) -> Vec<Token> {
    if room >= 3 && rng.random_bool(0.7) {
        let output = Token::Command(Command::Output, random_param(Argument::Weight, limits, rng));
        vec![random_joint(rng), part, output]
    } else {
        vec![part]
    }
}

/// A maturing token; `mforward(0)` has a joint command before it 7 times in 10 (the output
/// that drives that joint comes at the start of `mforward`'s successor, see [`random_rule`]).
pub(super) fn grower_motif(
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
pub(super) fn random_motif(
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
pub(super) fn random_sequence(
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

/// Fills `tokens` up to `len` with random motifs at the top level, using at most `growers`
/// maturing tokens (it decreases as they are used).
fn fill_with_motifs(
    tokens: &mut Vec<Token>,
    len: usize,
    growers: &mut usize,
    limits: &ContinuousLimits,
    active: &[Grower],
    rng: &mut Rng,
) {
    let rest = len - tokens.len();
    tokens.extend(random_sequence(rest, rest, growers, 0, limits, active, rng));
}

/// A random rule for `grower`; `active` are the symbols the genome has rules for.
pub(super) fn random_rule(
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
    fill_with_motifs(&mut successor, len, &mut growers, limits, active, rng);
    Rule {
        grower,
        threshold,
        rate: random_rate(threshold, limits, rng),
        successor,
        plastic: None,
    }
}

/// A random axiom: a first part (`forward`), a maturing token one of the rules rewrites (when
/// the limits allow one), and random motifs, at most `max_axiom` tokens in all.
pub(super) fn random_axiom(
    limits: &ContinuousLimits,
    active: &[Grower],
    rng: &mut Rng,
) -> Vec<Token> {
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
    fill_with_motifs(&mut axiom, len, &mut growers, limits, active, rng);
    axiom
}

/// A random plastic branch for rule `i` of `genome` (which has an environment): a random
/// slot, a value on the grid of [0, 1], and the successor of a random rule for its symbol.
pub(super) fn random_branch(
    genome: &ContinuousGenome,
    i: usize,
    limits: &ContinuousLimits,
    active: &[Grower],
    rng: &mut Rng,
) -> Plastic {
    let slot = rng.random_range(0..genome.environment.len().max(1));
    let above = on_grid(rng.random_range(0.0..=1.0), GRID);
    let successor = random_rule(genome.rules[i].grower, limits, active, rng).successor;
    Plastic {
        slot,
        above,
        successor,
    }
}

/// A plastic branch's value changed a little (a triangular step of up to 0.25), kept in
/// [0, 1].
pub(super) fn perturb_above(v: f64, rng: &mut Rng) -> f64 {
    let d = (rng.random_range(0.0..1.0) + rng.random_range(0.0..1.0) - 1.0) * 0.25;
    on_grid(v + d, GRID).clamp(0.0, 1.0)
}

// ---- mutation ------------------------------------------------------------------------

/// The index of the bracket matching the one at `i` (scanning forward from a `[`, backward
/// from a `]`).
pub(super) fn matching_bracket(seq: &[Token], i: usize) -> Option<usize> {
    let forward = seq[i] == Token::Push;
    if !forward && seq[i] != Token::Pop {
        return None;
    }
    let (opens, closes) = if forward {
        (Token::Push, Token::Pop)
    } else {
        (Token::Pop, Token::Push)
    };
    let order: Box<dyn Iterator<Item = usize>> = if forward {
        Box::new(i..seq.len())
    } else {
        Box::new((0..=i).rev())
    };
    let mut depth = 0i64;
    for k in order {
        if seq[k] == opens {
            depth += 1;
        } else if seq[k] == closes {
            depth -= 1;
            if depth == 0 {
                return Some(k);
            }
        }
    }
    None
}

/// Mutates a sequence in place, keeping it balanced, between `min_len` and `max_len` tokens
/// long and with at most `max_growers` maturing tokens. Sites: every token (replaced by a
/// random one), every parameter (changed a little), one insertion and one deletion.
pub(super) fn mutate_sequence(
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
            *v = perturb_triangular(*v, c.argument(), limits, rng);
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

impl ContinuousGenome {
    /// A random genome within `limits` (always a rule for `mforward`).
    pub(super) fn random_genome(limits: &ContinuousLimits, rng: &mut Rng) -> Self {
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
            environment: Vec::new(),
            projectile: limits.projectile,
        };
        for &g in &active {
            genome.insert_rule(random_rule(g, &limits, &active, rng));
        }
        genome.axiom = random_axiom(&limits, &active, rng);
        if limits.environment_reads > 0.0 {
            if genome.environment.is_empty() {
                genome.environment = vec![0.0];
            }
            for i in 0..genome.rules.len() {
                if chance(rng, limits.environment_reads) {
                    genome.rules[i].plastic =
                        Some(random_branch(&genome, i, &limits, &active, rng));
                }
            }
            if chance(rng, limits.environment_reads) {
                genome.insert_neuron(&limits, rng);
            }
        }
        genome
    }

    /// Inserts a random `chem` or `secrete` neuron at a random place of a random sequence
    /// with room for it.
    fn insert_neuron(&mut self, limits: &ContinuousLimits, rng: &mut Rng) {
        let slots = self.environment.len();
        if slots == 0 {
            return;
        }
        let weights: Vec<f64> = ENVIRONMENT_CHOICES.iter().map(|&(_, w)| w).collect();
        let command = ENVIRONMENT_CHOICES[weighted(rng, &weights)].0;
        let token = Token::Command(command, Some(rng.random_range(0..slots) as f64));
        let mut places: Vec<&mut Vec<Token>> = Vec::new();
        if self.axiom.len() < limits.max_axiom {
            places.push(&mut self.axiom);
        }
        for rule in &mut self.rules {
            if rule.successor.len() < limits.max_successor {
                places.push(&mut rule.successor);
            }
            if let Some(b) = &mut rule.plastic
                && b.successor.len() < limits.max_successor
            {
                places.push(&mut b.successor);
            }
        }
        if places.is_empty() {
            return;
        }
        let k = rng.random_range(0..places.len());
        let seq = &mut places[k];
        let at = rng.random_range(0..=seq.len());
        seq.insert(at, token);
    }

    /// Removes a random `chem` or `secrete` neuron, if the genome has one (never the axiom's
    /// last token).
    fn remove_neuron(&mut self, rng: &mut Rng) -> bool {
        let is_neuron = |t: &Token| matches!(t, Token::Command(c, _) if is_environment_command(*c));
        let axiom_len = self.axiom.len();
        let mut sites: Vec<(usize, usize)> = Vec::new();
        let mut seqs: Vec<&mut Vec<Token>> = vec![&mut self.axiom];
        for rule in &mut self.rules {
            seqs.push(&mut rule.successor);
            if let Some(b) = &mut rule.plastic {
                seqs.push(&mut b.successor);
            }
        }
        for (k, seq) in seqs.iter().enumerate() {
            for (i, t) in seq.iter().enumerate() {
                if is_neuron(t) && !(k == 0 && axiom_len == 1) {
                    sites.push((k, i));
                }
            }
        }
        if sites.is_empty() {
            return false;
        }
        let (k, i) = sites[rng.random_range(0..sites.len())];
        seqs[k].remove(i);
        true
    }

    /// Keeps what reads and writes the environment within it (no random draws): slots past
    /// its end become its last; without an environment, plastic branches and the neurons
    /// that need one go.
    pub(super) fn fit_environment(&mut self, limits: &ContinuousLimits) {
        let slots = self.environment.len();
        let fit = |seq: &mut Vec<Token>| {
            if slots == 0 {
                seq.retain(|t| !matches!(t, Token::Command(c, _) if is_environment_command(*c)));
            }
            for t in seq.iter_mut() {
                if let Token::Command(c, Some(v)) = t
                    && is_environment_command(*c)
                {
                    *v = v.round().clamp(0.0, slots.saturating_sub(1) as f64);
                }
            }
        };
        fit(&mut self.axiom);
        if self.axiom.is_empty() {
            self.axiom
                .push(Token::Command(Command::Forward, Some(limits.min_threshold)));
        }
        for rule in &mut self.rules {
            fit(&mut rule.successor);
            if slots == 0 {
                rule.plastic = None;
            }
            if let Some(b) = &mut rule.plastic {
                b.slot = b.slot.min(slots - 1);
                fit(&mut b.successor);
            }
        }
    }

    /// Mutates the plastic branches (their slot, value and successor, each a site), and with
    /// chance `environment_reads` makes or removes one, and adds or removes a neuron that
    /// reads or writes the array. Draws nothing from a genome without reads when reads are
    /// not allowed.
    fn mutate_reads(
        &mut self,
        limits: &ContinuousLimits,
        active: &[Grower],
        rate: f64,
        rng: &mut Rng,
    ) {
        let slots = self.environment.len();
        for rule in &mut self.rules {
            let Some(b) = &mut rule.plastic else { continue };
            if chance(rng, rate) && slots > 1 {
                b.slot = rng.random_range(0..slots);
            }
            if chance(rng, rate) {
                b.above = perturb_above(b.above, rng);
            }
            mutate_sequence(
                &mut b.successor,
                0,
                limits.max_successor,
                limits,
                active,
                rate,
                rng,
            );
        }
        let p = limits.environment_reads;
        if p > 0.0 && !self.rules.is_empty() && chance(rng, p) {
            if self.environment.is_empty() {
                self.environment = vec![0.0];
            }
            let i = rng.random_range(0..self.rules.len());
            self.rules[i].plastic = match self.rules[i].plastic {
                Some(_) => None,
                None => Some(random_branch(self, i, limits, active, rng)),
            };
        }
        if p > 0.0 && chance(rng, p) {
            if self.environment.is_empty() {
                self.environment = vec![0.0];
            }
            if !(rng.random_bool(0.5) && self.remove_neuron(rng)) {
                self.insert_neuron(limits, rng);
            }
        }
    }

    /// A mutant: every mutation site changes with probability `rate`.
    pub(super) fn mutant(&self, limits: &ContinuousLimits, rate: f64, rng: &mut Rng) -> Self {
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
                rule.threshold = perturb_triangular(rule.threshold, Argument::Length, &limits, rng);
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
        g.mutate_reads(&limits, &active, rate, rng);
        g.fit_environment(&limits);
        // Last, so that a run whose projectile does not evolve draws as it always has.
        g.projectile = crate::encoding::projectile::mutated(
            g.projectile,
            limits.projectile,
            rate,
            crate::encoding::projectile::Step::Stepwise,
            rng,
        );
        g
    }

    /// A child: the rules of `self` before a random cut and those of `other` after it.
    pub(super) fn child(&self, other: &Self, limits: &ContinuousLimits, rng: &mut Rng) -> Self {
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
        if other.environment.len() > child.environment.len() {
            child.environment = other.environment.clone();
        }
        child.fit_environment(&limits);
        child
    }
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
    fn a_control_token_has_no_twin_and_may_vanish() {
        let g = ContinuousGenome::on_a_forward_part(
            2.0,
            &[Grower::Control(0)],
            vec![Rule {
                grower: Grower::Control(0),
                threshold: 0.5,
                rate: 0.5,
                successor: vec![],
                plastic: None,
            }],
        );
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
            plastic: None,
        };
        let mk = |t: f64| ContinuousGenome {
            time: 4.0,
            dt: 1.0,
            environment: Vec::new(),
            projectile: None,
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
