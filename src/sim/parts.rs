//! The creature's parts and joints in the world, keyed by their stable ids ([`PartId`],
//! [`JointId`]), and the three ways the body changes: [`World::add_part`],
//! [`World::add_joint`] and [`World::resize_part`]. [`World::new`] builds a creature with the
//! first two, in the creature's order, so a part or joint added later while the world runs is
//! made the same way and gets the next id. New mass arrives moving with what it is attached to,
//! and a resized part keeps its velocity field and carries its children ([`super::motion`]).

use ::nalgebra::{UnitQuaternion, Vector3};
use rapier3d::math::{Pose, Real, Rotation, Vector};
use rapier3d::prelude::*;

use super::actuators::max_torque_between;
use super::build::BuildError;
use super::motion::Attach;
use super::options::JointModel;
use super::slots::{JointHandle, JointSlot, PartSlot};
use super::world::{ANGULAR, World};
use crate::creature::{Joint, JointId, Part, PartId};

pub(super) fn vector(v: &Vector3<f64>) -> Vector {
    Vector::new(v.x as Real, v.y as Real, v.z as Real)
}

fn rotation(q: &UnitQuaternion<f64>) -> Rotation {
    Rotation::from_xyzw(q.i as Real, q.j as Real, q.k as Real, q.w as Real).normalize()
}

/// The joint frame: its x axis along the first axis, its y axis along the second (made
/// perpendicular to the first), so that AngX, AngY and AngZ are the joint's degrees of
/// freedom in order.
fn joint_frame(axes: &[Vector3<f64>]) -> Rotation {
    let Some(first) = axes.first() else {
        return Rotation::IDENTITY;
    };
    let x = vector(first).normalize();
    let second = axes
        .get(1)
        .map(|a| {
            let a = vector(a);
            a - x * a.dot(x)
        })
        .filter(|y| y.length() > 1e-6);
    match second {
        Some(y) => {
            let y = y.normalize();
            let z = x.cross(y);
            Rotation::from_mat3(&rapier3d::glamx::Mat3::from_cols(x, y, z))
        }
        None => Rotation::from_rotation_arc(Vector::X, x),
    }
}

impl World {
    /// Adds `part` — its pose in the world's coordinates, held as `attach` says — and returns
    /// its id, the next one. It is placed where `part` says (no drop lift). Its mass arrives
    /// moving with what it is attached to (at rest when [`Attach::Free`]), so the creature's
    /// momentum rises by exactly the part's mass × that velocity. The creature's mass and
    /// mechanical energy count it from now on.
    ///
    /// # Panics
    ///
    /// If `attach` names no part of this world.
    pub fn add_part(&mut self, part: &Part, attach: Attach) -> PartId {
        let pose = Pose::from_parts(vector(&part.position), rotation(&part.orientation));
        let (body, field) = match attach {
            Attach::FusedTo(other) => {
                let body = self.parts[other].body;
                (body, Some(self.field_of(body)))
            }
            Attach::Free | Attach::MovingWith(_) => {
                let body = self
                    .bodies
                    .insert(RigidBodyBuilder::dynamic().pose(pose).can_sleep(false));
                self.creature_bodies.push(body);
                let field = match attach {
                    Attach::MovingWith(other) => Some(self.field_of(self.parts[other].body)),
                    _ => None,
                };
                (body, field)
            }
        };
        let relative = self.bodies[body].position().inverse() * pose;
        let half = part.size / 2.0;
        let collider = ColliderBuilder::cuboid(half.x as Real, half.y as Real, half.z as Real)
            .position(relative)
            .density(part.density as Real)
            .friction(self.options.friction as Real)
            .collision_groups(self.part_groups());
        let collider = self
            .colliders
            .insert_with_parent(collider, body, &mut self.bodies);
        let id = self.parts.push(PartSlot {
            body,
            collider,
            size: part.size,
            previous: Vector::ZERO,
        });
        self.parts[id].previous = self.part_world_pose(id).translation;
        if let Some(field) = field {
            self.move_with(body, &field);
        }
        self.body_changed();
        id
    }

