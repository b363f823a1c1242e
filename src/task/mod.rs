//! Tasks: the seed papers' protocols and fitness formulas, with the guards against cheating
//! and numerical explosion. Every task takes a [`Creature`] and gives an [`Evaluation`].

use std::collections::BTreeMap;

use nalgebra::{UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

mod check;
mod compact;
mod spec;
pub use check::{MAX_SECONDS, check_duration};
pub use spec::{TaskKind, TaskSpec};

use crate::creature::{Creature, Severity};
use crate::sim::{DragMeter, SimOptions, World};

/// The fitness of every failed evaluation, whatever the task: Walking with Dinosaurs' value
/// for illegal creatures (3.5.1), and Chaumont et al.'s "arbitrary low value" (5.4). Every
/// valid score of every task is above it: walker, catapult and jump scores are never
/// negative, except the walker's Hornby & Pollack score, held at −[`MAX_TARGET_DISTANCE`] or
/// above, and an aim score D_p − D_t is at least −D_t ≥ −|target| > −[`MAX_TARGET_DISTANCE`].
pub const FAILURE_FITNESS: f64 = -999_999.0;

/// The farthest an aim task's target may be from the projectile's start (m), so that every
/// aim score stays above [`FAILURE_FITNESS`].
pub const MAX_TARGET_DISTANCE: f64 = 100_000.0;

/// How an evaluation ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    /// Evaluated normally.
    Ok,
    /// Never came to rest when the protocol needed it to.
    Unstable,
    /// The physics blew up: NaN in a body, a part jumping too far in one step, or moving
    /// too fast.
    Exploded,
    /// Parts interpenetrate from the start (Chaumont 5.5): not simulated.
    SelfIntersecting,
    /// Taller than the height limit (Walking with Dinosaurs' height test): not simulated.
    TooTall,
    /// Development reported an error, or there is nothing to simulate.
    Invalid,
}

/// The walker's fitness formula.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WalkerFitness {
    /// Chaumont et al.'s equation (1): D_w · C_v / (C_s · C_l) · κ^N.
    Normalised,
    /// The raw distance D_w.
    Distance,
    /// Walking with Dinosaurs' iterative move: "distance gained late in the process" counts
    /// more, which "favour[s] creatures that move a certain distance continuous but slow
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
    /// at −[`MAX_TARGET_DISTANCE`] or above, so that it stays above [`FAILURE_FITNESS`].
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

/// When a creature counts as at rest (Chaumont et al. 3.3): for `duration` seconds in a row,
/// every part's centre moves less than `distance` per 1/60 s (a speed, so the test means the
/// same at any time step) and drifts less than `drift` in all (Ontogeny's addition, so that
/// a slowly toppling tower, whose parts creep below the speed threshold, is not at rest);
/// within `limit` seconds.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Rest {
    /// Δx, per 1/60 s (Chaumont: 1/300 m).
    pub distance: f64,
    /// How long every part must stay calm (s): 0.5 s, the 30 steps of 1/60 s of the first
    /// implementation.
    pub duration: f64,
    /// The most any part's centre may drift over the calm window (m): 1 cm, three times Δx.
    pub drift: f64,
    /// A creature not at rest after this many seconds is unstable.
    pub limit: f64,
}

impl Default for Rest {
    fn default() -> Self {
        Rest {
            distance: 1.0 / 300.0,
            duration: 0.5,
            drift: 0.01,
            limit: 10.0,
        }
    }
}

/// Whole control steps in `seconds` at time step `dt` (at least one when `seconds` > 0).
fn steps_in(seconds: f64, dt: f64) -> usize {
    let steps = (seconds / dt - 1e-9).ceil().max(0.0) as usize;
    if seconds > 0.0 { steps.max(1) } else { 0 }
}

/// The most control steps one wait for rest can take: the creature is unstable once it has
/// stepped past `rest.limit`.
fn settle_steps(rest: &Rest, dt: f64) -> usize {
    steps_in(rest.limit, dt).saturating_add(1)
}

