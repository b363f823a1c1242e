//! A creature summarised as `ontogeny grow` reports it: parts, joints by kind, brain, mass,
//! bounding box, validity and problems; as JSON (serde) or as text.

use std::collections::BTreeMap;

use serde::Serialize;

use super::{Creature, Problem, Role};

/// `n` and the noun, singular for one (`"1 neuron"`, `"3 neurons"`); `noun` is the singular
/// and the plural adds an `s`.
pub fn counted(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// What `grow` says about a creature: the last frame of growing `file`, at developmental
/// time `t`, after `frames` frames.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// The grammar's name.
    pub file: String,
    /// Developmental time of the frame.
    pub t: f64,
    /// Frames grown.
    pub frames: usize,
    /// Parts.
    pub parts: usize,
    /// Joints by kind (`revolute1`, ...).
    pub joints: BTreeMap<String, usize>,
    /// Neurons.
    pub neurons: usize,
    /// Links between neurons.
    pub links: usize,
    /// Sensor neurons.
    pub sensors: usize,
    /// Actuator neurons.
    pub actuators: usize,
    /// Mass (kg).
    pub mass: f64,
    /// The axis-aligned bounding box, lowest then highest corner.
    pub bounding_box: [[f64; 3]; 2],
    /// Whether the creature can be simulated.
    pub valid: bool,
    /// Whether it has a picture's warning about what physics refuses
    /// ([`Problem::is_picture_only`]).
    pub picture_only: bool,
    /// Its problems, as people read them.
    pub problems: Vec<String>,
}

impl Summary {
    /// The summary of `c`, the last of `frames` frames of growing `file` to time `t`.
    pub fn of(file: &str, t: f64, frames: usize, c: &Creature) -> Summary {
        let mut joints = BTreeMap::new();
        for j in &c.joints {
            let name = serde_json::to_value(j.kind)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_default();
            *joints.entry(name).or_insert(0) += 1;
        }
        let (lo, hi) = c.bounding_box();
        let count = |f: fn(&Role) -> bool| c.brain.neurons.iter().filter(|n| f(&n.role)).count();
        Summary {
            file: file.to_string(),
            t,
            frames,
            parts: c.parts.len(),
            joints,
            neurons: c.brain.neurons.len(),
            links: c.brain.links.len(),
            sensors: count(|r| matches!(r, Role::Sensor { .. })),
            actuators: count(|r| matches!(r, Role::Actuator { .. })),
            mass: c.mass(),
            bounding_box: [[lo.x, lo.y, lo.z], [hi.x, hi.y, hi.z]],
            valid: c.is_valid(),
            picture_only: c.problems.iter().any(Problem::is_picture_only),
            problems: super::repeats::said_once(
                no_part(c)
                    .into_iter()
                    .chain(c.problems.iter().map(Problem::to_string)),
            ),
        }
    }

    /// The summary as text, a line for each of: the growth, parts and joints, brain, mass and
    /// bounding box, validity, and each problem.
    pub fn text(&self) -> String {
        let s = self;
        let joints: Vec<String> = s.joints.iter().map(|(k, n)| format!("{n} {k}")).collect();
        let [lo, hi] = s.bounding_box;
        let mut lines = vec![
            format!(
                "{}: grown to t = {} in {}",
                s.file,
                crate::number::format_number(s.t),
                counted(s.frames, "frame")
            ),
            format!(
                "parts: {}   joints: {}",
                s.parts,
                if joints.is_empty() {
                    "none".to_string()
                } else {
                    joints.join(", ")
                }
            ),
            format!(
                "brain: {} ({}, {}), {}",
                counted(s.neurons, "neuron"),
                counted(s.sensors, "sensor"),
                counted(s.actuators, "actuator"),
                counted(s.links, "link")
            ),
            format!(
                "mass: {:.4}   bounding box: ({:.3}, {:.3}, {:.3}) to ({:.3}, {:.3}, {:.3})",
                s.mass, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
            ),
            format!(
                "valid: {}",
                match (s.valid, s.picture_only) {
                    (false, _) => "no",
                    (true, false) => "yes",
                    (true, true) => "as a picture only (eval and evolve refuse it)",
                }
            ),
        ];
        lines.extend(s.problems.iter().map(|p| format!("  {p}")));
        lines.join("\n")
    }
}

/// The problem of a creature without parts, which development does not list (growth may
/// start from nothing): there is nothing to simulate.
fn no_part(c: &Creature) -> Option<String> {
    c.parts.is_empty().then(|| {
        "error: no part: the string builds nothing (a part comes from forward or its maturing twin mforward; see docs/reference/commands.md)".to_string()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_of_a_thing_is_counted_in_the_singular() {
        assert_eq!(counted(1, "neuron"), "1 neuron");
        assert_eq!(counted(0, "neuron"), "0 neurons");
        assert_eq!(counted(2, "link"), "2 links");
    }
}
