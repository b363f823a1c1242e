//! Hornby & Pollack's non-generative baseline (2001, section "Generative vs non-generative
//! encodings"): one string of the same body and brain commands as the L-system genome's
//! successors, `[` `]` branches included, and no productions. What the builder reads is the
//! genome itself; nothing is rewritten.
//!
//! Its text form is an `.lsys` file with an axiom and nothing else, which `ontogeny grow` and
//! `ontogeny eval` accept, and [`DirectGenome::develop`] grows that text through the language
//! exactly as `grow` does. Its limits equal the L-system genome's ([`DirectLimits::default`]
//! is derived from [`LSystemLimits::default`]): at most as many modules as an L-system
//! genome's derived string may hold, and at most as many parts.
//!
//! Every operator keeps the genome within [`DirectLimits`] by construction and never retries
//! a draw.

use std::f64::consts::FRAC_PI_2;
use std::ops::Range;

use rand::RngExt;
use serde::{Deserialize, Serialize};

use super::draw::clamp_rate;
use super::lsystem::{
    Arg, Item, LSystemLimits, MAX_RUN, balance, is_balanced, last_frame, perturb_argument,
    pick_run, push_item_text, random_command, random_run,
};
use super::{DevelopError, Genome, Rng, Seed};
use crate::creature::Creature;
use crate::lang;
use crate::lang::commands::Command;
use crate::lsystem::{DeriveOptions, LSystem};

/// The limits of the direct genome: every operator keeps a genome within them. They are part
/// of a run's configuration (`config.toml`); unknown keys are refused.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DirectLimits {
    /// Most modules (commands and brackets) in the genome: the L-system genome's
    /// `max_modules`, the longest derived string it may build from. At least 1.
    pub max_modules: usize,
    /// A creature with more parts than this is invalid: the L-system genome's `max_parts`.
    pub max_parts: usize,
    /// Random genomes are 1 to this many modules long: the L-system genome's
    /// `max_successor`, so that a random direct genome is drawn exactly as one random
    /// L-system successor without calls (and as often a driven walker: 19.5% against 19.6%
    /// over 1000 seeds). At most `max_modules`.
    pub random_length: usize,
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
    /// The projectile newborns carry when the run evolves it (set by
    /// [`Genome::evolve_projectile`]; not a key of the limits). None: no genome carries one.
    #[serde(skip)]
    pub projectile: Option<[f64; 3]>,
}

impl Default for DirectLimits {
    fn default() -> Self {
        DirectLimits::from(&LSystemLimits::default())
    }
}

impl From<&LSystemLimits> for DirectLimits {
    /// The direct genome's limits that equal an L-system genome's.
    fn from(l: &LSystemLimits) -> Self {
        DirectLimits {
            max_modules: l.max_modules,
            max_parts: l.max_parts,
            random_length: l.max_successor,
            max_neurons: l.max_neurons,
            max_chain: l.max_chain,
            projectile: l.projectile,
        }
    }
}

impl DirectLimits {
    /// The most modules, at least 1 (a genome always has a module: an axiom is never empty).
    fn modules(&self) -> usize {
        self.max_modules.max(1)
    }

    /// The longest random genome: 1 to `max_modules`.
    fn random_modules(&self) -> usize {
        self.random_length.clamp(1, self.modules())
    }
}

/// The direct genome: a string of building commands and brackets, read by the builder as it
/// is.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DirectGenome {
    /// The modules: commands with constant arguments, `[` and `]` (never calls).
    pub modules: Vec<Item>,
    /// The edge lengths (m) of the projectile it throws, when its run evolves the projectile
    /// (the printed `# projectile:` line; see [`Genome::evolve_projectile`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub projectile: Option<[f64; 3]>,
}

/// How many insertion (and deletion) sites a string of `len` modules has: one per started
/// L-system successor's worth of modules (`max_successor` of the default limits), so that a
/// module is as likely to see a run inserted or deleted nearby as in an L-system successor.
fn run_sites(len: usize) -> usize {
    len.div_ceil(LSystemLimits::default().max_successor.max(1))
        .max(1)
}

