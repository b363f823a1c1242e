//! The protocol's common steps, shared by every task: screening a creature before it is
//! simulated, building its world, stepping it with the controller on or off, waiting for it to
//! come to rest, the height test, recording samples and telling progress; what every protocol
//! is given ([`Setup`]) and what every task's settings bound ([`Bounds`]). A task's own file
//! says in what order these steps run and how its fitness is computed from them.

use std::collections::BTreeMap;

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

use super::recorded_growth::GrowthRecorder;
use super::recording::{Phase, Sample, recording_interval};
use super::{Evaluation, Status, UNSTABLE_FITNESS};
use crate::cancel::{Cancel, Interrupted};
use crate::creature::{Creature, Severity};
use crate::sim::{Grown, SettingError, SimOptions, World, WorldSpec};

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

/// `failure` scored as Chaumont et al. 3.3 score a creature that never comes to rest: 0
/// ([`UNSTABLE_FITNESS`]: "no distance will ever be recorded for them, so their fitness will
/// be zero") when the task's lowest valid score `floor` is 0; any other failure, or any
/// failure where valid scores may be negative (there 0 would rank the creature above some
/// that did the task), keeps the failure floor.
pub(super) fn scored_if_unstable(mut failure: Evaluation, floor: Option<f64>) -> Evaluation {
    if failure.status == Status::Unstable && floor == Some(0.0) {
        failure.fitness = UNSTABLE_FITNESS;
    }
    failure
}

/// Whole control steps in `seconds` at time step `dt` (at least one when `seconds` > 0).
pub(super) fn steps_in(seconds: f64, dt: f64) -> usize {
    let steps = (seconds / dt - 1e-9).ceil().max(0.0) as usize;
    if seconds > 0.0 { steps.max(1) } else { 0 }
}

