//! The builder's commands: the one table of their names, arguments and kinds (see the
//! reference page `docs/reference/commands.md`), from which the parser's built-in names, the builder's
//! reading of a module and the genomes' vocabularies all derive.
//!
//! Each of Ontogeny's own commands also has a maturing twin prefixed `m` (`mforward`,
//! `mrevolute1`, ...) that the language knows; [`CommandInfo::grows`] says whether the twin
//! grows (Matos & Arita). The textbook turtle's symbols ([`CommandKind::Textbook`]: `F`, `f`,
//! `+`, ...) come last and have no twin.

use serde::{Deserialize, Serialize};

/// A building command, as a module string names it.
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
    Chem,
    Target,
    Secrete,
    Release,
    /// `F(l)`: the textbook's part along the heading.
    #[serde(rename = "F")]
    Segment,
    /// `f(l)`: the textbook's move without building.
    #[serde(rename = "f")]
    Move,
    /// `+(δ)`
    #[serde(rename = "+")]
    TurnLeft,
    /// `-(δ)`
    #[serde(rename = "-")]
    TurnRight,
    /// `&(δ)`
    #[serde(rename = "&")]
    PitchDown,
    /// `^(δ)`
    #[serde(rename = "^")]
    PitchUp,
    /// `\(δ)`
    #[serde(rename = "\\")]
    RollLeft,
    /// `/(δ)`
    #[serde(rename = "/")]
    RollRight,
    /// `|`
    #[serde(rename = "|")]
    TurnAround,
    /// `!(w)`
    #[serde(rename = "!")]
    Diameter,
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
    /// An index among links or neurons (or chemicals).
    Index,
    /// A transfer function number.
    Function,
    /// A neuron's bias.
    Bias,
    /// A turn in degrees (the textbook's; default the file's `angle:`).
    Degrees,
}

impl Argument {
    /// What the argument is, in words, for messages: `a part's length (m)`.
    pub fn describe(self) -> &'static str {
        match self {
            Argument::None => "no argument",
            Argument::Length => "a part's length in metres",
            Argument::Size => "a part's width or thickness in metres",
            Argument::Turn => "a turn, in quarter turns",
            Argument::Weight => "a link weight",
            Argument::Index => "an index",
            Argument::Function => "a transfer function number",
            Argument::Bias => "a neuron's bias",
            Argument::Degrees => "a turn in degrees",
        }
    }
}

/// What a command acts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CommandKind {
    /// The body turtle: parts, their size, and turns.
    Body,
    /// The joint of the next part.
    Joint,
    /// The brain (edge encoding): links and neurons.
    Brain,
    /// The environment's chemicals (`chem`, `secrete`).
    Environment,
    /// The task (`target`, `release`).
    Task,
    /// The textbook turtle's symbols (*The Algorithmic Beauty of Plants*, chapter 1): `F`,
    /// `f`, `+`, `-`, `&`, `^`, `\`, `/`, `|`, `!`. Genomes do not write them and they have
    /// no maturing twin.
    Textbook,
}

/// One row of the table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CommandInfo {
    /// The command.
    pub command: Command,
    /// Its name in a module string.
    pub name: &'static str,
    /// What its argument means.
    pub argument: Argument,
    /// What it acts on.
    pub kind: CommandKind,
    /// Whether its maturing twin grows (the body commands that make or turn parts, and the
    /// joints): those twins are the maturing symbols of continuous genomes.
    pub grows: bool,
}

const fn row(
    command: Command,
    name: &'static str,
    argument: Argument,
    kind: CommandKind,
    grows: bool,
) -> CommandInfo {
    CommandInfo {
        command,
        name,
        argument,
        kind,
        grows,
    }
}

use Argument as A;
use CommandKind as K;

