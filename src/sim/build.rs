//! Building a rapier world from a [`Creature`]: parts as boxes (parts fused by rigid joints
//! share one body), joints with their limits and motors switched off, the ground, and the
//! creature dropped from its drop height.

use ::nalgebra::{UnitQuaternion, Vector3};
use rapier3d::math::{Pose, Real, Rotation, Vector};
use rapier3d::prelude::*;

use super::actuators::max_torque;
use super::brain::BrainRuntime;
use super::options::{JointModel, SimOptions};
use super::setting::SettingError;
use super::world::{ANGULAR, GRAVITY, JointHandle, JointInfo, World};
use crate::creature::Creature;

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
    /// The options are out of range ([`SimOptions::check`]): the message names the key.
    #[error("{0}")]
    Options(#[from] SettingError),
    /// A multibody joint would close a loop.
    #[error("joint {0} closes a loop, which multibody joints cannot simulate")]
    Loop(usize),
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

impl World {
    /// Builds the world: the creature lifted so that its lowest point is `drop_height` above
    /// the ground, at rest. Options out of their ranges ([`SimOptions::check`]: no substeps,
    /// say) are refused.
    pub fn new(creature: &Creature, options: &SimOptions) -> Result<World, BuildError> {
        options.check()?;
        if creature.parts.is_empty() {
            return Err(BuildError::NoParts);
        }
        creature
            .check_consistency()
            .map_err(BuildError::Malformed)?;
        let params = IntegrationParameters {
            dt: (options.control_step / options.substeps as f64) as Real,
            num_solver_iterations: options.solver_iterations,
            num_internal_pgs_iterations: options.pgs_iterations,
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
}
