//! The steady-state algorithm (`[ga] algorithm = "steady-state"`): births one at a time, no
//! barrier between generations, and the same result on any number of threads or ranks.
//!
//! Births are numbered b = 0, 1, 2, …. The first P (the population) are generation 0, made
//! exactly as the generational algorithm makes it. After it, births come in blocks of C, the
//! children the generational algorithm makes per generation (the population less the elite):
//! block k ≥ 1 holds births P + (k − 1)·C to P + k·C − 1, and once its last birth is
//! integrated the population is stored as generation k (so a run's plots, `runs show` and the
//! viewer read it as they read any run). Birth b:
//!
//! - is **bred** from generation s(b), the last generation that ended at or before birth
//!   b + 1 − W, where W is `in_flight` (generation 0 when none did): by the preset's operator
//!   for its place j in its block ([`super::ga::schedule`] over C) and the preset's
//!   selection of parents among that generation's ranked survivors, with the random streams
//!   of individual (survivors + j) of generation k, as the generational algorithm would make
//!   child j of generation k. So at least W evaluations can be in flight at any moment (at
//!   most W + C − 1), whatever the number of threads; W is part of the algorithm.
//! - is **evaluated** anywhere, in any order; an identical creature (same key) stored in a
//!   generation up to s(b) lends it its evaluation instead (when the run's cache is on).
//! - is **integrated** strictly in birth order: it replaces the population's worst (the last
//!   of [`super::ga::ranking`]: lowest fitness, among equals the highest index) if its fitness
//!   is greater ("replace-worst"); on a tie the incumbent stays. The best is never lost, as
//!   with the generational algorithm's elite, and a creature stays in its slot for life.
//!
//! Lineage: a newborn's parents are its indices in generation s(b), which it records
//! (`parents_generation`); a member of generation k not replaced during block k is stored
//! as the generational algorithm stores its elite, operator `elite` and parents its own
//! slot in generation k − 1.
//!
//! Replace-worst rather than a tournament: it needs no random draw at integration (so nothing
//! but the birth order decides), it is elitist like the published generational protocols, and
//! its selection pressure comes from the preset's breeding, which is the presets' own.
//!
//! Breeding from stored generations, rather than from the population after birth b − W,
//! makes a resume exact with nothing more in the store than a generational run keeps: the
//! births in flight when a run was killed are bred again, the same, from the generations
//! stored.

use std::cmp::Reverse;
use std::collections::{BTreeSet, HashMap};
use std::sync::Arc;
use std::time::Instant;

use super::ga::{Evolution, Individual, Operator, Ranked, Unborn, ranking};
use super::key::EvaluationKey;
use super::timing::WalkTime;
use crate::cancel::{Cancel, Interrupted};
use crate::creature::Creature;
use crate::develop::Seedling;
use crate::encoding::Genome;
use crate::task::{Evaluation, TaskSpec, Watch};

#[cfg(feature = "mpi")]
mod ranks;
#[cfg(feature = "mpi")]
pub use ranks::{BirthStream, Next};

/// A birth to make: its number and the generation it is bred from.
pub type Order<G> = (u64, Arc<Snapshot<G>>);

/// The message of a panic's payload (a birth's, or its breeding's, on a thread of its own).
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    match (
        payload.downcast_ref::<&str>(),
        payload.downcast_ref::<String>(),
    ) {
        (Some(s), _) => s.to_string(),
        (_, Some(s)) => s.clone(),
        _ => "a panic without a message".to_string(),
    }
}

/// The arithmetic of births and blocks: the population P, the block C and the evaluations in
/// flight W.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Blocks {
    /// P: the population, and the births of generation 0.
    pub population: u64,
    /// C: the births of each later generation (at least 1).
    pub children: u64,
    /// W: the evaluations in flight at the least (at least 1).
    pub in_flight: u64,
}

impl Blocks {
    /// The births of a run with `settings`.
    pub fn of(settings: &super::ga::GaSettings) -> Blocks {
        Blocks {
            population: settings.population as u64,
            children: settings.children().max(1) as u64,
            in_flight: settings.in_flight().max(1) as u64,
        }
    }

    /// How many births are integrated once generation `generation` is complete.
    pub fn end_of(&self, generation: u32) -> u64 {
        self.population + generation as u64 * self.children
    }

    /// The generation birth `birth` (≥ P) belongs to, and its place in it.
    pub fn place(&self, birth: u64) -> (u32, usize) {
        let after = birth - self.population;
        (
            1 + (after / self.children) as u32,
            (after % self.children) as usize,
        )
    }

