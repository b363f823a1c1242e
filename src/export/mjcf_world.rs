//! A creature's world in MJCF, beside the creature of [`super::mjcf`] (docs/guide/exporting.md
//! says the same for users), in MuJoCo's Z-up axes (Ontogeny's (x, y, z) is (x, −z, y)):
//!
//! - **Ground.** Level ground is the `plane` at z = 0; a slope is that plane turned to the
//!   slope's normal (`quat`); a flight of steps is one `box` per step on a plane at the steps'
//!   base; rough ground is an `hfield` asset (its samples, rows from −y to +y, normalised to
//!   [0, 1] as MuJoCo reads them, `size`'s elevation their range) placed at its lowest sample,
//!   with the four level slabs round it as boxes. Water has no ground.
//! - **Obstacles.** One `box` per obstacle on the worldbody, with the ground's friction.
//! - **Objects.** One free body per object (`<freejoint/>`), a `sphere` or a `box` of its
//!   mass; its starting velocity is written in a comment (MJCF sets velocities only in a
//!   keyframe).
//! - **Friction.** The ground's own coefficient when the world sets one; its patches are not
//!   exported (a comment lists them).
//! - **Water.** `<option>` gets `gravity="0 0 0"`, water's density and the world's viscosity,
//!   with a comment: MuJoCo's viscous model (Stokes drag on each body's equivalent box) is not
//!   Ontogeny's resistance on every face.

use std::fmt::Write as _;

use nalgebra::{UnitQuaternion, Vector3};

use super::mjcf_numbers::{coordinates, numbers, quat, vec3, z_up};
use crate::sim::terrain::{Cuboid, Terrain};
use crate::sim::world_spec::{Medium, ObjectShape};

/// Water's density (kg/m³) written for a world in water.
const WATER_DENSITY: f64 = 1000.0;

/// The `<option>` attributes of `terrain`'s medium: none in air; in water, no gravity, water's
/// density and the world's viscosity.
pub(super) fn medium_attributes(terrain: &Terrain) -> Option<String> {
    match terrain.spec().medium {
        Medium::Air => None,
        Medium::Water { viscosity } => Some(format!(
            "gravity=\"0 0 0\" density=\"{}\" viscosity=\"{}\"",
            numbers(&[WATER_DENSITY]),
            numbers(&[viscosity])
        )),
    }
}

/// The comment written beside a world in water's `<option>`.
pub(super) const WATER_NOTE: &str = "<!-- Water: MuJoCo's viscosity is Stokes drag on each \
body's equivalent box, not Ontogeny's resistance -k*A*(v.n)*n on every face of every part; \
the viscosity is Ontogeny's k. -->";

/// The ground's friction attribute's value: the world's own ground coefficient when it sets
/// one, else `friction` (the simulator's), with MuJoCo's default torsional and rolling
/// friction after it (`rest`).
pub(super) fn ground_friction(terrain: &Terrain, friction: &str, rest: &str) -> String {
    match &terrain.spec().friction {
        Some(ground) => format!("{} {rest}", numbers(&[ground.coefficient])),
        None => friction.to_string(),
    }
}

/// The `<asset>` of `terrain`'s rough ground, when it has one.
pub(super) fn write_assets(w: &mut String, terrain: &Terrain) {
    let Some(field) = terrain.heightfield() else {
        return;
    };
    let (lo, hi) = span(&field.heights);
    let range = hi - lo;
    let n = field.samples;
    // MuJoCo's rows run from −y to +y, that is from +z to −z in Ontogeny's axes.
    let mut elevation = Vec::with_capacity(n * n);
    for row in (0..n).rev() {
        for column in 0..n {
            let h = field.heights[row * n + column];
            elevation.push(if range > 0.0 { (h - lo) / range } else { 0.0 });
        }
    }
    let _ = writeln!(w, "  <asset>");
    let _ = writeln!(
        w,
        "    <hfield name=\"rough\" nrow=\"{n}\" ncol=\"{n}\" size=\"{}\" elevation=\"{}\"/>",
        numbers(&[field.side / 2.0, field.side / 2.0, range.max(1e-9), 1.0]),
        coordinates(&elevation)
    );
    let _ = writeln!(w, "  </asset>");
}

