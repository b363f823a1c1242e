//! One population's evaluations spread over the ranks of an MPI job (the `mpi` feature).
//!
//! Rank 0 runs the genetic algorithm and owns the run directory; every other rank is a
//! worker that does the jobs rank 0 sends it and sends their outcomes back. A generation's
//! births go in two phases (`ga/remote.rs`): rank 0 sends genomes with their development
//! seeds, and the ranks develop and key them, each holding the creatures it developed and
//! sending back their keys and sizes; rank 0 de-duplicates against the cache and within the
//! generation, then sends each holder the walks of its own creatures (an index and a unit, a
//! few bytes), and gets their evaluations back. Jobs of whole creatures (a batch of a verb
//! that develops them itself) go too. The encoding and its limits are sent once per worker,
//! the task once per worker and again when it changes.
//!
//! A steady-state run's births go as a stream instead ([`Stream`], driven by
//! `evolve::steady::BirthStream`): rank 0 sends each birth's genome and development seed to a
//! worker with room for it, and the worker develops, keys and evaluates it, skipping the walks
//! of a creature the run stored up to the birth's source generation (rank 0 sends the keys it
//! stores, each with the first generation that stored it). Its answers are sent and waited
//! for, not left in flight.
//!
//! Work is handed out dynamically ([`master`]): rank 0's own threads take jobs one at a time
//! while its main thread serves the workers in chunks. A job that walks a held creature goes
//! to the rank that holds it, unless another rank has run out of its own jobs (it then
//! develops the creature again). The exchange with each worker strictly alternates — it
//! sends a request (the outcomes it finished and how many threads it has), rank 0 answers
//! with jobs (or holds the answer while it has none, or says stop) — so two sends never
//! cross and no message size can deadlock; rank 0 sends without waiting for the receiver.
//! Both sides look for messages with sleeps between looks, not in MPI's busy-waiting
//! blocking receive, so a rank that waits leaves its cores to the evaluations. Messages are
//! MessagePack ([`wire`]): an evaluation made on a worker is bit-identical to one made on
//! rank 0.
//!
//! Set `ONTOGENY_MPI_TIMING=1` to have rank 0 say, at the end, how its work was shared, how
//! much CPU time it spent per walk, and how often its main thread woke and messages crossed.

use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};
use std::time::Duration;

use mpi::environment::Universe;
use mpi::point_to_point::MatchedReceiveVec;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use rayon::prelude::*;

use crate::creature::Creature;
use crate::task::{Evaluation, TaskSpec, Unit};

mod grow;
mod master;
mod queue;
mod wire;
mod worker;
pub(super) use grow::{Grown, Setup, Sizes, key_version_number};
pub use master::{Clock, Stream};
use master::{Master, Worker, stored_keys};
pub(super) use wire::{Bytes, Outcome, Work, encode};
use wire::{Reply, Request};
use worker::serve;

/// A walk to simulate: a creature and its unit, if any ([`TaskSpec::evaluate_job`]).
pub type Job<'a> = (&'a Creature, Option<Unit>);

/// Worker → rank 0: outcomes finished, and the worker's number of threads.
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

/// CPU time rank 0 spent on walks of its own (its threads' share of batches, the fine
/// re-walks), in nanoseconds, counted with `ONTOGENY_MPI_TIMING` set.
static OWN_WALK_NANOS: AtomicU64 = AtomicU64::new(0);

/// Whether an MPI launcher started this process.
pub fn launched() -> bool {
    LAUNCHER_VARIABLES
        .iter()
        .any(|name| std::env::var_os(name).is_some())
}

/// The CPU time this thread has used (`None` where the system cannot say).
fn thread_cpu() -> Option<Duration> {
    cpu_time::ThreadTime::try_now()
        .ok()
        .map(|t| t.as_duration())
}

/// The CPU time this process has used, every thread's (ended ones too), user and system
/// (`None` where the system cannot say).
fn process_cpu() -> Option<Duration> {
    cpu_time::ProcessTime::try_now()
        .ok()
        .map(|t| t.as_duration())
}

/// CPU time rank 0's threads spent breeding births for other ranks (a steady-state run's), in
/// nanoseconds, counted with `ONTOGENY_MPI_TIMING` set.
static BREEDING_NANOS: AtomicU64 = AtomicU64::new(0);

