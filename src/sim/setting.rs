//! The simulator's settings as a user gives them: the named step settings (`fast`, `default`,
//! `fine`), the error a value out of its range gets ([`SettingError`]; the range check itself
//! is [`SimOptions::check`]), and the `[task.sim]` table as a person writes it (a named setting
//! with any of its values overridden).
//!
//! What a setting means physically is documented on [`SimOptions`]; what a task does with it
//! belongs to `task`.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use super::options::{ActuatorModel, JointModel, SimOptions, StrengthFrom};

/// A named step setting: how finely the physics steps, in five values (substeps, solver
/// iterations and Gauss-Seidel passes while walking; substeps and solver iterations while a
/// task waits for rest). Everything else (the control step `dt` included) is left as it is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StepSetting {
    /// One physics step of 1/60 s with 2 solver iterations of 3 Gauss-Seidel passes while
    /// walking, 2 substeps of 4 iterations while waiting for rest: about 4× cheaper than the
    /// default, good for ranking random creatures, but evolved creatures learn to walk on its
    /// errors (see [`SimOptions::fast`]).
    Fast,
    /// Physics at 1/240 s: 4 substeps of 4 solver iterations while walking, 4 of 8 while
    /// waiting for rest (see [`SimOptions::default`]).
    #[default]
    Default,
    /// The fine reference: 4 substeps of 8 solver iterations both while walking and while
    /// waiting for rest (see [`SimOptions::fine_reference`]).
    Fine,
}

/// The five stepping values of a setting, in the order of [`SimOptions`]' fields: substeps,
/// solver iterations, PGS passes, rest substeps, rest solver iterations.
type Stepping = (usize, usize, usize, usize, usize);

impl StepSetting {
    /// Every named setting, coarsest first.
    pub const ALL: [StepSetting; 3] = [StepSetting::Fast, StepSetting::Default, StepSetting::Fine];

    /// The setting's name, as the command line (`--setting`) and config files
    /// (`[task.sim] setting`) spell it.
    pub fn name(self) -> &'static str {
        match self {
            StepSetting::Fast => "fast",
            StepSetting::Default => "default",
            StepSetting::Fine => "fine",
        }
    }

    /// The setting in a few words, for `--help`.
    pub fn summary(self) -> &'static str {
        match self {
            StepSetting::Fast => {
                "1 substep of 2 solver iterations × 3 Gauss-Seidel passes, settling at 2 × 4: about 4× quicker, but evolution exploits it"
            }
            StepSetting::Default => {
                "4 substeps of 4 solver iterations (physics at 1/240 s), settling at 4 × 8"
            }
            StepSetting::Fine => {
                "the fine reference: 4 substeps of 8 solver iterations, settling at 4 × 8"
            }
        }
    }

    /// The one definition of each setting's five stepping values.
    pub(super) const fn stepping(self) -> Stepping {
        match self {
            StepSetting::Fast => (1, 2, 3, 2, 4),
            StepSetting::Default => (4, 4, 1, 4, 8),
            StepSetting::Fine => (4, 8, 1, 4, 8),
        }
    }

    /// `base` with this setting's five stepping values; everything else as `base`.
    pub fn apply(self, base: &SimOptions) -> SimOptions {
        let (substeps, solver_iterations, pgs_iterations, rest_substeps, rest_solver_iterations) =
            self.stepping();
        SimOptions {
            substeps,
            solver_iterations,
            pgs_iterations,
            rest_substeps,
            rest_solver_iterations,
            ..base.clone()
        }
    }

    /// The named setting whose five stepping values `options` has, if any.
    pub fn of(options: &SimOptions) -> Option<StepSetting> {
        let stepping = (
            options.substeps,
            options.solver_iterations,
            options.pgs_iterations,
            options.rest_substeps,
            options.rest_solver_iterations,
        );
        StepSetting::ALL
            .into_iter()
            .find(|s| s.stepping() == stepping)
    }
}

impl fmt::Display for StepSetting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not a step setting's.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("'{0}' is not a step setting (fast, default or fine)")]
pub struct UnknownSetting(pub String);

impl FromStr for StepSetting {
    type Err = UnknownSetting;

    fn from_str(text: &str) -> Result<StepSetting, UnknownSetting> {
        StepSetting::ALL
            .into_iter()
            .find(|s| s.name() == text)
            .ok_or_else(|| UnknownSetting(text.to_string()))
    }
}

/// A setting out of its range, or missing where it is needed: which key, in which table, and
/// what is wrong. The library names the key as a config file spells it (`[task.sim]
/// substeps`); a command line whose flag set the value names the flag instead
/// ([`SettingError::for_flag`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SettingError {
    /// The TOML table that holds the key, e.g. `task.sim`; empty when the options were checked
    /// on their own.
    pub table: String,
    /// The key, as a config file spells it (`substeps`).
    pub key: &'static str,
    /// What is wrong, after the key: "must be 1 to 64, not 0".
    pub problem: String,
}

