//! What the builder does for each module name: the commands of the language's table
//! ([`crate::lang::commands`]), their maturing twins, the textbook turtle's symbols, and the
//! brackets.

use std::f64::consts::FRAC_PI_2;

use nalgebra::Vector3;

use crate::creature::JointKind;
use crate::lang::commands::Command;

/// What a module makes the builder do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// `forward(l)` / `mforward(l)` / `F(l)`
    Forward {
        /// Made by the maturing twin.
        maturing: bool,
        /// The textbook's `F`: its default length is the file's `step:`.
        textbook: bool,
    },
    /// `f(l)`: the turtle moves without building; the next part starts a new piece.
    Move,
    /// `backward`
    Backward,
    /// A turn about one of the turtle's axes by n × 90°, or for the textbook's symbols by
    /// n degrees (`sign` gives the direction).
    Turn {
        /// The turtle's local axis.
        axis: Vector3<f64>,
        /// +1 or −1.
        sign: f64,
        /// The argument is in degrees, by default the file's `angle:` (the textbook's
        /// symbols); otherwise in quarter turns, by default 1.
        degrees: bool,
    },
    /// `|`: a half turn about the turtle's up axis.
    TurnAround,
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
    /// `!(w)`: width and thickness both `w`; a bare `!` scales both by
    /// [`DIAMETER_FACTOR`](super::DIAMETER_FACTOR).
    Diameter,
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
    Command::from_name(rest)
        .filter(|c| c.has_maturing_twin())
        .map(|command| action(command, true))
}

/// What `command` (or its maturing twin) makes the builder do.
fn action(command: Command, maturing: bool) -> Action {
    let turn = |axis: Vector3<f64>, sign: f64| Action::Turn {
        axis,
        sign,
        degrees: command.is_textbook(),
    };
    let joint = |kind, limits| Action::Joint {
        kind,
        limits,
        maturing,
    };
    match command {
        Command::Forward => Action::Forward {
            maturing,
            textbook: false,
        },
        Command::Segment => Action::Forward {
            maturing: false,
            textbook: true,
        },
        Command::Move => Action::Move,
        // The textbook's heading H is the turtle's x, its up U is y, its left L is −z:
        // `+` turns left about U, `&` pitches down about L, `\` rolls left about H. The
        // turtle's own names turn the same ways.
        Command::TurnLeft | Command::Left => turn(Vector3::y(), 1.0),
        Command::TurnRight | Command::Right => turn(Vector3::y(), -1.0),
        Command::PitchUp | Command::Up => turn(Vector3::z(), 1.0),
        Command::PitchDown | Command::Down => turn(Vector3::z(), -1.0),
        Command::RollRight | Command::Clockwise => turn(Vector3::x(), 1.0),
        Command::RollLeft | Command::Counterclockwise => turn(Vector3::x(), -1.0),
        Command::TurnAround => Action::TurnAround,
        Command::Diameter => Action::Diameter,
        Command::Backward => Action::Backward,
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
            let twin = Command::from_name(name).unwrap().has_maturing_twin();
            assert_eq!(command_of(&format!("m{name}")).is_some(), twin, "m{name}");
        }
        assert_eq!(command_of("A"), None);
        assert_eq!(command_of("mF"), None);
        assert_eq!(
            command_of("mforward"),
            Some(Action::Forward {
                maturing: true,
                textbook: false
            })
        );
        assert_eq!(
            command_of("F"),
            Some(Action::Forward {
                maturing: false,
                textbook: true
            })
        );
    }
}
