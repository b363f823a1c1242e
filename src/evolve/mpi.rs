//! One population's evaluations spread over the ranks of an MPI job (the `mpi` feature).
//!
//! Rank 0 runs the genetic algorithm and owns the run directory; every other rank is a
//! worker that evaluates the creatures rank 0 sends it and sends their evaluations back.
//! Rank 0 sends developed creatures, not genomes: it must develop every individual anyway, to
//! key it for the evaluation cache before deciding which individuals to simulate, and a
//! creature is all an evaluation depends on besides the task — so workers need no encoding and
//! never develop twice. The task is sent once per worker and again only when it changes.
//!
//! Work is handed out dynamically from one queue of job indices: rank 0's own threads take
//! jobs from it one at a time while its main thread serves the workers, each of which holds
//! at most one job per thread. The exchange with each worker strictly alternates — it sends a
//! request (the evaluations it finished and how many threads it has), rank 0 answers with jobs
//! (or holds the answer while it has none, or says stop) — so two sends never cross and no
//! message size can deadlock; rank 0 sends without waiting for the receiver. Both sides look
//! for messages by polling with short sleeps, not in MPI's busy-waiting blocking receive, so
//! a rank that waits leaves its cores to the evaluations.
//! Messages are MessagePack, which carries every `f64` and `f32` exactly (NaN included): an
//! evaluation made on a worker is bit-identical to one made on rank 0.
//!
//! Set `ONTOGENY_MPI_TIMING=1` to have rank 0 say, at the end, how its evaluations were shared
//! and how long it spent per remote evaluation on encoding, messages and decoding.

use std::ops::Range;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, mpsc};
use std::time::{Duration, Instant};

use mpi::environment::Universe;
use mpi::point_to_point::MatchedReceiveVec;
use mpi::request::LocalScope;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::creature::Creature;
use crate::task::{Evaluation, TaskSpec, Unit};

/// A walk to simulate: a creature and its unit, if any ([`TaskSpec::evaluate_job`]).
pub type Job<'a> = (&'a Creature, Option<Unit>);

/// Worker → rank 0: evaluations finished, and the worker's number of threads.
const REQUEST: i32 = 1;
/// Rank 0 → worker: jobs, or stop.
const REPLY: i32 = 2;

/// The environment variables an MPI launcher sets in the processes it starts (Open MPI's
/// `mpirun`, MPICH's Hydra, Slurm's `srun` through PMI or PMIx).
const LAUNCHER_VARIABLES: [&str; 5] = [
    "OMPI_COMM_WORLD_SIZE",
    "PMI_RANK",
    "PMI_SIZE",
    "PMIX_RANK",
    "MPI_LOCALNRANKS",
];

/// The environment variable that asks rank 0 for its dispatch figures.
const TIMING_VARIABLE: &str = "ONTOGENY_MPI_TIMING";

/// What a worker sends rank 0.
#[derive(Serialize, Deserialize)]
struct Request {
    /// The worker's number of threads: it holds at most this many jobs.
    threads: u32,
    /// Evaluations finished since its last request, by job index in the batch.
    evaluations: Vec<(u32, Evaluation)>,
}

/// What rank 0 sends a worker (`C` and `T`: a creature and a task, owned or borrowed).
#[derive(Serialize, Deserialize)]
enum Reply<C, T> {
    /// Jobs of the current batch, by index, with the batch's task when the worker lacks it.
    Work {
        /// The task, when it differs from the one the worker has.
        task: Option<T>,
        /// The jobs: index, creature and unit.
        jobs: Vec<(u32, C, Option<Unit>)>,
    },
    /// No more work: the worker ends.
    Stop,
}

/// Whether an MPI launcher started this process.
pub fn launched() -> bool {
    LAUNCHER_VARIABLES
        .iter()
        .any(|name| std::env::var_os(name).is_some())
}

/// Rank 0's view of a worker.
#[derive(Default)]
struct Worker {
    /// Its threads, as it last said.
    threads: usize,
    /// Jobs sent and not yet evaluated.
    in_flight: usize,
    /// Whether it waits for an answer: it sent a request rank 0 has not answered (rank 0
    /// holds the answer back while the worker has no job and there is none to give).
    waiting: bool,
    /// The version of the task it has (0: none).
    task_version: u64,
}

