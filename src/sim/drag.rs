//! Hornby & Pollack's D_drag: how far a creature's parts are dragged along the ground.

use super::World;

/// Sums the distance the creature's parts slide along the ground, step by step: each
/// control step adds its duration times the mean of the sliding speed
/// ([`World::ground_sliding_speed`]) at its start and at its end (the trapezoid rule, so that
/// a part slowing steadily to a stop drags the distance it slid).
#[derive(Clone, Copy, Debug)]
pub struct DragMeter {
    /// The sliding speed after the last step (m/s).
    speed: f64,
    /// The distance dragged so far (m).
    dragged: f64,
}

impl DragMeter {
    /// Starts measuring from `world`'s present state: nothing dragged yet.
    pub fn start(world: &World) -> DragMeter {
        DragMeter {
            speed: world.ground_sliding_speed(),
            dragged: 0.0,
        }
    }

    /// Counts the control step of `dt` seconds `world` has just taken.
    pub fn after_step(&mut self, world: &World, dt: f64) {
        let speed = world.ground_sliding_speed();
        self.dragged += 0.5 * (self.speed + speed) * dt;
        self.speed = speed;
    }

    /// The distance dragged so far (m).
    pub fn dragged(&self) -> f64 {
        self.dragged
    }
}
