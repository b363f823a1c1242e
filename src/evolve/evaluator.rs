//! Where evaluations run: on this process's threads (rayon), or — in a build with the `mpi`
//! feature started by an MPI launcher (`mpirun`, `srun`) — over every rank of the job
//! (`evolve::mpi`, with the feature). The genetic algorithm hands a batch of creatures to
//! [`Evaluator::evaluate`] and gets their evaluations back in the same order. An evaluation is
//! a pure function of the creature and the task, so where it runs never changes a result.
//!
//! A verb that evaluates joins the cluster first with [`join_cluster`]: on a worker rank that
//! call serves rank 0's jobs until rank 0 is done and returns `None` (the verb then has nothing
//! to do); everywhere else it returns the [`Cluster`] to hold while the verb runs.

use std::time::Instant;

use rayon::prelude::*;

use super::timing::WalkTime;

use crate::cancel::{Cancel, Interrupted};
use crate::creature::Creature;
use crate::develop::Seedling;
use crate::task::{Evaluation, GrowError, TaskSpec, Unit, Watch};

/// One walk to simulate: a creature, and the unit of its individual's evaluation it is (its
/// habitat, trial and draw), or `None` for the one walk of a plain specification.
#[derive(Clone, Copy, Debug)]
pub struct Job<'a> {
    /// The creature, developed in the unit's habitat.
    pub creature: &'a Creature,
    /// The unit ([`TaskSpec::evaluate_unit_watched`]), or `None`
    /// ([`TaskSpec::evaluate_watched`]).
    pub unit: Option<Unit>,
    /// What the creature grows from during its evaluation (`develop = "during"`): then
    /// `creature` is its creature at t₀, and the walk starts it anew
    /// ([`TaskSpec::evaluate_grown_job`]). `None` for a creature that does not grow.
    pub seedling: Option<&'a Seedling>,
}

impl Job<'_> {
    /// The job's evaluation, watched as `watch` says: a growing creature whose development
    /// fails during the walk is `invalid` (`development: ...`).
    pub fn evaluate(&self, task: &TaskSpec, watch: Watch<'_>) -> Result<Evaluation, Interrupted> {
        let Some(seedling) = self.seedling else {
            return task.evaluate_job(self.creature, self.unit.as_ref(), watch);
        };
        match task.evaluate_grown_job(seedling, self.unit.as_ref(), watch) {
            Ok(evaluation) => Ok(evaluation),
            Err(GrowError::Interrupted(i)) => Err(i),
            Err(e) => Ok(Evaluation::invalid(
                task.task.name(),
                format!("development: {e}"),
            )),
        }
    }
}

/// What evaluates a batch of creatures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluator {
    /// This process's worker threads (rayon).
    Local,
    /// Every rank of an MPI job, rank 0 (this process) included, each with its threads.
    #[cfg(feature = "mpi")]
    Mpi,
}

impl Evaluator {
    /// This process's evaluator: `Evaluator::Mpi` on rank 0 of an MPI job of several ranks
    /// that [`join_cluster`] joined, [`Evaluator::Local`] otherwise.
    pub fn current() -> Evaluator {
        #[cfg(feature = "mpi")]
        if super::mpi::is_master() {
            return Evaluator::Mpi;
        }
        Evaluator::Local
    }