/// The most frames a recording holds. A run that may take more control steps keeps one step
/// in every [`recording_interval`], chosen before the run from its longest possible duration,
/// so the frames stay evenly spaced in time; the first and the last step are always kept.
/// 12,000 frames are 200 s at 1/60 s per step (every step of the default walker, jump and
/// catapult), about 11 MB of `recording.json` for a 10-part creature; an hour's walk keeps
/// one step in 19 (a frame every 0.32 s).
pub const MAX_RECORDED_FRAMES: usize = 12_000;

/// Every how many control steps a recording keeps a frame, for a run of at most `max_steps`
/// steps: 1 (every step) when they fit in [`MAX_RECORDED_FRAMES`]; otherwise the least k for
/// which the kept steps 1, 1 + k, 1 + 2k, ... and the last step fit.
pub fn recording_interval(max_steps: usize) -> usize {
    if max_steps <= MAX_RECORDED_FRAMES {
        1
    } else {
        max_steps.div_ceil(MAX_RECORDED_FRAMES - 1)
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
    /// Which formula.
    pub fitness: WalkerFitness,
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
            fitness: WalkerFitness::Normalised,
            rest: Rest::default(),
            activation: 1.0,
            second_settle: 0.5,
            max_height: 15.0,
        }
    }
}

/// Which stage of a task's protocol a recorded frame belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Phase {
    /// Controller off, waiting for the creature to come to rest (walker, jump).
    Settling,
    /// The walker's first activation of the controller (1 s), before it settles again.
    ControllerOn,
    /// Controller on, the fitness being measured (walker, jump).
    Measuring,
    /// Catapult and aim: controller on, the projectile still held.
    Throwing,
    /// Catapult and aim: the projectile released, until it comes to rest.
    Flying,
}

impl Phase {
    /// The phase in words, as pictures label it.
    pub fn label(self) -> &'static str {
        match self {
            Phase::Settling => "settling",
            Phase::ControllerOn => "controller on",
            Phase::Measuring => "measuring",
            Phase::Throwing => "throwing",
            Phase::Flying => "projectile flying",
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

/// The poses of every part at one moment.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RecordedFrame {
    /// Simulated time.
    pub t: f64,
    /// The protocol's phase during the step that ended here (absent in recordings made
    /// before phases were recorded).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub phase: Option<Phase>,
    /// Each part's centre and orientation (written at the physics' f32 precision).
    #[serde(serialize_with = "compact::poses")]
    pub parts: Vec<(Vector3<f64>, UnitQuaternion<f64>)>,
    /// The projectile's centre, in the catapult and aim tasks.
    #[serde(
        skip_serializing_if = "Option::is_none",
        default,
        serialize_with = "compact::point"
    )]
    pub projectile: Option<Vector3<f64>>,
    /// The projectile's size, in the catapult and aim tasks.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub projectile_size: Option<Vector3<f64>>,
}

/// The outcome of one evaluation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// The task's name.
    pub task: String,
    /// The fitness; [`FAILURE_FITNESS`] unless the status is `ok`.
    pub fitness: f64,
    /// How it ended.
    pub status: Status,
    /// The terms behind the fitness (D_w, C_l, C_s, C_v, N, ...).
    pub terms: BTreeMap<String, f64>,
    /// What went wrong, when something did.
    pub message: Option<String>,
    /// Poses per recorded frame, when recording was asked for.
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub recording: Vec<RecordedFrame>,
}

impl Evaluation {
    /// The evaluation of something that never became a creature (a developmental error):
    /// status `invalid`, the failure floor.
    pub fn invalid(task: &str, message: String) -> Evaluation {
        Evaluation::failed(task, Status::Invalid, message)
    }

