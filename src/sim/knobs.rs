//! The simulator's knobs, each defined once ([`KNOBS`]): its config key (and the older name a
//! file may still use), its command-line flag, its range, unit and description, and how to read
//! and write it on [`SimOptions`]. What derives from the table: the `[task.sim]` reader (in
//! [`setting`](super::setting)), the range check ([`SimOptions::check`]), the command line's
//! stepping flags, the error messages' flag names, `bench`'s stepping notation and the
//! configuration reference's table of keys ([`reference_table`]). The error a value out of its
//! range gets is [`SettingError`].
//!
//! Adding a knob is a field of [`SimOptions`] (with its default) and one entry of [`KNOBS`].

use std::fmt;

use super::options::{
    ActuatorModel, JointModel, MAX_DT, MAX_ITERATIONS, MAX_SUBSTEPS, MIN_DT, SimOptions,
    StrengthFrom,
};

/// A knob's value, of one of the kinds [`SimOptions`] holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A real number.
    Real(f64),
    /// A whole number (a count of steps or iterations).
    Count(usize),
    /// A switch.
    Switch(bool),
    /// A joint model.
    Joints(JointModel),
    /// An actuator model.
    Actuator(ActuatorModel),
    /// Whose cross-section sets a joint's strength.
    StrengthFrom(StrengthFrom),
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Real(x) => write!(f, "{x}"),
            Value::Count(n) => write!(f, "{n}"),
            Value::Switch(b) => write!(f, "{b}"),
            Value::Joints(j) => f.write_str(j.name()),
            Value::Actuator(a) => f.write_str(a.name()),
            Value::StrengthFrom(s) => f.write_str(s.name()),
        }
    }
}

/// The values a knob may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// A whole number from 1 to `most`.
    Count {
        /// The largest allowed.
        most: usize,
    },
    /// A finite real in [`least`, `most`].
    Between {
        /// The smallest allowed.
        least: f64,
        /// The largest allowed.
        most: f64,
    },
    /// A finite real of at least `least` (above it, when `strictly`).
    From {
        /// The bound.
        least: f64,
        /// Whether the bound itself is refused.
        strictly: bool,
    },
    /// Any of the kind's values: a switch, or one of a vocabulary's names.
    Any,
}

impl Range {
    /// The range in words, as an error message says it after "must be": `1 to 64`, `finite
    /// and positive`, `in [0.001, 0.1]`.
    pub fn words(self) -> String {
        match self {
            Range::Count { most } => format!("1 to {most}"),
            Range::Between { least, most } => format!("in [{least}, {most}]"),
            Range::From { least, strictly } => match (least == 0.0, strictly) {
                (true, true) => "finite and positive".to_string(),
                (true, false) => "finite and not negative".to_string(),
                (false, true) => format!("finite and above {least}"),
                (false, false) => format!("finite and at least {least}"),
            },
            Range::Any => String::new(),
        }
    }

    /// Whether `value` is in the range.
    pub fn holds(self, value: Value) -> bool {
        match (self, value) {
            (Range::Count { most }, Value::Count(n)) => (1..=most).contains(&n),
            (Range::Between { least, most }, Value::Real(x)) => (least..=most).contains(&x),
            (Range::From { least, strictly }, Value::Real(x)) => {
                x.is_finite() && if strictly { x > least } else { x >= least }
            }
            (Range::Any, _) => true,
            _ => false,
        }
    }
}

/// One of the simulator's settings: everything the config reader, the range check, the
/// command line and the reference need to know about it.
#[derive(Clone, Copy)]
pub struct Knob {
    /// The key in `[task.sim]`, the field of [`SimOptions`].
    pub key: &'static str,
    /// The name files written before the key had its own still use (read as the key; a table
    /// may not give both; never written).
    pub older_key: Option<&'static str>,
    /// The command-line flag that sets it (`--time-step`), if there is one.
    pub flag: Option<&'static str>,
    /// Its range.
    pub range: Range,
    /// What the range's words are followed by in an error message: ` (0 turns the audit off)`.
    pub range_note: &'static str,
    /// Its unit, as the reference writes it; empty for a count, a switch or a name.
    pub unit: &'static str,
    /// What it is, in a phrase (no full stop): the `--help` of its flag and the reference's
    /// description.
    pub doc: &'static str,
    /// Whether it is one of the five stepping values a named step setting
    /// ([`StepSetting`](super::StepSetting)) sets.
    pub stepping: bool,
    /// Its value in `options`.
    pub get: fn(&SimOptions) -> Value,
    /// Sets it in `options`; a value of another kind leaves `options` as it is.
    pub set: fn(&mut SimOptions, Value),
}

