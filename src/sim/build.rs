//! Building a rapier world from a [`Creature`]: parts as boxes (parts fused by rigid joints
//! share one body), joints with their limits and motors switched off, the ground, and the
//! creature dropped from its drop height; or, in water, no ground and no gravity.

use ::nalgebra::Vector3;
use rapier3d::math::{Real, Vector};
use rapier3d::prelude::*;

use super::brain::BrainRuntime;
use super::motion::Attach;
use super::options::SimOptions;
use super::setting::SettingError;
use super::slots::Ground;
use super::slots::Keyed;
use super::terrain::Terrain;
use super::world::{GRAVITY, World};
use super::world_spec::{Medium, WorldSpec};
use crate::creature::{Creature, Joint, Part, PartId};

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

impl World {
    /// Builds the world: the creature lifted so that its lowest point is `drop_height` above
    /// the ground, at rest. Options out of their ranges ([`SimOptions::check`]: no substeps,
    /// say) are refused.
    pub fn new(creature: &Creature, options: &SimOptions) -> Result<World, BuildError> {
        World::in_world(creature, options, &WorldSpec::default())
    }

    /// Builds the world of `spec` ([`WorldSpec::check`] must pass, else the error names the
    /// key) with the creature dropped so that its lowest point is `drop_height` above the
    /// highest ground under its footprint ([`Terrain::extremes_under`]), at rest. The free
    /// objects are held where they start until [`World::release_objects`]. In water there is
    /// no ground and no gravity: the creature is at rest where it is, its bounding box centred
    /// on the origin, every part feeling water resistance ([`super::water`]).
    pub fn in_world(
        creature: &Creature,
        options: &SimOptions,
        spec: &WorldSpec,
    ) -> Result<World, BuildError> {
        options.check()?;
        spec.check().map_err(|e| e.within("world"))?;
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
            parts: Keyed::new(),
            joints: Keyed::new(),
            brain: BrainRuntime::new(&creature.brain),
            roles: creature.brain.neurons.iter().map(|n| n.role).collect(),
            environment: creature.environment.clone(),
            released: false,
            projectile: None,
            target: None,
            time: 0.0,
            physics_time: std::time::Duration::ZERO,
            resting: false,
            creature_bodies: Vec::new(),
            creature_mass: 0.0,
            energy: 0.0,
            unexplained_energy: 0.0,
            growth_work: 0.0,
            peak_unexplained: 0.0,
            peak_joint_gap: 0.0,
            ground: Ground::empty(),
            water: None,
        };
        let (lo, hi) = creature.bounding_box();
        let lift = match spec.medium {
            Medium::Air => {
                let terrain = Terrain::new(spec);
                let (beneath, _) = terrain.extremes_under([lo.x, hi.x], [lo.z, hi.z]);
                world.ground = Ground::build(&mut world, &terrain, beneath);
                Vector3::new(0.0, options.drop_height + beneath - lo.y, 0.0)
            }
            Medium::Water { viscosity } => {
                world.gravity = Vector::ZERO;
                world.water = Some(viscosity);
                -(lo + hi) / 2.0
            }
        };
        // Parts fused by rigid joints share one rigid body, a collider each (as MuJoCo welds
        // them): a chain of fixed joints is the stiffest thing an impulse solver meets, and
        // at one substep it can pump energy into a creature that has no motor at all.
        let group = fused_groups(creature);
        for (i, part) in creature.parts.iter().enumerate() {
            let lifted = Part {
                position: part.position + lift,
                ..part.clone()
            };
            let attach = if group[i] == i {
                Attach::Free
            } else {
                Attach::FusedTo(PartId(group[i]))
            };
            world.add_part(&lifted, attach);
        }
        for joint in &creature.joints {
            let lifted = Joint {
                anchor: joint.anchor + lift,
                ..joint.clone()
            };
            world.add_joint(&lifted)?;
        }
        world.energy = world.mechanical_energy();
        Ok(world)
    }
}
