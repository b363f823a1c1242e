//! What the builder does for each module name: the commands of the language's table
//! ([`crate::lang::commands`]), their maturing twins, and the brackets.

use std::f64::consts::FRAC_PI_2;

use nalgebra::Vector3;

use crate::creature::JointKind;
use crate::lang::commands::Command;

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
    /// A brain command (edge encoding, sensors and effectors): one of the table's commands
    /// that are not the body's or a joint's.
    Brain(Command),
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
        brain => Action::Brain(brain),
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
