//! The records the world keeps of the creature's parts and joints, keyed by their stable ids
//! ([`PartId`], [`JointId`](crate::creature::JointId)): a part's body, box and size, a joint's
//! rapier handle, ends, limits and motor; and what it holds besides the creature (the ground,
//! obstacles and objects). [`World`](super::World) holds them; `parts` adds and resizes the
//! parts and joints, `ground` builds the ground.

use std::marker::PhantomData;

use ::nalgebra::Vector3;
use rapier3d::math::Vector;
use rapier3d::prelude::*;

use super::terrain::Terrain;
use crate::creature::PartId;

/// A joint handle of either model.
#[derive(Clone, Copy, Debug)]
pub(super) enum JointHandle {
    Impulse(ImpulseJointHandle),
    Multibody(MultibodyJointHandle),
    /// No rapier joint: a rigid joint, or a joint between two parts of one rigid body (its
    /// parts are fused into one body with a collider per part).
    Fused,
}

/// Items keyed by an id that is their place in order: pushing gives the next id, and nothing
/// is ever removed, so an id names the same item for the world's whole life.
pub(super) struct Keyed<I, T> {
    items: Vec<T>,
    id: PhantomData<I>,
}

impl<I: From<usize> + Into<usize>, T> Keyed<I, T> {
    pub(super) fn new() -> Self {
        Keyed {
            items: Vec::new(),
            id: PhantomData,
        }
    }

    /// Adds `item`; returns its id.
    pub(super) fn push(&mut self, item: T) -> I {
        self.items.push(item);
        I::from(self.items.len() - 1)
    }

    /// How many items.
    pub(super) fn len(&self) -> usize {
        self.items.len()
    }

    /// The item with id `id`, if there is one.
    pub(super) fn get(&self, id: I) -> Option<&T> {
        self.items.get(id.into())
    }

    /// The items, in id order.
    pub(super) fn iter(&self) -> std::slice::Iter<'_, T> {
        self.items.iter()
    }

    /// The items, in id order, to change.
    pub(super) fn iter_mut(&mut self) -> std::slice::IterMut<'_, T> {
        self.items.iter_mut()
    }
}

impl<I: Into<usize>, T> std::ops::Index<I> for Keyed<I, T> {
    type Output = T;
    fn index(&self, id: I) -> &T {
        &self.items[id.into()]
    }
}

impl<I: Into<usize>, T> std::ops::IndexMut<I> for Keyed<I, T> {
    fn index_mut(&mut self, id: I) -> &mut T {
        &mut self.items[id.into()]
    }
}

/// A part in the world.
pub(super) struct PartSlot {
    /// Its rigid body (shared with the parts fused to it).
    pub(super) body: RigidBodyHandle,
    /// Its box.
    pub(super) collider: ColliderHandle,
    /// Its edge lengths (m), as the creature gave them or [`World::resize_part`] set them.
    pub(super) size: Vector3<f64>,
    /// Its centre after the last step, for the explosion checks.
    pub(super) previous: Vector,
}

/// A joint in the world, with what the motors need to know of it.
pub(super) struct JointSlot {
    /// The rapier joint, or none for a fused or rigid joint.
    pub(super) handle: JointHandle,
    /// The parent and the child part.
    pub(super) parts: (PartId, PartId),
    /// The parent's and the child's bodies.
    pub(super) ends: (RigidBodyHandle, RigidBodyHandle),
    /// Angle limits per degree of freedom (radians).
    pub(super) limits: Vec<(f64, f64)>,
    /// The joint's own strength (its maximum torque follows its parts' sizes).
    pub(super) strength: f64,
    /// The motor's maximum torque (N·m).
    pub(super) max_torque: f64,
    /// The torques (N·m) the torque muscle applies about the joint's axes this control step.
    pub(super) torques: [f64; 3],
}

impl<I: From<usize> + Into<usize>> Keyed<I, JointSlot> {
    /// `from` and everything jointed beyond it, not back through `stop`, found through each
    /// joint's ends as `ends` reads them (its parts or its bodies, parent first): what a part
    /// carries when it grows or moves.
    pub(super) fn beyond<T: Copy + PartialEq>(
        &self,
        from: T,
        stop: T,
        ends: impl Fn(&JointSlot) -> (T, T),
    ) -> Vec<T> {
        let mut found = vec![from];
        let mut next = 0;
        while next < found.len() {
            let at = found[next];
            for (parent, child) in self.iter().map(&ends) {
                if parent == at && child != stop && !found.contains(&child) {
                    found.push(child);
                }
            }
            next += 1;
        }
        found
    }
}

/// What a world holds besides the creature, in rapier.
pub(super) struct Ground {
    /// The ground's colliders: the first is the halfspace or the heightfield.
    pub(super) colliders: Vec<ColliderHandle>,
    /// The free objects' bodies and their starting velocities.
    pub(super) objects: Vec<(RigidBodyHandle, Vector)>,
    /// Whether the objects have been let go.
    pub(super) released: bool,
    /// The ground's friction, when the world sets it.
    pub(super) friction: Option<GroundFriction>,
    /// The highest ground under the creature where it was dropped (m).
    pub(super) start: f64,
}

/// The physics hook that gives a contact with the ground the ground's coefficient there.
pub(super) struct GroundFriction {
    pub(super) terrain: Terrain,
}
