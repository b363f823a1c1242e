//! A rapier3d world built from a [`Creature`]: box bodies on a flat high-friction ground,
//! joints, motors driven by the brain, sensors read back every control step.

use ::nalgebra::{Quaternion, UnitQuaternion, Vector3};
use rapier3d::math::{Pose, Real, Rotation, Vector};
use rapier3d::prelude::*;

use super::brain::BrainRuntime;
use super::setting::StepSetting;
use crate::creature::{Actuator, Creature, Face, Joint, Role, Sensor};

/// Gravity's acceleration (m/s²), pulling along −Y.
pub const GRAVITY: f64 = 9.81;

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
    let (a, b) = (parent.size.y * parent.size.z, child.size.y * child.size.z);
    let section = match options.strength_from {
        StrengthFrom::Smaller => a.min(b),
        StrengthFrom::Bigger => a.max(b),
    };
    options.strength * joint.strength * section
}

/// How joints are simulated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JointModel {
    /// Impulse-based constraints between free bodies (rapier's `ImpulseJointSet`).
    Impulse,
    /// Reduced coordinates (rapier's `MultibodyJointSet`).
    Multibody,
}

/// How an actuator neuron's signal s ∈ [−1, 1] drives its joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ActuatorModel {
    /// Chaumont et al. 5.3: the motor runs at saturation, its target velocity fixed high in
    /// the signal's sign, its maximum torque |s| × the joint's strength.
    Muscle,
    /// Chaumont et al. 5.3's muscle applied as what a saturated motor gives: a torque of
    /// s × the joint's strength about the joint's axis, equal and opposite on its two parts,
    /// with no motor row in the joint's constraint.
    MuscleTorque,
    /// Hornby & Pollack: s sets the target angle inside the joint's range.
    Angle,
    /// Matos & Arita: s sets the target angular velocity (s × `max_speed`).
    Velocity,
}

/// Which part's cross-section sets a joint's strength.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StrengthFrom {
    /// The smaller of the two parts (Walking with Dinosaurs 3.4.4: "the smallest contact
    /// area").
    Smaller,
    /// The bigger of the two parts (the default: Chaumont et al. 3.4, after Sims 1994, and
    /// the assumption behind the size normalisation of their walker fitness, equation 1).
    Bigger,
}

/// The default joint strength: maximum torque per square metre of cross-section (N·m/m²).
///
/// Calibrated so that a joint can hold a horizontal one-part limb of its own cross-section
/// and the default density against gravity up to a length of
/// L = √(2 · strength / (ρ g)) = √(2 · 10⁴ / (1000 · 9.81)) ≈ 1.43 m: a 1 m limb with a
/// margin of 2.04 (the torque needed is ρ g A L² / 2).
pub const DEFAULT_STRENGTH: f64 = 1.0e4;

/// The muscle model's target speed V_des (rad/s), "fixed and high" (Chaumont et al. 5.3) so
/// that a muscle is torque-limited, never speed-limited, in every shipped creature.
pub const DEFAULT_MUSCLE_SPEED: f64 = 100.0;

/// The default [`SimOptions::energy_tolerance`] (J/kg): the energy a creature may gain from
/// nothing within about [`ENERGY_WINDOW`], what lifting it by 1 m takes: three times the
/// most the shipped and random creatures reach at the fast setting ([`SimOptions::fast`], 3.2 J/kg), well
/// below what the exploits evolution found reach (27 J/kg). See the README's "energy audit".
pub const ENERGY_TOLERANCE: f64 = 10.0;

/// A joint gap (m) beyond which `ontogeny eval` warns that the step setting is too coarse for
/// the creature: the fine reference keeps the evolved walkers measured under 1.1 cm, while
/// the champions that exploited the fast setting reach 7 to 23 cm. See the README's
/// "Speed and fidelity".
pub const JOINT_GAP_WARNING: f64 = 0.05;

