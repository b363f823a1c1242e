//! Growth between two moments of development: what changed from the creature at
//! developmental time t to the one the string at t + Δt builds, as a list of
//! [`GrowthEvent`]s that name parts, joints and neurons by their stable ids.
//!
//! The builder numbers parts in the order the string makes them, so a bud that matures in the
//! middle of the string shifts the numbers of every part after it. Identity is therefore not
//! the builder's number but the body's tree, matched from the root outwards:
//!
//! - the root (the first part the string builds) is the root;
//! - a child of a matched part is the unmatched child of its match, jointed by the same kind of
//!   joint, attached at the same place and turned the same way: the joint's anchor in the
//!   parent's axes as a fraction of the parent's half-size (so a point on a face stays on it
//!   however the parent grows) and the child's orientation relative to the parent's, both
//!   within [`ATTACHMENT_TOLERANCE`]. Among several such, the first in the string's order.
//!
//! A part of the new string that matches none is new: it gets the next free id, after every
//! part there was, in the string's order (a parent before its children), with its joint to
//! its parent. A part there was that matches none is **kept** ([`Growth::lost`] names it):
//! growth adds and lengthens, it does not remove. A matched part whose edge lengths differ is
//! resized.
//!
//! Neurons are matched by what they are — their function, their role (the sensor or actuator,
//! its part or joint through the ids above), the part they belong to — and, among several
//! alike, by their order; a neuron of the new string that matches none is new and gets the
//! next index. A link is new when the new string has more links between two matched (or new)
//! neurons than there were. A neuron keeps the parameters and a link the weight it had when it
//! appeared.

use nalgebra::{UnitQuaternion, Vector3};

use super::{BuildOptions, build};
use crate::creature::{
    Actuator, Creature, Joint, JointId, Link, Neuron, Part, PartId, Role, Sensor,
};
use crate::environment::Environment;
use crate::lang::Diagnostic;
use crate::lsystem::{DeriveOptions, LSystem, ModuleString};

/// How far two attachments may differ and be the same: in fractions of the parent's
/// half-size for the anchor, in radians for the orientation. Far above the round-off of
/// rebuilding a string, far below any distinct place on a part.
pub const ATTACHMENT_TOLERANCE: f64 = 1e-6;

/// One change to a growing creature.
#[derive(Clone, Debug, PartialEq)]
pub enum GrowthEvent {
    /// Part `part` has new edge lengths.
    Resize {
        /// The part.
        part: PartId,
        /// Its new edge lengths.
        size: Vector3<f64>,
    },
    /// A new part, jointed to a part that exists (or that an earlier event added).
    NewPart {
        /// Its id: the next free one.
        part: PartId,
        /// The part, placed where the turtle puts it in the new string's creature.
        shape: Part,
        /// The part it is jointed to.
        parent: PartId,
        /// Its joint's id: the next free one.
        joint: JointId,
        /// The joint, its `parent` and `child` as ids, its anchor and axes where the turtle
        /// puts them in the new string's creature.
        spec: Joint,
    },
    /// A new neuron, its parts and joints named by id; it gets the next index.
    NewNeuron {
        /// Its index in the running brain.
        neuron: usize,
        /// The neuron.
        spec: Neuron,
    },
    /// A new link between neurons named by their index in the running brain.
    NewLink {
        /// The link.
        link: Link,
    },
}

/// What changed between two moments of development.
#[derive(Clone, Debug, PartialEq)]
pub struct Growth {
    /// The changes, in this order: resized parts (by id), new parts with their joints (parents
    /// first), new neurons, new links.
    pub events: Vec<GrowthEvent>,
    /// The creature after growth with parts, joints and neurons at their ids: the parts there
    /// were (their sizes and poses as the new string builds them, a part the string no longer
    /// builds as it was), then the new ones. Its problems are the new string's.
    pub creature: Creature,
    /// Parts there were that the new string no longer builds (kept as they were).
    pub lost: Vec<PartId>,
}

impl Growth {
    /// Whether nothing changed.
    pub fn is_empty(&self) -> bool {
        self.events.is_empty()
    }
}

