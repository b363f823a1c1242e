//! Simulation: running a creature's brain against its body in a rapier3d world.

pub mod brain;
pub mod drag;
mod model_names;
pub mod setting;
pub mod world;

pub use brain::BrainRuntime;
pub use drag::DragMeter;
pub use model_names::UnknownName;
pub use setting::{
    MAX_DT, MAX_ITERATIONS, MAX_SUBSTEPS, MIN_DT, SettingError, SimTable, StepSetting,
    UnknownSetting,
};
pub use world::{
    ANGLE_DAMPING, ANGLE_STIFFNESS, ActuatorModel, BuildError, DEFAULT_MUSCLE_SPEED,
    DEFAULT_STRENGTH, ENERGY_TOLERANCE, Exploded, GRAVITY, JOINT_GAP_WARNING, JointModel,
    SATURATION_DAMPING, SimOptions, StrengthFrom, TOUCH_DISTANCE, World, max_torque,
};
