//! Interpenetration of parts, found with the separating-axis test on oriented boxes.

use nalgebra::{Matrix3, Vector3};

use crate::creature::{Creature, Part, Problem, Severity};

/// Boxes are shrunk by this much (metres) before testing, so that faces that merely touch do
/// not count.
const MARGIN: f64 = 1e-6;

/// Adds an error for every pair of parts that interpenetrate other than at a joint: pairs
/// joined by a joint, and pairs that both hang from the same joint point (branches leaving
/// one place), are allowed to overlap there.
pub(super) fn report(creature: &mut Creature, t: Option<f64>) {
    let n = creature.parts.len();
    let mut anchors: Vec<Vec<Vector3<f64>>> = vec![Vec::new(); n];
    let mut joined = std::collections::HashSet::new();
    for j in &creature.joints {
        anchors[j.parent].push(j.anchor);
        anchors[j.child].push(j.anchor);
        joined.insert((j.parent.min(j.child), j.parent.max(j.child)));
    }
    let mut problems = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            if joined.contains(&(a, b))
                || anchors[a]
                    .iter()
                    .any(|p| anchors[b].iter().any(|q| (p - q).norm() < 1e-9))
            {
                continue;
            }
            if intersect(&creature.parts[a], &creature.parts[b]) {
                problems.push(Problem {
                    severity: Severity::Error,
                    message: format!("parts {a} and {b} interpenetrate"),
                    module: None,
                    t,
                });
            }
        }
    }
    creature.problems.extend(problems);
}

/// Whether two oriented boxes overlap (separating-axis test, 15 axes).
pub fn intersect(a: &Part, b: &Part) -> bool {
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
