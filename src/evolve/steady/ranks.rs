//! A steady-state run's births over the ranks of an MPI job (the `mpi` feature), on rank 0.
//!
//! The run's driver (on rank 0's main thread, the one that initialised MPI) offers each birth
//! as soon as the generation it is bred from is integrated ([`BirthStream::offer`]), and takes
//! the births made, in any order ([`BirthStream::next`]). A birth goes either to rank 0's own
//! threads, which breed, develop, key and evaluate it as a run on one process does
//! ([`Evolution::birth`]), or to a worker: rank 0's rayon threads breed it ahead of need
//! ([`Evolution::breed_birth`]), the main thread sends its genome and development seed
//! ([`Work::Birth`], through a [`Stream`]), and the worker develops and keys it, skips its
//! walks if its copy of the stored keys holds its key from a generation up to its source, and
//! otherwise evaluates it as rank 0 would ([`super::evaluate_birth`]). A skipped birth gets
//! the stored evaluation here, from the run's [`Lookup`]. A birth is therefore the same
//! wherever it is made, and the run the same on any number of ranks.
//!
//! Rank 0's threads hold at most one birth more than they are; the workers are given births
//! as they ask ([`Stream`]); births bred for the workers that none wants go back to rank 0's
//! threads. Between looks for requests the main thread waits for its own threads' births, up
//! to a pause set by the workers' pace.

use std::collections::{HashMap, VecDeque};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, RwLock};
use std::time::Duration;

use super::super::ga::{Evolution, Operator, Unborn};
use super::super::key::EvaluationKey;
use super::super::mpi::{
    Bytes, Outcome, Setup, Stream, Work, breeding, encode, key_version_number,
};
use super::{Birth, Blocks, Lookup, Made, Order, panic_message};
use crate::cancel::Cancel;
use crate::encoding::Genome;

/// The wait for this process's births between two looks for requests before the workers'
/// pace is known.
const FIRST: Duration = Duration::from_micros(500);
/// The bounds of the wait once it is known: a quarter of a birth's length on a worker
/// divided by its threads.
const BOUNDS: (Duration, Duration) = (Duration::from_micros(500), Duration::from_millis(50));

/// What [`BirthStream::next`] gives.
pub enum Next<L, G> {
    /// A result of this process's threads, as they sent it.
    Local(L),
    /// A birth a worker made.
    Remote(Box<Birth<G>>),
    /// This process's threads ended (they dropped their results' sender).
    Closed,
    /// The run was told to stop.
    Cancelled,
    /// Breeding a birth for the workers panicked: its message.
    Panicked(String),
}

/// A birth bred for a worker, not yet sent.
struct Bred<G> {
    order: Order<G>,
    unborn: Unborn<G>,
    fell_back: Option<Operator>,
    genome: Bytes,
}

/// A birth on a worker: what rank 0 keeps of it until its outcome comes.
struct Away<G> {
    number: u64,
    unborn: Unborn<G>,
    fell_back: Option<Operator>,
}

/// Rank 0's side of a steady-state run's births over the ranks (see the module's
/// documentation). Dropped, it waits for the births still on workers and forgets them.
pub struct BirthStream<G: Genome> {
    stream: Stream,
    evolution: Arc<Evolution<G>>,
    blocks: Blocks,
    lookup: Option<Arc<RwLock<Lookup>>>,
    cancel: Cancel,
    key_version: u8,
    /// Births offered and neither handed to this process's threads nor being bred.
    offered: VecDeque<Order<G>>,
    /// Births bred for the workers; how many are being bred; where the breeding sends them.
    bred: VecDeque<Bred<G>>,
    breeding: usize,
    bred_sender: Sender<Result<Bred<G>, String>>,
    bred_receiver: Receiver<Result<Bred<G>, String>>,
    /// The message of a breeding that panicked.
    panicked: Option<String>,
    /// This process's threads, and the births handed to them and not yet given back.
    threads: usize,
    here: usize,
    /// Births on workers, by job number; the next job number.
    away: HashMap<u32, Away<G>>,
    job: u32,
    /// Births the workers made, not yet given back.
    made: VecDeque<Birth<G>>,
    /// The wait for this process's births between looks for requests, and the sum and count
    /// of the births' lengths the workers reported.
    pause: Duration,
    lengths: (f64, u64),
}

