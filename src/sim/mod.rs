//! Simulation: running a creature's brain against its body in a rapier3d world.

pub mod brain;
pub mod world;

pub use brain::BrainRuntime;
pub use world::{ActuatorModel, BuildError, Exploded, JointModel, SimOptions, StrengthFrom, World};
