//! Ontogeny: grow virtual creatures from L-systems and evolve them in physics.
//!
//! The pipeline runs one way (see `DESIGN.md`): [`lang`] parses `.lsys` text, [`lsystem`]
//! derives module strings from it.

pub mod lang;
pub mod lsystem;
