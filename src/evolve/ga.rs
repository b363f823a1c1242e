//! The genetic algorithm: generational, elitist, with the operators' schedule of Chaumont et
//! al. 5.7 or of Walking with Dinosaurs 3.3 (presets as data), over any [`Genome`].
//!
//! Every individual's randomness comes from (run seed, generation, index) through a portable
//! generator, and evaluations run in parallel with rayon, so a run is bit-identical on any
//! number of threads and after a resume from any complete generation.

use rand::{RngExt, SeedableRng};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use std::collections::HashMap;
use std::time::Instant;

use super::cache::EvaluationCache;
use super::evaluator::{Evaluator, Job};
use super::habitats::develop_with_seedlings;
use super::key::{EvaluationKey, KeyVersion};
use super::record::GenerationRecord;
use super::timing::{GenerationTimes, WalkTime};
use crate::cancel::{Cancel, Interrupted};
use crate::creature::Creature;
use crate::encoding::{Genome, Rng};
use crate::task::{Evaluation, Status, TaskSpec, TaskTables, Unit};

#[cfg(feature = "mpi")]
mod remote;

pub use super::operator::{Fallbacks, Operator, schedule};
pub use super::settings::{Algorithm, GaSettings, Preset, WwdCrossover};
pub use super::walk_order::WalkOrder;

/// One member of a generation: its genome, how it was made, and its evaluation.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Individual<G> {
    /// The genome.
    pub genome: G,
    /// The seed of its development (stochastic rules), kept with it for life.
    pub develop_seed: u64,
    /// Its parents' indices in generation [`Individual::parents_generation`]: for an elite (a
    /// member carried over from the previous generation, or in a steady-state run kept
    /// through a block) its own index there.
    pub parents: Vec<u32>,
    /// How it was made.
    pub operator: Operator,
    /// Its evaluation (no recording).
    pub evaluation: Evaluation,
    /// Parts, joints and neurons of the creature it developed into (0 when it did not).
    pub size: (u32, u32, u32),
    /// The key of the creature it developed into and the run's task (`None` when it did not
    /// develop). Not part of its JSON form: the run store keeps it in a column.
    #[serde(skip)]
    pub key: Option<EvaluationKey>,
    /// Whether its evaluation was taken from an identical creature evaluated earlier in the
    /// run rather than simulated (never for an elite, which is carried over). Not part of its
    /// JSON form: the run store keeps it in a column.
    #[serde(skip)]
    pub reused: bool,
    /// The generation its `parents` index: the previous generation in a generational run and
    /// for an elite; for a steady-state run's newborn the generation its birth was bred from
    /// ([`super::steady::Blocks::source`]); `None` in generation 0 (no parents). Not part of
    /// its JSON form: the run store keeps it in a column.
    #[serde(skip)]
    pub parents_generation: Option<u32>,
}

impl GenerationRecord {
    /// The figures of `population`, `evaluations` of whom were evaluated this generation.
    /// Mean, median and standard deviation are over the individuals whose status is `ok` (NaN
    /// when there are none); the failure floor would swamp them. Its `index` is 0, `best_fine` `None` and the timings NaN, for the run to fill in.
    pub fn of<G>(population: &[Individual<G>], evaluations: u64) -> GenerationRecord {
        let best = population
            .iter()
            .map(|i| i.evaluation.fitness)
            .fold(f64::NEG_INFINITY, f64::max);
        let mut valid: Vec<f64> = population
            .iter()
            .filter(|i| i.evaluation.status == Status::Ok)
            .map(|i| i.evaluation.fitness)
            .collect();
        valid.sort_by(f64::total_cmp);
        let n = valid.len();
        let (mean, median, sd) = if n == 0 {
            (f64::NAN, f64::NAN, f64::NAN)
        } else {
            let mean = valid.iter().sum::<f64>() / n as f64;
            let median = if n % 2 == 1 {
                valid[n / 2]
            } else {
                (valid[n / 2 - 1] + valid[n / 2]) / 2.0
            };
            let var = valid.iter().map(|f| (f - mean).powi(2)).sum::<f64>() / n as f64;
            (mean, median, var.sqrt())
        };
        GenerationRecord {
            index: 0,
            best,
            mean,
            median,
            sd,
            valid_fraction: n as f64 / population.len().max(1) as f64,
            evaluations,
            reused: population.iter().filter(|i| i.reused).count() as u64,
            wall_seconds: f64::NAN,
            evaluations_per_second: f64::NAN,
            best_fine: None,
        }
    }
}

