//! Simulation: running a creature's brain against its body in a rapier3d world.

pub mod brain;
pub mod world;

pub use brain::BrainRuntime;
pub use world::{
    ActuatorModel, BuildError, DEFAULT_MUSCLE_SPEED, DEFAULT_STRENGTH, Exploded, JointModel,
    SimOptions, StrengthFrom, World,
};
