//! The simulator's settings as a user gives them: the named step settings (`fast`, `default`,
//! `fine`; [`SimOptions::fast`] and [`SimOptions::fine_reference`]), and the `[task.sim]`
//! table as a person writes it (a named setting with any of its values overridden), read key
//! by key from the table of knobs ([`KNOBS`]; the range check is [`SimOptions::check`]).
//!
//! What a setting means physically is documented on [`SimOptions`]; what a task does with it
//! belongs to `task`.

use std::fmt;
use std::str::FromStr;

use std::sync::OnceLock;

use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, Visitor};
use serde::{Deserialize, Serialize};

use super::knobs::{KNOBS, Knob, Value, knob, set_stepping, stepping_of};
use super::options::{DEFAULT_STEPPING, SimOptions};

/// The range error and check, at the path they had before the table of knobs held them.
pub use super::knobs::{SettingError, check_real};

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

/// The five stepping values of a setting, in the order of the stepping knobs
/// ([`stepping_knobs`](super::knobs::stepping_knobs)): substeps, solver iterations, PGS
/// passes, rest substeps, rest solver iterations.
type Stepping = [usize; 5];

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
            StepSetting::Fast => [1, 2, 3, 2, 4],
            StepSetting::Default => DEFAULT_STEPPING,
            StepSetting::Fine => [4, 8, 1, 4, 8],
        }
    }

    /// `base` with this setting's five stepping values; everything else as `base`.
    pub fn apply(self, base: &SimOptions) -> SimOptions {
        let mut options = base.clone();
        set_stepping(&mut options, self.stepping());
        options
    }

    /// The named setting whose five stepping values `options` has, if any.
    pub fn of(options: &SimOptions) -> Option<StepSetting> {
        let stepping = stepping_of(options);
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

impl SimOptions {
    /// The fast setting ([`StepSetting::Fast`]), the default until evolution was found to
    /// exploit it: one physics step of 1/60 s with 2 solver iterations of 3 Gauss-Seidel
    /// passes while walking, 2 substeps of 4 iterations while waiting for rest; everything else
    /// as `self`. About 4× cheaper than the default per walk (3.6× with the rest phases, 4.7×
    /// controller on), and good for ranking random creatures (`bench --fidelity`), but evolved
    /// creatures learn to walk on its errors (docs/results/speed.md).
    pub fn fast(&self) -> SimOptions {
        StepSetting::Fast.apply(self)
    }

    /// The fine reference setting ([`StepSetting::Fine`]): these settings with 4 physics
    /// substeps of 8 solver iterations (one PGS pass each) both while walking and while waiting
    /// for rest; the control step `dt` and everything else unchanged. At the default `dt` of
    /// 1/60 s that is physics at 1/240 s. `ontogeny bench --fidelity` ranks stepping settings
    /// against it, and `ontogeny evolve` re-walks each generation's best with it, since
    /// evolution learns to exploit a coarse setting (see docs/results/speed.md and
    /// docs/guide/evolving.md).
    pub fn fine_reference(&self) -> SimOptions {
        StepSetting::Fine.apply(self)
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

/// The keys of `[task.sim]` that have been renamed, as (today's name, the older name that
/// files written before may still use; serde reads both).
pub const RENAMED_KEYS: &[(&str, &str)] = &[("control_step", "dt")];

/// The `[task.sim]` table as a person writes it: a named step setting (`setting = "fast"`,
/// default `default`) and any knob's key ([`KNOBS`]) over it. A key given beside `setting`
/// overrides the setting's value. Read into [`SimOptions`], which holds every value resolved
/// and is written back that way (without `setting`), so that a run's `config.toml` never
/// depends on what a name means in a later version. A key renamed since is read under its
/// older name too ([`Knob::older_key`]; a table may not give both); an unknown key is refused
/// with the keys allowed.
impl<'de> Deserialize<'de> for SimOptions {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<SimOptions, D::Error> {
        deserializer.deserialize_struct("SimTable", table_keys(), TableVisitor)
    }
}

/// Every key a `[task.sim]` table may hold: `setting`, then each knob's, its older name after
/// it.
fn table_keys() -> &'static [&'static str] {
    static KEYS: OnceLock<Vec<&'static str>> = OnceLock::new();
    KEYS.get_or_init(|| {
        let mut keys = vec!["setting"];
        for knob in KNOBS {
            keys.push(knob.key);
            keys.extend(knob.older_key);
        }
        keys
    })
}

/// A key of a `[task.sim]` table.
enum TableKey {
    /// `setting`.
    Setting,
    /// A knob's key, or its older name.
    Knob(&'static Knob),
}

/// Reads a [`TableKey`], refusing an unknown one at its place.
struct TableKeySeed;

impl<'de> DeserializeSeed<'de> for TableKeySeed {
    type Value = TableKey;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<TableKey, D::Error> {
        deserializer.deserialize_identifier(self)
    }
}

impl Visitor<'_> for TableKeySeed {
    type Value = TableKey;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("field identifier")
    }

    fn visit_str<E: de::Error>(self, key: &str) -> Result<TableKey, E> {
        match (key, knob(key)) {
            ("setting", _) => Ok(TableKey::Setting),
            (_, Some(knob)) => Ok(TableKey::Knob(knob)),
            (_, None) => Err(E::unknown_field(key, table_keys())),
        }
    }
}

/// Reads a `[task.sim]` table into [`SimOptions`].
struct TableVisitor;

impl<'de> Visitor<'de> for TableVisitor {
    type Value = SimOptions;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("struct SimTable")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<SimOptions, A::Error> {
        let mut setting: Option<StepSetting> = None;
        let mut given: Vec<(&'static Knob, Value)> = Vec::new();
        let defaults = SimOptions::default();
        while let Some(key) = map.next_key_seed(TableKeySeed)? {
            match key {
                TableKey::Setting if setting.is_some() => {
                    return Err(de::Error::duplicate_field("setting"));
                }
                TableKey::Setting => setting = Some(map.next_value()?),
                TableKey::Knob(knob) if given.iter().any(|(k, _)| k.key == knob.key) => {
                    return Err(de::Error::duplicate_field(knob.key));
                }
                TableKey::Knob(knob) => {
                    let value = match (knob.get)(&defaults) {
                        Value::Real(_) => Value::Real(map.next_value()?),
                        Value::Count(_) => Value::Count(map.next_value()?),
                        Value::Switch(_) => Value::Switch(map.next_value()?),
                        Value::Joints(_) => Value::Joints(map.next_value()?),
                        Value::Actuator(_) => Value::Actuator(map.next_value()?),
                        Value::StrengthFrom(_) => Value::StrengthFrom(map.next_value()?),
                    };
                    given.push((knob, value));
                }
            }
        }
        // The named setting's values over the defaults, and the table's values over those.
        let mut options = setting.unwrap_or_default().apply(&defaults);
        for (knob, value) in given {
            (knob.set)(&mut options, value);
        }
        Ok(options)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_pass_the_check_and_every_named_setting_too() {
        for setting in StepSetting::ALL {
            assert_eq!(setting.apply(&SimOptions::default()).check(), Ok(()));
        }
    }

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
    fn the_renamed_keys_are_the_knobs_older_names() {
        let older: Vec<(&str, &str)> = KNOBS
            .iter()
            .filter_map(|k| Some((k.key, k.older_key?)))
            .collect();
        assert_eq!(older, RENAMED_KEYS);
    }

    #[test]
    fn a_table_s_errors_are_serde_s_own_at_the_key_or_value_at_fault() {
        let keys = "`setting`, `control_step`, `dt`, `substeps`, `solver_iterations`, `pgs_iterations`, `rest_substeps`, `rest_solver_iterations`, `joints`, `self_collision`, `friction`, `actuator`, `strength`, `strength_from`, `muscle_speed`, `max_speed`, `drop_height`, `explosion_distance`, `speed_limit`, `energy_tolerance`";
        let cases = [
            (
                "substep = 2\n",
                format!("unknown field `substep`, expected one of {keys}"),
                0..7,
            ),
            (
                "substeps = \"four\"\n",
                "invalid type: string \"four\", expected usize".to_string(),
                11..17,
            ),
            (
                "joints = \"hinge\"\n",
                "unknown variant `hinge`, expected `impulse` or `multibody`".to_string(),
                9..16,
            ),
            (
                "dt = 0.1\ncontrol_step = 0.1\n",
                "duplicate field `control_step`".to_string(),
                0..0,
            ),
            ("joints = 3\n", "wanted string or table".to_string(), 9..10),
            (
                "[x]\n",
                format!("unknown field `x`, expected one of {keys}"),
                1..2,
            ),
        ];
        for (text, message, span) in cases {
            let e = toml::from_str::<SimOptions>(text).unwrap_err();
            assert_eq!(
                (e.message(), e.span()),
                (message.as_str(), Some(span)),
                "{text}"
            );
        }
        let e = serde_json::from_str::<SimOptions>("{\"x\": 1}").unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("unknown field `x`, expected one of {keys} at line 1 column 4")
        );
        let e = serde_json::from_str::<SimOptions>("3").unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid type: integer `3`, expected struct SimTable at line 1 column 1"
        );
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