/// The memory (s) of the energy audit: unexplained energy gained this long ago counts for
/// 1/e of its amount.
pub const ENERGY_WINDOW: f64 = 0.5;

/// World settings. Read from a `[task.sim]` table through [`SimTable`](super::SimTable) (a named
/// step setting and any value over it); checked by [`SimOptions::check`].
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
#[serde(from = "super::SimTable")]
pub struct SimOptions {
    /// Control step in seconds: the brain runs once per step; physics runs `substeps`
    /// times per step, at `dt / substeps`.
    pub dt: f64,
    /// Physics substeps per control step.
    pub substeps: usize,
    /// Solver iterations per substep (rapier's `num_solver_iterations`: each one re-linearises
    /// the constraints and integrates positions over a fraction of the substep).
    pub solver_iterations: usize,
    /// Gauss-Seidel passes inside each solver iteration (rapier's
    /// `num_internal_pgs_iterations`): cheaper than solver iterations, as the constraints are
    /// not rebuilt.
    pub pgs_iterations: usize,
    /// Physics substeps per control step while a task waits for the creature to come to rest
    /// (controller off): Chaumont's rest test compares per-step motion with Δx, so it wants
    /// a steadier solver than walking does.
    pub rest_substeps: usize,
    /// Solver iterations per substep while a task waits for rest (one PGS pass each).
    pub rest_solver_iterations: usize,
    /// Joint model.
    pub joints: JointModel,
    /// Whether parts of one creature that are not joint neighbours collide.
    pub self_collision: bool,
    /// Friction coefficient of the ground and the parts.
    pub friction: f64,
    /// Actuator model.
    pub actuator: ActuatorModel,
    /// Maximum joint torque per square metre of cross-section (N·m/m²), multiplied by the
    /// joint's own strength.
    pub strength: f64,
    /// Whose cross-section: the smaller or the bigger of the two parts.
    pub strength_from: StrengthFrom,
    /// The muscle model's target speed V_des (rad/s), fixed and high so that the motor runs
    /// at saturation (torque-limited).
    pub muscle_speed: f64,
    /// The velocity model's top speed (rad/s): a signal s asks for s × `max_speed`.
    pub max_speed: f64,
    /// Height of the creature's lowest point above the ground when it is dropped.
    pub drop_height: f64,
    /// A part moving farther than this in one control step means the world exploded.
    pub explosion_distance: f64,
    /// A part faster than this (m/s) means the world exploded.
    pub speed_limit: f64,
    /// Energy from nowhere (J per kg of creature) that means the world exploded: the sum,
    /// over control steps, of every rise of the creature's mechanical energy (kinetic plus
    /// gravitational) beyond the most work its motors could have done in that step. 0 turns
    /// the audit off.
    pub energy_tolerance: f64,
}

impl Default for SimOptions {
    fn default() -> Self {
        // Physics at 1/240 s: 4 substeps of 4 solver iterations (one PGS pass each) while
        // walking, 4 substeps of 8 iterations (the fine reference's own setting) while a task
        // waits for rest. The champions evolved at the faster `SimOptions::fast` setting lost
        // most of their distance at the fine reference; those of the few runs evolved at this
        // one kept most of theirs (lucky walks aside), and this setting ranks random creatures
        // about as alike to the fine reference as the reference ranks them to itself (see
        // `ontogeny bench --fidelity` and the README's "Speed and fidelity").
        let (substeps, solver_iterations, pgs_iterations, rest_substeps, rest_solver_iterations) =
            StepSetting::Default.stepping();
        SimOptions {
            dt: 1.0 / 60.0,
            substeps,
            solver_iterations,
            pgs_iterations,
            rest_substeps,
            rest_solver_iterations,
            joints: JointModel::Impulse,
            self_collision: true,
            friction: 1.0,
            actuator: ActuatorModel::Muscle,
            strength: DEFAULT_STRENGTH,
            strength_from: StrengthFrom::Bigger,
            muscle_speed: DEFAULT_MUSCLE_SPEED,
            max_speed: 5.0,
            drop_height: 0.05,
            explosion_distance: 2.0,
            speed_limit: 100.0,
            energy_tolerance: ENERGY_TOLERANCE,
        }
    }
}