impl Knob {
    /// The flag that names it in an error from the command line: its own, else the key in
    /// kebab case (`--drop-height`).
    pub fn flag_name(&self) -> String {
        self.flag.map_or_else(
            || format!("--{}", self.key.replace('_', "-")),
            str::to_string,
        )
    }

    /// Its range in words with its note, as an error message says it after "must be":
    /// `1 to 64`, `in [0.001, 0.1] seconds`, `finite and not negative (0 turns the audit off)`.
    pub fn range_words(&self) -> String {
        format!("{}{}", self.range.words(), self.range_note)
    }

    /// The `--help` of its flag: the phrase, its unit (but a span of seconds', which its range
    /// says) and its range, then `suffix` (` [default: the setting's]`), without a full stop
    /// (as clap writes a flag's one-line help). An enum knob's names are left to the flag's
    /// list of values ([`Knob::choices`]); a switch's flag that turns it off says so.
    pub fn help(&self, suffix: &str) -> String {
        let unit = match (self.unit, self.range) {
            ("", _) | (_, Range::Between { .. }) => String::new(),
            (unit, _) => format!(" ({unit})"),
        };
        let turns_off = matches!((self.get)(&SimOptions::default()), Value::Switch(_))
            && self.flag.is_some_and(|f| f.starts_with("--no-"));
        match self.range {
            Range::Any if turns_off => {
                format!("{} (on unless this flag is given){suffix}", self.doc)
            }
            Range::Any => format!("{}{unit}{suffix}", self.doc),
            _ => format!("{}{unit}, {}{suffix}", self.doc, self.range_words()),
        }
    }

    /// The names an enum knob takes, each with its summary, from its vocabulary (in the order
    /// `--help` lists them); none for a number or a switch.
    pub fn choices(&self) -> Vec<(&'static str, &'static str)> {
        fn of<T: Copy>(
            all: &[T],
            name: fn(T) -> &'static str,
            summary: fn(T) -> &'static str,
        ) -> Vec<(&'static str, &'static str)> {
            all.iter().map(|&v| (name(v), summary(v))).collect()
        }
        match (self.get)(&SimOptions::default()) {
            Value::Joints(_) => of(&JointModel::ALL, JointModel::name, JointModel::summary),
            Value::Actuator(_) => of(
                &ActuatorModel::ALL,
                ActuatorModel::name,
                ActuatorModel::summary,
            ),
            Value::StrengthFrom(_) => of(
                &StrengthFrom::ALL,
                StrengthFrom::name,
                StrengthFrom::summary,
            ),
            Value::Real(_) | Value::Count(_) | Value::Switch(_) => Vec::new(),
        }
    }

    /// Its value in `options` checked against its range; the error names the key.
    pub fn check(&self, options: &SimOptions) -> Result<(), SettingError> {
        let value = (self.get)(options);
        if self.range.holds(value) {
            return Ok(());
        }
        Err(SettingError::out_of_range(
            self.key,
            &self.range_words(),
            value,
        ))
    }
}

/// One entry of [`KNOBS`]: the field, the kind of its [`Value`], and the rest of [`Knob`]'s
/// fields but `key`, `get`, `set` (`older_key`, `flag`, `range_note` and `stepping` default to
/// none, empty and false).
macro_rules! knob {
    ($field:ident: $kind:ident { $($name:ident: $value:expr),* $(,)? }) => {
        Knob {
            key: stringify!($field),
            get: |o| Value::$kind(o.$field),
            set: |o, v| {
                if let Value::$kind(x) = v {
                    o.$field = x;
                }
            },
            $($name: $value,)*
            ..Knob::BLANK
        }
    };
}