impl DirectGenome {
    /// Whether the genome lies within `limits` and is well formed: 1 to `max_modules`
    /// modules, commands only with finite constant arguments where they take one, balanced
    /// brackets. `Err` says what is wrong.
    pub fn check(&self, limits: &DirectLimits) -> Result<(), String> {
        super::projectile::check(self.projectile)?;
        let n = self.modules.len();
        if n == 0 || n > limits.modules() {
            return Err(format!("{n} modules, not 1 to {}", limits.modules()));
        }
        for (k, item) in self.modules.iter().enumerate() {
            let ok = match item {
                Item::Push | Item::Pop | Item::Command(_, None) => true,
                Item::Command(c, Some(Arg::Const(v))) => c.has_argument() && v.is_finite(),
                Item::Command(_, Some(_))
                | Item::Call(..)
                | Item::RepeatOpen
                | Item::RepeatClose(_) => false,
            };
            if !ok {
                return Err(format!("module {k} is malformed: {item:?}"));
            }
        }
        if !is_balanced(&self.modules) {
            return Err("the brackets are not balanced".into());
        }
        Ok(())
    }

    /// Replaces each command (not a bracket), with probability `rate`, by a random command.
    pub fn replace_commands(&mut self, rate: f64, rng: &mut Rng) {
        let rate = clamp_rate(rate);
        for item in &mut self.modules {
            if rng.random_bool(rate) && !matches!(item, Item::Push | Item::Pop) {
                *item = random_command(rng);
            }
        }
    }

    /// Perturbs each argument, with probability `rate`, as the L-system genome does: up to a
    /// tenth of its range either way, staying in range and on its grid.
    pub fn perturb_arguments(&mut self, rate: f64, rng: &mut Rng) {
        let rate = clamp_rate(rate);
        for item in &mut self.modules {
            if rng.random_bool(rate)
                && let Item::Command(c, Some(arg)) = item
            {
                perturb_argument(*c, arg, rng);
            }
        }
    }

    /// At each insertion site (one per started 15 modules, the L-system genome's default
    /// `max_successor`), with probability `rate`, inserts a random run of 1 to 3 modules
    /// (fewer when `max_modules` leaves less room) at a random place.
    pub fn insert_runs(&mut self, limits: &DirectLimits, rate: f64, rng: &mut Rng) {
        let rate = clamp_rate(rate);
        for _ in 0..run_sites(self.modules.len()) {
            let room = limits.modules().saturating_sub(self.modules.len());
            if room > 0 && rng.random_bool(rate) {
                let len = rng.random_range(1..=room.min(MAX_RUN));
                let at = rng.random_range(0..=self.modules.len());
                self.modules
                    .splice(at..at, random_run(len, 0, 0, 0, 0, rng));
            }
        }
    }

    /// At each deletion site (one per started 15 modules), with probability `rate`, deletes
    /// a run of 1 to 3 modules at a random place, never the last module. Brackets left
    /// without a partner are dropped too; a deletion that would leave nothing is undone.
    pub fn delete_runs(&mut self, rate: f64, rng: &mut Rng) {
        let rate = clamp_rate(rate);
        for _ in 0..run_sites(self.modules.len()) {
            if self.modules.len() > 1 && rng.random_bool(rate) {
                let before = self.clone();
                let run = pick_run(&self.modules, (self.modules.len() - 1).min(MAX_RUN), rng);
                self.modules.drain(run);
                self.settle(&before);
            }
        }
    }

    /// One-point crossover: the first `cut` modules of `self`, then `other`'s from
    /// `other_cut` on (as many as `max_modules` leaves room for). Brackets left without a
    /// partner are dropped; a child left empty is a copy of `self`.
    pub fn one_point(
        &self,
        other: &DirectGenome,
        cut: usize,
        other_cut: usize,
        limits: &DirectLimits,
    ) -> DirectGenome {
        let cut = cut.min(self.modules.len());
        let other_cut = other_cut.min(other.modules.len());
        self.exchange(
            other,
            cut..self.modules.len(),
            other_cut..other.modules.len(),
            limits,
        )
    }

