//! Growth applied to a running world: a part that lengthens as the turtle lengthens it
//! ([`World::grow_part`]), and one step of development's [`Growth`] — parts resized, new parts
//! with their joints, new neurons and links — applied honestly ([`World::apply_growth`]).
//!
//! Honest means that growth is not a motor:
//!
//! - a lengthened part keeps its near face (where it is jointed to its parent, where the turtle
//!   started it) in place; what it carries beyond its far joints is carried with it;
//! - a new part appears where the turtle puts it relative to its parent, at rest relative to
//!   it, so no joint is strained;
//! - then the creature's velocities are given back the momenta they had before the step: its
//!   linear momentum, its angular momentum about its centre of mass, and at most its kinetic
//!   energy relative to its centre of mass (see `World::conserve_momenta` in `motion.rs`). The
//!   creature grows as a closed body does, from within: growth neither pushes it, nor spins
//!   it, nor gives it kinetic energy. A creature that spins while it grows a long limb slows,
//!   as a skater who opens her arms does. (Mass that arrived moving with its parent, v + ω × r,
//!   and kept that speed was a motor: a creature that swung a limb and then grew a chain of
//!   parts at its tip multiplied its kinetic energy, and evolution found it: creatures that
//!   "walked" over 100 m in 10 s.);
//! - the energy growth brings (the potential energy of added and moved mass, less any kinetic
//!   energy it costs) is counted apart, as [`World::growth_work`], so the energy audit does not
//!   take it for energy from nowhere, and still catches any energy the growth does not
//!   account for;
//! - a part whose growth would reach into the ground, or into another part (when parts
//!   collide with each other), deeper than [`GROWTH_CLEARANCE`] where it did not already reach,
//!   or would put a part it carries there, **stops growing** rather than pushing the creature:
//!   the step is refused and tried again at the next one, so it grows again once it is clear;
//!   a new part that would appear inside something waits the same way, and with it the rest
//!   of that step's new parts, neurons and links. Two parts may overlap only where the
//!   builder lets them, in the contact region of a joint point they share (a joint between
//!   them, or an anchor both hang from: `creature::overlap_beyond_joints`), so a part may turn
//!   about its joint into its parent's corner but a new branch may not appear inside a
//!   sibling (where the contact solver would push the two apart every step: a motor).

use ::nalgebra::{Isometry3, Point3, Translation3, Vector3};
use rapier3d::math::{Pose, Real, Vector};
use rapier3d::parry::query::intersection_test;
use rapier3d::prelude::*;

use super::motion::Attach;
use super::parts::vector;
use super::slots::PartSlot;
use super::world::{World, na_pose, to_na};
use crate::creature::{JointKind, Part, PartId, boxes_intersect, overlap_beyond_joints};
use crate::develop::{Growth, GrowthEvent};

/// How deep (m) growth may reach into something it did not reach into before and still grow:
/// far above the contact solver's resting overlap, far below a part.
pub const GROWTH_CLEARANCE: f64 = 0.01;

/// What applying one step of growth did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Grown {
    /// Parts resized.
    pub resized: usize,
    /// Parts added (each with its joint).
    pub added: usize,
    /// Neurons added.
    pub neurons: usize,
    /// Links added.
    pub links: usize,
    /// Parts whose growth stopped this step (or new parts that wait), by id.
    pub stopped: Vec<PartId>,
    /// The energy growth brought this step (J).
    pub work: f64,
}

fn pose_of(isometry: &Isometry3<f64>) -> Pose {
    let q = isometry.rotation;
    Pose::from_parts(
        vector(&isometry.translation.vector),
        rapier3d::math::Rotation::from_xyzw(q.i as Real, q.j as Real, q.k as Real, q.w as Real)
            .normalize(),
    )
}

fn isometry_of(part: &Part) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(part.position), part.orientation)
}

impl World {
    /// The energy growth has brought so far (J): what the audit does not count as energy from
    /// nowhere.
    pub fn growth_work(&self) -> f64 {
        self.growth_work
    }

    /// The length of a control step (s).
    pub fn control_step(&self) -> f64 {
        self.options.control_step
    }

