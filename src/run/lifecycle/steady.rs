//! The run loop of a steady-state run ([`crate::evolve::steady`]): generation 0 as the
//! generational algorithm makes it, then births handed to this process's threads as soon as
//! the generation they are bred from is stored, evaluated in any order, integrated in birth
//! order through a reorder buffer, and every block of births stored as a generation. The
//! threads never wait for a generation's end: only the births of the block after next wait.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, Mutex, RwLock, mpsc};
use std::time::Instant;

use super::progress::Progress;
use super::{GenerationReport, Run, RunError};
use crate::cancel::Interrupted;
use crate::encoding::Genome;
use crate::evolve::evaluator::Evaluator;
use crate::evolve::evaluator_version::EVALUATOR_VERSION;
use crate::evolve::steady::{Birth, Blocks, Lookup, Snapshot, replace_worst};
use crate::evolve::timing::{GenerationTimes, WalkTime};
use crate::lang::{Diagnostic, DiagnosticKind};

/// A birth to make: its number and the generation it is bred from.
type Order<G> = (u64, Arc<Snapshot<G>>);

/// What happened in the block of births being integrated.
struct Block {
    started: Instant,
    /// The slots a newborn took.
    replaced: BTreeSet<usize>,
    /// Each birth's evaluation, in birth order.
    walks: Vec<WalkTime>,
}

impl Block {
    fn new() -> Block {
        Block {
            started: Instant::now(),
            replaced: BTreeSet::new(),
            walks: Vec::new(),
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
        if Evaluator::current().ranks() > 1 {
            return Err(RunError::Config(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                "algorithm \"steady-state\" runs on one process's threads: start it without an \
                 MPI launcher (over MPI ranks only \"generational\" runs)"
                    .to_string(),
            )));
        }
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
        let (order_tx, order_rx) = mpsc::channel::<Order<G>>();
        let order_rx = Mutex::new(order_rx);
        let (birth_tx, birth_rx) = mpsc::channel::<Result<Birth<G>, Interrupted>>();
        std::thread::scope(|scope| {
            for thread in 0..threads {
                let (order_rx, birth_tx) = (&order_rx, birth_tx.clone());
                let (evolution, lookup) = (&evolution, &lookup);
                let cancel = self.cancel.clone();
                scope.spawn(move || {
                    loop {
                        let next = order_rx
                            .lock()
                            .unwrap_or_else(|poisoned| poisoned.into_inner())
                            .recv();
                        let Ok((number, snapshot)) = next else {
                            return; // the run is over: no more births
                        };
                        let birth = evolution
                            .birth(number, &snapshot, lookup.as_deref(), &cancel)
                            .map(|mut b| {
                                b.walk.thread = thread as u32;
                                b
                            });
                        if birth_tx.send(birth).is_err() {
                            return;
                        }
                    }
                });
            }
            drop(birth_tx);
            let mut bred = integrated;
            let mut stored = last;
            let mut waiting: BTreeMap<u64, Birth<G>> = BTreeMap::new();
            let mut block = Block::new();
            let outcome = (|| -> Result<(), RunError> {
                while integrated < end {
                    while bred < end && blocks.source(bred) <= stored {
                        let snapshot = snapshots[&blocks.source(bred)].clone();
                        // The workers hold the receiver until this function returns.
                        let _ = order_tx.send((bred, snapshot));
                        bred += 1;
                    }
                    let birth = birth_rx.recv().map_err(|_| Interrupted)??;
                    waiting.insert(birth.number, birth);
                    while let Some(birth) = waiting.remove(&integrated) {
                        self.integrate(progress, &mut block, birth);
                        integrated += 1;
                        if integrated < blocks.end_of(stored + 1) {
                            continue;
                        }
                        stored += 1;
                        let done = std::mem::replace(&mut block, Block::new());
                        self.conclude_block(progress, stored, done, observer)?;
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
            drop(order_tx);
            outcome
        })
    }

    /// Integrates `birth` into the population (replace-worst), noting it in `block`.
    fn integrate(&mut self, progress: &mut Progress<G>, block: &mut Block, birth: Birth<G>) {
        block.walks.push(birth.walk);
        if let Some(slot) = replace_worst(&progress.population, birth.individual.evaluation.fitness)
        {
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
        // reused: `reused` marks the births of this block that reused an evaluation.
        for (slot, member) in progress.population.iter_mut().enumerate() {
            if !block.replaced.contains(&slot) {
                member.reused = false;
            }
        }
        let births = block.walks.len() as u64;
        let times = GenerationTimes {
            evaluating: block.started.elapsed().as_secs_f64(),
            walks: block.walks,
            ..GenerationTimes::default()
        };
        self.conclude(progress, generation, births, times, block.started, observer)
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