/// `breed()`, its CPU time counted as rank 0's breeding for other ranks (with
/// `ONTOGENY_MPI_TIMING` set, on rank 0 of a job of several ranks).
pub(in crate::evolve) fn breeding<T>(breed: impl FnOnce() -> T) -> T {
    let counting = std::env::var_os(TIMING_VARIABLE).is_some() && is_master();
    let started = counting.then(thread_cpu).flatten();
    let bred = breed();
    if let (Some(started), Some(now)) = (started, thread_cpu()) {
        let nanos = now.saturating_sub(started).as_nanos() as u64;
        BREEDING_NANOS.fetch_add(nanos, Ordering::SeqCst);
    }
    bred
}

/// A walk rank 0 makes outside batches (the fine re-walk), counted as its own while this
/// lives: [`OwnWalk::start`] it before the walk, drop it after.
pub struct OwnWalk {
    started: Option<Duration>,
}

impl OwnWalk {
    /// Starts counting this thread's CPU time (only on rank 0 of a job of several ranks, with
    /// `ONTOGENY_MPI_TIMING` set).
    pub fn start() -> OwnWalk {
        let counting = std::env::var_os(TIMING_VARIABLE).is_some() && is_master();
        OwnWalk {
            started: counting.then(thread_cpu).flatten(),
        }
    }
}

impl Drop for OwnWalk {
    fn drop(&mut self) {
        if let (Some(started), Some(now)) = (self.started, thread_cpu()) {
            let walked = now.saturating_sub(started).as_nanos() as u64;
            OWN_WALK_NANOS.fetch_add(walked, Ordering::SeqCst);
        }
    }
}

/// Rank 0's state, when this process is rank 0 of a job of several ranks.
static MASTER: Mutex<Option<Master>> = Mutex::new(None);

/// Whether this process is rank 0 of a job of several ranks (read without waiting for
/// [`MASTER`], which a batch holds).
static IS_MASTER: AtomicBool = AtomicBool::new(false);

/// The ranks of the job this process is rank 0 of (1 when it is none's), read without
/// waiting for [`MASTER`] (which a batch or a stream holds).
static RANKS: AtomicU32 = AtomicU32::new(1);

fn master() -> MutexGuard<'static, Option<Master>> {
    MASTER
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Whether this process is rank 0 of a job of several ranks that it joined.
pub fn is_master() -> bool {
    IS_MASTER.load(Ordering::SeqCst)
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
/// on rank 0 (or a job of one rank) returns the membership to hold, once every worker has
/// said how many threads it has. The error says why this process cannot take its part.
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
        let mut workers: Vec<Worker> = (1..world.size()).map(|_| Worker::default()).collect();
        // Every worker's first request says its threads, which the first births are dealt by.
        while workers.iter().any(|w| !w.waiting) {
            let (rank, bytes) = receive(&world, None, REQUEST);
            let request: Request = rmp_serde::from_slice(&bytes).unwrap_or_else(|e| {
                fail(
                    &world,
                    &format!("cannot decode rank {rank}'s first request: {e} (are all ranks the same ontogeny build?)"),
                )
            });
            let worker = &mut workers[rank as usize - 1];
            worker.threads = request.threads.max(1) as usize;
            worker.waiting = true;
        }
        let timing = std::env::var_os(TIMING_VARIABLE).is_some();
        *master() = Some(Master::new(workers, timing));
        RANKS.store(world.size() as u32, Ordering::SeqCst);
        IS_MASTER.store(true, Ordering::SeqCst);
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
        IS_MASTER.store(false, Ordering::SeqCst);
        RANKS.store(1, Ordering::SeqCst);
        let world = SimpleCommunicator::world();
        state.stop(&world);
        if std::env::var_os(TIMING_VARIABLE).is_some() {
            eprintln!("{}", state.report(world.size()));
        }
    }
}

/// The number of ranks of the job this process is rank 0 of (1 when it is none's).
pub fn ranks() -> u32 {
    RANKS.load(Ordering::SeqCst)
}