/// What changed from `before` (the creature at time t, its parts, joints and neurons at their
/// ids: a creature as built, or the [`Growth::creature`] of the last step) to the creature
/// `lsys`'s `string` builds at time `t` (t + Δt) in the environment `env`: the string through
/// the interpretation rules, built with `options` (their turtle settings `lsys`'s).
pub fn growth_from_string(
    before: &Creature,
    lsys: &LSystem,
    string: &ModuleString,
    env: &Environment,
    t: f64,
    derive: &DeriveOptions,
    options: &BuildOptions,
) -> Result<Growth, Diagnostic> {
    let shown = lsys.interpret(string, t, derive)?;
    let after = build(&shown, lsys.symbols(), env, Some(t), options);
    Ok(growth_between(before, &after, options.max_parts))
}

/// For each part of `creature`, the joint that holds it to its parent, if any.
fn parent_joints(creature: &Creature) -> Vec<Option<usize>> {
    let mut of = vec![None; creature.parts.len()];
    for (j, joint) in creature.joints.iter().enumerate() {
        if let Some(slot) = of.get_mut(joint.child)
            && slot.is_none()
        {
            *slot = Some(j);
        }
    }
    of
}

/// Where `joint` holds its child on its parent, and how the child is turned: the anchor in the
/// parent's axes over its half-size, and the child's orientation in the parent's axes.
fn attachment(creature: &Creature, joint: &Joint) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let parent = &creature.parts[joint.parent];
    let child = &creature.parts[joint.child];
    let local = parent.orientation.inverse() * (joint.anchor - parent.position);
    let half = parent.size / 2.0;
    (
        local.component_div(&half),
        parent.orientation.inverse() * child.orientation,
    )
}

/// What a neuron is, its parts and joints named through `part_id` and `joint_id`.
fn identity(
    neuron: &Neuron,
    part_id: &dyn Fn(usize) -> usize,
    joint_id: &dyn Fn(usize) -> usize,
) -> Neuron {
    let role = match neuron.role {
        Role::Hidden => Role::Hidden,
        Role::Sensor { sensor } => Role::Sensor {
            sensor: match sensor {
                Sensor::Touch { part, face } => Sensor::Touch {
                    part: part_id(part),
                    face,
                },
                Sensor::Angle { joint, dof } => Sensor::Angle {
                    joint: joint_id(joint),
                    dof,
                },
                other => other,
            },
        },
        Role::Actuator { actuator } => Role::Actuator {
            actuator: match actuator {
                Actuator::Joint { joint, dof } => Actuator::Joint {
                    joint: joint_id(joint),
                    dof,
                },
                other => other,
            },
        },
    };
    Neuron {
        role,
        part: neuron.part.map(part_id),
        ..neuron.clone()
    }
}

/// Whether two neurons are the same neuron (their parameters, bias aside).
fn same_neuron(a: &Neuron, b: &Neuron) -> bool {
    a.function == b.function && a.role == b.role && a.part == b.part
}

