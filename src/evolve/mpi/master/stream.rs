//! A steady-state run's births over the ranks of an MPI job: rank 0's side of the stream.
//!
//! The run's driver (on rank 0's main thread, the one that initialised MPI) offers each birth
//! as soon as the generation it is bred from is integrated ([`BirthStream::offer`]), and takes
//! the births made, in any order ([`BirthStream::next`]). A birth goes either to rank 0's own
//! threads, which breed, develop, key and evaluate it as a run on one process does, or to a
//! worker: rank 0 breeds it (its genome and development seed), and the worker develops, keys
//! and evaluates it ([`Work::Birth`]) and sends back its key, its creatures' sizes and its
//! evaluation. A worker keeps a copy of the keys stored so far, each with the first generation
//! that stored it, sent with its replies ([`BirthStream::stored`]): a birth whose key a
//! generation up to its source stored is not walked, and rank 0 gives it the stored
//! evaluation, as a run on one process does. A birth is therefore the same wherever it is
//! made, and the run the same on any number of ranks.
//!
//! Each worker holds at most one birth more than it has threads: it asks again, with the
//! births it finished, as soon as one of its threads falls free, so a birth's outcome comes
//! back while its thread goes on with the next. Rank 0's own threads likewise hold one birth
//! more than they are. Between looks for requests the main thread waits for its own threads'
//! births, up to a pause that grows while nothing comes.

use std::collections::{HashMap, VecDeque};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, MutexGuard, RwLock};
use std::time::{Duration, Instant};

use mpi::point_to_point::MatchedReceiveVec;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

use super::super::super::ga::{Evolution, Operator, Unborn};
use super::super::super::key::EvaluationKey;
use super::super::super::steady::{Birth, Blocks, Lookup, Snapshot};
use super::super::super::timing::WalkTime;
use super::super::wire::{Outcome, Reply, Request, Work, encode};
use super::super::{Bytes, REPLY, REQUEST, Setup, fail, receive, thread_cpu};
use super::{Master, Worker};
use crate::cancel::Cancel;
use crate::creature::Creature;
use crate::encoding::Genome;
use crate::task::TaskSpec;

/// The shortest wait for this process's births between two looks for requests.
const SHORTEST: Duration = Duration::from_micros(100);
/// The bounds of the longest wait, which is a fraction of a birth's length.
const LONGEST: (Duration, Duration) = (Duration::from_micros(500), Duration::from_millis(20));

/// A birth to make: its number and the generation it is bred from.
pub type Order<G> = (u64, Arc<Snapshot<G>>);

/// What [`BirthStream::next`] gives.
pub enum Next<L, G> {
    /// A result of this process's threads, as they sent it.
    Local(L),
    /// A birth a worker made.
    Remote(Birth<G>),
    /// This process's threads ended (they dropped their results' sender).
    Closed,
    /// The run was told to stop.
    Cancelled,
}

/// A birth on a worker: what rank 0 keeps of it until its outcome comes.
struct Away<G> {
    number: u64,
    unborn: Unborn<G>,
    fell_back: Option<Operator>,
    rank: i32,
}

/// Rank 0's side of a steady-state run's births over the ranks (see the module's
/// documentation); dropped, it waits for the workers' births in flight and leaves the
/// workers waiting for the next batch.
pub struct BirthStream<'e, G: Genome> {
    master: MutexGuard<'static, Option<Master>>,
    world: SimpleCommunicator,
    evolution: &'e Evolution<G>,
    blocks: Blocks,
    lookup: Option<Arc<RwLock<Lookup>>>,
    cancel: Cancel,
    key_version: u8,
    /// Births offered and not yet handed out, in birth order.
    offered: VecDeque<Order<G>>,
    /// This process's threads, and the births handed to them not yet given back by `next`.
    threads: usize,
    here: usize,
    /// The births this process's threads made (counted as `next` gave them back).
    made_here: u64,
    /// Births on workers, by job index; the next index.
    away: HashMap<u32, Away<G>>,
    index: u32,
    /// Births the workers made, not yet given back.
    made: VecDeque<Birth<G>>,
    /// Every key stored, with its first generation, in the order stored; per worker, how many
    /// of them it was sent.
    keys: Vec<([u8; 32], u32)>,
    keys_sent: Vec<usize>,
    /// The wait for this process's births between looks for requests, and the sum and count
    /// of the births' lengths the workers reported.
    pause: Duration,
    lengths: (f64, u64),
    /// The main thread's CPU time and the wall clock when the stream started.
    cpu: Option<Duration>,
    started: Instant,
}