    /// s(b): the generation birth `birth` (≥ P) is bred from, the last that ended at or before
    /// birth b + 1 − W (generation 0 when none did).
    pub fn source(&self, birth: u64) -> u32 {
        let ready = birth + 1;
        if ready < self.population + self.in_flight {
            0
        } else {
            ((ready - self.in_flight - self.population) / self.children) as u32
        }
    }
}

/// Replace-worst: the slot of `population` a newborn of fitness `fitness` takes, the slot of
/// the worst (the last of [`ranking`]), if its fitness is greater in `f64`'s total order (the
/// ranking's); `None` (it is not kept) otherwise, ties included. A run integrates its births
/// through [`Standings`], which gives the same slots without ranking the population each time.
pub fn replace_worst<G>(population: &[Individual<G>], fitness: f64) -> Option<usize> {
    Standings::of(population).replace_worst(fitness)
}

/// A fitness in `f64`'s total order (the order of [`ranking`]: NaN above +∞).
#[derive(Clone, Copy, Debug)]
struct Total(f64);

impl PartialEq for Total {
    fn eq(&self, other: &Total) -> bool {
        self.0.total_cmp(&other.0).is_eq()
    }
}

impl Eq for Total {}

impl PartialOrd for Total {
    fn partial_cmp(&self, other: &Total) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Total {
    fn cmp(&self, other: &Total) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// The population's slots in the order of [`ranking`], reversed: worst first (lowest fitness,
/// among equals the highest index), kept as an ordered set so that each replace-worst costs
/// O(log P) rather than a ranking of the whole population.
#[derive(Clone, Debug)]
pub struct Standings {
    worst_first: BTreeSet<(Total, Reverse<usize>)>,
}

impl Standings {
    /// The standings of `population`'s slots.
    pub fn of<G>(population: &[Individual<G>]) -> Standings {
        Standings {
            worst_first: population
                .iter()
                .enumerate()
                .map(|(slot, i)| (Total(i.evaluation.fitness), Reverse(slot)))
                .collect(),
        }
    }

    /// The worst slot: the last of [`ranking`] (`None` for no population).
    pub fn worst(&self) -> Option<usize> {
        self.worst_first.first().map(|&(_, Reverse(slot))| slot)
    }

    /// Replace-worst ([`replace_worst`]): the slot a newborn of fitness `fitness` takes, which
    /// then holds `fitness` in these standings; `None`, and nothing changed, when it is not
    /// greater than the worst's.
    pub fn replace_worst(&mut self, fitness: f64) -> Option<usize> {
        let &(worst, Reverse(slot)) = self.worst_first.first()?;
        if !Total(fitness).gt(&worst) {
            return None;
        }
        self.worst_first.pop_first();
        self.worst_first.insert((Total(fitness), Reverse(slot)));
        Some(slot)
    }
}

/// A stored generation as breeding reads it: its members, ranked, and Walking with Dinosaurs'
/// mutation rate over them.
#[derive(Debug)]
pub struct Snapshot<G> {
    population: Vec<Individual<G>>,
    order: Vec<usize>,
    rate: f64,
}

impl<G: Genome> Snapshot<G> {
    /// The generation `population` of the run of `evolution`, ready to breed from.
    pub fn new(evolution: &Evolution<G>, population: Vec<Individual<G>>) -> Snapshot<G> {
        Snapshot {
            order: ranking(&population),
            rate: evolution.adaptive_rate(&population),
            population,
        }
    }
}

/// The evaluations stored so far by key, with the first generation each key was stored in:
/// what a steady-state birth may reuse (a creature stored up to the generation it was bred
/// from), the same in a run and in its resume.
#[derive(Clone, Debug, Default)]
pub struct Lookup {
    evaluations: HashMap<EvaluationKey, (u32, Evaluation)>,
}

impl Lookup {
    /// Adds generation `generation`'s members (a key seen before keeps its first); returns
    /// the keys new to it.
    pub fn add<G>(&mut self, generation: u32, population: &[Individual<G>]) -> Vec<EvaluationKey> {
        let mut new = Vec::new();
        for i in population {
            if let Some(key) = i.key {
                self.evaluations.entry(key).or_insert_with(|| {
                    new.push(key);
                    (generation, i.evaluation.clone())
                });
            }
        }
        new
    }

    /// Every key it holds, with the first generation that stored it, in no particular order.
    pub fn entries(&self) -> impl Iterator<Item = (EvaluationKey, u32)> + '_ {
        self.evaluations
            .iter()
            .map(|(key, (first, _))| (*key, *first))
    }

    /// The evaluation of `key`, if a generation up to `generation` stored it.
    pub fn find(&self, key: &EvaluationKey, generation: u32) -> Option<&Evaluation> {
        self.evaluations
            .get(key)
            .filter(|(first, _)| *first <= generation)
            .map(|(_, e)| e)
    }
}

/// One birth, evaluated, waiting to be integrated.
#[derive(Debug)]
pub struct Birth<G> {
    /// Its number, b.
    pub number: u64,
    /// The newborn; its parents are indices in generation s(b), its `parents_generation`.
    pub individual: Individual<G>,
    /// Whether it was simulated (rather than reusing a stored evaluation).
    pub simulated: bool,
    /// The operator the encoding could not apply, if it fell back to mutation.
    pub fell_back: Option<Operator>,
    /// Its evaluation's wall time and thread (its `individual` the birth's place in its block).
    pub walk: WalkTime,
}

impl<G: Genome> Evolution<G> {
    /// Birth `number` (≥ P) bred from `snapshot`, generation s(b), and not yet developed:
    /// with the operator the encoding could not apply, if it fell back to mutation.
    pub(super) fn breed_birth(
        &self,
        number: u64,
        snapshot: &Snapshot<G>,
    ) -> (Unborn<G>, Option<Operator>) {
        let blocks = Blocks::of(&self.settings);
        let (generation, place) = blocks.place(number);
        let survivors = self.settings.survivors().min(snapshot.population.len());
        let ranked = Ranked {
            previous: &snapshot.population,
            order: &snapshot.order,
            survivors,
        };
        let children = blocks.children as usize;
        self.child(&ranked, snapshot.rate, generation, place, children)
    }