/// SplitMix64: mixes (seed, generation, index, stream) into one well-spread seed.
fn mix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

/// The random source of individual `index` of generation `generation` in run `seed`;
/// `stream` separates independent uses (0: operators, 1: development).
pub fn individual_rng(seed: u64, generation: u32, index: u32, stream: u64) -> Rng {
    let s = mix(mix(mix(mix(seed) ^ generation as u64) ^ index as u64) ^ stream);
    Rng::seed_from_u64(s)
}

/// What the genetic algorithm needs to run: the settings, the encoding's limits and the task.
#[derive(Clone, Debug)]
pub struct Evolution<G: Genome> {
    /// The schedule and sizes.
    pub settings: GaSettings,
    /// The encoding's limits.
    pub limits: G::Limits,
    /// The task every individual is evaluated on.
    pub task: TaskSpec,
    /// The run's seed.
    pub seed: u64,
    /// A genome whose mutants seed the first generation (`--init`).
    pub init: Option<G>,
    /// The version of the evaluation keys: today's for a new run, the one its store holds
    /// for a run made before (`run::Run::resume`).
    pub key_version: KeyVersion,
    /// The `[task]` table of the run's stored settings, every task's table as it was written,
    /// which version 1 keys hash ([`EvaluationKey::of_tables`]); `None`: the task's own
    /// table and the other tasks' defaults.
    pub key_tables: Option<TaskTables>,
    /// The order a generation's walks are handed to the evaluator in: it changes when each
    /// walk starts, never a result.
    pub walk_order: WalkOrder,
}

/// A new individual before evaluation.
pub(super) struct Unborn<G> {
    pub(super) genome: G,
    pub(super) develop_seed: u64,
    pub(super) parents: Vec<u32>,
    pub(super) operator: Operator,
}

/// A new individual developed, before evaluation: its creatures, one per habitat (or why it
/// has none), and key.
pub(super) struct Developed<G> {
    pub(super) unborn: Unborn<G>,
    pub(super) creatures: Result<Vec<Creature>, String>,
    /// What they grow from during their evaluation, one per habitat (`develop = "during"`;
    /// none otherwise).
    pub(super) seedlings: Vec<crate::develop::Seedling>,
    pub(super) key: Option<EvaluationKey>,
}

/// Where a new individual's evaluation comes from.
enum Source {
    /// Simulated now.
    Simulated,
    /// An earlier generation's evaluation of the same key.
    Cached(Evaluation),
    /// The evaluation of the lower-indexed individual of this generation with the same key.
    Sibling(usize),
}

impl<G: Genome> Evolution<G> {
    /// The evaluation key of the creatures `genome` develops into with `develop_seed` in the
    /// task's habitats (`None` when it does not develop): for an individual stored before keys
    /// were.
    pub fn key(&self, genome: &G, develop_seed: u64) -> Option<EvaluationKey> {
        self.key_of_version(genome, develop_seed, self.key_version)
    }

    /// [`Evolution::key`], of version `version`.
    pub fn key_of_version(
        &self,
        genome: &G,
        develop_seed: u64,
        version: KeyVersion,
    ) -> Option<EvaluationKey> {
        develop_with_seedlings(genome, &self.limits, develop_seed, &self.task)
            .ok()
            .map(|(c, _)| {
                self.key_of_creatures(&c, version)
                    .growing(&self.task, genome)
            })
    }

    /// The key of an individual developed into `creatures` (one per habitat), of version
    /// `version`: a run made before version 2, which has no habitats, keys its one creature
    /// with its stored tables.
    fn key_of_creatures(&self, creatures: &[Creature], version: KeyVersion) -> EvaluationKey {
        match (version, &self.key_tables, creatures) {
            (KeyVersion::V1, Some(tables), [creature]) if self.task.is_plain() => {
                EvaluationKey::of_tables(creature, tables)
            }
            _ => EvaluationKey::of_habitats(creatures, &self.task, version),
        }
    }

