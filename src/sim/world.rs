//! A creature in a rapier3d world ([`World`]) and its stepping: one control step runs the
//! sensors, the brain, the actuators, the physics substeps, the energy audit and the explosion
//! checks. Building the world is in [`super::build`], the options in [`super::options`], the
//! senses in [`super::sensors`], the motors in [`super::actuators`], the energy audit in
//! [`super::audit`], the catapult's projectile in [`super::projectile`], water resistance in
//! [`super::water`].

use ::nalgebra::{Quaternion, UnitQuaternion, Vector3};
use rapier3d::math::{Pose, Real, Vector};
use rapier3d::prelude::*;

use super::brain::BrainRuntime;
use super::options::{ActuatorModel, SimOptions};
use super::slots::{JointHandle, JointSlot, Keyed, PartSlot};
use crate::creature::{JointId, Link, Neuron, PartId, Role};

/// Gravity's acceleration (m/s²), pulling along −Y.
pub const GRAVITY: f64 = 9.81;

/// The three angular axes of a joint frame, in the order of a joint's degrees of freedom.
pub(super) const ANGULAR: [JointAxis; 3] = [JointAxis::AngX, JointAxis::AngY, JointAxis::AngZ];

/// A creature in a physics world, with its brain.
pub struct World {
    pub(super) options: SimOptions,
    pub(super) gravity: Vector,
    pub(super) params: IntegrationParameters,
    pub(super) pipeline: PhysicsPipeline,
    pub(super) islands: IslandManager,
    pub(super) broad_phase: BroadPhaseBvh,
    pub(super) narrow_phase: NarrowPhase,
    pub(super) bodies: RigidBodySet,
    pub(super) colliders: ColliderSet,
    pub(super) impulse_joints: ImpulseJointSet,
    pub(super) multibody_joints: MultibodyJointSet,
    pub(super) soft_bodies: SoftBodySet,
    pub(super) ccd: CCDSolver,
    /// The creature's parts, by id.
    pub(super) parts: Keyed<PartId, PartSlot>,
    /// The creature's joints, by id.
    pub(super) joints: Keyed<JointId, JointSlot>,
    pub(super) brain: BrainRuntime,
    pub(super) roles: Vec<Role>,
    pub(super) environment: Vec<f64>,
    /// Early-release signal seen (a `release` effector above 0).
    pub(super) released: bool,
    /// The catapult's projectile and the joint holding it, when there is one.
    pub(super) projectile: Option<(RigidBodyHandle, Option<JointHandle>)>,
    /// The aiming task's target, for the target sensor.
    pub(super) target: Option<Vector3<f64>>,
    pub(super) time: f64,
    /// Wall-clock time spent inside rapier's pipeline, for measuring the evaluator's overhead.
    pub(super) physics_time: std::time::Duration,
    /// Whether the world steps with the rest setting (see [`World::set_resting`]).
    pub(super) resting: bool,
    /// The creature's bodies, once each.
    pub(super) creature_bodies: Vec<RigidBodyHandle>,
    /// The creature's mass (kg).
    pub(super) creature_mass: f64,
    /// The creature's mechanical energy after the last step (J).
    pub(super) energy: f64,
    /// Energy gained beyond what the motors could supply, summed over the recent steps (J).
    pub(super) unexplained_energy: f64,
    /// The energy growth has brought so far (J; [`super::growth`]).
    pub(super) growth_work: f64,
    /// The most `unexplained_energy` has been (J).
    pub(super) peak_unexplained: f64,
    /// The largest gap seen between the two ends of any joint's anchor (m).
    pub(super) peak_joint_gap: f64,
    /// The ground, the obstacles and the free objects (none in water).
    pub(super) ground: super::slots::Ground,
    /// The water's viscosity (N·s/m³) when the creature swims ([`super::water`]); `None` in
    /// air.
    pub(super) water: Option<f64>,
}

/// A world vector back in the project's nalgebra.
pub fn to_na(v: Vector) -> Vector3<f64> {
    Vector3::new(v.x as f64, v.y as f64, v.z as f64)
}

/// A rapier pose as nalgebra's position and rotation.
pub(super) fn na_pose(pose: &Pose) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let q = pose.rotation;
    (
        to_na(pose.translation),
        UnitQuaternion::from_quaternion(Quaternion::new(
            q.w as f64, q.x as f64, q.y as f64, q.z as f64,
        )),
    )
}

impl World {
    /// Wall-clock time spent inside rapier's physics pipeline so far (the rest of a step —
    /// sensors, brain, motors, checks — is the evaluator's overhead).
    pub fn physics_time(&self) -> std::time::Duration {
        self.physics_time
    }