/// Every command, in the order of [`Command`]'s variants: the building commands genomes
/// write first, then the environment and task commands, and the textbook's symbols last.
pub const COMMANDS: [CommandInfo; 44] = [
    row(Command::Forward, "forward", A::Length, K::Body, true),
    row(Command::Backward, "backward", A::None, K::Body, false),
    row(Command::Left, "left", A::Turn, K::Body, true),
    row(Command::Right, "right", A::Turn, K::Body, true),
    row(Command::Up, "up", A::Turn, K::Body, true),
    row(Command::Down, "down", A::Turn, K::Body, true),
    row(Command::Clockwise, "clockwise", A::Turn, K::Body, true),
    row(
        Command::Counterclockwise,
        "counterclockwise",
        A::Turn,
        K::Body,
        true,
    ),
    row(Command::Revolute1, "revolute1", A::None, K::Joint, true),
    row(Command::Revolute2, "revolute2", A::None, K::Joint, true),
    row(Command::Twist90, "twist90", A::None, K::Joint, true),
    row(Command::Twist180, "twist180", A::None, K::Joint, true),
    row(Command::Width, "width", A::Size, K::Body, false),
    row(Command::Thickness, "thickness", A::Size, K::Body, false),
    row(Command::Split, "split", A::Weight, K::Brain, false),
    row(Command::Duplicate, "duplicate", A::Weight, K::Brain, false),
    row(Command::Loop, "loop", A::Weight, K::Brain, false),
    row(Command::Merge, "merge", A::Index, K::Brain, false),
    row(Command::Next, "next", A::Index, K::Brain, false),
    row(Command::Parent, "parent", A::Index, K::Brain, false),
    row(Command::Output, "output", A::Weight, K::Brain, false),
    row(Command::Reverse, "reverse", A::None, K::Brain, false),
    row(Command::Setfunc, "setfunc", A::Function, K::Brain, false),
    row(Command::Bias, "bias", A::Bias, K::Brain, false),
    row(Command::Cut, "cut", A::None, K::Brain, false),
    row(Command::Weight, "weight", A::Weight, K::Brain, false),
    row(Command::Increase, "increase", A::Weight, K::Brain, false),
    row(Command::Decrease, "decrease", A::Weight, K::Brain, false),
    row(Command::Touch, "touch", A::None, K::Brain, false),
    row(Command::Angle, "angle", A::None, K::Brain, false),
    row(Command::Chem, "chem", A::Index, K::Environment, false),
    row(Command::Target, "target", A::None, K::Task, false),
    row(Command::Secrete, "secrete", A::Index, K::Environment, false),
    row(Command::Release, "release", A::None, K::Task, false),
    row(Command::Segment, "F", A::Length, K::Textbook, false),
    row(Command::Move, "f", A::Length, K::Textbook, false),
    row(Command::TurnLeft, "+", A::Degrees, K::Textbook, false),
    row(Command::TurnRight, "-", A::Degrees, K::Textbook, false),
    row(Command::PitchDown, "&", A::Degrees, K::Textbook, false),
    row(Command::PitchUp, "^", A::Degrees, K::Textbook, false),
    row(Command::RollLeft, "\\", A::Degrees, K::Textbook, false),
    row(Command::RollRight, "/", A::Degrees, K::Textbook, false),
    row(Command::TurnAround, "|", A::None, K::Textbook, false),
    row(Command::Diameter, "!", A::Size, K::Textbook, false),
];

/// How many of [`COMMANDS`], from the first, build the creature (body, joints, brain).
const BUILDING_COUNT: usize = {
    let mut n = 0;
    while n < COMMANDS.len()
        && !matches!(
            COMMANDS[n].kind,
            CommandKind::Environment | CommandKind::Task | CommandKind::Textbook
        )
    {
        n += 1;
    }
    n
};

/// How many of [`COMMANDS`] have a maturing twin that grows.
const GROWING_COUNT: usize = {
    let (mut i, mut n) = (0, 0);
    while i < COMMANDS.len() {
        if COMMANDS[i].grows {
            n += 1;
        }
        i += 1;
    }
    n
};

/// Every command's name, in table order: the language's built-in names.
pub const NAMES: [&str; COMMANDS.len()] = {
    let mut names = [""; COMMANDS.len()];
    let mut i = 0;
    while i < COMMANDS.len() {
        names[i] = COMMANDS[i].name;
        i += 1;
    }
    names
};

