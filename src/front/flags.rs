//! A task from `ontogeny eval`'s flags: its specification built and checked
//! ([`TaskFlags::spec`]), the flags the task does not use, and what `eval` says before and
//! after the evaluation (its progress label, the note on a long recording, the warning on a
//! coarse step setting, the result as text).

use crate::sim::{SettingError, SimOptions};

use crate::task::{
    CatapultOptions, Evaluation, MAX_RECORDED_SAMPLES, Status, TaskKind, TaskSpec, WalkerOptions,
};

/// The option that sets the value a [`SettingError`] names by its key, in snake case: a
/// simulator knob's flag ([`Knob::flag_name`](crate::sim::Knob::flag_name): `time_step` for
/// `control_step`), `seconds` for every task's duration, the key itself otherwise. The
/// command line spells it `--time-step`, Python `time_step=`.
pub fn option_of(key: &str) -> String {
    match (key, crate::sim::knobs::knob(key)) {
        ("seconds" | "max_seconds", _) => "seconds".to_string(),
        (_, Some(knob)) => knob.flag_name().trim_start_matches("--").replace('-', "_"),
        (key, None) => key.to_string(),
    }
}

/// The task flags of `ontogeny eval` (each `None` when not given).
#[derive(Clone, Debug)]
pub struct TaskFlags {
    /// `--task`.
    pub task: TaskKind,
    /// `--seconds`.
    pub seconds: Option<f64>,
    /// `--fitness`: one of the task's formulas by name, or an expression of its terms.
    pub fitness: Option<String>,
    /// `--activation`.
    pub activation: Option<f64>,
    /// `--target`.
    pub target: Option<[f64; 3]>,
    /// `--projectile-size`.
    pub projectile_size: Option<f64>,
    /// `--projectile-density`.
    pub projectile_density: Option<f64>,
}

impl TaskFlags {
    /// The task's specification with the simulator's settings `sim`, checked
    /// ([`TaskSpec::check`]); an error's key names the setting at fault.
    pub fn spec(&self, sim: SimOptions) -> Result<TaskSpec, SettingError> {
        if let Some(seconds) = self.seconds {
            crate::task::check_duration("seconds", seconds)?;
        }
        let mut spec = TaskSpec::new(self.task);
        spec.sim = sim;
        if let Some(fitness) = &self.fitness {
            spec.set_fitness(fitness);
        }
        if let (Some(walker), Some(a)) = (spec.task.get_mut::<WalkerOptions>(), self.activation) {
            walker.activation = a;
        }
        if let Some(s) = self.seconds {
            *spec.seconds_mut() = s;
        }
        if let Some(catapult) = spec.task.get_mut::<CatapultOptions>() {
            if let Some(size) = self.projectile_size {
                catapult.projectile_size = nalgebra::Vector3::repeat(size);
            }
            if let Some(density) = self.projectile_density {
                catapult.projectile_density = density;
            }
            if self.task == TaskKind::Aim {
                let [x, y, z] = self.target.unwrap_or([5.0, 0.0, 0.0]);
                catapult.target = Some(nalgebra::Vector3::new(x, y, z));
            }
        }
        spec.check()?;
        Ok(spec)
    }

    /// The flags given that the task does not use, each with the tasks it is for.
    pub fn inapplicable(&self) -> Vec<String> {
        let mut out = Vec::new();
        let task = self.task;
        if self.target.is_some() && task != TaskKind::Aim {
            out.push(match task {
                TaskKind::Catapult => {
                    "--target is for the aim task only (the catapult has no target)".to_string()
                }
                _ => "--target is for the aim task only".to_string(),
            });
        }
        if self.activation.is_some() && task != TaskKind::Walker {
            out.push("--activation is for the walker task only".to_string());
        }
        let throwing = task.throws();
        if self.projectile_size.is_some() && !throwing {
            out.push("--projectile-size is for the catapult and aim tasks only".to_string());
        }
        if self.projectile_density.is_some() && !throwing {
            out.push("--projectile-density is for the catapult and aim tasks only".to_string());
        }
        out
    }
}

