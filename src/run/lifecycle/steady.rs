//! The run loop of a steady-state run ([`crate::evolve::steady`]): generation 0 as the
//! generational algorithm makes it, then births handed to this process's threads as soon as
//! the generation they are bred from is integrated, evaluated in any order, integrated in
//! birth order through a reorder buffer, and every block of births stored as a generation once
//! its best's fine reference figure, walked beside the births that follow
//! ([`super::beside`]), is in. The threads never wait for a generation's end: only the births
//! of the block after next wait.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, RwLock};
use std::thread::Scope;
use std::time::Instant;

use rayon::ThreadPool;

use super::beside::{Evaluated, Pending, fine_pool};
use super::births::Births;
use super::pool::with_workers;
use super::progress::Progress;
use super::{GenerationReport, Run, RunError};
use crate::cancel::Cancel;
use crate::encoding::Genome;
use crate::evolve::evaluator_version::EVALUATOR_VERSION;
use crate::evolve::ga::{Individual, Operator};
use crate::evolve::steady::{Birth, Blocks, Lookup, Order, Snapshot, Standings};
use crate::evolve::timing::{GenerationTimes, WalkTime};

/// Sets the run's cancellation token if the thread unwinds while it is held, so that the
/// births in flight stop rather than run to their end.
struct CancelOnUnwind(Cancel);

impl Drop for CancelOnUnwind {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.cancel();
        }
    }
}

/// What happened in the block of births being integrated.
struct Block {
    started: Instant,
    /// The slots a newborn took.
    replaced: BTreeSet<usize>,
    /// Each birth's evaluation, in birth order.
    walks: Vec<WalkTime>,
    /// The births that reused a stored evaluation rather than simulate, kept or not.
    reused: u64,
}

impl Block {
    fn new() -> Block {
        Block {
            started: Instant::now(),
            replaced: BTreeSet::new(),
            walks: Vec::new(),
            reused: 0,
        }
    }
}