    /// Develops one genome in every habitat (its key is left for [`Evolution::key_developed`]).
    pub(super) fn develop(&self, unborn: Unborn<G>) -> Developed<G> {
        let (creatures, seedlings) = match develop_with_seedlings(
            &unborn.genome,
            &self.limits,
            unborn.develop_seed,
            &self.task,
        ) {
            Ok((creatures, seedlings)) => (Ok(creatures), seedlings),
            Err(e) => (Err(e.to_string()), Vec::new()),
        };
        Developed {
            unborn,
            creatures,
            seedlings,
            key: None,
        }
    }

    /// Keys a developed genome's creatures with the task (none when it did not develop).
    pub(super) fn key_developed(&self, developed: &mut Developed<G>) {
        developed.key = developed.creatures.as_ref().ok().map(|c| {
            self.key_of_creatures(c, self.key_version)
                .growing(&self.task, &developed.unborn.genome)
        });
    }

    /// Develops and evaluates new individuals, in parallel, each walk (habitat × trial) a
    /// separate job. With the cache on, an individual whose key the cache holds reuses that
    /// evaluation, and one whose key a lower-indexed individual of `unborn` has reuses that
    /// one's (decided before any simulation, so the result does not depend on the number of
    /// threads); every new evaluation joins the cache. With fresh trials (drawn anew each
    /// generation, `generation` joining the seed) no evaluation of another generation is
    /// reused or kept. `times` gets the wall time of developing, keying and evaluating, and
    /// each walk's.
    fn evaluate_all(
        &self,
        unborn: Vec<Unborn<G>>,
        generation: u32,
        cache: &mut EvaluationCache,
        cancel: &Cancel,
        times: &mut GenerationTimes,
    ) -> Result<Vec<Individual<G>>, Interrupted> {
        #[cfg(feature = "mpi")]
        if remote::births_go_remote(self) {
            return remote::evaluate_all(self, unborn, generation, cache, cancel, times);
        }
        let fresh = self.task.trials.fresh;
        let started = Instant::now();
        let mut developed: Vec<Developed<G>> = unborn
            .into_par_iter()
            .map(|u| cancel.check().map(|()| self.develop(u)))
            .collect::<Result<_, _>>()?;
        times.developing = started.elapsed().as_secs_f64();
        let started = Instant::now();
        developed.par_iter_mut().for_each(|d| self.key_developed(d));
        times.keying = started.elapsed().as_secs_f64();
        let mut first_with: HashMap<EvaluationKey, usize> = HashMap::new();
        let sources: Vec<Source> = developed
            .iter()
            .enumerate()
            .map(|(index, d)| match d.key {
                Some(key) if cache.enabled() => {
                    if let Some(evaluation) = cache.get(&key).filter(|_| !fresh) {
                        Source::Cached(evaluation.clone())
                    } else if let Some(&first) = first_with.get(&key) {
                        Source::Sibling(first)
                    } else {
                        first_with.insert(key, index);
                        Source::Simulated
                    }
                }
                _ => Source::Simulated,
            })
            .collect();
        let mut simulated: Vec<Option<Evaluation>> = developed
            .iter()
            .zip(&sources)
            .map(|(d, source)| match (source, &d.creatures) {
                (Source::Simulated, Err(e)) => Some(Evaluation::invalid(
                    self.task.task.name(),
                    format!("development: {e}"),
                )),
                _ => None,
            })
            .collect();
        // Each simulated individual's units (none for a plain task) and its jobs' range.
        let mut jobs: Vec<Job<'_>> = Vec::new();
        let mut owners: Vec<(usize, Vec<Unit>, std::ops::Range<usize>)> = Vec::new();
        for (index, (d, source)) in developed.iter().zip(&sources).enumerate() {
            let (Source::Simulated, Ok(creatures), Some(key)) = (source, &d.creatures, d.key)
            else {
                continue;
            };
            let start = jobs.len();
            let units = if self.task.is_plain() {
                jobs.push(Job {
                    creature: &creatures[0],
                    unit: None,
                    seedling: d.seedlings.first(),
                });
                Vec::new()
            } else {
                let units = self.task.units(key.0, generation);
                jobs.extend(units.iter().map(|u| Job {
                    creature: &creatures[u.habitat as usize],
                    unit: Some(*u),
                    seedling: d.seedlings.get(u.habitat as usize),
                }));
                units
            };
            owners.push((index, units, start..jobs.len()));
        }
        // Handed out in the walk order, put back in the jobs' order.
        let order = self.walk_order.order(
            &jobs
                .iter()
                .map(|j| j.creature.parts.len())
                .collect::<Vec<_>>(),
        );
        let handed: Vec<Job<'_>> = order.iter().map(|&j| jobs[j]).collect();
        let started = Instant::now();
        let (evaluations_handed, walks) =
            Evaluator::current().evaluate_timed(&self.task, &handed, cancel)?;
        times.evaluating = started.elapsed().as_secs_f64();
        let mut evaluations: Vec<Option<Evaluation>> = vec![None; jobs.len()];
        for (&j, evaluation) in order.iter().zip(evaluations_handed) {
            evaluations[j] = Some(evaluation);
        }
        let mut evaluations: Vec<Evaluation> = evaluations
            .into_iter()
            .map(|e| e.expect("every job is handed out once"))
            .collect();
        // Each walk's job index becomes its individual's; the walks stay in the order handed.
        let mut owner_of_job = vec![0u32; jobs.len()];
        for (index, _, range) in &owners {
            owner_of_job[range.clone()].fill(*index as u32);
        }
        times.walks = walks
            .into_iter()
            .map(|w| WalkTime {
                individual: owner_of_job[order[w.individual as usize]],
                ..w
            })
            .collect();
        for (index, units, range) in owners.into_iter().rev() {
            let mine: Vec<Evaluation> = evaluations.drain(range).collect();
            simulated[index] = Some(match &developed[index].creatures {
                Ok(creatures) if !units.is_empty() => self.task.combine(&units, mine, creatures),
                _ => mine
                    .into_iter()
                    .next()
                    .expect("a plain individual has one walk"),
            });
        }
        let mut born = Vec::with_capacity(developed.len());
        for (d, source) in developed.into_iter().zip(sources) {
            let (evaluation, reused) = match source {
                Source::Simulated => (
                    simulated[born.len()]
                        .clone()
                        .expect("a simulated individual has an evaluation"),
                    false,
                ),
                Source::Cached(evaluation) => (evaluation, true),
                Source::Sibling(first) => (
                    simulated[first]
                        .clone()
                        .expect("the first of a key is simulated"),
                    true,
                ),
            };
            if let (Some(key), false, false) = (d.key, reused, fresh) {
                cache.insert(key, &evaluation);
            }
            let size = match d.creatures.as_ref().map(|c| &c[0]) {
                Ok(c) => (
                    c.parts.len() as u32,
                    c.joints.len() as u32,
                    c.neuron_count() as u32,
                ),
                Err(_) => (0, 0, 0),
            };
            born.push(Individual {
                genome: d.unborn.genome,
                develop_seed: d.unborn.develop_seed,
                parents: d.unborn.parents,
                operator: d.unborn.operator,
                evaluation,
                size,
                key: d.key,
                reused,
                parents_generation: generation.checked_sub(1),
            });
        }
        Ok(born)
    }