impl SimOptions {
    /// The fast setting ([`StepSetting::Fast`]), the default until evolution was found to
    /// exploit it: one physics step of 1/60 s with 2 solver iterations of 3 Gauss-Seidel
    /// passes while walking, 2 substeps of 4 iterations while waiting for rest; everything else
    /// as `self`. About 4× cheaper than the default per walk (3.6× with the rest phases, 4.7×
    /// controller on), and good for ranking random creatures (`bench --fidelity`), but evolved
    /// creatures learn to walk on its errors (README, "Speed and fidelity").
    pub fn fast(&self) -> SimOptions {
        StepSetting::Fast.apply(self)
    }

    /// The fine reference setting ([`StepSetting::Fine`]): these settings with 4 physics
    /// substeps of 8 solver iterations (one PGS pass each) both while walking and while waiting
    /// for rest; the control step `dt` and everything else unchanged. At the default `dt` of
    /// 1/60 s that is physics at 1/240 s. `ontogeny bench --fidelity` ranks stepping settings
    /// against it, and `ontogeny evolve` re-walks each generation's best with it, since
    /// evolution learns to exploit a coarse setting (see the README's *Speed and fidelity* and
    /// *Evolve*).
    pub fn fine_reference(&self) -> SimOptions {
        StepSetting::Fine.apply(self)
    }
}

/// A joint handle of either model.
#[derive(Clone, Copy, Debug)]
enum JointHandle {
    Impulse(ImpulseJointHandle),
    Multibody(MultibodyJointHandle),
    /// No rapier joint: a rigid joint, or a joint between two parts of one rigid body (its
    /// parts are fused into one body with a collider per part).
    Fused,
}

/// The groups of parts fused by rigid joints: for each part, the lowest-numbered part of its
/// group (union-find over the creature's rigid joints).
fn fused_groups(creature: &Creature) -> Vec<usize> {
    let mut root: Vec<usize> = (0..creature.parts.len()).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    for joint in &creature.joints {
        if joint.kind.dof() == 0 {
            let (a, b) = (find(&mut root, joint.parent), find(&mut root, joint.child));
            let (lo, hi) = (a.min(b), a.max(b));
            root[hi] = lo;
        }
    }
    (0..root.len()).map(|i| find(&mut root, i)).collect()
}

/// Why a world could not be built.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// The creature has no parts.
    #[error("the creature has no parts")]
    NoParts,
    /// The creature is malformed (see `Creature::check_consistency`).
    #[error("malformed creature: {0}")]
    Malformed(String),
    /// A multibody joint would close a loop.
    #[error("joint {0} closes a loop, which multibody joints cannot simulate")]
    Loop(usize),
}

const ANGULAR: [JointAxis; 3] = [JointAxis::AngX, JointAxis::AngY, JointAxis::AngZ];

/// What the motors need to know of a joint.
struct JointInfo {
    limits: Vec<(f64, f64)>,
    max_torque: f64,
    /// The torques (N·m) the torque muscle applies about the joint's axes this control step.
    torques: [f64; 3],
}

/// How near a part's contact point must be to the ground to count as touching it (m): the
/// touch sensors' and the ground drag's threshold.
pub const TOUCH_DISTANCE: Real = 1e-3;

