//! The catapult's projectile: a box held at the root part's near end by a fixed joint until
//! the creature releases it, and the release signal.

use ::nalgebra::Vector3;
use rapier3d::math::{Pose, Real, Vector};
use rapier3d::prelude::*;

use super::options::JointModel;
use super::slots::JointHandle;
use super::slots::PartSlot;
use super::world::{World, to_na};
use crate::creature::PartId;

impl World {
    /// Whether a `release` effector has fired.
    pub fn release_signalled(&self) -> bool {
        self.released
    }

    /// Attaches a projectile box of `size` and `density` to the root part's near end (its local
    /// −x face, where the turtle started and nothing else grows), held by a fixed joint until
    /// [`release`](Self::release) (Chaumont 4.1: the root part is the arm).
    pub fn attach_projectile(&mut self, size: Vector3<f64>, density: f64) {
        let PartSlot {
            body: root,
            collider: root_collider,
            ..
        } = self.parts[PartId(0)];
        let root_pose = self.part_world_pose(PartId(0));
        // The root part's pose in its body's frame (fused parts share a body).
        let root_in_body = self.colliders[root_collider]
            .position_wrt_parent()
            .copied()
            .unwrap_or(Pose::IDENTITY);
        let root_half = self.colliders[root_collider]
            .shape()
            .as_cuboid()
            .map_or(Vector::ZERO, |c| c.half_extents);
        let half = size / 2.0;
        let grip_local = Vector::new(-root_half.x, 0.0, 0.0);
        let centre_local = Vector::new(-(root_half.x + half.x as Real), 0.0, 0.0);
        let mut pose = root_pose * Pose::from_translation(centre_local);
        // Lift everything if the projectile would start below the drop height.
        let reach = (half.x.abs() + half.y.abs() + half.z.abs()) as Real;
        let projectile_bottom = pose.translation.y - reach;
        let lift = (self.options.drop_height as Real - projectile_bottom).max(0.0);
        if lift > 0.0 {
            let up = Vector::new(0.0, lift, 0.0);
            let mut moved: Vec<RigidBodyHandle> = Vec::new();
            for part in self.parts.iter() {
                if moved.contains(&part.body) {
                    continue;
                }
                moved.push(part.body);
                let b = &mut self.bodies[part.body];
                let t = b.translation() + up;
                b.set_translation(t, true);
            }
            for part in self.parts.iter_mut() {
                part.previous += up;
            }
            pose.translation += up;
        }
        let body = self
            .bodies
            .insert(RigidBodyBuilder::dynamic().pose(pose).can_sleep(false));
        let collider = ColliderBuilder::cuboid(half.x as Real, half.y as Real, half.z as Real)
            .density(density as Real)
            .friction(self.options.friction as Real);
        self.colliders
            .insert_with_parent(collider, body, &mut self.bodies);
        let mut grip = GenericJointBuilder::new(JointAxesMask::LOCKED_FIXED_AXES)
            .contacts_enabled(false)
            .build();
        grip.set_local_frame1(root_in_body * Pose::from_translation(grip_local));
        grip.set_local_frame2(Pose::from_translation(Vector::new(
            half.x as Real,
            0.0,
            0.0,
        )));
        let handle = match self.options.joints {
            JointModel::Impulse => {
                JointHandle::Impulse(self.impulse_joints.insert(root, body, grip, true))
            }
            JointModel::Multibody => match self.multibody_joints.insert(root, body, grip, true) {
                Some(h) => JointHandle::Multibody(h),
                None => JointHandle::Impulse(self.impulse_joints.insert(root, body, grip, true)),
            },
        };
        self.projectile = Some((body, Some(handle)));
    }

    /// Breaks the joint holding the projectile.
    pub fn release(&mut self) {
        if let Some((_, joint)) = &mut self.projectile
            && let Some(handle) = joint.take()
        {
            match handle {
                JointHandle::Impulse(h) => {
                    self.impulse_joints.remove(h, true);
                }
                JointHandle::Multibody(h) => self.multibody_joints.remove(h, true),
                JointHandle::Fused => {}
            }
        }
    }

    /// The projectile's mass (kg), as the physics holds it, when there is one.
    pub fn projectile_mass(&self) -> Option<f64> {
        self.projectile
            .map(|(body, _)| self.bodies[body].mass() as f64)
    }

    /// The projectile's centre and speed, when there is one.
    pub fn projectile_state(&self) -> Option<(Vector3<f64>, f64)> {
        self.projectile.map(|(body, _)| {
            let b = &self.bodies[body];
            (to_na(b.translation()), b.linvel().length() as f64)
        })
    }
}
