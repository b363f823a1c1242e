//! A growing body in a recording: the changes to the body that a sample records
//! ([`BodyChange`], a sample's `growth` in `recording.json`), how the protocol's recorder
//! finds them in the world after each step of growth ([`GrowthRecorder`]), and how a reader
//! rebuilds the body at each sample from the creature as dropped ([`GrowingBody`]).
//!
//! A sample lists every part's pose by id, so a part that appears during the walk lengthens
//! the sample's `parts`. The sample whose step added it (or, when the recording keeps one
//! step in several, the next sample kept) says what it is: its shape and its joint, placed
//! relative to its parent part (its centre and axes), since the parent's pose is the sample's.
//! A part that changed size says its new edge lengths; a part whose growth stopped because it
//! would have reached into something says so. A neuron or link added to the running brain is
//! recorded too, by its index there, with the sample whose step added it.

use nalgebra::{UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

use crate::creature::{Creature, Joint, Link, Neuron, Part, PartId};
use crate::sim::{Grown, World};

/// One change to a growing body, recorded with the first sample that shows it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum BodyChange {
    /// A new part, with the joint that holds it to its parent (`joint.parent`); its id is the
    /// next one (the number of parts there were).
    Appears {
        /// Its id.
        part: PartId,
        /// The part: its size, and its centre and orientation in its parent's axes (from the
        /// parent's centre).
        shape: Part,
        /// Its joint: `parent` and `child` by id, the anchor and axes in the parent's axes.
        joint: Joint,
    },
    /// A part's new edge lengths.
    Resized {
        /// The part.
        part: PartId,
        /// Its edge lengths (m).
        size: Vector3<f64>,
    },
    /// A part whose growth stopped, because it would have reached into the ground or another
    /// part (a new part that waits to appear for the same reason is named too).
    Stopped {
        /// The part.
        part: PartId,
    },
    /// A neuron added to the running brain; its index is the next one (the number of neurons
    /// there were). Its parts and joints are named by id.
    Neuron {
        /// Its index in the brain.
        neuron: usize,
        /// The neuron.
        spec: Neuron,
    },
    /// A link added to the running brain, between neurons named by their index there.
    Link {
        /// The link.
        link: Link,
    },
}

/// Finds what one step of growth changed in a world and keeps it until a sample is kept.
#[derive(Debug, Default)]
pub(super) struct GrowthRecorder {
    /// Every part's size as the last change recorded it.
    sizes: Vec<Vector3<f64>>,
    /// The changes since the last sample kept.
    changes: Vec<BodyChange>,
}

impl GrowthRecorder {
    /// Notes the world's parts before growth begins, if not noted yet.
    pub(super) fn begin(&mut self, world: &World) {
        if self.sizes.is_empty() {
            self.sizes = world.part_ids().map(|id| world.part_size(id)).collect();
        }
    }

    /// What a step of growth (`grown`) did to `world`, whose creature is now `creature` (the
    /// growing development's, its parts and joints at their ids).
    pub(super) fn after(&mut self, world: &World, creature: &Creature, grown: &Grown) {
        for id in world.part_ids() {
            let size = world.part_size(id);
            match self.sizes.get_mut(id.0) {
                Some(known) if *known != size => {
                    *known = size;
                    // The latest size of a part replaces one not yet kept.
                    self.changes
                        .retain(|c| !matches!(c, BodyChange::Resized { part, .. } if *part == id));
                    self.changes.push(BodyChange::Resized { part: id, size });
                }
                Some(_) => {}
                None => {
                    self.sizes.push(size);
                    if let Some(change) = appearance(creature, id, size) {
                        self.changes.push(change);
                    }
                }
            }
        }
        // The brain's new neurons and links are the last ones of the creature's, in the
        // order the running brain took them.
        let neurons = &creature.brain.neurons;
        let first = neurons.len().saturating_sub(grown.neurons);
        for (k, spec) in neurons.iter().enumerate().skip(first) {
            self.changes.push(BodyChange::Neuron {
                neuron: k,
                spec: spec.clone(),
            });
        }
        let links = &creature.brain.links;
        for link in &links[links.len().saturating_sub(grown.links)..] {
            self.changes.push(BodyChange::Link { link: link.clone() });
        }
        for &id in &grown.stopped {
            let stopped = BodyChange::Stopped { part: id };
            if !self.changes.contains(&stopped) {
                self.changes.push(stopped);
            }
        }
    }