    /// The root part's anchor: the centre of its near face, where the turtle started it, a
    /// point its own growth does not move.
    pub fn root_anchor(&self) -> Vector3<f64> {
        self.near_face(PartId(0))
    }

    /// The centre of part `id`'s near face (its −x face, where the turtle started it) in the
    /// world now.
    fn near_face(&self, id: PartId) -> Vector3<f64> {
        let (centre, orientation) = self.part_pose(id);
        centre + orientation * Vector3::new(-self.part_size(id).x / 2.0, 0.0, 0.0)
    }

    /// The points where part `id` is jointed, in the world now, each with the part on the
    /// joint's other side: a joint's anchor as each of its parts holds it (they differ by how
    /// far the joint has come apart), a fused joint's at its child's near face.
    fn joint_points(&self, id: PartId) -> Vec<(Vector3<f64>, PartId)> {
        let mut points = Vec::new();
        for j in self.joint_ids() {
            let (parent, child) = self.joints[j].parts;
            let other = match (parent == id, child == id) {
                (true, _) => child,
                (_, true) => parent,
                _ => continue,
            };
            match self.joint_anchors(j) {
                Some((first, second)) => points.extend([(first, other), (second, other)]),
                None => points.push((self.near_face(child), other)),
            }
        }
        points
    }

    /// Whether a box of `size` at `pose` reaches deeper than [`GROWTH_CLEARANCE`] into the
    /// ground, or (when parts collide) into a part not in `exempt` other than where they meet
    /// at a joint, where a box of `old` size at `old_pose` (if any) did not. Where they meet at
    /// a joint is the builder's rule ([`overlap_beyond_joints`]): the box's joint `points`
    /// (each with the part on its other side) that the other part also holds — a joint between
    /// them, or an anchor both hang from — may have the contact region of two parts leaving
    /// it, [`GROWTH_CLEARANCE`] allowed for joints that have come apart. So a part may turn
    /// about its joint into its parent's corner, but a branch may not appear inside a sibling.
    fn reaches_in(
        &self,
        exempt: &[PartId],
        (pose, size): (Pose, Vector3<f64>),
        points: &[(Vector3<f64>, PartId)],
        old: Option<(Pose, Vector3<f64>)>,
    ) -> bool {
        let shrunk = |size: Vector3<f64>| {
            let half = (size / 2.0).map(|h| (h - GROWTH_CLEARANCE).max(1e-6));
            SharedShape::cuboid(half.x as Real, half.y as Real, half.z as Real)
        };
        let new_shape = shrunk(size);
        let old_shape = old.map(|(p, s)| (p, shrunk(s)));
        let hits = |at: &Pose, shape: &SharedShape, collider: ColliderHandle| {
            let other = &self.colliders[collider];
            intersection_test(at, shape.as_ref(), other.position(), other.shape())
                .map(|i| i.intersecting)
                .unwrap_or(false)
        };
        let blocks = |collider: ColliderHandle| {
            hits(&pose, &new_shape, collider)
                && !old_shape
                    .as_ref()
                    .is_some_and(|(p, s)| hits(p, s, collider))
        };
        if self.ground.colliders.iter().any(|&c| blocks(c)) {
            return true;
        }
        if !self.options.self_collision {
            return false;
        }
        let box_at = |pose: &Pose, size: Vector3<f64>| {
            let (position, orientation) = na_pose(pose);
            Part {
                size: size.map(|e| (e - 2.0 * GROWTH_CLEARANCE).max(2e-6)),
                position,
                orientation,
                density: 0.0,
                growing: false,
            }
        };
        let new = box_at(&pose, size);
        let old = old.map(|(p, s)| box_at(&p, s));
        self.part_ids().filter(|p| !exempt.contains(p)).any(|p| {
            // The other part where it is now (its collider may not be synchronised yet).
            let (position, orientation) = self.part_pose(p);
            let other = Part {
                size: self.parts[p].size,
                position,
                orientation,
                density: 0.0,
                growing: false,
            };
            let reach = (new.size.norm() + other.size.norm()) / 2.0;
            if (new.position - other.position).norm_squared() > reach * reach
                || !boxes_intersect(&new, &other)
            {
                return false;
            }
            let theirs = self.joint_points(p);
            let shared: Vec<Vector3<f64>> = points
                .iter()
                .filter(|(x, partner)| {
                    *partner == p
                        || theirs
                            .iter()
                            .any(|(y, _)| (x - y).norm() <= GROWTH_CLEARANCE)
                })
                .map(|(x, _)| *x)
                .collect();
            overlap_beyond_joints(&new, &other, &shared, GROWTH_CLEARANCE)
                && !old.as_ref().is_some_and(|old| {
                    overlap_beyond_joints(old, &other, &shared, GROWTH_CLEARANCE)
                })
        })
    }