impl<G: Genome> BirthStream<G> {
    /// The stream of `evolution`'s births over the job's ranks, with `threads` threads of this
    /// process beside the workers; a birth stored as `lookup` says up to its source is not
    /// walked. `None` on a process that is not rank 0 of a job of several ranks, and for a run
    /// whose keys hash stored `[task]` tables (version 1 keys of an old run: its births stay
    /// on this process).
    pub fn start(
        evolution: Arc<Evolution<G>>,
        lookup: Option<Arc<RwLock<Lookup>>>,
        threads: usize,
        cancel: Cancel,
    ) -> Option<BirthStream<G>> {
        if evolution.key_tables.is_some() {
            return None;
        }
        let stored: Vec<([u8; 32], u32)> = match &lookup {
            Some(lookup) => lookup
                .read()
                .unwrap_or_else(|poisoned| poisoned.into_inner())
                .entries()
                .map(|(key, first)| (key.0, first))
                .collect(),
            None => Vec::new(),
        };
        let setup = Setup::of::<G>(&evolution.limits, &evolution.task);
        let stream = Stream::start(&evolution.task, setup, stored)?;
        let (bred_sender, bred_receiver) = mpsc::channel();
        Some(BirthStream {
            stream,
            blocks: Blocks::of(&evolution.settings),
            key_version: key_version_number(evolution.key_version),
            evolution,
            lookup,
            cancel,
            offered: VecDeque::new(),
            bred: VecDeque::new(),
            breeding: 0,
            bred_sender,
            bred_receiver,
            panicked: None,
            threads: threads.max(1),
            here: 0,
            away: HashMap::new(),
            job: 0,
            made: VecDeque::new(),
            pause: FIRST,
            lengths: (0.0, 0),
        })
    }

    /// Offers birth `order`: it goes to the first rank (or thread of this process) with room
    /// for it, from the next [`BirthStream::dispatch`] on.
    pub fn offer(&mut self, order: Order<G>) {
        self.offered.push_back(order);
    }

    /// Notes `keys` as first stored by generation `generation` (those stored before keep
    /// their first generation): the workers learn them before any birth offered after.
    pub fn stored(&mut self, generation: u32, keys: Vec<EvaluationKey>) {
        self.stream
            .stored(generation, keys.into_iter().map(|key| key.0));
    }

    /// Hands the births offered out: to this process's threads through `orders` (up to one
    /// more than they are), bred ahead for the workers, and sent to the workers that ask;
    /// takes the births the workers made.
    pub fn dispatch(&mut self, orders: &Sender<Order<G>>) {
        let clock = self.stream.clock();
        self.hand_out(orders);
        self.stream.clocked(clock);
    }

    /// [`BirthStream::dispatch`], its time not counted.
    fn hand_out(&mut self, orders: &Sender<Order<G>>) {
        self.feed(orders);
        // Enough bred ahead to fill every worker twice over.
        let ahead = 2 * self.stream.capacity();
        while self.bred.len() + self.breeding < ahead
            && let Some(order) = self.offered.pop_front()
        {
            self.breed(order);
        }
        while let Ok(bred) = self.bred_receiver.try_recv() {
            self.breeding -= 1;
            match bred {
                Ok(bred) => self.bred.push_back(bred),
                Err(message) => {
                    self.panicked.get_or_insert(message);
                }
            }
        }
        let outcomes = self.stream.receive();
        for (job, rank, outcome) in outcomes {
            let birth = self.born(job, rank, outcome);
            self.made.push_back(birth);
        }
        for (rank, room) in self.stream.hungry() {
            let count = room.min(self.bred.len());
            if count == 0 {
                continue;
            }
            let jobs = self
                .bred
                .drain(..count)
                .map(|bred| {
                    let job = self.job;
                    self.job = self.job.wrapping_add(1);
                    let work = Work::Birth {
                        genome: bred.genome,
                        seed: bred.unborn.develop_seed,
                        key_version: self.key_version,
                        source: self.blocks.source(bred.order.0),
                    };
                    self.away.insert(
                        job,
                        Away {
                            number: bred.order.0,
                            unborn: bred.unborn,
                            fell_back: bred.fell_back,
                        },
                    );
                    (job, work)
                })
                .collect();
            self.stream.send(rank, jobs);
        }
        // A worker that asked while it holds births gets an empty answer, so that it goes on
        // sending back what it finishes, unless births are being bred for it.
        if self.breeding == 0 {
            self.stream.release();
        }
        // Births bred for workers that none wants go to this process's threads (which breed
        // them again) once nothing else is offered.
        while self.here <= self.threads
            && self.offered.is_empty()
            && let Some(bred) = self.bred.pop_back()
        {
            let _ = orders.send(bred.order);
            self.here += 1;
        }
    }