impl Command {
    /// Every command, in table order.
    pub const EVERY: [Command; COMMANDS.len()] = {
        let mut all = [Command::Forward; COMMANDS.len()];
        let mut i = 0;
        while i < COMMANDS.len() {
            all[i] = COMMANDS[i].command;
            i += 1;
        }
        all
    };

    /// The commands that build the creature (body, joints, brain), in table order: what
    /// genomes write. The environment and task commands (`chem`, `secrete`, `target`,
    /// `release`) are left out.
    pub const ALL: [Command; BUILDING_COUNT] = {
        let mut all = [Command::Forward; BUILDING_COUNT];
        let mut i = 0;
        while i < BUILDING_COUNT {
            all[i] = COMMANDS[i].command;
            i += 1;
        }
        all
    };

    /// The commands whose maturing twins grow (`mforward`, `mleft`, ..., `mrevolute1`, ...),
    /// in table order.
    pub const GROWING: [Command; GROWING_COUNT] = {
        let mut all = [Command::Forward; GROWING_COUNT];
        let (mut i, mut n) = (0, 0);
        while i < COMMANDS.len() {
            if COMMANDS[i].grows {
                all[n] = COMMANDS[i].command;
                n += 1;
            }
            i += 1;
        }
        all
    };

    /// The command's row of the table.
    pub const fn info(self) -> &'static CommandInfo {
        &COMMANDS[self as usize]
    }

    /// The command's name in a module string.
    pub fn name(self) -> &'static str {
        self.info().name
    }

    /// Whether it is one of the textbook turtle's symbols ([`CommandKind::Textbook`]).
    pub fn is_textbook(self) -> bool {
        self.kind() == CommandKind::Textbook
    }

    /// Whether it has a maturing twin prefixed `m` that the language knows (every command
    /// but the textbook's symbols).
    pub fn has_maturing_twin(self) -> bool {
        !self.is_textbook()
    }

    /// The command a name stands for (not its maturing twin).
    pub fn from_name(name: &str) -> Option<Command> {
        COMMANDS.iter().find(|c| c.name == name).map(|c| c.command)
    }

    /// The building command (body, joint or brain: one of [`Command::ALL`]) a name stands
    /// for; `None` for the environment and task commands, which genomes do not write.
    pub fn building_from_name(name: &str) -> Option<Command> {
        Command::from_name(name).filter(|c| Command::ALL.contains(c))
    }

    /// What its argument means.
    pub fn argument(self) -> Argument {
        self.info().argument
    }

    /// Whether it takes an argument.
    pub fn has_argument(self) -> bool {
        self.argument() != Argument::None
    }

    /// How many parameters it takes: none for [`Argument::None`], else one (the builder reads
    /// no other). Its maturing twin takes one whatever the command (its length or age).
    pub fn parameters(self) -> usize {
        usize::from(self.has_argument())
    }

    /// What it acts on.
    pub fn kind(self) -> CommandKind {
        self.info().kind
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_row_stands_in_the_place_of_its_command_and_reads_back() {
        for (i, row) in COMMANDS.iter().enumerate() {
            assert_eq!(row.command as usize, i, "{}", row.name);
            assert_eq!(Command::from_name(row.name), Some(row.command));
        }
        assert_eq!(Command::ALL.len(), 30);
        assert_eq!(Command::GROWING.len(), 11);
        assert_eq!(Command::from_name("mforward"), None);
        assert_eq!(Command::building_from_name("chem"), None);
        assert_eq!(Command::building_from_name("angle"), Some(Command::Angle));
        assert_eq!(Command::from_name("F"), Some(Command::Segment));
        assert_eq!(Command::from_name("\\"), Some(Command::RollLeft));
        assert_eq!(Command::building_from_name("F"), None);
        assert!(!Command::TurnAround.has_argument());
        assert!(Command::TurnLeft.has_argument());
    }
}