    /// Two-point crossover: `self` with its modules `cut` replaced by `other`'s modules
    /// `other_cut` (as many as `max_modules` leaves room for). Brackets left without a
    /// partner are dropped; a child left empty is a copy of `self`.
    pub fn two_point(
        &self,
        other: &DirectGenome,
        cut: Range<usize>,
        other_cut: Range<usize>,
        limits: &DirectLimits,
    ) -> DirectGenome {
        let fit = |r: Range<usize>, n: usize| r.start.min(n)..r.end.clamp(r.start.min(n), n);
        self.exchange(
            other,
            fit(cut, self.modules.len()),
            fit(other_cut, other.modules.len()),
            limits,
        )
    }

    /// `self` with `out` replaced by `other`'s `run`, cut to the room left.
    fn exchange(
        &self,
        other: &DirectGenome,
        out: Range<usize>,
        run: Range<usize>,
        limits: &DirectLimits,
    ) -> DirectGenome {
        let kept = self.modules.len() - out.len();
        let room = limits.modules().saturating_sub(kept);
        let end = run.end.min(run.start + room);
        let mut modules = self.modules.clone();
        modules.splice(out, other.modules[run.start..end].iter().cloned());
        let mut child = DirectGenome {
            modules,
            projectile: self.projectile,
        };
        child.settle(self);
        child
    }

    /// Balances the brackets; a string left empty becomes a copy of `fallback`.
    fn settle(&mut self, fallback: &DirectGenome) {
        balance(&mut self.modules);
        if self.modules.is_empty() {
            self.modules = fallback.modules.clone();
        }
    }
}

fn refuse(message: impl Into<String>) -> DevelopError {
    DevelopError(format!(
        "this file does not fit the direct genome: {}",
        message.into()
    ))
}

impl Genome for DirectGenome {
    type Limits = DirectLimits;

    const NAME: &'static str = "direct";

    const DESCRIPTION: &'static str =
        "Hornby & Pollack's non-generative baseline: one string of commands";

    fn random(limits: &DirectLimits, rng: &mut Rng) -> Self {
        let len = rng.random_range(1..=limits.random_modules());
        DirectGenome {
            modules: random_run(len, 0, 0, 0, 0, rng),
            projectile: limits.projectile,
        }
    }

    fn mutate(&self, limits: &DirectLimits, rate: f64, rng: &mut Rng) -> Self {
        let mut g = self.clone();
        g.replace_commands(rate, rng);
        g.perturb_arguments(rate, rng);
        g.insert_runs(limits, rate, rng);
        g.delete_runs(rate, rng);
        // Last, so that a run whose projectile does not evolve draws as it always has.
        g.projectile = super::projectile::mutated(
            g.projectile,
            limits.projectile,
            rate,
            super::projectile::Step::Stepwise,
            rng,
        );
        g
    }

    fn evolve_projectile(limits: &mut DirectLimits, start: [f64; 3]) {
        limits.projectile = Some(start);
    }

    fn projectile(&self) -> Option<[f64; 3]> {
        self.projectile
    }

    fn crossover(&self, other: &Self, limits: &DirectLimits, rng: &mut Rng) -> Option<Self> {
        let (n, m) = (self.modules.len(), other.modules.len());
        if rng.random_bool(0.5) {
            let cut = rng.random_range(0..=n);
            let other_cut = rng.random_range(0..=m);
            Some(self.one_point(other, cut, other_cut, limits))
        } else {
            let sorted = |a: usize, b: usize| a.min(b)..a.max(b);
            let cut = sorted(rng.random_range(0..=n), rng.random_range(0..=n));
            let other_cut = sorted(rng.random_range(0..=m), rng.random_range(0..=m));
            Some(self.two_point(other, cut, other_cut, limits))
        }
    }

    /// Walking with Dinosaurs' crossover: a part of `other` other than its root (a branch
    /// `[` ... `]`, or a tail: a part built after another, with what places it and what
    /// follows it), copied as a branch and half turned (`left(2)`; see `encoding::mirror`),
    /// replaces a part of `self` (or, when `self` has only its root, is inserted at a place
    /// of it), drawn among the pairs that keep `max_modules`. `None` when `other` has only
    /// its root or no copy fits.
    fn mirroring_crossover(
        &self,
        other: &Self,
        limits: &DirectLimits,
        rng: &mut Rng,
    ) -> Option<Self> {
        let fits = |copy: &[Item], site: &super::mirror::Site| {
            self.modules.len() - site.range.len() + copy.len() <= limits.modules()
        };
        let (copy, site) = super::mirror::copy_a_part(
            &[&other.modules],
            &[&self.modules],
            &super::lsystem::ITEMS,
            fits,
            rng,
        )?;
        let mut modules = self.modules.clone();
        modules.splice(site.range, copy);
        // The breeder's projectile, whole (Chaumont 4.1: one projectile only).
        Some(DirectGenome {
            modules,
            projectile: self.projectile,
        })
    }

