//! The walker (Chaumont et al. 3.3–3.5): its settings, its fitness formulas (Chaumont's
//! normalised distance, Walking with Dinosaurs' iterative move and its variants, Hornby &
//! Pollack's distance less drag), or an expression of its terms, and its protocol.

use std::collections::BTreeMap;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::protocol::{
    Rest, Setup, evaluate, on_flat_ground, scored_if_unstable, settle_steps, steps_in,
};
use super::recording::Phase;
use super::{Evaluation, Fitness, FitnessExpression, MAX_TARGET_DISTANCE, Task};
use crate::cancel::Interrupted;
use crate::creature::{Creature, PartId};
use crate::sim::{DragMeter, SimOptions, World};

/// The walker's fitness formula.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WalkerFitness {
    /// Chaumont et al.'s equation (1): D_w · C_v / (C_s · C_l) · κ^N.
    Normalised,
    /// The raw distance D_w.
    Distance,
    /// Walking with Dinosaurs' iterative move: "distance gained late in the process" counts
    /// more, which "favour\[s\] creatures that move a certain distance continuous but slow
    /// compared to one doing the same distance fast and then stopping" (3.3.3). The gain g_k
    /// of second k = 1..K of the measured walk is the horizontal distance the creature's centre
    /// of mass moves during that second; the fitness is Σ_k w_k · g_k with w_k = 2k / (K + 1),
    /// weights that average 1, so a steady walk scores the distance it covers.
    IterativeMove,
    /// Iterative move × the number of parts.
    BoxLover,
    /// Iterative move × the creature's mass.
    FatLover,
    /// Iterative move, but 0 for creatures of fewer than 3 parts.
    DwarfSlayer,
    /// Hornby & Pollack's walker fitness: "the distance moved by the creature's centre of
    /// mass, minus the distance ground points were dragged along the ground". The horizontal
    /// displacement of the whole creature's centre of mass over the measured walk, minus
    /// D_drag, the horizontal distance its parts slid along the ground while touching it
    /// (see [`crate::sim::DragMeter`]): stepping and rolling score, sliding does not. Held
    /// at −[`MAX_TARGET_DISTANCE`] or above, so that it stays above [`FAILURE_FITNESS`](super::FAILURE_FITNESS).
    HornbyPollack,
}

impl WalkerFitness {
    /// Every formula, in the order the CLI lists them.
    pub const ALL: [WalkerFitness; 7] = [
        WalkerFitness::Normalised,
        WalkerFitness::Distance,
        WalkerFitness::IterativeMove,
        WalkerFitness::BoxLover,
        WalkerFitness::FatLover,
        WalkerFitness::DwarfSlayer,
        WalkerFitness::HornbyPollack,
    ];

    /// The formula's name as configs and the CLI spell it (`"hornby-pollack"`).
    pub fn name(self) -> &'static str {
        match self {
            WalkerFitness::Normalised => "normalised",
            WalkerFitness::Distance => "distance",
            WalkerFitness::IterativeMove => "iterative-move",
            WalkerFitness::BoxLover => "box-lover",
            WalkerFitness::FatLover => "fat-lover",
            WalkerFitness::DwarfSlayer => "dwarf-slayer",
            WalkerFitness::HornbyPollack => "hornby-pollack",
        }
    }

    /// The formula and what its score measures, as reports show it:
    /// `"distance (m)"`, `"normalised (Chaumont eq. 1)"`.
    pub fn label(self) -> &'static str {
        match self {
            WalkerFitness::Normalised => "normalised (Chaumont eq. 1)",
            WalkerFitness::Distance => "distance (m)",
            WalkerFitness::IterativeMove => "iterative-move (m)",
            WalkerFitness::BoxLover => "box-lover (m × parts)",
            WalkerFitness::FatLover => "fat-lover (m × kg)",
            WalkerFitness::DwarfSlayer => "dwarf-slayer (m)",
            WalkerFitness::HornbyPollack => "hornby-pollack (m)",
        }
    }
}