    /// Joins two parts of the world by `joint` (its `parent` and `child` are part ids, its
    /// anchor and axes in the world's coordinates, as the parts are now) and returns its id,
    /// the next one. Its motor is off until the brain drives it; its maximum torque follows
    /// the two parts' sizes ([`max_torque`](super::max_torque)). Two parts of one rigid body
    /// get no rapier joint (a fused joint).
    ///
    /// # Errors
    ///
    /// [`BuildError::Loop`] when multibody joints cannot close the loop the joint would
    /// make; [`BuildError::Malformed`] when it names a part the world does not have.
    pub fn add_joint(&mut self, joint: &Joint) -> Result<JointId, BuildError> {
        let (parent, child) = (PartId(joint.parent), PartId(joint.child));
        let (Some(first), Some(second)) = (self.parts.get(parent), self.parts.get(child)) else {
            return Err(BuildError::Malformed(format!(
                "joint {} joins part {} to part {}, but the world has {} parts",
                self.joints.len(),
                joint.parent,
                joint.child,
                self.parts.len()
            )));
        };
        let (b1, b2) = (first.body, second.body);
        let max_torque =
            max_torque_between(&first.size, &second.size, joint.strength, &self.options);
        let handle = if b1 == b2 {
            JointHandle::Fused
        } else {
            let pose1 = *self.bodies[b1].position();
            let pose2 = *self.bodies[b2].position();
            let anchor = vector(&joint.anchor);
            // The joint frame: x along the first axis (if any), at the anchor.
            let frame_rotation = joint_frame(&joint.axes);
            let world_frame = Pose::from_parts(anchor, frame_rotation);
            let mask = match joint.kind.dof() {
                0 => JointAxesMask::LOCKED_FIXED_AXES,
                1 => JointAxesMask::LOCKED_REVOLUTE_AXES,
                2 => JointAxesMask::LOCKED_SPHERICAL_AXES | JointAxesMask::ANG_Z,
                _ => JointAxesMask::LOCKED_SPHERICAL_AXES,
            };
            let mut data = GenericJointBuilder::new(mask)
                .contacts_enabled(false)
                .build();
            data.set_local_frame1(pose1.inverse() * world_frame);
            data.set_local_frame2(pose2.inverse() * world_frame);
            for (k, &(lo, hi)) in joint.limits.iter().enumerate().take(joint.kind.dof()) {
                data.set_limits(ANGULAR[k], [lo as Real, hi as Real]);
                data.set_motor_model(ANGULAR[k], MotorModel::ForceBased);
                data.set_motor_max_force(ANGULAR[k], 0.0);
            }
            match self.options.joints {
                JointModel::Impulse => {
                    JointHandle::Impulse(self.impulse_joints.insert(b1, b2, data, true))
                }
                JointModel::Multibody => JointHandle::Multibody(
                    self.multibody_joints
                        .insert(b1, b2, data, true)
                        .ok_or(BuildError::Loop(self.joints.len()))?,
                ),
            }
        };
        Ok(self.joints.push(JointSlot {
            handle,
            parts: (parent, child),
            ends: (b1, b2),
            limits: joint.limits.clone(),
            strength: joint.strength,
            max_torque,
            torques: [0.0; 3],
        }))
    }

