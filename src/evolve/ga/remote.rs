//! A generation's births over the ranks of an MPI job (the `mpi` feature), in two phases.
//! First rank 0 sends the genomes and their development seeds; the ranks (rank 0's threads
//! among them) develop and key them, each holding the creatures it developed, and send back
//! what rank 0 needs: each birth's key, its creatures' sizes, or why it did not develop. Rank
//! 0 then de-duplicates, as [`Evolution`]'s own batches do (against the cache, and within the
//! generation: the lowest-indexed birth of a key is simulated), and hands out the walks of
//! the births to simulate in the walk order, each to the rank that holds its creature (an
//! index and a unit: a few bytes). A birth's walks are thus done where it was developed; the
//! ranks share the births as they ask for them in the first phase, and keep that share in the
//! second.
//!
//! The individuals, their keys and evaluations are those of a batch on one process: every
//! rank develops and keys as [`Evolution`] does, and an evaluation is a pure function of the
//! creature, its unit and the task. Runs whose keys hash the stored `[task]` tables of a run
//! made before key version 2 stay with [`Evolution`]'s own batches (rank 0 develops and sends
//! creatures).
//!
//! The fine re-walk of a generation's best stays on rank 0: it walks on a thread of its own
//! beside the next generation's batch, which a job sent to a worker would have to wait for.

use std::sync::OnceLock;
use std::time::Instant;

use super::super::cache::EvaluationCache;
use super::super::key::EvaluationKey;
use super::super::mpi::{
    self, Batch, Bytes, Grown, Outcome, Setup, Sizes, Work, encode, key_version_number,
};
use super::super::timing::GenerationTimes;
use super::{Evolution, Individual, Unborn};
use crate::cancel::{Cancel, Interrupted};
use crate::encoding::Genome;
use crate::task::{Evaluation, Unit};

/// Whether `evolution`'s births go to the ranks: on rank 0 of an MPI job of several ranks,
/// for a run whose keys hash no stored `[task]` tables.
pub(super) fn births_go_remote<G: Genome>(evolution: &Evolution<G>) -> bool {
    mpi::is_master() && evolution.key_tables.is_none()
}

/// Where a birth's evaluation comes from.
enum Source {
    /// Simulated now.
    Simulated,
    /// An earlier generation's evaluation of the same key.
    Cached(Evaluation),
    /// The evaluation of the lower-indexed birth of this generation with the same key.
    Sibling(usize),
}

/// A walk of phase two: the birth and its unit.
struct Walk {
    birth: usize,
    unit: Option<Unit>,
}

