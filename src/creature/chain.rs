//! The longest chain of a body: its longest row of parts without a branch, the measure of
//! Hornby & Pollack's (2001) constraint that "creatures have no sequence of more than N bars in
//! a row that is not part of a cycle" (our bodies are trees, so no row is part of a cycle).
//!
//! A chain is a path of parts in the body tree whose inner parts each have exactly two
//! neighbours (an unbranched row); its length is its number of parts, ends included. A snake
//! of 20 parts has a chain of 20; a body part carrying four legs of 3 parts has chains of 4
//! (the body part and a leg), and a body part with exactly two neighbours joins the legs on
//! either side of it into one chain.

use super::Creature;

impl Creature {
    /// The number of parts of the body's longest chain (see the module documentation): 1 for
    /// a single part, 0 for a creature without parts. Joints that do not join two distinct
    /// parts of the creature are ignored; a row that closes on itself (which no encoding
    /// builds) is counted once round.
    pub fn longest_chain(&self) -> usize {
        let n = self.parts.len();
        let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
        for j in &self.joints {
            if j.parent < n && j.child < n && j.parent != j.child {
                neighbours[j.parent].push(j.child);
                neighbours[j.child].push(j.parent);
            }
        }
        let mut longest = usize::from(n > 0);
        for (start, around) in neighbours.iter().enumerate() {
            // Chains start at an end or a branch: a part whose neighbours are not two.
            if around.len() == 2 {
                continue;
            }
            for &first in around {
                let (mut previous, mut here, mut parts) = (start, first, 2);
                while neighbours[here].len() == 2 && parts < n {
                    let next = match neighbours[here][0] == previous {
                        true => neighbours[here][1],
                        false => neighbours[here][0],
                    };
                    (previous, here) = (here, next);
                    parts += 1;
                }
                longest = longest.max(parts);
            }
        }
        // A body that is one closed row has no end to start from.
        if longest < 2 && n > 1 && neighbours.iter().all(|a| a.len() == 2) {
            longest = n;
        }
        longest
    }
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
    fn a_star_of_four_legs_of_three_parts_has_chains_of_four() {
        // Body 0; legs 1-2-3, 4-5-6, 7-8-9, 10-11-12.
        let mut joints = Vec::new();
        for leg in 0..4 {
            let first = 1 + 3 * leg;
            joints.extend([(0, first), (first, first + 1), (first + 1, first + 2)]);
        }
        assert_eq!(body(13, &joints).longest_chain(), 4);
    }

    #[test]
    fn a_body_part_with_two_neighbours_joins_the_legs_across_it_into_one_chain() {
        // Legs 1-2 and 3-4 on either side of body part 0: 2-1-0-3-4.
        let c = body(5, &[(0, 1), (1, 2), (0, 3), (3, 4)]);
        assert_eq!(c.longest_chain(), 5);
    }

    #[test]
    fn a_t_counts_its_longest_arm_with_the_branch_part() {
        // A row 0-1-2-3-4-5 with an arm 6-7 on part 2: part 2 has three neighbours, so the
        // rows are 0-1-2 (3 parts), 2-3-4-5 (4) and 2-6-7 (3).
        let c = body(8, &[(0, 1), (1, 2), (2, 3), (3, 4), (4, 5), (2, 6), (6, 7)]);
        assert_eq!(c.longest_chain(), 4);
    }

    #[test]
    fn joints_that_join_no_two_parts_are_ignored() {
        let c = body(3, &[(0, 1), (1, 2), (1, 1), (0, 9)]);
        assert_eq!(c.longest_chain(), 3);
    }

    #[test]
    fn a_closed_row_is_counted_once_round() {
        assert_eq!(
            body(4, &[(0, 1), (1, 2), (2, 3), (3, 0)]).longest_chain(),
            4
        );
    }
}