/// The evaluations of `creatures` (with their units) on `task`, in order, over every rank of
/// the job.
pub fn evaluate(task: &TaskSpec, creatures: &[Job<'_>]) -> Vec<Evaluation> {
    if !is_master() {
        return evaluate_locally(task, creatures);
    }
    let wire = |i: usize, _| Work::Walk(creatures[i].0, creatures[i].1);
    let local = |i: usize, _| {
        let (creature, unit) = &creatures[i];
        Outcome::Evaluated(task.evaluate_job_plainly(creature, unit.as_ref()))
    };
    let batch = Batch {
        holders: vec![None; creatures.len()],
        new_births: false,
        steal: true,
        wire: &wire,
        local: &local,
    };
    run(task, &batch)
        .into_iter()
        .map(|(rank, outcome)| match outcome {
            Outcome::Evaluated(evaluation) => evaluation,
            _ => broken(&format!("rank {rank} developed a walk")),
        })
        .collect()
}

/// The evaluations of `creatures` on `task`, in order, on this process's worker threads: a
/// batch on a process that is not rank 0 of a job of several ranks, and a worker's share.
pub fn evaluate_locally(task: &TaskSpec, creatures: &[Job<'_>]) -> Vec<Evaluation> {
    creatures
        .par_iter()
        .map(|(creature, unit)| task.evaluate_job_plainly(creature, unit.as_ref()))
        .collect()
}

/// Makes `setup` the encoding and limits of the genomes the next batches send (sent to each
/// worker once, and again when it changes). Nothing on a process that is not rank 0 of a
/// job of several ranks.
pub(super) fn set_setup(setup: Setup) {
    if let Some(state) = master().as_mut() {
        state.set_setup(setup);
    }
}

/// A batch of jobs as rank 0 hands them out.
pub(super) struct Batch<'a> {
    /// Per job, the rank that holds what it needs (the job's creature), or `None`: none.
    pub holders: Vec<Option<u32>>,
    /// Whether its jobs develop new births (every rank forgets the creatures it held). The
    /// jobs without a holder are then dealt to the ranks in proportion to their threads (a
    /// birth's walks are done where it was developed, so the births are shared out as the
    /// walks should be), and no rank takes another's.
    pub new_births: bool,
    /// Whether a rank that has run out of its own jobs takes over other ranks' (not with
    /// `new_births`).
    pub steal: bool,
    /// Job `i` as sent to a worker; `true`: a job of another rank's, taken over.
    pub wire: &'a dyn Fn(usize, bool) -> Work<&'a Creature>,
    /// Job `i` done on this process's threads; `true`: a job of another rank's.
    pub local: &'a (dyn Fn(usize, bool) -> Outcome + Sync),
}

/// The outcomes of `batch`'s jobs on `task`, in order, each with the rank that did it, over
/// every rank of the job (on this process's threads when it is not rank 0 of a job of
/// several ranks).
pub(super) fn run(task: &TaskSpec, batch: &Batch<'_>) -> Vec<(u32, Outcome)> {
    let mut guard = master();
    match guard.as_mut() {
        Some(state) => state.run(&SimpleCommunicator::world(), task, batch),
        None => (0..batch.holders.len())
            .into_par_iter()
            .map(|i| (0, (batch.local)(i, false)))
            .collect(),
    }
}

/// Waits (looking every 20 µs at first, then less and less often, at least every
/// millisecond) for a message with `tag` from `source` (any rank when `None`); returns its
/// sender and bytes.
fn receive(world: &SimpleCommunicator, source: Option<i32>, tag: i32) -> (i32, Vec<u8>) {
    let mut pause = Duration::from_micros(20);
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
        pause = (pause * 2).min(Duration::from_millis(1));
    }
}

/// Ends the whole job after saying why (a message that does not decode: ranks built from
/// different sources; or one that breaks the exchange).
fn fail(world: &SimpleCommunicator, what: &str) -> ! {
    eprintln!("error: MPI rank {}: {what}", world.rank());
    world.abort(1)
}

/// Ends the whole job from rank 0 after saying what broke in the exchange with the workers
/// (which a correct build never does).
pub(super) fn broken(what: &str) -> ! {
    fail(&SimpleCommunicator::world(), what)
}
