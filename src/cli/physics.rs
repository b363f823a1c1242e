//! The flags that set the simulated model, shared by every verb that simulates (`eval`,
//! `export`, `bench`, and `--setting`/`--task` on `evolve` and `compare`): the parsers of the
//! library's vocabularies (tasks, step settings, actuator and joint models), and the error
//! that names the flag at fault.

use clap::Args;
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use ontogeny::front::flags::option_of;
use ontogeny::sim::{ActuatorModel, SettingError, SimOptions, StepSetting, StrengthFrom};
use ontogeny::task::TaskKind;

/// The flags that set the simulated model: shared by `eval`, `export` and `bench`.
#[derive(Args)]
pub struct PhysicsArgs {
    /// Actuator model.
    #[arg(long, value_parser = actuator_parser(), default_value = "muscle")]
    actuator: ActuatorModel,
    /// Control time step in seconds, in [0.001, 0.1]; the physics runs `--substeps` times per
    /// step.
    #[arg(long, default_value_t = SimOptions::default().control_step)]
    time_step: f64,
    #[command(flatten)]
    stepping: SteppingArgs,
    /// Whose cross-section sets a joint's strength.
    #[arg(long, value_parser = names_parser(StrengthFrom::ALL, StrengthFrom::name, StrengthFrom::summary), default_value = "bigger")]
    strength_from: StrengthFrom,
    /// Joint strength: maximum torque per square metre of cross-section (N·m/m², finite, not
    /// negative).
    #[arg(long, default_value_t = ontogeny::sim::DEFAULT_STRENGTH)]
    strength: f64,
    /// The muscle model's target speed V_des (rad/s), high so that muscles are
    /// torque-limited (Chaumont et al. 5.3); finite and positive.
    #[arg(long, default_value_t = ontogeny::sim::DEFAULT_MUSCLE_SPEED)]
    muscle_speed: f64,
    /// Let parts of one creature pass through each other (joint neighbours never collide).
    #[arg(long)]
    no_self_collision: bool,
    /// Energy from nowhere, in J per kg of creature, that counts as an explosion (the energy
    /// audit; 0 turns it off).
    #[arg(long, default_value_t = ontogeny::sim::ENERGY_TOLERANCE)]
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
    names_parser(TaskKind::ALL, TaskKind::name, TaskKind::summary)
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
/// experts. Shared by `eval`, `export` and `bench`.
#[derive(Args)]
pub struct SteppingArgs {
    /// The named step setting [default: default]; the five stepping flags override its values.
    #[arg(long, value_name = "NAME", value_parser = setting_parser())]
    setting: Option<StepSetting>,
    /// Physics substeps per control step, 1 to 64 [default: the setting's].
    #[arg(long)]
    substeps: Option<usize>,
    /// Solver iterations per substep, 1 to 256 [default: the setting's].
    #[arg(long)]
    solver_iterations: Option<usize>,
    /// Gauss-Seidel passes inside each solver iteration, 1 to 256 [default: the setting's].
    #[arg(long)]
    pgs_iterations: Option<usize>,
    /// Substeps per control step while waiting for the creature to come to rest, 1 to 64
    /// [default: the setting's].
    #[arg(long)]
    rest_substeps: Option<usize>,
    /// Solver iterations per substep while waiting for the creature to come to rest, 1 to
    /// 256 [default: the setting's].
    #[arg(long)]
    rest_solver_iterations: Option<usize>,
}

/// `--fitness`: the walker's fitness formula, shared by `eval` and `replay`.
#[derive(Args)]
pub struct FitnessArgs {
    /// Walker fitness formula (walker only) [default: a run's or a champion file's own, else
    /// normalised].
    #[arg(long, value_parser = super::walker_fitness_parser())]
    pub fitness: Option<ontogeny::task::WalkerFitness>,
}

impl SteppingArgs {
    /// Whether any of the stepping flags (`--setting` and the five values) was given.
    pub fn any_given(&self) -> bool {
        self.setting.is_some()
            || self.substeps.is_some()
            || self.solver_iterations.is_some()
            || self.pgs_iterations.is_some()
            || self.rest_substeps.is_some()
            || self.rest_solver_iterations.is_some()
    }

    /// `base` with the named setting's stepping and the given stepping flags over it, checked
    /// ([`SimOptions::check`]); an error names the flag at fault.
    pub fn apply(&self, base: &SimOptions) -> anyhow::Result<SimOptions> {
        let mut options = self.setting.unwrap_or_default().apply(base);
        let flags = [
            (&mut options.substeps, self.substeps),
            (&mut options.solver_iterations, self.solver_iterations),
            (&mut options.pgs_iterations, self.pgs_iterations),
            (&mut options.rest_substeps, self.rest_substeps),
            (
                &mut options.rest_solver_iterations,
                self.rest_solver_iterations,
            ),
        ];
        for (field, flag) in flags {
            if let Some(value) = flag {
                *field = value;
            }
        }
        options.check().map_err(flag_error)?;
        Ok(options)
    }
}

/// The bad-input error for a setting a flag gave: the message names the flag (`--time-step`
/// for `control_step`, `--seconds` for a task's duration, else the key in kebab case: `--substeps`).
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
