//! Water resistance: in water ([`Medium::Water`](super::Medium::Water)) there is no ground and
//! no gravity, and every face of every part (parts are boxes: six faces) that moves into the
//! water in front of it is pushed back by a viscous resistance
//!
//! F = −k · A · (v·n) · n, only when v·n > 0,
//!
//! A the face's area, n its outward normal, v the velocity of the face's centre
//! (v_body + ω × r), applied at the face's centre, so that it turns the body as well as
//! slowing it. Each face is taken as [`PATCHES`] × [`PATCHES`] patches, each one such a
//! face, so that a turning part is resisted too. This is Sims' model (1994, "Evolving virtual creatures", section 5): a face
//! moving away from the water behind it (v·n < 0) feels nothing, so a plate moving face-on
//! at speed v feels k·A·v from its front face alone. The term is called water resistance, not
//! drag (Hornby & Pollack's sliding term, [`super::DragMeter`]). It only ever takes energy
//! away: its power at each face is −k·A·(v·n)² ≤ 0.

use ::nalgebra::Vector3;
use rapier3d::math::Vector;

use super::parts::vector;
use super::world::{World, to_na};
use crate::creature::PartId;

/// The default viscosity k (N·s/m³): the linear resistance that matches the quadratic drag
/// of a flat face in real water, ½·ρ·C_d·v² with ρ = 1000 kg/m³ and C_d ≈ 1, at 1 m/s —
/// the speed of a limb's stroke under the default muscle strength. A part of default density
/// (1000 kg/m³) and thickness t moving face-on slows with a time constant ρ·t / k: 0.1 s for
/// a part 5 cm thick, 0.5 s for one 25 cm thick.
pub const DEFAULT_VISCOSITY: f64 = 500.0;

/// The largest viscosity a config may set (N·s/m³): beyond it, the resistance on a thin part
/// would reverse its velocity within one physics substep.
pub const MAX_VISCOSITY: f64 = 10_000.0;

/// Each face is cut into `PATCHES` × `PATCHES` equal patches, and each patch feels the
/// resistance at its own centre: a body moving without turning feels exactly −k·A·(v·n)·n on
/// each face moving into the water, and a turning one feels the resistance of the parts of
/// its faces that move into the water (a box turning about its centre would feel none if
/// each face were taken at its centre, whose velocity lies in the face). With 3 × 3 patches,
/// a face turning about its own centre line feels 8/9 of the exact integral's torque.
pub const PATCHES: usize = 3;

/// The resistance on one face of area `area` (m²), outward normal `normal` (a unit vector),
/// whose centre moves at `velocity` (m/s), in water of viscosity `viscosity` (N·s/m³):
/// −k·A·(v·n)·n when the face moves into the water (v·n > 0), nothing otherwise.
pub fn face_resistance(
    viscosity: f64,
    area: f64,
    normal: Vector3<f64>,
    velocity: Vector3<f64>,
) -> Vector3<f64> {
    let into = velocity.dot(&normal);
    if into > 0.0 {
        -viscosity * area * into * normal
    } else {
        Vector3::zeros()
    }
}

impl World {
    /// The viscosity of the water the creature swims in (N·s/m³), or `None` in air.
    pub fn water_viscosity(&self) -> Option<f64> {
        self.water
    }

    /// Sets the forces of water resistance on every creature body for the next physics
    /// substep: clears the bodies' user forces (and their user torques when `reset_torques`:
    /// torque muscles clear them themselves), then adds each patch's resistance
    /// ([`PATCHES`]), as a force and a torque about the body's centre of mass. Allocates
    /// nothing.
    pub(super) fn apply_water_resistance(&mut self, viscosity: f64, reset_torques: bool) {
        for &b in &self.creature_bodies {
            let body = &mut self.bodies[b];
            body.reset_forces(false);
            if reset_torques {
                body.reset_torques(false);
            }
        }
        for i in 0..self.parts.len() {
            let slot = &self.parts[PartId(i)];
            let (handle, size) = (slot.body, slot.size);
            let pose = self.part_world_pose(PartId(i));
            let body = &self.bodies[handle];
            let (force, torque) = part_resistance(
                viscosity,
                size,
                (
                    to_na(pose.translation),
                    [Vector::X, Vector::Y, Vector::Z].map(|a| to_na(pose.rotation * a)),
                ),
                (
                    to_na(body.center_of_mass()),
                    to_na(body.linvel()),
                    to_na(body.angvel()),
                ),
            );
            let body = &mut self.bodies[handle];
            body.add_force(vector(&force), true);
            body.add_torque(vector(&torque), true);
        }
    }
}