    fn failed(task: &str, status: Status, message: String) -> Evaluation {
        Evaluation {
            task: task.to_string(),
            fitness: FAILURE_FITNESS,
            status,
            terms: BTreeMap::new(),
            message: Some(message),
            recording: Vec::new(),
        }
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

/// Checks that apply to every task before simulating. `seconds` is the task's duration.
fn screen(task: &str, creature: &Creature, max_height: f64, seconds: f64) -> Option<Evaluation> {
    if !(seconds.is_finite() && (0.0..=1e6).contains(&seconds)) {
        return Some(Evaluation::failed(
            task,
            Status::Invalid,
            format!("the task's duration must be 0 to 10^6 s, not {seconds}"),
        ));
    }
    if creature.parts.is_empty() {
        return Some(Evaluation::failed(
            task,
            Status::Invalid,
            "the creature has no parts".into(),
        ));
    }
    let errors: Vec<&str> = creature
        .problems
        .iter()
        .filter(|p| p.severity == Severity::Error)
        .map(|p| p.message.as_str())
        .collect();
    // Checked on the creature itself, not only trusted from its list of problems (a
    // creature.json may come from anywhere).
    let pairs = creature.interpenetrating_pairs();
    if !pairs.is_empty() || errors.iter().any(|m| m.contains("interpenetrate")) {
        let listed: Vec<String> = pairs
            .iter()
            .map(|(a, b)| format!("parts {a} and {b} interpenetrate"))
            .collect();
        let message = if listed.is_empty() {
            errors.join("; ")
        } else {
            listed.join("; ")
        };
        return Some(Evaluation::failed(task, Status::SelfIntersecting, message));
    }
    if !errors.is_empty() {
        return Some(Evaluation::failed(task, Status::Invalid, errors.join("; ")));
    }
    let (lo, hi) = creature.bounding_box();
    too_tall(task, hi.y - lo.y, max_height, "")
}

/// Walking with Dinosaurs' height test, before simulating and again after settling.
fn too_tall(task: &str, height: f64, max_height: f64, when: &str) -> Option<Evaluation> {
    (height > max_height).then(|| {
        Evaluation::failed(
            task,
            Status::TooTall,
            format!("{height:.2} m tall{when}, more than {max_height} m"),
        )
    })
}

/// A running evaluation: the world plus the bookkeeping every protocol needs.
struct Run<'p> {
    world: World,
    projectile_size: Option<Vector3<f64>>,
    record: bool,
    recording: Vec<RecordedFrame>,
    task: &'static str,
    phase: Phase,
    /// Control steps taken.
    steps: usize,
    /// The most control steps the protocol can take (every phase at its longest).
    max_steps: usize,
    /// Every how many steps the recording keeps a frame.
    interval: usize,
    /// The last step's frame when the interval skipped it: kept at the end of the run.
    pending: Option<RecordedFrame>,
    /// Steps counted as done: every finished phase at its longest, so the fraction done
    /// grows steadily and ends at 1.
    counted: usize,
    /// Steps taken when the current phase began.
    phase_start: usize,
    /// Told the fraction done, in steps of 0.001 (and 1 at the end).
    progress: &'p mut dyn FnMut(f64),
    /// The last fraction told, in thousandths.
    told: Option<usize>,
}

impl Run<'_> {
    fn step(&mut self, controller: bool) -> Result<f64, Evaluation> {
        let moved = self.world.step(controller).map_err(|e| {
            Evaluation::failed(
                self.task,
                Status::Exploded,
                format!("{e} at t = {:.3} s", self.world.time()),
            )
        })?;
        self.steps += 1;
        if self.record {
            let frame = RecordedFrame {
                t: self.world.time(),
                phase: Some(self.phase),
                parts: (0..self.world.part_count())
                    .map(|i| self.world.part_pose(i))
                    .collect(),
                projectile: self.world.projectile_state().map(|(p, _)| p),
                projectile_size: self.projectile_size,
            };
            self.keep(frame);
        }
        self.tell();
        Ok(moved)
    }

    /// Keeps the frame of step `steps` if the recording's interval falls on it; otherwise
    /// holds it back, in case it is the last.
    fn keep(&mut self, frame: RecordedFrame) {
        if (self.steps - 1).is_multiple_of(self.interval) {
            self.recording.push(frame);
            self.pending = None;
        } else {
            self.pending = Some(frame);
        }
    }

