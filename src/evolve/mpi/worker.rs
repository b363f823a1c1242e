//! A worker rank's side of the job: it asks rank 0 for work, does it on its threads, holds
//! the creatures it develops until rank 0 starts new births, and sends the outcomes back.
//! For a steady-state run it keeps a copy of the keys rank 0 has stored, each with the first
//! generation that stored it, so that a birth whose creature is stored is not walked.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, MutexGuard, RwLock, mpsc};
use std::time::Instant;

use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

use super::grow::{Grower, Grown};
use super::{Outcome, REPLY, REQUEST, Reply, Request, Setup, Work, encode, fail, receive};
use crate::creature::Creature;
use crate::task::TaskSpec;

/// A worker's loop: asks rank 0 for work, does it on this process's threads, sends the
/// outcomes back with the next request; ends when rank 0 says stop. It holds the creatures
/// it develops until rank 0 starts new births. It asks again once it holds no more jobs than
/// it has threads (and has finished one since it last asked), or, after its last jobs of a
/// batch, once it has finished them all.
pub(super) fn serve(world: &SimpleCommunicator) -> Result<(), String> {
    let threads = rayon::current_num_threads() as u32;
    let master = world.process_at_rank(0);
    let (finished, results) = mpsc::channel::<(u32, Result<Outcome, String>)>();
    let mut task: Option<Arc<TaskSpec>> = None;
    let mut grower: Option<Arc<dyn Grower>> = None;
    let held: Arc<Mutex<HashMap<u32, Arc<Grown>>>> = Arc::default();
    let stored: Arc<RwLock<HashMap<[u8; 32], u32>>> = Arc::default();
    let mut births = 0u64;
    let mut in_flight = 0usize;
    let mut outcomes = Vec::new();
    loop {
        let request = Request {
            threads,
            outcomes: std::mem::take(&mut outcomes),
        };
        master.send_with_tag(&encode(&request)[..], REQUEST);
        let (_, bytes) = receive(world, Some(0), REPLY);
        let reply: Reply<Creature, TaskSpec, Setup> =
            rmp_serde::from_slice(&bytes).unwrap_or_else(|e| {
                fail(
                    world,
                    &format!("cannot decode a job: {e} (are all ranks the same ontogeny build?)"),
                )
            });
        let (jobs, last) = match reply {
            Reply::Stop => return Ok(()),
            Reply::Work {
                task: sent,
                setup,
                births: now,
                jobs,
                known,
                last,
            } => {
                if let Some(sent) = sent {
                    task = Some(Arc::new(sent));
                }
                if let Some(setup) = setup {
                    grower = Some(super::grow::grower(&setup)?);
                }
                if now != births {
                    births = now;
                    lock(&held).clear();
                    write(&stored).clear();
                }
                if !known.0.is_empty() {
                    let mut stored = write(&stored);
                    for (key, generation) in super::stored_keys(&known.0)? {
                        stored.entry(key).or_insert(generation);
                    }
                }
                (jobs, last)
            }
        };
        for (index, work) in jobs {
            let task = task
                .clone()
                .ok_or_else(|| "a job came before its task".to_string())?;
            let finished = finished.clone();
            let grower = || {
                grower
                    .clone()
                    .ok_or_else(|| "a genome came before its encoding".to_string())
            };
            in_flight += 1;
            match work {
                Work::Walk(creature, unit) => rayon::spawn(move || {
                    let evaluation = task.evaluate_job_plainly(&creature, unit.as_ref());
                    let _ = finished.send((index, Ok(Outcome::Evaluated(evaluation))));
                }),
                Work::Develop {
                    genome,
                    seed,
                    key_version,
                } => {
                    let (grower, held) = (grower()?, held.clone());
                    rayon::spawn(move || {
                        let outcome = grower.grow(&genome.0, seed, key_version, &task).map(|g| {
                            let sizes = g.sizes();
                            lock(&held).insert(index, Arc::new(g));
                            Outcome::Developed(sizes)
                        });
                        let _ = finished.send((index, outcome));
                    })
                }
                Work::WalkHeld { birth, unit } => {
                    let grown = lock(&held).get(&birth).cloned().ok_or_else(|| {
                        format!("rank 0 asked for a walk of birth {birth}, which this rank does not hold")
                    })?;
                    rayon::spawn(move || {
                        let evaluation = grown.walk(&task, unit);
                        let _ = finished.send((index, Ok(Outcome::Evaluated(evaluation))));
                    })
                }
                Work::Birth {
                    genome,
                    seed,
                    key_version,
                    source,
                } => {
                    let (grower, stored) = (grower()?, stored.clone());
                    rayon::spawn(move || {
                        let first = |key: &[u8; 32]| read(&stored).get(key).copied();
                        let birth = (&genome.0[..], seed, key_version, source);
                        let outcome = make_birth(grower.as_ref(), birth, &task, first);
                        let _ = finished.send((index, outcome));
                    })
                }
                Work::GrowAndWalk {
                    genome,
                    seed,
                    key_version,
                    unit,
                } => {
                    let grower = grower()?;
                    rayon::spawn(move || {
                        let outcome = grower
                            .grow(&genome.0, seed, key_version, &task)
                            .map(|grown| Outcome::Evaluated(grown.walk(&task, unit)));
                        let _ = finished.send((index, outcome));
                    })
                }
            }
        }
        // Ask again with at least one outcome, once this rank holds no more jobs than it has
        // threads (its threads have those to go on with while rank 0 answers), or, after its
        // last jobs of the batch, once they are all done.
        let enough = if last { 0 } else { threads as usize };
        while in_flight > 0 && (in_flight > enough || outcomes.is_empty()) {
            let (index, outcome) = results
                .recv()
                .map_err(|_| "an evaluation thread ended".to_string())?;
            outcomes.push((index, outcome?));
            in_flight -= 1;
            for (index, outcome) in results.try_iter() {
                outcomes.push((index, outcome?));
                in_flight -= 1;
            }
        }
    }
}