    fn develop(&self, limits: &DirectLimits, seed: u64) -> Result<Creature, DevelopError> {
        if self.modules.is_empty() {
            return Err(DevelopError("the genome has no modules".into()));
        }
        super::lsystem::develop_text(
            &self.to_text(),
            limits.modules(),
            limits.max_parts,
            seed,
            None,
        )
        .map(|c| Creature {
            projectile: self.projectile,
            ..c
        })
    }

    fn to_text(&self) -> String {
        let mut out = format!(
            "# A direct genome (Hornby & Pollack 2001's non-generative encoding): {} module(s).\naxiom:",
            self.modules.len()
        );
        let line = super::projectile::text_line(self.projectile);
        if !line.is_empty() {
            // After the first line: the line names the genome, and stays first.
            let at = out.find('\n').map_or(0, |i| i + 1);
            out.insert_str(at, &line);
        }
        for item in &self.modules {
            out.push(' ');
            push_item_text(item, &mut out);
        }
        out.push('\n');
        out
    }

    fn from_lsys(text: &str, limits: &DirectLimits) -> Result<Self, DevelopError> {
        from_lsys("file.lsys", text, limits)
    }

    fn seed_from_lsys(
        name: &str,
        text: &str,
        limits: &DirectLimits,
    ) -> Result<Seed<Self>, DevelopError> {
        from_lsys(name, text, limits).map(|genome| Seed {
            genome,
            limits: limits.clone(),
            notes: Vec::new(),
        })
    }

    /// Its text form alone: an axiom has no rules to summarise.
    fn show(&self) -> String {
        self.to_text().trim_end().to_string()
    }

    /// Its text form is an axiom alone: a grammar with rules is some other file (which
    /// [`Genome::from_lsys`] would derive).
    fn read_text(text: &str, limits: &DirectLimits) -> Result<Self, DevelopError> {
        let lsys =
            LSystem::from_text("file.lsys", text).map_err(|d| DevelopError(d.to_string()))?;
        let report = lsys.check();
        if report.productions + report.interpretation_rules > 0 || lsys.is_continuous() {
            return Err(DevelopError(
                "a direct genome's file is an axiom alone, without rules".into(),
            ));
        }
        from_lsys("file.lsys", text, limits)
    }
}

/// Any grammar, derived as `ontogeny grow` derives it (its own derivation length or time,
/// seed and interpretation rules; `max_modules` caps the string), gives the direct genome of
/// its last string: commands and brackets in order, control symbols (which build nothing)
/// dropped.
fn from_lsys(name: &str, text: &str, limits: &DirectLimits) -> Result<DirectGenome, DevelopError> {
    let modules = derived_items(name, text, limits.modules())
        .map_err(|problems| refuse(problems.join("; ")))?;
    let genome = DirectGenome {
        modules,
        projectile: super::projectile::read_line(text)?,
    };
    genome.check(limits).map_err(refuse)?;
    Ok(genome)
}

/// A diagnostic's text without its notes that name a command-line flag: `evolve` and
/// `genome show`, which read grammars as genomes, have none of `grow`'s.
pub(crate) fn without_flags(mut d: lang::Diagnostic) -> String {
    d.notes.retain(|n| !n.contains("--"));
    d.to_string()
}

/// What a grammar may write that the genomes do not, for the messages that refuse it.
pub(crate) const NOT_USED: &str = "not used: repeat blocks, maturing m-commands but mforward, chem, secrete, \
     target, release; of the textbook's symbols f, a bare !, turns by other than a multiple of \
     90°, and heading: up";