impl WalkerFitness {
    /// The lowest score the formula can give an evaluation that succeeds: 0 for those made
    /// of distances (D_w, iterative move and its variants), none for Hornby & Pollack's,
    /// which drag can make negative.
    pub fn floor(self) -> Option<f64> {
        match self {
            WalkerFitness::HornbyPollack => None,
            _ => Some(0.0),
        }
    }
}

impl std::str::FromStr for WalkerFitness {
    type Err = String;

    /// The formula named `name` ([`WalkerFitness::name`]).
    fn from_str(name: &str) -> Result<WalkerFitness, String> {
        WalkerFitness::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| format!("unknown walker fitness '{name}'"))
    }
}

/// Settings of the walker task (Chaumont et al. sections 3.3–3.5).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WalkerOptions {
    /// Seconds of measured walking (section 3.5: 20).
    pub seconds: f64,
    /// κ of the block-count bonus κ^N.
    pub kappa: f64,
    /// Which formula, or an expression of the walker's terms.
    pub fitness: Fitness<WalkerFitness>,
    /// When the creature is at rest.
    pub rest: Rest,
    /// The first activation of the controller (s), between the two waits for rest: 1 s,
    /// Chaumont et al.'s final protocol (3.3: their first attempt, "less than 10 time
    /// steps", let balanced creatures through that toppled during the measured walk, "so we
    /// simply increase the interval for the initial controller activation to 1 second").
    pub activation: f64,
    /// The second stabilisation, controller off: at least this long (s), and until the
    /// creature is at rest by the same criterion as the first.
    pub second_settle: f64,
    /// Creatures taller than this (m) are not simulated.
    pub max_height: f64,
}

impl Default for WalkerOptions {
    fn default() -> Self {
        WalkerOptions {
            seconds: 20.0,
            kappa: 1.02,
            fitness: Fitness::Formula(WalkerFitness::Normalised),
            rest: Rest::default(),
            activation: 1.0,
            second_settle: 0.5,
            max_height: 15.0,
        }
    }
}

impl WalkerOptions {
    /// The most control steps of `dt` the walker can take: both waits for rest at their
    /// time limit, the activation and the measured walk.
    pub fn max_steps(&self, dt: f64) -> usize {
        // Saturating: a duration out of range is refused later, not an overflow here.
        let settle = settle_steps(&self.rest, dt);
        settle
            .saturating_add(settle)
            .saturating_add(steps_in(self.activation, dt))
            .saturating_add(steps_in(self.seconds, dt))
    }
}

/// Chaumont's size coefficients over the N parts: C_l (mean of B_x + B_y + B_z), C_s (mean
/// surface area) and C_v (mean volume).
pub fn size_coefficients(creature: &Creature) -> (f64, f64, f64) {
    let n = creature.parts.len().max(1) as f64;
    let (mut l, mut s, mut v) = (0.0, 0.0, 0.0);
    for p in &creature.parts {
        let b = p.size;
        l += b.x + b.y + b.z;
        s += 2.0 * (b.x * b.y + b.x * b.z + b.y * b.z);
        v += b.x * b.y * b.z;
    }
    (l / n, s / n, v / n)
}

/// WWD's iterative move over per-second gains `gains` (g_1 .. g_K): Σ_k 2k / (K + 1) · g_k.
pub fn iterative_move(gains: &[f64]) -> f64 {
    let k_total = gains.len() as f64;
    gains
        .iter()
        .enumerate()
        .map(|(k, g)| 2.0 * (k + 1) as f64 / (k_total + 1.0) * g)
        .sum()
}

/// The walker (Chaumont et al. 3.3–3.5): stabilise with the controller off until at rest,
/// check the height again, activate the controller for `activation` (1 s),
/// stabilise again (at least `second_settle`, and until at rest), then walk with the
/// controller on for `seconds`; D_w is the horizontal distance the root part's centre of mass
/// travels (for a creature that grows during the walk, its anchor, with the size terms of
/// the body at the start of the walk: [`super::Growing`]). The fitness is the formula
/// `options` names, or its expression's value.
pub fn walker(
    creature: &Creature,
    sim: &SimOptions,
    options: &WalkerOptions,
    record: bool,
) -> Evaluation {
    let evaluation = on_flat_ground(creature, sim, options, record, WalkerTask::evaluate);
    match options.fitness.expression() {
        Some(expression) => expression.score(evaluation),
        None => evaluation,
    }
}

