//! How regular a body is: three measures of a [`Creature`]'s body that separate regular bodies
//! (repeated limbs, mirror symmetry) from irregular ones, pure functions of its parts and
//! joints (the brain is left out).
//!
//! - [`Regularity::repeated`]: the share of parts whose sub-assembly — the part with its
//!   joints and its children, up to scale — has a twin elsewhere in the body. Higher is more
//!   regular.
//! - [`Regularity::symmetry`]: the share of parts with a mirror partner across the best of the
//!   root's three planes. Higher is more regular.
//! - [`Regularity::description_bytes`]: the size, in bytes per part, of the body's canonical
//!   description compressed with deflate. Lower is more regular.
//!
//! Positions and directions are compared in the frame of the part they hang from, so a body
//! turned or moved as a whole scores the same.

use std::collections::HashMap;
use std::fmt::Write as _;

use nalgebra::{UnitQuaternion, Vector3};

use super::{Creature, Part};

/// Lengths in a sub-assembly or a description are divided by a reference length (the
/// sub-assembly's or the body's root's longest edge) and rounded to this step: two values
/// closer than half of it almost always agree (a pair on either side of a rounding boundary
/// does not).
pub const LENGTH_STEP: f64 = 0.01;

/// Two parts are mirror partners when the reflected centre of one lies within this share of
/// the root's longest edge of the other's centre, and their edges match within it too.
pub const MIRROR_TOLERANCE: f64 = 0.02;

/// Reflected axes match when the absolute cosine of their angle is at least this (about 2.6°).
pub const MIRROR_AXIS_COSINE: f64 = 0.999;

/// The three measures: the share of parts in repeated sub-assemblies, the share with a mirror
/// partner, the compressed description's bytes per part. An empty body scores NaN on each.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Regularity {
    /// The share of parts in a repeated sub-assembly, 0 to 1; higher is more regular.
    pub repeated: f64,
    /// The share of parts with a mirror partner across the best plane of the root, 0 to 1
    /// (the root is its own partner, so at least 1/parts); higher is more regular.
    pub symmetry: f64,
    /// The deflate-compressed canonical description's bytes per part; lower is more
    /// regular.
    pub description_bytes: f64,
}

/// The three measures of `creature`'s body.
pub fn regularity(creature: &Creature) -> Regularity {
    if creature.parts.is_empty() {
        return Regularity {
            repeated: f64::NAN,
            symmetry: f64::NAN,
            description_bytes: f64::NAN,
        };
    }
    Regularity {
        repeated: repeated_share(creature),
        symmetry: symmetry_share(creature),
        description_bytes: description_bytes(creature),
    }
}

/// The longest edge of a part (1 for a degenerate part, so that nothing divides by zero).
fn longest(part: &Part) -> f64 {
    let l = part.size.x.max(part.size.y).max(part.size.z);
    if l > 0.0 && l.is_finite() { l } else { 1.0 }
}

/// `v` rounded to [`LENGTH_STEP`], as text, never "-0.00".
fn round(v: f64) -> String {
    let r = (v / LENGTH_STEP).round() * LENGTH_STEP + 0.0;
    format!("{r:.2}")
}

fn vector(out: &mut String, v: &Vector3<f64>) {
    let _ = write!(out, "{} {} {}", round(v.x), round(v.y), round(v.z));
}

/// The children of each part: (joint index, child index) for every joint it is the parent of.
fn children(creature: &Creature) -> Vec<Vec<(usize, usize)>> {
    let mut out = vec![Vec::new(); creature.parts.len()];
    for (j, joint) in creature.joints.iter().enumerate() {
        if joint.parent < out.len() && joint.child < out.len() {
            out[joint.parent].push((j, joint.child));
        }
    }
    out
}

/// How child `c` hangs from its parent `p` by joint `j`, in `p`'s frame, lengths divided by
/// `scale`: the joint's kind, anchor and axes, the child's centre, its rotation from the
/// parent's axes (as the rotation matrix, which has one form per rotation) and its edges.
fn attachment(creature: &Creature, p: usize, j: usize, c: usize, scale: f64) -> String {
    let (parent, child, joint) = (&creature.parts[p], &creature.parts[c], &creature.joints[j]);
    let inverse: UnitQuaternion<f64> = parent.orientation.inverse();
    let mut s = format!("{:?} a ", joint.kind);
    vector(
        &mut s,
        &(inverse * (joint.anchor - parent.position) / scale),
    );
    for axis in &joint.axes {
        s.push_str(" x ");
        vector(&mut s, &(inverse * axis));
    }
    s.push_str(" c ");
    vector(
        &mut s,
        &(inverse * (child.position - parent.position) / scale),
    );
    let rotation = (inverse * child.orientation).to_rotation_matrix();
    for column in rotation.matrix().column_iter() {
        s.push_str(" r ");
        vector(&mut s, &column.into_owned());
    }
    s.push_str(" e ");
    vector(&mut s, &(child.size / scale));
    s
}

