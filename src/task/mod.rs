//! Tasks: the seed papers' protocols and fitness formulas, with the guards against cheating
//! and numerical explosion. Every task takes a [`Creature`](crate::creature::Creature) and
//! gives an [`Evaluation`].
//!
//! This module keeps what every task shares (the failure floor, [`Status`], [`Evaluation`]);
//! each task has its own file ([`walker`](walker()), [`jump`](jump()), [`catapult`](catapult()),
//! aim, stand and swim), implements [`Task`] and has one line in the registry
//! ([`for_each_task!`](crate::for_each_task)), the protocol's common steps (screening, waiting for rest, recording) are in
//! `protocol`, the recording's file format in `recording`, and a task's specification as data
//! in [`TaskSpec`]: the simulator's settings and one task's ([`TaskOptions`]), read from a
//! `[task]` table that may hold several tasks' ([`TaskTables`]), the habitats one evaluation spans in `habitat` and the noisy trials drawn in each in `trials`.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

mod aim;
mod catapult;
mod check;
mod compact;
mod fitness;
mod grow;
mod habitat;
mod jump;
mod options;
mod protocol;
mod recorded_growth;
mod recording;
mod registry;
mod rested;
mod spec;
mod stand;
mod swim;
mod tables;
mod trials;
mod walker;
pub use aim::AimTask;
pub use catapult::{CatapultOptions, CatapultTask, catapult, distance_to_trajectory};
pub use check::{MAX_SECONDS, check_duration};
pub use fitness::{Fitness, FitnessExpression, PROTOCOL_TERMS};
pub use grow::{
    DEFAULT_RATE, Develop, DevelopWhen, GrowError, Growing, GrowthTally, check_continuous,
};
pub use habitat::{Habitat, HabitatResult, MAX_HABITATS, Noise, Unit};
pub use jump::{JumpOptions, JumpTask, jump};
pub use options::TaskOptions;
pub use protocol::{Bounds, Rest, Setup, Watch};
pub use recorded_growth::{BodyChange, GrowingBody};
pub use recording::{
    MAX_RECORDED_FRAMES, MAX_RECORDED_SAMPLES, Phase, RecordedFrame, Recording, Sample,
    recording_interval,
};
pub use registry::{TASKS, Task, TaskInfo, keyword_refusal, task_named, tasks_reading};
pub use rested::RestedOptions;
pub use spec::{TaskKind, TaskSpec};
pub use stand::{StandOptions, StandTask};
pub use swim::{SwimOptions, SwimTask, swim_viscosity};
pub use tables::TaskTables;
pub use trials::{Aggregate, MAX_TRIALS, Perturbation, Trials};
pub use walker::{
    WalkerFitness, WalkerOptions, WalkerTask, iterative_move, size_coefficients, walker,
};

/// The fitness of every failed evaluation, whatever the task: Walking with Dinosaurs' value
/// for illegal creatures (3.5.1), and Chaumont et al.'s "arbitrary low value" (5.4). Every
/// valid score of every task is above it: walker, catapult and jump scores are never
/// negative, except the walker's Hornby & Pollack score, held at −[`MAX_TARGET_DISTANCE`] or
/// above, and an aim score D_p − D_t is at least −D_t ≥ −|target| > −[`MAX_TARGET_DISTANCE`].
pub const FAILURE_FITNESS: f64 = -999_999.0;

/// The fitness of a creature that never comes to rest when its protocol needs it to, in a
/// task whose valid scores are never negative (the walker but for Hornby & Pollack's
/// formula and fitness expressions, jump, stand): Chaumont et al. 3.3, "such individuals
/// will never be considered stable, and no distance will ever be recorded for them, so their
/// fitness will be zero". Every other failure scores [`FAILURE_FITNESS`] (5.4's "arbitrary
/// low value" for explosions), and so does an unstable creature where a valid score may be
/// negative (there 0 would rank it above creatures that did the task).
pub const UNSTABLE_FITNESS: f64 = 0.0;

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

impl Status {
    /// The status as reports and files spell it (`"self-intersecting"`).
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Unstable => "unstable",
            Status::Exploded => "exploded",
            Status::SelfIntersecting => "self-intersecting",
            Status::TooTall => "too-tall",
            Status::Invalid => "invalid",
        }
    }
}

/// The outcome of one evaluation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// The task's name.
    pub task: String,
    /// The fitness; [`FAILURE_FITNESS`] unless the status is `ok`, but for a creature that
    /// never came to rest in a task whose valid scores are never negative (`unstable`,
    /// [`UNSTABLE_FITNESS`], 0: Chaumont et al. 3.3).
    pub fitness: f64,
    /// How it ended.
    pub status: Status,
    /// The terms behind the fitness (D_w, C_l, C_s, C_v, N, ...).
    pub terms: BTreeMap<String, f64>,
    /// What went wrong, when something did.
    pub message: Option<String>,
    /// The recorded samples (every part's pose at evenly spaced moments), when recording was
    /// asked for.
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub recording: Vec<Sample>,
    /// Each habitat's and trial's result, habitat by habitat, when the specification has
    /// habitats or trials (the fitness is then their aggregate); none, and not written, for
    /// a plain one.
    /// (Boxed, so that an evaluation stays small where it is returned as an error.)
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub habitats: Option<Box<Vec<HabitatResult>>>,
}

impl Evaluation {
    /// Each habitat's and trial's result (none for a plain specification).
    pub fn units(&self) -> &[HabitatResult] {
        self.habitats.as_deref().map_or(&[], Vec::as_slice)
    }

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
            habitats: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Status;

    #[test]
    fn a_status_is_named_as_its_json_spells_it() {
        for status in [
            Status::Ok,
            Status::Unstable,
            Status::Exploded,
            Status::SelfIntersecting,
            Status::TooTall,
            Status::Invalid,
        ] {
            assert_eq!(
                serde_json::to_value(status).unwrap(),
                serde_json::json!(status.name())
            );
        }
    }
}
