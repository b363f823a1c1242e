//! Walking with Dinosaurs' crossover (3.3.1) for the graph genome. A part of a graph genome
//! is a node with the nodes reachable from it (the sub-assembly it grows) and the connection
//! that places it on its parent. The crossover copies such a part of the elite, turns its
//! connection half a turn ([`half_turned`]), and hangs it from one of the breeder's
//! connections in place of what that connection grew (or, when the breeder has no
//! connection, from a new one on its root); nodes of the breeder nothing reaches any more go,
//! as in grafting.

use super::operators::{graft_site, joined};
use super::*;

/// `c` turned half a turn about its parent part's up axis (the parent's thickness axis, y,
/// through its centre): what hung on one side of the parent hangs on the other, still
/// pointing away from it, and what pointed down still points down. For a body lying on the
/// ground that axis is the vertical, and the half turn takes a limb on the parent's right
/// face to its left face, where a mirror across the parent's length–thickness plane takes it.
///
/// The half turn diag(−1, 1, −1) maps the front face's frame onto the back face's and the
/// right face's onto the left face's, so those connections only swap faces: the same place on
/// the face and the same turn give exactly the turned part. The top and bottom faces are on
/// the axis: the half turn keeps the face, negates both coordinates of the place and both
/// bends, and would add half a turn to the roll about the child's length. The roll's range is
/// ±90° (a box is the same after a half turn), so the roll is kept: the child's box is exactly
/// the turned one, but the parts that grow from it are not turned with it.
pub(super) fn half_turned(c: &Connection) -> Connection {
    let mut c = c.clone();
    match c.face {
        Face::Front => c.face = Face::Back,
        Face::Back => c.face = Face::Front,
        Face::Right => c.face = Face::Left,
        Face::Left => c.face = Face::Right,
        Face::Top | Face::Bottom => {
            c.position = c.position.map(|v| -v);
            c.orientation[0] = -c.orientation[0];
            c.orientation[1] = -c.orientation[1];
        }
    }
    c
}

impl GraphGenome {
    /// One try of Walking with Dinosaurs' crossover (see the module documentation): the site
    /// is one of `self`'s connections drawn uniformly, the part one of `other`'s connections
    /// reachable from its root whose nodes fit the room `max_nodes` leaves. On the throwing
    /// tasks a copy on the root never takes the back face, which holds the projectile (it
    /// takes the front, as mutation does). `None` when `other` has no connection, no part
    /// fits, or `self` has no connection and no room for one.
    pub(super) fn mirror_once(
        &self,
        other: &GraphGenome,
        limits: &GraphLimits,
        rng: &mut Rng,
    ) -> Option<GraphGenome> {
        const MARK: usize = usize::MAX;
        let reach = other.reachable();
        let donors: Vec<(usize, usize)> =
            crate::encoding::index_pairs(&other.nodes, |n| n.connections.len())
                .into_iter()
                .filter(|&(a, k)| reach[a] && other.nodes[a].connections[k].to < other.nodes.len())
                .collect();
        if donors.is_empty() {
            return None;
        }
        let mut g = self.clone();
        let ((i, j), keep, room) = graft_site(&mut g, limits, rng, |_| {
            let (a, k) = donors[0];
            other.nodes[a].connections[k].clone()
        })?;
        let fitting: Vec<((usize, usize), Vec<usize>)> = donors
            .into_iter()
            .map(|(a, k)| {
                let list = reachable_list(&other.nodes, other.nodes[a].connections[k].to);
                ((a, k), list)
            })
            .filter(|(_, list)| list.len() <= room)
            .collect();
        if fitting.is_empty() {
            return None;
        }
        let ((a, k), list) = &fitting[rng.random_range(0..fitting.len())];
        let mut placed = half_turned(&other.nodes[*a].connections[*k]);
        if i == 0 && limits.throwing() && placed.face == Face::Back {
            placed.face = Face::Front;
        }
        placed.to = MARK;
        g.nodes[i].connections[j] = placed;
        Some(GraphGenome {
            nodes: joined(&g.nodes, &keep, other, list),
            neurons: g.neurons,
            // The breeder's projectile, whole (Chaumont 4.1: one projectile only).
            projectile: g.projectile,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn connection(face: Face) -> Connection {
        Connection {
            to: 1,
            face,
            position: [0.25, -0.5],
            orientation: [0.5, -0.25, 1.0],
            scale: 1.0,
            reflection: false,
            terminal_only: false,
        }
    }

    /// The half turn about the parent's y axis, diag(−1, 1, −1), applied to a connection's
    /// anchor and frame gives the turned connection's anchor and frame, for every face (the
    /// roll of a top or bottom connection aside: its frame differs by a half turn about the
    /// child's length, which leaves the box where it was).
    #[test]
    fn a_half_turned_connection_is_its_connection_turned_about_the_parents_up_axis() {
        let turn_y = Matrix3::from_diagonal(&Vector3::new(-1.0, 1.0, -1.0));
        let roll = Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0));
        let half = Vector3::new(0.5, 0.2, 0.3);
        let anchor = |c: &Connection| {
            let f = develop::face_frame(c.face);
            let extent = |col: usize| f.column(col).abs().dot(&half);
            f.column(0) * extent(0)
                + f.column(1) * (c.position[0] * extent(1))
                + f.column(2) * (c.position[1] * extent(2))
        };
        let frame = |c: &Connection| develop::face_frame(c.face) * develop::turn(&c.orientation);
        for face in FACES {
            let c = connection(face);
            let t = half_turned(&c);
            assert!(
                (anchor(&t) - turn_y * anchor(&c)).norm() < 1e-12,
                "{face:?}"
            );
            let expected = turn_y * frame(&c);
            let on_axis = matches!(face, Face::Top | Face::Bottom);
            let got = if on_axis { frame(&t) * roll } else { frame(&t) };
            assert!((got - expected).norm() < 1e-12, "{face:?}");
        }
    }
}