    /// The changes since the last sample kept, for a sample; `kept` when that sample is kept
    /// (the changes then start again), not when it is only held back.
    pub(super) fn for_sample(&mut self, kept: bool) -> Vec<BodyChange> {
        if kept {
            std::mem::take(&mut self.changes)
        } else {
            self.changes.clone()
        }
    }
}

/// Part `id` of `creature`, of `size`, with its joint, placed in its parent's axes.
fn appearance(creature: &Creature, id: PartId, size: Vector3<f64>) -> Option<BodyChange> {
    let part = creature.parts.get(id.0)?;
    let joint = creature.joints.iter().rev().find(|j| j.child == id.0)?;
    let parent = creature.parts.get(joint.parent)?;
    let into = parent.orientation.inverse();
    Some(BodyChange::Appears {
        part: id,
        shape: Part {
            size,
            position: into * (part.position - parent.position),
            orientation: into * part.orientation,
            ..part.clone()
        },
        joint: Joint {
            anchor: into * (joint.anchor - parent.position),
            axes: joint.axes.iter().map(|a| into * a).collect(),
            ..joint.clone()
        },
    })
}

/// Why a recording's growth cannot be read: the sample (from 0) and what is wrong. Each sample
/// is given as its changes and the number of parts it poses.
pub fn check_growth<'s>(
    creature: &Creature,
    samples: impl IntoIterator<Item = (&'s [BodyChange], usize)>,
) -> Result<(), String> {
    let mut parts = creature.parts.len();
    let mut neurons = creature.brain.neurons.len();
    for (i, (growth, posed)) in samples.into_iter().enumerate() {
        for change in growth {
            let bad = match change {
                BodyChange::Appears { part, joint, .. } => {
                    if part.0 != parts {
                        Some(format!("{part} appears, but the next part is {parts}"))
                    } else if joint.child != parts || joint.parent >= parts {
                        Some(format!(
                            "{part} appears with a joint from part {} to part {}",
                            joint.parent, joint.child
                        ))
                    } else {
                        parts += 1;
                        None
                    }
                }
                // (A part stopped before it appears is a new part waiting to appear.)
                BodyChange::Resized { part, .. } if part.0 >= parts => {
                    Some(format!("{part} changes before it appears"))
                }
                BodyChange::Neuron { neuron, .. } if *neuron != neurons => Some(format!(
                    "neuron {neuron} is added, but the next neuron is {neurons}"
                )),
                BodyChange::Neuron { .. } => {
                    neurons += 1;
                    None
                }
                BodyChange::Link { link } if link.from >= neurons || link.to >= neurons => {
                    Some(format!(
                        "a link from neuron {} to neuron {} is added, but the brain has {neurons}",
                        link.from, link.to
                    ))
                }
                _ => None,
            };
            if let Some(bad) = bad {
                return Err(format!("frame {}: {bad}", i + 1));
            }
        }
        if posed > parts {
            return Err(format!(
                "frame {}: {posed} parts posed, but the body has {parts}",
                i + 1
            ));
        }
    }
    Ok(())
}

/// The body a recording shows at each sample: the creature as dropped, with the changes of
/// every sample up to it (a recording whose growth
/// [`Recording::check_growth`](super::Recording::check_growth) passed).
pub struct GrowingBody<'r> {
    first: &'r Creature,
    /// Each sample's changes.
    growth: Vec<&'r [BodyChange]>,
    body: Creature,
    /// The samples whose changes `body` holds.
    applied: usize,
}

