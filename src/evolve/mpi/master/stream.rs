//! A stream of jobs over the workers of an MPI job: rank 0's side, for work that is handed
//! out as it becomes known rather than in batches (a steady-state run's births,
//! `evolve::steady::ranks`).
//!
//! The caller numbers its jobs and sends each to a worker that waits for work
//! ([`Stream::hungry`], [`Stream::send`]); [`Stream::receive`] takes the requests that came,
//! with the outcomes they bring. A worker holds at most one job more than it has threads: it
//! asks again, with the jobs it finished, as soon as one of its threads falls free, so an
//! outcome comes back while its thread goes on with the next job. A worker that asks while it
//! still has jobs and there is nothing to give it gets an empty answer at once
//! ([`Stream::release`]), so that it goes on sending back what it finishes; one with none is
//! left waiting until there is. The stream also carries the keys a steady-state run has
//! stored, each with the first generation that stored it ([`Stream::stored`]): a worker
//! learns them with its next answer, before any job sent after them.

use std::collections::HashMap;
use std::sync::MutexGuard;
use std::time::{Duration, Instant};

use mpi::point_to_point::MatchedReceiveVec;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

use super::super::wire::{Outcome, Reply, Request, Work, encode};
use super::super::{Bytes, REPLY, REQUEST, Setup, fail, receive, thread_cpu};
use super::Master;
use crate::creature::Creature;
use crate::task::TaskSpec;

/// Rank 0's side of a stream of jobs (see the module's documentation). Dropped, it waits for
/// every job still on a worker, forgets their outcomes, and leaves every worker waiting for
/// the next batch, as a batch leaves it.
pub struct Stream {
    master: MutexGuard<'static, Option<Master>>,
    world: SimpleCommunicator,
    task: TaskSpec,
    /// Per job on a worker, by number, the rank it was sent to.
    away: HashMap<u32, i32>,
    /// Every key stored, with its first generation, in the order noted; per worker, how many
    /// of them it was sent.
    keys: Vec<([u8; 32], u32)>,
    keys_sent: Vec<usize>,
    /// The main thread's CPU time in the calls that dispatched jobs ([`Stream::clocked`]), and
    /// when the stream started (its whole life is counted as a batch).
    cpu: Option<Duration>,
    started: Instant,
}

/// Where the main thread's CPU clock stood when a call that dispatches jobs began
/// ([`Stream::clock`]).
pub struct Clock(Option<Duration>);

/// A stored key and its first generation as they travel: the key's 32 bytes, then the
/// generation's 4, little-endian.
const KEY_ENTRY: usize = 36;

impl Stream {
    /// A stream of jobs on `task` whose genomes need `setup`, over the workers of the job this
    /// process is rank 0 of (`None` when it is not rank 0 of a job of several ranks), with the
    /// keys stored so far, `stored`. The workers forget what they held.
    pub(in crate::evolve) fn start(
        task: &TaskSpec,
        setup: Setup,
        stored: impl IntoIterator<Item = ([u8; 32], u32)>,
    ) -> Option<Stream> {
        if !super::super::is_master() {
            return None;
        }
        let mut master = super::super::master();
        let state = master.as_mut()?;
        state.set_task(task);
        state.set_setup(setup);
        state.births += 1;
        let workers = state.workers.len();
        let mut keys: Vec<([u8; 32], u32)> = stored.into_iter().collect();
        // The order they are sent in changes nothing; sorted, it is the same on every run.
        keys.sort_unstable();
        Some(Stream {
            master,
            world: SimpleCommunicator::world(),
            task: task.clone(),
            away: HashMap::new(),
            keys,
            keys_sent: vec![0; workers],
            cpu: Some(Duration::ZERO),
            started: Instant::now(),
        })
    }

    fn state(&mut self) -> &mut Master {
        self.master.as_mut().expect("a stream has rank 0's state")
    }

    /// Notes `keys` as first stored by generation `generation`: each worker learns them with
    /// its next answer.
    pub(in crate::evolve) fn stored(
        &mut self,
        generation: u32,
        keys: impl IntoIterator<Item = [u8; 32]>,
    ) {
        self.keys
            .extend(keys.into_iter().map(|key| (key, generation)));
    }

    /// The main thread's CPU clock now, as a call that dispatches jobs begins.
    pub(in crate::evolve) fn clock(&self) -> Clock {
        let timing = self.master.as_ref().is_some_and(|state| state.timing);
        Clock(timing.then(thread_cpu).flatten())
    }

