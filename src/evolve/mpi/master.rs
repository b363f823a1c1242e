//! Rank 0's side of the job: it hands a batch's jobs to its own threads and to the workers,
//! and gathers their outcomes.
//!
//! Rank 0's threads take jobs one at a time from the [`Queues`] while its main thread serves
//! the workers. A worker gets its jobs in chunks, guided self-scheduling: a share of the
//! jobs not yet handed out in proportion to its threads (half of it, so that the last
//! chunks are small), at least two jobs a thread; it asks again once it holds no more than
//! one job a thread, with every outcome it finished, or, told it had its last jobs of the
//! batch, once it has done them all. A batch that develops new births deals them out at the
//! start, every worker its whole share in one message, and each sends the outcomes back in
//! one. Between messages the main thread sleeps, longer and longer up to half the length of
//! a job (never back to the shortest sleep after a request: workers ask a job ahead), and its
//! own threads wake it when they finish the batch's last job.

use std::any::Any;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use mpi::point_to_point::MatchedReceiveVec;
use mpi::request::LocalScope;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use rayon::prelude::*;

mod stream;
use stream::decode_request;
pub(super) use stream::stored_keys;
pub use stream::{Clock, Stream};

use super::queue::Queues;
use super::wire::{Bytes, Outcome, Reply, Work, encode};
use super::{
    BREEDING_NANOS, Batch, OWN_WALK_NANOS, REPLY, REQUEST, Setup, fail, process_cpu, receive,
    thread_cpu,
};
use crate::creature::Creature;
use crate::task::TaskSpec;

/// The shortest and longest sleeps of rank 0's main thread between two looks for requests
/// when one may come any time.
const MIN_PAUSE: Duration = Duration::from_micros(20);
const MAX_PAUSE: Duration = Duration::from_millis(50);
/// The longest sleep while a request is expected at a known time, or none can come (its
/// threads wake it at the batch's end).
const LONG_PAUSE: Duration = Duration::from_secs(1);
/// The least of the longest sleeps (for jobs shorter than two of it).
const FIRST_PAUSE: Duration = Duration::from_millis(1);

/// Rank 0's view of a worker.
#[derive(Default)]
pub(super) struct Worker {
    /// Its threads, as it last said.
    pub threads: usize,
    /// Jobs sent and not yet done.
    in_flight: usize,
    /// Whether it waits for an answer: it sent a request rank 0 has not answered (rank 0
    /// holds the answer back while the worker has no job and there is none to give).
    pub waiting: bool,
    /// The version of the task it has (0: none).
    task_version: u64,
    /// The version of the setup it has (0: none).
    setup_version: u64,
    /// Whether its last answer held its last jobs of the batch.
    last: bool,
    /// When rank 0 last answered it.
    answered: Option<Instant>,
    /// How long a job of the current batch takes it, as its requests show (`None`: not
    /// known yet).
    length: Option<Duration>,
}

/// What rank 0 knows of the job between batches.
pub(super) struct Master {
    pub workers: Vec<Worker>,
    /// The current task, encoded, and its version (1 for the first).
    task: Vec<u8>,
    task_version: u64,
    /// The current setup, encoded and as sent, and its version (0: none yet).
    setup: Option<(Vec<u8>, Setup)>,
    setup_version: u64,
    /// The number of the current births.
    births: u64,
    /// Whether to count CPU time (`ONTOGENY_MPI_TIMING`).
    timing: bool,
    /// How long one of this process's jobs took in the last batch of births developed and
    /// of walks, on average.
    job_length: [Option<Duration>; 2],
    /// What [`Master::report`] says.
    counts: Counts,
}

/// Rank 0's figures for `ONTOGENY_MPI_TIMING`.
#[derive(Default)]
struct Counts {
    /// Walks evaluated on other ranks and on this one.
    remote: u64,
    local: u64,
    /// Births developed on other ranks and on this one.
    developed_remote: u64,
    developed_local: u64,
    /// Steady-state births made on other ranks (and, of them, those found stored, not
    /// walked) and on this one; each is counted as one walk too.
    born_remote: u64,
    stored_remote: u64,
    born_local: u64,
    /// CPU time of rank 0's main thread in batches (`None`: unreadable).
    main_cpu: Option<Duration>,
    /// The process's CPU time when it joined.
    process_joined: Option<Duration>,
    /// Times the main thread woke from a sleep in a batch; requests received; replies sent;
    /// bytes of replies.
    wakes: u64,
    requests: u64,
    replies: u64,
    bytes: u64,
    /// Wall time spent in batches (from the first job handed out to the last outcome in).
    batches: Duration,
    /// When this process joined the job.
    joined: Option<Instant>,
}