/// The most control steps one wait for rest can take: the creature is unstable once it has
/// stepped past `rest.limit`.
pub(super) fn settle_steps(rest: &Rest, dt: f64) -> usize {
    steps_in(rest.limit, dt).saturating_add(1)
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
        let listed = crate::creature::interpenetration_messages(&pairs);
        // The creature's other errors too (more parts than the limit, say).
        let others = errors.iter().filter(|m| !m.contains("interpenetrate"));
        let message = if listed.is_empty() {
            errors.join("; ")
        } else {
            listed
                .iter()
                .map(String::as_str)
                .chain(others.copied())
                .collect::<Vec<_>>()
                .join("; ")
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
pub(super) struct Run<'p> {
    pub(super) world: World,
    pub(super) projectile_size: Option<Vector3<f64>>,
    record: bool,
    recording: Vec<Sample>,
    task: &'static str,
    pub(super) phase: Phase,
    /// Control steps taken.
    steps: usize,
    /// The most control steps the protocol can take (every phase at its longest).
    max_steps: usize,
    /// Every how many steps the recording keeps a sample.
    interval: usize,
    /// The last step's sample when the interval skipped it: kept at the end of the run.
    pending: Option<Sample>,
    /// Steps counted as done: every finished phase at its longest, so the fraction done
    /// grows steadily and ends at 1.
    counted: usize,
    /// Steps taken when the current phase began.
    phase_start: usize,
    /// Told the fraction done, in steps of 0.001 (and 1 at the end).
    progress: &'p mut dyn FnMut(f64),
    /// The last fraction told, in thousandths.
    told: Option<usize>,
    /// Checked before every control step (one atomic load beside a step of physics).
    cancel: Option<&'p Cancel>,
    /// Whether a step found `cancel` set: the evaluation is then interrupted, whatever its
    /// protocol made of the failed step.
    interrupted: bool,
    /// The development that goes on while the controller runs, when the creature grows.
    pub(super) growing: Option<&'p mut super::grow::Growing>,
    /// What growth changed since the last sample kept, when recording a growing creature.
    grew: GrowthRecorder,
}

impl Run<'_> {
    pub(super) fn step(&mut self, controller: bool) -> Result<f64, Evaluation> {
        if self.cancel.is_some_and(Cancel::is_cancelled) {
            self.interrupted = true;
            return Err(Evaluation::failed(
                self.task,
                Status::Invalid,
                Interrupted.to_string(),
            ));
        }
        if matches!(self.phase, Phase::Measuring | Phase::Throwing) {
            // The world's free objects move from the measured part of the task on.
            self.world.release_objects();
        }
        let moved = self.world.step(controller).map_err(|e| {
            Evaluation::failed(
                self.task,
                Status::Exploded,
                format!("{e} at t = {:.3} s", self.world.time()),
            )
        })?;
        self.steps += 1;
        // Development goes on while the controller runs, and pauses while the creature
        // comes to rest.
        if self.phase != Phase::Settling
            && let Some(growing) = self.growing.as_deref_mut()
        {
            let dt = self.world.control_step();
            if self.record {
                self.grew.begin(&self.world);
            }
            let grown = growing.step(&mut self.world, dt).map_err(|e| {
                Evaluation::failed(
                    self.task,
                    Status::Invalid,
                    format!("development failed at t = {:.3} s: {e}", self.world.time()),
                )
            })?;
            if self.record && grown != Grown::default() {
                self.grew.after(&self.world, growing.creature(), &grown);
            }
        }
        if self.record {
            let sample = Sample {
                t: self.world.time(),
                phase: Some(self.phase),
                parts: self
                    .world
                    .part_ids()
                    .map(|id| self.world.part_pose(id))
                    .collect(),
                projectile: self.world.projectile_state().map(|(p, _)| p),
                projectile_size: self.projectile_size,
                objects: self
                    .world
                    .object_positions()
                    .into_iter()
                    .zip(self.world.object_rotations())
                    .map(|(p, [w, i, j, k])| {
                        let q = Quaternion::new(w, i, j, k);
                        (Vector3::from(p), UnitQuaternion::from_quaternion(q))
                    })
                    .collect(),
                growth: Vec::new(),
            };
            self.keep(sample);
        }
        self.tell();
        Ok(moved)
    }

    /// Keeps the sample of step `steps` if the recording's interval falls on it; otherwise
    /// holds it back, in case it is the last.
    fn keep(&mut self, mut sample: Sample) {
        let kept = (self.steps - 1).is_multiple_of(self.interval);
        sample.growth = self.grew.for_sample(kept);
        if kept {
            self.recording.push(sample);
            self.pending = None;
        } else {
            self.pending = Some(sample);
        }
    }

    /// The recording, its last step included.
    fn take_recording(&mut self) -> Vec<Sample> {
        self.recording.extend(self.pending.take());
        std::mem::take(&mut self.recording)
    }

    /// A phase that can take at most `longest` steps is over: it counts as that many.
    fn end_phase(&mut self, longest: usize) {
        self.counted = self.counted.saturating_add(longest);
        self.phase_start = self.steps;
        self.tell();
    }

    /// Tells the progress callback the fraction done, when it has grown by a thousandth (an
    /// interrupted evaluation tells nothing more).
    fn tell(&mut self) {
        if self.interrupted {
            return;
        }
        let done = self.counted.saturating_add(self.steps - self.phase_start);
        let thousandths = ((1000.0 * done as f64 / self.max_steps.max(1) as f64) as usize).min(999);
        if self.told.is_none_or(|told| thousandths > told) {
            self.told = Some(thousandths);
            (self.progress)(thousandths as f64 / 1000.0);
        }
    }

    /// Steps with the controller off for at least `at_least` seconds and until the creature
    /// is at rest; `Unstable` if it is not within the time limit.
    pub(super) fn settle(&mut self, rest: &Rest, at_least: f64, dt: f64) -> Result<(), Evaluation> {
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
                window.extend(self.world.part_ids().map(|id| self.world.part_position(id)));
            }
            let moved = self.step(false)?;
            taken += 1;
            // Calm: every part moves less than Δx per 1/60 s (Chaumont), and none has drifted
            // more than `drift` since the window began (a slowly toppling tower is not at rest).
            let drifted = self
                .world
                .part_ids()
                .zip(&window)
                .any(|(id, at)| (self.world.part_position(id) - at).norm() >= rest.drift);
            calm = if moved < threshold && !drifted {
                calm + 1
            } else {
                0
            };
        }
        Ok(())
    }

    pub(super) fn run_for(
        &mut self,
        seconds: f64,
        controller: bool,
        dt: f64,
    ) -> Result<(), Evaluation> {
        let steps = steps_in(seconds, dt);
        for _ in 0..steps {
            self.step(controller)?;
        }
        self.end_phase(steps);
        Ok(())
    }

    /// The height test again, on the settled creature.
    pub(super) fn check_height(&self, max_height: f64) -> Result<(), Evaluation> {
        let height = self.world.highest_point() - self.world.lowest_point();
        match too_tall(self.task, height, max_height, " after settling") {
            Some(failed) => Err(failed),
            None => Ok(()),
        }
    }
}

