//! Ontogeny: grow virtual creatures from L-systems and evolve them in physics.
//!
//! The pipeline runs one way (see `DESIGN.md`): [`lang`] parses `.lsys` text; [`lsystem`]
//! derives module strings from it in discrete steps or continuous developmental time,
//! exchanging chemicals with an [`environment`]; [`develop`] builds a [`creature`] (body and
//! brain) from each string; [`render`] draws it; [`sim`] runs it in a rapier3d world; and
//! [`task`] scores it on the seed papers' walker, catapult, aim and jump tasks; [`encoding`]
//! holds the genomes evolution searches, which develop into creatures; [`evolve`] runs the
//! genetic algorithm over them into a run directory with its SQLite store, and holds the
//! statistics that compare settings.
//! [`export`] writes a creature with the simulator's settings in other simulators' formats
//! (MuJoCo's MJCF). [`view`] serves a local web page that shows creatures growing, recordings
//! playing and runs' progress in the browser. [`output`] writes every file for the user whole or
//! not at all, never over something that is not a regular file, and into a folder only when it
//! is new, empty or Ontogeny's own; [`input`] reads every file with a cap on its size. [`cancel`] lets a
//! caller stop long work (growth, evaluation, evolution) from another thread.

#![warn(missing_docs)]

pub mod cancel;
pub mod creature;
pub mod develop;
pub mod encoding;
pub mod environment;
pub mod evolve;
pub mod export;
pub mod front;
pub mod input;
pub mod lang;
pub mod lsystem;
pub mod output;
pub mod render;
pub mod run;
pub mod sim;
pub mod study;
pub mod task;
pub mod view;
