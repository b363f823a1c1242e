//! The drawing of a creature's neural network beside its body: neurons on a circle coloured
//! by role and labelled with what they do, links by sign and weight.

use tiny_skia::{PathBuilder, Pixmap, Transform};

use super::palette::{ACTUATOR, INK, NEURON, OSCILLATOR, PANEL, SENSOR, paint, solid};
use super::pen::{fill, stroke_width};
use super::text::{draw_text, fit, text_width};
use crate::creature::{Actuator, Creature, JointKind, Neuron, NeuronFunction, Role, Sensor};

/// A neuron function's name as files spell it (`"sum-greater"`).
fn function_name(function: NeuronFunction) -> String {
    serde_json::to_value(function)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

/// What a joint's degree of freedom is called in a label: the joint's kind and number
/// (`"hinge j3"`), with the axis when the joint has more than one (`"universal j2 axis 1"`).
fn joint_label(creature: &Creature, joint: usize, dof: usize) -> String {
    let Some(kind) = creature.joints.get(joint).map(|j| j.kind) else {
        return format!("joint j{joint}");
    };
    let name = match kind {
        JointKind::Revolute => "hinge".to_string(),
        JointKind::Spherical => "ball".to_string(),
        kind => serde_json::to_value(kind)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default(),
    };
    if kind.dof() > 1 {
        format!("{name} j{joint} axis {dof}")
    } else {
        format!("{name} j{joint}")
    }
}

/// What a neuron of `creature` does, in a few words: a sensor what it reads (`"touch p1"`,
/// `"angle hinge j0"`), an actuator the joint it drives (`"hinge j3"`, `"universal j2 axis 1"`)
/// or what else it does (`"secrete 0"`), a hidden neuron its function (`"oscillator"`), as the
/// viewer labels them.
pub(super) fn neuron_label(creature: &Creature, neuron: &Neuron) -> String {
    let function = function_name(neuron.function);
    match neuron.role {
        Role::Sensor { sensor } => match sensor {
            Sensor::Touch { part, .. } => format!("touch p{part}"),
            Sensor::Angle { joint, dof } => format!("angle {}", joint_label(creature, joint, dof)),
            Sensor::Chemical { slot } => format!("chemical {slot}"),
            Sensor::Target => "target".to_string(),
        },
        Role::Actuator { actuator } => match actuator {
            Actuator::Joint { joint, dof } => joint_label(creature, joint, dof),
            Actuator::Secrete { slot } => format!("secrete {slot}"),
            Actuator::Release => "release".to_string(),
        },
        Role::Hidden => function,
    }
}

/// Draws the brain into `(x, y, w, h)`: neurons on a circle — sensors green, actuators red,
/// oscillators purple, other neurons blue — and links as lines, dark for positive weights and
/// red for negative, thicker for larger weights, with a dot at the receiving end — each
/// neuron labelled with what it does ([`neuron_label`]) where the label has room.
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
    let mut placed: Vec<(f32, f32, f32)> = Vec::new();
    for (i, neuron) in neurons.iter().enumerate() {
        let (x, y) = place(i);
        // Centred above a neuron in the upper half of the circle, below one in the lower
        // half, inside the panel.
        let label = fit(&neuron_label(creature, neuron), rw - 4.0, 1.0);
        let width = text_width(&label, 1.0);
        let left = (x - width / 2.0).clamp(rx + 2.0, (rx + rw - width - 2.0).max(rx + 2.0));
        let upper = n > 1 && y < cy - 1.0;
        let mut top = if upper { y - dot - 12.0 } else { y + dot + 4.0 };
        // A line further out while it would cover a label already written.
        let covers = |top: f32, placed: &[(f32, f32, f32)]| {
            placed.iter().any(|&(l, t, w)| {
                left < l + w + 4.0 && l < left + width + 4.0 && (top - t).abs() < 10.0
            })
        };
        for _ in 0..3 {
            if !covers(top, &placed) {
                break;
            }
            top += if upper { -10.0 } else { 10.0 };
        }
        // A dense brain: a label with no free place, or outside the panel, is left out
        // rather than drawn over others.
        if covers(top, &placed) || top < ry + 1.0 || top + 9.0 > ry + rh {
            continue;
        }
        placed.push((left, top, width));
        draw_text(pixmap, (left, top), &label, 1.0, INK, true);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::develop::creature_from_commands;

    #[test]
    fn neurons_are_labelled_with_the_joint_they_drive() {
        let c = creature_from_commands("forward(1) revolute2 forward(1) output(1)").unwrap();
        let labels: Vec<String> = c
            .brain
            .neurons
            .iter()
            .map(|n| neuron_label(&c, n))
            .collect();
        assert!(labels.contains(&"hinge j0".to_string()), "{labels:?}");
        assert!(
            labels.iter().all(|l| !l.starts_with("linear")),
            "{labels:?}"
        );
        let mut hidden = c.brain.neurons[0].clone();
        hidden.role = Role::Hidden;
        hidden.function = NeuronFunction::SumGreater;
        assert_eq!(neuron_label(&c, &hidden), "sum-greater");
        hidden.role = Role::Sensor {
            sensor: Sensor::Angle { joint: 0, dof: 0 },
        };
        assert_eq!(neuron_label(&c, &hidden), "angle hinge j0");
        // A joint of two axes names the axis.
        let mut two = c.clone();
        two.joints[0].kind = JointKind::Universal;
        hidden.role = Role::Sensor {
            sensor: Sensor::Angle { joint: 0, dof: 1 },
        };
        assert_eq!(neuron_label(&two, &hidden), "angle universal j0 axis 1");
        hidden.role = Role::Actuator {
            actuator: Actuator::Joint { joint: 0, dof: 0 },
        };
        assert_eq!(neuron_label(&c, &hidden), "hinge j0");
        hidden.role = Role::Actuator {
            actuator: Actuator::Joint { joint: 7, dof: 0 },
        };
        assert_eq!(neuron_label(&c, &hidden), "joint j7");
    }
}