/// A steady-state birth ([`Work::Birth`]): `genome` (encoded) developed with `seed`, keyed
/// with keys of `key_version`, and evaluated on this thread unless `first` (the first
/// generation that stored a key, if any did) says it was stored up to `source`.
fn make_birth(
    grower: &dyn Grower,
    (genome, seed, key_version, source): (&[u8], u64, u8, u32),
    task: &TaskSpec,
    first: impl Fn(&[u8; 32]) -> Option<u32>,
) -> Result<Outcome, String> {
    let started = Instant::now();
    let grown = grower.grow(genome, seed, key_version, task)?;
    let stored = grown
        .key()
        .and_then(|key| first(&key.0))
        .is_some_and(|generation| generation <= source);
    let evaluation = (!stored).then(|| grown.evaluate_as_birth(task));
    Ok(Outcome::Born {
        sizes: grown.sizes(),
        evaluation,
        seconds: started.elapsed().as_secs_f64(),
        thread: rayon::current_thread_index().unwrap_or(0) as u32,
    })
}

/// The map of held creatures, locked (a thread that panicked while holding it left it whole).
fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The stored keys, to read (a thread that panicked while holding them left them whole).
fn read<T>(lock: &RwLock<T>) -> std::sync::RwLockReadGuard<'_, T> {
    lock.read().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The stored keys, to add to.
fn write<T>(lock: &RwLock<T>) -> std::sync::RwLockWriteGuard<'_, T> {
    lock.write()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

#[cfg(test)]
mod tests {
    use rand::SeedableRng;

    use std::collections::HashMap;

    use super::super::super::ga::{Algorithm, Evolution, GaSettings, Individual, Operator, Preset};
    use super::super::super::habitats::develop_with_seedlings;
    use super::super::super::key::{EvaluationKey, KeyVersion};
    use super::super::super::steady::{Blocks, Lookup, Snapshot};
    use super::super::grow::{Grown, Setup, grower};
    use super::super::{Bytes, Outcome, Work, encode, key_version_number};
    use super::make_birth;
    use crate::cancel::Cancel;
    use crate::creature::Creature;
    use crate::encoding::{
        ContinuousGenome, DirectGenome, Genome, GraphGenome, LSystemGenome, Purpose, Rng,
    };
    use crate::sim::WorldSpec;
    use crate::sim::world_spec::Slope;
    use crate::task::{Evaluation, Habitat};
    use crate::task::{TaskKind, TaskSpec};

    #[test]
    fn a_genome_travels_as_one_binary_string() {
        // MessagePack's bin 8: 0xc4, the length, the bytes.
        assert_eq!(encode(&Bytes(vec![1, 2, 200])), vec![0xc4, 3, 1, 2, 200]);
        let sent: Work<&Creature> = Work::Develop {
            genome: Bytes(vec![7, 0, 255]),
            seed: u64::MAX,
            key_version: 2,
        };
        let received: Work<Creature> = rmp_serde::from_slice(&encode(&sent)).unwrap();
        assert_eq!(
            received,
            Work::Develop {
                genome: Bytes(vec![7, 0, 255]),
                seed: u64::MAX,
                key_version: 2,
            }
        );
    }