impl Knob {
    /// The fields an entry of [`KNOBS`] leaves out.
    const BLANK: Knob = Knob {
        key: "",
        older_key: None,
        flag: None,
        range: Range::Any,
        range_note: "",
        unit: "",
        doc: "",
        stepping: false,
        get: |_| Value::Switch(false),
        set: |_, _| {},
    };
}

/// A count of substeps: 1 to [`MAX_SUBSTEPS`].
const SUBSTEPS: Range = Range::Count { most: MAX_SUBSTEPS };
/// A count of iterations: 1 to [`MAX_ITERATIONS`].
const ITERATIONS: Range = Range::Count {
    most: MAX_ITERATIONS,
};
/// Finite and not negative.
const NOT_NEGATIVE: Range = Range::From {
    least: 0.0,
    strictly: false,
};
/// Finite and positive.
const POSITIVE: Range = Range::From {
    least: 0.0,
    strictly: true,
};

/// Every knob of the simulator, in the order of [`SimOptions`]' fields (the order a run's
/// `config.toml` lists them and the check tries them).
pub const KNOBS: &[Knob] = &[
    knob!(control_step: Real {
        older_key: Some("dt"),
        flag: Some("--time-step"),
        range: Range::Between { least: MIN_DT, most: MAX_DT },
        range_note: " seconds",
        unit: "s",
        doc: "The control step: the brain runs once per step, the physics `--substeps` times per step",
    }),
    knob!(substeps: Count {
        flag: Some("--substeps"),
        range: SUBSTEPS,
        doc: "Physics substeps per control step",
        stepping: true,
    }),
    knob!(solver_iterations: Count {
        flag: Some("--solver-iterations"),
        range: ITERATIONS,
        doc: "Solver iterations per substep",
        stepping: true,
    }),
    knob!(pgs_iterations: Count {
        flag: Some("--pgs-iterations"),
        range: ITERATIONS,
        doc: "Gauss-Seidel passes inside each solver iteration",
        stepping: true,
    }),
    knob!(rest_substeps: Count {
        flag: Some("--rest-substeps"),
        range: SUBSTEPS,
        doc: "Substeps per control step while waiting for the creature to come to rest",
        stepping: true,
    }),
    knob!(rest_solver_iterations: Count {
        flag: Some("--rest-solver-iterations"),
        range: ITERATIONS,
        doc: "Solver iterations per substep while waiting for the creature to come to rest",
        stepping: true,
    }),
    knob!(joints: Joints {
        flag: Some("--joints"),
        doc: "The joint model",
    }),
    knob!(self_collision: Switch {
        flag: Some("--no-self-collision"),
        doc: "Whether parts of one creature that are not joint neighbours collide",
    }),
    knob!(friction: Real {
        range: NOT_NEGATIVE,
        doc: "Friction coefficient of the ground and the parts",
    }),
    knob!(actuator: Actuator {
        flag: Some("--actuator"),
        doc: "The actuator model",
    }),
    knob!(strength: Real {
        flag: Some("--strength"),
        range: NOT_NEGATIVE,
        unit: "N·m/m²",
        doc: "Joint strength: maximum torque per square metre of cross-section",
    }),
    knob!(strength_from: StrengthFrom {
        flag: Some("--strength-from"),
        doc: "Whose cross-section sets a joint's strength",
    }),
    knob!(muscle_speed: Real {
        flag: Some("--muscle-speed"),
        range: POSITIVE,
        unit: "rad/s",
        doc: "The muscle model's target speed V_des (Chaumont et al. 5.3), high so that muscles are torque-limited",
    }),
    knob!(max_speed: Real {
        range: POSITIVE,
        unit: "rad/s",
        doc: "The velocity model's top speed: a signal s asks for s × `max_speed`",
    }),
    knob!(drop_height: Real {
        range: NOT_NEGATIVE,
        unit: "m",
        doc: "Height of the creature's lowest point above the ground when it is dropped",
    }),
    knob!(explosion_distance: Real {
        range: POSITIVE,
        unit: "m",
        doc: "A part moving farther than this in one control step means the world exploded",
    }),
    knob!(speed_limit: Real {
        range: POSITIVE,
        unit: "m/s",
        doc: "A part faster than this means the world exploded",
    }),
    knob!(energy_tolerance: Real {
        flag: Some("--energy-tolerance"),
        range: NOT_NEGATIVE,
        range_note: " (0 turns the audit off)",
        unit: "J/kg",
        doc: "Energy from nowhere per kg of creature that counts as an explosion, in the energy audit",
    }),
];