    /// Counts the main thread's CPU time since `clock` as rank 0's dispatching
    /// (`ONTOGENY_MPI_TIMING`'s "main thread in batches").
    pub(in crate::evolve) fn clocked(&mut self, clock: Clock) {
        if let Some(start) = clock.0 {
            self.cpu = match (self.cpu, thread_cpu()) {
                (Some(sum), Some(end)) => Some(sum + end.saturating_sub(start)),
                _ => None,
            };
        }
    }

    /// Counts births made: `remote` on other ranks (`stored` of them found stored, not
    /// walked) and `here` on this one, each as one walk too.
    pub(in crate::evolve) fn count_births(&mut self, remote: u64, stored: u64, here: u64) {
        let counts = &mut self.state().counts;
        counts.remote += remote;
        counts.born_remote += remote;
        counts.stored_remote += stored;
        counts.local += here;
        counts.born_local += here;
    }

    /// Notes a sleep of the main thread between looks for requests.
    pub(in crate::evolve) fn woke(&mut self) {
        self.state().counts.wakes += 1;
    }

    /// Takes every request that has come: the outcomes they bring, each with its job's number
    /// and the rank that did it. An outcome of a job not sent to that rank ends the job.
    pub(in crate::evolve) fn receive(&mut self) -> Vec<(u32, i32, Outcome)> {
        let mut outcomes = Vec::new();
        while let Some(matched) = self
            .world
            .any_process()
            .immediate_matched_probe_with_tag(REQUEST)
        {
            let (bytes, status) = matched.matched_receive_vec::<u8>();
            let rank = status.source_rank();
            for (job, outcome) in self.take_request(rank, &bytes) {
                if self.away.remove(&job) != Some(rank) {
                    fail(
                        &self.world,
                        &format!("rank {rank} sent an outcome for job {job} that it was not given"),
                    );
                }
                outcomes.push((job, rank, outcome));
            }
        }
        outcomes
    }

    /// `rank`'s request `bytes`, noted: the outcomes it brings.
    fn take_request(&mut self, rank: i32, bytes: &[u8]) -> Vec<(u32, Outcome)> {
        let request = decode_request(&self.world, rank, bytes);
        let state = self.state();
        state.counts.requests += 1;
        let worker = &mut state.workers[rank as usize - 1];
        worker.threads = request.threads.max(1) as usize;
        worker.in_flight = worker.in_flight.saturating_sub(request.outcomes.len());
        worker.waiting = true;
        request.outcomes
    }

    /// The workers that wait for jobs, each with the jobs it has room for: one more than its
    /// threads, less those it holds.
    pub(in crate::evolve) fn hungry(&self) -> Vec<(i32, usize)> {
        let state = self.master.as_ref().expect("a stream has rank 0's state");
        state
            .workers
            .iter()
            .enumerate()
            .filter(|(_, w)| w.waiting)
            .map(|(i, w)| (i as i32 + 1, (w.threads + 1).saturating_sub(w.in_flight)))
            .collect()
    }

    /// The most threads a worker has.
    pub(in crate::evolve) fn most_threads(&self) -> usize {
        let state = self.master.as_ref().expect("a stream has rank 0's state");
        state.workers.iter().map(|w| w.threads).max().unwrap_or(1)
    }

    /// The most jobs the workers hold at once: one more than its threads each.
    pub(in crate::evolve) fn capacity(&self) -> usize {
        let state = self.master.as_ref().expect("a stream has rank 0's state");
        state.workers.iter().map(|w| w.threads.max(1) + 1).sum()
    }

    /// Sends `jobs`, each with its number, to the worker of `rank` (which waits for work),
    /// with the keys stored since its last answer.
    pub(in crate::evolve) fn send(&mut self, rank: i32, jobs: Vec<(u32, Work<Creature>)>) {
        for (job, _) in &jobs {
            self.away.insert(*job, rank);
        }
        let sent = &mut self.keys_sent[rank as usize - 1];
        let mut known = Vec::with_capacity((self.keys.len() - *sent) * KEY_ENTRY);
        for (key, generation) in &self.keys[*sent..] {
            known.extend_from_slice(key);
            known.extend_from_slice(&generation.to_le_bytes());
        }
        *sent = self.keys.len();
        let state = self.master.as_mut().expect("a stream has rank 0's state");
        state.reply(&self.world, rank, &self.task, jobs, Bytes(known));
    }