/// [`walker`] in any world, watched: recorded, told its progress and stopped by a token as
/// `setup` says.
fn walker_watched(setup: Setup<'_, '_, WalkerOptions>) -> Result<Evaluation, Interrupted> {
    let Setup {
        creature,
        sim,
        options,
        ..
    } = setup;
    // A creature that never comes to rest scores 0 where valid scores never fall below 0.
    let floor = WalkerTask::floor(options);
    let unstable = |failure| scored_if_unstable(failure, floor);
    evaluate(WalkerTask::NAME, setup, |run| {
        run.settle(&options.rest, 0.0, sim.control_step)
            .map_err(unstable)?;
        let settled_at = run.world.time();
        run.check_height(options.max_height)?;
        run.phase = Phase::ControllerOn;
        run.run_for(options.activation, true, sim.control_step)?;
        run.settle(&options.rest, options.second_settle, sim.control_step)
            .map_err(unstable)?;
        let measure_from = run.world.time();
        run.phase = Phase::Measuring;
        // A growing creature: D_w at the root's anchor, which growth does not move, and the
        // size terms of the body at the start of the walk.
        let grows = run.growing.is_some();
        let at_start: std::borrow::Cow<'_, Creature> = match run.growing.as_deref() {
            Some(growing) => std::borrow::Cow::Owned(growing.creature().clone()),
            None => std::borrow::Cow::Borrowed(creature),
        };
        let root = |world: &World| {
            if grows {
                world.root_anchor()
            } else {
                world.part_position(PartId(0))
            }
        };
        let from = root(&run.world);
        // Iterative move: the centre of mass's horizontal gain over every whole second.
        let mut gains = Vec::new();
        let mut last_second = centre_of_mass(&run.world, &at_start);
        let centre_from = last_second;
        // Hornby & Pollack's D_drag, measured only when the fitness reads it.
        let formula = match &options.fitness {
            Fitness::Formula(formula) => Some(*formula),
            Fitness::Expression(_) => None,
        };
        let sliding = formula == Some(WalkerFitness::HornbyPollack)
            || options
                .fitness
                .expression()
                .is_some_and(|e| e.reads("drag") || e.reads("displacement"));
        let mut drag = sliding.then(|| DragMeter::start(&run.world));
        let steps = steps_in(options.seconds, sim.control_step);
        let start_time = run.world.time();
        for _ in 0..steps {
            run.step(true)?;
            if let Some(drag) = &mut drag {
                drag.after_step(&run.world, sim.control_step);
            }
            let elapsed = run.world.time() - start_time;
            if elapsed + 1e-9 >= (gains.len() + 1) as f64 {
                let centre = match run.growing.as_deref() {
                    Some(growing) => centre_of_mass(&run.world, growing.creature()),
                    None => centre_of_mass(&run.world, creature),
                };
                let d = centre - last_second;
                gains.push((d.x * d.x + d.z * d.z).sqrt());
                last_second = centre;
            }
        }
        let iterative = iterative_move(&gains);
        let to = root(&run.world);
        let d = to - from;
        let distance = (d.x * d.x + d.z * d.z).sqrt();
        let (c_l, c_s, c_v) = size_coefficients(&at_start);
        let n = at_start.parts.len() as f64;
        let centre_now = match run.growing.as_deref() {
            Some(growing) => centre_of_mass(&run.world, growing.creature()),
            None => centre_of_mass(&run.world, creature),
        };
        let centre_moved = centre_now - centre_from;
        let displacement = centre_moved.x.hypot(centre_moved.z);
        let dragged = drag.map_or(0.0, |drag| drag.dragged());
        // An expression's value is had from the terms once they are all in
        // ([`FitnessExpression::score`]): 0 until then.
        let fitness = match formula {
            None => 0.0,
            Some(WalkerFitness::Normalised) => {
                distance * (c_v / (c_s * c_l)) * options.kappa.powf(n)
            }
            Some(WalkerFitness::Distance) => distance,
            Some(WalkerFitness::IterativeMove) => iterative,
            Some(WalkerFitness::BoxLover) => iterative * n,
            Some(WalkerFitness::FatLover) => iterative * at_start.mass(),
            Some(WalkerFitness::DwarfSlayer) => {
                if n < 3.0 {
                    0.0
                } else {
                    iterative
                }
            }
            Some(WalkerFitness::HornbyPollack) => {
                (displacement - dragged).max(-MAX_TARGET_DISTANCE)
            }
        };
        let mut terms = BTreeMap::from([
            ("D_w".to_string(), distance),
            ("C_l".to_string(), c_l),
            ("C_s".to_string(), c_s),
            ("C_v".to_string(), c_v),
            ("N".to_string(), n),
            ("kappa".to_string(), options.kappa),
            ("settled_at".to_string(), settled_at),
            ("iterative_move".to_string(), iterative),
            ("mass".to_string(), at_start.mass()),
            ("measured_from".to_string(), measure_from),
        ]);
        if let Some(growing) = run.growing.as_deref() {
            // How much development remained during the evaluation, body against brain.
            let tally = growing.tally();
            terms.insert("grown_parts".into(), tally.parts as f64);
            terms.insert("grown_length".into(), tally.length);
            terms.insert("grown_neurons".into(), tally.neurons as f64);
            terms.insert("grown_links".into(), tally.links as f64);
            terms.insert("growth_stopped".into(), tally.stopped as f64);
            terms.insert("growth_work".into(), run.world.growth_work());
        }
        if sliding {
            terms.insert("displacement".into(), displacement);
            terms.insert("drag".into(), dragged);
        }
        Ok((fitness, terms))
    })
}