    /// Generation 0: random genomes (or mutants of the `init` genome), evaluated in parallel
    /// (identical creatures once, when `cache` is on); `Interrupted`, with `cache` as it was,
    /// once `cancel` is set.
    pub fn first_generation(
        &self,
        cache: &mut EvaluationCache,
        cancel: &Cancel,
    ) -> Result<Vec<Individual<G>>, Interrupted> {
        self.first_generation_timed(cache, cancel, &mut GenerationTimes::default())
    }

    /// [`Evolution::first_generation`], saying in `times` where its time went.
    pub fn first_generation_timed(
        &self,
        cache: &mut EvaluationCache,
        cancel: &Cancel,
        times: &mut GenerationTimes,
    ) -> Result<Vec<Individual<G>>, Interrupted> {
        let started = Instant::now();
        let unborn: Vec<Unborn<G>> = (0..self.settings.population as u32)
            .into_par_iter()
            .map(|index| {
                let mut rng = individual_rng(self.seed, 0, index, 0);
                let develop_seed = individual_rng(self.seed, 0, index, 1).random();
                let (genome, operator) = match &self.init {
                    // The first one is the grammar itself, as its author wrote it.
                    Some(init) if index == 0 => (init.clone(), Operator::Init),
                    Some(init) => (
                        self.regenerated(
                            develop_seed,
                            || init.mutate(&self.limits, self.settings.mutation_rate, &mut rng),
                            |g| g,
                        ),
                        Operator::Init,
                    ),
                    None => (
                        self.regenerated(develop_seed, || G::random(&self.limits, &mut rng), |g| g),
                        Operator::Random,
                    ),
                };
                Unborn {
                    genome,
                    develop_seed,
                    parents: Vec::new(),
                    operator,
                }
            })
            .collect();
        times.breeding = started.elapsed().as_secs_f64();
        self.evaluate_all(unborn, 0, cache, cancel, times)
    }