/// The sub-assembly of part `p`, up to scale: its edges and how each child hangs from it (see
/// [`attachment`]), lengths divided by its longest edge, the children in sorted order.
fn sub_assembly(creature: &Creature, kids: &[Vec<(usize, usize)>], p: usize) -> String {
    let scale = longest(&creature.parts[p]);
    let mut s = String::from("e ");
    vector(&mut s, &(creature.parts[p].size / scale));
    let mut hung: Vec<String> = kids[p]
        .iter()
        .map(|&(j, c)| attachment(creature, p, j, c, scale))
        .collect();
    hung.sort();
    for h in hung {
        s.push_str(" [");
        s.push_str(&h);
        s.push(']');
    }
    s
}

/// The share of parts whose sub-assembly (the part, its joints and its children, up to
/// scale) is another part's as well. A sub-assembly is one level deep so that a chain of
/// equal segments counts as repeated: its whole subtrees (the last segment, the last two, ...)
/// all differ.
fn repeated_share(creature: &Creature) -> f64 {
    let kids = children(creature);
    let keys: Vec<String> = (0..creature.parts.len())
        .map(|p| sub_assembly(creature, &kids, p))
        .collect();
    let mut count: HashMap<&str, usize> = HashMap::new();
    for k in &keys {
        *count.entry(k).or_default() += 1;
    }
    let repeated = keys.iter().filter(|k| count[k.as_str()] > 1).count();
    repeated as f64 / keys.len() as f64
}

/// The share of parts with a mirror partner (of the same edges, reflected centre and axes
/// within [`MIRROR_TOLERANCE`] and [`MIRROR_AXIS_COSINE`]) across the best of the three
/// planes through the root's centre normal to its axes. A part on the plane may be its own
/// partner.
fn symmetry_share(creature: &Creature) -> f64 {
    let root = &creature.parts[0];
    let tolerance = MIRROR_TOLERANCE * longest(root);
    let axes =
        |part: &Part| [Vector3::x(), Vector3::y(), Vector3::z()].map(|a| part.orientation * a);
    let mut best = 0;
    for normal in axes(root) {
        let reflect = |v: Vector3<f64>| v - 2.0 * v.dot(&normal) * normal;
        let partnered = creature
            .parts
            .iter()
            .filter(|part| {
                let centre = root.position + reflect(part.position - root.position);
                let mirrored = axes(part).map(reflect);
                creature.parts.iter().any(|other| {
                    let their = axes(other);
                    (centre - other.position).norm() <= tolerance
                        && (0..3).all(|k| {
                            (0..3).any(|l| {
                                mirrored[k].dot(&their[l]).abs() >= MIRROR_AXIS_COSINE
                                    && (part.size[k] - other.size[l]).abs() <= tolerance
                            })
                        })
                })
            })
            .count();
        best = best.max(partnered);
    }
    best as f64 / creature.parts.len() as f64
}

/// The body's canonical description: each part's subtree written as its attachment to its
/// parent (the joint's kind, anchor and axes, the part's centre, rotation and edges, in the
/// parent's frame) and its children's subtrees in sorted order, lengths divided
/// by the root's longest edge; parts no joint reaches are further roots, also sorted.
pub fn canonical_description(creature: &Creature) -> String {
    if creature.parts.is_empty() {
        return String::new();
    }
    let kids = children(creature);
    let scale = longest(&creature.parts[0]);
    let mut reached = vec![false; creature.parts.len()];
    for j in &creature.joints {
        if j.child < reached.len() {
            reached[j.child] = true;
        }
    }
    let mut visited = vec![false; creature.parts.len()];
    let mut roots: Vec<String> = (0..creature.parts.len())
        .filter(|&p| p == 0 || !reached[p])
        .map(|p| {
            let mut head = String::from("e ");
            vector(&mut head, &(creature.parts[p].size / scale));
            subtree(creature, &kids, p, head, scale, &mut visited)
        })
        .collect();
    // The root first, then any unreached parts in sorted order.
    roots[1..].sort();
    roots.concat()
}