    /// Switches between the walking setting (`substeps`, `solver_iterations`,
    /// `pgs_iterations`) and the rest setting (`rest_substeps`, `rest_solver_iterations`, one
    /// PGS pass) used while a task waits for the creature to come to rest.
    pub fn set_resting(&mut self, resting: bool) {
        self.resting = resting;
        let (substeps, iterations, pgs) = self.stepping();
        self.params.dt = (self.options.control_step / substeps as f64) as Real;
        self.params.num_solver_iterations = iterations;
        self.params.num_internal_pgs_iterations = pgs;
    }

    /// The current (substeps, solver iterations, PGS passes), each at least 1 ([`World::new`]
    /// refuses options that [`SimOptions::check`] refuses).
    pub(super) fn stepping(&self) -> (usize, usize, usize) {
        let o = &self.options;
        if self.resting {
            (o.rest_substeps, o.rest_solver_iterations, 1)
        } else {
            (o.substeps, o.solver_iterations, o.pgs_iterations)
        }
    }

    /// Adds `neuron` to the running brain (a sensor is read, an actuator drives, from the
    /// next control step on); returns its index, the next one.
    pub fn add_neuron(&mut self, neuron: &Neuron) -> usize {
        self.roles.push(neuron.role);
        self.brain.add_neuron(neuron)
    }

    /// Adds `link` to the running brain (see [`BrainRuntime::add_link`]).
    ///
    /// # Panics
    ///
    /// If either end names no neuron.
    pub fn add_link(&mut self, link: &Link) {
        self.brain.add_link(link);
    }

    /// The running brain.
    pub fn brain(&self) -> &BrainRuntime {
        &self.brain
    }

    /// Simulated time so far.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The environment array (secreting neurons write it).
    pub fn environment(&self) -> &[f64] {
        &self.environment
    }

    /// Sets the environment array to `values` (a growing creature's development writes it
    /// back after its `?E` exchanges). Slots past the shorter of the two are left as they are.
    pub fn set_environment(&mut self, values: &[f64]) {
        for (slot, &v) in self.environment.iter_mut().zip(values) {
            *slot = v;
        }
    }

    /// The world pose of part `id`: its body's pose and the part's place in the body (always
    /// in step with the body, even before the colliders are synchronised).
    pub(super) fn part_world_pose(&self, id: PartId) -> Pose {
        let PartSlot { body, collider, .. } = self.parts[id];
        let relative = self.colliders[collider]
            .position_wrt_parent()
            .copied()
            .unwrap_or(Pose::IDENTITY);
        *self.bodies[body].position() * relative
    }

    /// The centre of part `id`.
    ///
    /// # Panics
    ///
    /// If `id` names no part of this world.
    pub fn part_position(&self, id: PartId) -> Vector3<f64> {
        to_na(self.part_world_pose(id).translation)
    }

    /// The pose of part `id`: centre and orientation.
    ///
    /// # Panics
    ///
    /// If `id` names no part of this world.
    pub fn part_pose(&self, id: PartId) -> (Vector3<f64>, UnitQuaternion<f64>) {
        na_pose(&self.part_world_pose(id))
    }

    /// Number of parts.
    pub fn part_count(&self) -> usize {
        self.parts.len()
    }

    /// The lowest point of any part's box.
    pub fn lowest_point(&self) -> f64 {
        self.part_ids()
            .map(|id| self.part_aabb(id).mins.y as f64)
            .fold(f64::INFINITY, f64::min)
    }

    pub(super) fn part_aabb(&self, id: PartId) -> rapier3d::parry::bounding_volume::Aabb {
        self.colliders[self.parts[id].collider]
            .shape()
            .compute_aabb(&self.part_world_pose(id))
    }

