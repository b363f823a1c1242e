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

/// What a growth step conserves: the creature's linear momentum, its angular momentum about
/// the world's origin, and (as a ceiling) its kinetic energy relative to its centre of mass.
#[derive(Clone, Copy, Debug)]
pub(super) struct Momenta {
    linear: Vector3<f64>,
    angular: Vector3<f64>,
    internal: f64,
}

impl World {
    /// The creature's kinetic energy (J): Σ over its bodies of ½ m v² + ½ ω·Iω.
    pub fn kinetic_energy(&self) -> f64 {
        self.creature_bodies
            .iter()
            .map(|b| self.bodies[*b].kinetic_energy() as f64)
            .sum()
    }

    /// The creature's mass and centre of mass, from its bodies as they are now.
    fn creature_centre(&self) -> (f64, Vector3<f64>) {
        let (mass, moment) =
            self.creature_bodies
                .iter()
                .fold((0.0, Vector3::zeros()), |(m, c), b| {
                    let body = &self.bodies[*b];
                    let mb = body.mass() as f64;
                    (m + mb, c + to_na(body.center_of_mass()) * mb)
                });
        (mass, if mass > 0.0 { moment / mass } else { moment })
    }

    /// The creature's momenta now: what [`World::conserve_momenta`] restores.
    pub(super) fn momenta(&self) -> Momenta {
        let linear = self.creature_momentum();
        let (mass, _) = self.creature_centre();
        let bulk = if mass > 0.0 {
            linear.norm_squared() / (2.0 * mass)
        } else {
            0.0
        };
        Momenta {
            linear,
            angular: self.creature_angular_momentum(),
            internal: self.kinetic_energy() - bulk,
        }
    }

    /// Gives the creature back the momenta it had `before` a growth step, after new or moved
    /// mass was put in place moving with what holds it: one rigid motion (a + b × (x − c), c
    /// the new centre of mass) added to every body restores the linear momentum and the
    /// angular momentum about c; then, if the kinetic energy relative to the centre of mass
    /// is still above what it was, every velocity relative to the centre of mass is scaled
    /// down to it. Both keep every joint's two sides moving together. So growth brings mass
    /// as a closed creature would, from within: it neither pushes the creature nor spins it,
    /// and never raises its kinetic energy.
    pub(super) fn conserve_momenta(&mut self, before: &Momenta) {
        let (mass, centre) = self.creature_centre();
        if mass <= 0.0 {
            return;
        }
        let (linear, angular) = (self.creature_momentum(), self.creature_angular_momentum());
        // Angular momenta about the new centre of mass: L_c = L_O − c × P.
        let wanted = before.angular - centre.cross(&before.linear);
        let now = angular - centre.cross(&linear);
        // The creature's inertia about c (kg·m²), column by column.
        let mut inertia = ::nalgebra::Matrix3::zeros();
        for b in &self.creature_bodies {
            let body = &self.bodies[*b];
            let r = to_na(body.center_of_mass()) - centre;
            let m = body.mass() as f64;
            let own = body.mass_properties().effective_angular_inertia();
            for (k, axis) in [Vector::X, Vector::Y, Vector::Z].into_iter().enumerate() {
                let column = to_na(own * axis);
                let e = Vector3::ith(k, 1.0);
                let orbit = (e * r.norm_squared() - r * r[k]) * m;
                inertia.set_column(k, &(inertia.column(k) + column + orbit));
            }
        }
        let a = (before.linear - linear) / mass;
        let b = inertia
            .try_inverse()
            .map(|inverse| inverse * (wanted - now))
            .unwrap_or_else(Vector3::zeros);
        for handle in self.creature_bodies.clone() {
            let body = &mut self.bodies[handle];
            let r = to_na(body.center_of_mass()) - centre;
            let v = to_na(body.linvel()) + a + b.cross(&r);
            let w = to_na(body.angvel()) + b;
            body.set_linvel(vector(&v), true);
            body.set_angvel(vector(&w), true);
        }
        // The kinetic energy relative to the centre of mass may not rise.
        let bulk = before.linear.norm_squared() / (2.0 * mass);
        let internal = self.kinetic_energy() - bulk;
        if internal > before.internal.max(0.0) && internal > 0.0 {
            let k = (before.internal.max(0.0) / internal).sqrt();
            let v_c = before.linear / mass;
            for handle in self.creature_bodies.clone() {
                let body = &mut self.bodies[handle];
                let v = v_c + (to_na(body.linvel()) - v_c) * k;
                let w = to_na(body.angvel()) * k;
                body.set_linvel(vector(&v), true);
                body.set_angvel(vector(&w), true);
            }
        }
    }
}