    /// Hands offered births to this process's threads, up to one more than they are.
    fn feed(&mut self, orders: &Sender<Order<G>>) {
        while self.here <= self.threads
            && let Some(order) = self.offered.pop_front()
        {
            // The threads hold the receiver until the driver returns.
            let _ = orders.send(order);
            self.here += 1;
        }
    }

    /// Breeds `order` on one of rank 0's rayon threads, for a worker.
    fn breed(&mut self, order: Order<G>) {
        let (evolution, sender) = (self.evolution.clone(), self.bred_sender.clone());
        self.breeding += 1;
        rayon::spawn(move || {
            let bred = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                let (unborn, fell_back) = breeding(|| evolution.breed_birth(order.0, &order.1));
                let genome = Bytes(encode(&unborn.genome));
                Bred {
                    order,
                    unborn,
                    fell_back,
                    genome,
                }
            }));
            let _ = sender.send(bred.map_err(|payload| panic_message(payload.as_ref())));
        });
    }

    /// The birth of job `job` from `outcome`, which `rank` made.
    fn born(&mut self, job: u32, rank: i32, outcome: Outcome) -> Birth<G> {
        let Some(away) = self.away.remove(&job) else {
            super::super::mpi::broken(&format!("rank {rank} made job {job}, which is no birth"))
        };
        let Outcome::Born {
            sizes,
            evaluation,
            seconds,
            thread,
        } = outcome
        else {
            super::super::mpi::broken(&format!("rank {rank} sent no birth for job {job}"))
        };
        self.lengths.0 += seconds;
        self.lengths.1 += 1;
        let key = sizes.key.map(EvaluationKey);
        let simulated = evaluation.is_some();
        let evaluation = evaluation.unwrap_or_else(|| {
            let source = self.blocks.source(away.number);
            let stored = key.zip(self.lookup.as_ref()).and_then(|(key, lookup)| {
                lookup
                    .read()
                    .unwrap_or_else(|poisoned| poisoned.into_inner())
                    .find(&key, source)
                    .cloned()
            });
            stored.unwrap_or_else(|| {
                super::super::mpi::broken(&format!(
                    "rank {rank} found birth {} stored, which it is not",
                    away.number
                ))
            })
        });
        self.stream.count_births(1, u64::from(!simulated), 0);
        let made = Made {
            evaluation,
            simulated,
            size: sizes.size(),
            key,
            seconds,
            thread,
            rank: rank as u32,
        };
        Birth::of(&self.blocks, away.number, away.unborn, away.fell_back, made)
    }

    /// The next birth made, by a worker or by this process's threads (which take their
    /// orders from `orders` and give their results through `results`), waiting for one.
    pub fn next<L>(&mut self, orders: &Sender<Order<G>>, results: &Receiver<L>) -> Next<L, G> {
        loop {
            if self.cancel.is_cancelled() {
                return Next::Cancelled;
            }
            let clock = self.stream.clock();
            self.hand_out(orders);
            let birth = self.made.pop_front();
            self.stream.clocked(clock);
            if let Some(message) = self.panicked.take() {
                return Next::Panicked(message);
            }
            if let Some(birth) = birth {
                return Next::Remote(Box::new(birth));
            }
            match results.recv_timeout(self.pause) {
                Ok(result) => {
                    self.here = self.here.saturating_sub(1);
                    self.stream.count_births(0, 0, 1);
                    return Next::Local(result);
                }
                Err(RecvTimeoutError::Disconnected) => return Next::Closed,
                Err(RecvTimeoutError::Timeout) => {
                    self.stream.woke();
                    self.pause = self.longest();
                }
            }
        }
    }

    /// The wait between looks for requests: a quarter of the time between two births
    /// finishing on the busiest worker, as the workers report their lengths. A worker asks as
    /// soon as one of its threads takes its spare birth, so its threads idle only if rank 0
    /// has not answered by the time the next one finishes.
    fn longest(&self) -> Duration {
        let (sum, count) = self.lengths;
        match count {
            0 => FIRST,
            _ => {
                let threads = self.stream.most_threads().max(1) as f64;
                Duration::from_secs_f64(sum / count as f64 / threads / 4.0)
                    .clamp(BOUNDS.0, BOUNDS.1)
            }
        }
    }
}
