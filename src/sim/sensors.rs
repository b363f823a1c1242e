//! What a creature senses of its world, read back every control step: touch, joint angles,
//! chemicals, the target's bearing; and the joint and contact measurements they and the tasks
//! use (joint speed, ground sliding speed).

use ::nalgebra::Vector3;
use rapier3d::math::{Real, Vector};
use rapier3d::prelude::*;

use super::slots::JointHandle;
use super::slots::PartSlot;
use super::world::{World, to_na};
use crate::creature::{Face, JointId, PartId, Role, Sensor};

/// How near a part's contact point must be to the ground to count as touching it (m): the
/// touch sensors' and the ground drag's threshold.
pub const TOUCH_DISTANCE: Real = 1e-3;

impl World {
    /// Sets the point the target sensor points to.
    pub fn set_target(&mut self, target: Option<Vector3<f64>>) {
        self.target = target;
    }

    /// Neuron `i`'s current output: for a sensor neuron, its last reading.
    pub fn sensor_reading(&self, i: usize) -> f64 {
        self.brain.outputs()[i]
    }

    /// Angle of degree of freedom `dof` of joint `j` (radians), from the bodies' poses.
    pub(super) fn joint_angle(&self, j: JointId, dof: usize) -> f64 {
        let data = match self.joints[j].handle {
            JointHandle::Impulse(h) => match self.impulse_joints.get(h) {
                Some(joint) => &joint.data,
                None => return 0.0,
            },
            JointHandle::Multibody(h) => match self.multibody_joints.get(h) {
                Some((mb, link)) => &mb.link(link).expect("link exists").joint.data,
                None => return 0.0,
            },
            JointHandle::Fused => return 0.0,
        };
        let (b1, b2) = self.joint_bodies(j);
        let r1 = *self.bodies[b1].rotation() * data.local_frame1.rotation;
        let r2 = *self.bodies[b2].rotation() * data.local_frame2.rotation;
        let relative = r1.inverse() * r2;
        let (x, y, z) = relative.to_euler(rapier3d::glamx::EulerRot::XYZ);
        [x, y, z][dof.min(2)] as f64
    }

    /// Angular speed of joint `j` about its first axis (rad/s): the child's angular velocity
    /// relative to the parent's, projected on the axis.
    ///
    /// # Panics
    ///
    /// If `j` names no joint of this world.
    pub fn joint_speed(&self, j: JointId) -> f64 {
        let data = match self.joints[j].handle {
            JointHandle::Impulse(h) => match self.impulse_joints.get(h) {
                Some(joint) => joint.data,
                None => return 0.0,
            },
            JointHandle::Multibody(h) => match self.multibody_joints.get(h) {
                Some((mb, link)) => mb.link(link).expect("link exists").joint.data,
                None => return 0.0,
            },
            JointHandle::Fused => return 0.0,
        };
        let (b1, b2) = self.joint_bodies(j);
        let axis = *self.bodies[b1].rotation() * data.local_frame1.rotation * Vector::X;
        let relative = self.bodies[b2].angvel() - self.bodies[b1].angvel();
        relative.dot(axis) as f64
    }

    pub(super) fn joint_bodies(&self, j: JointId) -> (RigidBodyHandle, RigidBodyHandle) {
        self.joints[j].ends
    }

    /// How fast the creature's parts slide along the ground now (m/s): over every contact
    /// manifold between a part and the ground, the mean over its touching points (no farther
    /// apart than [`TOUCH_DISTANCE`]) of the horizontal speed of the part's material point
    /// there, summed over manifolds. One manifold is one contact: a face resting on four
    /// corners counts once, at its corners' mean sliding speed. A part that rolls without
    /// slipping, or stands still, slides at 0. Times the control step, it is the distance
    /// dragged during the step (Hornby & Pollack's D_drag).
    pub fn ground_sliding_speed(&self) -> f64 {
        let mut total = 0.0;
        let pairs = self.parts.iter().flat_map(|slot| {
            self.ground.colliders.iter().filter_map(move |&ground| {
                Some((slot, self.narrow_phase.contact_pair(slot.collider, ground)?))
            })
        });
        for (&PartSlot { body, collider, .. }, pair) in pairs {
            let ours_first = pair.collider1 == collider;
            let pose = self.colliders[collider].position();
            let body = &self.bodies[body];
            for manifold in pair.manifolds() {
                let mut speeds = 0.0;
                let mut touching = 0usize;
                for point in manifold.points.iter().filter(|p| p.dist <= TOUCH_DISTANCE) {
                    let local = if ours_first {
                        point.local_p1
                    } else {
                        point.local_p2
                    };
                    let v = body.velocity_at_point(pose.transform_point(local));
                    speeds += (v.x as f64).hypot(v.z as f64);
                    touching += 1;
                }
                if touching > 0 {
                    total += speeds / touching as f64;
                }
            }
        }
        total
    }

    /// Sets every sensor neuron from the world.
    pub(super) fn read_sensors(&mut self) {
        for i in 0..self.roles.len() {
            let Role::Sensor { sensor } = self.roles[i] else {
                continue;
            };
            let value = match sensor {
                Sensor::Touch { part, face } => {
                    let collider = self.parts[PartId(part)].collider;
                    let touching = self.narrow_phase.contact_pairs_with(collider).any(|p| {
                        let ours_first = p.collider1 == collider;
                        p.manifolds().iter().any(|m| {
                            m.points.iter().any(|pt| pt.dist <= TOUCH_DISTANCE)
                                && face.is_none_or(|face| {
                                    // The contact normal, outward from this part, in its axes.
                                    let n = if ours_first { m.local_n1 } else { m.local_n2 };
                                    Face::facing(&to_na(n)) == face
                                })
                        })
                    });
                    if touching { 1.0 } else { -1.0 }
                }
                Sensor::Angle { joint, dof } => {
                    let joint = JointId(joint);
                    let limits = &self.joints[joint].limits;
                    let (lo, hi) = limits.get(dof).copied().unwrap_or((-1.0, 1.0));
                    let a = self.joint_angle(joint, dof);
                    if hi > lo {
                        2.0 * (a - lo) / (hi - lo) - 1.0
                    } else {
                        0.0
                    }
                }
                Sensor::Chemical { slot } => self.environment.get(slot).copied().unwrap_or(0.0),
                Sensor::Target => match self.target {
                    // The horizontal angle from the root's heading to the target, over π.
                    Some(target) => {
                        let (position, orientation) = self.part_pose(PartId(0));
                        let heading = orientation * Vector3::x();
                        let to = target - position;
                        let a = heading.z.atan2(heading.x) - to.z.atan2(to.x);
                        let a = (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                            - std::f64::consts::PI;
                        a / std::f64::consts::PI
                    }
                    None => 0.0,
                },
            };
            self.brain.set_sensor(i, value);
        }
    }
}
