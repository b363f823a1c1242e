//! The genetic algorithm: [`ga`] (a generational loop over any
//! [`crate::encoding::Genome`], parallel evaluation), its operators and their schedule
//! ([`operator`]), the order of a generation's walks ([`walk_order`]) and its settings
//! ([`settings`]: presets as data), the evaluation cache and its keys
//! ([`cache`], [`key`]), an individual developed and evaluated in its habitats
//! ([`habitats`]), where evaluations run ([`evaluator`]: this process's threads, or every
//! rank of an MPI job with the `mpi` feature) and the version of their behaviour that a run
//! records ([`evaluator_version`]), the steady-state algorithm ([`steady`]), a generation's record ([`record`]), and where its time went
//! ([`timing`]).

pub mod cache;
pub mod evaluator;
pub mod evaluator_version;
pub mod ga;
pub mod habitats;
pub mod key;
#[cfg(feature = "mpi")]
pub mod mpi;
pub mod operator;
pub mod ranking;
pub mod record;
pub mod settings;
pub mod steady;
pub mod timing;
pub mod walk_order;