    /// A worker that knows the encoding by name grows and keys a genome sent as MessagePack
    /// into what rank 0 grows from the genome itself, for `task` (its limits adapted to it
    /// as a run adapts them): the same sizes and key, of either key version; and the walk
    /// of a creature a worker developed (its own birth, or another's taken over) is the walk
    /// of the creature rank 0 develops.
    fn grows_as_rank_0<G: Genome>(task: &TaskSpec) {
        let mut limits = G::Limits::default();
        let purpose = match task.task.throws() {
            true => Purpose::Throwing,
            false => Purpose::Locomotion,
        };
        G::adapt_limits(&mut limits, purpose);
        let grower = grower(&Setup::of::<G>(&limits, task)).unwrap();
        let mut developed = 0;
        for seed in 0..8u64 {
            let genome = G::random(&limits, &mut Rng::seed_from_u64(seed));
            for (version, number) in [(KeyVersion::V1, 1), (KeyVersion::V2, 2)] {
                let here = Grown::of(&genome, &limits, seed, task, version);
                let there = grower.grow(&encode(&genome), seed, number, task).unwrap();
                assert_eq!(there.sizes(), here.sizes(), "{} seed {seed}", G::NAME);
                developed += usize::from(here.sizes().key.is_some());
            }
            if let Ok((creatures, _)) = develop_with_seedlings(&genome, &limits, seed, task) {
                let there = grower.grow(&encode(&genome), seed, 2, task).unwrap();
                let walked = there.walk(task, None);
                assert_eq!(walked, task.evaluate_job_plainly(&creatures[0], None));
                assert_eq!(
                    walked.fitness.to_bits(),
                    task.evaluate_job_plainly(&creatures[0], None)
                        .fitness
                        .to_bits()
                );
            }
        }
        assert!(developed > 0, "{}: no genome developed", G::NAME);
        assert!(grower.grow(&[0xc1], 0, 2, task).is_err());
        // A key version this build does not know is refused, not taken for another.
        let genome = G::random(&limits, &mut Rng::seed_from_u64(0));
        let refused = grower.grow(&encode(&genome), 0, 3, task).err().unwrap();
        assert!(refused.contains("key version 3"), "{refused}");
    }

    /// A short walk of `kind`.
    fn short(kind: TaskKind) -> TaskSpec {
        let mut task = TaskSpec::new(kind);
        *task.seconds_mut() = 0.25;
        task
    }

    /// A steady-state run of `G` on `task`: population 6, 3 generations, 2 births in flight.
    fn steady<G: Genome>(task: TaskSpec) -> Evolution<G> {
        let mut limits = G::Limits::default();
        G::adapt_limits(&mut limits, Purpose::Locomotion);
        Evolution {
            settings: GaSettings {
                population: 6,
                generations: 3,
                algorithm: Algorithm::SteadyState,
                in_flight: Some(2),
                ..GaSettings::preset(Preset::Chaumont)
            },
            limits,
            task,
            seed: 11,
            init: None,
            key_version: Default::default(),
            key_tables: None,
            walk_order: Default::default(),
        }
    }

