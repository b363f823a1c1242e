//! Water resistance: in water ([`Medium::Water`](super::Medium::Water)) there is no ground and
//! no gravity, and every face of every part (parts are boxes: six faces) that moves into the
//! water in front of it is pushed back by a viscous resistance
//!
//! F = −k · A · (v·n) · n, only when v·n > 0,
//!
//! A the face's area, n its outward normal, v the velocity of the face's centre
//! (v_body + ω × r), applied at the face's centre, so that it turns the body as well as
//! slowing it. This is Sims' model (1994, "Evolving virtual creatures", section 5): a face
//! moving away from the water behind it (v·n < 0) feels nothing, so a plate moving face-on
//! at speed v feels k·A·v from its front face alone. The term is called water resistance, not
//! drag (Hornby & Pollack's sliding term, [`super::DragMeter`]). It only ever takes energy
//! away: its power at each face is −k·A·(v·n)² ≤ 0.

use ::nalgebra::Vector3;
use rapier3d::math::{Real, Vector};

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
    /// torque muscles clear them themselves), then adds each face's resistance at its centre.
    /// Allocates nothing.
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
            let pose = self.part_world_pose(i);
            let body = &self.bodies[handle];
            let areas = [size.y * size.z, size.x * size.z, size.x * size.y];
            let mut pushes = [(Vector::ZERO, Vector::ZERO); 6];
            for (axis, (local, area)) in [Vector::X, Vector::Y, Vector::Z]
                .into_iter()
                .zip(areas)
                .enumerate()
            {
                let half = size[axis] as Real / 2.0;
                for (side, sign) in [1.0 as Real, -1.0].into_iter().enumerate() {
                    let normal = pose.rotation * (local * sign);
                    let centre = pose.translation + normal * half;
                    let velocity = to_na(body.velocity_at_point(centre));
                    let force = face_resistance(viscosity, area, to_na(normal), velocity);
                    pushes[2 * axis + side] = (super::parts::vector(&force), centre);
                }
            }
            let body = &mut self.bodies[handle];
            for (force, centre) in pushes {
                body.add_force_at_point(force, centre, true);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
