//! The drawing of a creature's neural network beside its body: neurons on a circle coloured
//! by role, links by sign and weight.

use tiny_skia::{PathBuilder, Pixmap, Transform};

use super::palette::{ACTUATOR, NEURON, OSCILLATOR, PANEL, SENSOR, paint, solid};
use super::pen::{fill, stroke_width};
use crate::creature::{Creature, NeuronFunction, Role};

/// Draws the brain into `(x, y, w, h)`: neurons on a circle — sensors green, actuators red,
/// oscillators purple, other neurons blue — and links as lines, dark for positive weights and
/// red for negative, thicker for larger weights, with a dot at the receiving end.
pub(super) fn draw_brain(pixmap: &mut Pixmap, creature: &Creature, region: (f32, f32, f32, f32)) {
    let (rx, ry, rw, rh) = region;
    if let Some(rect) = tiny_skia::Rect::from_xywh(rx, ry, rw, rh) {
        pixmap.fill_rect(rect, &solid(PANEL), Transform::identity(), None);
    }
    let neurons = &creature.brain.neurons;
    if neurons.is_empty() {
        return;
    }
    let (cx, cy) = (rx + rw / 2.0, ry + rh / 2.0);
    let radius = 0.36 * rw.min(rh);
    let n = neurons.len();
    let place = |i: usize| {
        if n == 1 {
            return (cx, cy);
        }
        let a = std::f32::consts::TAU * i as f32 / n as f32 - std::f32::consts::FRAC_PI_2;
        (cx + radius * a.cos(), cy + radius * a.sin())
    };
    let dot = (0.3 * radius / (n as f32).sqrt()).clamp(3.0, 9.0);
    for link in &creature.brain.links {
        let (ax, ay) = place(link.from);
        let (bx, by) = place(link.to);
        let width = (1.0 + 1.5 * link.weight.abs().min(3.0)) as f32;
        let colour = if link.weight >= 0.0 {
            paint(40, 40, 60, 160)
        } else {
            paint(210, 50, 50, 170)
        };
        let stroke = stroke_width(width);
        let mut pb = PathBuilder::new();
        if link.from == link.to {
            pb.push_circle(ax, ay - dot * 1.6, dot * 1.2);
        } else {
            pb.move_to(ax, ay);
            pb.line_to(bx, by);
        }
        if let Some(path) = pb.finish() {
            pixmap.stroke_path(&path, &colour, &stroke, Transform::identity(), None);
        }
        if link.from != link.to {
            // A small dot near the receiving neuron shows the direction.
            let (dx, dy) = (bx - ax, by - ay);
            let len = (dx * dx + dy * dy).sqrt().max(1e-3);
            let (px, py) = (bx - dx / len * dot * 1.6, by - dy / len * dot * 1.6);
            if let Some(path) = PathBuilder::from_circle(px, py, width.max(2.0)) {
                fill(pixmap, &path, &colour, Transform::identity());
            }
        }
    }
    for (i, neuron) in neurons.iter().enumerate() {
        let (x, y) = place(i);
        let colour = solid(match (neuron.role, neuron.function) {
            (Role::Sensor { .. }, _) => SENSOR,
            (Role::Actuator { .. }, _) => ACTUATOR,
            (_, NeuronFunction::Oscillator) => OSCILLATOR,
            _ => NEURON,
        });
        if let Some(path) = PathBuilder::from_circle(x, y, dot) {
            fill(pixmap, &path, &colour, Transform::identity());
            let stroke = stroke_width(1.0);
            pixmap.stroke_path(
                &path,
                &paint(20, 20, 20, 255),
                &stroke,
                Transform::identity(),
                None,
            );
        }
    }
}
