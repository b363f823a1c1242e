//! The energy audit and the joint gap: the creature's mechanical energy, the most power its
//! motors can be giving, the energy gained beyond it (energy from nowhere, a sign that the
//! solver, not the brain, moved the creature), and how far joints come apart.

use rapier3d::math::Vector;

use super::slots::JointHandle;
use super::world::{Exploded, GRAVITY, World};

/// A joint gap (m) beyond which `ontogeny eval` warns that the step setting is too coarse for
/// the creature: the fine reference keeps the evolved walkers measured under 1.1 cm, while
/// the champions that exploited the fast setting reach 7 to 23 cm. See
/// docs/results/speed.md.
pub const JOINT_GAP_WARNING: f64 = 0.05;

/// The memory (s) of the energy audit: unexplained energy gained this long ago counts for
/// 1/e of its amount.
pub const ENERGY_WINDOW: f64 = 0.5;

impl World {
    /// The creature's mechanical energy (J): kinetic, and gravitational above the ground; and
    /// that of the world's free objects once they are let go.
    pub(super) fn mechanical_energy(&self) -> f64 {
        let creature: f64 = self
            .creature_bodies
            .iter()
            .map(|b| {
                let body = &self.bodies[*b];
                body.kinetic_energy() as f64
                    + body.mass() as f64 * GRAVITY * body.center_of_mass().y as f64
            })
            .sum();
        if self.ground.any_released() {
            creature + self.objects_energy()
        } else {
            creature
        }
    }

    /// The most energy the creature gained beyond what its motors could supply within
    /// about [`ENERGY_WINDOW`] (J), so far. A passive creature or a motor-driven one in a
    /// faithful world gains none; solver artefacts do.
    pub fn peak_unexplained_energy(&self) -> f64 {
        self.peak_unexplained
    }

    /// The largest distance between a joint's anchor as the parent and as the child see it
    /// (m), now: how far the impulse solver lets joints come apart (multibody joints and fused
    /// parts cannot).
    pub fn joint_gap(&self) -> f64 {
        let mut gap: f64 = 0.0;
        for joint in self.joints.iter() {
            let data = match joint.handle {
                JointHandle::Impulse(h) => match self.impulse_joints.get(h) {
                    Some(joint) => &joint.data,
                    None => continue,
                },
                _ => continue,
            };
            let (b1, b2) = joint.ends;
            let a1 = *self.bodies[b1].position() * data.local_frame1;
            let a2 = *self.bodies[b2].position() * data.local_frame2;
            gap = gap.max((a1.translation - a2.translation).length() as f64);
        }
        gap
    }

    /// The largest [`World::joint_gap`] so far (m).
    pub fn peak_joint_gap(&self) -> f64 {
        self.peak_joint_gap
    }

    /// The creature's mass (kg).
    pub fn creature_mass(&self) -> f64 {
        self.creature_mass
    }

    /// The most power the motors can be giving now (W): Σ over driven degrees of freedom of
    /// the torque limit × the joint's angular speed.
    pub(super) fn motor_power_bound(&self) -> f64 {
        let mut work = 0.0;
        for j in self.joint_ids() {
            let Some(data) = self.joint_data(j) else {
                continue;
            };
            let joint = &self.joints[j];
            let (b1, b2) = joint.ends;
            let relative = self.bodies[b2].angvel() - self.bodies[b1].angvel();
            let frame = *self.bodies[b1].rotation() * data.local_frame1.rotation;
            let dof = joint.limits.len().min(3);
            for (k, axis) in [Vector::X, Vector::Y, Vector::Z]
                .into_iter()
                .enumerate()
                .take(dof)
            {
                let limit = data.motors[3 + k].max_force as f64 + joint.torques[k].abs();
                if limit > 0.0 {
                    work += limit * (relative.dot(frame * axis) as f64).abs();
                }
            }
        }
        work
    }

    /// The energy audit at the end of a control step: a rise of the creature's mechanical
    /// energy beyond the most work its motors could have done (`power_before`: their power
    /// bound at the step's start) is energy from nowhere. Summed with a memory of
    /// [`ENERGY_WINDOW`], past `energy_tolerance` J per kg it means the world exploded.
    pub(super) fn audit_energy(&mut self, power_before: f64) -> Result<(), Exploded> {
        // The energy audit: a rise beyond the motors' possible work is energy from nowhere.
        let energy = self.mechanical_energy();
        // The motors' work over the step is at most the larger of their power bounds at its
        // two ends × dt (a speed through zero in between only lowers it).
        let allowed = power_before.max(self.motor_power_bound()) * self.options.control_step;
        // Summed with a memory of ENERGY_WINDOW seconds: a slow trickle of solver error
        // fades, a burst does not.
        let fade = (-self.options.control_step / ENERGY_WINDOW).exp();
        self.unexplained_energy =
            self.unexplained_energy * fade + (energy - self.energy - allowed).max(0.0);
        self.peak_unexplained = self.peak_unexplained.max(self.unexplained_energy);
        self.energy = energy;
        let tolerance = self.options.energy_tolerance;
        if tolerance > 0.0 && self.unexplained_energy > tolerance * self.creature_mass {
            return Err(Exploded::Energy(self.unexplained_energy));
        }
        Ok(())
    }
}
