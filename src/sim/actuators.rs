//! How the brain's outputs drive the body: each joint's maximum torque, the motor settings of
//! the muscle, angle and velocity models ([`World::drive`](super::World)), the torque muscle's
//! torques applied every substep, and secretion and release effectors.

use ::nalgebra::Vector3;
use rapier3d::math::{Real, Vector};
use rapier3d::prelude::*;

use super::options::{ActuatorModel, SimOptions, StrengthFrom};
use super::slots::JointHandle;
use super::world::{ANGULAR, World};
use crate::creature::{Actuator, Creature, Joint, JointId, Role};

/// Motor gains per N·m of a joint's maximum torque. A velocity motor's torque is damping ×
/// (target − current speed), clamped to the maximum: a damping of `SATURATION_DAMPING` ×
/// the maximum torque makes the muscle and velocity models run at saturation.
pub const SATURATION_DAMPING: f64 = 1000.0;

/// The angle model's stiffness (N·m/rad) per N·m of maximum torque.
pub const ANGLE_STIFFNESS: f64 = 20.0;

/// The angle model's damping (N·m·s/rad) per N·m of maximum torque.
pub const ANGLE_DAMPING: f64 = 2.0;

/// The maximum torque (N·m) of `joint`'s motor in `creature`: `options.strength` × the
/// joint's own strength × the cross-section (y × z) of the smaller or bigger of its two parts.
pub fn max_torque(creature: &Creature, joint: &Joint, options: &SimOptions) -> f64 {
    let parent = &creature.parts[joint.parent];
    let child = &creature.parts[joint.child];
    max_torque_between(&parent.size, &child.size, joint.strength, options)
}

/// The maximum torque (N·m) of a joint of `strength` between parts of sizes `parent` and
/// `child` (see [`max_torque`]).
pub(super) fn max_torque_between(
    parent: &Vector3<f64>,
    child: &Vector3<f64>,
    strength: f64,
    options: &SimOptions,
) -> f64 {
    let (a, b) = (parent.y * parent.z, child.y * child.z);
    let section = match options.strength_from {
        StrengthFrom::Smaller => a.min(b),
        StrengthFrom::Bigger => a.max(b),
    };
    options.strength * strength * section
}

impl World {
    /// Drives every actuator from the brain's outputs (or switches the motors off).
    pub(super) fn drive(&mut self, on: bool) {
        for i in 0..self.roles.len() {
            let Role::Actuator { actuator } = self.roles[i] else {
                continue;
            };
            let s = self.brain.outputs()[i];
            match actuator {
                Actuator::Joint { joint, dof } => {
                    let joint = JointId(joint);
                    let info = &self.joints[joint];
                    let (lo, hi) = info.limits.get(dof).copied().unwrap_or((0.0, 0.0));
                    let max_torque = info.max_torque;
                    let (muscle_speed, speed) = (self.options.muscle_speed, self.options.max_speed);
                    let model = self.options.actuator;
                    let axis = ANGULAR[dof.min(2)];
                    if model == ActuatorModel::MuscleTorque {
                        let torque = if on { s * max_torque } else { 0.0 };
                        self.joints[joint].torques[dof.min(2)] = torque;
                        continue;
                    }
                    self.with_joint(joint, |data| {
                        if !on {
                            data.set_motor_max_force(axis, 0.0);
                            return;
                        }
                        let stiff = (max_torque * SATURATION_DAMPING).max(1e-3) as Real;
                        match model {
                            ActuatorModel::Muscle | ActuatorModel::MuscleTorque => {
                                data.set_motor_velocity(
                                    axis,
                                    (muscle_speed * s.signum()) as Real,
                                    stiff,
                                );
                                data.set_motor_max_force(axis, (s.abs() * max_torque) as Real);
                            }
                            ActuatorModel::Angle => {
                                let target = lo + (s + 1.0) / 2.0 * (hi - lo);
                                data.set_motor_position(
                                    axis,
                                    target as Real,
                                    (max_torque * ANGLE_STIFFNESS) as Real,
                                    (max_torque * ANGLE_DAMPING) as Real,
                                );
                                data.set_motor_max_force(axis, max_torque as Real);
                            }
                            ActuatorModel::Velocity => {
                                data.set_motor_velocity(axis, (speed * s) as Real, stiff);
                                data.set_motor_max_force(axis, max_torque as Real);
                            }
                        }
                    });
                }
                Actuator::Secrete { slot } => {
                    if on && let Some(v) = self.environment.get_mut(slot) {
                        *v = s;
                    }
                }
                Actuator::Release => {
                    if on && s > 0.0 {
                        self.released = true;
                    }
                }
            }
        }
    }

    /// The torque muscle: sets every creature body's torque to the sum of the muscle torques
    /// of its joints, each about the joint's axis as it is now (its first part's frame), +τ on
    /// the second part and −τ on the first.
    pub(super) fn apply_muscle_torques(&mut self) {
        for &b in &self.creature_bodies {
            self.bodies[b].reset_torques(false);
        }
        for j in self.joint_ids() {
            let torques = self.joints[j].torques;
            if torques == [0.0; 3] {
                continue;
            }
            let Some(frame1) = self.joint_data(j).map(|data| data.local_frame1.rotation) else {
                continue;
            };
            let (b1, b2) = self.joints[j].ends;
            let frame = *self.bodies[b1].rotation() * frame1;
            let torque = [Vector::X, Vector::Y, Vector::Z]
                .into_iter()
                .zip(torques)
                .fold(Vector::ZERO, |sum, (axis, t)| {
                    sum + frame * axis * t as Real
                });
            self.bodies[b2].add_torque(torque, true);
            self.bodies[b1].add_torque(-torque, true);
        }
    }

    /// Joint `j`'s data, or `None` for a fused joint.
    pub(super) fn joint_data(&self, j: JointId) -> Option<&GenericJoint> {
        match self.joints[j].handle {
            JointHandle::Impulse(h) => self.impulse_joints.get(h).map(|joint| &joint.data),
            JointHandle::Multibody(h) => self
                .multibody_joints
                .get(h)
                .and_then(|(mb, link)| mb.link(link))
                .map(|link| &link.joint.data),
            JointHandle::Fused => None,
        }
    }

    pub(super) fn with_joint(&mut self, j: JointId, f: impl FnOnce(&mut GenericJoint)) {
        match self.joints[j].handle {
            JointHandle::Impulse(h) => {
                if let Some(joint) = self.impulse_joints.get_mut(h, false) {
                    f(&mut joint.data);
                }
            }
            JointHandle::Multibody(h) => {
                if let Some((mb, link)) = self.multibody_joints.get_mut(h)
                    && let Some(link) = mb.link_mut(link)
                {
                    f(&mut link.joint.data);
                }
            }
            JointHandle::Fused => {}
        }
    }
}
