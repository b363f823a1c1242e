//! Evolution and comparison: the genetic algorithm ([`ga`]: presets as data, a generational
//! loop over any [`crate::encoding::Genome`], parallel evaluation), a run's configuration
//! ([`config`], its errors in words: [`config_errors`]), its directory ([`run`]), its database ([`store`], the only code that knows
//! SQL), the record of a champion's evaluation in its file ([`champion`]), the lock that keeps a directory one process's ([`lock`]), its fitness plot
//! ([`plot`]), the statistics that compare settings and encodings ([`stats`]), the evaluation
//! cache and its keys ([`cache`], [`key`]), where evaluations run ([`evaluator`]: this
//! process's threads, or every rank of an MPI job with the `mpi` feature) and the version of
//! their behaviour that a run records ([`evaluator_version`]), comparisons of encodings over replicated runs
//! ([`compare`]), and the fidelity experiment that ranks step settings against the fine
//! reference ([`fidelity`]) and the bench's measurements ([`bench`](mod@bench)); a run's individual picked by rank ([`pick`]); the settings of a run or comparison from the command line
//! ([`settings`]) and what the command line says about them ([`text`]); the runs and comparisons under a
//! directory ([`listing`]).

pub mod bench;
pub mod cache;
pub mod champion;
pub mod compare;
pub mod config;
pub mod config_errors;
pub mod evaluator;
pub mod evaluator_version;
pub mod fidelity;
pub mod ga;
pub mod json;
pub mod key;
pub mod listing;
pub mod lock;
#[cfg(feature = "mpi")]
pub mod mpi;
pub mod pick;
pub mod plot;
pub mod run;
pub mod run_folder;
pub mod settings;
pub mod stats;
pub mod store;
pub mod text;
