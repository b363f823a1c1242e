//! Evolution and comparison: the genetic algorithm, parallel evaluation and the run store
//! come here (see `DESIGN.md`); today the room holds the statistics that compare settings
//! and, later, encodings, the run store (`store`, the only code that knows SQL) and the
//! fitness plot (`plot`).

pub mod plot;
pub mod stats;
pub mod store;
