//! The ranges of every encoding's `[limits]` keys, checked when a configuration is read: the
//! one table of them, so that no key goes unchecked and none can ask for a genome or a
//! development that exhausts memory or runs for minutes. A key out of its range is a
//! [`SettingError`] in the table `limits` (`[limits] max_pairs must be 1 to 16, not 0`),
//! which a configuration file's reader places at the key's line and column. The keys every
//! encoding shares on its creatures (`max_neurons`, `max_chain`: [`CreatureLimits`]) have one
//! range for all.

use std::fmt::Display;

use super::creature_limits::CreatureLimits;
use super::lsystem::MOST_REPEAT;
use super::{ContinuousLimits, DirectLimits, GraphLimits, LSystemLimits};
use crate::sim::SettingError;

/// The most modules any encoding's `max_modules` may allow: a derived string (or a direct
/// genome) of this many modules develops in well under a second.
pub const MOST_MODULES: usize = 100_000;

/// The most parts any encoding's `max_parts` may allow.
pub const MOST_PARTS: usize = 1_000;

/// The most neurons any encoding's `max_neurons` may allow.
pub const MOST_NEURONS: usize = 10_000;

/// The most observation steps (`time / dt`) of a continuous genome: as many frames as
/// `ontogeny grow --out` keeps.
pub const MOST_CONTINUOUS_FRAMES: f64 = 10_000.0;

/// An encoding's limits whose every key has a documented range.
pub trait CheckedLimits {
    /// `Err` names the first key out of its range, in the table `limits`.
    fn check_ranges(&self) -> Result<(), SettingError>;

    /// The keys every encoding shares on the creature its genome develops into; none by
    /// default (for an encoding of a library's user that has not these keys).
    fn creature_limits(&self) -> CreatureLimits {
        CreatureLimits::default()
    }
}

/// The ranges of the keys every encoding shares: `max_neurons` 1 to [`MOST_NEURONS`] and
/// `max_chain` 1 to [`MOST_PARTS`], where set.
fn shared(limits: CreatureLimits) -> Result<(), SettingError> {
    if let Some(most) = limits.max_neurons {
        count("max_neurons", most, 1, MOST_NEURONS)?;
    }
    if let Some(most) = limits.max_chain {
        count("max_chain", most, 1, MOST_PARTS)?;
    }
    Ok(())
}

/// The shared keys of an encoding's limits that hold them as fields `max_neurons` and
/// `max_chain`.
macro_rules! creature_limits {
    () => {
        fn creature_limits(&self) -> CreatureLimits {
            CreatureLimits {
                max_neurons: self.max_neurons,
                max_chain: self.max_chain,
            }
        }
    };
}

/// A count `value` of key `key` within `least..=most`.
fn count<T: PartialOrd + Display + Copy>(
    key: &'static str,
    value: T,
    least: T,
    most: T,
) -> Result<(), SettingError> {
    if value < least || value > most {
        return Err(
            SettingError::out_of_range(key, &format!("{least} to {most}"), value).within("limits"),
        );
    }
    Ok(())
}

/// A real `value` of key `key` finite and in `(least, most]` (`[least, most]` when
/// `closed`).
fn real(
    key: &'static str,
    value: f64,
    least: f64,
    closed: bool,
    most: f64,
) -> Result<(), SettingError> {
    let above = if closed {
        value >= least
    } else {
        value > least
    };
    if !(value.is_finite() && above && value <= most) {
        let range = match closed {
            true => format!("in [{least}, {most}]"),
            false => format!("in ({least}, {most}]"),
        };
        return Err(SettingError::out_of_range(key, &range, value).within("limits"));
    }
    Ok(())
}

impl CheckedLimits for LSystemLimits {
    creature_limits!();

    fn check_ranges(&self) -> Result<(), SettingError> {
        shared(self.creature_limits())?;
        count("max_productions", self.max_productions, 1, 64)?;
        count("max_pairs", self.max_pairs, 1, 16)?;
        count("params", self.params, 0, 8)?;
        count("max_successor", self.max_successor, 1, 256)?;
        count("derivation_length", self.derivation_length, 0, 64)?;
        count("max_modules", self.max_modules, 1, MOST_MODULES)?;
        count("max_parts", self.max_parts, 1, MOST_PARTS)?;
        // A block repeated once is no block: 0 (none) or 2 and more.
        if self.max_repeat == 1 || self.max_repeat > MOST_REPEAT {
            return Err(SettingError::out_of_range(
                "max_repeat",
                &format!("0 (no repeat blocks) or 2 to {MOST_REPEAT}"),
                self.max_repeat,
            )
            .within("limits"));
        }
        Ok(())
    }
}