/// The lowest and highest of `values`.
fn span(values: &[f64]) -> (f64, f64) {
    values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}

/// A `box` geom on the worldbody for `cuboid`.
fn write_box(w: &mut String, name: &str, cuboid: &Cuboid, friction: &str) {
    let turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -cuboid.direction.to_radians());
    let _ = writeln!(
        w,
        "    <geom name=\"{name}\" type=\"box\" pos=\"{}\" quat=\"{}\" size=\"{}\" friction=\"{friction}\"/>",
        vec3(&(z_up() * Vector3::from(cuboid.centre))),
        quat(&(z_up() * turn)),
        coordinates(&cuboid.half)
    );
}

/// Writes `terrain`'s ground, obstacles and objects on the worldbody, with `friction` (the
/// ground's) on the ground and obstacles and `object_friction` on the objects.
pub(super) fn write_world(
    w: &mut String,
    terrain: &Terrain,
    friction: &str,
    object_friction: &str,
) {
    let spec = terrain.spec();
    if let Some(patches) = spec.friction.as_ref().filter(|f| !f.patches.is_empty()) {
        let _ = writeln!(
            w,
            "    <!-- The ground's {} friction patches are not exported. -->",
            patches.patches.len()
        );
    }
    if !spec.medium.is_air() {
        let _ = writeln!(w, "    <!-- Water: no ground. -->");
    } else if let Some(normal) = terrain.slope_normal() {
        let up = z_up() * Vector3::from(normal);
        let tilt = UnitQuaternion::rotation_between(&Vector3::z(), &up)
            .unwrap_or_else(UnitQuaternion::identity);
        let _ = writeln!(
            w,
            "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" quat=\"{}\" friction=\"{friction}\"/>",
            quat(&tilt)
        );
    } else if let Some(field) = terrain.heightfield() {
        let (lo, _) = span(&field.heights);
        let _ = writeln!(
            w,
            "    <geom name=\"ground\" type=\"hfield\" hfield=\"rough\" pos=\"0 0 {}\" friction=\"{friction}\"/>",
            coordinates(&[lo])
        );
        for (k, slab) in terrain.ground_boxes().iter().enumerate() {
            write_box(w, &format!("level{k}"), slab, friction);
        }
    } else {
        let _ = writeln!(
            w,
            "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" pos=\"0 0 {}\" friction=\"{friction}\"/>",
            coordinates(&[terrain.base().unwrap_or(0.0)])
        );
        for (k, step) in terrain.ground_boxes().iter().enumerate() {
            write_box(w, &format!("step{k}"), step, friction);
        }
    }
    for (k, obstacle) in terrain.obstacle_boxes().iter().enumerate() {
        write_box(w, &format!("obstacle{k}"), obstacle, friction);
    }
    for (k, object) in terrain.objects().iter().enumerate() {
        let (kind, size) = match object.shape {
            ObjectShape::Ball => ("sphere", numbers(&[object.half])),
            ObjectShape::Box => ("box", numbers(&[object.half; 3])),
        };
        let velocity = z_up() * Vector3::from(object.velocity);
        if velocity.norm() > 0.0 {
            let _ = writeln!(
                w,
                "    <!-- object{k} starts with velocity {} (m/s). -->",
                vec3(&velocity)
            );
        }
        let _ = writeln!(
            w,
            "    <body name=\"object{k}\" pos=\"{}\">",
            vec3(&(z_up() * Vector3::from(object.centre)))
        );
        let _ = writeln!(w, "      <freejoint/>");
        let _ = writeln!(
            w,
            "      <geom name=\"object{k}\" type=\"{kind}\" size=\"{size}\" mass=\"{}\" friction=\"{object_friction}\"/>",
            numbers(&[object.mass])
        );
        let _ = writeln!(w, "    </body>");
    }
}
