//! Geometry of a creature's boxes: interpenetration (separating-axis test on oriented boxes).

use nalgebra::{Matrix3, Vector3};

use super::{Creature, Part};

/// Boxes are shrunk by this much (metres) before testing, so that faces that merely touch do
/// not count.
const MARGIN: f64 = 1e-6;

impl Creature {
    /// The pairs of parts that interpenetrate other than at a joint. Near a point where the
    /// two parts meet — a joint between them, or one joint point both hang from — each part's
    /// length is cut back by the joint region's radius (the sum of the two parts' largest half
    /// cross-sections) before testing; everywhere else they must not overlap.
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
                let shared: Vec<Vector3<f64>> = anchors[a]
                    .iter()
                    .filter(|p| anchors[b].iter().any(|q| (*p - q).norm() < 1e-9))
                    .copied()
                    .collect();
                let (pa, pb) = (&self.parts[a], &self.parts[b]);
                let radius = half_section(pa) + half_section(pb);
                let pieces_a = trimmed(pa, &shared, radius);
                let pieces_b = trimmed(pb, &shared, radius);
                if pieces_a
                    .iter()
                    .any(|x| pieces_b.iter().any(|y| boxes_intersect(x, y)))
                {
                    pairs.push((a, b));
                }
            }
        }
        pairs
    }
}

/// The larger half of a part's cross-section (thickness or width).
fn half_section(p: &Part) -> f64 {
    p.size.y.max(p.size.z) / 2.0
}

/// The part with the stretch of its length within `radius` of each point in `points` cut
/// out: zero, one or more boxes.
fn trimmed(part: &Part, points: &[Vector3<f64>], radius: f64) -> Vec<Part> {
    let axis = part.orientation * Vector3::x();
    let h = part.size.x / 2.0;
    let mut intervals = vec![(-h, h)];
    for p in points {
        let s = (p - part.position).dot(&axis);
        let (cut_lo, cut_hi) = (s - radius, s + radius);
        intervals = intervals
            .into_iter()
            .flat_map(|(lo, hi)| {
                let mut keep = Vec::new();
                if cut_lo > lo {
                    keep.push((lo, cut_lo.min(hi)));
                }
                if cut_hi < hi {
                    keep.push((cut_hi.max(lo), hi));
                }
                keep
            })
            .filter(|(lo, hi)| hi - lo > 2.0 * MARGIN)
            .collect();
    }
    intervals
        .into_iter()
        .map(|(lo, hi)| Part {
            size: Vector3::new(hi - lo, part.size.y, part.size.z),
            position: part.position + axis * ((lo + hi) / 2.0),
            ..part.clone()
        })
        .collect()
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