impl CheckedLimits for ContinuousLimits {
    creature_limits!();

    fn check_ranges(&self) -> Result<(), SettingError> {
        shared(self.creature_limits())?;
        count("max_rules", self.max_rules, 1, 64)?;
        count("control_tokens", self.control_tokens, 0, 26)?;
        count("max_axiom", self.max_axiom, 1, 256)?;
        count("max_successor", self.max_successor, 0, 256)?;
        count("max_growers", self.max_growers, 0, 8)?;
        real("time", self.time, 0.0, false, 1000.0)?;
        real(
            "dt",
            self.dt,
            self.time / MOST_CONTINUOUS_FRAMES,
            true,
            self.time,
        )?;
        real("min_threshold", self.min_threshold, 0.0, false, 10.0)?;
        real(
            "max_threshold",
            self.max_threshold,
            self.min_threshold,
            true,
            10.0,
        )?;
        real("min_duration", self.min_duration, 0.01, true, 1000.0)?;
        real(
            "max_duration",
            self.max_duration,
            self.min_duration,
            true,
            1000.0,
        )?;
        count("max_parts", self.max_parts, 2, MOST_PARTS)?;
        count(
            "max_modules",
            self.max_modules,
            self.max_axiom,
            MOST_MODULES,
        )
    }
}

impl CheckedLimits for DirectLimits {
    creature_limits!();

    fn check_ranges(&self) -> Result<(), SettingError> {
        shared(self.creature_limits())?;
        count("max_modules", self.max_modules, 1, MOST_MODULES)?;
        count("max_parts", self.max_parts, 1, MOST_PARTS)?;
        count("random_length", self.random_length, 1, self.max_modules)
    }
}

impl CheckedLimits for GraphLimits {
    creature_limits!();

    fn check_ranges(&self) -> Result<(), SettingError> {
        shared(self.creature_limits())?;
        count("max_nodes", self.max_nodes, 1, 100)?;
        count("max_parts", self.max_parts, 1, MOST_PARTS)?;
        count("max_connections", self.max_connections, 0, 16)?;
        count("max_recursion", self.max_recursion, 1, 16)?;
        count("max_local_neurons", self.max_local_neurons, 0, 16)?;
        count("max_global_neurons", self.max_global_neurons, 0, 16)?;
        count("max_inputs", self.max_inputs, 0, 8)?;
        count("regenerate_tries", self.regenerate_tries, 1, 100)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_default_is_within_its_range() {
        assert_eq!(LSystemLimits::default().check_ranges(), Ok(()));
        assert_eq!(ContinuousLimits::default().check_ranges(), Ok(()));
        assert_eq!(DirectLimits::default().check_ranges(), Ok(()));
        assert_eq!(GraphLimits::default().check_ranges(), Ok(()));
    }

    #[test]
    fn a_key_out_of_range_is_named_in_the_limits_table() {
        let limits = LSystemLimits {
            max_successor: 100_000_000,
            ..LSystemLimits::default()
        };
        assert_eq!(
            limits.check_ranges().unwrap_err().to_string(),
            "[limits] max_successor must be 1 to 256, not 100000000"
        );
        for (max_repeat, error) in [
            (0, None),
            (1, Some("1")),
            (2, None),
            (100, None),
            (101, Some("101")),
        ] {
            let limits = LSystemLimits {
                max_repeat,
                ..LSystemLimits::default()
            };
            assert_eq!(
                limits.check_ranges().err().map(|e| e.to_string()),
                error.map(|v| format!(
                    "[limits] max_repeat must be 0 (no repeat blocks) or 2 to 100, not {v}"
                ))
            );
            assert_eq!(limits.validate().is_err(), error.is_some());
        }
        let limits = ContinuousLimits {
            dt: 1e-9,
            ..ContinuousLimits::default()
        };
        assert_eq!(
            limits.check_ranges().unwrap_err().to_string(),
            "[limits] dt must be in [0.0004, 4], not 0.000000001"
        );
    }
}