impl SettingError {
    /// `key` out of range: it must be `range`, and is `value`.
    pub fn out_of_range(key: &'static str, range: &str, value: impl fmt::Display) -> SettingError {
        SettingError {
            table: String::new(),
            key,
            problem: format!("must be {range}, not {value}"),
        }
    }

    /// The same error, its table inside `outer` (`sim` inside `task` is `task.sim`).
    pub fn within(mut self, outer: &str) -> SettingError {
        self.table = if self.table.is_empty() {
            outer.to_string()
        } else {
            format!("{outer}.{}", self.table)
        };
        self
    }

    /// The message with `flag` (`--substeps`) in place of the key, for a value that came from
    /// the command line.
    pub fn for_flag(&self, flag: &str) -> String {
        format!("{flag} {}", self.problem)
    }
}

impl fmt::Display for SettingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.table.is_empty() {
            write!(f, "{} {}", self.key, self.problem)
        } else {
            write!(f, "[{}] {} {}", self.table, self.key, self.problem)
        }
    }
}

impl std::error::Error for SettingError {}

/// `value` is finite and at least `least` (or above it, when `strictly`); else the error for
/// `key` in words.
pub fn check_real(
    key: &'static str,
    value: f64,
    least: f64,
    strictly: bool,
) -> Result<(), SettingError> {
    let in_range = if strictly {
        value > least
    } else {
        value >= least
    };
    if value.is_finite() && in_range {
        return Ok(());
    }
    let range = match (least == 0.0, strictly) {
        (true, true) => "finite and positive".to_string(),
        (true, false) => "finite and not negative".to_string(),
        (false, true) => format!("finite and above {least}"),
        (false, false) => format!("finite and at least {least}"),
    };
    Err(SettingError::out_of_range(key, &range, value))
}

/// The keys of `[task.sim]` that have been renamed, as (today's name, the older name that
/// files written before may still use; serde reads both).
pub const RENAMED_KEYS: &[(&str, &str)] = &[("control_step", "dt")];

/// The `[task.sim]` table as a person writes it: a named step setting (`setting = "fast"`,
/// default `default`) and any value over it. A key given beside `setting` overrides the
/// setting's value. Read into [`SimOptions`], which holds every value resolved and is written
/// back that way (without `setting`), so that a run's `config.toml` never depends on what a
/// name means in a later version.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimTable {
    /// The named step setting the five stepping values start from.
    pub setting: Option<StepSetting>,
    /// See [`SimOptions::control_step`]: the control step, `dt` in files written before it
    /// had its own name (read as `control_step`; a table may not give both; [`RENAMED_KEYS`]).
    #[serde(alias = "dt")]
    pub control_step: Option<f64>,
    /// See [`SimOptions::substeps`].
    pub substeps: Option<usize>,
    /// See [`SimOptions::solver_iterations`].
    pub solver_iterations: Option<usize>,
    /// See [`SimOptions::pgs_iterations`].
    pub pgs_iterations: Option<usize>,
    /// See [`SimOptions::rest_substeps`].
    pub rest_substeps: Option<usize>,
    /// See [`SimOptions::rest_solver_iterations`].
    pub rest_solver_iterations: Option<usize>,
    /// See [`SimOptions::joints`].
    pub joints: Option<JointModel>,
    /// See [`SimOptions::self_collision`].
    pub self_collision: Option<bool>,
    /// See [`SimOptions::friction`].
    pub friction: Option<f64>,
    /// See [`SimOptions::actuator`].
    pub actuator: Option<ActuatorModel>,
    /// See [`SimOptions::strength`].
    pub strength: Option<f64>,
    /// See [`SimOptions::strength_from`].
    pub strength_from: Option<StrengthFrom>,
    /// See [`SimOptions::muscle_speed`].
    pub muscle_speed: Option<f64>,
    /// See [`SimOptions::max_speed`].
    pub max_speed: Option<f64>,
    /// See [`SimOptions::drop_height`].
    pub drop_height: Option<f64>,
    /// See [`SimOptions::explosion_distance`].
    pub explosion_distance: Option<f64>,
    /// See [`SimOptions::speed_limit`].
    pub speed_limit: Option<f64>,
    /// See [`SimOptions::energy_tolerance`].
    pub energy_tolerance: Option<f64>,
}