/// Rank 0's replies of one batch being sent without waiting (an MPI send of a large message
/// waits for its receiver, and workers look for messages only between sleeps).
struct Outgoing<'a, 's> {
    world: &'a SimpleCommunicator,
    scope: &'s LocalScope<'a>,
    /// The replies' bytes, which must outlive their sends; `used` of them are.
    outbox: &'a [OnceLock<Vec<u8>>],
    used: usize,
    sending: Vec<mpi::request::Request<'a, [u8], &'s LocalScope<'a>>>,
}

impl<'a, 's> Outgoing<'a, 's> {
    /// Starts sending `bytes` to `rank` as a reply; returns their length.
    fn send(&mut self, rank: i32, bytes: Vec<u8>) -> usize {
        let length = bytes.len();
        let process = self.world.process_at_rank(rank);
        match self.outbox.get(self.used) {
            Some(slot) => {
                self.used += 1;
                let _ = slot.set(bytes);
                let kept = slot.get().expect("just set");
                self.sending
                    .push(process.immediate_send_with_tag(self.scope, &kept[..], REPLY));
            }
            // More replies than a batch can need: send and wait.
            None => process.send_with_tag(&bytes[..], REPLY),
        }
        length
    }

    /// Lets MPI move the sends on; forgets those done.
    fn progress(&mut self) {
        self.sending = std::mem::take(&mut self.sending)
            .into_iter()
            .filter_map(|request| request.test().err())
            .collect();
    }

    /// Waits for every send to complete.
    fn finish(self) {
        for request in self.sending {
            request.wait();
        }
    }
}

/// The average of `jobs` lengths summing to `nanos` (`None` before the first).
fn average(nanos: &AtomicUsize, jobs: &AtomicUsize) -> Option<Duration> {
    match jobs.load(Ordering::SeqCst) {
        0 => None,
        jobs => Some(Duration::from_nanos(
            (nanos.load(Ordering::SeqCst) / jobs) as u64,
        )),
    }
}

/// When `worker` will send its next request, for jobs of the length its requests showed or
/// else of `length` (`None` where either is
/// unknown), counted from rank 0's last answer: once it has done all it holds after its last jobs,
/// otherwise once it holds one a thread; three quarters of that, since its threads may be
/// faster than this process's. A worker that waits for an answer sends none.
fn expected(worker: &Worker, length: Option<Duration>) -> Option<Instant> {
    if worker.waiting || worker.in_flight == 0 {
        return None;
    }
    let threads = worker.threads.max(1);
    let before = worker
        .in_flight
        .saturating_sub(if worker.last { 0 } else { threads });
    let length = worker.length.or(length)?;
    Some(worker.answered? + length * (before as u32) * 3 / (4 * threads as u32))
}

/// `cpu` per evaluation of `evaluations`, in microseconds, as words.
fn per_evaluation(cpu: Option<Duration>, evaluations: u64) -> String {
    match cpu {
        Some(cpu) => format!(
            "{:.1} µs",
            cpu.as_secs_f64() * 1e6 / evaluations.max(1) as f64
        ),
        None => "unknown (no CPU clock)".to_string(),
    }
}

impl Master {
    /// Rank 0 of a job whose workers (ranks 1 and on) have each sent their first request.
    pub(super) fn new(workers: Vec<Worker>, timing: bool) -> Master {
        Master {
            workers,
            task: Vec::new(),
            task_version: 0,
            setup: None,
            setup_version: 0,
            births: 0,
            timing,
            job_length: [None, None],
            counts: Counts {
                main_cpu: Some(Duration::ZERO),
                process_joined: process_cpu(),
                joined: Some(Instant::now()),
                ..Counts::default()
            },
        }
    }

