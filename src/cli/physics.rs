//! The flags that set the simulated model, shared by every verb that simulates (`eval`,
//! `export`, `bench`, and `--setting`/`--task` on `evolve` and `compare`): the parsers of the
//! library's vocabularies (tasks, step settings, actuator and joint models), and the error
//! that names the flag at fault. The simulator's flags, their help and the names in their
//! errors come from the table of knobs ([`ontogeny::sim::KNOBS`]).

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Arg, ArgMatches, Args, Command, FromArgMatches};
use ontogeny::front::flags::option_of;
use ontogeny::sim::knobs::{Value, knob, stepping_knobs};
use ontogeny::sim::{ActuatorModel, Knob, SettingError, SimOptions, StepSetting, StrengthFrom};
use ontogeny::task::TaskKind;

use super::{FitnessOf, fitness_help};

/// The `--help` of the flag of the knob `key` ([`Knob::help`]).
pub fn help(key: &str) -> String {
    knob(key).map_or_else(String::new, |k| k.help(""))
}

/// The flags that set the simulated model: shared by `eval`, `export` and `bench`.
#[derive(Args)]
pub struct PhysicsArgs {
    #[arg(long, help = help("actuator"), value_parser = actuator_parser(), default_value = "muscle")]
    actuator: ActuatorModel,
    #[arg(long, help = help("control_step"), default_value_t = SimOptions::default().control_step)]
    time_step: f64,
    #[command(flatten)]
    stepping: SteppingArgs,
    #[arg(long, help = help("strength_from"), value_parser = names_parser(StrengthFrom::ALL, StrengthFrom::name, StrengthFrom::summary), default_value = "bigger")]
    strength_from: StrengthFrom,
    #[arg(long, help = help("strength"), default_value_t = ontogeny::sim::DEFAULT_STRENGTH)]
    strength: f64,
    #[arg(long, help = help("muscle_speed"), default_value_t = ontogeny::sim::DEFAULT_MUSCLE_SPEED)]
    muscle_speed: f64,
    #[arg(long, help = help("self_collision"))]
    no_self_collision: bool,
    #[arg(long, help = help("energy_tolerance"), default_value_t = ontogeny::sim::ENERGY_TOLERANCE)]
    energy_tolerance: f64,
}

/// The parser of one of a library vocabulary's names (`all`, each spelt by `name`), listed in
/// `--help` with each one's `summary`: the one definition of the names is the library's.
pub fn names_parser<T>(
    all: impl IntoIterator<Item = T>,
    name: fn(T) -> &'static str,
    summary: fn(T) -> &'static str,
) -> impl TypedValueParser<Value = T>
where
    T: Copy + Send + Sync + 'static + std::str::FromStr,
    T::Err: std::fmt::Display,
{
    let values = all
        .into_iter()
        .map(|v| PossibleValue::new(name(v)).help(summary(v)));
    PossibleValuesParser::new(values).try_map(|n: String| n.parse::<T>().map_err(|e| e.to_string()))
}

/// The parser of `--setting NAME` on every verb that simulates ([`StepSetting`]).
pub fn setting_parser() -> impl TypedValueParser<Value = StepSetting> {
    names_parser(StepSetting::ALL, StepSetting::name, StepSetting::summary)
}

/// The parser of `--task NAME` on every verb that takes one ([`TaskKind`]).
pub fn task_parser() -> impl TypedValueParser<Value = TaskKind> {
    names_parser(
        TaskKind::ALL.iter().copied(),
        TaskKind::name,
        TaskKind::summary,
    )
}

/// The parser of `--actuator NAME` on every verb that simulates ([`ActuatorModel`]).
pub fn actuator_parser() -> impl TypedValueParser<Value = ActuatorModel> {
    names_parser(
        ActuatorModel::ALL,
        ActuatorModel::name,
        ActuatorModel::summary,
    )
}

