//! Studies over runs: comparisons of encodings or settings over replicated runs
//! ([`compare`]), the statistics that compare them ([`stats`]), the fidelity experiment that
//! ranks step settings against the fine reference ([`fidelity`]), the bench's measurements
//! ([`bench`](mod@bench)), the runs and comparisons under a directory ([`listing`]), how
//! much a run's champions vary under noise and mutation ([`canalization`]) and what
//! champions do in each habitat and how their bodies answer the chemical cue
//! ([`plasticity`]), whether champions go on walking after the time they were evolved for
//! ([`sustained`]), and the evaluations per second a profiled run would reach on other
//! numbers of threads and ranks, generational ([`schedule`]) or steady-state
//! ([`steady_schedule`]).

pub mod bench;
pub mod canalization;
pub mod compare;
pub mod fidelity;
pub mod lifetime;
pub mod listing;
pub mod plasticity;
pub mod schedule;
pub mod stats;
pub mod steady_schedule;
pub mod sustained;