    /// The recording, its last step included.
    fn take_recording(&mut self) -> Vec<RecordedFrame> {
        self.recording.extend(self.pending.take());
        std::mem::take(&mut self.recording)
    }

    /// A phase that can take at most `longest` steps is over: it counts as that many.
    fn end_phase(&mut self, longest: usize) {
        self.counted = self.counted.saturating_add(longest);
        self.phase_start = self.steps;
        self.tell();
    }

    /// Tells the progress callback the fraction done, when it has grown by a thousandth.
    fn tell(&mut self) {
        let done = self.counted.saturating_add(self.steps - self.phase_start);
        let thousandths = ((1000.0 * done as f64 / self.max_steps.max(1) as f64) as usize).min(999);
        if self.told.is_none_or(|told| thousandths > told) {
            self.told = Some(thousandths);
            (self.progress)(thousandths as f64 / 1000.0);
        }
    }

    /// Steps with the controller off for at least `at_least` seconds and until the creature
    /// is at rest; `Unstable` if it is not within the time limit.
    fn settle(&mut self, rest: &Rest, at_least: f64, dt: f64) -> Result<(), Evaluation> {
        self.phase = Phase::Settling;
        self.world.set_resting(true);
        let settled = self.wait_for_rest(rest, at_least, dt);
        self.world.set_resting(false);
        self.end_phase(settle_steps(rest, dt));
        settled
    }

    fn wait_for_rest(&mut self, rest: &Rest, at_least: f64, dt: f64) -> Result<(), Evaluation> {
        let threshold = rest.distance * dt * 60.0; // Δx is given per 1/60 s
        let calm_needed = steps_in(rest.duration, dt);
        let minimum = steps_in(at_least, dt);
        let mut calm = 0;
        let mut taken = 0;
        let mut window: Vec<Vector3<f64>> = Vec::with_capacity(self.world.part_count());
        while calm < calm_needed || taken < minimum {
            if taken as f64 * dt > rest.limit + 1e-9 {
                return Err(Evaluation::failed(
                    self.task,
                    Status::Unstable,
                    format!(
                        "not at rest after {} s (from t = {:.3} s)",
                        rest.limit,
                        self.world.time() - taken as f64 * dt
                    ),
                ));
            }
            if calm == 0 {
                // A new calm window starts here.
                window.clear();
                window.extend((0..self.world.part_count()).map(|i| self.world.part_position(i)));
            }
            let moved = self.step(false)?;
            taken += 1;
            // Calm: every part moves less than Δx per 1/60 s (Chaumont), and none has drifted
            // more than `drift` since the window began (a slowly toppling tower is not at rest).
            let drifted = (0..window.len())
                .any(|i| (self.world.part_position(i) - window[i]).norm() >= rest.drift);
            calm = if moved < threshold && !drifted {
                calm + 1
            } else {
                0
            };
        }
        Ok(())
    }

    fn run_for(&mut self, seconds: f64, controller: bool, dt: f64) -> Result<(), Evaluation> {
        let steps = steps_in(seconds, dt);
        for _ in 0..steps {
            self.step(controller)?;
        }
        self.end_phase(steps);
        Ok(())
    }

    /// The height test again, on the settled creature.
    fn check_height(&self, max_height: f64) -> Result<(), Evaluation> {
        let height = self.world.highest_point() - self.world.lowest_point();
        match too_tall(self.task, height, max_height, " after settling") {
            Some(failed) => Err(failed),
            None => Ok(()),
        }
    }
}

/// How an evaluation is watched: whether it is recorded, the most control steps its protocol
/// can take, and the callback told the fraction done.
struct Watch<'p> {
    record: bool,
    max_steps: usize,
    progress: &'p mut dyn FnMut(f64),
}