    /// Answers every waiting worker that still holds jobs with no new ones, so that it goes
    /// on sending back what it finishes.
    pub(in crate::evolve) fn release(&mut self) {
        for (rank, _) in self.hungry() {
            if self.state().workers[rank as usize - 1].in_flight > 0 {
                self.send(rank, Vec::new());
            }
        }
    }
}

/// A worker's stored keys as they travel, read back: each key with its first generation; the
/// error says they are cut short.
pub(in crate::evolve::mpi) fn stored_keys(
    known: &[u8],
) -> Result<impl Iterator<Item = ([u8; 32], u32)>, String> {
    if !known.len().is_multiple_of(KEY_ENTRY) {
        return Err(format!(
            "rank 0 sent {} bytes of stored keys, not a multiple of {KEY_ENTRY}",
            known.len()
        ));
    }
    Ok(known.chunks_exact(KEY_ENTRY).map(|entry| {
        let (key, generation) = entry.split_at(32);
        (
            key.try_into().expect("32 bytes"),
            u32::from_le_bytes(generation.try_into().expect("4 bytes")),
        )
    }))
}

/// `rank`'s request `bytes`, decoded; a request that does not decode ends the job.
pub(super) fn decode_request(world: &SimpleCommunicator, rank: i32, bytes: &[u8]) -> Request {
    rmp_serde::from_slice(bytes).unwrap_or_else(|e| {
        fail(
            world,
            &format!("cannot decode a request from rank {rank}: {e} (are all ranks the same ontogeny build?)"),
        )
    })
}

impl Master {
    /// [`Master::reply_with`], sent and waited for.
    fn reply<C: serde::Serialize>(
        &mut self,
        world: &SimpleCommunicator,
        rank: i32,
        task: &TaskSpec,
        jobs: Vec<(u32, Work<C>)>,
        known: Bytes,
    ) {
        self.reply_with(rank, task, jobs, known, false, |bytes| {
            world.process_at_rank(rank).send_with_tag(&bytes[..], REPLY);
            bytes.len()
        });
    }

    /// Sends `jobs` (and `known`, the stored keys it lacks) with `send` (which gives the
    /// length sent) to the worker of `rank` as an answer to its request, with `task` (the
    /// current one) and the setup if it lacks them, and notes them sent; `last`: they are its
    /// last of the batch.
    pub(super) fn reply_with<C: serde::Serialize>(
        &mut self,
        rank: i32,
        task: &TaskSpec,
        jobs: Vec<(u32, Work<C>)>,
        known: Bytes,
        last: bool,
        send: impl FnOnce(Vec<u8>) -> usize,
    ) {
        let (task_version, setup_version, births) =
            (self.task_version, self.setup_version, self.births);
        let count = jobs.len();
        let worker = &self.workers[rank as usize - 1];
        let reply: Reply<C, &TaskSpec, &Setup> = Reply::Work {
            task: (worker.task_version != task_version).then_some(task),
            setup: self
                .setup
                .as_ref()
                .filter(|_| worker.setup_version != setup_version)
                .map(|(_, setup)| setup),
            births,
            jobs,
            known,
            last,
        };
        let length = send(encode(&reply));
        let worker = &mut self.workers[rank as usize - 1];
        worker.task_version = task_version;
        worker.setup_version = setup_version;
        worker.in_flight += count;
        worker.waiting = false;
        worker.last = last;
        worker.answered = Some(Instant::now());
        self.counts.replies += 1;
        self.counts.bytes += length as u64;
    }
}

impl Drop for Stream {
    fn drop(&mut self) {
        // Every job still on a worker (a run stopped early) is waited for and its outcome
        // forgotten: a worker that asks while it holds jobs gets an empty answer, and once it
        // holds none it is left waiting, as a batch leaves it.
        loop {
            self.release();
            let state = self.state();
            if state.workers.iter().all(|w| w.waiting && w.in_flight == 0) {
                break;
            }
            let (rank, bytes) = receive(&self.world, None, REQUEST);
            self.take_request(rank, &bytes);
        }
        let (cpu, wall) = (self.cpu, self.started.elapsed());
        let counts = &mut self.state().counts;
        counts.batches += wall;
        counts.main_cpu = match (counts.main_cpu, cpu) {
            (Some(sum), Some(cpu)) => Some(sum + cpu),
            _ => None,
        };
    }
}
