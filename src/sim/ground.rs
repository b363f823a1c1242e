//! The ground and what stands on it, in rapier: the colliders of a world's [`Terrain`] (a
//! level or tilted halfspace, the steps' boxes, a heightfield and the level slabs round it),
//! its obstacles (fixed boxes), its free objects (balls and boxes, held where they start until
//! the walk begins, then let go with their starting velocity), and the ground's friction.
//!
//! **Friction against the ground.** Without `[task.world] friction`, every collider has the
//! simulator's `friction` and rapier's rule (the average of the two) combines them, so a part
//! on the ground meets `friction`. With it, a contact between the ground and anything else
//! meets the ground's coefficient at that contact as is (the first patch holding the mean of
//! the contact's points, else the ground's coefficient): the part's own coefficient plays no
//! part. Obstacles, objects and parts among themselves keep the simulator's `friction`.

use rapier3d::math::{Pose, Real, Rotation, Vector};
use rapier3d::parry::utils::Array2;
use rapier3d::prelude::*;

use super::slots::{Ground, GroundFriction};
use super::terrain::{Cuboid, Terrain};
use super::world::{GRAVITY, World};
use super::world_spec::ObjectShape;

impl PhysicsHooks for GroundFriction {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let Some(manifold) = context.rigid_mut() else {
            return;
        };
        let count = manifold.solver_contacts.len();
        if count == 0 {
            return;
        }
        // Inside the hook, anchors are world points.
        let sum = manifold
            .solver_contacts
            .iter()
            .fold(Vector::ZERO, |s, c| s + c.anchor1);
        let mean = sum / count as Real;
        if let Some(mu) = self.terrain.friction(mean.x as f64, mean.z as f64) {
            *manifold.friction = mu as Real;
        }
    }
}

fn vector(v: [f64; 3]) -> Vector {
    Vector::new(v[0] as Real, v[1] as Real, v[2] as Real)
}

/// A cuboid's collider, placed.
fn cuboid(c: &Cuboid) -> ColliderBuilder {
    let [hx, hy, hz] = c.half;
    let pose = Pose::from_parts(
        vector(c.centre),
        Rotation::from_axis_angle(Vector::Y, -(c.direction.to_radians() as Real)),
    );
    ColliderBuilder::cuboid(hx as Real, hy as Real, hz as Real).position(pose)
}

impl Ground {
    /// Nothing yet: a placeholder while the world is being built.
    pub(super) fn empty() -> Ground {
        Ground {
            colliders: Vec::new(),
            objects: Vec::new(),
            released: false,
            friction: None,
            start: 0.0,
        }
    }