    /// The highest point of any part's box.
    pub fn highest_point(&self) -> f64 {
        self.part_ids()
            .map(|id| self.part_aabb(id).maxs.y as f64)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// One control step: sensors, brain (when `controller` is on), actuators, physics.
    /// Returns the largest displacement of any part's centre, or an error when the world
    /// exploded (NaN, a jump past `explosion_distance`, a speed past `speed_limit`).
    pub fn step(&mut self, controller: bool) -> Result<f64, Exploded> {
        if controller {
            self.read_sensors();
            self.brain.step(self.time, self.options.control_step);
        }
        self.drive(controller);
        let power_before = self.motor_power_bound();
        let started = std::time::Instant::now();
        let torque_muscles = self.options.actuator == ActuatorModel::MuscleTorque;
        for _ in 0..self.stepping().0 {
            if torque_muscles {
                self.apply_muscle_torques();
            }
            if let Some(viscosity) = self.water {
                self.apply_water_resistance(viscosity, !torque_muscles);
            }
            self.pipeline.step(
                self.gravity,
                &self.params,
                &mut self.islands,
                &mut self.broad_phase,
                &mut self.narrow_phase,
                &mut self.bodies,
                &mut self.colliders,
                &mut self.impulse_joints,
                &mut self.multibody_joints,
                &mut self.soft_bodies,
                &mut self.ccd,
                self.ground.hooks(),
                &(),
            );
        }
        self.physics_time += started.elapsed();
        self.time += self.options.control_step;
        self.audit_energy(power_before)?;
        self.peak_joint_gap = self.peak_joint_gap.max(self.joint_gap());
        let mut largest: f64 = 0.0;
        for id in self.part_ids() {
            let body = &self.bodies[self.parts[id].body];
            let p = self.part_world_pose(id).translation;
            let v = body.linvel();
            if !p.is_finite() || !v.is_finite() {
                return Err(Exploded::NotANumber);
            }
            let moved = (p - self.parts[id].previous).length() as f64;
            if moved > self.options.explosion_distance {
                return Err(Exploded::Jump(moved));
            }
            if v.length() as f64 > self.options.speed_limit {
                return Err(Exploded::Speed(v.length() as f64));
            }
            largest = largest.max(moved);
            self.parts[id].previous = p;
        }
        if let Some((position, speed)) = self.projectile_state() {
            if !position.iter().all(|v| v.is_finite()) || !speed.is_finite() {
                return Err(Exploded::NotANumber);
            }
            if speed > self.options.speed_limit {
                return Err(Exploded::Speed(speed));
            }
        }
        Ok(largest)
    }
}

/// How a world exploded.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum Exploded {
    /// A position or velocity became NaN or infinite.
    #[error("a part's position or velocity is not a number")]
    NotANumber,
    /// A part moved too far in one step.
    #[error("a part moved {0:.2} m in one step")]
    Jump(f64),
    /// A part moved too fast.
    #[error("a part reached {0:.1} m/s")]
    Speed(f64),
    /// The creature gained energy its motors cannot have given it.
    #[error("the creature gained {0:.1} J its motors cannot have supplied")]
    Energy(f64),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One box, 1 m long, 0.25 m wide and thick, lying on the ground at rest.
    fn settled_box() -> World {
        let creature = crate::develop::creature_from_commands("forward(1)").unwrap();
        let mut world = World::new(&creature, &SimOptions::default()).unwrap();
        for _ in 0..60 {
            world.step(false).unwrap();
        }
        world
    }

    /// Steps `world` for `steps` control steps; the distance dragged along the ground.
    fn drag_over(world: &mut World, steps: usize) -> f64 {
        let dt = world.options.control_step;
        let mut meter = crate::sim::DragMeter::start(world);
        for _ in 0..steps {
            world.step(false).unwrap();
            meter.after_step(world, dt);
        }
        meter.dragged()
    }

    fn horizontal(v: Vector3<f64>) -> f64 {
        v.x.hypot(v.z)
    }

    #[test]
    fn a_box_lying_still_drags_nothing() {
        let mut world = settled_box();
        assert!(drag_over(&mut world, 30) < 1e-4);
    }

    #[test]
    fn a_box_sliding_to_a_stop_drags_the_distance_it_slides() {
        // Launched at v = 2 m/s along the ground with friction μ = 1 (part against ground),
        // it slows at μg = 9.81 m/s² and stops after v²/(2μg) = 4 / 19.62 ≈ 0.204 m, every
        // centimetre of it sliding: D_drag ≈ 0.204 m.
        let mut world = settled_box();
        let from = world.part_position(PartId(0));
        let body = world.parts[PartId(0)].body;
        world.bodies[body].set_linvel(Vector::new(2.0, 0.0, 0.0), true);
        let dragged = drag_over(&mut world, 60);
        let slid = horizontal(world.part_position(PartId(0)) - from);
        let by_hand = 4.0 / (2.0 * GRAVITY);
        assert!((slid - by_hand).abs() < 0.1 * by_hand, "slid {slid} m");
        assert!(
            (dragged - slid).abs() < 0.05 * slid,
            "dragged {dragged} m, slid {slid} m"
        );
    }

    #[test]
    fn a_ball_rolling_the_same_distance_drags_almost_nothing() {
        // The box's shape made a ball of radius r = 0.125 m, launched rolling without
        // slipping at v = 2 m/s, ω = v / r about −z: its contact point is still, so over
        // the 0.2 m it rolls (0.1 s) it drags next to nothing.
        let mut world = settled_box();
        let PartSlot { body, collider, .. } = world.parts[PartId(0)];
        world.colliders[collider].set_shape(SharedShape::ball(0.125));
        for _ in 0..60 {
            world.step(false).unwrap();
        }
        let from = world.part_position(PartId(0));
        world.bodies[body].set_linvel(Vector::new(2.0, 0.0, 0.0), true);
        world.bodies[body].set_angvel(Vector::new(0.0, 0.0, -2.0 / 0.125), true);
        let dragged = drag_over(&mut world, 6);
        let rolled = horizontal(world.part_position(PartId(0)) - from);
        assert!((rolled - 0.2).abs() < 0.02, "rolled {rolled} m");
        assert!(
            dragged < 0.1 * rolled,
            "dragged {dragged} m, rolled {rolled} m"
        );
    }
}
