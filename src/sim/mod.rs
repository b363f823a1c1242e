//! Simulation: running a creature's brain against its body in a rapier3d world.
//!
//! The options are in [`options`], each one's key, flag, range and description (and the one
//! check) in [`knobs`], the named step settings and the `[task.sim]` table in [`setting`];
//! the world is built in [`build`] from the parts and joints of [`parts`] (keyed by stable
//! ids, and added or resized while it runs), senses in [`sensors`], moves in [`actuators`],
//! is audited for energy from nowhere in [`audit`], grows as development says in [`growth`], holds the catapult's projectile in
//! [`projectile`], feels water's resistance in [`water`], and steps in [`world`]; its
//! velocities and momenta are [`motion`]'s; what the world holds besides the creature
//! (terrain, obstacles, objects, the medium) is described by [`world_spec`] and worked out
//! as geometry, without physics, in [`terrain`]; the ground and what stands on it are built
//! in rapier by `ground`.

pub mod actuators;
pub mod audit;
pub mod brain;
pub mod build;
pub mod drag;
mod ground;
pub mod growth;
pub mod knobs;
mod model_names;
pub mod motion;
pub mod options;
pub mod parts;
pub mod projectile;
pub mod sensors;
pub mod setting;
mod slots;
pub mod terrain;
pub mod water;
pub mod world;
pub mod world_spec;

pub use actuators::{ANGLE_DAMPING, ANGLE_STIFFNESS, SATURATION_DAMPING, max_torque};
pub use audit::{ENERGY_WINDOW, JOINT_GAP_WARNING};
pub use brain::BrainRuntime;
pub use build::BuildError;
pub use drag::DragMeter;
pub use growth::{GROWTH_CLEARANCE, Grown};
pub use knobs::{KNOBS, Knob, SettingError, check_real, table_name};
pub use model_names::UnknownName;
pub use motion::Attach;
pub use options::{
    ActuatorModel, DEFAULT_MUSCLE_SPEED, DEFAULT_STRENGTH, ENERGY_TOLERANCE, JointModel, MAX_DT,
    MAX_ITERATIONS, MAX_SUBSTEPS, MIN_DT, SimOptions, StrengthFrom,
};
pub use sensors::TOUCH_DISTANCE;
pub use setting::{RENAMED_KEYS, StepSetting, UnknownSetting};
pub use water::{DEFAULT_VISCOSITY, MAX_VISCOSITY};
pub use world::{Exploded, GRAVITY, World};
pub use world_spec::{Medium, WorldSpec};
