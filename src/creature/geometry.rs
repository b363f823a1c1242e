//! Geometry of a creature's boxes: interpenetration (separating-axis test on oriented boxes,
//! and the corners of two boxes' overlap to tell a joint's contact region from the rest).

use nalgebra::{Matrix3, Vector3};

use super::{Creature, Part};

/// Boxes are shrunk by this much (metres) before testing, so that faces that merely touch do
/// not count.
const MARGIN: f64 = 1e-6;

/// The most pairs of interpenetrating parts named one by one: beyond them, one message counts
/// the pairs and names the first few (a plant of thousands of parts has thousands of such
/// pairs).
const NAMED_PAIRS: usize = 5;

/// What interpenetrating `pairs` are, in words: a message for each pair (`parts 0 and 3
/// interpenetrate`), or one that counts them and names the first few when there are more than
/// five.
pub fn interpenetration_messages(pairs: &[(usize, usize)]) -> Vec<String> {
    if pairs.len() <= NAMED_PAIRS {
        return pairs
            .iter()
            .map(|(a, b)| format!("parts {a} and {b} interpenetrate"))
            .collect();
    }
    let named: Vec<String> = pairs[..NAMED_PAIRS]
        .iter()
        .map(|(a, b)| format!("{a} and {b}"))
        .collect();
    vec![format!(
        "{} pairs of parts interpenetrate (parts {}, ...)",
        pairs.len(),
        named.join(", ")
    )]
}

impl Creature {
    /// Whether the creature's parts collide with each other from the start, as the task's
    /// screening refuses it (`self-intersecting`): a pair of [`Creature::interpenetrating_pairs`],
    /// or an interpenetration its development reported among its errors.
    pub fn self_intersects(&self) -> bool {
        self.problems
            .iter()
            .any(|p| p.severity == super::Severity::Error && p.message.contains("interpenetrate"))
            || !self.interpenetrating_pairs().is_empty()
    }

    /// The pairs of parts that interpenetrate other than in a joint's own contact region.
    ///
    /// Two parts may overlap only where they meet at a **joint point** — the anchor of a joint
    /// between them, or an anchor both hang from (siblings) — and only there: the whole of
    /// their overlap must lie within the contact radius √(r_a² + r_b²) of that point, r being
    /// a part's cross-section half-diagonal (½√(thickness² + width²)). That is the farthest two
    /// boxes can overlap when each leaves the point from an end face, centred on its axis, at
    /// up to 90° from the other (a point of one inside the other lies within r_b of the second's
    /// axis and within r_a of its face), so every turn up to 90° is allowed and a branch that
    /// folds back onto its parent is not. The exemption also requires that the point lies on
    /// the surface of both parts, not inside either, and that neither part's centre lies
    /// inside the other: a part buried in its neighbour, or more than half sunk into it,
    /// always counts. Faces that merely touch never count (the boxes are shrunk by 1 µm).
    pub fn interpenetrating_pairs(&self) -> Vec<(usize, usize)> {
        let n = self.parts.len();
        let mut anchors: Vec<Vec<Vector3<f64>>> = vec![Vec::new(); n];
        for j in &self.joints {
            if j.parent < n && j.child < n {
                anchors[j.parent].push(j.anchor);
                anchors[j.child].push(j.anchor);
            }
        }
        let mut pairs = Vec::new();
        for a in 0..n {
            for b in a + 1..n {
                let (pa, pb) = (&self.parts[a], &self.parts[b]);
                // Boxes whose bounding spheres are apart do not meet: most pairs of a
                // plant of thousands of parts end here.
                let reach = (pa.size.norm() + pb.size.norm()) / 2.0;
                if (pa.position - pb.position).norm_squared() > reach * reach
                    || !boxes_intersect(pa, pb)
                {
                    continue;
                }
                let at_a_joint = anchors[a]
                    .iter()
                    .filter(|p| anchors[b].iter().any(|q| (*p - q).norm() < 1e-9))
                    .any(|p| contact_only(pa, pb, p, 0.0));
                if !at_a_joint {
                    pairs.push((a, b));
                }
            }
        }
        pairs
    }
}

/// Half the diagonal of a part's cross-section: how far its sides reach from its axis.
fn section_radius(p: &Part) -> f64 {
    0.5 * p.size.y.hypot(p.size.z)
}

/// Whether parts `a` and `b` overlap anywhere but in the contact region of a joint at one of
/// `points` (the rule of [`Creature::interpenetrating_pairs`]), `slack` metres allowed for
/// joints that have come a little apart: a joint point may lie that far inside a part and the
/// overlap reach that much beyond the contact radius. With `slack` 0 this is the builder's
/// rule to the micrometre.
pub fn overlap_beyond_joints(a: &Part, b: &Part, points: &[Vector3<f64>], slack: f64) -> bool {
    boxes_intersect(a, b) && !points.iter().any(|p| contact_only(a, b, p, slack))
}

