//! The names of the simulator's model choices ([`JointModel`], [`ActuatorModel`],
//! [`StrengthFrom`]) as configs and the command line spell them, with a summary of each for
//! `--help`: one definition of each vocabulary, which the command line lists and parses.

use std::str::FromStr;

use super::{ActuatorModel, JointModel, StrengthFrom};

/// A name that is none of a vocabulary's: which vocabulary, and the name given.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("'{name}' is not a {what}")]
pub struct UnknownName {
    /// What was being named (`"joint model"`).
    pub what: &'static str,
    /// The name given.
    pub name: String,
}

/// The value of `all` whose `name` is `text`.
fn find<T: Copy>(
    all: &[T],
    name: fn(T) -> &'static str,
    what: &'static str,
    text: &str,
) -> Result<T, UnknownName> {
    all.iter()
        .copied()
        .find(|v| name(*v) == text)
        .ok_or_else(|| UnknownName {
            what,
            name: text.to_string(),
        })
}

/// `FromStr` for a choice with `ALL` and `name`: the choice named `text` ([`find`]), or an
/// [`UnknownName`] that calls it `$what`.
macro_rules! from_name {
    ($choice:ident, $what:literal) => {
        impl FromStr for $choice {
            type Err = UnknownName;

            fn from_str(text: &str) -> Result<$choice, UnknownName> {
                find(&$choice::ALL, $choice::name, $what, text)
            }
        }
    };
}

impl JointModel {
    /// Every joint model, in the order `--help` lists them.
    pub const ALL: [JointModel; 2] = [JointModel::Impulse, JointModel::Multibody];

    /// The model's name (`"multibody"`).
    pub fn name(self) -> &'static str {
        match self {
            JointModel::Impulse => "impulse",
            JointModel::Multibody => "multibody",
        }
    }

    /// The model in a few words, for `--help`.
    pub fn summary(self) -> &'static str {
        match self {
            JointModel::Impulse => "Impulse joints (the default: faster)",
            JointModel::Multibody => "Multibody (reduced-coordinate) joints",
        }
    }
}

from_name!(JointModel, "joint model");

impl ActuatorModel {
    /// Every actuator model, in the order `--help` lists them.
    pub const ALL: [ActuatorModel; 4] = [
        ActuatorModel::Muscle,
        ActuatorModel::MuscleTorque,
        ActuatorModel::Angle,
        ActuatorModel::Velocity,
    ];

    /// The model's name (`"muscle-torque"`).
    pub fn name(self) -> &'static str {
        match self {
            ActuatorModel::Muscle => "muscle",
            ActuatorModel::MuscleTorque => "muscle-torque",
            ActuatorModel::Angle => "angle",
            ActuatorModel::Velocity => "velocity",
        }
    }

    /// The model in a few words, for `--help`.
    pub fn summary(self) -> &'static str {
        match self {
            ActuatorModel::Muscle => {
                "Chaumont's muscle: saturated motor, torque scaled by |signal|"
            }
            ActuatorModel::MuscleTorque => {
                "Chaumont's muscle as a torque of signal × strength on the joint's two parts, \
                 without a motor constraint"
            }
            ActuatorModel::Angle => "Hornby's: the signal sets the target angle",
            ActuatorModel::Velocity => "Matos's: the signal sets the target speed",
        }
    }
}

from_name!(ActuatorModel, "actuator model");

impl StrengthFrom {
    /// Both choices, in the order `--help` lists them.
    pub const ALL: [StrengthFrom; 2] = [StrengthFrom::Smaller, StrengthFrom::Bigger];

    /// The choice's name (`"bigger"`).
    pub fn name(self) -> &'static str {
        match self {
            StrengthFrom::Smaller => "smaller",
            StrengthFrom::Bigger => "bigger",
        }
    }

    /// The choice in a few words, for `--help`.
    pub fn summary(self) -> &'static str {
        match self {
            StrengthFrom::Smaller => "The smaller part's (Walking with Dinosaurs 3.4.4)",
            StrengthFrom::Bigger => {
                "The bigger part's (Chaumont et al. 3.4, after Sims; the default)"
            }
        }
    }
}

from_name!(StrengthFrom, "joint strength source");

#[cfg(test)]
mod tests {
    use super::*;

    /// Every value's name is the one its serde form (configs, run stores) spells, and reads
    /// back as that value.
    fn names_agree_with_serde<T>(all: &[T], name: fn(T) -> &'static str)
    where
        T: Copy + PartialEq + std::fmt::Debug + serde::Serialize + FromStr,
        T::Err: std::fmt::Debug,
    {
        for &value in all {
            assert_eq!(serde_json::to_value(value).unwrap(), name(value));
            assert_eq!(name(value).parse::<T>().unwrap(), value);
        }
        assert!("no-such-name".parse::<T>().is_err());
    }

    #[test]
    fn model_names_are_the_ones_configs_spell() {
        names_agree_with_serde(&JointModel::ALL, JointModel::name);
        names_agree_with_serde(&ActuatorModel::ALL, ActuatorModel::name);
        names_agree_with_serde(&StrengthFrom::ALL, StrengthFrom::name);
    }
}