/// Parses `X,Y,Z`: three finite numbers.
pub fn parse_point(text: &str) -> Result<[f64; 3], String> {
    let values: Vec<f64> = text
        .split(',')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .map_err(|_| format!("'{v}' is not a number"))
        })
        .collect::<Result<_, _>>()?;
    match values.as_slice() {
        [x, y, z] if values.iter().all(|v| v.is_finite()) => Ok([*x, *y, *z]),
        _ => Err(format!("'{text}' is not X,Y,Z")),
    }
}

/// What an evaluation of `spec` is, for a progress bar: `walker, 20 s`, `catapult`.
pub fn progress_label(spec: &TaskSpec) -> String {
    let task = spec.kind();
    if task.throws() {
        return task.name().to_string();
    }
    let seconds = *spec.clone().seconds_mut();
    format!("{}, {seconds} s", task.name())
}

/// The note for a recorded evaluation of `spec` long enough that its recording keeps only
/// one step in several.
pub fn recording_note(spec: &TaskSpec) -> Option<String> {
    let max_steps = spec.max_steps();
    let interval = crate::task::recording_interval(max_steps);
    let dt = spec.sim.control_step;
    (interval > 1).then(|| {
        format!(
            "note: this evaluation may take {max_steps} steps ({:.1} s): recording.json keeps one step in {interval} (a frame every {:.3} s), to stay under {} frames",
            max_steps as f64 * dt,
            interval as f64 * dt,
            MAX_RECORDED_SAMPLES
        )
    })
}

/// The warning for an evaluation in which the solver let a joint come apart more than
/// [`crate::sim::JOINT_GAP_WARNING`].
pub fn joint_gap_warning(evaluation: &Evaluation) -> Option<String> {
    let gap = *evaluation.terms.get("joint_gap")?;
    (gap > crate::sim::JOINT_GAP_WARNING).then(|| {
        format!(
            "warning: the solver let a joint come {:.1} cm apart: this step setting is too coarse \
             for this creature, and its fitness may not hold at a finer one (try --substeps 16 \
             --solver-iterations 8; docs/results/speed.md)",
            gap * 100.0
        )
    })
}

/// A line per habitat and trial of an evaluation with habitats
/// (`  habitat cued, trial 2: fitness 1.250000 (ok)`), then how they combine
/// (`  fitness: the mean of 4 walks`).
pub fn habitats_text(spec: &TaskSpec, evaluation: &Evaluation) -> String {
    let mut lines: Vec<String> = evaluation
        .units()
        .iter()
        .map(|r| {
            let place = match r.name.as_str() {
                "" => String::new(),
                name => format!("habitat {name}, "),
            };
            format!(
                "  {place}trial {}: fitness {:.6} ({})",
                r.trial + 1,
                r.fitness,
                r.status.name()
            )
        })
        .collect();
    let walks = evaluation.units().len();
    lines.push(match evaluation.status {
        Status::Ok => format!(
            "  fitness: the {} of {walks} walk{}",
            spec.trials.aggregate.name(),
            if walks == 1 { "" } else { "s" }
        ),
        _ => format!("  fitness: the failure floor, as a walk of the {walks} failed"),
    });
    lines.join("\n")
}

/// The evaluation of the creature named `name` as text: fitness and status, each term, and
/// the message if any.
pub fn evaluation_text(name: &str, evaluation: &Evaluation) -> String {
    let mut lines = vec![format!(
        "{name}: {} fitness {:.6} ({})",
        evaluation.task,
        evaluation.fitness,
        evaluation.status.name()
    )];
    for (name, value) in &evaluation.terms {
        lines.push(format!("  {name} = {value:.6}"));
    }
    if let Some(message) = &evaluation.message {
        lines.push(format!("  {message}"));
    }
    lines.join("\n")
}