/// What rank 0 knows of the job between batches.
struct Master {
    workers: Vec<Worker>,
    /// The current task, encoded, and its version (1 for the first).
    task: Vec<u8>,
    task_version: u64,
    /// Evaluations made on other ranks and on this one.
    remote: u64,
    local: u64,
    /// Time rank 0's main thread spent encoding jobs, sending, receiving and decoding.
    dispatch: Duration,
    /// Bytes of jobs sent.
    bytes: u64,
    /// Wall time spent in batches (from the first job handed out to the last evaluation in).
    batches: Duration,
    /// When this process joined the job.
    joined: Instant,
}

/// Rank 0's state, when this process is rank 0 of a job of several ranks.
static MASTER: Mutex<Option<Master>> = Mutex::new(None);

fn master() -> MutexGuard<'static, Option<Master>> {
    MASTER
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Whether this process is rank 0 of a job of several ranks that it joined.
pub fn is_master() -> bool {
    master().is_some()
}

/// This process's membership of the job, held by rank 0 while its verb runs: dropping it
/// stops the workers and ends MPI.
pub struct Membership {
    _universe: Universe,
}

impl std::fmt::Debug for Membership {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Membership")
    }
}

/// Joins the job: on a worker rank, serves rank 0 until it says stop and returns `None`;
/// on rank 0 (or a job of one rank) returns the membership to hold. The error says why this
/// process cannot take its part.
pub fn join() -> Result<Option<Membership>, String> {
    let (universe, threading) = mpi::initialize_with_threading(mpi::Threading::Serialized)
        .ok_or_else(|| "MPI was initialised twice".to_string())?;
    if threading < mpi::Threading::Funneled {
        return Err(format!(
            "the MPI library offers threading level {threading:?}; ontogeny needs Funneled"
        ));
    }
    let world = universe.world();
    if world.rank() > 0 {
        if let Err(message) = serve(&world) {
            eprintln!("error: MPI rank {}: {message}", world.rank());
            world.abort(1);
        }
        return Ok(None);
    }
    if world.size() > 1 {
        *master() = Some(Master {
            workers: (1..world.size()).map(|_| Worker::default()).collect(),
            task: Vec::new(),
            task_version: 0,
            remote: 0,
            local: 0,
            dispatch: Duration::ZERO,
            bytes: 0,
            batches: Duration::ZERO,
            joined: Instant::now(),
        });
    }
    Ok(Some(Membership {
        _universe: universe,
    }))
}

impl Drop for Membership {
    fn drop(&mut self) {
        let Some(mut state) = master().take() else {
            return;
        };
        let world = SimpleCommunicator::world();
        state.stop(&world);
        if std::env::var_os(TIMING_VARIABLE).is_some() {
            let per = state.dispatch.as_secs_f64() * 1e6 / state.remote.max(1) as f64;
            eprintln!(
                "MPI: {} ranks; {} evaluations on other ranks, {} on rank 0, in {:.2} s of batches ({:.2} s outside them: development, the fine re-walks, the store); rank 0 spent {per:.0} µs per remote evaluation on encoding, messages and decoding ({} bytes per job)",
                world.size(),
                state.remote,
                state.local,
                state.batches.as_secs_f64(),
                (state.joined.elapsed() - state.batches).as_secs_f64(),
                state.bytes / state.remote.max(1),
            );
        }
    }
}

/// The number of ranks of the job this process is rank 0 of (1 when it is none's).
pub fn ranks() -> u32 {
    master()
        .as_ref()
        .map_or(1, |state| state.workers.len() as u32 + 1)
}