fn subtree(
    creature: &Creature,
    kids: &[Vec<(usize, usize)>],
    p: usize,
    head: String,
    scale: f64,
    visited: &mut [bool],
) -> String {
    if std::mem::replace(&mut visited[p], true) {
        // A joint loop: the part is described once.
        return format!("({head})");
    }
    let mut below: Vec<String> = kids[p]
        .iter()
        .map(|&(j, c)| {
            let head = attachment(creature, p, j, c, scale);
            subtree(creature, kids, c, head, scale, visited)
        })
        .collect();
    below.sort();
    format!("({head}{})", below.concat())
}

/// The deflate-compressed size (level 9, raw deflate) of [`canonical_description`] per part.
fn description_bytes(creature: &Creature) -> f64 {
    let text = canonical_description(creature);
    let packed = miniz_oxide::deflate::compress_to_vec(text.as_bytes(), 9);
    packed.len() as f64 / creature.parts.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::creature::{Joint, JointKind};
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::FRAC_PI_2;

    fn part(size: [f64; 3], position: Vector3<f64>, orientation: UnitQuaternion<f64>) -> Part {
        Part {
            size: Vector3::from(size),
            position,
            orientation,
            density: 1000.0,
            growing: false,
        }
    }

    fn joint(parent: usize, child: usize, anchor: Vector3<f64>, axis: Vector3<f64>) -> Joint {
        Joint {
            parent,
            child,
            kind: JointKind::Revolute,
            anchor,
            axes: vec![axis],
            limits: vec![(-1.0, 1.0)],
            strength: 1.0,
            growing: false,
        }
    }

    /// A body (1 × 0.2 × 0.5 m) with a two-part leg at each corner: an upper leg (0.2 m)
    /// pointing sideways, out of the body's long sides, and a lower leg (0.3 m) hanging down
    /// from its end. The legs on either side are mirror images.
    fn quadruped() -> Creature {
        let mut c = Creature::default();
        c.parts.push(part(
            [1.0, 0.2, 0.5],
            Vector3::new(0.0, 0.5, 0.0),
            UnitQuaternion::identity(),
        ));
        let down = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -FRAC_PI_2);
        for (x, side) in [(0.4, 1.0), (-0.4, 1.0), (0.4, -1.0), (-0.4, -1.0)] {
            // x → +z on the right (side 1), x → −z on the left.
            let turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -side * FRAC_PI_2);
            let upper = Vector3::new(x, 0.5, side * 0.35);
            c.parts.push(part([0.2, 0.1, 0.1], upper, turn));
            let u = c.parts.len() - 1;
            c.joints.push(joint(
                0,
                u,
                upper - turn * Vector3::new(0.1, 0.0, 0.0),
                turn * Vector3::z(),
            ));
            let lower = upper + turn * Vector3::new(0.1, -0.15, 0.0);
            c.parts.push(part([0.3, 0.08, 0.08], lower, turn * down));
            let l = c.parts.len() - 1;
            c.joints.push(joint(
                u,
                l,
                upper + turn * Vector3::new(0.1, 0.0, 0.0),
                turn * Vector3::z(),
            ));
        }
        c
    }

    /// `n` parts of random edges, each hung at a random place, in a random orientation, from
    /// a random earlier part by a joint of a random axis.
    fn random_body(n: usize, seed: u64) -> Creature {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut c = Creature::default();
        let unit = |rng: &mut ChaCha8Rng| {
            Vector3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
        };
        for i in 0..n {
            let size = [0.0; 3].map(|_| rng.random_range(0.05..1.0));
            let turn = UnitQuaternion::from_scaled_axis(unit(&mut rng));
            let position = if i == 0 {
                Vector3::new(0.0, 0.5, 0.0)
            } else {
                c.parts[rng.random_range(0..i)].position + unit(&mut rng) * 0.5
            };
            c.parts.push(part(size, position, turn));
            if i > 0 {
                let parent = rng.random_range(0..i);
                let anchor = position + unit(&mut rng) * 0.1;
                let axis = unit(&mut rng).normalize();
                c.joints.push(joint(parent, i, anchor, axis));
            }
        }
        c
    }

    #[test]
    fn a_symmetric_quadruped_is_more_regular_than_a_random_body_of_as_many_parts_on_every_measure()
    {
        let q = regularity(&quadruped());
        let r = regularity(&random_body(9, 7));
        // By hand: the four upper legs have the same sub-assembly (a 0.2 × 0.1 × 0.1 box with
        // a 0.3 m box hanging from its end by a revolute joint), and so have the four lower
        // legs (a 0.3 × 0.08 × 0.08 box, no children); the body is alone: 8 of 9 parts.
        assert!((q.repeated - 8.0 / 9.0).abs() < 1e-12, "{q:?}");
        // Across the body's x = 0 plane each leg's parts meet the other leg's on that side,
        // and the body is its own mirror image: 9 of 9.
        assert_eq!(q.symmetry, 1.0);
        // The random body repeats nothing, and only its root is its own mirror image.
        assert_eq!(r.repeated, 0.0, "{r:?}");
        assert!(r.symmetry < q.symmetry, "{r:?}");
        assert!(r.description_bytes > q.description_bytes, "{q:?} {r:?}");
    }

    #[test]
    fn the_measures_do_not_change_when_the_body_is_turned_and_moved() {
        let q = quadruped();
        let turn = UnitQuaternion::from_euler_angles(0.3, -1.1, 0.7);
        let shift = Vector3::new(2.0, 1.0, -3.0);
        let mut moved = q.clone();
        for p in &mut moved.parts {
            p.position = turn * p.position + shift;
            p.orientation = turn * p.orientation;
        }
        for j in &mut moved.joints {
            j.anchor = turn * j.anchor + shift;
            j.axes = j.axes.iter().map(|a| turn * a).collect();
        }
        assert_eq!(regularity(&moved), regularity(&q));
        assert_eq!(canonical_description(&moved), canonical_description(&q));
    }

    #[test]
    fn a_chain_of_equal_segments_repeats_all_but_its_last_segment() {
        // Five 0.4 × 0.1 × 0.1 segments end to end along x, each hinged to the one before.
        // Segments 1 to 4 each hang the same segment from their far end: 4 of 5 repeat (the
        // last hangs nothing).
        let mut c = Creature::default();
        for i in 0..5 {
            let centre = Vector3::new(0.4 * i as f64, 0.5, 0.0);
            c.parts
                .push(part([0.4, 0.1, 0.1], centre, UnitQuaternion::identity()));
            if i > 0 {
                let anchor = centre - Vector3::new(0.2, 0.0, 0.0);
                c.joints.push(joint(i - 1, i, anchor, Vector3::z()));
            }
        }
        let m = regularity(&c);
        assert_eq!(m.repeated, 0.8);
        // The chain lies on the root's planes y = 0.5 and z = 0: every part is its own mirror
        // image.
        assert_eq!(m.symmetry, 1.0);
        // Longer, it says little more: the compressed description grows less than the parts.
        let mut longer = c.clone();
        for i in 5..20 {
            let centre = Vector3::new(0.4 * i as f64, 0.5, 0.0);
            longer
                .parts
                .push(part([0.4, 0.1, 0.1], centre, UnitQuaternion::identity()));
            let anchor = centre - Vector3::new(0.2, 0.0, 0.0);
            longer.joints.push(joint(i - 1, i, anchor, Vector3::z()));
        }
        let l = regularity(&longer);
        assert!(l.description_bytes < m.description_bytes, "{l:?} {m:?}");
        assert_eq!(l.repeated, 19.0 / 20.0);
    }

    #[test]
    fn a_single_part_and_an_empty_body_are_well_defined() {
        let mut c = Creature::default();
        let m = regularity(&c);
        assert!(m.repeated.is_nan() && m.symmetry.is_nan() && m.description_bytes.is_nan());
        c.parts.push(part(
            [1.0, 0.2, 0.1],
            Vector3::zeros(),
            UnitQuaternion::identity(),
        ));
        let m = regularity(&c);
        assert_eq!((m.repeated, m.symmetry), (0.0, 1.0));
        assert!(m.description_bytes.is_finite() && m.description_bytes > 0.0);
        // A degenerate part (no size) does not divide by zero.
        c.parts[0].size = Vector3::zeros();
        assert!(regularity(&c).description_bytes.is_finite());
    }

    #[test]
    fn the_description_sorts_children_and_rounds_numbers() {
        let q = quadruped();
        let mut shuffled = q.clone();
        // The same body with its joints listed in another order.
        shuffled.joints.reverse();
        assert_eq!(canonical_description(&shuffled), canonical_description(&q));
        // A change below the rounding step does not change it; a larger one does.
        shuffled.parts[2].size.x += 0.001;
        assert_eq!(canonical_description(&shuffled), canonical_description(&q));
        shuffled.parts[2].size.x += 0.05;
        assert_ne!(canonical_description(&shuffled), canonical_description(&q));
    }
}