/// The five stepping values of `options` in `bench`'s notation, `SxIxP/SxI`: substeps ×
/// solver iterations × PGS passes while walking, then substeps × iterations while waiting for
/// rest (`1x2x3/2x4`).
pub fn stepping_notation(options: &SimOptions) -> String {
    let [s, i, p, rest_s, rest_i] = stepping_of(options);
    format!("{s}x{i}x{p}/{rest_s}x{rest_i}")
}

/// The knob whose key (or older key) is `key`.
pub fn knob(key: &str) -> Option<&'static Knob> {
    KNOBS
        .iter()
        .find(|k| k.key == key || k.older_key == Some(key))
}

/// The five stepping knobs ([`Knob::stepping`]), in the order of [`SimOptions`]' fields:
/// substeps, solver iterations, PGS passes, rest substeps, rest solver iterations.
pub fn stepping_knobs() -> impl Iterator<Item = &'static Knob> {
    KNOBS.iter().filter(|k| k.stepping)
}

/// The five stepping values of `options`, in the order of [`stepping_knobs`].
pub fn stepping_of(options: &SimOptions) -> [usize; 5] {
    let mut values = [0; 5];
    for (v, knob) in values.iter_mut().zip(stepping_knobs()) {
        if let Value::Count(n) = (knob.get)(options) {
            *v = n;
        }
    }
    values
}

/// `options` with the five stepping values `values`, in the order of [`stepping_knobs`].
pub fn set_stepping(options: &mut SimOptions, values: [usize; 5]) {
    for (v, knob) in values.into_iter().zip(stepping_knobs()) {
        (knob.set)(options, Value::Count(v));
    }
}

impl SimOptions {
    /// Checks every value against its range ([`KNOBS`]), so that a world can be built and
    /// stepped in a bounded time: the control step in [[`MIN_DT`], [`MAX_DT`]] seconds,
    /// substeps 1 to [`MAX_SUBSTEPS`], solver iterations and Gauss-Seidel passes 1 to
    /// [`MAX_ITERATIONS`], friction, strength, drop height and energy tolerance finite and not
    /// negative, speeds and the explosion distance finite and positive. The error names the
    /// key of the first value out of range.
    pub fn check(&self) -> Result<(), SettingError> {
        KNOBS.iter().try_for_each(|knob| knob.check(self))
    }
}

/// The configuration reference's table of the `[task.sim]` keys (Markdown), from [`KNOBS`]:
/// each key, its default, its range and unit, and what it is. `docs/reference/configuration.md`
/// holds it, and a test checks it is this text.
pub fn reference_table() -> String {
    let defaults = SimOptions::default();
    let mut out =
        String::from("| key | default | range | flag | what it is |\n|---|---|---|---|---|\n");
    for knob in KNOBS {
        let default = match (knob.get)(&defaults) {
            Value::Real(x) => format!("{}", (x * 1e12).round() / 1e12),
            other => other.to_string(),
        };
        let default = match (knob.stepping, knob.unit) {
            (true, _) => format!("{default} (the setting's)"),
            (false, "") => default,
            (false, unit) => format!("{default} {unit}"),
        };
        let names: Vec<String> = knob
            .choices()
            .iter()
            .map(|(name, _)| format!("`{name}`"))
            .collect();
        let range = match names.split_last() {
            Some((last, [])) => last.clone(),
            Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
            None => knob.range_words(),
        };
        let key = match knob.older_key {
            Some(older) => format!("`{}` (older files: `{older}`)", knob.key),
            None => format!("`{}`", knob.key),
        };
        let flag = knob.flag.map_or_else(String::new, |f| format!("`{f}`"));
        out.push_str(&format!(
            "| {key} | {default} | {range} | {flag} | {}. |\n",
            knob.doc
        ));
    }
    out
}