/// A creature in a physics world, with its brain.
pub struct World {
    options: SimOptions,
    gravity: Vector,
    params: IntegrationParameters,
    pipeline: PhysicsPipeline,
    islands: IslandManager,
    broad_phase: BroadPhaseBvh,
    narrow_phase: NarrowPhase,
    bodies: RigidBodySet,
    colliders: ColliderSet,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    soft_bodies: SoftBodySet,
    ccd: CCDSolver,
    parts: Vec<(RigidBodyHandle, ColliderHandle)>,
    joints: Vec<JointHandle>,
    /// Per joint: the parent's and the child's bodies.
    joint_ends: Vec<(RigidBodyHandle, RigidBodyHandle)>,
    /// Per joint: its limits and maximum torque.
    joint_info: Vec<JointInfo>,
    brain: BrainRuntime,
    roles: Vec<Role>,
    environment: Vec<f64>,
    /// Early-release signal seen (a `release` effector above 0).
    released: bool,
    /// The catapult's projectile and the joint holding it, when there is one.
    projectile: Option<(RigidBodyHandle, Option<JointHandle>)>,
    /// The aiming task's target, for the target sensor.
    target: Option<Vector3<f64>>,
    time: f64,
    previous: Vec<Vector>,
    /// Wall-clock time spent inside rapier's pipeline, for measuring the evaluator's overhead.
    physics_time: std::time::Duration,
    /// Whether the world steps with the rest setting (see [`World::set_resting`]).
    resting: bool,
    /// The creature's bodies, once each.
    creature_bodies: Vec<RigidBodyHandle>,
    /// The creature's mass (kg).
    creature_mass: f64,
    /// The creature's mechanical energy after the last step (J).
    energy: f64,
    /// Energy gained beyond what the motors could supply, summed over the recent steps (J).
    unexplained_energy: f64,
    /// The most `unexplained_energy` has been (J).
    peak_unexplained: f64,
    /// The largest gap seen between the two ends of any joint's anchor (m).
    peak_joint_gap: f64,
    /// The ground's collider.
    ground_collider: ColliderHandle,
}

