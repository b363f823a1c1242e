//! Writing recorded poses compactly: at f32 precision, the precision rapier computes them in
//! (its `f32` build), so nothing the physics knew is lost, and a number takes about 10
//! characters instead of 19. Reading them back takes any number, as before.

use nalgebra::{UnitQuaternion, Vector3};
use serde::Serializer;
use serde::ser::SerializeSeq;

/// `[x, y, z]` at f32 precision.
fn vector(v: &Vector3<f64>) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

/// Poses as `[[x, y, z], [i, j, k, w]]`, nalgebra's own layout, at f32 precision.
pub fn poses<S: Serializer>(
    poses: &[(Vector3<f64>, UnitQuaternion<f64>)],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    let mut seq = serializer.serialize_seq(Some(poses.len()))?;
    for (position, orientation) in poses {
        let q = orientation.coords;
        seq.serialize_element(&(
            vector(position),
            [q.x as f32, q.y as f32, q.z as f32, q.w as f32],
        ))?;
    }
    seq.end()
}

/// An optional point as `[x, y, z]` at f32 precision.
pub fn point<S: Serializer>(
    point: &Option<Vector3<f64>>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    match point {
        Some(p) => serializer.serialize_some(&vector(p)),
        None => serializer.serialize_none(),
    }
}