    /// Gives part `id` the edge lengths `size` as the turtle grows a part: its near face (the
    /// −x face, where its joint to its parent sits) stays where it is, its length grows
    /// beyond it and its thickness and width about its axis. Its body's mass, centre of mass
    /// and inertia follow and the body keeps its velocity field; every joint anchor on it
    /// moves with the face it sits on; each part jointed beyond it (fused to it or not) is
    /// carried, with everything beyond, by its anchor's move, and moves with the part's
    /// velocity field where it is put. Returns false, changing nothing, when the grown part
    /// would reach into something (see the [module](self)).
    ///
    /// # Panics
    ///
    /// If `id` names no part of this world.
    pub fn grow_part(&mut self, id: PartId, size: Vector3<f64>) -> bool {
        let energy = self.mechanical_energy();
        let momenta = self.momenta();
        if !self.lengthen(id, size) {
            return false;
        }
        self.conserve_momenta(&momenta);
        self.body_changed();
        self.growth_work += self.energy - energy;
        true
    }

    /// [`World::grow_part`] but for giving the creature back its momenta and counting the
    /// energy, which [`World::apply_growth`] does once for a whole step.
    fn lengthen(&mut self, id: PartId, size: Vector3<f64>) -> bool {
        let PartSlot {
            body,
            collider,
            size: old,
            ..
        } = self.parts[id];
        if size == old {
            return true;
        }
        let in_body = self.colliders[collider]
            .position_wrt_parent()
            .copied()
            .unwrap_or(Pose::IDENTITY);
        let body_pose = *self.bodies[body].position();
        // A point p of the part (in its axes, about its old centre) goes to f(p).
        let s = Vector::new(
            (size.x / old.x) as Real,
            (size.y / old.y) as Real,
            (size.z / old.z) as Real,
        );
        let half_x = (old.x / 2.0) as Real;
        let f = move |p: Vector| Vector::new(s.x * (p.x + half_x) - half_x, s.y * p.y, s.z * p.z);
        let new_in_body = in_body * Pose::from_translation(f(Vector::ZERO));
        // Where each part jointed beyond this one goes: by its anchor's move.
        let mut moves: Vec<(PartId, Vector)> = Vec::new();
        for j in self.joint_ids() {
            let (parent, child) = self.joints[j].parts;
            if parent != id {
                continue;
            }
            // The anchor in this part's axes: the joint's frame, or, for a part fused to this
            // one, the child's near face (where the turtle started it).
            let anchor = match self.joint_data(j) {
                Some(data) => (in_body.inverse() * data.local_frame1).translation,
                None => {
                    let child_pose = self.part_world_pose(child);
                    let near = child_pose.transform_point(Vector::new(
                        -(self.parts[child].size.x / 2.0) as Real,
                        0.0,
                        0.0,
                    ));
                    (body_pose * in_body).inverse_transform_point(near)
                }
            };
            let by = (body_pose * in_body).rotation * (f(anchor) - anchor);
            for part in self.joints.beyond(child, id, |joint| joint.parts) {
                moves.push((part, by));
            }
        }

        // Neither the part nor what it carries may be put into something; what it carries
        // moves with it.
        let mut exempt: Vec<PartId> = moves.iter().map(|&(part, _)| part).collect();
        exempt.push(id);
        if self.reaches_in(
            &exempt,
            (body_pose * new_in_body, size),
            &self.joint_points(id),
            Some((body_pose * in_body, old)),
        ) {
            return false;
        }
        for &(part, by) in &moves {
            let at = self.part_world_pose(part);
            let size = self.parts[part].size;
            let points: Vec<(Vector3<f64>, PartId)> = self
                .joint_points(part)
                .into_iter()
                .map(|(x, other)| (x + to_na(by), other))
                .collect();
            if self.reaches_in(
                &exempt,
                (Pose::from_translation(by) * at, size),
                &points,
                Some((at, size)),
            ) {
                return false;
            }
        }
        let field = self.field_of(body);
        let omega = self.bodies[body].angvel();

        // The part itself: shape, place in its body, its joints' frames and torques.
        let half = size / 2.0;
        let c = &mut self.colliders[collider];
        c.set_shape(SharedShape::cuboid(
            half.x as Real,
            half.y as Real,
            half.z as Real,
        ));
        c.set_position_wrt_parent(new_in_body);
        self.parts[id].size = size;
        let scaled = |frame: Pose| {
            let mut local = in_body.inverse() * frame;
            local.translation = f(local.translation);
            in_body * local
        };
        for j in self.joint_ids() {
            let (parent, child) = self.joints[j].parts;
            if parent != id && child != id {
                continue;
            }
            let (first, second) = (self.parts[parent].size, self.parts[child].size);
            let slot = &mut self.joints[j];
            slot.max_torque =
                super::actuators::max_torque_between(&first, &second, slot.strength, &self.options);
            self.with_joint(j, |data| {
                if parent == id {
                    data.set_local_frame1(scaled(data.local_frame1));
                }
                if child == id {
                    data.set_local_frame2(scaled(data.local_frame2));
                }
            });
        }

        // What is carried: parts fused to this body slide in it, other bodies move whole.
        let body_rotation = body_pose.rotation;
        let mut bodies: Vec<(RigidBodyHandle, Vector)> = Vec::new();
        for &(part, by) in &moves {
            let (slot_body, slot_collider) = (self.parts[part].body, self.parts[part].collider);
            self.parts[part].previous += by;
            if slot_body == body {
                let local = body_rotation.inverse() * by;
                let c = &mut self.colliders[slot_collider];
                let at = c.position_wrt_parent().copied().unwrap_or(Pose::IDENTITY);
                c.set_position_wrt_parent(Pose::from_translation(local) * at);
                for j in self.joint_ids() {
                    let (p, q) = self.joints[j].parts;
                    let (b1, b2) = self.joints[j].ends;
                    let (first, second) = (p == part && b1 == body, q == part && b2 == body);
                    if first || second {
                        self.with_joint(j, |data| {
                            if first {
                                let frame = Pose::from_translation(local) * data.local_frame1;
                                data.set_local_frame1(frame);
                            }
                            if second {
                                let frame = Pose::from_translation(local) * data.local_frame2;
                                data.set_local_frame2(frame);
                            }
                        });
                    }
                }
            } else if !bodies.iter().any(|(b, _)| *b == slot_body) {
                bodies.push((slot_body, by));
            }
        }
        self.bodies[body].recompute_mass_properties_from_colliders(&self.colliders);
        self.move_with(body, &field);
        for (handle, by) in bodies {
            let b = &mut self.bodies[handle];
            let t = b.translation() + by;
            b.set_translation(t, true);
            let nudge = omega.cross(by);
            if nudge != Vector::ZERO {
                let v = b.linvel() + nudge;
                b.set_linvel(v, true);
            }
        }
        true
    }

