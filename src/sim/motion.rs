//! The creature's motion: a part's velocity, the creature's linear and angular momentum, and
//! how new or moved mass is given the motion of what holds it — a part added to a running
//! world ([`Attach`]) arrives moving with the velocity field of the body it is attached to,
//! a body whose mass changes keeps its velocity field, and a child carried by a growing part
//! moves with the part's field where it is put.

use ::nalgebra::Vector3;
use rapier3d::math::{Real, Vector};
use rapier3d::prelude::*;

use super::world::{World, to_na};
use crate::creature::PartId;

/// How a part added to the world ([`World::add_part`]) is held, and so how it moves when it
/// arrives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Attach {
    /// A rigid body of its own, at rest.
    Free,
    /// A rigid body of its own, moving with the given part's velocity field where it appears
    /// (v + ω × r, and the same ω): a child about to be jointed to that part.
    MovingWith(PartId),
    /// Welded to the given part's rigid body: a collider more on it, as [`World::new`] does
    /// for parts joined by rigid joints. The body keeps its velocity field.
    FusedTo(PartId),
}

/// A rigid body's velocity field: the velocity `linear` at `point`, and the angular velocity.
#[derive(Clone, Copy, Debug)]
pub(super) struct Field {
    point: Vector,
    linear: Vector,
    angular: Vector,
}

impl Field {
    /// The velocity of the material point at `x`: v + ω × (x − point).
    fn at(&self, x: Vector) -> Vector {
        self.linear + self.angular.cross(x - self.point)
    }

    /// Whether every point is at rest.
    fn is_rest(&self) -> bool {
        self.linear == Vector::ZERO && self.angular == Vector::ZERO
    }
}

fn vector(v: &Vector3<f64>) -> Vector {
    Vector::new(v.x as Real, v.y as Real, v.z as Real)
}

impl World {
    /// The velocity field of `body` now.
    pub(super) fn field_of(&self, body: RigidBodyHandle) -> Field {
        let b = &self.bodies[body];
        Field {
            point: b.center_of_mass(),
            linear: b.linvel(),
            angular: b.angvel(),
        }
    }

    /// Sets `body`'s velocity to `field` (its centre of mass moving as the field's point
    /// there); a body left at rest by a field at rest is not touched.
    pub(super) fn move_with(&mut self, body: RigidBodyHandle, field: &Field) {
        let b = &mut self.bodies[body];
        if field.is_rest() && b.linvel() == Vector::ZERO && b.angvel() == Vector::ZERO {
            return;
        }
        let linear = field.at(b.center_of_mass());
        b.set_linvel(linear, true);
        b.set_angvel(field.angular, true);
    }

    /// Translates `from` and every body jointed beyond it (not through `stop`) by `by`, each
    /// part's last position with it, and adds to each body's velocity ω × `by`, ω of `field`:
    /// what a growing part (`stop`, moving as `field`) does to a child whose anchor it moves.
    pub(super) fn carry(
        &mut self,
        from: RigidBodyHandle,
        stop: RigidBodyHandle,
        by: Vector,
        field: &Field,
    ) {
        let carried = self.joints.beyond(from, stop, |joint| joint.ends);
        let nudge = field.angular.cross(by);
        for &handle in &carried {
            let body = &mut self.bodies[handle];
            let t = body.translation() + by;
            body.set_translation(t, true);
            if nudge != Vector::ZERO {
                let v = body.linvel() + nudge;
                body.set_linvel(v, true);
            }
        }
        for part in self.parts.iter_mut() {
            if carried.contains(&part.body) {
                part.previous += by;
            }
        }
    }

    /// The velocity of part `id`'s centre (m/s) and its angular velocity (rad/s).
    ///
    /// # Panics
    ///
    /// If `id` names no part of this world.
    pub fn part_velocity(&self, id: PartId) -> (Vector3<f64>, Vector3<f64>) {
        let centre = self.part_world_pose(id).translation;
        let field = self.field_of(self.parts[id].body);
        (to_na(field.at(centre)), to_na(field.angular))
    }

    /// Sets the velocity of part `id`'s body so that the part's centre moves at `linear` (m/s)
    /// and the body turns at `angular` (rad/s): a push, for tests and experiments.
    ///
    /// # Panics
    ///
    /// If `id` names no part of this world.
    pub fn set_part_velocity(&mut self, id: PartId, linear: Vector3<f64>, angular: Vector3<f64>) {
        let field = Field {
            point: self.part_world_pose(id).translation,
            linear: vector(&linear),
            angular: vector(&angular),
        };
        self.move_with(self.parts[id].body, &field);
        self.energy = self.mechanical_energy();
    }

    /// The creature's linear momentum (kg·m/s): Σ over its bodies of mass × velocity.
    pub fn creature_momentum(&self) -> Vector3<f64> {
        self.creature_bodies
            .iter()
            .map(|b| {
                let body = &self.bodies[*b];
                to_na(body.linvel()) * body.mass() as f64
            })
            .sum()
    }

    /// The creature's angular momentum about the world's origin (kg·m²/s): Σ over its bodies
    /// of m c × v (c the centre of mass) plus the body's inertia in the world × ω.
    pub fn creature_angular_momentum(&self) -> Vector3<f64> {
        self.creature_bodies
            .iter()
            .map(|b| {
                let body = &self.bodies[*b];
                let orbital = body.center_of_mass().cross(body.linvel()) * body.mass();
                let spin = body.mass_properties().effective_angular_inertia() * body.angvel();
                to_na(orbital) + to_na(spin)
            })
            .sum()
    }
}