fn start<'p>(
    task: &'static str,
    creature: &Creature,
    sim: &SimOptions,
    watch: Watch<'p>,
) -> Result<Run<'p>, Evaluation> {
    let world = World::new(creature, sim)
        .map_err(|e| Evaluation::failed(task, Status::Invalid, e.to_string()))?;
    Ok(Run {
        world,
        projectile_size: None,
        record: watch.record,
        recording: Vec::new(),
        task,
        phase: Phase::Settling,
        steps: 0,
        max_steps: watch.max_steps,
        interval: recording_interval(watch.max_steps),
        pending: None,
        counted: 0,
        phase_start: 0,
        progress: watch.progress,
        told: None,
    })
}

/// Screens the creature, builds its world and runs `protocol`, which returns the fitness and
/// its terms (or a failed evaluation). The progress callback is told 1 at the end.
fn evaluate(
    task: &'static str,
    creature: &Creature,
    sim: &SimOptions,
    watch: Watch<'_>,
    limits: (f64, f64),
    protocol: impl FnOnce(&mut Run<'_>) -> Result<(f64, BTreeMap<String, f64>), Evaluation>,
) -> Evaluation {
    let Watch {
        record,
        max_steps,
        progress,
    } = watch;
    let watch = Watch {
        record,
        max_steps,
        progress: &mut *progress,
    };
    let evaluation = evaluate_run(task, creature, sim, watch, limits, protocol);
    progress(1.0);
    evaluation
}

fn evaluate_run(
    task: &'static str,
    creature: &Creature,
    sim: &SimOptions,
    watch: Watch<'_>,
    (max_height, seconds): (f64, f64),
    protocol: impl FnOnce(&mut Run<'_>) -> Result<(f64, BTreeMap<String, f64>), Evaluation>,
) -> Evaluation {
    if let Some(rejected) = screen(task, creature, max_height, seconds) {
        return rejected;
    }
    let mut run = match start(task, creature, sim, watch) {
        Ok(run) => run,
        Err(failed) => return failed,
    };
    match protocol(&mut run) {
        Ok((fitness, mut terms)) => {
            // How far the solver let any joint come apart (m): a diagnostic of the step
            // setting, not part of any fitness.
            terms.insert("joint_gap".into(), run.world.peak_joint_gap());
            // No NaN or infinity leaves an evaluation: JSON cannot hold them.
            if let Some((name, _)) = terms.iter().find(|(_, v)| !v.is_finite()) {
                return Evaluation::failed(task, Status::Invalid, format!("{name} is not finite"));
            }
            if !fitness.is_finite() {
                return Evaluation::failed(task, Status::Invalid, "fitness is not finite".into());
            }
            Evaluation {
                task: task.to_string(),
                fitness,
                status: Status::Ok,
                terms,
                message: None,
                recording: run.take_recording(),
            }
        }
        Err(mut failed) => {
            // What was recorded up to the failure shows why it failed.
            failed.recording = run.take_recording();
            failed
        }
    }
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
/// travels.
pub fn walker(
    creature: &Creature,
    sim: &SimOptions,
    options: &WalkerOptions,
    record: bool,
) -> Evaluation {
    walker_with_progress(creature, sim, options, record, &mut |_| {})
}

/// [`walker`], telling `progress` the fraction done: from 0, growing by thousandths as the
/// protocol steps (a phase that ends early counts as done at its longest), and 1 at the end.
pub fn walker_with_progress(
    creature: &Creature,
    sim: &SimOptions,
    options: &WalkerOptions,
    record: bool,
    progress: &mut dyn FnMut(f64),
) -> Evaluation {
    let limits = (options.max_height, options.seconds);
    let watch = Watch {
        record,
        max_steps: options.max_steps(sim.dt),
        progress,
    };
    evaluate("walker", creature, sim, watch, limits, |run| {
        run.settle(&options.rest, 0.0, sim.dt)?;
        let settled_at = run.world.time();
        run.check_height(options.max_height)?;
        run.phase = Phase::ControllerOn;
        run.run_for(options.activation, true, sim.dt)?;
        run.settle(&options.rest, options.second_settle, sim.dt)?;
        let measure_from = run.world.time();
        run.phase = Phase::Measuring;
        let from = run.world.part_position(0);
        // Iterative move: the centre of mass's horizontal gain over every whole second.
        let mut gains = Vec::new();
        let mut last_second = centre_of_mass(&run.world, creature);
        let centre_from = last_second;
        // Hornby & Pollack's D_drag, measured only when it is the fitness.
        let mut drag =
            (options.fitness == WalkerFitness::HornbyPollack).then(|| DragMeter::start(&run.world));
        let steps = steps_in(options.seconds, sim.dt);
        let start_time = run.world.time();
        for _ in 0..steps {
            run.step(true)?;
            if let Some(drag) = &mut drag {
                drag.after_step(&run.world, sim.dt);
            }
            let elapsed = run.world.time() - start_time;
            if elapsed + 1e-9 >= (gains.len() + 1) as f64 {
                let centre = centre_of_mass(&run.world, creature);
                let d = centre - last_second;
                gains.push((d.x * d.x + d.z * d.z).sqrt());
                last_second = centre;
            }
        }
        let iterative = iterative_move(&gains);
        let to = run.world.part_position(0);
        let d = to - from;
        let distance = (d.x * d.x + d.z * d.z).sqrt();
        let (c_l, c_s, c_v) = size_coefficients(creature);
        let n = creature.parts.len() as f64;
        let centre_moved = centre_of_mass(&run.world, creature) - centre_from;
        let displacement = centre_moved.x.hypot(centre_moved.z);
        let dragged = drag.map_or(0.0, |drag| drag.dragged());
        let fitness = match options.fitness {
            WalkerFitness::Normalised => distance * (c_v / (c_s * c_l)) * options.kappa.powf(n),
            WalkerFitness::Distance => distance,
            WalkerFitness::IterativeMove => iterative,
            WalkerFitness::BoxLover => iterative * n,
            WalkerFitness::FatLover => iterative * creature.mass(),
            WalkerFitness::DwarfSlayer => {
                if n < 3.0 {
                    0.0
                } else {
                    iterative
                }
            }
            WalkerFitness::HornbyPollack => (displacement - dragged).max(-MAX_TARGET_DISTANCE),
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
            ("mass".to_string(), creature.mass()),
            ("measured_from".to_string(), measure_from),
        ]);
        if options.fitness == WalkerFitness::HornbyPollack {
            terms.insert("displacement".into(), displacement);
            terms.insert("drag".into(), dragged);
        }
        Ok((fitness, terms))
    })
}

/// The mass-weighted centre of the creature's parts in `world`.
fn centre_of_mass(world: &World, creature: &Creature) -> Vector3<f64> {
    let total = creature.mass().max(f64::MIN_POSITIVE);
    (0..world.part_count())
        .map(|i| world.part_position(i) * creature.parts[i].mass())
        .sum::<Vector3<f64>>()
        / total
}

/// Settings of the jump task.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct JumpOptions {
    /// Seconds with the controller on, after the creature has come to rest.
    pub seconds: f64,
    /// Creatures taller than this (m) are not simulated.
    pub max_height: f64,
    /// When the creature is at rest, before jumping.
    pub rest: Rest,
}

impl Default for JumpOptions {
    fn default() -> Self {
        JumpOptions {
            seconds: 10.0,
            max_height: 15.0,
            rest: Rest::default(),
        }
    }
}

impl JumpOptions {
    /// The most control steps of `dt` the jump can take: the wait for rest at its time
    /// limit, then the jump.
    pub fn max_steps(&self, dt: f64) -> usize {
        settle_steps(&self.rest, dt).saturating_add(steps_in(self.seconds, dt))
    }
}

/// Jump (Walking with Dinosaurs 3.3.3): after coming to rest (and passing the height test
/// again), the controller runs for `seconds`; the fitness is the best height of the
/// creature's lowest point above the ground.
pub fn jump(
    creature: &Creature,
    sim: &SimOptions,
    options: &JumpOptions,
    record: bool,
) -> Evaluation {
    jump_with_progress(creature, sim, options, record, &mut |_| {})
}

/// [`jump`], telling `progress` the fraction done, as [`walker_with_progress`] does.
pub fn jump_with_progress(
    creature: &Creature,
    sim: &SimOptions,
    options: &JumpOptions,
    record: bool,
    progress: &mut dyn FnMut(f64),
) -> Evaluation {
    let limits = (options.max_height, options.seconds);
    let watch = Watch {
        record,
        max_steps: options.max_steps(sim.dt),
        progress,
    };
    evaluate("jump", creature, sim, watch, limits, |run| {
        run.settle(&options.rest, 0.0, sim.dt)?;
        run.check_height(options.max_height)?;
        let resting = run.world.lowest_point().max(0.0);
        let mut best: f64 = 0.0;
        run.phase = Phase::Measuring;
        for _ in 0..steps_in(options.seconds, sim.dt) {
            run.step(true)?;
            best = best.max(run.world.lowest_point());
        }
        let terms = BTreeMap::from([
            ("height".to_string(), best),
            ("resting_lowest_point".to_string(), resting),
        ]);
        Ok((best, terms))
    })
}

/// Settings of the catapult and aim tasks (Chaumont et al. section 4).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CatapultOptions {
    /// The projectile's size (m).
    pub projectile_size: Vector3<f64>,
    /// The projectile's density (kg/m³).
    pub projectile_density: f64,
    /// Seconds after which the release mechanism fires without a signal (Figure 4: 30
    /// steps of 1/60 s).
    pub release_delay: f64,
    /// The projectile is at rest when slower than this (m/s) ...
    pub rest_speed: f64,
    /// ... for this long (s) after release.
    pub rest_duration: f64,
    /// A projectile not at rest this many seconds after the start is `unstable` (Chaumont's
    /// blocks "roll for almost 20 seconds").
    pub max_seconds: f64,
    /// Creatures taller than this (m) are not simulated.
    pub max_height: f64,
    /// The aim task's target, relative to where the projectile starts (metres; y is up).
    pub target: Option<Vector3<f64>>,
}

