//! Recordings: the pose of every part at evenly spaced moments of an evaluation ([`Sample`])
//! and the stage of the protocol it is in ([`Phase`]), how many of them a recording keeps, and
//! the `recording.json` file ([`Recording`]) that `eval --record` writes and `replay` and
//! `view` read.

use std::borrow::Cow;

use nalgebra::{UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

use super::compact;
use super::recorded_growth::{BodyChange, GrowingBody, check_growth};
use super::{Evaluation, Status};
use crate::creature::Creature;
use crate::sim::WorldSpec;

/// Which stage of a task's protocol a recorded sample belongs to.
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

/// The most samples a recording holds. A run that may take more control steps keeps one step
/// in every [`recording_interval`], chosen before the run from its longest possible duration,
/// so the samples stay evenly spaced in time; the first and the last step are always kept.
/// 12,000 samples are 200 s at 1/60 s per step (every step of the default walker, jump and
/// catapult), about 11 MB of `recording.json` for a 10-part creature; an hour's walk keeps
/// one step in 19 (a sample every 0.32 s).
pub const MAX_RECORDED_SAMPLES: usize = 12_000;

/// [`MAX_RECORDED_SAMPLES`] under its former name, for existing callers.
pub const MAX_RECORDED_FRAMES: usize = MAX_RECORDED_SAMPLES;

/// Every how many control steps a recording keeps a sample, for a run of at most `max_steps`
/// steps: 1 (every step) when they fit in [`MAX_RECORDED_SAMPLES`]; otherwise the least k for
/// which the kept steps 1, 1 + k, 1 + 2k, ... and the last step fit.
pub fn recording_interval(max_steps: usize) -> usize {
    if max_steps <= MAX_RECORDED_SAMPLES {
        1
    } else {
        max_steps.div_ceil(MAX_RECORDED_SAMPLES - 1)
    }
}

/// [`Sample`] under its former name, for existing callers.
pub type RecordedFrame = Sample;

/// A sample of a recording: the poses of every part at one moment (in `recording.json`, one
/// element of `frames`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sample {
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
    /// The world's free objects' centres and orientations, in the order of
    /// [`WorldSpec::objects`] (empty, and not written, in a world without objects).
    #[serde(
        skip_serializing_if = "Vec::is_empty",
        default,
        serialize_with = "compact::poses"
    )]
    pub objects: Vec<(Vector3<f64>, UnitQuaternion<f64>)>,
    /// What changed in a growing body since the sample before: parts that appeared, were
    /// resized or stopped growing (empty, and not written, for a body that does not grow).
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub growth: Vec<BodyChange>,
}

/// The `recording.json` file `eval --record` writes and `replay` and `view` read: the creature
/// as built, the evaluation's task, status and message, the aim task's target, and the
/// samples. Written with the keys in this order, the poses at f32 precision. The creature and
/// the samples are borrowed when writing (a recording may hold 12,000 samples) and owned when
/// read.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Recording<'a> {
    /// The creature as built, before it was simulated.
    pub creature: Cow<'a, Creature>,
    /// The task's name (absent from some hand-written files).
    #[serde(default)]
    pub task: String,
    /// How the evaluation ended (absent from files written before it was recorded).
    #[serde(default)]
    pub status: Option<Status>,
    /// What went wrong, when something did.
    #[serde(default)]
    pub message: Option<String>,
    /// The evaluation's fitness (absent from files written before it was recorded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fitness: Option<f64>,
    /// The aim task's target in the world (null for other tasks).
    #[serde(default)]
    pub target: Option<[f64; 3]>,
    /// The samples, in time order (the file's `frames`).
    #[serde(rename = "frames", default)]
    pub samples: Cow<'a, [Sample]>,
    /// The task's world (`[task.world]`), when it is not the flat world (absent, and not
    /// written, for a flat one).
    #[serde(default, skip_serializing_if = "WorldSpec::is_flat")]
    pub world: WorldSpec,
}