/// What changed from `before` (parts, joints and neurons at their ids) to `after` (as the
/// builder numbers them), the creature kept to `max_parts` parts (or the parts `before` has,
/// if more); see the [module](self) for how parts and neurons are matched.
///
/// A `before` with no parts is no creature yet: `after` is where growth starts, with no events.
pub fn growth_between(before: &Creature, after: &Creature, max_parts: usize) -> Growth {
    if before.parts.is_empty() {
        return Growth {
            events: Vec::new(),
            creature: after.clone(),
            lost: Vec::new(),
        };
    }
    let before_joint = parent_joints(before);
    let after_joint = parent_joints(after);

    // Parts: from the root outwards. The builder makes a parent before its children, so one
    // pass in the new string's order sees every parent matched (or new) before its children.
    let mut id_of: Vec<Option<usize>> = vec![None; after.parts.len()];
    let mut taken = vec![false; before.parts.len()];
    for k in 0..after.parts.len() {
        let candidate = match after_joint[k] {
            None => (k == 0).then_some(0),
            Some(j) => {
                let joint = &after.joints[j];
                id_of[joint.parent].and_then(|parent| {
                    let (anchor, turn) = attachment(after, joint);
                    (0..before.parts.len()).find(|&b| {
                        !taken[b]
                            && before_joint[b].is_some_and(|bj| {
                                let old = &before.joints[bj];
                                old.parent == parent && old.kind == joint.kind && {
                                    let (a, q) = attachment(before, old);
                                    (a - anchor).amax() <= ATTACHMENT_TOLERANCE
                                        && q.angle_to(&turn) <= ATTACHMENT_TOLERANCE
                                }
                            })
                    })
                })
            }
        };
        if let Some(b) = candidate {
            taken[b] = true;
            id_of[k] = Some(b);
        }
    }

    let mut creature = before.clone();
    creature.problems = after.problems.clone();
    creature.environment = after.environment.clone();
    let mut events = Vec::new();
    // Resized parts, by id; every matched part takes its new pose.
    let mut matched: Vec<(usize, usize)> = id_of
        .iter()
        .enumerate()
        .filter_map(|(k, id)| id.map(|b| (b, k)))
        .collect();
    matched.sort_unstable();
    for &(b, k) in &matched {
        let new = &after.parts[k];
        if new.size != before.parts[b].size {
            events.push(GrowthEvent::Resize {
                part: PartId(b),
                size: new.size,
            });
        }
        creature.parts[b] = new.clone();
        if let (Some(bj), Some(aj)) = (before_joint[b], after_joint[k]) {
            let joint = &mut creature.joints[bj];
            joint.anchor = after.joints[aj].anchor;
            joint.axes = after.joints[aj].axes.clone();
        }
    }
    // New parts with their joints, in the string's order.
    let mut joint_id_of: Vec<Option<usize>> = vec![None; after.joints.len()];
    for (k, aj) in after_joint.iter().enumerate() {
        if let (Some(b), Some(aj)) = (id_of[k], aj) {
            joint_id_of[*aj] = before_joint[b];
        }
    }
    for k in 0..after.parts.len() {
        if id_of[k].is_some() {
            continue;
        }
        // A part with no joint is the start of another piece: a body in pieces is an error of
        // the new string's creature, and there is nothing to attach it to.
        let Some(aj) = after_joint[k] else { continue };
        let Some(parent) = id_of[after.joints[aj].parent] else {
            continue;
        };
        let part = creature.parts.len();
        if part >= max_parts {
            continue;
        }
        let joint = creature.joints.len();
        id_of[k] = Some(part);
        joint_id_of[aj] = Some(joint);
        let spec = Joint {
            parent,
            child: part,
            ..after.joints[aj].clone()
        };
        creature.parts.push(after.parts[k].clone());
        creature.joints.push(spec.clone());
        events.push(GrowthEvent::NewPart {
            part: PartId(part),
            shape: after.parts[k].clone(),
            parent: PartId(parent),
            joint: JointId(joint),
            spec,
        });
    }
    let lost = (0..before.parts.len())
        .filter(|&b| !taken[b])
        .map(PartId)
        .collect();

    // Neurons: what each is, through the ids; the k-th of a kind matches the k-th.
    let part_id = |k: usize| id_of.get(k).copied().flatten().unwrap_or(usize::MAX);
    let joint_id = |j: usize| joint_id_of.get(j).copied().flatten().unwrap_or(usize::MAX);
    let mut neuron_of: Vec<Option<usize>> = vec![None; after.brain.neurons.len()];
    let mut neuron_taken = vec![false; before.brain.neurons.len()];
    for (n, neuron) in after.brain.neurons.iter().enumerate() {
        let mapped = identity(neuron, &part_id, &joint_id);
        if let Some(b) = (0..before.brain.neurons.len())
            .find(|&b| !neuron_taken[b] && same_neuron(&before.brain.neurons[b], &mapped))
        {
            neuron_taken[b] = true;
            neuron_of[n] = Some(b);
        }
    }
    for (n, neuron) in after.brain.neurons.iter().enumerate() {
        if neuron_of[n].is_some() {
            continue;
        }
        let mapped = identity(neuron, &part_id, &joint_id);
        // A neuron naming a part or joint the creature does not have is left out.
        if mapped.part == Some(usize::MAX) || mentions_missing(&mapped) {
            continue;
        }
        let index = creature.brain.neurons.len();
        neuron_of[n] = Some(index);
        creature.brain.neurons.push(mapped.clone());
        events.push(GrowthEvent::NewNeuron {
            neuron: index,
            spec: mapped,
        });
    }
    // Links: as many between two neurons as the new string has.
    let mut counted: std::collections::HashMap<(usize, usize), usize> = Default::default();
    for link in &creature.brain.links {
        *counted.entry((link.from, link.to)).or_default() += 1;
    }
    for link in &after.brain.links {
        let (Some(from), Some(to)) = (neuron_of[link.from], neuron_of[link.to]) else {
            continue;
        };
        match counted.get_mut(&(from, to)) {
            Some(left) if *left > 0 => *left -= 1,
            _ => {
                let link = Link {
                    from,
                    to,
                    weight: link.weight,
                };
                creature.brain.links.push(link.clone());
                events.push(GrowthEvent::NewLink { link });
            }
        }
    }
    Growth {
        events,
        creature,
        lost,
    }
}