    /// Applies one step of development's growth (see [`Growth`]): resized parts grow as
    /// [`World::grow_part`] grows them, new parts appear where the turtle puts them relative
    /// to their parent as it is now, moving with it, jointed to it; new neurons and links join
    /// the running brain, the neurons there were keeping their state. A part that stops
    /// growing keeps its size in `growth`'s creature, and a new part that waits is taken out
    /// of it with the rest of the step's new parts, neurons and links, so that the next step's
    /// growth tries them again.
    ///
    /// # Panics
    ///
    /// If `growth` names parts, joints or neurons this world does not have: it must be the
    /// growth from the creature this world holds.
    pub fn apply_growth(&mut self, growth: &mut Growth) -> Grown {
        let energy = self.mechanical_energy();
        let momenta = self.momenta();
        let mut grown = Grown::default();
        let parts = self.part_count();
        let counted = self.growth_work;
        let neurons = self.brain.neuron_count();
        let mut waiting = false;
        for event in &growth.events {
            match event {
                GrowthEvent::Resize { part, size } => {
                    if self.lengthen(*part, *size) {
                        grown.resized += 1;
                    } else {
                        grown.stopped.push(*part);
                    }
                }
                GrowthEvent::NewPart {
                    part,
                    shape,
                    parent,
                    spec,
                    ..
                } if !waiting => {
                    // From the new string's coordinates to the world's, by the parent.
                    let (at, turned) = self.part_pose(*parent);
                    let there = Isometry3::from_parts(Translation3::from(at), turned)
                        * isometry_of(&growth.creature.parts[parent.0]).inverse();
                    let placed = Part {
                        position: (there * Point3::from(shape.position)).coords,
                        orientation: there.rotation * shape.orientation,
                        ..shape.clone()
                    };
                    let anchor = (there * Point3::from(spec.anchor)).coords;
                    if self.reaches_in(
                        &[],
                        (pose_of(&isometry_of(&placed)), placed.size),
                        &[(anchor, *parent)],
                        None,
                    ) {
                        grown.stopped.push(*part);
                        waiting = true;
                        continue;
                    }
                    let attach = if spec.kind == JointKind::Rigid {
                        Attach::FusedTo(*parent)
                    } else {
                        Attach::MovingWith(*parent)
                    };
                    let id = self.add_part(&placed, attach);
                    debug_assert_eq!(id, *part);
                    let joint = crate::creature::Joint {
                        anchor,
                        axes: spec.axes.iter().map(|a| there.rotation * a).collect(),
                        ..spec.clone()
                    };
                    if self.add_joint(&joint).is_ok() {
                        grown.added += 1;
                    }
                }
                GrowthEvent::NewNeuron { spec, .. } if !waiting => {
                    self.add_neuron(spec);
                    grown.neurons += 1;
                }
                GrowthEvent::NewLink { link } if !waiting => {
                    self.add_link(link);
                    grown.links += 1;
                }
                _ => {}
            }
        }
        // What the world did not take, the creature does not have.
        for id in &grown.stopped {
            if let Some(part) = growth.creature.parts.get_mut(id.0)
                && id.0 < parts
            {
                part.size = self.parts[*id].size;
            }
        }
        if waiting {
            let pending = pending_links(growth);
            let creature = &mut growth.creature;
            creature.parts.truncate(self.part_count());
            creature.joints.truncate(self.joint_count());
            creature.brain.neurons.truncate(neurons);
            let links = creature.brain.links.len() - pending;
            creature.brain.links.truncate(links);
            growth.events.retain(|e| match e {
                GrowthEvent::Resize { .. } => true,
                GrowthEvent::NewPart { part, .. } => part.0 < self.part_count(),
                _ => false,
            });
        }
        self.conserve_momenta(&momenta);
        self.body_changed();
        grown.work = self.mechanical_energy() - energy;
        self.growth_work = counted + grown.work;
        grown
    }
}

/// The links `growth` adds.
fn pending_links(growth: &Growth) -> usize {
    growth
        .events
        .iter()
        .filter(|e| matches!(e, GrowthEvent::NewLink { .. }))
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::develop::creature_from_commands;
    use crate::sim::{Exploded, SimOptions};

    #[test]
    fn the_audit_still_catches_a_fake_source_after_honest_growth() {
        let sim = SimOptions {
            drop_height: 5.0,
            ..SimOptions::default()
        };
        let mut world = World::new(&creature_from_commands("forward(1)").unwrap(), &sim).unwrap();
        // The root lengthens by 2 cm a control step for 25 steps while it falls.
        for k in 1..=25 {
            let size = Vector3::new(1.0 + 0.02 * k as f64, 0.25, 0.25);
            assert!(world.grow_part(PartId(0), size));
            world.step(false).unwrap();
        }
        assert!(world.growth_work() > 0.0);

        // A fake source: 5 m/s more along x, given by no motor and no growth.
        let body = world.parts[PartId(0)].body;
        let v = world.bodies[body].linvel() + Vector::new(5.0, 0.0, 0.0);
        world.bodies[body].set_linvel(v, true);
        assert!(matches!(world.step(false), Err(Exploded::Energy(_))));
    }
}