impl Default for CatapultOptions {
    fn default() -> Self {
        CatapultOptions {
            projectile_size: Vector3::new(0.2, 0.2, 0.2),
            projectile_density: crate::creature::DEFAULT_DENSITY,
            release_delay: 0.5,
            rest_speed: 0.01,
            rest_duration: 0.5,
            max_seconds: 60.0,
            max_height: 15.0,
            target: None,
        }
    }
}

impl CatapultOptions {
    /// The most control steps of `dt` the catapult and aim tasks can take: `max_seconds`.
    pub fn max_steps(&self, dt: f64) -> usize {
        steps_in(self.max_seconds, dt)
    }
}

/// The minimum distance between the polyline `trajectory` and `target` (D_t of equation 3).
pub fn distance_to_trajectory(trajectory: &[Vector3<f64>], target: &Vector3<f64>) -> f64 {
    match trajectory {
        [] => f64::INFINITY,
        [only] => (only - target).norm(),
        _ => trajectory
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let ab = b - a;
                let len2 = ab.norm_squared();
                let s = if len2 > 0.0 {
                    ((target - a).dot(&ab) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (a + ab * s - target).norm()
            })
            .fold(f64::INFINITY, f64::min),
    }
}

/// Catapult (`options.target` = None, equation 2: F_D = D_p) or aim (equation 3:
/// F_a = D_p − D_t). The creature's root part is the arm; a projectile is held at its near
/// end and released after `release_delay` seconds, or earlier when the brain's first
/// `release` effector fires. D_p is the horizontal distance of the projectile's centre from
/// release to rest; the simulation ends when the projectile comes to rest, and a projectile
/// still moving after `max_seconds` is `unstable`. Once the projectile is placed, the aim
/// task's target in the world is in the terms (`target_x`, `target_y`, `target_z`), of a
/// failed evaluation too.
pub fn catapult(
    creature: &Creature,
    sim: &SimOptions,
    options: &CatapultOptions,
    record: bool,
) -> Evaluation {
    catapult_with_progress(creature, sim, options, record, &mut |_| {})
}

