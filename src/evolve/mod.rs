//! Evolution and comparison: the genetic algorithm, parallel evaluation and the run store
//! come here (see `DESIGN.md`); today the room holds the statistics that compare settings
//! and, later, encodings.

pub mod config;
pub mod ga;
pub mod stats;
