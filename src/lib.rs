//! Ontogeny: grow virtual creatures from L-systems and evolve them in physics.
//!
//! The pipeline runs one way (see `DESIGN.md`): [`lang`] parses `.lsys` text, [`lsystem`]
//! derives module strings from it
//! in discrete steps or continuous developmental time, exchanging chemicals with an
//! [`environment`].

pub mod creature;
pub mod develop;
pub mod environment;
pub mod lang;
pub mod lsystem;
pub mod render;
pub mod sim;
pub mod task;