/// [`Evolution`]'s batch of `unborn` in generation `generation`, over the ranks: the same
/// individuals, keys, evaluations and cache. `times` gets the wall time of the two phases
/// (developing and keying as one, then evaluating) and no walks.
pub(super) fn evaluate_all<G: Genome>(
    evolution: &Evolution<G>,
    unborn: Vec<Unborn<G>>,
    generation: u32,
    cache: &mut EvaluationCache,
    cancel: &Cancel,
    times: &mut GenerationTimes,
) -> Result<Vec<Individual<G>>, Interrupted> {
    cancel.check()?;
    let task = &evolution.task;
    let fresh = task.trials.fresh;
    let version = evolution.key_version;
    mpi::set_setup(Setup::of::<G>(&evolution.limits, task));
    // Phase one: every rank develops and keys births as it asks for them.
    let started = Instant::now();
    let here: Vec<OnceLock<Grown>> = unborn.iter().map(|_| OnceLock::new()).collect();
    let wire = |i: usize, _| Work::Develop {
        genome: Bytes(encode(&unborn[i].genome)),
        seed: unborn[i].develop_seed,
        key_version: key_version_number(version),
    };
    let local = |i: usize, _| {
        let grown = Grown::of(
            &unborn[i].genome,
            &evolution.limits,
            unborn[i].develop_seed,
            task,
            version,
        );
        let sizes = grown.sizes();
        let _ = here[i].set(grown);
        Outcome::Developed(sizes)
    };
    let developed = mpi::run(
        task,
        &Batch {
            holders: vec![None; unborn.len()],
            new_births: true,
            steal: false,
            wire: &wire,
            local: &local,
        },
    );
    times.developing = started.elapsed().as_secs_f64();
    times.keying = 0.0;
    cancel.check()?;
    let (holders, sizes): (Vec<u32>, Vec<Sizes>) = developed
        .into_iter()
        .map(|(rank, outcome)| match outcome {
            Outcome::Developed(sizes) => (rank, sizes),
            _ => mpi::broken(&format!("rank {rank} walked a birth to develop")),
        })
        .unzip();
    let keys: Vec<Option<EvaluationKey>> = sizes.iter().map(|s| s.key.map(EvaluationKey)).collect();
    // De-duplicated as `Evolution`'s own batches are, before any walk.
    let mut first_with = std::collections::HashMap::new();
    let sources: Vec<Source> = keys
        .iter()
        .enumerate()
        .map(|(index, key)| match key {
            Some(key) if cache.enabled() => {
                if let Some(evaluation) = cache.get(key).filter(|_| !fresh) {
                    Source::Cached(evaluation.clone())
                } else if let Some(&first) = first_with.get(key) {
                    Source::Sibling(first)
                } else {
                    first_with.insert(*key, index);
                    Source::Simulated
                }
            }
            _ => Source::Simulated,
        })
        .collect();
    let mut simulated: Vec<Option<Evaluation>> = sizes
        .iter()
        .zip(&sources)
        .map(|(s, source)| match (source, &s.creatures) {
            (Source::Simulated, Err(e)) => Some(Evaluation::invalid(
                task.task.name(),
                format!("development: {e}"),
            )),
            _ => None,
        })
        .collect();
    // Phase two: each simulated birth's walks, handed out in the walk order to its holder.
    let mut walks: Vec<Walk> = Vec::new();
    let mut parts: Vec<usize> = Vec::new();
    let mut owners: Vec<(usize, Vec<Unit>, std::ops::Range<usize>)> = Vec::new();
    for (index, (s, source)) in sizes.iter().zip(&sources).enumerate() {
        let (Source::Simulated, Ok(creatures), Some(key)) = (source, &s.creatures, keys[index])
        else {
            continue;
        };
        let start = walks.len();
        let units = if task.is_plain() {
            walks.push(Walk {
                birth: index,
                unit: None,
            });
            parts.push(creatures.first().map_or(0, |c| c.0 as usize));
            Vec::new()
        } else {
            let units = task.units(key.0, generation);
            for u in &units {
                walks.push(Walk {
                    birth: index,
                    unit: Some(*u),
                });
                parts.push(
                    creatures
                        .get(u.habitat as usize)
                        .map_or(0, |c| c.0 as usize),
                );
            }
            units
        };
        owners.push((index, units, start..walks.len()));
    }
    let order = evolution.walk_order.order(&parts);
    let started = Instant::now();
    // A walk of a birth another rank holds, taken over by a rank that ran out of its own,
    // develops the birth again (a small part of a walk's cost).
    let wire = |h: usize, stolen: bool| {
        let walk = &walks[order[h]];
        let unborn = &unborn[walk.birth];
        match stolen {
            true => Work::GrowAndWalk {
                genome: Bytes(encode(&unborn.genome)),
                seed: unborn.develop_seed,
                key_version: key_version_number(version),
                unit: walk.unit,
            },
            false => Work::WalkHeld {
                birth: walk.birth as u32,
                unit: walk.unit,
            },
        }
    };
    let local = |h: usize, _| {
        let walk = &walks[order[h]];
        let unborn = &unborn[walk.birth];
        let grow = || {
            Grown::of(
                &unborn.genome,
                &evolution.limits,
                unborn.develop_seed,
                task,
                version,
            )
        };
        Outcome::Evaluated(match here[walk.birth].get() {
            Some(grown) => grown.walk(task, walk.unit),
            None => grow().walk(task, walk.unit),
        })
    };
    let walked = mpi::run(
        task,
        &Batch {
            holders: order
                .iter()
                .map(|&j| Some(holders[walks[j].birth]))
                .collect(),
            new_births: false,
            steal: true,
            wire: &wire,
            local: &local,
        },
    );
    times.evaluating = started.elapsed().as_secs_f64();
    // Told to stop while the walks went on: nothing of this generation is kept.
    cancel.check()?;
    times.walks = Vec::new();
    let mut evaluations: Vec<Option<Evaluation>> = vec![None; walks.len()];
    for (&j, (rank, outcome)) in order.iter().zip(walked) {
        evaluations[j] = Some(match outcome {
            Outcome::Evaluated(evaluation) => evaluation,
            _ => mpi::broken(&format!("rank {rank} developed a walk")),
        });
    }
    let mut evaluations: Vec<Evaluation> = evaluations
        .into_iter()
        .map(|e| e.unwrap_or_else(|| mpi::broken("a walk has no evaluation")))
        .collect();
    for (index, units, range) in owners.into_iter().rev() {
        let mine: Vec<Evaluation> = evaluations.drain(range).collect();
        simulated[index] = match &sizes[index].creatures {
            Ok(creatures) if !units.is_empty() => Some(task.combine_sizes(&units, mine, creatures)),
            _ => mine.into_iter().next(),
        };
    }
    let mut born = Vec::with_capacity(unborn.len());
    for (index, ((u, s), source)) in unborn.into_iter().zip(&sizes).zip(sources).enumerate() {
        let missing = || mpi::broken(&format!("birth {index} has no evaluation"));
        let (evaluation, reused) = match source {
            Source::Simulated => (simulated[index].clone().unwrap_or_else(missing), false),
            Source::Cached(evaluation) => (evaluation, true),
            Source::Sibling(first) => (simulated[first].clone().unwrap_or_else(missing), true),
        };
        if let (Some(key), false, false) = (keys[index], reused, fresh) {
            cache.insert(key, &evaluation);
        }
        let size = s.size();
        born.push(Individual {
            genome: u.genome,
            develop_seed: u.develop_seed,
            parents: u.parents,
            operator: u.operator,
            evaluation,
            size,
            key: keys[index],
            reused,
            parents_generation: generation.checked_sub(1),
        });
    }
    Ok(born)
}