    /// The evaluations of `jobs` on `task`, in order, each job a separate unit of parallel
    /// work, handed out in the order of `jobs` (each to the first thread, or rank, to fall
    /// free); `Interrupted` once `cancel` is set (on this process's threads, every evaluation
    /// stops at its next control step and no new one starts; a batch sent to MPI ranks runs to
    /// its end first).
    pub fn evaluate(
        self,
        task: &TaskSpec,
        jobs: &[Job<'_>],
        cancel: &Cancel,
    ) -> Result<Vec<Evaluation>, Interrupted> {
        self.evaluate_timed(task, jobs, cancel)
            .map(|(evaluations, _)| evaluations)
    }

    /// [`Evaluator::evaluate`], with each job's wall time and the thread that ran it, in the
    /// jobs' order (a [`WalkTime`] whose `individual` is the job's index in `jobs`); none when
    /// the batch went to MPI ranks. Timing changes no evaluation.
    pub fn evaluate_timed(
        self,
        task: &TaskSpec,
        jobs: &[Job<'_>],
        cancel: &Cancel,
    ) -> Result<(Vec<Evaluation>, Vec<WalkTime>), Interrupted> {
        // A growing creature's grammar stays with this process: its walks run on its threads.
        #[cfg(feature = "mpi")]
        let this = match jobs.iter().any(|j| j.seedling.is_some()) {
            true => Evaluator::Local,
            false => self,
        };
        #[cfg(not(feature = "mpi"))]
        let this = self;
        match this {
            Evaluator::Local => {
                // Handed out in order, one walk to each thread as it falls free (a shared
                // iterator), and put back in order: whatever thread runs a walk, its result
                // lands in its job's place.
                let mut timed: Vec<(usize, Evaluation, WalkTime)> = jobs
                    .iter()
                    .enumerate()
                    .par_bridge()
                    .map(|(index, job)| {
                        cancel.check()?;
                        let watch = Watch {
                            record: false,
                            progress: &mut |_| {},
                            cancel: Some(cancel),
                        };
                        let started = Instant::now();
                        let evaluation = job.evaluate(task, watch)?;
                        let time = WalkTime {
                            individual: index as u32,
                            seconds: started.elapsed().as_secs_f64(),
                            thread: rayon::current_thread_index().unwrap_or(0) as u32,
                            rank: 0,
                            parts: job.creature.parts.len() as u32,
                        };
                        Ok((index, evaluation, time))
                    })
                    .collect::<Result<_, Interrupted>>()?;
                timed.sort_unstable_by_key(|(index, _, _)| *index);
                let timed: Vec<(Evaluation, WalkTime)> =
                    timed.into_iter().map(|(_, e, t)| (e, t)).collect();
                Ok(timed.into_iter().unzip())
            }
            #[cfg(feature = "mpi")]
            Evaluator::Mpi => {
                let jobs: Vec<_> = jobs.iter().map(|j| (j.creature, j.unit)).collect();
                let evaluations = super::mpi::evaluate(task, &jobs);
                cancel.check()?;
                Ok((evaluations, Vec::new()))
            }
        }
    }

    /// How many processes evaluate: the ranks of the MPI job for `Evaluator::Mpi` (with the
    /// `mpi` feature), 1 for [`Evaluator::Local`].
    pub fn ranks(self) -> u32 {
        match self {
            Evaluator::Local => 1,
            #[cfg(feature = "mpi")]
            Evaluator::Mpi => super::mpi::ranks(),
        }
    }
}

/// Why a process could not take its part in an MPI job.
#[derive(Debug, thiserror::Error)]
#[error("MPI: {0}")]
pub struct ClusterError(pub String);

/// This process's part in the job, held while a verb evaluates: on rank 0 of an MPI job, when
/// dropped, it tells the other ranks to stop and ends MPI. Without an MPI launcher (or in a
/// build without the `mpi` feature) it does nothing.
#[derive(Debug)]
pub struct Cluster {
    #[cfg(feature = "mpi")]
    _membership: Option<super::mpi::Membership>,
}

/// Joins the MPI job this process was started in, if any (see the module's documentation):
/// `Ok(None)` on a worker rank once rank 0 has told it to stop.
pub fn join_cluster() -> Result<Option<Cluster>, ClusterError> {
    #[cfg(feature = "mpi")]
    {
        if !super::mpi::launched() {
            return Ok(Some(Cluster { _membership: None }));
        }
        match super::mpi::join().map_err(ClusterError)? {
            Some(membership) => Ok(Some(Cluster {
                _membership: Some(membership),
            })),
            None => Ok(None),
        }
    }
    #[cfg(not(feature = "mpi"))]
    Ok(Some(Cluster {}))
}