/// What the L-system genome leaves out of the language: [`NOT_USED`] but repeat blocks,
/// which it writes.
pub(crate) const LSYSTEM_NOT_USED: &str = "not used: maturing m-commands but mforward, target, \
     release; of the textbook's symbols f, a bare !, turns by other than a multiple of 90°, and \
     heading: up";

/// The genome's items that build exactly what the textbook's command `c` with argument `arg`
/// builds under the file's `turtle` headers: `F(l)` is `forward(l)` (by default the file's
/// `step:`), `+(δ)` `-(δ)` `^(δ)` `&(δ)` `/(δ)` `\(δ)` with δ a multiple of 90° are `left`
/// `right` `up` `down` `clockwise` `counterclockwise` by δ/90 quarter turns (by default the
/// file's `angle:`), `|` is `left(2)`, `!(w)` is `width(w) thickness(w)`; `Err` says why there
/// are none.
pub(crate) fn textbook_items(
    c: Command,
    arg: Option<Arg>,
    turtle: &crate::lsystem::TurtleHeaders,
) -> Result<Vec<Item>, String> {
    let name = c.name();
    let quarter = |to: Command, default: f64| match arg.unwrap_or(Arg::Const(default)) {
        Arg::Const(d) if (d / 90.0).fract() == 0.0 && d.to_radians() == d / 90.0 * FRAC_PI_2 => {
            Ok(vec![Item::Command(to, Some(Arg::Const(d / 90.0)))])
        }
        Arg::Const(d) => Err(format!(
            "'{name}' turns by {d}°, not a multiple of 90°; the genome turns by quarter turns"
        )),
        _ => Err(format!(
            "'{name}' turns by a parameter's degrees; the genome turns by quarter turns"
        )),
    };
    let angle = turtle.angle.unwrap_or(crate::develop::DEFAULT_ANGLE);
    match c {
        Command::Segment => {
            let step = turtle
                .step
                .unwrap_or(crate::develop::BuildOptions::default().default_length);
            Ok(vec![Item::Command(
                Command::Forward,
                Some(arg.unwrap_or(Arg::Const(step))),
            )])
        }
        Command::TurnLeft => quarter(Command::Left, angle),
        Command::TurnRight => quarter(Command::Right, angle),
        Command::PitchUp => quarter(Command::Up, angle),
        Command::PitchDown => quarter(Command::Down, angle),
        Command::RollRight => quarter(Command::Clockwise, angle),
        Command::RollLeft => quarter(Command::Counterclockwise, angle),
        Command::TurnAround => Ok(vec![Item::Command(Command::Left, Some(Arg::Const(2.0)))]),
        Command::Diameter => match arg {
            Some(w) => Ok(vec![
                Item::Command(Command::Width, Some(w)),
                Item::Command(Command::Thickness, Some(w)),
            ]),
            None => Err(format!(
                "a bare '!' scales the width by {}; the genome sets widths, it does not scale them",
                crate::develop::DIAMETER_FACTOR
            )),
        },
        Command::Move => Err(
            "'f' moves without building and leaves a gap; the genome builds one body".to_string(),
        ),
        _ => Err(format!(
            "'{name}' is not a command the genome uses ({NOT_USED})"
        )),
    }
}

