//! The messages between rank 0 and a worker, as MessagePack: what rank 0 asks a worker to
//! do ([`Work`], in a [`Reply`]) and what comes back ([`Outcome`], in a [`Request`]).
//! MessagePack carries every `f64` and `f32` exactly (NaN included): an evaluation made on a
//! worker is bit-identical to one made on rank 0.

use serde::{Deserialize, Serialize};

use crate::task::{Evaluation, Unit};

use super::grow::Sizes;

/// Bytes already encoded (a genome, an encoding's limits), which MessagePack carries as one
/// binary string rather than as an array of numbers.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(in crate::evolve) struct Bytes(pub Vec<u8>);

impl Serialize for Bytes {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_bytes(&self.0)
    }
}

impl<'de> Deserialize<'de> for Bytes {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Bytes, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Bytes;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a binary string")
            }
            fn visit_bytes<E: serde::de::Error>(self, bytes: &[u8]) -> Result<Bytes, E> {
                Ok(Bytes(bytes.to_vec()))
            }
            fn visit_byte_buf<E: serde::de::Error>(self, bytes: Vec<u8>) -> Result<Bytes, E> {
                Ok(Bytes(bytes))
            }
        }
        deserializer.deserialize_byte_buf(Visitor)
    }
}

/// One job as rank 0 sends it (`C`: a creature, owned or borrowed).
#[derive(Debug, PartialEq, Serialize, Deserialize)]
pub(in crate::evolve) enum Work<C> {
    /// Walk this creature on this unit (`None`: a plain task's one walk).
    Walk(C, Option<Unit>),
    /// Develop this genome (its MessagePack) with this development seed in the task's
    /// habitats, key it (key version 1 or 2, [`super::super::key::KeyVersion`]), and hold it
    /// as birth number the job's index of the current births.
    Develop {
        /// The genome, encoded.
        genome: Bytes,
        /// Its development seed.
        seed: u64,
        /// The version of its key.
        key_version: u8,
    },
    /// Walk the creature this rank holds as birth `birth` of the current births, on `unit`.
    WalkHeld {
        /// The birth, by its index in the batch that developed it.
        birth: u32,
        /// The unit (`None`: a plain task's one walk).
        unit: Option<Unit>,
    },
    /// Develop this genome with this development seed and walk its creature on `unit`: the
    /// walk of a birth another rank holds, taken over by a rank that has run out of its own.
    GrowAndWalk {
        /// The genome, encoded.
        genome: Bytes,
        /// Its development seed.
        seed: u64,
        /// The version of its key (as in [`Work::Develop`]).
        key_version: u8,
        /// The unit (`None`: a plain task's one walk).
        unit: Option<Unit>,
    },
    /// Develop and key this genome with this development seed, and evaluate it as a
    /// steady-state run evaluates a birth (its walks one after another on one thread), unless
    /// a generation up to `source` stored its key (then rank 0 gives it that evaluation).
    Birth {
        /// The genome, encoded.
        genome: Bytes,
        /// Its development seed.
        seed: u64,
        /// The version of its key (as in [`Work::Develop`]).
        key_version: u8,
        /// s(b): the generation it was bred from.
        source: u32,
    },
}

/// What a job gives.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(in crate::evolve) enum Outcome {
    /// An evaluation of a walk.
    Evaluated(Evaluation),
    /// A birth developed and keyed: what rank 0 needs of it.
    Developed(Sizes),
    /// A steady-state birth developed, keyed and evaluated ([`Work::Birth`]).
    Born {
        /// What rank 0 needs of its creatures.
        sizes: Sizes,
        /// Its evaluation, or `None`: its key was stored up to its source generation.
        evaluation: Option<Evaluation>,
        /// The wall time of its development and walks, in seconds.
        seconds: f64,
        /// The worker's thread that made it.
        thread: u32,
    },
}

/// What a worker sends rank 0.
#[derive(Serialize, Deserialize)]
pub(super) struct Request {
    /// The worker's number of threads.
    pub threads: u32,
    /// Outcomes finished since its last request, by job index in the batch.
    pub outcomes: Vec<(u32, Outcome)>,
}

/// What rank 0 sends a worker (`C`, `T` and `S`: a creature, a task and a setup, owned or
/// borrowed).
#[derive(Serialize, Deserialize)]
pub(super) enum Reply<C, T, S> {
    /// Jobs of the current batch, by index, with what the worker lacks to do them.
    Work {
        /// The task, when it differs from the one the worker has.
        task: Option<T>,
        /// The encoding and its limits, when they differ from the ones the worker has.
        setup: Option<S>,
        /// The number of the births the jobs develop or walk: a worker forgets the creatures
        /// it held when it changes.
        births: u64,
        /// The jobs, by index.
        jobs: Vec<(u32, Work<C>)>,
        /// Keys stored since the last reply, each with the first generation that stored it,
        /// for the worker's copy of a steady-state run's lookup ([`Work::Birth`]): 36 bytes
        /// each, the key's 32 then the generation's 4, little-endian. A worker forgets its
        /// copy when `births` changes.
        known: Bytes,
        /// Whether these are the worker's last jobs of the batch: it then sends its next
        /// request once it has done every job it holds, not when it runs low.
        last: bool,
    },
    /// No more work: the worker ends.
    Stop,
}