    /// Gives part `id` the edge lengths `size`, about its centre: its body's mass, centre of
    /// mass and inertia follow (the body keeps its velocity field), every joint's anchor on it
    /// moves with the face it sits on (each coordinate in the part's axes scaled by the new
    /// over the old length), and the maximum torque of its joints follows the new
    /// cross-section. Each child jointed to it is carried, with everything beyond it, by its
    /// anchor's move, so the joint stays closed, and moves with the part's velocity field
    /// where it now is. The joint to the part's own parent is left to the solver to close.
    ///
    /// # Panics
    ///
    /// If `id` names no part of this world.
    pub fn resize_part(&mut self, id: PartId, size: Vector3<f64>) {
        let PartSlot {
            body,
            collider,
            size: old,
            ..
        } = self.parts[id];
        let half = size / 2.0;
        self.colliders[collider].set_shape(SharedShape::cuboid(
            half.x as Real,
            half.y as Real,
            half.z as Real,
        ));
        self.parts[id].size = size;
        let field = self.field_of(body);
        self.bodies[body].recompute_mass_properties_from_colliders(&self.colliders);
        self.move_with(body, &field);
        // The part's pose in its body's frame: anchors are scaled in the part's own axes.
        let in_body = self.colliders[collider]
            .position_wrt_parent()
            .copied()
            .unwrap_or(Pose::IDENTITY);
        let scale = Vector::new(
            ratio(size.x, old.x),
            ratio(size.y, old.y),
            ratio(size.z, old.z),
        );
        let moved = |frame: Pose| {
            let mut local = in_body.inverse() * frame;
            local.translation *= scale;
            in_body * local
        };
        for j in self.joint_ids() {
            let (parent, child) = self.joints[j].parts;
            if parent != id && child != id {
                continue;
            }
            let first = self.parts[parent].size;
            let second = self.parts[child].size;
            let slot = &mut self.joints[j];
            slot.max_torque = max_torque_between(&first, &second, slot.strength, &self.options);
            let before = self.joint_anchors(j);
            self.with_joint(j, |data| {
                if parent == id {
                    data.set_local_frame1(moved(data.local_frame1));
                }
                if child == id {
                    data.set_local_frame2(moved(data.local_frame2));
                }
            });
            let (_, b2) = self.joints[j].ends;
            if parent == id
                && b2 != body
                && let (Some((from, _)), Some((to, _))) = (before, self.joint_anchors(j))
            {
                self.carry(b2, body, vector(&(to - from)), &field);
            }
        }
        self.body_changed();
    }

    /// The collision groups of the creature's parts: everything, or the ground only.
    fn part_groups(&self) -> InteractionGroups {
        if self.options.self_collision {
            InteractionGroups::all()
        } else {
            // Parts collide with the ground only.
            InteractionGroups::new(Group::GROUP_2, Group::GROUP_1, InteractionTestMode::And)
        }
    }

    /// Counts the creature's mass and energy again after its body changed, so that the energy
    /// audit does not take the change for energy from nowhere.
    pub(super) fn body_changed(&mut self) {
        self.creature_mass = self
            .creature_bodies
            .iter()
            .map(|b| self.bodies[*b].mass() as f64)
            .sum();
        self.energy = self.mechanical_energy();
    }

    /// Every part's id, in order.
    pub fn part_ids(&self) -> impl Iterator<Item = PartId> + use<> {
        (0..self.parts.len()).map(PartId)
    }

    /// Every joint's id, in order.
    pub fn joint_ids(&self) -> impl Iterator<Item = JointId> + use<> {
        (0..self.joints.len()).map(JointId)
    }

    /// Number of joints.
    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// The edge lengths of part `id` (m).
    ///
    /// # Panics
    ///
    /// If `id` names no part of this world.
    pub fn part_size(&self, id: PartId) -> Vector3<f64> {
        self.parts[id].size
    }

    /// The mass (kg) and principal moments of inertia (kg·m², about the principal axes
    /// through the centre of mass) of the rigid body part `id` is on (with the parts fused
    /// to it).
    ///
    /// # Panics
    ///
    /// If `id` names no part of this world.
    pub fn part_body_mass(&self, id: PartId) -> (f64, Vector3<f64>) {
        let body = &self.bodies[self.parts[id].body];
        let inertia = body.mass_properties().local_mprops.principal_inertia();
        (body.mass() as f64, super::world::to_na(inertia))
    }

    /// The anchor of joint `id` in the world as its parent part and as its child part hold
    /// it now (they differ by how far the solver lets the joint come apart), or `None` for a
    /// fused joint.
    ///
    /// # Panics
    ///
    /// If `id` names no joint of this world.
    pub fn joint_anchors(&self, id: JointId) -> Option<(Vector3<f64>, Vector3<f64>)> {
        let data = self.joint_data(id)?;
        let (b1, b2) = self.joints[id].ends;
        let a1 = *self.bodies[b1].position() * data.local_frame1;
        let a2 = *self.bodies[b2].position() * data.local_frame2;
        Some((
            super::world::to_na(a1.translation),
            super::world::to_na(a2.translation),
        ))
    }
}

/// `new / old` as a scale factor (1 when `old` is 0).
fn ratio(new: f64, old: f64) -> Real {
    if old == 0.0 { 1.0 } else { (new / old) as Real }
}
