//! Simulation: running a creature's brain against its body in a rapier3d world.

pub mod brain;

pub use brain::BrainRuntime;