    /// Makes `task` the one the next jobs are of (a new version when it differs).
    pub(super) fn set_task(&mut self, task: &TaskSpec) {
        let encoded = encode(task);
        if encoded != self.task {
            self.task = encoded;
            self.task_version += 1;
        }
    }

    /// Makes `setup` the one the next batches' genomes need.
    pub(super) fn set_setup(&mut self, setup: Setup) {
        let encoded = encode(&setup);
        if self.setup.as_ref().map(|(bytes, _)| bytes) != Some(&encoded) {
            self.setup = Some((encoded, setup));
            self.setup_version += 1;
        }
    }

    /// The outcomes of `batch`'s jobs on `task`, in order, with the rank that did each:
    /// this process's threads and the workers take jobs from the queues until every job is
    /// done. A panic of a job on this process's threads is raised again here once the
    /// workers have finished theirs.
    pub(super) fn run(
        &mut self,
        world: &SimpleCommunicator,
        task: &TaskSpec,
        batch: &Batch<'_>,
    ) -> Vec<(u32, Outcome)> {
        let main_started = thread_cpu();
        let size = batch.holders.len();
        let batch_started = Instant::now();
        self.set_task(task);
        if batch.new_births {
            self.births += 1;
        }
        for worker in &mut self.workers {
            worker.length = None;
        }
        let threads = rayon::current_num_threads();
        let mut dealt = vec![threads];
        dealt.extend(self.workers.iter().map(|w| w.threads));
        let all_threads: usize = dealt.iter().sum();
        let queues = Queues::new(
            &batch.holders,
            world.size() as usize,
            batch.new_births.then_some(&dealt[..]),
            batch.steal,
        );
        // How long this process's jobs take, on average: rank 0's main thread sleeps up to
        // half of that between looks for requests.
        let local_nanos = AtomicUsize::new(0);
        let local_jobs = AtomicUsize::new(0);
        let done = AtomicUsize::new(0);
        let panicked: Mutex<Option<Box<dyn Any + Send>>> = Mutex::new(None);
        let slots: Vec<OnceLock<(u32, Outcome)>> = (0..size).map(|_| OnceLock::new()).collect();
        // The replies of this batch, kept until their sends complete: at most one per
        // request with outcomes (one per job) and two per worker (its first request, and
        // the answer held back from the previous batch).
        let outbox: Vec<OnceLock<Vec<u8>>> = (0..size + 2 * self.workers.len() + 1)
            .map(|_| OnceLock::new())
            .collect();
        let main = std::thread::current();
        let timing = self.timing;
        std::thread::scope(|threads_scope| {
            // This process's threads take jobs one at a time from the queues the workers'
            // jobs come from, while this thread (the one that initialised MPI) serves them.
            threads_scope.spawn(|| {
                (0..threads).into_par_iter().for_each(|_| {
                    while let Some(&(index, stolen)) = queues.take(0, 1).first() {
                        let started = Instant::now();
                        let cpu = thread_cpu().filter(|_| timing);
                        let job = std::panic::AssertUnwindSafe(|| (batch.local)(index, stolen));
                        match std::panic::catch_unwind(job) {
                            Ok(outcome) => {
                                if let (Outcome::Evaluated(_), Some(before), Some(after)) =
                                    (&outcome, cpu, thread_cpu().filter(|_| timing))
                                {
                                    let walked = after.saturating_sub(before).as_nanos();
                                    OWN_WALK_NANOS.fetch_add(walked as u64, Ordering::SeqCst);
                                }
                                let _ = slots[index].set((0, outcome));
                            }
                            Err(payload) => {
                                let mut first = panicked.lock().unwrap_or_else(|p| p.into_inner());
                                first.get_or_insert(payload);
                            }
                        }
                        local_nanos
                            .fetch_add(started.elapsed().as_nanos() as usize, Ordering::SeqCst);
                        local_jobs.fetch_add(1, Ordering::SeqCst);
                        if done.fetch_add(1, Ordering::SeqCst) + 1 == size {
                            main.unpark();
                        }
                    }
                })
            });
            mpi::request::scope(|scope| {
                let mut outgoing = Outgoing {
                    world,
                    scope,
                    outbox: &outbox,
                    used: 0,
                    sending: Vec::new(),
                };
                let mut pause = MIN_PAUSE;
                for rank in 1..world.size() {
                    self.answer_if_waiting(&mut outgoing, rank, task, batch, &queues, all_threads);
                }
                while done.load(Ordering::SeqCst) < size {
                    outgoing.progress();
                    let Some(matched) = world
                        .any_process()
                        .immediate_matched_probe_with_tag(REQUEST)
                    else {
                        std::thread::park_timeout(pause);
                        self.counts.wakes += 1;
                        let length = average(&local_nanos, &local_jobs)
                            .or(self.job_length[usize::from(!batch.new_births)]);
                        let longest =
                            length.map_or(MAX_PAUSE, |l| (l / 2).clamp(FIRST_PAUSE, MAX_PAUSE));
                        // Asleep until the first request rank 0 expects (or, with none to
                        // expect, until its threads wake it), then looking more and more
                        // often.
                        let now = Instant::now();
                        let busy: Vec<&Worker> =
                            self.workers.iter().filter(|w| !w.waiting).collect();
                        let next = busy.iter().filter_map(|w| expected(w, length)).min();
                        // A worker on its last jobs asks only when done, which a guess of
                        // its pace may put late: look at least every `longest` then.
                        let most = match busy.iter().any(|w| w.last) {
                            true => longest,
                            false => LONG_PAUSE,
                        };
                        pause = match next {
                            _ if busy.is_empty() => LONG_PAUSE,
                            Some(due) if due > now + MIN_PAUSE => (due - now).min(most),
                            _ => (pause * 2).min(longest),
                        };
                        continue;
                    };
                    let (bytes, status) = matched.matched_receive_vec::<u8>();
                    let rank = status.source_rank();
                    self.counts.requests += 1;
                    let request = decode_request(world, rank, &bytes);
                    let worker = &mut self.workers[rank as usize - 1];
                    worker.threads = request.threads.max(1) as usize;
                    worker.in_flight = worker.in_flight.saturating_sub(request.outcomes.len());
                    if let (Some(answered), Ok(done @ 1..)) =
                        (worker.answered, u32::try_from(request.outcomes.len()))
                    {
                        worker.length = Some(answered.elapsed() * worker.threads as u32 / done);
                    }
                    worker.waiting = true;
                    for (index, outcome) in request.outcomes {
                        let fits = matches!(
                            (&outcome, batch.new_births),
                            (Outcome::Developed(_), true) | (Outcome::Evaluated(_), false)
                        );
                        let slot = slots.get(index as usize).filter(|_| fits);
                        match slot {
                            Some(slot) if slot.get().is_none() => {
                                let _ = slot.set((rank as u32, outcome));
                                done.fetch_add(1, Ordering::SeqCst);
                            }
                            _ => fail(
                                world,
                                &format!(
                                    "rank {rank} sent an outcome for job {index} that it was not given"
                                ),
                            ),
                        }
                    }
                    self.answer_if_waiting(&mut outgoing, rank, task, batch, &queues, all_threads);
                }
                outgoing.finish();
            });
        });
        self.counts.batches += batch_started.elapsed();
        if let Some(length) = average(&local_nanos, &local_jobs) {
            self.job_length[usize::from(!batch.new_births)] = Some(length);
        }
        if let Some(payload) = panicked.into_inner().unwrap_or_else(|p| p.into_inner()) {
            std::panic::resume_unwind(payload);
        }
        let outcomes: Vec<(u32, Outcome)> = slots
            .into_iter()
            .enumerate()
            .map(|(index, slot)| {
                slot.into_inner()
                    .unwrap_or_else(|| fail(world, &format!("job {index} has no outcome")))
            })
            .collect();
        let counts = &mut self.counts;
        for (rank, outcome) in &outcomes {
            *match (outcome, *rank == 0) {
                (Outcome::Evaluated(_) | Outcome::Born { .. }, false) => &mut counts.remote,
                (Outcome::Evaluated(_) | Outcome::Born { .. }, true) => &mut counts.local,
                (Outcome::Developed(_), false) => &mut counts.developed_remote,
                (Outcome::Developed(_), true) => &mut counts.developed_local,
            } += 1;
        }
        counts.main_cpu = match (counts.main_cpu, main_started, thread_cpu()) {
            (Some(sum), Some(start), Some(end)) => Some(sum + end.saturating_sub(start)),
            _ => None,
        };
        outcomes
    }