impl Master {
    /// Makes `task` the current one (a new version when it differs) and starts new births: the
    /// workers forget what they held.
    fn begin(&mut self, task: &TaskSpec, setup: Setup) {
        let encoded = encode(task);
        if encoded != self.task {
            self.task = encoded;
            self.task_version += 1;
        }
        self.set_setup(setup);
        self.births += 1;
    }
}

impl<'e, G: Genome> BirthStream<'e, G> {
    /// The stream of `evolution`'s births over the job's ranks, with `threads` threads of this
    /// process beside the workers; a birth stored as `lookup` says up to its source is not
    /// walked. `None` on a process that is not rank 0 of a job of several ranks, and for a run
    /// whose keys hash stored `[task]` tables (version 1 keys of an old run: its births stay
    /// on this process).
    pub fn start(
        evolution: &'e Evolution<G>,
        lookup: Option<Arc<RwLock<Lookup>>>,
        threads: usize,
        cancel: Cancel,
    ) -> Option<BirthStream<'e, G>> {
        if !super::super::is_master() || evolution.key_tables.is_some() {
            return None;
        }
        let mut master = super::super::master();
        let state = master.as_mut()?;
        state.begin(
            &evolution.task,
            Setup::of::<G>(&evolution.limits, &evolution.task),
        );
        let workers = state.workers.len();
        let mut keys = Vec::new();
        if let Some(lookup) = &lookup {
            keys = lookup
                .read()
                .unwrap_or_else(|poisoned| poisoned.into_inner())
                .entries()
                .map(|(key, first)| (key.0, first))
                .collect();
            // The order the keys are sent in changes nothing; sorted, it is the same on every
            // run.
            keys.sort_unstable();
        }
        Some(BirthStream {
            master,
            world: SimpleCommunicator::world(),
            evolution,
            blocks: Blocks::of(&evolution.settings),
            lookup,
            cancel,
            key_version: super::super::super::ga::remote::version_number(evolution.key_version),
            offered: VecDeque::new(),
            threads: threads.max(1),
            here: 0,
            made_here: 0,
            away: HashMap::new(),
            index: 0,
            made: VecDeque::new(),
            keys,
            keys_sent: vec![0; workers],
            pause: SHORTEST,
            lengths: (0.0, 0),
            cpu: thread_cpu(),
            started: Instant::now(),
        })
    }

    /// Offers birth `number`, bred from `snapshot`: it goes to the first rank (or thread of
    /// this process) with room for it.
    pub fn offer(&mut self, number: u64, snapshot: Arc<Snapshot<G>>) {
        self.offered.push_back((number, snapshot));
    }

    /// Notes `keys` as stored by generation `generation` (those stored before keep their
    /// first generation): the workers learn them with their next replies, before any birth
    /// bred from that generation.
    pub fn stored(&mut self, generation: u32, keys: impl IntoIterator<Item = EvaluationKey>) {
        self.keys
            .extend(keys.into_iter().map(|key| (key.0, generation)));
    }

    /// The next birth made, by a worker or by this process's threads (which take their
    /// orders from `orders` and give their results through `results`), waiting for one.
    pub fn next<L>(&mut self, orders: &Sender<Order<G>>, results: &Receiver<L>) -> Next<L, G> {
        loop {
            if self.cancel.is_cancelled() {
                return Next::Cancelled;
            }
            while self.here <= self.threads
                && let Some(order) = self.offered.pop_front()
            {
                // The threads hold the receiver until the driver returns.
                let _ = orders.send(order);
                self.here += 1;
            }
            self.serve();
            if let Some(birth) = self.made.pop_front() {
                return Next::Remote(birth);
            }
            match results.recv_timeout(self.pause) {
                Ok(result) => {
                    self.here = self.here.saturating_sub(1);
                    self.made_here += 1;
                    return Next::Local(result);
                }
                Err(RecvTimeoutError::Disconnected) => return Next::Closed,
                Err(RecvTimeoutError::Timeout) => {
                    self.master_state().counts.wakes += 1;
                    self.pause = (self.pause * 2).min(self.longest());
                }
            }
        }
    }

    fn master_state(&mut self) -> &mut Master {
        self.master.as_mut().expect("a stream has rank 0's state")
    }

    /// The longest wait between looks for requests: a fraction of a birth's length as the
    /// workers report it, so that a worker's free thread rarely waits long for its next
    /// birth (it holds one ahead).
    fn longest(&self) -> Duration {
        let (sum, count) = self.lengths;
        match count {
            0 => LONGEST.0,
            _ => Duration::from_secs_f64(sum / count as f64 / 8.0).clamp(LONGEST.0, LONGEST.1),
        }
    }

    /// Takes every request that has come, with its births, and answers every worker that
    /// waits.
    fn serve(&mut self) {
        while let Some(matched) = self
            .world
            .any_process()
            .immediate_matched_probe_with_tag(REQUEST)
        {
            let (bytes, status) = matched.matched_receive_vec::<u8>();
            let rank = status.source_rank();
            self.take_request(rank, &bytes);
            self.pause = SHORTEST;
        }
        for rank in 1..self.world.size() {
            self.answer(rank);
        }
    }

    /// Takes `rank`'s request `bytes`: its births made.
    fn take_request(&mut self, rank: i32, bytes: &[u8]) {
        let world = &self.world;
        let request: Request = rmp_serde::from_slice(bytes).unwrap_or_else(|e| {
            fail(
                world,
                &format!("cannot decode a request from rank {rank}: {e} (are all ranks the same ontogeny build?)"),
            )
        });
        let state = self.master.as_mut().expect("a stream has rank 0's state");
        state.counts.requests += 1;
        let worker = &mut state.workers[rank as usize - 1];
        worker.threads = request.threads.max(1) as usize;
        worker.in_flight = worker.in_flight.saturating_sub(request.outcomes.len());
        worker.waiting = true;
        state.counts.remote += request.outcomes.len() as u64;
        state.counts.born_remote += request.outcomes.len() as u64;
        for (index, outcome) in request.outcomes {
            let birth = self.born(rank, index, outcome);
            self.made.push_back(birth);
        }
    }

    /// The birth of job `index` from `outcome`, which `rank` sent.
    fn born(&mut self, rank: i32, index: u32, outcome: Outcome) -> Birth<G> {
        let world = &self.world;
        let away = self.away.remove(&index).filter(|a| a.rank == rank);
        let (
            Some(away),
            Outcome::Born {
                sizes,
                evaluation,
                seconds,
                thread,
            },
        ) = (away, outcome)
        else {
            fail(
                world,
                &format!("rank {rank} sent an outcome for job {index} that it was not given"),
            )
        };
        self.lengths.0 += seconds;
        self.lengths.1 += 1;
        let source = self.blocks.source(away.number);
        let (_, place) = self.blocks.place(away.number);
        let key = sizes.key.map(EvaluationKey);
        let simulated = evaluation.is_some();
        if !simulated && let Some(state) = self.master.as_mut() {
            state.counts.stored_remote += 1;
        }
        let evaluation = evaluation.unwrap_or_else(|| {
            let stored = key.zip(self.lookup.as_ref()).and_then(|(key, lookup)| {
                lookup
                    .read()
                    .unwrap_or_else(|poisoned| poisoned.into_inner())
                    .find(&key, source)
                    .cloned()
            });
            stored.unwrap_or_else(|| {
                fail(
                    world,
                    &format!(
                        "rank {rank} found birth {} stored, which it is not",
                        away.number
                    ),
                )
            })
        });
        let size = match &sizes.creatures {
            Ok(creatures) => creatures
                .first()
                .map_or((0, 0, 0), |c| (c.0, c.1, sizes.neurons)),
            Err(_) => (0, 0, 0),
        };
        Birth {
            number: away.number,
            individual: away
                .unborn
                .into_individual(evaluation, size, key, !simulated, source),
            simulated,
            fell_back: away.fell_back,
            walk: WalkTime {
                individual: place as u32,
                seconds,
                thread,
                rank: rank as u32,
                parts: size.0,
            },
        }
    }

    /// Sends births to the worker of `rank` if it waits for an answer: as many as keep it one
    /// ahead of its threads, bred here, with the keys stored since its last answer; an empty
    /// answer if there are none and it has births to finish; nothing (it keeps waiting) if it
    /// has none.
    fn answer(&mut self, rank: i32) {
        let state = self.master.as_mut().expect("a stream has rank 0's state");
        let worker = &state.workers[rank as usize - 1];
        if !worker.waiting {
            return;
        }
        let room = (worker.threads + 1).saturating_sub(worker.in_flight);
        let count = room.min(self.offered.len());
        if count == 0 && worker.in_flight == 0 {
            return;
        }
        let mut jobs: Vec<(u32, Work<&Creature>)> = Vec::with_capacity(count);
        for (number, snapshot) in self.offered.drain(..count) {
            let (unborn, fell_back) = self.evolution.breed_birth(number, &snapshot);
            let index = self.index;
            self.index = self.index.wrapping_add(1);
            jobs.push((
                index,
                Work::Birth {
                    genome: Bytes(encode(&unborn.genome)),
                    seed: unborn.develop_seed,
                    key_version: self.key_version,
                    source: self.blocks.source(number),
                },
            ));
            self.away.insert(
                index,
                Away {
                    number,
                    unborn,
                    fell_back,
                    rank,
                },
            );
        }
        let sent = &mut self.keys_sent[rank as usize - 1];
        let known = self.keys[*sent..].to_vec();
        *sent = self.keys.len();
        send_work(state, &self.world, &self.evolution.task, rank, jobs, known);
    }
}

