//! What the builder does for each module name: the commands of the language's table
//! ([`crate::lang::commands`]), their maturing twins, and the brackets.

use std::f64::consts::FRAC_PI_2;

use nalgebra::Vector3;

use crate::creature::JointKind;
use crate::lang::commands::Command;

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
pub enum Action {
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

/// The action a module name stands for; `None` for control tokens and anything else.
pub fn command_of(name: &str) -> Option<Action> {
    match name {
        "[" => return Some(Action::Push),
        "]" => return Some(Action::Pop),
        "{" => return Some(Action::RepeatStart),
        "}" => return Some(Action::RepeatEnd),
        _ => {}
    }
    if let Some(command) = Command::from_name(name) {
        return Some(action(command, false));
    }
    let rest = name.strip_prefix('m')?;
    Command::from_name(rest).map(|command| action(command, true))
}

/// What `command` (or its maturing twin) makes the builder do.
fn action(command: Command, maturing: bool) -> Action {
    let turn = |axis: Vector3<f64>, sign: f64| Action::Turn { axis, sign };
    let joint = |kind, limits| Action::Joint {
        kind,
        limits,
        maturing,
    };
    match command {
        Command::Forward => Action::Forward { maturing },
        Command::Backward => Action::Backward,
        Command::Left => turn(Vector3::y(), 1.0),
        Command::Right => turn(Vector3::y(), -1.0),
        Command::Up => turn(Vector3::z(), 1.0),
        Command::Down => turn(Vector3::z(), -1.0),
        Command::Clockwise => turn(Vector3::x(), 1.0),
        Command::Counterclockwise => turn(Vector3::x(), -1.0),
        Command::Revolute1 => joint(JointKind::Revolute, (0.0, FRAC_PI_2)),
        Command::Revolute2 => joint(JointKind::Revolute, (-FRAC_PI_2, FRAC_PI_2)),
        Command::Twist90 => joint(JointKind::Twist, (0.0, FRAC_PI_2)),
        Command::Twist180 => joint(JointKind::Twist, (-FRAC_PI_2, FRAC_PI_2)),
        Command::Width => Action::Width,
        Command::Thickness => Action::Thickness,
        Command::Split => Action::Brain(BrainOp::Split),
        Command::Duplicate => Action::Brain(BrainOp::Duplicate),
        Command::Loop => Action::Brain(BrainOp::Loop),
        Command::Merge => Action::Brain(BrainOp::Merge),
        Command::Next => Action::Brain(BrainOp::Next),
        Command::Parent => Action::Brain(BrainOp::Parent),
        Command::Output => Action::Brain(BrainOp::Output),
        Command::Reverse => Action::Brain(BrainOp::Reverse),
        Command::Setfunc => Action::Brain(BrainOp::SetFunc),
        Command::Bias => Action::Brain(BrainOp::Bias),
        Command::Cut => Action::Brain(BrainOp::Cut),
        Command::Weight => Action::Brain(BrainOp::Weight),
        Command::Increase => Action::Brain(BrainOp::Increase),
        Command::Decrease => Action::Brain(BrainOp::Decrease),
        Command::Touch => Action::Brain(BrainOp::Touch),
        Command::Angle => Action::Brain(BrainOp::Angle),
        Command::Chem => Action::Brain(BrainOp::Chem),
        Command::Target => Action::Brain(BrainOp::Target),
        Command::Secrete => Action::Brain(BrainOp::Secrete),
        Command::Release => Action::Brain(BrainOp::Release),
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
            Some(Action::Forward { maturing: true })
        );
    }
}
