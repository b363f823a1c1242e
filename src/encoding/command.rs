//! The building commands genomes write into successors: one list of the turtle's and the
//! edge-encoding builder's commands (see the README's "Building creatures"), their names in a
//! module string, and what each one's argument means. Each genome chooses its own subset,
//! ranges and weights.

use serde::{Deserialize, Serialize};

/// A building command. Left out: repeat blocks `{ }(n)`, the maturing `m` twins (a genome's
/// own business), and the environment and task commands (`chem`, `secrete`, `target`,
/// `release`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[allow(missing_docs)]
pub enum Command {
    Forward,
    Backward,
    Left,
    Right,
    Up,
    Down,
    Clockwise,
    Counterclockwise,
    Revolute1,
    Revolute2,
    Twist90,
    Twist180,
    Width,
    Thickness,
    Split,
    Duplicate,
    Loop,
    Merge,
    Next,
    Parent,
    Output,
    Reverse,
    Setfunc,
    Bias,
    Cut,
    Weight,
    Increase,
    Decrease,
    Touch,
    Angle,
}

/// What a command's argument means.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Argument {
    /// No argument.
    None,
    /// A part's length (m).
    Length,
    /// A part's width or thickness (m).
    Size,
    /// A turn, in units of 90°.
    Turn,
    /// A link weight.
    Weight,
    /// An index among links or neurons.
    Index,
    /// A transfer function number.
    Function,
    /// A neuron's bias.
    Bias,
}

impl Command {
    /// Every command, in declaration order.
    pub const ALL: [Command; 30] = [
        Command::Forward,
        Command::Backward,
        Command::Left,
        Command::Right,
        Command::Up,
        Command::Down,
        Command::Clockwise,
        Command::Counterclockwise,
        Command::Revolute1,
        Command::Revolute2,
        Command::Twist90,
        Command::Twist180,
        Command::Width,
        Command::Thickness,
        Command::Split,
        Command::Duplicate,
        Command::Loop,
        Command::Merge,
        Command::Next,
        Command::Parent,
        Command::Output,
        Command::Reverse,
        Command::Setfunc,
        Command::Bias,
        Command::Cut,
        Command::Weight,
        Command::Increase,
        Command::Decrease,
        Command::Touch,
        Command::Angle,
    ];

    /// The command's name in a module string.
    pub fn name(self) -> &'static str {
        match self {
            Command::Forward => "forward",
            Command::Backward => "backward",
            Command::Left => "left",
            Command::Right => "right",
            Command::Up => "up",
            Command::Down => "down",
            Command::Clockwise => "clockwise",
            Command::Counterclockwise => "counterclockwise",
            Command::Revolute1 => "revolute1",
            Command::Revolute2 => "revolute2",
            Command::Twist90 => "twist90",
            Command::Twist180 => "twist180",
            Command::Width => "width",
            Command::Thickness => "thickness",
            Command::Split => "split",
            Command::Duplicate => "duplicate",
            Command::Loop => "loop",
            Command::Merge => "merge",
            Command::Next => "next",
            Command::Parent => "parent",
            Command::Output => "output",
            Command::Reverse => "reverse",
            Command::Setfunc => "setfunc",
            Command::Bias => "bias",
            Command::Cut => "cut",
            Command::Weight => "weight",
            Command::Increase => "increase",
            Command::Decrease => "decrease",
            Command::Touch => "touch",
            Command::Angle => "angle",
        }
    }

    /// The command a name stands for.
    pub fn from_name(name: &str) -> Option<Command> {
        Command::ALL.into_iter().find(|c| c.name() == name)
    }

    /// What its argument means.
    pub fn argument(self) -> Argument {
        match self {
            Command::Forward => Argument::Length,
            Command::Left
            | Command::Right
            | Command::Up
            | Command::Down
            | Command::Clockwise
            | Command::Counterclockwise => Argument::Turn,
            Command::Width | Command::Thickness => Argument::Size,
            Command::Split
            | Command::Duplicate
            | Command::Loop
            | Command::Output
            | Command::Weight
            | Command::Increase
            | Command::Decrease => Argument::Weight,
            Command::Merge | Command::Next | Command::Parent => Argument::Index,
            Command::Setfunc => Argument::Function,
            Command::Bias => Argument::Bias,
            Command::Backward
            | Command::Revolute1
            | Command::Revolute2
            | Command::Twist90
            | Command::Twist180
            | Command::Reverse
            | Command::Cut
            | Command::Touch
            | Command::Angle => Argument::None,
        }
    }

    /// Whether it takes an argument.
    pub fn has_argument(self) -> bool {
        self.argument() != Argument::None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_is_a_builder_command_and_reads_back() {
        for c in Command::ALL {
            assert_eq!(Command::from_name(c.name()), Some(c));
            assert!(crate::lang::is_builtin_command(c.name()), "{}", c.name());
        }
        assert_eq!(Command::from_name("chem"), None);
    }
}