    /// The next generation, number `generation`, from `previous` (in any order): the elite
    /// carried over with their evaluations (or walked again, with fresh trials), the rest made by the preset's operators and
    /// evaluated in parallel. Returns it, best first among the elite, and the number of
    /// evaluations made. `fallbacks` counts children made by mutation because the encoding
    /// lacks the scheduled operator. A child identical to a creature of `cache` reuses its
    /// evaluation. `Interrupted`, with `cache` and `fallbacks` as they were, once `cancel` is
    /// set.
    pub fn next_generation(
        &self,
        previous: &[Individual<G>],
        generation: u32,
        fallbacks: &mut Fallbacks,
        cache: &mut EvaluationCache,
        cancel: &Cancel,
    ) -> Result<(Vec<Individual<G>>, u64), Interrupted> {
        let mut times = GenerationTimes::default();
        self.next_generation_timed(previous, generation, fallbacks, cache, cancel, &mut times)
    }

    /// [`Evolution::next_generation`], saying in `times` where its time went.
    pub fn next_generation_timed(
        &self,
        previous: &[Individual<G>],
        generation: u32,
        fallbacks: &mut Fallbacks,
        cache: &mut EvaluationCache,
        cancel: &Cancel,
        times: &mut GenerationTimes,
    ) -> Result<(Vec<Individual<G>>, u64), Interrupted> {
        let started = Instant::now();
        let order = ranking(previous);
        let population = self.settings.population;
        let survivors = self.settings.survivors().min(previous.len());
        let mut next: Vec<Individual<G>> = order[..survivors]
            .iter()
            .map(|&i| Individual {
                operator: Operator::Elite,
                parents: vec![i as u32],
                reused: false,
                parents_generation: generation.checked_sub(1),
                ..previous[i].clone()
            })
            .collect();
        let children = population - survivors;
        let ranked = Ranked {
            previous,
            order: &order,
            survivors,
        };
        let adaptive_rate = self.adaptive_rate(previous);
        let (unborn, fell_back): (Vec<Unborn<G>>, Vec<Option<Operator>>) = (0..children)
            .into_par_iter()
            .map(|k| self.child(&ranked, adaptive_rate, generation, k, children))
            .unzip();
        let mut unborn = unborn;
        if self.task.trials.fresh {
            // The elite are walked again on this generation's draws, before the children.
            let elite: Vec<Unborn<G>> = next
                .drain(..)
                .map(|e| Unborn {
                    genome: e.genome,
                    develop_seed: e.develop_seed,
                    parents: e.parents,
                    operator: Operator::Elite,
                })
                .collect();
            unborn.splice(0..0, elite);
        }
        times.breeding = started.elapsed().as_secs_f64();
        let born = self.evaluate_all(unborn, generation, cache, cancel, times)?;
        // The walks' individuals, counted from the first child, become the generation's.
        for walk in &mut times.walks {
            walk.individual += next.len() as u32;
        }
        for op in fell_back.into_iter().flatten() {
            fallbacks.count(op);
        }
        let evaluations = born.len() as u64;
        next.extend(born);
        Ok((next, evaluations))
    }