/// A setting out of its range, or missing where it is needed: which key, in which table, and
/// what is wrong. The library names the key as a config file spells it (`[task.sim]
/// substeps`); a command line whose flag set the value names the flag instead
/// ([`SettingError::for_flag`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SettingError {
    /// The TOML table that holds the key, e.g. `task.sim`; empty when the options were checked
    /// on their own. An entry of an array of tables is named by its index from 0 after the
    /// array's name (`task.habitats.1`, its world `task.habitats.1.world`), so that the key
    /// can be found in the file; messages leave the index out ([`table_name`]).
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
            write!(
                f,
                "{} {} {}",
                table_name(&self.table),
                self.key,
                self.problem
            )
        }
    }
}

/// A table's path (`task.sim`, `task.habitats.1.world`, `task.habitats.1`) as a config file
/// heads it: `[task.sim]`, `[task.habitats.world]`; an entry of an array of tables itself,
/// `[[task.habitats]]`. Indices (whole numbers) are left out.
pub fn table_name(table: &str) -> String {
    let names: Vec<&str> = table
        .split('.')
        .filter(|t| !t.is_empty() && !t.bytes().all(|b| b.is_ascii_digit()))
        .collect();
    let entry = table
        .rsplit('.')
        .next()
        .is_some_and(|t| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit()));
    if entry {
        format!("[[{}]]", names.join("."))
    } else {
        format!("[{}]", names.join("."))
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
    let range = Range::From { least, strictly };
    if range.holds(Value::Real(value)) {
        return Ok(());
    }
    Err(SettingError::out_of_range(key, &range.words(), value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_is_named_as_a_config_heads_it_without_indices() {
        assert_eq!(table_name("task.sim"), "[task.sim]");
        assert_eq!(table_name("task.habitats.1"), "[[task.habitats]]");
        assert_eq!(
            table_name("task.habitats.12.world.slope"),
            "[task.habitats.world.slope]"
        );
        let mut e = SettingError::out_of_range("name", "unique", "'a'").within("task.habitats.3");
        assert_eq!(
            e.to_string(),
            "[[task.habitats]] name must be unique, not 'a'"
        );
        e.table.clear();
        assert_eq!(e.to_string(), "name must be unique, not 'a'");
    }

    #[test]
    fn every_field_of_the_options_is_one_knob_in_field_order() {
        let fields: Vec<String> = toml::Table::try_from(SimOptions::default())
            .unwrap()
            .keys()
            .cloned()
            .collect();
        let mut keys: Vec<String> = KNOBS.iter().map(|k| k.key.to_string()).collect();
        // toml's table is sorted; so is this list, for the comparison.
        keys.sort();
        assert_eq!(fields, keys);
        let serialised = toml::to_string(&SimOptions::default()).unwrap();
        let order: Vec<&str> = serialised
            .lines()
            .filter_map(|l| l.split_once(" = ").map(|(k, _)| k))
            .collect();
        let table: Vec<&str> = KNOBS.iter().map(|k| k.key).collect();
        assert_eq!(order, table);
    }

    #[test]
    fn each_knob_reads_and_writes_its_own_field() {
        let mut options = SimOptions::default();
        for knob in KNOBS {
            let changed = match (knob.get)(&options) {
                Value::Real(x) => Value::Real(x + 0.5),
                Value::Count(n) => Value::Count(n + 1),
                Value::Switch(b) => Value::Switch(!b),
                Value::Joints(_) => Value::Joints(JointModel::Multibody),
                Value::Actuator(_) => Value::Actuator(ActuatorModel::Velocity),
                Value::StrengthFrom(_) => Value::StrengthFrom(StrengthFrom::Smaller),
            };
            let before = toml::Table::try_from(&options).unwrap();
            (knob.set)(&mut options, changed);
            assert_eq!((knob.get)(&options), changed, "{}", knob.key);
            let after = toml::Table::try_from(&options).unwrap();
            let differing: Vec<&String> =
                after.keys().filter(|k| after[*k] != before[*k]).collect();
            assert_eq!(differing, [knob.key], "{}", knob.key);
        }
    }

    #[test]
    fn the_stepping_knobs_are_the_five_a_step_setting_sets() {
        let keys: Vec<&str> = stepping_knobs().map(|k| k.key).collect();
        assert_eq!(
            keys,
            [
                "substeps",
                "solver_iterations",
                "pgs_iterations",
                "rest_substeps",
                "rest_solver_iterations"
            ]
        );
        let mut options = SimOptions::default();
        assert_eq!(stepping_of(&options), [4, 4, 1, 4, 8]);
        set_stepping(&mut options, [1, 2, 3, 2, 4]);
        assert_eq!(stepping_notation(&options), "1x2x3/2x4");
        assert_eq!(
            (
                options.substeps,
                options.solver_iterations,
                options.pgs_iterations,
                options.rest_substeps,
                options.rest_solver_iterations
            ),
            (1, 2, 3, 2, 4)
        );
    }

    #[test]
    fn a_flag_s_help_is_its_phrase_and_its_range() {
        assert_eq!(
            knob("substeps").unwrap().help(" [default: the setting's]"),
            "Physics substeps per control step, 1 to 64 [default: the setting's]"
        );
        assert_eq!(
            knob("energy_tolerance").unwrap().help(""),
            "Energy from nowhere per kg of creature that counts as an explosion, in the energy audit (J/kg), finite and not negative (0 turns the audit off)"
        );
        assert_eq!(knob("dt").unwrap().key, "control_step");
        assert_eq!(knob("control_step").unwrap().flag_name(), "--time-step");
        assert_eq!(knob("drop_height").unwrap().flag_name(), "--drop-height");
        assert!(knob("substep").is_none());
        assert_eq!(knob("actuator").unwrap().help(""), "The actuator model");
        assert_eq!(
            knob("self_collision").unwrap().help(""),
            "Whether parts of one creature that are not joint neighbours collide (on unless this flag is given)"
        );
    }

    #[test]
    fn an_enum_knob_s_choices_are_its_vocabulary_s() {
        let names =
            |key| -> Vec<&str> { knob(key).unwrap().choices().iter().map(|c| c.0).collect() };
        assert_eq!(names("joints"), ["impulse", "multibody"]);
        assert_eq!(
            names("actuator"),
            ["muscle", "muscle-torque", "angle", "velocity"]
        );
        assert_eq!(names("strength_from"), ["smaller", "bigger"]);
        assert!(names("substeps").is_empty() && names("self_collision").is_empty());
        assert_eq!(
            knob("joints").unwrap().choices()[1],
            ("multibody", "Multibody (reduced-coordinate) joints")
        );
        let table = reference_table();
        assert!(table.contains(
            "| `actuator` | muscle | `muscle`, `muscle-torque`, `angle` or `velocity` | `--actuator` | The actuator model. |"
        ));
    }

    /// What adding a knob takes: one entry (and the field it reads and writes). This one
    /// reuses `friction`'s field under another key, to show the entry alone gives the range
    /// check, the message, the flag's name and help, and the reference's row.
    #[test]
    fn a_new_knob_is_one_entry() {
        let grip = knob!(friction: Real {
            flag: Some("--grip"),
            range: Range::Between { least: 0.0, most: 2.0 },
            doc: "How hard the ground holds",
        });
        let options = SimOptions {
            friction: 3.0,
            ..SimOptions::default()
        };
        let e = grip.check(&options).unwrap_err();
        assert_eq!(
            e.for_flag(&grip.flag_name()),
            "--grip must be in [0, 2], not 3"
        );
        assert_eq!(grip.help(""), "How hard the ground holds, in [0, 2]");
    }

    #[test]
    fn the_range_words_are_those_of_the_messages() {
        assert_eq!(
            check_real("x", -1.0, 0.0, false).unwrap_err().to_string(),
            "x must be finite and not negative, not -1"
        );
        assert_eq!(
            check_real("x", 0.0, 0.0, true).unwrap_err().to_string(),
            "x must be finite and positive, not 0"
        );
        assert_eq!(
            check_real("x", 1.0, 2.0, true).unwrap_err().to_string(),
            "x must be finite and above 2, not 1"
        );
        assert_eq!(
            check_real("x", f64::NAN, 2.0, false)
                .unwrap_err()
                .to_string(),
            "x must be finite and at least 2, not NaN"
        );
        assert_eq!(check_real("x", 2.0, 2.0, false), Ok(()));
    }
}