    /// Every birth of block 1 of `evolution`'s run, made by a worker from its genome sent as
    /// rank 0 breeds it, is the birth rank 0 makes: the same evaluation to the bit, size and
    /// key, and the same decision to reuse a stored evaluation — taken for a creature stored
    /// up to the birth's source generation, not for one first stored after it. Returns how
    /// many were found stored and how many creatures first stored after their birth's source
    /// were walked.
    fn makes_births_as_rank_0<G: Genome>(evolution: &Evolution<G>) -> (usize, usize) {
        let mut rng = Rng::seed_from_u64(3);
        let population: Vec<Individual<G>> = (0..6)
            .map(|i| Individual {
                genome: G::random(&evolution.limits, &mut rng),
                develop_seed: i,
                parents: Vec::new(),
                operator: Operator::Random,
                evaluation: Evaluation {
                    fitness: i as f64,
                    ..Evaluation::invalid("walker", String::new())
                },
                size: (0, 0, 0),
                key: None,
                reused: false,
                parents_generation: None,
            })
            .collect();
        let snapshot = Snapshot::new(evolution, population);
        let blocks = Blocks::of(&evolution.settings);
        let cancel = Cancel::default();
        let births: Vec<u64> = (blocks.end_of(0)..blocks.end_of(1)).collect();
        // Made once without a lookup, their creatures are then stored: the even ones by
        // generation 0 (up to every birth's source), the odd ones by generation 1 (after it).
        let fresh: Vec<_> = births
            .iter()
            .map(|&b| evolution.birth(b, &snapshot, None, &cancel).unwrap())
            .collect();
        let mut lookup = Lookup::default();
        for (k, birth) in fresh.iter().enumerate() {
            assert_eq!(blocks.source(birth.number), 0);
            lookup.add((k % 2) as u32, std::slice::from_ref(&birth.individual));
        }
        let grower = grower(&Setup::of::<G>(&evolution.limits, &evolution.task)).unwrap();
        let first: HashMap<[u8; 32], u32> = lookup.entries().map(|(k, g)| (k.0, g)).collect();
        let lookup = std::sync::RwLock::new(lookup);
        let (mut stored, mut walked) = (0, 0);
        for &b in &births {
            let here = evolution
                .birth(b, &snapshot, Some(&lookup), &cancel)
                .unwrap();
            let (unborn, _) = evolution.breed_birth(b, &snapshot);
            let sent = (
                &encode(&unborn.genome)[..],
                unborn.develop_seed,
                key_version_number(evolution.key_version),
                blocks.source(b),
            );
            let Ok(Outcome::Born {
                sizes, evaluation, ..
            }) = make_birth(grower.as_ref(), sent, &evolution.task, |k| {
                first.get(k).copied()
            })
            else {
                panic!("{}: birth {b} not made", G::NAME);
            };
            assert_eq!(sizes.size(), here.individual.size, "{} birth {b}", G::NAME);
            assert_eq!(sizes.key.map(EvaluationKey), here.individual.key);
            assert_eq!(evaluation.is_none(), here.individual.reused, "birth {b}");
            match evaluation {
                Some(evaluation) => {
                    // A creature first stored after the birth's source: walked all the same.
                    let key = sizes.key.map(EvaluationKey);
                    if key.is_some_and(|k| first.get(&k.0) == Some(&1)) {
                        walked += 1;
                    }
                    let made = &here.individual.evaluation;
                    assert_eq!(&evaluation, made, "{} birth {b}", G::NAME);
                    assert_eq!(evaluation.fitness.to_bits(), made.fitness.to_bits());
                }
                None => stored += 1,
            }
        }
        (stored, walked)
    }

    #[test]
    fn a_worker_makes_a_steady_state_birth_as_rank_0_does() {
        let lsystem = makes_births_as_rank_0(&steady::<LSystemGenome>(short(TaskKind::Walker)));
        let direct = makes_births_as_rank_0(&steady::<DirectGenome>(short(TaskKind::Walker)));
        // In two habitats with two noisy trials each: each birth's walks combined on the
        // worker.
        let mut habitats = short(TaskKind::Walker);
        habitats.habitats = ["flat", "hill"]
            .into_iter()
            .enumerate()
            .map(|(i, name)| Habitat {
                name: name.into(),
                world: WorldSpec {
                    slope: (i == 1).then_some(Slope {
                        degrees: 5.0,
                        direction: 0.0,
                    }),
                    ..WorldSpec::default()
                },
                environment: None,
                trials: None,
            })
            .collect();
        habitats.trials.count = 2;
        habitats.trials.heading = 10.0;
        let graph = makes_births_as_rank_0(&steady::<GraphGenome>(habitats));
        for (stored, walked_after) in [lsystem, direct, graph] {
            assert!(
                stored > 0 && walked_after > 0,
                "{stored} stored, {walked_after} stored after their source and walked"
            );
        }
    }

    #[test]
    fn a_worker_grows_and_keys_a_sent_genome_as_rank_0_does() {
        let walker = short(TaskKind::Walker);
        grows_as_rank_0::<LSystemGenome>(&walker);
        grows_as_rank_0::<GraphGenome>(&walker);
        grows_as_rank_0::<ContinuousGenome>(&walker);
        grows_as_rank_0::<DirectGenome>(&walker);
        // A thrower's graph genomes keep their root as an arm: limits serde does not carry.
        grows_as_rank_0::<GraphGenome>(&short(TaskKind::Catapult));
        let unknown = Setup {
            encoding: "none".into(),
            limits: Bytes(Vec::new()),
            throwing: false,
        };
        assert!(grower(&unknown).is_err());
    }
}