/// The evaluations of `creatures` (with their units) on `task`, in order, over every rank of
/// the job.
pub fn evaluate(task: &TaskSpec, creatures: &[Job<'_>]) -> Vec<Evaluation> {
    let mut guard = master();
    match guard.as_mut() {
        Some(state) => state.evaluate(&SimpleCommunicator::world(), task, creatures),
        None => evaluate_locally(task, creatures),
    }
}

/// The evaluations of `creatures` on `task`, in order, on this process's worker threads: a
/// batch on a process that is not rank 0 of a job of several ranks, and a worker's share.
pub fn evaluate_locally(task: &TaskSpec, creatures: &[Job<'_>]) -> Vec<Evaluation> {
    creatures
        .par_iter()
        .map(|(creature, unit)| task.evaluate_job_plainly(creature, unit.as_ref()))
        .collect()
}

/// The next `count` jobs of a batch of `size` from `queue` (fewer, or none, near its end).
fn take(queue: &AtomicUsize, count: usize, size: usize) -> Range<usize> {
    let start = queue.fetch_add(count, Ordering::SeqCst);
    start.min(size)..(start + count).min(size)
}

/// Waits (polling, with sleeps growing to a millisecond) for a message with `tag` from
/// `source` (any rank when `None`); returns its sender and bytes.
fn receive(world: &SimpleCommunicator, source: Option<i32>, tag: i32) -> (i32, Vec<u8>) {
    let mut pause = MIN_PAUSE;
    loop {
        let probe = match source {
            Some(rank) => world
                .process_at_rank(rank)
                .immediate_matched_probe_with_tag(tag),
            None => world.any_process().immediate_matched_probe_with_tag(tag),
        };
        if let Some(matched) = probe {
            let (bytes, status) = matched.matched_receive_vec::<u8>();
            return (status.source_rank(), bytes);
        }
        std::thread::sleep(pause);
        pause = (pause * 2).min(MAX_PAUSE);
    }
}

fn encode<T: Serialize>(value: &T) -> Vec<u8> {
    rmp_serde::to_vec_named(value).expect("plain data encodes as MessagePack")
}

/// The shortest and longest sleeps between two looks for a message.
const MIN_PAUSE: Duration = Duration::from_micros(20);
const MAX_PAUSE: Duration = Duration::from_millis(1);

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

impl Master {
    /// The evaluations of `creatures` on `task`, in order: this process's threads and the
    /// workers take jobs from one queue until every job is evaluated.
    fn evaluate(
        &mut self,
        world: &SimpleCommunicator,
        task: &TaskSpec,
        creatures: &[Job<'_>],
    ) -> Vec<Evaluation> {
        let size = creatures.len();
        let batch_started = Instant::now();
        let encoded = encode(task);
        if encoded != self.task {
            self.task = encoded;
            self.task_version += 1;
        }
        let queue = AtomicUsize::new(0);
        let done = AtomicUsize::new(0);
        let slots: Vec<OnceLock<Evaluation>> = (0..size).map(|_| OnceLock::new()).collect();
        // The replies of this batch, kept until their sends complete: at most one per
        // request with evaluations (one per job) and two per worker (its first request, and
        // the answer held back from the previous batch).
        let outbox: Vec<OnceLock<Vec<u8>>> = (0..size + 2 * self.workers.len() + 1)
            .map(|_| OnceLock::new())
            .collect();
        let threads = rayon::current_num_threads();
        let remote_before = self.remote;
        std::thread::scope(|threads_scope| {
            // This process's threads take jobs one at a time from the queue the workers'
            // jobs come from, while this thread (the one that initialised MPI) serves them.
            threads_scope.spawn(|| {
                (0..threads).into_par_iter().for_each(|_| {
                    while let Some(index) = take(&queue, 1, size).next() {
                        let (creature, unit) = &creatures[index];
                        let _ =
                            slots[index].set(task.evaluate_job_plainly(creature, unit.as_ref()));
                        done.fetch_add(1, Ordering::SeqCst);
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
                for rank in 1..world.size() {
                    self.answer_if_waiting(&mut outgoing, rank, task, creatures, &queue);
                }
                let mut pause = MIN_PAUSE;
                while done.load(Ordering::SeqCst) < size {
                    outgoing.progress();
                    let Some(matched) = world
                        .any_process()
                        .immediate_matched_probe_with_tag(REQUEST)
                    else {
                        std::thread::sleep(pause);
                        pause = (pause * 2).min(MAX_PAUSE);
                        continue;
                    };
                    pause = MIN_PAUSE;
                    let started = Instant::now();
                    let (bytes, status) = matched.matched_receive_vec::<u8>();
                    let rank = status.source_rank();
                    let request: Request = rmp_serde::from_slice(&bytes).unwrap_or_else(|e| {
                        fail(world, &format!("a request from rank {rank}: {e}"))
                    });
                    let worker = &mut self.workers[rank as usize - 1];
                    worker.threads = request.threads.max(1) as usize;
                    worker.in_flight = worker.in_flight.saturating_sub(request.evaluations.len());
                    worker.waiting = true;
                    for (index, evaluation) in request.evaluations {
                        let _ = slots[index as usize].set(evaluation);
                        done.fetch_add(1, Ordering::SeqCst);
                    }
                    self.dispatch += started.elapsed();
                    self.answer_if_waiting(&mut outgoing, rank, task, creatures, &queue);
                }
                outgoing.finish();
            });
        });
        self.local += (size as u64).saturating_sub(self.remote - remote_before);
        self.batches += batch_started.elapsed();
        slots
            .into_iter()
            .map(|slot| slot.into_inner().expect("every job is evaluated"))
            .collect()
    }

    /// Sends jobs to the worker of `rank` if it waits for an answer and the queue has some,
    /// or an empty answer if it waits with jobs still to finish (its next request brings
    /// them); a worker with nothing to do keeps waiting.
    fn answer_if_waiting<'a>(
        &mut self,
        outgoing: &mut Outgoing<'a, '_>,
        rank: i32,
        task: &TaskSpec,
        creatures: &[Job<'_>],
        queue: &AtomicUsize,
    ) {
        let started = Instant::now();
        let version = self.task_version;
        let worker = &mut self.workers[rank as usize - 1];
        if !worker.waiting || worker.threads == 0 {
            return;
        }
        let jobs = take(
            queue,
            worker.threads.saturating_sub(worker.in_flight),
            creatures.len(),
        );
        if jobs.is_empty() && worker.in_flight == 0 {
            return;
        }
        let reply: Reply<&Creature, &TaskSpec> = Reply::Work {
            task: (worker.task_version != version).then_some(task),
            jobs: jobs
                .clone()
                .map(|i| (i as u32, creatures[i].0, creatures[i].1))
                .collect(),
        };
        let bytes = outgoing.send(rank, encode(&reply));
        worker.task_version = version;
        worker.in_flight += jobs.len();
        worker.waiting = false;
        self.remote += jobs.len() as u64;
        self.bytes += bytes as u64;
        self.dispatch += started.elapsed();
    }

    /// Waits for every worker to ask for work, then tells each to stop.
    fn stop(&mut self, world: &SimpleCommunicator) {
        while self.workers.iter().any(|w| !w.waiting) {
            let (rank, _) = receive(world, None, REQUEST);
            let worker = &mut self.workers[rank as usize - 1];
            worker.waiting = true;
            worker.in_flight = 0;
        }
        let bytes = encode(&Reply::<Creature, TaskSpec>::Stop);
        for rank in 1..world.size() {
            world.process_at_rank(rank).send_with_tag(&bytes[..], REPLY);
        }
    }
}

/// Ends the whole job after saying why (a message that does not decode: ranks built from
/// different sources).
fn fail(world: &SimpleCommunicator, what: &str) -> ! {
    eprintln!(
        "error: MPI rank {}: cannot decode {what} (are all ranks the same ontogeny build?)",
        world.rank()
    );
    world.abort(1)
}

/// A worker's loop: asks rank 0 for work, evaluates it on this process's threads, sends the
/// evaluations back with the next request; ends when rank 0 says stop.
fn serve(world: &SimpleCommunicator) -> Result<(), String> {
    let threads = rayon::current_num_threads() as u32;
    let master = world.process_at_rank(0);
    let (finished, results) = mpsc::channel::<(u32, Evaluation)>();
    let mut task: Option<Arc<TaskSpec>> = None;
    let mut in_flight = 0usize;
    let mut evaluations = Vec::new();
    loop {
        let request = Request {
            threads,
            evaluations: std::mem::take(&mut evaluations),
        };
        master.send_with_tag(&encode(&request)[..], REQUEST);
        let (_, bytes) = receive(world, Some(0), REPLY);
        let reply: Reply<Creature, TaskSpec> =
            rmp_serde::from_slice(&bytes).unwrap_or_else(|e| fail(world, &format!("a job: {e}")));
        let jobs = match reply {
            Reply::Stop => return Ok(()),
            Reply::Work { task: sent, jobs } => {
                if let Some(sent) = sent {
                    task = Some(Arc::new(sent));
                }
                jobs
            }
        };
        for (index, creature, unit) in jobs {
            let task = task
                .clone()
                .ok_or_else(|| "a job came before its task".to_string())?;
            let finished = finished.clone();
            in_flight += 1;
            rayon::spawn(move || {
                let evaluation = task.evaluate_job_plainly(&creature, unit.as_ref());
                let _ = finished.send((index, evaluation));
            });
        }
        if in_flight > 0 {
            let first = results
                .recv()
                .map_err(|_| "an evaluation thread ended".to_string())?;
            evaluations.push(first);
            evaluations.extend(results.try_iter());
            in_flight -= evaluations.len();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::develop::{BuildOptions, grow};
    use crate::lsystem::{DeriveOptions, LSystem};
    use crate::sim::WorldSpec;
    use crate::sim::world_spec::Slope;
    use crate::task::{Habitat, Status, TaskKind};

    /// A creature with real numbers in it: the shipped Hornby & Pollack walker, grown.
    fn walker() -> Creature {
        let lsys = LSystem::from_text(
            "hornby-walker.lsys",
            include_str!("../../examples/hornby-walker.lsys"),
        )
        .unwrap();
        let frames = grow(
            &lsys,
            &DeriveOptions::default(),
            None,
            &BuildOptions::default(),
        )
        .unwrap();
        frames.into_iter().last().unwrap().creature
    }

    #[test]
    fn a_job_and_its_evaluation_cross_between_ranks_bit_for_bit() {
        let creature = walker();
        assert!(!creature.parts.is_empty());
        let mut task = TaskSpec::new(TaskKind::Walker);
        *task.seconds_mut() = 1.0 / 3.0;
        // A habitat on a slope, two noisy trials: the unit and its world cross too.
        task.habitats = vec![Habitat {
            name: "hill".into(),
            world: WorldSpec {
                slope: Some(Slope {
                    degrees: 5.0,
                    direction: 0.0,
                }),
                ..WorldSpec::default()
            },
            environment: None,
            trials: None,
        }];
        task.trials.count = 2;
        task.trials.heading = 10.0;
        let unit = task.units([3; 32], 0)[1];
        let sent: Reply<&Creature, &TaskSpec> = Reply::Work {
            task: Some(&task),
            jobs: vec![(7, &creature, Some(unit))],
        };
        let bytes = encode(&sent);
        let Reply::Work {
            task: Some(received_task),
            jobs,
        } = rmp_serde::from_slice::<Reply<Creature, TaskSpec>>(&bytes).unwrap()
        else {
            panic!("not the work sent");
        };
        assert_eq!(jobs, vec![(7, creature.clone(), Some(unit))]);
        assert_eq!(encode(&received_task), encode(&task));
        assert_eq!(received_task.habitats, task.habitats);
        // The task evaluates the received creature and unit as it does the originals.
        let evaluation = task.evaluate_job_plainly(&creature, Some(&unit));
        assert_eq!(
            received_task.evaluate_job_plainly(&jobs[0].1, jobs[0].2.as_ref()),
            evaluation
        );
        // Every f64, even those JSON cannot carry, comes back with the same bits.
        let odd = [
            f64::NAN,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.1 + 0.2,
            5e-324,
        ];
        let mut strange = Evaluation {
            status: Status::Unstable,
            ..evaluation
        };
        for (i, value) in odd.iter().enumerate() {
            strange.terms.insert(format!("t{i}"), *value);
        }
        let request = Request {
            threads: 3,
            evaluations: vec![(7, strange.clone())],
        };
        let back: Request = rmp_serde::from_slice(&encode(&request)).unwrap();
        assert_eq!(back.threads, 3);
        let (index, returned) = &back.evaluations[0];
        assert_eq!(*index, 7);
        assert_eq!(returned.fitness.to_bits(), strange.fitness.to_bits());
        for (name, value) in &strange.terms {
            assert_eq!(returned.terms[name].to_bits(), value.to_bits(), "{name}");
        }
    }
}