    /// Child `k` of the `children` of generation `generation`, bred from `ranked` (the
    /// mutation rate `adaptive_rate` for Walking with Dinosaurs' preset), and the operator it
    /// fell back from, if any: a pure function of its arguments and the run's seed.
    pub(super) fn child(
        &self,
        ranked: &Ranked<G>,
        adaptive_rate: f64,
        generation: u32,
        k: usize,
        children: usize,
    ) -> (Unborn<G>, Option<Operator>) {
        let index = (ranked.survivors + k) as u32;
        let mut rng = individual_rng(self.seed, generation, index, 0);
        let develop_seed = individual_rng(self.seed, generation, index, 1).random();
        let child = self.regenerated(
            develop_seed,
            || match self.settings.preset {
                Preset::Chaumont => self.vary_chaumont(ranked, k, children, &mut rng),
                Preset::Wwd => self.vary_wwd(ranked, adaptive_rate, &mut rng),
            },
            |child| &child.genome,
        );
        child.into_unborn(develop_seed)
    }

    /// A newborn made by `make`, made again while the creature it develops into (in its own
    /// chemical array, from `develop_seed`) has parts that interpenetrate, at most
    /// [`GaSettings::regenerate`] times in all (Chaumont et al. 5.5); the last try is kept,
    /// and is evaluated as `self-intersecting` if it still collides. Only collisions are made
    /// again: a genome that does not develop for another reason is kept, and fails as it
    /// would have. Every try draws on from the newborn's own random stream, so the result
    /// does not depend on threads or ranks; with one try nothing is developed here.
    fn regenerated<T>(
        &self,
        develop_seed: u64,
        mut make: impl FnMut() -> T,
        genome: impl Fn(&T) -> &G,
    ) -> T {
        let mut newborn = make();
        for _ in 1..self.settings.regenerate {
            let collides = genome(&newborn)
                .develop(&self.limits, develop_seed)
                .is_ok_and(|creature| creature.self_intersects());
            if !collides {
                break;
            }
            newborn = make();
        }
        newborn
    }