/// [`catapult`], telling `progress` the fraction done, as [`walker_with_progress`] does (the
/// run counts as done when the projectile comes to rest).
pub fn catapult_with_progress(
    creature: &Creature,
    sim: &SimOptions,
    options: &CatapultOptions,
    record: bool,
    progress: &mut dyn FnMut(f64),
) -> Evaluation {
    let task: &'static str = if options.target.is_some() {
        "aim"
    } else {
        "catapult"
    };
    let limits = (options.max_height, options.max_seconds);
    if let Some(target) = options.target
        && !(target.iter().all(|v| v.is_finite()) && target.norm() <= MAX_TARGET_DISTANCE)
    {
        return Evaluation::failed(
            task,
            Status::Invalid,
            format!("the target must be within {MAX_TARGET_DISTANCE} m of the projectile"),
        );
    }
    let watch = Watch {
        record,
        max_steps: options.max_steps(sim.dt),
        progress,
    };
    // The target in the world, once the projectile is placed: kept in the terms of a failed
    // evaluation too, so that its recording can show the target.
    let placed_target = std::cell::Cell::new(None);
    let mut evaluation = evaluate(task, creature, sim, watch, limits, |run| {
        run.world
            .attach_projectile(options.projectile_size, options.projectile_density);
        run.projectile_size = Some(options.projectile_size);
        run.phase = Phase::Throwing;
        let (start_position, _) = run.world.projectile_state().expect("attached");
        let target = options.target.map(|t| start_position + t);
        placed_target.set(target);
        run.world.set_target(target);
        let mut released_at = None;
        let mut release_point = start_position;
        let mut trajectory = Vec::new();
        let mut calm = 0;
        let mut step = 0usize;
        let limit = steps_in(options.max_seconds, sim.dt);
        let release_step = steps_in(options.release_delay, sim.dt);
        let calm_needed = steps_in(options.rest_duration, sim.dt);
        let mut at_rest = false;
        while step < limit {
            run.step(true)?;
            step += 1;
            let (position, speed) = run.world.projectile_state().expect("attached");
            if released_at.is_none() && (step >= release_step || run.world.release_signalled()) {
                run.world.release();
                run.phase = Phase::Flying;
                released_at = Some(step);
                release_point = position;
            }
            if released_at.is_some() {
                trajectory.push(position);
                calm = if speed < options.rest_speed {
                    calm + 1
                } else {
                    0
                };
                if calm >= calm_needed {
                    at_rest = true;
                    break;
                }
            }
        }
        let Some(released_at) = released_at else {
            return Err(Evaluation::failed(
                task,
                Status::Invalid,
                format!(
                    "the run ended after {step} steps, before the projectile was released (step {release_step})"
                ),
            ));
        };
        if !at_rest {
            return Err(Evaluation::failed(
                task,
                Status::Unstable,
                format!(
                    "the projectile was still moving after {} s",
                    options.max_seconds
                ),
            ));
        }
        let (rest_point, _) = run.world.projectile_state().expect("attached");
        let d = rest_point - release_point;
        let distance = (d.x * d.x + d.z * d.z).sqrt();
        let mut terms = BTreeMap::from([
            ("D_p".to_string(), distance),
            ("release_step".to_string(), released_at as f64),
            ("release_time".to_string(), released_at as f64 * sim.dt),
            ("seconds".to_string(), run.world.time()),
        ]);
        let fitness = match target {
            Some(target) => {
                terms.insert("target_x".to_string(), target.x);
                terms.insert("target_y".to_string(), target.y);
                terms.insert("target_z".to_string(), target.z);
                let d_t = distance_to_trajectory(&trajectory, &target);
                terms.insert("D_t".to_string(), d_t);
                distance - d_t
            }
            None => distance,
        };
        Ok((fitness, terms))
    });
    if let Some(target) = placed_target.get() {
        for (name, value) in [
            ("target_x", target.x),
            ("target_y", target.y),
            ("target_z", target.z),
        ] {
            evaluation.terms.entry(name.to_string()).or_insert(value);
        }
    }
    evaluation
}