impl From<SimTable> for SimOptions {
    /// The named setting's values over the defaults, and the table's values over those.
    fn from(table: SimTable) -> SimOptions {
        let mut options = table
            .setting
            .unwrap_or_default()
            .apply(&SimOptions::default());
        macro_rules! over {
            ($($field:ident),*) => {$(if let Some(v) = table.$field { options.$field = v; })*};
        }
        if let Some(control_step) = table.control_step {
            options.control_step = control_step;
        }
        over!(
            substeps,
            solver_iterations,
            pgs_iterations,
            rest_substeps,
            rest_solver_iterations,
            joints,
            self_collision,
            friction,
            actuator,
            strength,
            strength_from,
            muscle_speed,
            max_speed,
            drop_height,
            explosion_distance,
            speed_limit,
            energy_tolerance
        );
        options
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_named_settings_are_the_options_they_name() {
        let base = SimOptions::default();
        let fast = StepSetting::Fast.apply(&base);
        assert_eq!(
            (
                fast.substeps,
                fast.solver_iterations,
                fast.pgs_iterations,
                fast.rest_substeps,
                fast.rest_solver_iterations
            ),
            (1, 2, 3, 2, 4)
        );
        assert_eq!(StepSetting::of(&base), Some(StepSetting::Default));
        assert_eq!(StepSetting::of(&base.fast()), Some(StepSetting::Fast));
        assert_eq!(
            StepSetting::of(&base.fine_reference()),
            Some(StepSetting::Fine)
        );
        let odd = SimOptions {
            substeps: 16,
            ..base.clone()
        };
        assert_eq!(StepSetting::of(&odd), None);
        // A setting leaves everything but the stepping alone.
        let coarse = SimOptions {
            control_step: 0.02,
            friction: 0.5,
            ..base
        };
        let fine = StepSetting::Fine.apply(&coarse);
        assert_eq!((fine.control_step, fine.friction), (0.02, 0.5));
    }

    #[test]
    fn a_setting_is_read_from_its_name_and_nothing_else() {
        for setting in StepSetting::ALL {
            assert_eq!(setting.name().parse::<StepSetting>(), Ok(setting));
            assert_eq!(setting.to_string(), setting.name());
        }
        let e = "Fast".parse::<StepSetting>().unwrap_err();
        assert_eq!(
            e.to_string(),
            "'Fast' is not a step setting (fast, default or fine)"
        );
    }

    #[test]
    fn a_table_takes_its_setting_and_overrides_it_with_its_own_keys() {
        let options: SimOptions =
            toml::from_str("setting = \"fast\"\nsubsteps = 3\nfriction = 0.5\n").unwrap();
        let fast = SimOptions::default().fast();
        assert_eq!(options.substeps, 3);
        assert_eq!(
            (
                options.solver_iterations,
                options.pgs_iterations,
                options.rest_substeps,
                options.rest_solver_iterations
            ),
            (
                fast.solver_iterations,
                fast.pgs_iterations,
                fast.rest_substeps,
                fast.rest_solver_iterations
            )
        );
        assert_eq!(options.friction, 0.5);
        // No setting: the default's values; an empty table is the defaults.
        let options: SimOptions = toml::from_str("").unwrap();
        assert_eq!(StepSetting::of(&options), Some(StepSetting::Default));
        // Written back resolved, without the name, and read back the same.
        let text = toml::to_string(&StepSetting::Fine.apply(&SimOptions::default())).unwrap();
        assert!(!text.contains("setting"), "{text}");
        assert!(text.contains("solver_iterations = 8"), "{text}");
        let again: SimOptions = toml::from_str(&text).unwrap();
        assert_eq!(StepSetting::of(&again), Some(StepSetting::Fine));
        // An unknown name or key is refused.
        let e = toml::from_str::<SimOptions>("setting = \"coarse\"\n").unwrap_err();
        assert!(e.to_string().contains("unknown variant `coarse`"), "{e}");
        let e = toml::from_str::<SimOptions>("substep = 2\n").unwrap_err();
        assert!(e.to_string().contains("unknown field `substep`"), "{e}");
    }

    #[test]
    fn the_control_step_is_read_under_its_name_and_its_old_one_and_written_under_its_name() {
        let new: SimOptions = toml::from_str("control_step = 0.02\n").unwrap();
        let old: SimOptions = toml::from_str("dt = 0.02\n").unwrap();
        assert_eq!((new.control_step, old.control_step), (0.02, 0.02));
        let text = toml::to_string(&old).unwrap();
        assert!(text.contains("control_step = 0.02"), "{text}");
        assert!(!text.contains("dt ="), "{text}");
        // Not both: one value, one key.
        let e = toml::from_str::<SimOptions>("dt = 0.02\ncontrol_step = 0.02\n").unwrap_err();
        assert!(e.to_string().contains("duplicate field"), "{e}");
    }
}