/// Whether `neuron` senses or drives a part or joint that is not there (named `usize::MAX`).
fn mentions_missing(neuron: &Neuron) -> bool {
    match neuron.role {
        Role::Sensor {
            sensor: Sensor::Touch { part, .. },
        } => part == usize::MAX,
        Role::Sensor {
            sensor: Sensor::Angle { joint, .. },
        }
        | Role::Actuator {
            actuator: Actuator::Joint { joint, .. },
        } => joint == usize::MAX,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    /// The creature `lsys` builds at developmental time `t`.
    fn grown(lsys: &Arc<LSystem>, t: f64) -> Creature {
        growth(lsys, &Creature::default(), t).creature
    }

    /// The growth of `lsys` from `before` (the creature at an earlier time, at its ids) to
    /// developmental time `t`.
    fn growth(lsys: &Arc<LSystem>, before: &Creature, t: f64) -> Growth {
        let derive = DeriveOptions::default();
        let mut development =
            crate::lsystem::Development::start(Arc::clone(lsys), &derive).unwrap();
        development.advance_by(t).unwrap();
        let options = BuildOptions::default().with_headers(lsys);
        let env = development.environment();
        growth_from_string(
            before,
            lsys,
            development.current(),
            env,
            t,
            &derive,
            &options,
        )
        .unwrap()
    }

    fn lsystem(text: &str) -> Arc<LSystem> {
        Arc::new(LSystem::from_text("growth.lsys", text).unwrap())
    }

    #[test]
    fn a_limb_lengthening_gives_only_resize_events_with_the_lengths_it_reached() {
        // A root and a limb that both lengthen at 0.5 m per unit of time.
        let lsys = lsystem(
            "time: 2\n\
             axiom: G(1) revolute1 G(0.5)\n\
             G(x) --> solve dx/dt = 0.5\n\
             interpretation:\n\
             G(x) --> forward(x)\n",
        );
        let before = grown(&lsys, 0.0);
        assert_eq!(before.parts.len(), 2);
        let growth = growth(&lsys, &before, 0.4);
        let sizes: Vec<(PartId, f64)> = growth
            .events
            .iter()
            .map(|e| match e {
                GrowthEvent::Resize { part, size } => (*part, size.x),
                other => panic!("only resizes, not {other:?}"),
            })
            .collect();
        assert_eq!(sizes.len(), 2);
        assert_eq!(sizes[0].0, PartId(0));
        assert_eq!(sizes[1].0, PartId(1));
        assert!((sizes[0].1 - 1.2).abs() < 1e-9, "{}", sizes[0].1);
        assert!((sizes[1].1 - 0.7).abs() < 1e-9, "{}", sizes[1].1);
        assert!(growth.lost.is_empty());
        // The limb's joint now sits at the root's far end, 1.2 m from its start.
        assert!((growth.creature.joints[0].anchor.x - 1.2).abs() < 1e-9);
    }

    /// A root with a bud in the middle of the string that matures at t = 1 into a limb
    /// (jointed by a hinge, turned left), between two limbs that exist from the start.
    const BUD: &str = "time: 2\n\
         axiom: forward(1) [ revolute1 forward(0.5) ] [ left revolute1 B(0) ] [ right revolute1 forward(0.5) ]\n\
         B(x) : x < 1 --> solve dx/dt = 1\n\
         B(x) : x >= 1 --> mforward(0.25) touch\n";

    #[test]
    fn a_bud_maturing_in_the_middle_of_the_string_is_one_new_part_and_joint_on_its_parent() {
        let lsys = lsystem(BUD);
        let before = grown(&lsys, 0.5);
        assert_eq!(before.parts.len(), 3);
        let growth = growth(&lsys, &before, 1.5);
        // The builder numbers the new limb 2, between the two others; its id is the next, 3.
        let new: Vec<_> = growth
            .events
            .iter()
            .filter(|e| matches!(e, GrowthEvent::NewPart { .. }))
            .collect();
        assert_eq!(new.len(), 1, "{:?}", growth.events);
        let GrowthEvent::NewPart {
            part,
            shape,
            parent,
            joint,
            spec,
        } = new[0]
        else {
            unreachable!()
        };
        assert_eq!((*part, *parent, *joint), (PartId(3), PartId(0), JointId(2)));
        assert_eq!((spec.parent, spec.child), (0, 3));
        assert_eq!(spec.kind, crate::creature::JointKind::Revolute);
        assert_eq!(shape.size, Vector3::new(0.25, 0.25, 0.25));
        // Placed where the turtle puts it: from the root's far end, heading left (−z).
        assert!((spec.anchor - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-9);
        assert!((shape.position - Vector3::new(1.0, 0.0, -0.125)).norm() < 1e-9);
        // No other part changed; the limbs there were keep their ids.
        assert!(
            growth
                .events
                .iter()
                .all(|e| !matches!(e, GrowthEvent::Resize { .. }))
        );
        assert_eq!(growth.creature.parts.len(), 4);
        assert_eq!(growth.creature.parts[1], before.parts[1]);
        assert_eq!(growth.creature.parts[2], before.parts[2]);
        assert!(growth.lost.is_empty());
        // The touch sensor on the new part is one new neuron naming part 3.
        let neurons: Vec<_> = growth
            .events
            .iter()
            .filter_map(|e| match e {
                GrowthEvent::NewNeuron { neuron, spec } => Some((*neuron, spec.role)),
                _ => None,
            })
            .collect();
        assert_eq!(
            neurons,
            [(
                before.brain.neurons.len(),
                Role::Sensor {
                    sensor: Sensor::Touch {
                        part: 3,
                        face: None
                    }
                }
            )]
        );
    }

    #[test]
    fn a_creature_at_its_most_parts_grows_no_new_part_nor_its_sensor() {
        let lsys = lsystem(BUD);
        let before = grown(&lsys, 0.5);
        let full = before.parts.len();
        let after = grown(&lsys, 1.5);
        assert_eq!(after.parts.len(), full + 1);
        // At most 3 parts: the bud matures in the string but adds nothing to the creature.
        let growth = growth_between(&before, &after, full);
        assert!(growth.events.is_empty(), "{:?}", growth.events);
        assert_eq!(growth.creature.parts.len(), full);
        assert_eq!(growth.creature.joints.len(), before.joints.len());
        assert_eq!(growth.creature.brain, before.brain);
        // One more allowed: the part, its touch sensor and the sensor's link arrive.
        let growth = growth_between(&before, &after, full + 1);
        assert_eq!(growth.events.len(), 3, "{:?}", growth.events);
        assert_eq!(growth.creature.parts.len(), full + 1);
    }

    #[test]
    fn nothing_changing_gives_no_events() {
        let lsys = lsystem(BUD);
        let before = grown(&lsys, 0.25);
        let growth = growth(&lsys, &before, 0.75);
        assert!(growth.is_empty(), "{:?}", growth.events);
        assert_eq!(growth.creature.parts, before.parts);
        assert_eq!(growth.creature.brain, before.brain);
    }

    #[test]
    fn growth_after_growth_keeps_the_ids_the_first_gave() {
        let lsys = lsystem(BUD);
        let first = growth(&lsys, &grown(&lsys, 0.5), 1.5);
        let again = growth(&lsys, &first.creature, 2.0);
        assert!(again.is_empty(), "{:?}", again.events);
        assert_eq!(again.creature.parts.len(), 4);
    }
}
