//! The longest chain of a body: its longest sequence of parts joined end to end, the measure
//! of Hornby & Pollack's (2001) constraint that "creatures have no sequence of more than N bars
//! in a row that is not part of a cycle", which keeps their creatures physically plausible (a
//! long unsupported row of bars sags or breaks, whatever hangs off its side).
//!
//! A chain is a path of parts in the body tree, each part joined to the next; its length is its
//! number of parts, ends included, and the body's chain is its longest path: a side branch
//! neither breaks a row nor shortens it. A snake of 20 parts has a chain of 20; a body part
//! carrying four legs of 3 parts has a chain of 7 (a leg, the body part and another leg); a
//! straight row of 11 parts with a nub on each has a chain of at least 11. Our bodies are
//! trees, so no row is part of a cycle; a joint that would close a cycle (which no encoding
//! builds) is left out of the count, as Hornby & Pollack exempt a row in a cycle.

use super::Creature;

impl Creature {
    /// The number of parts of the body's longest chain (see the module documentation): 1 for
    /// a single part, 0 for a creature without parts. Joints that do not join two distinct
    /// parts of the creature, or that would close a cycle, are ignored.
    pub fn longest_chain(&self) -> usize {
        let n = self.parts.len();
        let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut root: Vec<usize> = (0..n).collect();
        for j in &self.joints {
            if j.parent >= n || j.child >= n || j.parent == j.child {
                continue;
            }
            let (a, b) = (find(&mut root, j.parent), find(&mut root, j.child));
            if a != b {
                root[a] = b;
                neighbours[j.parent].push(j.child);
                neighbours[j.child].push(j.parent);
            }
        }
        // In each tree of the forest, the part farthest from any part is one end of a longest
        // path, and the part farthest from it the other (the double sweep).
        let mut seen = vec![false; n];
        let mut longest = 0;
        for start in 0..n {
            if seen[start] {
                continue;
            }
            let (end, _) = farthest(&neighbours, start, &mut seen);
            let (_, parts) = farthest(&neighbours, end, &mut seen);
            longest = longest.max(parts);
        }
        longest
    }
}

/// The representative of `i`'s set (union–find with path halving).
fn find(root: &mut [usize], mut i: usize) -> usize {
    while root[i] != i {
        root[i] = root[root[i]];
        i = root[i];
    }
    i
}

/// The part of `start`'s tree farthest from it, and the parts on the path between them (ends
/// included), breadth first; marks the tree's parts in `seen`.
fn farthest(neighbours: &[Vec<usize>], start: usize, seen: &mut [bool]) -> (usize, usize) {
    let mut parts_to = vec![0usize; neighbours.len()];
    parts_to[start] = 1;
    seen[start] = true;
    let mut queue = std::collections::VecDeque::from([start]);
    let mut far = (start, 1);
    while let Some(here) = queue.pop_front() {
        if parts_to[here] > far.1 {
            far = (here, parts_to[here]);
        }
        for &next in &neighbours[here] {
            if parts_to[next] == 0 {
                parts_to[next] = parts_to[here] + 1;
                seen[next] = true;
                queue.push_back(next);
            }
        }
    }
    far
}

#[cfg(test)]
mod tests {
    use nalgebra::{UnitQuaternion, Vector3};

    use super::*;
    use crate::creature::{Joint, JointKind, Part};

    /// A body of `n` unit parts joined by the (parent, child) pairs `joints`.
    fn body(n: usize, joints: &[(usize, usize)]) -> Creature {
        let part = Part {
            size: Vector3::new(1.0, 1.0, 1.0),
            position: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
            density: 1000.0,
            growing: false,
        };
        Creature {
            parts: vec![part; n],
            joints: joints
                .iter()
                .map(|&(parent, child)| Joint {
                    parent,
                    child,
                    kind: JointKind::Rigid,
                    anchor: Vector3::zeros(),
                    axes: Vec::new(),
                    limits: Vec::new(),
                    strength: 0.0,
                    growing: false,
                })
                .collect(),
            ..Creature::default()
        }
    }

    /// A snake of `n` parts, each the child of the one before.
    fn snake(n: usize) -> Creature {
        let joints: Vec<(usize, usize)> = (1..n).map(|k| (k - 1, k)).collect();
        body(n, &joints)
    }

    #[test]
    fn a_snake_of_twenty_parts_is_one_chain_of_twenty() {
        assert_eq!(snake(20).longest_chain(), 20);
        assert_eq!(snake(2).longest_chain(), 2);
    }

    #[test]
    fn a_single_part_is_a_chain_of_one_and_no_part_none() {
        assert_eq!(body(1, &[]).longest_chain(), 1);
        assert_eq!(Creature::default().longest_chain(), 0);
    }

    #[test]
    fn a_star_of_four_legs_of_three_parts_has_a_chain_of_seven() {
        // Body 0; legs 1-2-3, 4-5-6, 7-8-9, 10-11-12: 3-2-1-0-4-5-6.
        let mut joints = Vec::new();
        for leg in 0..4 {
            let first = 1 + 3 * leg;
            joints.extend([(0, first), (first, first + 1), (first + 1, first + 2)]);
        }
        assert_eq!(body(13, &joints).longest_chain(), 7);
    }

    #[test]
    fn nubs_on_a_row_neither_break_nor_lengthen_it() {
        // A row 0-1-...-10 with a nub on each of parts 1 to 9 (parts 11 to 19).
        let mut joints: Vec<(usize, usize)> = (1..11).map(|k| (k - 1, k)).collect();
        joints.extend((1..10).map(|k| (k, 10 + k)));
        // The longest path runs from a nub at one end to the row's far end: nub 11 on part 1,
        // then parts 1 to 10 (11 parts), or part 0 to part 10 (11 parts).
        assert_eq!(body(20, &joints).longest_chain(), 11);
    }

    #[test]
    fn the_longest_of_separate_bodies_counts() {
        // Parts 0-1-2 and 3-4, not joined.
        assert_eq!(body(5, &[(0, 1), (1, 2), (3, 4)]).longest_chain(), 3);
    }

    #[test]
    fn a_body_part_with_two_neighbours_joins_the_legs_across_it_into_one_chain() {
        // Legs 1-2 and 3-4 on either side of body part 0: 2-1-0-3-4.
        let c = body(5, &[(0, 1), (1, 2), (0, 3), (3, 4)]);
        assert_eq!(c.longest_chain(), 5);
    }

    #[test]
    fn a_t_counts_its_longest_path_across_the_branch() {
        // A row 0-1-2-3-4-5 with an arm 6-7 on part 2: the longest paths are 0-1-2-3-4-5 and
        // 7-6-2-3-4-5, 6 parts each.
        let c = body(8, &[(0, 1), (1, 2), (2, 3), (3, 4), (4, 5), (2, 6), (6, 7)]);
        assert_eq!(c.longest_chain(), 6);
    }

    #[test]
    fn joints_that_join_no_two_parts_are_ignored() {
        let c = body(3, &[(0, 1), (1, 2), (1, 1), (0, 9)]);
        assert_eq!(c.longest_chain(), 3);
    }

    #[test]
    fn a_joint_that_would_close_a_cycle_is_left_out() {
        // 0-1-2-3 and a joint 3-0 closing the ring: the row of 4 is counted without it.
        assert_eq!(
            body(4, &[(0, 1), (1, 2), (2, 3), (3, 0)]).longest_chain(),
            4
        );
    }
}