impl<G: Genome> Run<G> {
    /// Runs a steady-state run's remaining generations (generation 0 first, if the store has
    /// none), calling `observer` after each is stored. Each generation's best is re-walked at
    /// the fine reference beside the births that follow it ([`super::beside`]): births bred
    /// from a generation start as soon as its last birth is integrated, and the generation is
    /// stored once its figure is in, before the next one.
    pub(super) fn run_steady(
        &mut self,
        progress: &mut Progress<G>,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError> {
        let fine_pool = fine_pool();
        std::thread::scope(|scope| {
            let mut pending: Option<Pending<'_, G>> = None;
            let pool = fine_pool.as_ref();
            let outcome = self.steady_blocks(scope, pool, progress, &mut pending, observer);
            self.finish_beside(progress, pending, outcome, observer)
        })
    }

    /// [`Run::run_steady`]'s generations, each handed over to `pending` as it is integrated.
    fn steady_blocks<'scope>(
        &mut self,
        scope: &'scope Scope<'scope, '_>,
        pool: Option<&'scope ThreadPool>,
        progress: &mut Progress<G>,
        pending: &mut Option<Pending<'scope, G>>,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError>
    where
        G: 'scope,
        G::Limits: 'scope,
    {
        let generations = self.config.ga.generations as u32;
        // Whether the last generation was bred in this call (it may not be stored yet).
        let mut fresh = false;
        if progress.next == 0 && generations > 0 {
            self.cancel.check()?;
            let started = Instant::now();
            let mut times = GenerationTimes::default();
            let evaluations = self.breed(progress, 0, &mut times)?;
            let evaluated = Evaluated {
                generation: 0,
                evaluations,
                reused: None,
                times,
                started,
                evaluated: started.elapsed().as_secs_f64(),
            };
            self.hand_over(scope, pool, progress, pending, evaluated, observer)?;
            progress.next = 1;
            fresh = true;
        }
        let Some(last) = progress.next.checked_sub(1) else {
            return Ok(());
        };
        let blocks = Blocks::of(&self.config.ga);
        let end = blocks.end_of(generations.saturating_sub(1));
        let mut integrated = blocks.end_of(last);
        if integrated >= end {
            return Ok(());
        }
        let evolution = Arc::new(self.evolution.clone());
        let mut snapshots: BTreeMap<u32, Arc<Snapshot<G>>> = BTreeMap::new();
        for g in blocks.source(integrated)..=last {
            let population = match g == last {
                true => progress.population.clone(),
                false => self.population(g)?,
            };
            snapshots.insert(g, Arc::new(Snapshot::new(&evolution, population)));
        }
        let lookup = self
            .stored_lookup(last, &progress.population, fresh)?
            .map(|l| Arc::new(RwLock::new(l)));
        let threads = rayon::current_num_threads().max(1);
        let mut standings = Standings::of(&progress.population);
        let cancel = self.cancel.clone();
        let work = |thread: usize, (number, snapshot): Order<G>| {
            // On rank 0 of an MPI job, its own births count as its own walks.
            #[cfg(feature = "mpi")]
            let _own = crate::evolve::mpi::OwnWalk::start();
            evolution
                .birth(number, &snapshot, lookup.as_deref(), &cancel)
                .map(|mut b| {
                    b.walk.thread = thread as u32;
                    b
                })
        };
        // On rank 0 of an MPI job, the other ranks make births too.
        #[cfg(feature = "mpi")]
        let stream = crate::evolve::steady::BirthStream::start(
            evolution.clone(),
            lookup.clone(),
            threads,
            self.cancel.clone(),
        );
        with_workers(threads, work, |orders, made| {
            #[cfg(feature = "mpi")]
            let mut births = match stream {
                Some(stream) => Births::Ranks {
                    stream: Box::new(stream),
                    orders,
                    made,
                },
                None => Births::Here { orders, made },
            };
            #[cfg(not(feature = "mpi"))]
            let mut births = Births::Here { orders, made };
            // A panic of this thread stops the births in flight at their next control step
            // (dropped before `births`, which waits for the births on other ranks).
            let _stop = CancelOnUnwind(self.cancel.clone());
            let mut bred = integrated;
            // The last generation whose births are all integrated: births bred from it may
            // start.
            let mut ready = last;
            let send = |births: &mut Births<'_, G>,
                        bred: &mut u64,
                        ready: u32,
                        snapshots: &BTreeMap<u32, Arc<Snapshot<G>>>| {
                while *bred < end && blocks.source(*bred) <= ready {
                    let snapshot = snapshots[&blocks.source(*bred)].clone();
                    births.offer((*bred, snapshot));
                    *bred += 1;
                }
                births.dispatch();
            };
            let mut waiting: BTreeMap<u64, Birth<G>> = BTreeMap::new();
            let mut block = Block::new();
            let outcome = (|| -> Result<(), RunError> {
                while integrated < end {
                    send(&mut births, &mut bred, ready, &snapshots);
                    let birth = births.next()?;
                    waiting.insert(birth.number, birth);
                    while let Some(birth) = waiting.remove(&integrated) {
                        self.integrate(progress, &mut standings, &mut block, birth);
                        integrated += 1;
                        if integrated < blocks.end_of(ready + 1) {
                            continue;
                        }
                        ready += 1;
                        let done = std::mem::replace(&mut block, Block::new());
                        mark_survivors(progress, ready, &done.replaced);
                        // The births bred from this generation go out before anything waits.
                        if let Some(lookup) = &lookup {
                            let new = lookup
                                .write()
                                .unwrap_or_else(|poisoned| poisoned.into_inner())
                                .add(ready, &progress.population);
                            births.stored(ready, new);
                        }
                        let snapshot = Snapshot::new(&evolution, progress.population.clone());
                        snapshots.insert(ready, Arc::new(snapshot));
                        send(&mut births, &mut bred, ready, &snapshots);
                        let needed = blocks.source(bred.min(end.saturating_sub(1)));
                        snapshots.retain(|&g, _| g >= needed);
                        let evaluated = done.started.elapsed().as_secs_f64();
                        self.conclude_block(
                            scope, pool, progress, pending, ready, done, evaluated, observer,
                        )?;
                        // The next block's clock starts once this one is handed over.
                        block.started = Instant::now();
                    }
                }
                Ok(())
            })();
            if outcome.is_err() {
                // The births in flight stop at their next control step.
                self.cancel.cancel();
            }
            outcome
        })
    }

    /// Integrates `birth` into the population (replace-worst), noting it in `block`.
    fn integrate(
        &mut self,
        progress: &mut Progress<G>,
        standings: &mut Standings,
        block: &mut Block,
        birth: Birth<G>,
    ) {
        block.walks.push(birth.walk);
        if !birth.simulated {
            block.reused += 1;
        }
        if let Some(slot) = standings.replace_worst(birth.individual.evaluation.fitness) {
            progress.population[slot] = birth.individual;
            block.replaced.insert(slot);
        }
    }

    /// Hands generation `generation`, the population once `block`'s births are integrated
    /// (in `evaluated` seconds), over to be stored ([`Run::hand_over`]), after the one
    /// `pending` holds.
    #[allow(clippy::too_many_arguments)]
    fn conclude_block<'scope>(
        &mut self,
        scope: &'scope Scope<'scope, '_>,
        pool: Option<&'scope ThreadPool>,
        progress: &mut Progress<G>,
        pending: &mut Option<Pending<'scope, G>>,
        generation: u32,
        block: Block,
        evaluated: f64,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError>
    where
        G: 'scope,
        G::Limits: 'scope,
    {
        if let Some(previous) = pending.take() {
            self.conclude_pending(progress, previous, observer)?;
        }
        // The previous generation's best, replaced in this block, is not this one's elite.
        if let Some((p, _)) = progress.previous_best
            && block.replaced.contains(&(p as usize))
        {
            progress.previous_best = None;
        }
        let births = block.walks.len() as u64;
        let times = GenerationTimes {
            evaluating: evaluated,
            walks: block.walks,
            ..GenerationTimes::default()
        };
        let evaluated = Evaluated {
            generation,
            evaluations: births,
            reused: Some(block.reused),
            times,
            started: block.started,
            evaluated,
        };
        self.hand_over(scope, pool, progress, pending, evaluated, observer)
    }

    /// The evaluations a steady-state birth may reuse: every member of the generations up to
    /// `last` (`population`, when `fresh`: bred in this call, perhaps not stored yet) that
    /// this program's evaluator made, by key, as the store holds them; `None` with the cache
    /// off.
    fn stored_lookup(
        &self,
        last: u32,
        population: &[Individual<G>],
        fresh: bool,
    ) -> Result<Option<Lookup>, RunError> {
        if !self.config.cache {
            return Ok(None);
        }
        let current = self.store.evaluators()?;
        let mut lookup = Lookup::default();
        for g in 0..=last {
            let made_here = fresh && g == last;
            if made_here || current.contains(&(g, EVALUATOR_VERSION)) {
                let _ = match made_here {
                    true => lookup.add(g, population),
                    false => lookup.add(g, &self.population(g)?),
                };
            }
        }
        Ok(Some(lookup))
    }
}

/// Marks the members of generation `generation` not `replaced` in its block as a
/// generational run's elite are stored: not reused (`reused` marks the births of this block
/// that reused an evaluation: the generation's count of reused evaluations is the block's,
/// kept or not), made by `elite` from itself, its own slot in the generation before.
fn mark_survivors<G>(progress: &mut Progress<G>, generation: u32, replaced: &BTreeSet<usize>) {
    for (slot, member) in progress.population.iter_mut().enumerate() {
        if !replaced.contains(&slot) {
            member.reused = false;
            member.operator = Operator::Elite;
            member.parents = vec![slot as u32];
            member.parents_generation = generation.checked_sub(1);
        }
    }
}
