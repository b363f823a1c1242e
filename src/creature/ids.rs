//! Stable ids of parts and joints, from the builder to the world and back.
//!
//! A part's id is its index in [`Creature::parts`](super::Creature::parts), a joint's its
//! index in [`Creature::joints`](super::Creature::joints): the builder hands them out in the
//! order it makes parts and joints, and nothing stores them, so a serialised creature (and
//! every evaluation key hashed from one) is the same with or without them. The simulated world
//! keys its parts and joints by the same ids, and gives the next free one to a part or joint
//! added while it runs; ids are never reused. A sensor, an actuator or a recording naming a
//! part or joint by number names it by id.

use serde::{Deserialize, Serialize};

/// Declares an id type: a number kept as is through serde, converted from and to `usize`,
/// and written as `"{noun} {number}"`.
macro_rules! stable_id {
    ($(#[$doc:meta])* $name:ident, $noun:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
        #[serde(transparent)]
        pub struct $name(pub usize);

        impl From<usize> for $name {
            fn from(index: usize) -> Self {
                $name(index)
            }
        }

        impl From<$name> for usize {
            fn from(id: $name) -> Self {
                id.0
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                write!(f, concat!($noun, " {}"), self.0)
            }
        }
    };
}

stable_id!(
    /// A part's stable id: its index in the creature's parts.
    PartId,
    "part"
);
stable_id!(
    /// A joint's stable id: its index in the creature's joints.
    JointId,
    "joint"
);

impl super::Creature {
    /// Every part's id with the part, in order.
    pub fn parts_by_id(&self) -> impl Iterator<Item = (PartId, &super::Part)> {
        self.parts.iter().enumerate().map(|(i, p)| (PartId(i), p))
    }

    /// Every joint's id with the joint, in order.
    pub fn joints_by_id(&self) -> impl Iterator<Item = (JointId, &super::Joint)> {
        self.joints.iter().enumerate().map(|(i, j)| (JointId(i), j))
    }
}