/// Sends `jobs` and the stored keys `known` to the worker of `rank`, with `task` (the
/// current one) and the setup if it lacks them, and notes them sent.
fn send_work(
    state: &mut Master,
    world: &SimpleCommunicator,
    task: &TaskSpec,
    rank: i32,
    jobs: Vec<(u32, Work<&Creature>)>,
    known: Vec<([u8; 32], u32)>,
) {
    let (task_version, setup_version, births) =
        (state.task_version, state.setup_version, state.births);
    let count = jobs.len();
    let worker = &state.workers[rank as usize - 1];
    let reply: Reply<&Creature, &TaskSpec, &Setup> = Reply::Work {
        task: (worker.task_version != task_version).then_some(task),
        setup: state
            .setup
            .as_ref()
            .filter(|_| worker.setup_version != setup_version)
            .map(|(_, setup)| setup),
        births,
        jobs,
        known,
        last: false,
    };
    let bytes = encode(&reply);
    world.process_at_rank(rank).send_with_tag(&bytes[..], REPLY);
    let worker: &mut Worker = &mut state.workers[rank as usize - 1];
    worker.task_version = task_version;
    worker.setup_version = setup_version;
    worker.in_flight += count;
    worker.waiting = false;
    worker.answered = Some(Instant::now());
    state.counts.replies += 1;
    state.counts.bytes += bytes.len() as u64;
}

impl<G: Genome> Drop for BirthStream<'_, G> {
    fn drop(&mut self) {
        // The births still on workers (a run stopped early) are waited for and forgotten:
        // every worker is left waiting for the next batch, as a batch leaves it.
        let world = SimpleCommunicator::world();
        let state = self.master.as_mut().expect("a stream has rank 0's state");
        while state.workers.iter().any(|w| !w.waiting) {
            let (rank, _) = receive(&world, None, REQUEST);
            let worker = &mut state.workers[rank as usize - 1];
            worker.waiting = true;
            worker.in_flight = 0;
        }
        let counts = &mut state.counts;
        counts.local += self.made_here;
        counts.born_local += self.made_here;
        counts.batches += self.started.elapsed();
        counts.main_cpu = match (counts.main_cpu, self.cpu, thread_cpu()) {
            (Some(sum), Some(start), Some(end)) => Some(sum + end.saturating_sub(start)),
            _ => None,
        };
    }
}
