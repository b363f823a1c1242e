//! The building commands a module name stands for.

use std::f64::consts::FRAC_PI_2;

use nalgebra::Vector3;

use crate::creature::JointKind;

/// An edge-encoding (brain) command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BrainOp {
    /// `split(w)`
    Split,
    /// `duplicate(w)`
    Duplicate,
    /// `loop(w)`
    Loop,
    /// `merge(n)`
    Merge,
    /// `next(n)`
    Next,
    /// `parent(n)`
    Parent,
    /// `output(w)`
    Output,
    /// `reverse`
    Reverse,
    /// `setfunc(n)`: the target's function, from [`NeuronFunction::SETFUNC`]
    ///
    /// [`NeuronFunction::SETFUNC`]: crate::creature::NeuronFunction::SETFUNC
    SetFunc,
    /// `bias(b)`: sets the target's bias (Ontogeny's addition; neither Hornby & Pollack nor
    /// Matos & Arita have one)
    Bias,
    /// `cut`
    Cut,
    /// `weight(n)`: adds n to the weight (Matos & Arita's offset-weight)
    Weight,
    /// `increase(n)` (Hornby)
    Increase,
    /// `decrease(n)` (Hornby)
    Decrease,
    /// `touch`
    Touch,
    /// `angle`
    Angle,
    /// `chem(i)`
    Chem,
    /// `target`
    Target,
    /// `secrete(i)`
    Secrete,
    /// `release`
    Release,
}

/// What a module makes the builder do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Command {
    /// `forward(l)` / `mforward(l)`
    Forward {
        /// Made by the maturing twin.
        maturing: bool,
    },
    /// `backward`
    Backward,
    /// A turn about one of the turtle's axes by n × 90° (`sign` gives the direction).
    Turn {
        /// The turtle's local axis.
        axis: Vector3<f64>,
        /// +1 or −1.
        sign: f64,
    },
    /// `revolute1`, `revolute2`, `twist90`, `twist180`: the next forward's joint.
    Joint {
        /// The joint's kind.
        kind: JointKind,
        /// Its limits (radians).
        limits: (f64, f64),
        /// Made by the maturing twin.
        maturing: bool,
    },
    /// `width(w)`
    Width,
    /// `thickness(h)`
    Thickness,
    /// `[`
    Push,
    /// `]`
    Pop,
    /// `{`
    RepeatStart,
    /// `}(n)`
    RepeatEnd,
    /// A brain command.
    Brain(BrainOp),
}

/// The command a module name stands for; `None` for control tokens and anything else.
pub fn command_of(name: &str) -> Option<Command> {
    match name {
        "[" => return Some(Command::Push),
        "]" => return Some(Command::Pop),
        "{" => return Some(Command::RepeatStart),
        "}" => return Some(Command::RepeatEnd),
        _ => {}
    }
    if let Some(c) = plain(name, false) {
        return Some(c);
    }
    let rest = name.strip_prefix('m')?;
    plain(rest, true)
}

fn plain(name: &str, maturing: bool) -> Option<Command> {
    let turn = |axis: Vector3<f64>, sign: f64| Some(Command::Turn { axis, sign });
    let joint = |kind, limits| {
        Some(Command::Joint {
            kind,
            limits,
            maturing,
        })
    };
    let brain = |op| Some(Command::Brain(op));
    match name {
        "forward" => Some(Command::Forward { maturing }),
        "backward" => Some(Command::Backward),
        "left" => turn(Vector3::y(), 1.0),
        "right" => turn(Vector3::y(), -1.0),
        "up" => turn(Vector3::z(), 1.0),
        "down" => turn(Vector3::z(), -1.0),
        "clockwise" => turn(Vector3::x(), 1.0),
        "counterclockwise" => turn(Vector3::x(), -1.0),
        "revolute1" => joint(JointKind::Revolute, (0.0, FRAC_PI_2)),
        "revolute2" => joint(JointKind::Revolute, (-FRAC_PI_2, FRAC_PI_2)),
        "twist90" => joint(JointKind::Twist, (0.0, FRAC_PI_2)),
        "twist180" => joint(JointKind::Twist, (-FRAC_PI_2, FRAC_PI_2)),
        "width" => Some(Command::Width),
        "thickness" => Some(Command::Thickness),
        "split" => brain(BrainOp::Split),
        "duplicate" => brain(BrainOp::Duplicate),
        "loop" => brain(BrainOp::Loop),
        "merge" => brain(BrainOp::Merge),
        "next" => brain(BrainOp::Next),
        "parent" => brain(BrainOp::Parent),
        "output" => brain(BrainOp::Output),
        "reverse" => brain(BrainOp::Reverse),
        "setfunc" => brain(BrainOp::SetFunc),
        "bias" => brain(BrainOp::Bias),
        "cut" => brain(BrainOp::Cut),
        "weight" => brain(BrainOp::Weight),
        "increase" => brain(BrainOp::Increase),
        "decrease" => brain(BrainOp::Decrease),
        "touch" => brain(BrainOp::Touch),
        "angle" => brain(BrainOp::Angle),
        "chem" => brain(BrainOp::Chem),
        "target" => brain(BrainOp::Target),
        "secrete" => brain(BrainOp::Secrete),
        "release" => brain(BrainOp::Release),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_name_is_a_command_and_so_is_its_maturing_twin() {
        for name in crate::lang::BUILTIN_COMMANDS {
            assert!(command_of(name).is_some(), "{name}");
            assert!(command_of(&format!("m{name}")).is_some(), "m{name}");
        }
        assert_eq!(command_of("A"), None);
        assert_eq!(command_of("F"), None);
        assert_eq!(
            command_of("mforward"),
            Some(Command::Forward { maturing: true })
        );
    }
}
