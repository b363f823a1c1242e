//! The run loop of a steady-state run ([`crate::evolve::steady`]): generation 0 as the
//! generational algorithm makes it, then births handed to this process's threads as soon as
//! the generation they are bred from is stored, evaluated in any order, integrated in birth
//! order through a reorder buffer, and every block of births stored as a generation. The
//! threads never wait for a generation's end: only the births of the block after next wait.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, RwLock};
use std::time::Instant;

use super::pool::{Panicked, with_workers};
use super::progress::Progress;
use super::{GenerationReport, Run, RunError};
use crate::cancel::{Cancel, Interrupted};
use crate::encoding::Genome;
use crate::evolve::evaluator_version::EVALUATOR_VERSION;
use crate::evolve::ga::Operator;
use crate::evolve::steady::{Birth, Blocks, Lookup, Snapshot, Standings};
use crate::evolve::timing::{GenerationTimes, WalkTime};

/// A birth to make: its number and the generation it is bred from.
type Order<G> = (u64, Arc<Snapshot<G>>);

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
    /// none), calling `observer` after each.
    pub(super) fn run_steady(
        &mut self,
        progress: &mut Progress<G>,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError> {
        let generations = self.config.ga.generations as u32;
        if progress.next == 0 && generations > 0 {
            self.generation(progress, 0, observer)?;
            progress.next = 1;
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
        let lookup = self.stored_lookup(last)?.map(|l| Arc::new(RwLock::new(l)));
        let threads = rayon::current_num_threads().max(1);
        let mut standings = Standings::of(&progress.population);
        let cancel = self.cancel.clone();
        let work = |thread: usize, (number, snapshot): Order<G>| {
            evolution
                .birth(number, &snapshot, lookup.as_deref(), &cancel)
                .map(|mut b| {
                    b.walk.thread = thread as u32;
                    b
                })
        };
        with_workers(threads, work, |orders, births| {
            // A panic of this thread stops the births in flight at their next control step.
            let _stop = CancelOnUnwind(self.cancel.clone());
            let mut bred = integrated;
            let mut stored = last;
            let mut waiting: BTreeMap<u64, Birth<G>> = BTreeMap::new();
            let mut block = Block::new();
            let outcome = (|| -> Result<(), RunError> {
                while integrated < end {
                    while bred < end && blocks.source(bred) <= stored {
                        let snapshot = snapshots[&blocks.source(bred)].clone();
                        // The workers hold the receiver until this function returns.
                        let _ = orders.send((bred, snapshot));
                        bred += 1;
                    }
                    let birth = match births.recv() {
                        Ok(Ok(birth)) => birth?,
                        Ok(Err(Panicked(message))) => return Err(RunError::Panicked(message)),
                        Err(_) => return Err(RunError::Interrupted(Interrupted)),
                    };
                    waiting.insert(birth.number, birth);
                    while let Some(birth) = waiting.remove(&integrated) {
                        self.integrate(progress, &mut standings, &mut block, birth);
                        integrated += 1;
                        if integrated < blocks.end_of(stored + 1) {
                            continue;
                        }
                        stored += 1;
                        let done = std::mem::replace(&mut block, Block::new());
                        self.conclude_block(progress, stored, done, observer)?;
                        // The next block's clock starts once this one is stored.
                        block.started = Instant::now();
                        if let Some(lookup) = &lookup {
                            lookup
                                .write()
                                .unwrap_or_else(|poisoned| poisoned.into_inner())
                                .add(stored, &progress.population);
                        }
                        let snapshot = Snapshot::new(&evolution, progress.population.clone());
                        snapshots.insert(stored, Arc::new(snapshot));
                        let needed = blocks.source(bred.min(end.saturating_sub(1)));
                        snapshots.retain(|&g, _| g >= needed);
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

    /// Stores generation `generation`, the population once `block`'s births are integrated.
    fn conclude_block(
        &mut self,
        progress: &mut Progress<G>,
        generation: u32,
        block: Block,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError> {
        if let Some((p, _)) = progress.previous_best
            && block.replaced.contains(&(p as usize))
        {
            progress.previous_best = None;
        }
        // As a generational run's elite, a member born before this block is stored as not
        // reused (`reused` marks the births of this block that reused an evaluation: the
        // generation's count of reused evaluations is the block's, kept or not), made by
        // `elite` from itself, its own slot in the generation before.
        for (slot, member) in progress.population.iter_mut().enumerate() {
            if !block.replaced.contains(&slot) {
                member.reused = false;
                member.operator = Operator::Elite;
                member.parents = vec![slot as u32];
                member.parents_generation = generation.checked_sub(1);
            }
        }
        let births = block.walks.len() as u64;
        let times = GenerationTimes {
            evaluating: block.started.elapsed().as_secs_f64(),
            walks: block.walks,
            ..GenerationTimes::default()
        };
        let counts = (births, Some(block.reused));
        self.conclude(progress, generation, counts, times, block.started, observer)
    }

    /// The evaluations a steady-state birth may reuse: every member of the stored generations
    /// up to `last` that this program's evaluator made, by key; `None` with the cache off.
    fn stored_lookup(&self, last: u32) -> Result<Option<Lookup>, RunError> {
        if !self.config.cache {
            return Ok(None);
        }
        let current = self.store.evaluators()?;
        let mut lookup = Lookup::default();
        for g in 0..=last {
            if current.contains(&(g, EVALUATOR_VERSION)) {
                lookup.add(g, &self.population(g)?);
            }
        }
        Ok(Some(lookup))
    }
}