    /// Builds `terrain` into `world`'s sets, the creature's drop resting on `start`: level
    /// ground alone is today's halfspace, exactly.
    pub(super) fn build(world: &mut World, terrain: &Terrain, start: f64) -> Ground {
        let friction = world.options.friction as Real;
        let hooks = if terrain.spec().friction.is_some() {
            ActiveHooks::MODIFY_SOLVER_CONTACTS
        } else {
            ActiveHooks::empty()
        };
        let body = world.bodies.insert(RigidBodyBuilder::fixed());
        let mut shapes: Vec<ColliderBuilder> = Vec::new();
        if let Some(n) = terrain.slope_normal() {
            let normal = rapier3d::na::Unit::new_unchecked(vector(n).normalize());
            shapes.push(ColliderBuilder::halfspace(normal));
        } else if let Some(field) = terrain.heightfield() {
            let n = field.samples;
            // Column-major, rows along z and columns along x: element (i, j) at i + j·n.
            let mut heights: Vec<Real> = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    heights[i + j * n] = field.heights[i * n + j] as Real;
                }
            }
            let side = field.side as Real;
            shapes.push(ColliderBuilder::heightfield_with_flags(
                Array2::new(n, n, heights),
                Vector::new(side, 1.0, side),
                HeightFieldFlags::FIX_INTERNAL_EDGES,
            ));
        } else if let Some(base) = terrain.base() {
            let halfspace =
                ColliderBuilder::halfspace(rapier3d::na::Unit::new_unchecked(Vector::Y));
            shapes.push(if base == 0.0 {
                halfspace
            } else {
                halfspace.translation(Vector::new(0.0, base as Real, 0.0))
            });
        }
        shapes.extend(terrain.ground_boxes().iter().map(cuboid));
        let colliders = shapes
            .into_iter()
            .map(|shape| {
                let shape = if hooks.is_empty() {
                    shape
                } else {
                    shape.active_hooks(hooks)
                };
                world.colliders.insert_with_parent(
                    shape.friction(friction),
                    body,
                    &mut world.bodies,
                )
            })
            .collect();
        for obstacle in terrain.obstacle_boxes() {
            world.colliders.insert_with_parent(
                cuboid(&obstacle).friction(friction),
                body,
                &mut world.bodies,
            );
        }
        let objects = terrain
            .objects()
            .into_iter()
            .map(|object| {
                let handle = world.bodies.insert(
                    RigidBodyBuilder::kinematic_position_based()
                        .translation(vector(object.centre))
                        .can_sleep(false),
                );
                let half = object.half as Real;
                let shape = match object.shape {
                    ObjectShape::Ball => ColliderBuilder::ball(half),
                    ObjectShape::Box => ColliderBuilder::cuboid(half, half, half),
                };
                world.colliders.insert_with_parent(
                    shape.mass(object.mass as Real).friction(friction),
                    handle,
                    &mut world.bodies,
                );
                (handle, vector(object.velocity))
            })
            .collect();
        Ground {
            colliders,
            objects,
            released: false,
            friction: terrain.spec().friction.is_some().then(|| GroundFriction {
                terrain: terrain.clone(),
            }),
            start,
        }
    }

    /// The hooks the physics pipeline runs with.
    pub(super) fn hooks(&self) -> &dyn PhysicsHooks {
        match &self.friction {
            Some(friction) => friction,
            None => &(),
        }
    }

    /// Whether there are objects and they have been let go.
    pub(super) fn any_released(&self) -> bool {
        self.released && !self.objects.is_empty()
    }

    /// The objects' bodies, once let go (they count in the energy audit from then on).
    pub(super) fn released_objects(&self) -> impl Iterator<Item = RigidBodyHandle> + '_ {
        self.objects
            .iter()
            .filter(|_| self.released)
            .map(|(handle, _)| *handle)
    }
}

impl World {
    /// Lets the free objects go, each with its starting velocity (the walker and every task
    /// call it when their measured part begins); once only. Until then they are held where
    /// they start, and the creature meets them as fixed.
    pub fn release_objects(&mut self) {
        if self.ground.released {
            return;
        }
        self.ground.released = true;
        for &(handle, velocity) in &self.ground.objects {
            let body = &mut self.bodies[handle];
            body.set_body_type(RigidBodyType::Dynamic, true);
            body.set_linvel(velocity, true);
        }
        self.energy = self.mechanical_energy();
    }

    /// What `read` reads of each free object's body now, in the order of `[task.world]
    /// objects`.
    fn each_object<T>(&self, read: impl Fn(&RigidBody) -> T) -> Vec<T> {
        let bodies = self.ground.objects.iter().map(|(h, _)| &self.bodies[*h]);
        bodies.map(read).collect()
    }

    /// The free objects' centres now, in the order of `[task.world] objects`.
    pub fn object_positions(&self) -> Vec<[f64; 3]> {
        self.each_object(|body| {
            let p = body.translation();
            [p.x as f64, p.y as f64, p.z as f64]
        })
    }

    /// The free objects' orientations now, as quaternions [w, x, y, z].
    pub fn object_rotations(&self) -> Vec<[f64; 4]> {
        self.each_object(|body| {
            let q = body.rotation();
            [q.w as f64, q.x as f64, q.y as f64, q.z as f64]
        })
    }

    /// The height of the highest ground under the creature's footprint where it was dropped
    /// (m): 0 on level ground. Heights the tasks measure (the jump's) count from it.
    pub fn start_ground(&self) -> f64 {
        self.ground.start
    }

    /// The gravitational and kinetic energy of the let-go objects (J), so that a ball's
    /// blow is no energy from nowhere.
    pub(super) fn objects_energy(&self) -> f64 {
        self.ground
            .released_objects()
            .map(|b| {
                let body = &self.bodies[b];
                body.kinetic_energy() as f64
                    + body.mass() as f64 * GRAVITY * body.center_of_mass().y as f64
            })
            .sum()
    }
}