    /// Birth `number` (≥ P), bred from `snapshot`, generation s(b), developed, keyed and
    /// evaluated on this thread, or given the evaluation `lookup` holds for its key up to
    /// s(b) (`None`: the cache is off); `Interrupted` once `cancel` is set.
    pub fn birth(
        &self,
        number: u64,
        snapshot: &Snapshot<G>,
        lookup: Option<&std::sync::RwLock<Lookup>>,
        cancel: &Cancel,
    ) -> Result<Birth<G>, Interrupted> {
        cancel.check()?;
        let blocks = Blocks::of(&self.settings);
        let source = blocks.source(number);
        let (unborn, fell_back) = self.breed_birth(number, snapshot);
        let started = Instant::now();
        let mut developed = self.develop(unborn);
        self.key_developed(&mut developed);
        let stored = match (developed.key, lookup) {
            (Some(key), Some(lookup)) => lookup
                .read()
                .unwrap_or_else(|poisoned| poisoned.into_inner())
                .find(&key, source)
                .cloned(),
            _ => None,
        };
        let simulated = stored.is_none();
        let evaluation = match stored {
            Some(e) => e,
            None => evaluate_birth(
                &self.task,
                &developed.creatures,
                &developed.seedlings,
                developed.key,
                Some(cancel),
            )?,
        };
        let size = match developed.creatures.as_ref().map(|c| c.first()) {
            Ok(Some(c)) => (
                c.parts.len() as u32,
                c.joints.len() as u32,
                c.neuron_count() as u32,
            ),
            _ => (0, 0, 0),
        };
        let made = Made {
            evaluation,
            simulated,
            size,
            key: developed.key,
            seconds: started.elapsed().as_secs_f64(),
            thread: rayon::current_thread_index().unwrap_or(0) as u32,
            rank: 0,
        };
        Ok(Birth::of(
            &blocks,
            number,
            developed.unborn,
            fell_back,
            made,
        ))
    }
}

/// What the making of a birth gave, wherever it was made.
pub(super) struct Made {
    /// Its evaluation, simulated or stored.
    pub(super) evaluation: Evaluation,
    /// Whether it was simulated (rather than reusing a stored evaluation).
    pub(super) simulated: bool,
    /// Its first creature's parts and joints and its neurons.
    pub(super) size: (u32, u32, u32),
    /// Its key (`None` when it did not develop).
    pub(super) key: Option<EvaluationKey>,
    /// The wall time of its development and walks, the thread and the rank that made it.
    pub(super) seconds: f64,
    pub(super) thread: u32,
    pub(super) rank: u32,
}

impl<G> Birth<G> {
    /// Birth `number` of a run of `blocks`, bred as `unborn` (falling back to mutation from
    /// `fell_back`, if it did) and made as `made` says.
    pub(super) fn of(
        blocks: &Blocks,
        number: u64,
        unborn: Unborn<G>,
        fell_back: Option<Operator>,
        made: Made,
    ) -> Birth<G> {
        let Unborn {
            genome,
            develop_seed,
            parents,
            operator,
        } = unborn;
        Birth {
            number,
            individual: Individual {
                genome,
                develop_seed,
                parents,
                operator,
                evaluation: made.evaluation,
                size: made.size,
                key: made.key,
                reused: !made.simulated,
                parents_generation: Some(blocks.source(number)),
            },
            simulated: made.simulated,
            fell_back,
            walk: WalkTime {
                individual: blocks.place(number).1 as u32,
                seconds: made.seconds,
                thread: made.thread,
                rank: made.rank,
                parts: made.size.0,
            },
        }
    }
}

/// The evaluation of a steady-state newborn developed into `creatures` (one per habitat, or
/// why it did not develop; `seedlings` what they grow from during their walks) and keyed
/// `key`: its walks (one per habitat and trial) one after another on this thread, combined as
/// the generational algorithm combines them; `Interrupted` once `cancel` is set. Rank 0 and
/// the ranks of an MPI job evaluate a birth with this.
pub(super) fn evaluate_birth(
    task: &TaskSpec,
    creatures: &Result<Vec<Creature>, String>,
    seedlings: &[Seedling],
    key: Option<EvaluationKey>,
    cancel: Option<&Cancel>,
) -> Result<Evaluation, Interrupted> {
    let (Ok(creatures), Some(key)) = (creatures, key) else {
        let why = creatures.as_ref().err().cloned().unwrap_or_default();
        return Ok(Evaluation::invalid(
            task.task.name(),
            format!("development: {why}"),
        ));
    };
    let walk = |job: super::evaluator::Job<'_>| {
        let watch = Watch {
            record: false,
            progress: &mut |_| {},
            cancel,
        };
        job.evaluate(task, watch)
    };
    if task.is_plain() {
        return walk(super::evaluator::Job {
            creature: &creatures[0],
            unit: None,
            seedling: seedlings.first(),
        });
    }
    // Trials are never fresh in a steady-state run: the generation does not join them.
    let units = task.units(key.0, 0);
    let evaluations = units
        .iter()
        .map(|u| {
            walk(super::evaluator::Job {
                creature: &creatures[u.habitat as usize],
                unit: Some(*u),
                seedling: seedlings.get(u.habitat as usize),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(task.combine(&units, evaluations, creatures))
}

#[cfg(test)]
mod tests {
    use rand::{RngExt, SeedableRng};

    use super::*;
    use crate::task::Evaluation;

    fn of_fitness(fitness: f64) -> Individual<()> {
        Individual {
            genome: (),
            develop_seed: 0,
            parents: Vec::new(),
            operator: Operator::Random,
            evaluation: Evaluation {
                fitness,
                ..Evaluation::invalid("walker", String::new())
            },
            size: (0, 0, 0),
            key: None,
            reused: false,
            parents_generation: None,
        }
    }

    #[test]
    fn the_standings_worst_is_the_rankings_last_after_every_replacement() {
        // Fitnesses from a small set, so that ties are common, with the failure floor, NaN
        // (above every number in the total order) and both zeros.
        let values = [
            0.0,
            -0.0,
            1.0,
            2.0,
            2.0,
            -999_999.0,
            f64::NAN,
            0.5,
            3.0,
            -1.0,
        ];
        let mut rng = crate::encoding::Rng::seed_from_u64(7);
        for size in [1, 2, 5, 17] {
            let mut population: Vec<Individual<()>> = (0..size)
                .map(|_| of_fitness(values[rng.random_range(0..values.len())]))
                .collect();
            let mut standings = Standings::of(&population);
            let mut replaced = 0;
            for _ in 0..2_000 {
                assert_eq!(standings.worst(), ranking(&population).last().copied());
                let fitness = values[rng.random_range(0..values.len())];
                // Replace-worst by the ranking itself: its last, if strictly below.
                let worst = *ranking(&population).last().unwrap();
                let expected = fitness
                    .total_cmp(&population[worst].evaluation.fitness)
                    .is_gt()
                    .then_some(worst);
                assert_eq!(standings.replace_worst(fitness), expected, "{fitness}");
                if let Some(slot) = expected {
                    population[slot] = of_fitness(fitness);
                    replaced += 1;
                }
            }
            assert!(replaced > 0, "some births are kept");
        }
    }

    #[test]
    fn the_worst_by_hand() {
        // Worst first: 1.0 at slot 2 (the higher of the two equal lows), then slot 0.
        let population: Vec<_> = [1.0, 3.0, 1.0].map(of_fitness).into();
        let mut standings = Standings::of(&population);
        assert_eq!(standings.worst(), Some(2));
        assert_eq!(
            standings.replace_worst(1.0),
            None,
            "a tie keeps the incumbent"
        );
        assert_eq!(standings.replace_worst(2.0), Some(2));
        assert_eq!(standings.worst(), Some(0));
        // NaN is above every number in the total order: it replaces, and is never the worst.
        assert_eq!(standings.replace_worst(f64::NAN), Some(0));
        assert_eq!(standings.worst(), Some(2));
    }
}