impl<'r> GrowingBody<'r> {
    /// The body of `creature` (as dropped), grown as each sample's changes (`growth`) say.
    pub fn new(creature: &'r Creature, growth: Vec<&'r [BodyChange]>) -> GrowingBody<'r> {
        GrowingBody {
            first: creature,
            growth,
            body: creature.clone(),
            applied: 0,
        }
    }

    /// The body at sample `i`: its parts at their ids, placed in the creature's first axes
    /// (pose it with the sample). Fastest when asked in time order.
    pub fn at(&mut self, i: usize) -> &Creature {
        if i < self.applied.saturating_sub(1) {
            self.body = self.first.clone();
            self.applied = 0;
        }
        while self.applied <= i && self.applied < self.growth.len() {
            for change in self.growth[self.applied] {
                apply(&mut self.body, change);
            }
            self.applied += 1;
        }
        &self.body
    }
}

/// Applies `change` to `body`: a new part placed by its parent, a part resized (the anchors of
/// the joints it holds kept at the same place on its faces), a stop changing nothing, a new
/// neuron or link added to its brain.
fn apply(body: &mut Creature, change: &BodyChange) {
    match change {
        BodyChange::Appears { part, shape, joint } => {
            let Some(parent) = body.parts.get(joint.parent) else {
                return;
            };
            if part.0 != body.parts.len() {
                return;
            }
            let (at, turned) = (parent.position, parent.orientation);
            body.parts.push(Part {
                position: at + turned * shape.position,
                orientation: turned * shape.orientation,
                ..shape.clone()
            });
            body.joints.push(Joint {
                anchor: at + turned * joint.anchor,
                axes: joint.axes.iter().map(|a| turned * a).collect(),
                ..joint.clone()
            });
        }
        BodyChange::Resized { part, size } => {
            let Some(p) = body.parts.get_mut(part.0) else {
                return;
            };
            let scale = size.component_div(&p.size.map(|s| s.max(1e-12)));
            p.size = *size;
            let (at, turned): (Vector3<f64>, UnitQuaternion<f64>) = (p.position, p.orientation);
            for joint in body.joints.iter_mut().filter(|j| j.parent == part.0) {
                let local = turned.inverse() * (joint.anchor - at);
                joint.anchor = at + turned * local.component_mul(&scale);
            }
        }
        BodyChange::Stopped { .. } => {}
        BodyChange::Neuron { neuron, spec } => {
            if *neuron == body.brain.neurons.len() {
                body.brain.neurons.push(spec.clone());
            }
        }
        BodyChange::Link { link } => body.brain.links.push(link.clone()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::develop::creature_from_commands;

    /// The samples of a growth from a one-part body, as the checks see them (each sample's
    /// changes and how many parts it poses): a first sample of the one part unchanged, then one
    /// sample per change, posing the given number of parts.
    fn from_one_part(changes: Vec<(usize, BodyChange)>) -> Vec<(Vec<BodyChange>, usize)> {
        let mut samples = vec![(vec![], 1)];
        samples.extend(changes.into_iter().map(|(parts, c)| (vec![c], parts)));
        samples
    }

    fn views(samples: &[(Vec<BodyChange>, usize)]) -> Vec<(&[BodyChange], usize)> {
        samples.iter().map(|(g, n)| (g.as_slice(), *n)).collect()
    }

    #[test]
    fn a_body_grows_a_part_placed_by_its_parent_and_moves_the_anchors_of_a_resized_part() {
        // One 1 m part, its centre at x = 0.5, turned a quarter turn about y.
        let mut creature = creature_from_commands("forward(1)").unwrap();
        let quarter =
            UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2);
        creature.parts[0].orientation = quarter;
        let size = creature.parts[0].size;
        let shape = Part {
            size: Vector3::new(0.5, 0.1, 0.1),
            position: Vector3::new(0.75, 0.0, 0.0),
            orientation: UnitQuaternion::identity(),
            density: 1000.0,
            growing: false,
        };
        let joint = Joint {
            parent: 0,
            child: 1,
            kind: crate::creature::JointKind::Rigid,
            anchor: Vector3::new(0.5, 0.0, 0.0),
            axes: vec![Vector3::z()],
            limits: vec![(-1.0, 1.0)],
            strength: 1.0,
            growing: false,
        };
        let samples = from_one_part(vec![
            (
                2,
                BodyChange::Appears {
                    part: PartId(1),
                    shape,
                    joint,
                },
            ),
            (
                2,
                BodyChange::Resized {
                    part: PartId(0),
                    size: Vector3::new(2.0, size.y, size.z),
                },
            ),
        ]);
        assert_eq!(check_growth(&creature, views(&samples)), Ok(()));
        let mut body = GrowingBody::new(
            &creature,
            views(&samples).into_iter().map(|v| v.0).collect(),
        );
        assert_eq!(body.at(0).parts.len(), 1);
        let grown = body.at(1).clone();
        assert_eq!(grown.parts.len(), 2);
        // 0.75 m along the parent's x, which points along the world's −z.
        let at = grown.parts[1].position - grown.parts[0].position;
        assert!((at - Vector3::new(0.0, 0.0, -0.75)).norm() < 1e-12, "{at}");
        assert!((grown.joints[0].axes[0] - Vector3::x()).norm() < 1e-12);
        // The parent doubles in length: the anchor at its far face is 1 m from its centre.
        let resized = body.at(2);
        assert_eq!(resized.parts[0].size.x, 2.0);
        let anchor = resized.joints[0].anchor - resized.parts[0].position;
        assert!(
            (anchor - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-12,
            "{anchor}"
        );
        // Asked again from the start, it starts again.
        assert_eq!(body.at(0).parts.len(), 1);
    }

    #[test]
    fn a_recorded_neuron_and_link_read_back_and_join_the_body_s_brain() {
        let creature = creature_from_commands("forward(1)").unwrap();
        let n = creature.brain.neurons.len();
        let spec = creature.brain.neurons[0].clone();
        let link = Link {
            from: 0,
            to: n,
            weight: 0.5,
        };
        let changes = vec![
            BodyChange::Neuron {
                neuron: n,
                spec: spec.clone(),
            },
            BodyChange::Link { link: link.clone() },
        ];
        let text = serde_json::to_string(&changes).unwrap();
        assert!(text.contains(r#"{"link":{"from":0,"to":"#), "{text}");
        let read: Vec<BodyChange> = serde_json::from_str(&text).unwrap();
        assert_eq!(read, changes);
        let samples = vec![(vec![], 1), (changes, 1)];
        assert_eq!(check_growth(&creature, views(&samples)), Ok(()));
        let mut body = GrowingBody::new(
            &creature,
            views(&samples).into_iter().map(|v| v.0).collect(),
        );
        let grown = body.at(1);
        assert_eq!(grown.brain.neurons.len(), n + 1);
        assert_eq!(grown.brain.neurons[n], spec);
        assert_eq!(grown.brain.links.last(), Some(&link));
        // A neuron out of turn, and a link to a neuron there is not, are refused.
        let skipped = vec![(
            vec![BodyChange::Neuron {
                neuron: n + 1,
                spec,
            }],
            1,
        )];
        assert_eq!(
            check_growth(&creature, views(&skipped)),
            Err(format!(
                "frame 1: neuron {} is added, but the next neuron is {n}",
                n + 1
            ))
        );
        let dangling = vec![(vec![BodyChange::Link { link }], 1)];
        assert_eq!(
            check_growth(&creature, views(&dangling)),
            Err(format!(
                "frame 1: a link from neuron 0 to neuron {n} is added, but the brain has {n}"
            ))
        );
    }

    #[test]
    fn growth_that_names_a_part_out_of_turn_is_refused_with_its_frame() {
        let creature = creature_from_commands("forward(1)").unwrap();
        let samples = from_one_part(vec![(
            1,
            BodyChange::Resized {
                part: PartId(3),
                size: Vector3::repeat(1.0),
            },
        )]);
        assert_eq!(
            check_growth(&creature, views(&samples)),
            Err("frame 2: part 3 changes before it appears".to_string())
        );
        let waiting = from_one_part(vec![(1, BodyChange::Stopped { part: PartId(1) })]);
        assert_eq!(check_growth(&creature, views(&waiting)), Ok(()));
        let posed_more = vec![(vec![], 2)];
        assert_eq!(
            check_growth(&creature, views(&posed_more)),
            Err("frame 1: 2 parts posed, but the body has 1".to_string())
        );
    }
}