/// `value` as MessagePack (structures as maps, by field name).
pub(in crate::evolve) fn encode<T: Serialize + ?Sized>(value: &T) -> Vec<u8> {
    rmp_serde::to_vec_named(value).expect("plain data encodes as MessagePack")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::creature::Creature;
    use crate::develop::{BuildOptions, grow};
    use crate::evolve::mpi::Setup;
    use crate::lsystem::{DeriveOptions, LSystem};
    use crate::sim::WorldSpec;
    use crate::sim::world_spec::Slope;
    use crate::task::TaskSpec;
    use crate::task::{Habitat, Status, TaskKind};

    /// A creature with real numbers in it: the shipped Hornby & Pollack walker, grown.
    fn walker() -> Creature {
        let lsys = LSystem::from_text(
            "hornby-walker.lsys",
            include_str!("../../../examples/hornby-walker.lsys"),
        )
        .unwrap();
        let frames = grow(
            &lsys,
            &DeriveOptions::default(),
            None,
            &BuildOptions::default(),
        )
        .unwrap();
        frames.into_iter().last().unwrap().creature
    }

    #[test]
    fn a_job_and_its_evaluation_cross_between_ranks_bit_for_bit() {
        let creature = walker();
        assert!(!creature.parts.is_empty());
        let mut task = TaskSpec::new(TaskKind::Walker);
        *task.seconds_mut() = 1.0 / 3.0;
        // A habitat on a slope, two noisy trials: the unit and its world cross too.
        task.habitats = vec![Habitat {
            name: "hill".into(),
            world: WorldSpec {
                slope: Some(Slope {
                    degrees: 5.0,
                    direction: 0.0,
                }),
                ..WorldSpec::default()
            },
            environment: None,
            trials: None,
        }];
        task.trials.count = 2;
        task.trials.heading = 10.0;
        let unit = task.units([3; 32], 0)[1];
        let sent: Reply<&Creature, &TaskSpec, &Setup> = Reply::Work {
            task: Some(&task),
            setup: None,
            births: 4,
            jobs: vec![(7, Work::Walk(&creature, Some(unit)))],
            known: Bytes(vec![9; 36]),
            last: true,
        };
        let bytes = encode(&sent);
        let Reply::Work {
            task: Some(received_task),
            setup: None,
            births: 4,
            jobs,
            known,
            last: true,
        } = rmp_serde::from_slice::<Reply<Creature, TaskSpec, Setup>>(&bytes).unwrap()
        else {
            panic!("not the work sent");
        };
        assert_eq!(jobs, vec![(7, Work::Walk(creature.clone(), Some(unit)))]);
        assert_eq!(known, Bytes(vec![9; 36]));
        let Work::Walk(received, received_unit) = &jobs[0].1 else {
            panic!("not a walk");
        };
        assert_eq!(encode(&received_task), encode(&task));
        assert_eq!(received_task.habitats, task.habitats);
        // The task evaluates the received creature and unit as it does the originals.
        let evaluation = task.evaluate_job_plainly(&creature, Some(&unit));
        assert_eq!(
            received_task.evaluate_job_plainly(received, received_unit.as_ref()),
            evaluation
        );
        // Every f64, even those JSON cannot carry, comes back with the same bits.
        let odd = [
            f64::NAN,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.1 + 0.2,
            5e-324,
        ];
        let mut strange = Evaluation {
            status: Status::Unstable,
            ..evaluation
        };
        for (i, value) in odd.iter().enumerate() {
            strange.terms.insert(format!("t{i}"), *value);
        }
        let request = Request {
            threads: 3,
            outcomes: vec![(7, Outcome::Evaluated(strange.clone()))],
        };
        let back: Request = rmp_serde::from_slice(&encode(&request)).unwrap();
        assert_eq!(back.threads, 3);
        let (index, Outcome::Evaluated(returned)) = &back.outcomes[0] else {
            panic!("not an evaluation");
        };
        assert_eq!(*index, 7);
        assert_eq!(returned.fitness.to_bits(), strange.fitness.to_bits());
        for (name, value) in &strange.terms {
            assert_eq!(returned.terms[name].to_bits(), value.to_bits(), "{name}");
        }
    }
}