/// Whether the overlap of two intersecting parts is only the contact region of a joint at
/// `point` (see [`Creature::interpenetrating_pairs`]), give or take `slack` metres (see
/// [`overlap_beyond_joints`]).
fn contact_only(a: &Part, b: &Part, point: &Vector3<f64>, slack: f64) -> bool {
    let margin = MARGIN + slack;
    if inside(a, point, margin)
        || inside(b, point, margin)
        || inside(a, &b.position, MARGIN)
        || inside(b, &a.position, MARGIN)
    {
        return false;
    }
    let radius = section_radius(a).hypot(section_radius(b));
    let corners = overlap_corners(a, b);
    !corners.is_empty()
        && corners
            .iter()
            .all(|c| (c - point).norm() <= radius + TOLERANCE + slack)
}

/// Slack (metres) for round-off in the overlap's corners.
const TOLERANCE: f64 = 1e-9;

/// Whether `point` lies strictly inside the part, deeper than `margin` below its surface.
fn inside(part: &Part, point: &Vector3<f64>, margin: f64) -> bool {
    let local = part.orientation.inverse() * (point - part.position);
    (0..3).all(|k| local[k].abs() < part.size[k] / 2.0 - margin)
}

/// The corners of the overlap of two boxes (each shrunk by [`MARGIN`]), a convex polyhedron:
/// the points where three of the twelve face planes meet that lie inside both boxes.
fn overlap_corners(a: &Part, b: &Part) -> Vec<Vector3<f64>> {
    // Faces as half-spaces n · x <= d.
    let mut planes: Vec<(Vector3<f64>, f64)> = Vec::with_capacity(12);
    for part in [a, b] {
        for k in 0..3 {
            let axis = part.orientation * Vector3::ith(k, 1.0);
            let half = (part.size[k] / 2.0 - MARGIN).max(0.0);
            let centre = axis.dot(&part.position);
            planes.push((axis, centre + half));
            planes.push((-axis, -centre + half));
        }
    }
    let mut corners = Vec::new();
    for i in 0..planes.len() {
        for j in i + 1..planes.len() {
            for k in j + 1..planes.len() {
                let m = Matrix3::from_rows(&[
                    planes[i].0.transpose(),
                    planes[j].0.transpose(),
                    planes[k].0.transpose(),
                ]);
                if m.determinant().abs() < 1e-9 {
                    continue; // two of the planes are (nearly) parallel
                }
                let Some(inverse) = m.try_inverse() else {
                    continue;
                };
                let x = inverse * Vector3::new(planes[i].1, planes[j].1, planes[k].1);
                if planes.iter().all(|(n, d)| n.dot(&x) <= d + TOLERANCE) {
                    corners.push(x);
                }
            }
        }
    }
    corners
}

/// Whether two oriented boxes overlap (separating-axis test, 15 axes), each shrunk by a
/// hair so that touching faces do not count.
pub fn boxes_intersect(a: &Part, b: &Part) -> bool {
    let ra: Matrix3<f64> = *a.orientation.to_rotation_matrix().matrix();
    let rb: Matrix3<f64> = *b.orientation.to_rotation_matrix().matrix();
    let ha = (a.size / 2.0).map(|v| (v - MARGIN).max(0.0));
    let hb = (b.size / 2.0).map(|v| (v - MARGIN).max(0.0));
    let d = b.position - a.position;
    let axes_a: [Vector3<f64>; 3] = [
        ra.column(0).into(),
        ra.column(1).into(),
        ra.column(2).into(),
    ];
    let axes_b: [Vector3<f64>; 3] = [
        rb.column(0).into(),
        rb.column(1).into(),
        rb.column(2).into(),
    ];
    let separated = |axis: Vector3<f64>| {
        let len = axis.norm();
        if len < 1e-12 {
            return false; // parallel edges: covered by the face axes
        }
        let axis = axis / len;
        let pa: f64 = (0..3).map(|k| ha[k] * axes_a[k].dot(&axis).abs()).sum();
        let pb: f64 = (0..3).map(|k| hb[k] * axes_b[k].dot(&axis).abs()).sum();
        d.dot(&axis).abs() > pa + pb
    };
    for k in 0..3 {
        if separated(axes_a[k]) || separated(axes_b[k]) {
            return false;
        }
    }
    for x in &axes_a {
        for y in &axes_b {
            if separated(x.cross(y)) {
                return false;
            }
        }
    }
    true
}