    /// Walking with Dinosaurs' mutation rate: the base rate × 0.25 / σ, clamped to [½, 4] ×
    /// the base rate, where σ is the standard deviation of the valid individuals' fitness
    /// normalised to [0, 1] (0.25 is near a uniform spread's 0.29): less diversity, more
    /// mutation. Chaumont's preset does not adapt.
    pub(super) fn adaptive_rate(&self, previous: &[Individual<G>]) -> f64 {
        let base = self.settings.mutation_rate;
        if self.settings.preset != Preset::Wwd {
            return base;
        }
        let valid: Vec<f64> = previous
            .iter()
            .filter(|i| i.evaluation.status == Status::Ok)
            .map(|i| i.evaluation.fitness)
            .collect();
        let (lo, hi) = valid
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &f| {
                (a.min(f), b.max(f))
            });
        let sigma = if valid.len() < 2 || hi - lo <= 0.0 {
            0.0
        } else {
            let normalised: Vec<f64> = valid.iter().map(|f| (f - lo) / (hi - lo)).collect();
            let mean = normalised.iter().sum::<f64>() / normalised.len() as f64;
            (normalised.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / normalised.len() as f64)
                .sqrt()
        };
        let factor = if sigma > 0.0 { 0.25 / sigma } else { 4.0 };
        (base * factor.clamp(0.5, 4.0)).min(1.0)
    }

    /// Chaumont et al. 5.7's variation, child `k` of `children`: the operator
    /// [`schedule`] gives it, on parents drawn from the elite: mutation alone (at the
    /// `mutation_rate`), or crossover or grafting of two, the child then mutated with the
    /// `mutation_chance_after_mating` (at the `mutation_rate_after_mating`). An encoding that
    /// cannot mate the two makes the child by mutation instead, and says so.
    fn vary_chaumont(
        &self,
        ranked: &Ranked<G>,
        k: usize,
        children: usize,
        rng: &mut Rng,
    ) -> Child<G> {
        let s = &self.settings;
        let scheduled = schedule(k, children, s.asexual, s.crossover);
        let a = pick(rng, ranked.elite());
        let ga = &ranked.previous[a].genome;
        if scheduled == Operator::Mutation {
            return Child::new(
                ga.mutate(&self.limits, s.mutation_rate, rng),
                vec![a],
                Operator::Mutation,
                None,
            );
        }
        let b = pick(rng, ranked.elite());
        let gb = &ranked.previous[b].genome;
        let mated = match scheduled {
            Operator::Crossover => ga.crossover(gb, &self.limits, rng),
            _ => ga.graft(gb, &self.limits, rng),
        };
        match mated {
            Some(mut child) => {
                if rng.random_bool(s.mutation_chance_after_mating) {
                    child = child.mutate(&self.limits, s.mutation_rate_after_mating, rng);
                }
                Child::new(child, vec![a, b], scheduled, None)
            }
            None => Child::new(
                ga.mutate(&self.limits, s.mutation_rate, rng),
                vec![a],
                Operator::Mutation,
                Some(scheduled),
            ),
        }
    }

    /// Walking with Dinosaurs 3.3's variation: a breeder (ranked after the elite; the elite
    /// when there are none) receives a part of an elite's genome by crossover (3.3.1: the
    /// `wwd_crossover` key, the report's mirroring crossover or the encoding's plain one), and
    /// every new creature is then mutated at the adaptive `rate` (3.3.2). Where the encoding
    /// makes no child (it lacks the crossover, or the elite has no part that fits), the
    /// breeder is mutated alone, and the fallback is counted.
    fn vary_wwd(&self, ranked: &Ranked<G>, rate: f64, rng: &mut Rng) -> Child<G> {
        let (order, survivors) = (ranked.order, ranked.survivors);
        let breeders_end = (survivors + self.settings.breeder_count()).min(order.len());
        let breeders = if breeders_end > survivors {
            &order[survivors..breeders_end]
        } else {
            ranked.elite()
        };
        let e = pick(rng, ranked.elite());
        let b = pick(rng, breeders);
        let breeder = &ranked.previous[b].genome;
        let elite = &ranked.previous[e].genome;
        let mated = match self.settings.wwd_crossover {
            WwdCrossover::Mirroring => breeder.mirroring_crossover(elite, &self.limits, rng),
            WwdCrossover::Plain => breeder.crossover(elite, &self.limits, rng),
        };
        match mated {
            Some(child) => Child::new(
                child.mutate(&self.limits, rate, rng),
                vec![b, e],
                Operator::Crossover,
                None,
            ),
            None => Child::new(
                breeder.mutate(&self.limits, rate, rng),
                vec![b],
                Operator::Mutation,
                Some(Operator::Crossover),
            ),
        }
    }
}

/// The previous generation as variation sees it: its members, their indices ranked best
/// first ([`ranking`]), and how many of the first are the elite.
pub(super) struct Ranked<'a, G> {
    pub(super) previous: &'a [Individual<G>],
    pub(super) order: &'a [usize],
    pub(super) survivors: usize,
}

impl<G> Ranked<'_, G> {
    /// The elite's indices, best first.
    fn elite(&self) -> &[usize] {
        &self.order[..self.survivors]
    }
}

/// One of `from`, drawn uniformly.
fn pick(rng: &mut Rng, from: &[usize]) -> usize {
    from[rng.random_range(0..from.len())]
}

/// A child genome before evaluation, and the operator it fell back from, if any.
struct Child<G> {
    genome: G,
    parents: Vec<u32>,
    operator: Operator,
    fell_back_from: Option<Operator>,
}

impl<G> Child<G> {
    fn new(genome: G, parents: Vec<usize>, operator: Operator, fell: Option<Operator>) -> Self {
        Child {
            genome,
            parents: parents.into_iter().map(|p| p as u32).collect(),
            operator,
            fell_back_from: fell,
        }
    }

    fn into_unborn(self, develop_seed: u64) -> (Unborn<G>, Option<Operator>) {
        (
            Unborn {
                genome: self.genome,
                develop_seed,
                parents: self.parents,
                operator: self.operator,
            },
            self.fell_back_from,
        )
    }
}

pub use super::ranking::ranking_by;

/// Indices of `population` from best to worst fitness (ties: lower index first), as
/// [`ranking_by`] orders them.
pub fn ranking<G>(population: &[Individual<G>]) -> Vec<usize> {
    ranking_by(population, |individual| individual.evaluation.fitness)
}
