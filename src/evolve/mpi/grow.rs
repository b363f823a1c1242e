//! A birth developed and keyed on a worker rank (or on rank 0's threads), as the two-phase
//! batches of the genetic algorithm hand them out over an MPI job: what a worker needs to
//! develop a run's genomes ([`Setup`]), what it holds ([`Grown`]) and what rank 0 learns of it
//! ([`Sizes`]).

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::super::evaluator::Job;
use super::super::habitats::develop_with_seedlings;
use super::super::key::{EvaluationKey, KeyVersion};
use super::{Bytes, encode};
use crate::creature::Creature;
use crate::develop::Seedling;
use crate::encoding::{Genome, Purpose};
use crate::task::{Evaluation, TaskSpec, Unit, Watch};

/// What a worker needs to develop a run's genomes: the encoding's name and its limits.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(in crate::evolve) struct Setup {
    /// The encoding's name ([`Genome::NAME`]).
    pub encoding: String,
    /// Its limits, as MessagePack (without the settings serde skips: `environment_reads` and
    /// `projectile` only steer the operators, which run on rank 0, and the purpose is
    /// `throwing`).
    pub limits: Bytes,
    /// Whether the run's task throws ([`Genome::adapt_limits`] with [`Purpose::Throwing`]).
    pub throwing: bool,
}

impl Setup {
    /// The setup of genomes `G` within `limits` for `task`.
    pub(in crate::evolve) fn of<G: Genome>(limits: &G::Limits, task: &TaskSpec) -> Setup {
        Setup {
            encoding: G::NAME.to_string(),
            limits: Bytes(encode(limits)),
            throwing: task.task.throws(),
        }
    }
}

/// What rank 0 learns of a birth developed on some rank.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(in crate::evolve) struct Sizes {
    /// Its key (`None` when it did not develop).
    pub key: Option<[u8; 32]>,
    /// Its creatures' parts and joints, one per habitat; or why it did not develop.
    pub creatures: Result<Vec<(u32, u32)>, String>,
    /// The neurons of its first creature (0 when it did not develop).
    pub neurons: u32,
}

impl Sizes {
    /// Its first creature's parts and joints and its neurons, as an individual records its
    /// size (zeros when it did not develop).
    pub(in crate::evolve) fn size(&self) -> (u32, u32, u32) {
        match &self.creatures {
            Ok(creatures) => creatures
                .first()
                .map_or((0, 0, 0), |c| (c.0, c.1, self.neurons)),
            Err(_) => (0, 0, 0),
        }
    }
}

/// A birth developed and keyed, held by the rank that developed it.
pub(in crate::evolve) struct Grown {
    /// Its creatures, one per habitat, or why it did not develop.
    creatures: Result<Vec<Creature>, String>,
    /// What they grow from during their evaluation (`develop = "during"`; none otherwise).
    seedlings: Vec<Seedling>,
    /// Its key (`None` when it did not develop).
    key: Option<EvaluationKey>,
}

impl Grown {
    /// `genome` developed with `seed` in `task`'s habitats and keyed with keys of `version`,
    /// as the genetic algorithm develops and keys a birth of a run whose keys hash no stored tables.
    pub(in crate::evolve) fn of<G: Genome>(
        genome: &G,
        limits: &G::Limits,
        seed: u64,
        task: &TaskSpec,
        version: KeyVersion,
    ) -> Grown {
        let (creatures, seedlings) = match develop_with_seedlings(genome, limits, seed, task) {
            Ok((creatures, seedlings)) => (Ok(creatures), seedlings),
            Err(e) => (Err(e.to_string()), Vec::new()),
        };
        let key = creatures
            .as_ref()
            .ok()
            .map(|c| EvaluationKey::of_habitats(c, task, version).growing(task, genome));
        Grown {
            creatures,
            seedlings,
            key,
        }
    }

    /// What rank 0 needs of it.
    pub(in crate::evolve) fn sizes(&self) -> Sizes {
        Sizes {
            key: self.key.map(|k| k.0),
            creatures: match &self.creatures {
                Ok(creatures) => Ok(creatures
                    .iter()
                    .map(|c| (c.parts.len() as u32, c.joints.len() as u32))
                    .collect()),
                Err(e) => Err(e.clone()),
            },
            neurons: match &self.creatures {
                Ok(creatures) => creatures.first().map_or(0, |c| c.neuron_count() as u32),
                Err(_) => 0,
            },
        }
    }