/// The building commands and brackets of the last string `text` derives (as `ontogeny grow`
/// derives it, `max_modules` capping the string), in order, control symbols dropped; `Err`
/// lists every reason they are not that (a module no genome builds with, named with where
/// the file writes it first; unbalanced brackets; no building command at all).
pub(crate) fn derived_items(
    name: &str,
    text: &str,
    max_modules: usize,
) -> Result<Vec<Item>, Vec<String>> {
    let lsys = LSystem::from_text(name, text).map_err(|d| vec![without_flags(d)])?;
    let source = lang::Source::new(name, text);
    let written = lang::parse(&source).ok();
    // Where the file writes module `name` first (line and column), if it does.
    let place = |name: &str| -> String {
        let file = written.as_ref();
        let calls = file
            .into_iter()
            .flat_map(|f| f.axiom.iter().flat_map(|(a, _)| a.iter()))
            .chain(
                file.into_iter()
                    .flat_map(|f| f.rules.iter().flat_map(|r| r.successor.iter())),
            );
        let mut first: Option<usize> = None;
        for call in calls.filter(|c| c.name == name) {
            first = Some(first.map_or(call.span.start, |f| f.min(call.span.start)));
        }
        match first {
            Some(at) => {
                let (line, column) = source.line_col(at);
                format!("line {line}, column {column}: ")
            }
            None => String::new(),
        }
    };
    let options = DeriveOptions {
        max_modules,
        ..DeriveOptions::default()
    };
    let turtle = lsys.turtle();
    let (modules, mut problems) = last_frame(&lsys, &options, |shown, _, _| {
        let symbols = lsys.symbols();
        let mut modules = Vec::new();
        let mut problems: Vec<String> = Vec::new();
        let mut said: Vec<String> = Vec::new();
        for (k, m) in shown.iter().enumerate() {
            let name = symbols.name(m.sym);
            let mut problem = |what: String| {
                if !said.iter().any(|s| s == name) {
                    said.push(name.to_string());
                    problems.push(format!(
                        "{}'{name}' (first at module {} of the derived string) {what}",
                        place(name),
                        k + 1
                    ));
                }
            };
            let textbook = Command::from_name(name).filter(|c| c.is_textbook());
            let item = match (name, Command::building_from_name(name)) {
                ("[", _) => Item::Push,
                ("]", _) => Item::Pop,
                (_, Some(c)) => match m.params {
                    [] => Item::Command(c, None),
                    [v] if c.has_argument() && v.is_finite() => {
                        Item::Command(c, Some(Arg::Const(*v)))
                    }
                    [v] if c.has_argument() => {
                        problem(format!("has the argument {v}"));
                        continue;
                    }
                    _ => {
                        problem(format!(
                            "has {} arguments; the genome's '{}' takes {}",
                            m.params.len(),
                            c.name(),
                            if c.has_argument() {
                                "at most one"
                            } else {
                                "none"
                            }
                        ));
                        continue;
                    }
                },
                // `mforward(x, ...)` builds what `forward(x)` builds (a part drawn growing; physics
                // does not tell them apart), or nothing while it is a bud.
                ("mforward", None) => match m.params.first() {
                    Some(v) if !v.is_finite() => {
                        problem(format!("has the argument {v}"));
                        continue;
                    }
                    Some(v) if v.abs() >= crate::develop::MIN_PART_LENGTH => {
                        Item::Command(Command::Forward, Some(Arg::Const(*v)))
                    }
                    _ => continue,
                },
                (_, None) if textbook.is_some() => {
                    let Some(c) = textbook else { continue };
                    if let Some(v) = m.params.iter().find(|v| !v.is_finite()) {
                        problem(format!("has the argument {v}"));
                        continue;
                    }
                    let arg = m.params.first().map(|v| Arg::Const(*v));
                    match textbook_items(c, arg, &turtle) {
                        Ok(items) => modules.extend(items),
                        Err(why) => problem(format!("cannot be written: {why}")),
                    }
                    continue;
                }
                _ if lang::is_builtin_command(name) || name == "{" || name == "}" => {
                    problem(format!("is not a command the genome uses ({NOT_USED})"));
                    continue;
                }
                // A control symbol: the builder skips it.
                _ => continue,
            };
            modules.push(item);
        }
        (modules, problems)
    })
    .map_err(|d| vec![without_flags(d)])?;
    if turtle.heading == lang::ast::Heading::Up {
        problems.push(
            "its turtle starts heading up ('heading: up'); the genome's starts on the ground"
                .to_string(),
        );
    }
    if modules.is_empty() && problems.is_empty() {
        problems.push("its derived string has no building command".to_string());
    }
    if !is_balanced(&modules) {
        problems.push("the brackets of its derived string are not balanced".to_string());
    }
    if problems.is_empty() {
        Ok(modules)
    } else {
        Err(problems)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_limits_are_the_lsystem_genomes() {
        let l = LSystemLimits::default();
        let d = DirectLimits::default();
        assert_eq!((d.max_modules, d.max_parts), (l.max_modules, l.max_parts));
        assert_eq!(d.random_length, l.max_successor);
    }

    #[test]
    fn run_sites_are_one_per_started_successor_length() {
        assert_eq!([0, 1, 15, 16, 30, 31].map(run_sites), [1, 1, 1, 2, 2, 3]);
    }
}