fn vector(v: &Vector3<f64>) -> Vector {
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

/// A world vector back in the project's nalgebra.
pub fn to_na(v: Vector) -> Vector3<f64> {
    Vector3::new(v.x as f64, v.y as f64, v.z as f64)
}

impl World {
    /// Builds the world: the creature lifted so that its lowest point is `drop_height` above
    /// the ground, at rest.
    pub fn new(creature: &Creature, options: &SimOptions) -> Result<World, BuildError> {
        if creature.parts.is_empty() {
            return Err(BuildError::NoParts);
        }
        creature
            .check_consistency()
            .map_err(BuildError::Malformed)?;
        let params = IntegrationParameters {
            dt: (options.dt / options.substeps.max(1) as f64) as Real,
            num_solver_iterations: options.solver_iterations.max(1),
            num_internal_pgs_iterations: options.pgs_iterations.max(1),
            ..IntegrationParameters::default()
        };
        let mut world = World {
            options: options.clone(),
            gravity: Vector::new(0.0, -GRAVITY as Real, 0.0),
            params,
            pipeline: PhysicsPipeline::new(),
            islands: IslandManager::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd: CCDSolver::new(),
            parts: Vec::new(),
            joints: Vec::new(),
            joint_ends: Vec::new(),
            joint_info: Vec::new(),
            brain: BrainRuntime::new(&creature.brain),
            roles: creature.brain.neurons.iter().map(|n| n.role).collect(),
            environment: creature.environment.clone(),
            released: false,
            projectile: None,
            target: None,
            time: 0.0,
            previous: Vec::new(),
            physics_time: std::time::Duration::ZERO,
            resting: false,
            creature_bodies: Vec::new(),
            creature_mass: 0.0,
            energy: 0.0,
            unexplained_energy: 0.0,
            peak_unexplained: 0.0,
            peak_joint_gap: 0.0,
            ground_collider: ColliderHandle::invalid(),
        };
        let ground = world.bodies.insert(RigidBodyBuilder::fixed());
        world.ground_collider = world.colliders.insert_with_parent(
            ColliderBuilder::halfspace(rapier3d::na::Unit::new_unchecked(Vector::Y))
                .friction(options.friction as Real),
            ground,
            &mut world.bodies,
        );

        let (lo, _) = creature.bounding_box();
        let lift = Vector3::new(0.0, options.drop_height - lo.y, 0.0);
        let groups = if options.self_collision {
            InteractionGroups::all()
        } else {
            // Parts collide with the ground only.
            InteractionGroups::new(Group::GROUP_2, Group::GROUP_1, InteractionTestMode::And)
        };
        // Parts fused by rigid joints share one rigid body, a collider each (as MuJoCo welds
        // them): a chain of fixed joints is the stiffest thing an impulse solver meets, and
        // at one substep it can pump energy into a creature that has no motor at all.
        let group = fused_groups(creature);
        let mut group_body: Vec<Option<RigidBodyHandle>> = vec![None; creature.parts.len()];
        for (i, part) in creature.parts.iter().enumerate() {
            let pose =
                Pose::from_parts(vector(&(part.position + lift)), rotation(&part.orientation));
            let body = match group_body[group[i]] {
                Some(body) => body,
                None => {
                    let body = world
                        .bodies
                        .insert(RigidBodyBuilder::dynamic().pose(pose).can_sleep(false));
                    group_body[group[i]] = Some(body);
                    body
                }
            };
            let relative = world.bodies[body].position().inverse() * pose;
            let half = part.size / 2.0;
            let collider = ColliderBuilder::cuboid(half.x as Real, half.y as Real, half.z as Real)
                .position(relative)
                .density(part.density as Real)
                .friction(options.friction as Real)
                .collision_groups(groups);
            let collider = world
                .colliders
                .insert_with_parent(collider, body, &mut world.bodies);
            world.parts.push((body, collider));
        }

        for (index, joint) in creature.joints.iter().enumerate() {
            let (b1, _) = world.parts[joint.parent];
            let (b2, _) = world.parts[joint.child];
            let max_torque = max_torque(creature, joint, options);
            if b1 == b2 {
                world.joints.push(JointHandle::Fused);
                world.joint_ends.push((b1, b2));
                world.joint_info.push(JointInfo {
                    limits: joint.limits.clone(),
                    max_torque,
                    torques: [0.0; 3],
                });
                continue;
            }
            let pose1 = *world.bodies[b1].position();
            let pose2 = *world.bodies[b2].position();
            let anchor = vector(&(joint.anchor + lift));
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
            let handle = match options.joints {
                JointModel::Impulse => {
                    JointHandle::Impulse(world.impulse_joints.insert(b1, b2, data, true))
                }
                JointModel::Multibody => JointHandle::Multibody(
                    world
                        .multibody_joints
                        .insert(b1, b2, data, true)
                        .ok_or(BuildError::Loop(index))?,
                ),
            };
            world.joints.push(handle);
            world.joint_ends.push((b1, b2));
            world.joint_info.push(JointInfo {
                limits: joint.limits.clone(),
                max_torque,
                torques: [0.0; 3],
            });
        }
        world.previous = (0..world.parts.len())
            .map(|i| world.part_world_pose(i).translation)
            .collect();
        world.creature_bodies = group_body.into_iter().flatten().collect();
        world.creature_mass = world
            .creature_bodies
            .iter()
            .map(|b| world.bodies[*b].mass() as f64)
            .sum();
        world.energy = world.mechanical_energy();
        Ok(world)
    }

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
        self.params.dt = (self.options.dt / substeps as f64) as Real;
        self.params.num_solver_iterations = iterations;
        self.params.num_internal_pgs_iterations = pgs;
    }

    /// The current (substeps, solver iterations, PGS passes).
    fn stepping(&self) -> (usize, usize, usize) {
        let o = &self.options;
        if self.resting {
            (o.rest_substeps.max(1), o.rest_solver_iterations.max(1), 1)
        } else {
            (
                o.substeps.max(1),
                o.solver_iterations.max(1),
                o.pgs_iterations.max(1),
            )
        }
    }

    /// The creature's mechanical energy (J): kinetic, and gravitational above the ground.
    fn mechanical_energy(&self) -> f64 {
        self.creature_bodies
            .iter()
            .map(|b| {
                let body = &self.bodies[*b];
                body.kinetic_energy() as f64
                    + body.mass() as f64 * GRAVITY * body.center_of_mass().y as f64
            })
            .sum()
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
        for (j, handle) in self.joints.iter().enumerate() {
            let data = match *handle {
                JointHandle::Impulse(h) => match self.impulse_joints.get(h) {
                    Some(joint) => &joint.data,
                    None => continue,
                },
                _ => continue,
            };
            let (b1, b2) = self.joint_ends[j];
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
    fn motor_power_bound(&self) -> f64 {
        let mut work = 0.0;
        for j in 0..self.joints.len() {
            let Some(data) = self.joint_data(j) else {
                continue;
            };
            let (b1, b2) = self.joint_ends[j];
            let relative = self.bodies[b2].angvel() - self.bodies[b1].angvel();
            let frame = *self.bodies[b1].rotation() * data.local_frame1.rotation;
            let dof = self.joint_info[j].limits.len().min(3);
            for (k, axis) in [Vector::X, Vector::Y, Vector::Z]
                .into_iter()
                .enumerate()
                .take(dof)
            {
                let limit =
                    data.motors[3 + k].max_force as f64 + self.joint_info[j].torques[k].abs();
                if limit > 0.0 {
                    work += limit * (relative.dot(frame * axis) as f64).abs();
                }
            }
        }
        work
    }

    /// Simulated time so far.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The environment array (secreting neurons write it).
    pub fn environment(&self) -> &[f64] {
        &self.environment
    }

    /// Neuron `i`'s current output: for a sensor neuron, its last reading.
    pub fn sensor_reading(&self, i: usize) -> f64 {
        self.brain.outputs()[i]
    }

    /// Whether a `release` effector has fired.
    pub fn release_signalled(&self) -> bool {
        self.released
    }

    /// Attaches a projectile box of `size` and `density` to the root part's near end (its local
    /// −x face, where the turtle started and nothing else grows), held by a fixed joint until
    /// [`release`](Self::release) (Chaumont 4.1: the root part is the arm).
    pub fn attach_projectile(&mut self, size: Vector3<f64>, density: f64) {
        let (root, root_collider) = self.parts[0];
        let root_pose = self.part_world_pose(0);
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
            for (body, _) in &self.parts {
                if moved.contains(body) {
                    continue;
                }
                moved.push(*body);
                let b = &mut self.bodies[*body];
                let t = b.translation() + up;
                b.set_translation(t, true);
            }
            for p in &mut self.previous {
                *p += up;
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

    /// The projectile's centre and speed, when there is one.
    pub fn projectile_state(&self) -> Option<(Vector3<f64>, f64)> {
        self.projectile.map(|(body, _)| {
            let b = &self.bodies[body];
            (to_na(b.translation()), b.linvel().length() as f64)
        })
    }

    /// Sets the point the target sensor points to.
    pub fn set_target(&mut self, target: Option<Vector3<f64>>) {
        self.target = target;
    }

    /// The world pose of part `i`: its body's pose and the part's place in the body (always
    /// in step with the body, even before the colliders are synchronised).
    fn part_world_pose(&self, i: usize) -> Pose {
        let (body, collider) = self.parts[i];
        let relative = self.colliders[collider]
            .position_wrt_parent()
            .copied()
            .unwrap_or(Pose::IDENTITY);
        *self.bodies[body].position() * relative
    }

    /// The centre of part `i`.
    pub fn part_position(&self, i: usize) -> Vector3<f64> {
        to_na(self.part_world_pose(i).translation)
    }

    /// The pose of part `i`: centre and orientation.
    pub fn part_pose(&self, i: usize) -> (Vector3<f64>, UnitQuaternion<f64>) {
        let pose = self.part_world_pose(i);
        let q = pose.rotation;
        (
            to_na(pose.translation),
            UnitQuaternion::from_quaternion(Quaternion::new(
                q.w as f64, q.x as f64, q.y as f64, q.z as f64,
            )),
        )
    }

    /// Number of parts.
    pub fn part_count(&self) -> usize {
        self.parts.len()
    }

    /// The lowest point of any part's box.
    pub fn lowest_point(&self) -> f64 {
        (0..self.parts.len())
            .map(|i| self.part_aabb(i).mins.y as f64)
            .fold(f64::INFINITY, f64::min)
    }

    fn part_aabb(&self, i: usize) -> rapier3d::parry::bounding_volume::Aabb {
        self.colliders[self.parts[i].1]
            .shape()
            .compute_aabb(&self.part_world_pose(i))
    }

    /// The highest point of any part's box.
    pub fn highest_point(&self) -> f64 {
        (0..self.parts.len())
            .map(|i| self.part_aabb(i).maxs.y as f64)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Angle of degree of freedom `dof` of joint `j` (radians), from the bodies' poses.
    fn joint_angle(&self, j: usize, dof: usize) -> f64 {
        let data = match self.joints[j] {
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
    pub fn joint_speed(&self, j: usize) -> f64 {
        let data = match self.joints[j] {
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

    fn joint_bodies(&self, j: usize) -> (RigidBodyHandle, RigidBodyHandle) {
        self.joint_ends[j]
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
        for &(body, collider) in &self.parts {
            let Some(pair) = self
                .narrow_phase
                .contact_pair(collider, self.ground_collider)
            else {
                continue;
            };
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
    fn read_sensors(&mut self) {
        for i in 0..self.roles.len() {
            let Role::Sensor { sensor } = self.roles[i] else {
                continue;
            };
            let value = match sensor {
                Sensor::Touch { part, face } => {
                    let collider = self.parts[part].1;
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
                    let limits = &self.joint_info[joint].limits;
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
                        let (position, orientation) = self.part_pose(0);
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

    /// Drives every actuator from the brain's outputs (or switches the motors off).
    fn drive(&mut self, on: bool) {
        for i in 0..self.roles.len() {
            let Role::Actuator { actuator } = self.roles[i] else {
                continue;
            };
            let s = self.brain.outputs()[i];
            match actuator {
                Actuator::Joint { joint, dof } => {
                    let info = &self.joint_info[joint];
                    let (lo, hi) = info.limits.get(dof).copied().unwrap_or((0.0, 0.0));
                    let max_torque = info.max_torque;
                    let (muscle_speed, speed) = (self.options.muscle_speed, self.options.max_speed);
                    let model = self.options.actuator;
                    let axis = ANGULAR[dof.min(2)];
                    if model == ActuatorModel::MuscleTorque {
                        let torque = if on { s * max_torque } else { 0.0 };
                        self.joint_info[joint].torques[dof.min(2)] = torque;
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
    fn apply_muscle_torques(&mut self) {
        for &b in &self.creature_bodies {
            self.bodies[b].reset_torques(false);
        }
        for j in 0..self.joints.len() {
            let torques = self.joint_info[j].torques;
            if torques == [0.0; 3] {
                continue;
            }
            let Some(frame1) = self.joint_data(j).map(|data| data.local_frame1.rotation) else {
                continue;
            };
            let (b1, b2) = self.joint_ends[j];
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
    fn joint_data(&self, j: usize) -> Option<&GenericJoint> {
        match self.joints[j] {
            JointHandle::Impulse(h) => self.impulse_joints.get(h).map(|joint| &joint.data),
            JointHandle::Multibody(h) => self
                .multibody_joints
                .get(h)
                .and_then(|(mb, link)| mb.link(link))
                .map(|link| &link.joint.data),
            JointHandle::Fused => None,
        }
    }

    fn with_joint(&mut self, j: usize, f: impl FnOnce(&mut GenericJoint)) {
        match self.joints[j] {
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

    /// One control step: sensors, brain (when `controller` is on), actuators, physics.
    /// Returns the largest displacement of any part's centre, or an error when the world
    /// exploded (NaN, a jump past `explosion_distance`, a speed past `speed_limit`).
    pub fn step(&mut self, controller: bool) -> Result<f64, Exploded> {
        if controller {
            self.read_sensors();
            self.brain.step(self.time, self.options.dt);
        }
        self.drive(controller);
        let power_before = self.motor_power_bound();
        let started = std::time::Instant::now();
        let torque_muscles = self.options.actuator == ActuatorModel::MuscleTorque;
        for _ in 0..self.stepping().0 {
            if torque_muscles {
                self.apply_muscle_torques();
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
                &(),
                &(),
            );
        }
        self.physics_time += started.elapsed();
        self.time += self.options.dt;
        // The energy audit: a rise beyond the motors' possible work is energy from nowhere.
        let energy = self.mechanical_energy();
        // The motors' work over the step is at most the larger of their power bounds at its
        // two ends × dt (a speed through zero in between only lowers it).
        let allowed = power_before.max(self.motor_power_bound()) * self.options.dt;
        // Summed with a memory of ENERGY_WINDOW seconds: a slow trickle of solver error
        // fades, a burst does not.
        let fade = (-self.options.dt / ENERGY_WINDOW).exp();
        self.unexplained_energy =
            self.unexplained_energy * fade + (energy - self.energy - allowed).max(0.0);
        self.peak_unexplained = self.peak_unexplained.max(self.unexplained_energy);
        self.energy = energy;
        let tolerance = self.options.energy_tolerance;
        if tolerance > 0.0 && self.unexplained_energy > tolerance * self.creature_mass {
            return Err(Exploded::Energy(self.unexplained_energy));
        }
        self.peak_joint_gap = self.peak_joint_gap.max(self.joint_gap());
        let mut largest: f64 = 0.0;
        for k in 0..self.parts.len() {
            let body = &self.bodies[self.parts[k].0];
            let p = self.part_world_pose(k).translation;
            let v = body.linvel();
            if !p.is_finite() || !v.is_finite() {
                return Err(Exploded::NotANumber);
            }
            let moved = (p - self.previous[k]).length() as f64;
            if moved > self.options.explosion_distance {
                return Err(Exploded::Jump(moved));
            }
            if v.length() as f64 > self.options.speed_limit {
                return Err(Exploded::Speed(v.length() as f64));
            }
            largest = largest.max(moved);
            self.previous[k] = p;
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
        let dt = world.options.dt;
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
        let from = world.part_position(0);
        let body = world.parts[0].0;
        world.bodies[body].set_linvel(Vector::new(2.0, 0.0, 0.0), true);
        let dragged = drag_over(&mut world, 60);
        let slid = horizontal(world.part_position(0) - from);
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
        let (body, collider) = world.parts[0];
        world.colliders[collider].set_shape(SharedShape::ball(0.125));
        for _ in 0..60 {
            world.step(false).unwrap();
        }
        let from = world.part_position(0);
        world.bodies[body].set_linvel(Vector::new(2.0, 0.0, 0.0), true);
        world.bodies[body].set_angvel(Vector::new(0.0, 0.0, -2.0 / 0.125), true);
        let dragged = drag_over(&mut world, 6);
        let rolled = horizontal(world.part_position(0) - from);
        assert!((rolled - 0.2).abs() < 0.02, "rolled {rolled} m");
        assert!(
            dragged < 0.1 * rolled,
            "dragged {dragged} m, rolled {rolled} m"
        );
    }
}