    /// Sends jobs to the worker of `rank` if it waits for an answer and the queues have some
    /// for it (its whole share of new births, or a guided chunk of walks), or an empty answer
    /// if it waits with jobs still to finish (its next request brings them); a worker with
    /// nothing to do keeps waiting.
    fn answer_if_waiting<'a>(
        &mut self,
        outgoing: &mut Outgoing<'a, '_>,
        rank: i32,
        task: &TaskSpec,
        batch: &Batch<'_>,
        queues: &Queues,
        all_threads: usize,
    ) {
        let worker = &self.workers[rank as usize - 1];
        if !worker.waiting {
            return;
        }
        let threads = worker.threads.max(1);
        let wanted = match batch.new_births {
            true => usize::MAX,
            false => (queues.remaining() * threads)
                .div_ceil(2 * all_threads.max(1))
                .max(2 * threads)
                .saturating_sub(worker.in_flight),
        };
        let jobs = queues.take(rank as usize, wanted);
        if jobs.is_empty() && worker.in_flight == 0 {
            return;
        }
        let last = jobs.len() < wanted;
        let jobs: Vec<(u32, Work<&Creature>)> = jobs
            .iter()
            .map(|&(i, stolen)| (i as u32, (batch.wire)(i, stolen)))
            .collect();
        self.reply_with(rank, task, jobs, Bytes::default(), last, |bytes| {
            outgoing.send(rank, bytes)
        });
    }

    /// Waits for every worker to ask for work, then tells each to stop.
    pub(super) fn stop(&mut self, world: &SimpleCommunicator) {
        while self.workers.iter().any(|w| !w.waiting) {
            let (rank, _) = receive(world, None, REQUEST);
            let worker = &mut self.workers[rank as usize - 1];
            worker.waiting = true;
            worker.in_flight = 0;
        }
        let bytes = encode(&Reply::<Creature, TaskSpec, Setup>::Stop);
        for rank in 1..world.size() {
            world.process_at_rank(rank).send_with_tag(&bytes[..], REPLY);
        }
    }

    /// Rank 0's figures, as `ONTOGENY_MPI_TIMING` prints them.
    pub(super) fn report(&self, ranks: i32) -> String {
        let c = &self.counts;
        let evaluations = c.remote + c.local;
        let own_walks = Duration::from_nanos(OWN_WALK_NANOS.load(Ordering::SeqCst));
        let process = match (process_cpu(), c.process_joined) {
            (Some(now), Some(joined)) => Some(now.saturating_sub(joined).saturating_sub(own_walks)),
            _ => None,
        };
        let outside = c.joined.map_or(0.0, |joined| {
            (joined.elapsed().saturating_sub(c.batches)).as_secs_f64()
        });
        let steady = match c.born_remote + c.born_local {
            0 => String::new(),
            _ => format!(
                "; {} steady-state births made on other ranks ({} of them found stored, not walked; {:.2} s of rank 0's CPU time breeding them), {} on rank 0",
                c.born_remote,
                c.stored_remote,
                Duration::from_nanos(BREEDING_NANOS.load(Ordering::SeqCst)).as_secs_f64(),
                c.born_local
            ),
        };
        format!(
            "MPI: {ranks} ranks; {} walks on other ranks, {} on rank 0; {} births developed on other ranks, {} on rank 0{steady}; {:.2} s of batches ({outside:.2} s outside them: breeding, the store); rank 0's CPU time per walk: {} on its main thread in batches, {} in the whole process less its own walks ({:.2} s of them, the fine re-walks among them); main thread woke {} times, {} requests in, {} replies out ({} bytes per reply)",
            c.remote,
            c.local,
            c.developed_remote,
            c.developed_local,
            c.batches.as_secs_f64(),
            per_evaluation(c.main_cpu, evaluations),
            per_evaluation(process, evaluations),
            own_walks.as_secs_f64(),
            c.wakes,
            c.requests,
            c.replies,
            c.bytes / c.replies.max(1),
        )
    }
}