impl<'a> Recording<'a> {
    /// The recording of `evaluation` of `creature`, borrowing both. The target is the one in
    /// the terms of every aim evaluation that got as far as placing the projectile, failed or
    /// not.
    pub fn of(creature: &'a Creature, evaluation: &'a Evaluation) -> Recording<'a> {
        let term = |name: &str| evaluation.terms.get(name).copied();
        let target = match (term("target_x"), term("target_y"), term("target_z")) {
            (Some(x), Some(y), Some(z)) => Some([x, y, z]),
            _ => None,
        };
        Recording {
            creature: Cow::Borrowed(creature),
            task: evaluation.task.clone(),
            status: Some(evaluation.status),
            message: evaluation.message.clone(),
            fitness: Some(evaluation.fitness),
            target,
            samples: Cow::Borrowed(&evaluation.recording),
            world: WorldSpec::default(),
        }
    }

    /// The recording, in `world` (the task's [`crate::task::TaskSpec::world`]).
    pub fn in_world(self, world: &WorldSpec) -> Recording<'a> {
        Recording {
            world: world.clone(),
            ..self
        }
    }

    /// The aim task's target as a point, when there is one.
    pub fn target_point(&self) -> Option<Vector3<f64>> {
        self.target.map(|[x, y, z]| Vector3::new(x, y, z))
    }

    /// Whether the body grows during the recording (some sample records a change).
    pub fn grows(&self) -> bool {
        self.samples.iter().any(|s| !s.growth.is_empty())
    }

    /// Why the recording's growth cannot be read, if it cannot: a part that appears out of
    /// turn or changes before it appears, or a sample posing more parts than the body has.
    pub fn check_growth(&self) -> Result<(), String> {
        let samples = self.samples.iter();
        check_growth(
            &self.creature,
            samples.map(|s| (s.growth.as_slice(), s.parts.len())),
        )
    }

    /// The body at each sample, the creature as dropped grown as the samples say.
    pub fn bodies(&self) -> GrowingBody<'_> {
        let growth = self.samples.iter().map(|s| s.growth.as_slice()).collect();
        GrowingBody::new(&self.creature, growth)
    }

    /// The status as files spell it (`"self-intersecting"`), when the file holds one.
    pub fn status_name(&self) -> Option<&'static str> {
        self.status.map(Status::name)
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::develop::creature_from_commands;

    #[test]
    fn a_world_and_its_objects_are_written_only_when_there_are_some() {
        let creature = creature_from_commands("forward(1)").unwrap();
        let mut evaluation = Evaluation {
            task: "walker".into(),
            fitness: 1.0,
            status: Status::Ok,
            terms: BTreeMap::new(),
            message: None,
            recording: vec![Sample {
                t: 0.0,
                phase: None,
                parts: vec![(Vector3::zeros(), UnitQuaternion::identity())],
                projectile: None,
                projectile_size: None,
                objects: Vec::new(),
                growth: Vec::new(),
            }],
            habitats: None,
        };
        let flat = serde_json::to_string(&Recording::of(&creature, &evaluation)).unwrap();
        assert!(
            !flat.contains("world") && !flat.contains("objects"),
            "{flat}"
        );
        evaluation.recording[0].objects =
            vec![(Vector3::new(1.0, 0.5, 0.0), UnitQuaternion::identity())];
        let world: WorldSpec = toml::from_str(
            "objects = [{ shape = \"ball\", size = 0.25, mass = 1, position = [1, 0.5, 0] }]",
        )
        .unwrap();
        let text =
            serde_json::to_string(&Recording::of(&creature, &evaluation).in_world(&world)).unwrap();
        assert!(
            text.contains(r#""objects":[[[1.0,0.5,0.0],[0.0,0.0,0.0,1.0]]]"#),
            "{text}"
        );
        let back: Recording = serde_json::from_str(&text).unwrap();
        assert_eq!(back.world, world);
        assert_eq!(back.samples[0].objects, evaluation.recording[0].objects);
        let old: Recording = serde_json::from_str(&flat).unwrap();
        assert!(old.world.is_flat() && old.samples[0].objects.is_empty());
    }

    #[test]
    fn a_recording_is_written_in_its_key_order_and_reads_back() {
        let creature = creature_from_commands("forward(1)").unwrap();
        let evaluation = Evaluation {
            task: "aim".into(),
            fitness: 1.0,
            status: Status::Ok,
            terms: BTreeMap::from([
                ("target_x".to_string(), 5.0),
                ("target_y".to_string(), 0.5),
                ("target_z".to_string(), 0.0),
            ]),
            message: None,
            recording: vec![Sample {
                t: 0.1,
                phase: Some(Phase::Flying),
                parts: vec![(Vector3::new(0.1, 0.2, 0.3), UnitQuaternion::identity())],
                projectile: None,
                projectile_size: None,
                objects: Vec::new(),
                growth: Vec::new(),
            }],
            habitats: None,
        };
        let text = serde_json::to_string(&Recording::of(&creature, &evaluation)).unwrap();
        let keys = [
            "creature", "task", "status", "message", "fitness", "target", "frames",
        ];
        let at: Vec<usize> = keys
            .iter()
            .map(|k| text.find(&format!("\"{k}\":")).unwrap())
            .collect();
        assert!(at.windows(2).all(|w| w[0] < w[1]), "{text}");
        assert!(text.contains(
            r#""task":"aim","status":"ok","message":null,"fitness":1.0,"target":[5.0,0.5,0.0]"#
        ));
        // Poses at f32 precision, as the physics computed them.
        assert!(
            text.contains(r#""parts":[[[0.1,0.2,0.3],[0.0,0.0,0.0,1.0]]]"#),
            "{text}"
        );
        let back: Recording = serde_json::from_str(&text).unwrap();
        assert_eq!(back.samples.as_ref(), evaluation.recording.as_slice());
        assert_eq!(back.target_point(), Some(Vector3::new(5.0, 0.5, 0.0)));
        // A file without task, status, message or target (hand-written, or from before they
        // were recorded) still reads.
        let old = format!(
            r#"{{"creature": {}}}"#,
            serde_json::to_string(&creature).unwrap()
        );
        let old: Recording = serde_json::from_str(&old).unwrap();
        assert!(old.samples.is_empty() && old.status.is_none() && old.target.is_none());
    }
}
