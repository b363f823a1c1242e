//! Export: writing a [`Creature`](crate::creature::Creature) in other simulators' formats,
//! with the physics settings of [`SimOptions`](crate::sim::SimOptions), so that the same
//! creature can be run, inspected or compared elsewhere.
//!
//! [`mjcf`] writes MuJoCo's MJCF, and the creature's world beside it. This room reads creatures and simulator settings; it never
//! builds a world or runs one, and nothing reads the formats back.

pub mod mjcf;
mod mjcf_numbers;
mod mjcf_world;

pub use mjcf::{MjcfActuator, mjcf_actuators, to_mjcf, to_mjcf_in};

/// Why a creature could not be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The creature has no parts.
    #[error("the creature has no parts")]
    NoParts,
    /// The creature is malformed (see `Creature::check_consistency`).
    #[error("malformed creature: {0}")]
    Malformed(String),
    /// A part is the child of two joints: the joints form a loop, and the target format's
    /// bodies form a tree.
    #[error(
        "joint {joint} makes part {part} the child of a second joint (joint {first} already \
         holds it): the joints form a loop, and exported bodies must form a tree"
    )]
    SecondParent {
        /// The joint that closes the loop.
        joint: usize,
        /// The part with two parents.
        part: usize,
        /// The part's first parent joint.
        first: usize,
    },
    /// Some parts are joined in a ring with no root part (no part of the ring is free).
    #[error(
        "part {part} lies on a ring of joints with no root part: exported bodies must form a tree"
    )]
    Ring {
        /// A part on the ring.
        part: usize,
    },
    /// A degree of freedom whose limits are equal: MJCF needs a range of positive width.
    #[error(
        "joint {joint} has equal limits on degree of freedom {dof}, which MJCF cannot express \
         (a range must have positive width)"
    )]
    EqualLimits {
        /// The joint.
        joint: usize,
        /// The degree of freedom.
        dof: usize,
    },
    /// The simulator settings cannot be written (a time step or friction out of range).
    #[error("{0}")]
    Settings(String),
}
