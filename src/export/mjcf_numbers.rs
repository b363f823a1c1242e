//! How MJCF writes numbers: coordinates in the shortest form that reads back exactly,
//! round-off written as 0, and the turn from Ontogeny's Y-up world to MuJoCo's Z-up one.
//! Shared by the creature's model (`mjcf`) and its world (`mjcf_world`).

use std::f64::consts::FRAC_PI_2;

use nalgebra::{UnitQuaternion, Vector3};

/// Writes numbers separated by spaces, each in the shortest form that reads back exactly
/// (in scientific notation when very small or very large).
pub(crate) fn numbers(values: &[f64]) -> String {
    let texts: Vec<String> = values
        .iter()
        .map(|&v| {
            let v = v + 0.0; // no "-0"
            if v != 0.0 && !(1e-4..1e16).contains(&v.abs()) {
                format!("{v:e}")
            } else {
                format!("{v}")
            }
        })
        .collect();
    texts.join(" ")
}

/// Below this, a coordinate of a position, axis or quaternion is round-off: written as 0.
const ROUND_OFF: f64 = 1e-12;

/// Writes the coordinates of a position, axis or quaternion, round-off written as 0.
pub(crate) fn coordinates(values: &[f64]) -> String {
    let snapped: Vec<f64> = values
        .iter()
        .map(|&v| if v.abs() < ROUND_OFF { 0.0 } else { v })
        .collect();
    numbers(&snapped)
}

pub(crate) fn vec3(v: &Vector3<f64>) -> String {
    coordinates(&[v.x, v.y, v.z])
}

/// MJCF's `quat`: w x y z.
pub(crate) fn quat(q: &UnitQuaternion<f64>) -> String {
    coordinates(&[q.w, q.i, q.j, q.k])
}

/// The rotation from Ontogeny's world (Y up) to MuJoCo's (Z up): +90° about x.
pub fn z_up() -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::x_axis(), FRAC_PI_2)
}