/// The step setting: a named one (`--setting`), and the five stepping flags over it, for
/// experts, one per stepping knob ([`stepping_knobs`]). Shared by `eval`, `export`, `bench`
/// and `replay`.
pub struct SteppingArgs {
    /// `--setting`.
    setting: Option<StepSetting>,
    /// The stepping flags given, with their values.
    values: Vec<(&'static Knob, usize)>,
}

impl Args for SteppingArgs {
    fn augment_args(command: Command) -> Command {
        let setting = Arg::new("setting")
            .long("setting")
            .value_name("NAME")
            .value_parser(setting_parser())
            .help(
                "The named step setting [default: default]; the five stepping flags override its values",
            );
        stepping_knobs().fold(command.arg(setting), |command, knob| {
            let long = knob.flag.map_or(knob.key, |f| f.trim_start_matches('-'));
            command.arg(
                Arg::new(knob.key)
                    .long(long)
                    // As clap's derive names a flag's value: the key in capitals (a few
                    // bytes, once per command line).
                    .value_name(&*knob.key.to_uppercase().leak())
                    .value_parser(clap::value_parser!(usize))
                    .help(knob.help(" [default: the setting's]")),
            )
        })
    }

    fn augment_args_for_update(command: Command) -> Command {
        Self::augment_args(command)
    }
}

impl FromArgMatches for SteppingArgs {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        Ok(SteppingArgs {
            setting: matches.get_one::<StepSetting>("setting").copied(),
            values: stepping_knobs()
                .filter_map(|k| Some((k, *matches.get_one::<usize>(k.key)?)))
                .collect(),
        })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = SteppingArgs::from_arg_matches(matches)?;
        Ok(())
    }
}

/// `--fitness`: the walker's fitness formula, shared by `eval` and `replay`.
#[derive(Args)]
pub struct FitnessArgs {
    #[arg(long, value_name = "FORMULA|EXPRESSION", help = fitness_help(FitnessOf::Evaluation))]
    pub fitness: Option<String>,
}

/// `--task` and `--fitness` of a run: shared by `evolve` and `compare`, over a config's.
#[derive(Args)]
pub struct RunTaskArgs {
    /// The task (default: the config's, else walker).
    #[arg(long, value_parser = task_parser())]
    pub task: Option<TaskKind>,
    #[arg(long, value_name = "FORMULA|EXPRESSION", help = fitness_help(FitnessOf::Run))]
    pub fitness: Option<String>,
}

impl SteppingArgs {
    /// Whether any of the stepping flags (`--setting` and the five values) was given.
    pub fn any_given(&self) -> bool {
        self.setting.is_some() || !self.values.is_empty()
    }

    /// `base` with the named setting's stepping and the given stepping flags over it, checked
    /// ([`SimOptions::check`]); an error names the flag at fault.
    pub fn apply(&self, base: &SimOptions) -> anyhow::Result<SimOptions> {
        let mut options = self.setting.unwrap_or_default().apply(base);
        for (knob, value) in &self.values {
            (knob.set)(&mut options, Value::Count(*value));
        }
        options.check().map_err(flag_error)?;
        Ok(options)
    }
}

/// The bad-input error for a setting a flag gave: the message names the flag (a knob's own,
/// [`Knob::flag_name`]: `--time-step` for `control_step`; `--seconds` for a task's duration;
/// else the key in kebab case).
pub fn flag_error(error: SettingError) -> anyhow::Error {
    let flag = format!("--{}", option_of(error.key).replace('_', "-"));
    super::bad(error.for_flag(&flag))
}

impl PhysicsArgs {
    /// The simulator settings the flags ask for (the rest at their defaults), or an error
    /// naming the flag that is out of range.
    pub fn sim_options(&self) -> anyhow::Result<SimOptions> {
        let base = SimOptions {
            control_step: self.time_step,
            strength: self.strength,
            muscle_speed: self.muscle_speed,
            self_collision: !self.no_self_collision,
            energy_tolerance: self.energy_tolerance,
            strength_from: self.strength_from,
            actuator: self.actuator,
            ..SimOptions::default()
        };
        self.stepping.apply(&base)
    }
}