/// The mass-weighted centre of the creature's parts in `world`.
pub(super) fn centre_of_mass(world: &World, creature: &Creature) -> Vector3<f64> {
    let total = creature.mass().max(f64::MIN_POSITIVE);
    creature
        .parts_by_id()
        .map(|(id, part)| world.part_position(id) * part.mass())
        .sum::<Vector3<f64>>()
        / total
}

/// Chaumont et al.'s walker, in the registry ([`super::Task`]).
pub struct WalkerTask;

impl Task for WalkerTask {
    const NAME: &'static str = "walker";
    const SUMMARY: &'static str =
        "Chaumont et al.'s walker: distance of the root part, normalised by size (eq. 1)";
    const FITNESS_VARIANTS: &'static [&'static str] = &[
        "normalised",
        "distance",
        "iterative-move",
        "box-lover",
        "fat-lover",
        "dwarf-slayer",
        "hornby-pollack",
    ];
    const TERMS: &'static [&'static str] = &[
        "D_w",
        "C_l",
        "C_s",
        "C_v",
        "N",
        "kappa",
        "settled_at",
        "iterative_move",
        "mass",
        "measured_from",
        "displacement",
        "drag",
    ];
    type Options = WalkerOptions;

    fn expression(options: &WalkerOptions) -> Option<&FitnessExpression> {
        options.fitness.expression()
    }
    fn set_fitness(options: &mut WalkerOptions, text: &str) {
        options.fitness = Fitness::new(text);
    }
    fn measure(options: &WalkerOptions) -> &'static str {
        match &options.fitness {
            Fitness::Formula(formula) => formula.label(),
            Fitness::Expression(_) => "expression",
        }
    }
    fn floor(options: &WalkerOptions) -> Option<f64> {
        match &options.fitness {
            Fitness::Formula(formula) => formula.floor(),
            Fitness::Expression(_) => None,
        }
    }
    fn evaluate(setup: Setup<'_, '_, WalkerOptions>) -> Result<Evaluation, Interrupted> {
        walker_watched(setup)
    }
}