/// The water resistance on a box of `size` (m) whose centre and axes are `(centre, axes)`,
/// part of a body whose centre of mass, velocity and angular velocity are `(com, linvel,
/// angvel)`: the total force (N) and its torque about the centre of mass (N·m), summed over
/// the [`PATCHES`] × [`PATCHES`] patches of each of its six faces.
pub fn part_resistance(
    viscosity: f64,
    size: Vector3<f64>,
    (centre, axes): (Vector3<f64>, [Vector3<f64>; 3]),
    (com, linvel, angvel): (Vector3<f64>, Vector3<f64>, Vector3<f64>),
) -> (Vector3<f64>, Vector3<f64>) {
    let (mut force, mut torque) = (Vector3::zeros(), Vector3::zeros());
    let cut = PATCHES as f64;
    for a in 0..3 {
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        let area = size[b] * size[c] / (cut * cut);
        for sign in [1.0, -1.0] {
            let normal = axes[a] * sign;
            let face = centre + normal * (size[a] / 2.0);
            for j in 0..PATCHES {
                for l in 0..PATCHES {
                    let u = ((j as f64 + 0.5) / cut - 0.5) * size[b];
                    let w = ((l as f64 + 0.5) / cut - 0.5) * size[c];
                    let arm = face + axes[b] * u + axes[c] * w - com;
                    let velocity = linvel + angvel.cross(&arm);
                    let push = face_resistance(viscosity, area, normal, velocity);
                    force += push;
                    torque += arm.cross(&push);
                }
            }
        }
    }
    (force, torque)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::{Medium, SimOptions, WorldSpec};
    use rapier3d::prelude::RigidBodyHandle;

    #[test]
    fn a_face_moving_into_the_water_is_pushed_back_and_one_moving_away_is_not() {
        let n = Vector3::new(0.0, 0.0, 1.0);
        let pushed = face_resistance(500.0, 0.5, n, Vector3::new(3.0, 0.0, 2.0));
        assert_eq!(pushed, Vector3::new(0.0, 0.0, -500.0 * 0.5 * 2.0));
        let away = face_resistance(500.0, 0.5, n, Vector3::new(3.0, 0.0, -2.0));
        assert_eq!(away, Vector3::zeros());
        let sliding = face_resistance(500.0, 0.5, n, Vector3::new(3.0, 0.0, 0.0));
        assert_eq!(sliding, Vector3::zeros());
    }

    /// The resistance on a plate 1 m along x, 0.05 m along y, 1 m along z, at the origin
    /// with its axes the world's, moving at `linvel` and turning at `angvel`.
    fn plate(
        viscosity: f64,
        linvel: Vector3<f64>,
        angvel: Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        part_resistance(
            viscosity,
            Vector3::new(1.0, 0.05, 1.0),
            (Vector3::zeros(), [Vector3::x(), Vector3::y(), Vector3::z()]),
            (Vector3::zeros(), linvel, angvel),
        )
    }

    #[test]
    fn a_plate_moving_face_on_feels_k_a_v_and_edge_on_twenty_times_less() {
        // Face-on along +y at 2 m/s: only the +y face (1 m²) moves into the water, so
        // F = −k·1·2 = −1000 N along y; the −y face moves away and the four edges slide.
        let (force, torque) = plate(500.0, Vector3::new(0.0, 2.0, 0.0), Vector3::zeros());
        assert!(
            (force - Vector3::new(0.0, -1000.0, 0.0)).norm() < 1e-9,
            "{force}"
        );
        assert!(torque.norm() < 1e-9, "{torque}");
        // Edge-on along +x: the +x edge, 0.05 m², feels −k·0.05·2 = −50 N.
        let (force, torque) = plate(500.0, Vector3::new(2.0, 0.0, 0.0), Vector3::zeros());
        assert!(
            (force - Vector3::new(-50.0, 0.0, 0.0)).norm() < 1e-9,
            "{force}"
        );
        assert!(torque.norm() < 1e-9, "{torque}");
    }

    #[test]
    fn a_plate_turning_about_its_centre_feels_the_torque_of_its_patches() {
        // Turning at ω about x: on each big face (L = 1 m), the row of 3 patches at
        // z = ∓L/3 moves into the water at ωL/3, each of area L²/9 at a lever L/3: a torque
        // of 3·k·(L²/9)·(ωL/3)·(L/3) = k·ω·L⁴/27 per face. Each edge normal to z (t = 0.05 m)
        // gives k·ω·L·t³/27 the same way; the edges normal to x slide. In all
        // −2·k·ω·(L⁴ + L·t³)/27 about x, and no force.
        let (force, torque) = plate(500.0, Vector3::zeros(), Vector3::new(2.0, 0.0, 0.0));
        let by_hand = -2.0 * 500.0 * 2.0 * (1.0 + 0.05f64.powi(3)) / 27.0;
        assert!(force.norm() < 1e-9, "{force}");
        assert!(
            (torque - Vector3::new(by_hand, 0.0, 0.0)).norm() < 1e-9,
            "{torque}"
        );
    }

    /// A plate 1 m by 1 m, 0.05 m thick, in water of viscosity `k`: its world, its body, its
    /// mass, and its axes in the world (along its length, its thickness, its width).
    fn plate_in_water(k: f64) -> (World, RigidBodyHandle, f64, [Vector3<f64>; 3]) {
        let creature =
            crate::develop::creature_from_commands("width(1) thickness(0.05) forward(1)").unwrap();
        let water = WorldSpec {
            medium: Medium::Water { viscosity: k },
            ..WorldSpec::default()
        };
        let world = World::in_world(&creature, &SimOptions::default(), &water).unwrap();
        assert_eq!(world.part_size(PartId(0)), Vector3::new(1.0, 0.05, 1.0));
        let body = world.parts[PartId(0)].body;
        let mass = world.bodies[body].mass() as f64;
        let (_, rotation) = world.part_pose(PartId(0));
        let axes = [Vector3::x(), Vector3::y(), Vector3::z()].map(|a| rotation * a);
        (world, body, mass, axes)
    }

    #[test]
    fn a_plate_launched_face_on_slows_exponentially() {
        // m dv/dt = −k·A·v: v(t) = v0·exp(−k·A·t/m). Rapier's step is semi-implicit Euler
        // with the force held over each substep of h = 1/240 s: v_n = v0·(1 − λh)^n exactly,
        // λ = k·A/m, which differs from the exponential by about λ²·h·t/2 relative (0.21%
        // here); we allow 0.5%, and 1e-4 against the discrete formula (single precision).
        let k = 50.0;
        let (mut world, body, mass, axes) = plate_in_water(k);
        assert!((mass - 50.0).abs() < 1e-3, "{mass}");
        world.bodies[body].set_linvel(super::vector(&(axes[1] * 2.0)), true);
        for _ in 0..60 {
            world.step(false).unwrap();
        }
        let speed = to_na(world.bodies[body].linvel()).dot(&axes[1]);
        let lambda = k * 1.0 / mass;
        let exact = 2.0 * (-lambda).exp();
        let discrete = 2.0 * (1.0 - lambda / 240.0).powi(240);
        assert!(
            (speed - discrete).abs() < 1e-4 * discrete,
            "{speed} against {discrete}"
        );
        assert!(
            (speed - exact).abs() < 5e-3 * exact,
            "{speed} against {exact}"
        );
        // It went straight: nothing turned it, nothing pushed it sideways.
        assert!(to_na(world.bodies[body].angvel()).norm() < 1e-6);
        assert!(to_na(world.bodies[body].linvel()).cross(&axes[1]).norm() < 1e-6);
    }

    #[test]
    fn a_turning_plate_slows_as_its_torque_by_hand_says() {
        // About its length: I = m·(t² + L²)/12, the torque −c·ω with c = 2·k·(L⁴ + L·t³)/27
        // (see above): ω(t) = ω0·exp(−c·t/I), within 0.5% after 1 s.
        let k = 50.0;
        let (mut world, body, mass, axes) = plate_in_water(k);
        world.bodies[body].set_angvel(super::vector(&(axes[0] * 3.0)), true);
        for _ in 0..60 {
            world.step(false).unwrap();
        }
        let spin = to_na(world.bodies[body].angvel()).dot(&axes[0]);
        let inertia = mass * (0.05f64.powi(2) + 1.0) / 12.0;
        let c = 2.0 * k * (1.0 + 0.05f64.powi(3)) / 27.0;
        let by_hand = 3.0 * (-c / inertia).exp();
        assert!(
            (spin - by_hand).abs() < 5e-3 * by_hand,
            "{spin} against {by_hand}"
        );
    }

    #[test]
    fn a_box_at_rest_in_water_stays_where_it_is() {
        let (mut world, body, _, _) = plate_in_water(DEFAULT_VISCOSITY);
        let start = world.part_position(PartId(0));
        assert!(start.norm() < 1e-6, "centred on the origin: {start}");
        for _ in 0..120 {
            world.step(true).unwrap();
        }
        assert_eq!(world.part_position(PartId(0)), start);
        assert_eq!(to_na(world.bodies[body].linvel()), Vector3::zeros());
        assert_eq!(world.peak_unexplained_energy(), 0.0);
    }
}