/// What a task's settings ([`Task::Options`](super::Task::Options)) bound, which the protocol
/// and the registry read of every task alike.
pub trait Bounds {
    /// The tallest creature simulated (m) and the seconds its measurement may last, both
    /// screened before simulating.
    fn limits(&self) -> (f64, f64);
    /// The most control steps of `dt` the whole protocol can take (every phase at its
    /// longest).
    fn max_steps(&self, dt: f64) -> usize;
    /// The length of its measurement (s), which `--seconds` sets.
    fn seconds(&mut self) -> &mut f64;
    /// Checks the ranges of the settings, the task's table; the error names the key in the
    /// table.
    fn check(&self) -> Result<(), SettingError>;
}

/// [`Bounds::limits`], [`Bounds::max_steps`] and [`Bounds::seconds`] of settings whose height
/// limit is the field `$height`, whose measurement is the field `$seconds` and whose most
/// steps their own `max_steps` counts: `bounds_of!(max_height, seconds);` in their `impl
/// Bounds`, beside their `check`.
macro_rules! bounds_of {
    ($height:ident, $seconds:ident) => {
        fn limits(&self) -> (f64, f64) {
            (self.$height, self.$seconds)
        }
        fn max_steps(&self, dt: f64) -> usize {
            Self::max_steps(self, dt)
        }
        fn seconds(&mut self) -> &mut f64 {
            &mut self.$seconds
        }
    };
}
pub(super) use bounds_of;

/// One evaluation as a task's protocol is given it: the creature, the simulator's settings,
/// the world, the task's settings `O`, and how it is watched. The watch has a lifetime of its
/// own, `'w`, as a [`Watch`] cannot be lent for less than its own: a protocol may evaluate in
/// a world it makes (the swim task's water), which lives less long.
pub struct Setup<'a, 'w, O> {
    /// The creature evaluated.
    pub creature: &'a Creature,
    /// The simulator's settings.
    pub sim: &'a SimOptions,
    /// The world besides the creature.
    pub world: &'a WorldSpec,
    /// The task's settings.
    pub options: &'a O,
    /// Whether it is recorded, who is told its progress and what stops it.
    pub watch: Watch<'w>,
    /// The development that goes on while the creature acts (`develop = "during"`), its
    /// creature `creature`; none when the creature is finished.
    pub growing: Option<&'w mut super::grow::Growing>,
}

/// How an evaluation is watched from outside: whether it is recorded, the callback told the
/// fraction done, and the token that stops it.
pub struct Watch<'p> {
    /// Whether to keep a recording (see [`super::recording_interval`]).
    pub record: bool,
    /// Told the fraction done: from 0, growing by thousandths as the protocol steps (a phase
    /// that ends early counts as done at its longest), and 1 at the end.
    pub progress: &'p mut dyn FnMut(f64),
    /// Set, it stops the evaluation before its next control step with [`Interrupted`].
    pub cancel: Option<&'p Cancel>,
}

impl<'p> Watch<'p> {
    /// A watch without a token: recorded as `record` says, telling `progress` the fraction
    /// done, and never stopped.
    pub fn uncancelled(record: bool, progress: &'p mut dyn FnMut(f64)) -> Watch<'p> {
        Watch {
            record,
            progress,
            cancel: None,
        }
    }
}

/// The evaluation `evaluate` gives with a watch that no one looks at and nothing stops: recorded
/// as `record` says.
pub(super) fn unwatched(
    record: bool,
    evaluate: impl FnOnce(Watch<'_>) -> Result<Evaluation, Interrupted>,
) -> Evaluation {
    uninterrupted(evaluate(Watch::uncancelled(record, &mut |_| {})))
}

/// The evaluation `evaluate` (a task's protocol) gives of `creature` on flat ground, with the
/// simulator's settings `sim` and the task's `options`, watched by no one and stopped by
/// nothing: recorded as `record` says.
pub(super) fn on_flat_ground<O>(
    creature: &Creature,
    sim: &SimOptions,
    options: &O,
    record: bool,
    evaluate: impl FnOnce(Setup<'_, '_, O>) -> Result<Evaluation, Interrupted>,
) -> Evaluation {
    let world = WorldSpec::default();
    unwatched(record, |watch| {
        evaluate(Setup {
            creature,
            sim,
            world: &world,
            options,
            watch,
            growing: None,
        })
    })
}

/// The evaluation of a watch without a token, which nothing can interrupt.
pub(super) fn uninterrupted(evaluation: Result<Evaluation, Interrupted>) -> Evaluation {
    evaluation.expect("an evaluation without a cancellation token is never interrupted")
}

fn start<'p>(
    task: &'static str,
    creature: &Creature,
    (sim, spec): (&SimOptions, &WorldSpec),
    watch: Watch<'p>,
    max_steps: usize,
) -> Result<Run<'p>, Evaluation> {
    let world = World::in_world(creature, sim, spec)
        .map_err(|e| Evaluation::failed(task, Status::Invalid, e.to_string()))?;
    Ok(Run {
        world,
        projectile_size: None,
        record: watch.record,
        recording: Vec::new(),
        task,
        phase: Phase::Settling,
        steps: 0,
        max_steps,
        interval: recording_interval(max_steps),
        pending: None,
        counted: 0,
        phase_start: 0,
        progress: watch.progress,
        told: None,
        cancel: watch.cancel,
        interrupted: false,
        growing: None,
        grew: GrowthRecorder::default(),
    })
}