    /// The evaluation of its walk on `unit` (`None`: a plain task's one walk) with `task`.
    pub(in crate::evolve) fn walk(&self, task: &TaskSpec, unit: Option<Unit>) -> Evaluation {
        let habitat = unit.map_or(0, |u| u.habitat as usize);
        let Some(creature) = self.creatures.as_ref().ok().and_then(|c| c.get(habitat)) else {
            return Evaluation::invalid(task.task.name(), "no creature to walk".to_string());
        };
        let job = Job {
            creature,
            unit,
            seedling: self.seedlings.get(habitat),
        };
        job.evaluate(task, Watch::uncancelled(false, &mut |_| {}))
            .unwrap_or_else(|_| Evaluation::invalid(task.task.name(), "interrupted".to_string()))
    }
}

impl Grown {
    /// Its evaluation as a steady-state run evaluates a birth
    /// ([`super::super::steady::evaluate_birth`]: its walks one after another on this
    /// thread).
    pub(in crate::evolve) fn evaluate_as_birth(&self, task: &TaskSpec) -> Evaluation {
        super::super::steady::evaluate_birth(task, &self.creatures, &self.seedlings, self.key, None)
            .expect("an evaluation without a cancellation token is never interrupted")
    }

    /// Its key, if it developed.
    pub(in crate::evolve) fn key(&self) -> Option<EvaluationKey> {
        self.key
    }
}

/// Develops genomes of one encoding from their MessagePack, for a worker that knows the
/// encoding by its name alone.
pub(in crate::evolve) trait Grower: Send + Sync {
    /// The genome encoded as `genome` developed with `seed` in `task`'s habitats and keyed
    /// with keys of version `key_version` (1 or 2); the error says why it did not decode.
    fn grow(
        &self,
        genome: &[u8],
        seed: u64,
        key_version: u8,
        task: &TaskSpec,
    ) -> Result<Grown, String>;
}

/// The [`Grower`] of genomes `G` within `limits`.
struct GrowerOf<G: Genome> {
    limits: G::Limits,
}

impl<G: Genome> GrowerOf<G> {
    fn decode(genome: &[u8]) -> Result<G, String> {
        rmp_serde::from_slice(genome).map_err(|e| {
            format!(
                "cannot decode a {} genome (are all ranks the same ontogeny build?): {e}",
                G::NAME
            )
        })
    }
}

impl<G: Genome> Grower for GrowerOf<G> {
    fn grow(
        &self,
        genome: &[u8],
        seed: u64,
        key_version: u8,
        task: &TaskSpec,
    ) -> Result<Grown, String> {
        let version = key_version_of(key_version)?;
        let genome = Self::decode(genome)?;
        Ok(Grown::of(&genome, &self.limits, seed, task, version))
    }
}

/// The [`Grower`] of the encoding and limits `setup` names; the error says why there is
/// none.
pub(in crate::evolve) fn grower(setup: &Setup) -> Result<Arc<dyn Grower>, String> {
    crate::with_genome!(
        setup.encoding.as_str(),
        G => {
            let mut limits: <G as Genome>::Limits = rmp_serde::from_slice(&setup.limits.0)
                .map_err(|e| format!("cannot decode the limits of encoding {}: {e}", G::NAME))?;
            let purpose = match setup.throwing {
                true => Purpose::Throwing,
                false => Purpose::Locomotion,
            };
            G::adapt_limits(&mut limits, purpose);
            Ok(Arc::new(GrowerOf::<G> { limits }) as Arc<dyn Grower>)
        },
        |other| Err(format!("rank 0 sent genomes of an unknown encoding, {other}"))
    )
}

/// The number a key version travels as ([`super::Work::Develop`]), which
/// [`key_version_of`] reads back.
pub(in crate::evolve) fn key_version_number(version: KeyVersion) -> u8 {
    match version {
        KeyVersion::V1 => 1,
        KeyVersion::V2 => 2,
    }
}

/// The key version [`Work::Develop`] carries as `number`; the error names an unknown one.
pub(in crate::evolve) fn key_version_of(number: u8) -> Result<KeyVersion, String> {
    match number {
        1 => Ok(KeyVersion::V1),
        2 => Ok(KeyVersion::V2),
        other => Err(format!(
            "rank 0 sent key version {other}, which this build does not know"
        )),
    }
}