/// Screens the creature of `setup`, builds its world (the simulator's settings, the world's
/// ground and objects, or its water) and runs `protocol` on it, within the [`Bounds`] of the
/// task's settings, watched as `setup` says; `protocol` returns the fitness and its terms (or
/// a failed evaluation). The progress callback is told 1 at the end. `Interrupted` when the watch's
/// token stopped it.
pub(super) fn evaluate(
    task: &'static str,
    setup: Setup<'_, '_, impl Bounds>,
    protocol: impl FnOnce(&mut Run<'_>) -> Result<(f64, BTreeMap<String, f64>), Evaluation>,
) -> Result<Evaluation, Interrupted> {
    let Setup {
        creature,
        sim,
        world,
        options: bounds,
        watch,
        growing,
    } = setup;
    let Watch {
        record,
        progress,
        cancel,
    } = watch;
    let watch = Watch {
        record,
        progress: &mut *progress,
        cancel,
    };
    let max_steps = bounds.max_steps(sim.control_step);
    let evaluation = evaluate_run(
        task,
        creature,
        (sim, world),
        (watch, max_steps, growing),
        bounds.limits(),
        protocol,
    )?;
    progress(1.0);
    Ok(evaluation)
}

fn evaluate_run<'w>(
    task: &'static str,
    creature: &Creature,
    sim: (&SimOptions, &WorldSpec),
    (watch, max_steps, growing): (Watch<'w>, usize, Option<&'w mut super::grow::Growing>),
    (max_height, seconds): (f64, f64),
    protocol: impl FnOnce(&mut Run<'_>) -> Result<(f64, BTreeMap<String, f64>), Evaluation>,
) -> Result<Evaluation, Interrupted> {
    if let Some(rejected) = screen(task, creature, max_height, seconds) {
        return Ok(rejected);
    }
    let mut run = match start(task, creature, sim, watch, max_steps) {
        Ok(run) => Run { growing, ..run },
        Err(failed) => return Ok(failed),
    };
    let outcome = protocol(&mut run);
    if run.interrupted {
        return Err(Interrupted);
    }
    Ok(match outcome {
        Ok((fitness, mut terms)) => {
            // How far the solver let any joint come apart (m): a diagnostic of the step
            // setting, not part of any fitness.
            terms.insert("joint_gap".into(), run.world.peak_joint_gap());
            // No NaN or infinity leaves an evaluation: JSON cannot hold them.
            if let Some((name, _)) = terms.iter().find(|(_, v)| !v.is_finite()) {
                return Ok(Evaluation::failed(
                    task,
                    Status::Invalid,
                    format!("{name} is not finite"),
                ));
            }
            if !fitness.is_finite() {
                return Ok(Evaluation::failed(
                    task,
                    Status::Invalid,
                    "fitness is not finite".into(),
                ));
            }
            Evaluation {
                task: task.to_string(),
                fitness,
                status: Status::Ok,
                terms,
                message: None,
                recording: run.take_recording(),
                habitats: None,
            }
        }
        Err(mut failed) => {
            // What was recorded up to the failure shows why it failed.
            failed.recording = run.take_recording();
            failed
        }
    })
}
