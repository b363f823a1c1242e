//! `ontogeny eval`

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::builder::TypedValueParser;
use clap::{Args, ValueEnum};
use ontogeny::creature::{Creature, Severity};
use ontogeny::develop::{BuildOptions, grow_last};
use ontogeny::lang::{Diagnostic, DiagnosticKind};
use ontogeny::lsystem::{DEFAULT_MAX_MODULES, LSystem};
use ontogeny::sim::{
    ActuatorModel, JointModel, SettingError, SimOptions, StepSetting, StrengthFrom,
};
use ontogeny::task::{self, Evaluation, TaskKind, TaskSpec, WalkerFitness};

use super::derive::{DevelopmentArgs, derive_options, discrete_steps};
use super::progress::Progress;

/// The tasks.
#[derive(Clone, Copy, ValueEnum)]
enum TaskArg {
    /// Chaumont et al.'s walker: distance of the root part, normalised by size (eq. 1).
    Walker,
    /// Walking with Dinosaurs' jump: best height of the lowest point.
    Jump,
    /// Chaumont et al.'s catapult: distance the projectile travels (eq. 2).
    Catapult,
    /// Chaumont et al.'s aiming catapult: D_p − D_t (eq. 3).
    Aim,
}

/// Joint models.
#[derive(Clone, Copy, ValueEnum)]
enum JointsArg {
    /// Impulse joints (the default: faster).
    Impulse,
    /// Multibody (reduced-coordinate) joints.
    Multibody,
}

/// Actuator models.
#[derive(Clone, Copy, ValueEnum)]
pub enum ActuatorArg {
    /// Chaumont's muscle: saturated motor, torque scaled by |signal|.
    Muscle,
    /// Chaumont's muscle as a torque of signal × strength on the joint's two parts, without
    /// a motor constraint.
    MuscleTorque,
    /// Hornby's: the signal sets the target angle.
    Angle,
    /// Matos's: the signal sets the target speed.
    Velocity,
}

impl ActuatorArg {
    /// The library's actuator model of this name.
    pub fn model(self) -> ActuatorModel {
        match self {
            ActuatorArg::Muscle => ActuatorModel::Muscle,
            ActuatorArg::MuscleTorque => ActuatorModel::MuscleTorque,
            ActuatorArg::Angle => ActuatorModel::Angle,
            ActuatorArg::Velocity => ActuatorModel::Velocity,
        }
    }
}

/// Whose cross-section sets a joint's strength.
#[derive(Clone, Copy, ValueEnum)]
enum StrengthArg {
    /// The smaller part's (Walking with Dinosaurs 3.4.4).
    Smaller,
    /// The bigger part's (Chaumont et al. 3.4, after Sims; the default).
    Bigger,
}

/// The flags that set the simulated model: shared by `eval`, `export` and `bench`.
#[derive(Args)]
pub struct PhysicsArgs {
    /// Actuator model.
    #[arg(long, value_enum, default_value = "muscle")]
    actuator: ActuatorArg,
    /// Control time step in seconds, in [0.001, 0.1]; the physics runs `--substeps` times per
    /// step.
    #[arg(long, default_value_t = SimOptions::default().dt)]
    time_step: f64,
    #[command(flatten)]
    stepping: SteppingArgs,
    /// Whose cross-section sets a joint's strength.
    #[arg(long, value_enum, default_value = "bigger")]
    strength_from: StrengthArg,
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

/// The parser of `--setting NAME` on every verb that simulates: the names and summaries of the
/// library's [`StepSetting`] (one definition of the names), listed in `--help`.
pub fn setting_parser() -> impl TypedValueParser<Value = StepSetting> {
    let names =
        StepSetting::ALL.map(|s| clap::builder::PossibleValue::new(s.name()).help(s.summary()));
    clap::builder::PossibleValuesParser::new(names)
        .try_map(|name: String| name.parse::<StepSetting>())
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

impl SteppingArgs {
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
    let flag = match error.key {
        "control_step" => "--time-step".to_string(),
        "seconds" | "max_seconds" => "--seconds".to_string(),
        key => format!("--{}", key.replace('_', "-")),
    };
    anyhow::Error::new(Diagnostic::without_location(
        DiagnosticKind::Semantic,
        error.for_flag(&flag),
    ))
}

impl PhysicsArgs {
    /// The simulator settings the flags ask for (the rest at their defaults), or an error
    /// naming the flag that is out of range.
    pub fn sim_options(&self) -> anyhow::Result<SimOptions> {
        let base = SimOptions {
            dt: self.time_step,
            strength: self.strength,
            muscle_speed: self.muscle_speed,
            self_collision: !self.no_self_collision,
            energy_tolerance: self.energy_tolerance,
            strength_from: match self.strength_from {
                StrengthArg::Smaller => StrengthFrom::Smaller,
                StrengthArg::Bigger => StrengthFrom::Bigger,
            },
            actuator: self.actuator.model(),
            ..SimOptions::default()
        };
        self.stepping.apply(&base)
    }
}

/// Flags of `ontogeny eval`.
#[derive(Args)]
pub struct EvalArgs {
    /// An L-system file (`.lsys`, grown to its last frame), a `creature.json` or a graph
    /// genome (`.json`); `-` reads an L-system from standard input.
    file: PathBuf,
    /// The task.
    #[arg(long, value_enum)]
    task: TaskArg,
    /// Seconds of evaluation, in (0, 3600] (walker: measured walking, default 20; jump:
    /// default 10; catapult and aim: the cap on waiting for the projectile to rest, default
    /// 60).
    #[arg(long)]
    seconds: Option<f64>,
    /// Seed for growing the creature from an L-system.
    #[arg(long)]
    seed: Option<u64>,
    #[command(flatten)]
    development: DevelopmentArgs,
    /// Most parts: a creature grown from an L-system with more is invalid, a
    /// `creature.json` with more is refused.
    #[arg(long, default_value_t = BuildOptions::default().max_parts)]
    max_parts: usize,
    /// Joint model.
    #[arg(long, value_enum, default_value = "impulse")]
    joints: JointsArg,
    #[command(flatten)]
    physics: PhysicsArgs,
    /// Walker fitness formula (walker only) [default: normalised].
    #[arg(long, value_parser = super::walker_fitness_parser())]
    fitness: Option<WalkerFitness>,
    /// Seconds of the walker's first activation of the controller, between its two waits
    /// for rest, in [0, 3600] (walker only) [default: 1, Chaumont et al.'s final protocol;
    /// 0.15 is their first attempt, 9 steps of 1/60 s].
    #[arg(long, value_name = "SECONDS")]
    activation: Option<f64>,
    /// The aim task's target relative to the projectile's start, as X,Y,Z metres (aim only)
    /// [default: 5,0,0].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true)]
    target: Option<[f64; 3]>,
    /// The projectile: edge length of the cube in metres, positive (catapult and aim)
    /// [default: 0.2].
    #[arg(long)]
    projectile_size: Option<f64>,
    /// The projectile: density in kg/m³, positive (catapult and aim) [default: 1000].
    #[arg(long)]
    projectile_density: Option<f64>,
    /// Write recording.json (every part's pose per step; a long run keeps evenly spaced
    /// steps, at most 12,000 frames) and behaviour.gif into DIR.
    #[arg(long, value_name = "DIR")]
    record: Option<PathBuf>,
    /// Print the evaluation as JSON.
    #[arg(long)]
    json: bool,
}

/// The flags given that the chosen task does not use, each with the tasks it is for.
fn inapplicable_flags(args: &EvalArgs) -> Vec<String> {
    let mut out = Vec::new();
    let task = args.task;
    if args.fitness.is_some() && !matches!(task, TaskArg::Walker) {
        out.push("--fitness is for the walker task only".to_string());
    }
    if args.target.is_some() && !matches!(task, TaskArg::Aim) {
        out.push("--target is for the aim task only (the catapult has no target)".to_string());
    }
    let throwing = matches!(task, TaskArg::Catapult | TaskArg::Aim);
    if args.projectile_size.is_some() && !throwing {
        out.push("--projectile-size is for the catapult and aim tasks only".to_string());
    }
    if args.projectile_density.is_some() && !throwing {
        out.push("--projectile-density is for the catapult and aim tasks only".to_string());
    }
    out
}

fn parse_point(text: &str) -> Result<[f64; 3], String> {
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

/// How the input is named in reports: its path, or `<stdin>` for `-` (as in diagnostics).
fn input_name(file: &Path) -> String {
    if file.as_os_str() == "-" {
        "<stdin>".to_string()
    } else {
        file.display().to_string()
    }
}

/// Loads a creature from `file`: an L-system (`.lsys`, grown to its last frame with the
/// development flags and seed, invalid beyond `max_parts` parts), a `creature.json`, which
/// must be well formed and have at most `max_parts` parts, or a graph genome's JSON
/// (checked against the default limits before it develops, and developed with them).
pub(super) fn load_creature(
    file: &Path,
    development: &DevelopmentArgs,
    seed: Option<u64>,
    max_parts: usize,
) -> anyhow::Result<Creature> {
    if file.extension().is_some_and(|e| e == "json") {
        let given = development.given();
        if !given.is_empty() || seed.is_some() {
            let mut flags = given;
            if seed.is_some() {
                flags.push("--seed");
            }
            eprintln!(
                "warning: {} grow a creature from a grammar; {} is not one: ignored",
                flags.join(", "),
                file.display()
            );
        }
        let text = std::fs::read_to_string(file)
            .with_context(|| format!("cannot read {}", file.display()))?;
        // A graph genome (a run's best.json) develops with the default limits. Only the
        // presence of "nodes" is looked at here: the file is not held as a whole a second
        // time.
        if is_graph_genome(&text) {
            let genome = super::genome::read_graph(file)?;
            return Ok(genome.creature(ontogeny::encoding::GraphLimits::default().max_parts));
        }
        let creature: Creature = serde_json::from_str(&text).map_err(|e| {
            anyhow::Error::new(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!("{}: not a creature: {e}", file.display()),
            ))
        })?;
        creature.check_file(max_parts).map_err(|problem| {
            anyhow::Error::new(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!("{}: not a usable creature: {problem}", file.display()),
            ))
        })?;
        return Ok(creature);
    }
    let lsys = LSystem::from_path(file)?;
    let options = derive_options(development, seed, DEFAULT_MAX_MODULES);
    let steps = discrete_steps(&lsys, &options, development.steps, "building")?;
    let build_options = BuildOptions {
        max_parts,
        ..BuildOptions::default()
    };
    let mut progress = Progress::new("growing");
    let creature = grow_last(&lsys, &options, steps, &build_options, &mut |f| {
        progress.set(f)
    })?
    .creature;
    progress.finish();
    // The builder's warnings, as `grow` lists them (its errors make the creature invalid,
    // which the evaluation reports).
    for problem in &creature.problems {
        if problem.severity == Severity::Warning {
            eprintln!("{}", super::grow::problem_line(problem));
        }
    }
    Ok(creature)
}

/// The task and its settings the flags ask for, checked ([`TaskSpec::check`]); an error names
/// the flag at fault.
fn task_spec(args: &EvalArgs) -> anyhow::Result<TaskSpec> {
    let physics = args.physics.sim_options()?;
    if let Some(seconds) = args.seconds {
        task::check_duration("seconds", seconds).map_err(flag_error)?;
    }
    let mut spec = TaskSpec::new(match args.task {
        TaskArg::Walker => TaskKind::Walker,
        TaskArg::Jump => TaskKind::Jump,
        TaskArg::Catapult => TaskKind::Catapult,
        TaskArg::Aim => TaskKind::Aim,
    });
    spec.sim = SimOptions {
        joints: match args.joints {
            JointsArg::Impulse => JointModel::Impulse,
            JointsArg::Multibody => JointModel::Multibody,
        },
        ..physics
    };
    spec.walker.fitness = args.fitness.unwrap_or(WalkerFitness::Normalised);
    if let Some(a) = args.activation {
        spec.walker.activation = a;
    }
    if let Some(s) = args.seconds {
        spec.walker.seconds = s;
        spec.jump.seconds = s;
        spec.catapult.max_seconds = s;
    }
    if let Some(size) = args.projectile_size {
        spec.catapult.projectile_size = nalgebra::Vector3::repeat(size);
    }
    if let Some(density) = args.projectile_density {
        spec.catapult.projectile_density = density;
    }
    if spec.task == TaskKind::Aim {
        let [x, y, z] = args.target.unwrap_or([5.0, 0.0, 0.0]);
        spec.catapult.target = Some(nalgebra::Vector3::new(x, y, z));
    }
    spec.check().map_err(flag_error)?;
    Ok(spec)
}

/// Whether a `.json` file's text is a graph genome (an object with `nodes`) rather than a
/// creature, read without building anything of it.
fn is_graph_genome(text: &str) -> bool {
    #[derive(serde::Deserialize)]
    struct Probe {
        nodes: Option<serde::de::IgnoredAny>,
    }
    serde_json::from_str::<Probe>(text).is_ok_and(|p| p.nodes.is_some())
}

/// Evaluates the creature and prints the result.
pub fn run(args: &EvalArgs) -> anyhow::Result<()> {
    let creature = load_creature(&args.file, &args.development, args.seed, args.max_parts)?;
    let spec = task_spec(args)?;
    // A place to record into, checked before the evaluation runs.
    if let Some(dir) = &args.record {
        if dir.exists() && !dir.is_dir() {
            anyhow::bail!(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!(
                    "--record {}: a file is there; give a directory (made if missing)",
                    dir.display()
                ),
            ));
        }
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        super::check_outputs(["recording.json", "behaviour.gif"].map(|f| dir.join(f)))?;
    }
    let sim = &spec.sim;
    let record = args.record.is_some();
    for flag in inapplicable_flags(args) {
        eprintln!("warning: {flag}; ignored");
    }
    let what = match spec.task {
        TaskKind::Walker => format!("walker, {} s", spec.walker.seconds),
        TaskKind::Jump => format!("jump, {} s", spec.jump.seconds),
        TaskKind::Catapult => "catapult".to_string(),
        TaskKind::Aim => "aim".to_string(),
    };
    let mut progress = Progress::new(what);
    let mut tell = |fraction: f64| progress.set(fraction);
    let note = |max_steps: usize| {
        let interval = task::recording_interval(max_steps);
        if record && interval > 1 {
            eprintln!(
                "note: this evaluation may take {max_steps} steps ({:.1} s): recording.json keeps one step in {interval} (a frame every {:.3} s), to stay under {} frames",
                max_steps as f64 * sim.dt,
                interval as f64 * sim.dt,
                task::MAX_RECORDED_FRAMES
            );
        }
    };
    let evaluation = match spec.task {
        TaskKind::Walker => {
            note(spec.walker.max_steps(sim.dt));
            task::walker_with_progress(&creature, sim, &spec.walker, record, &mut tell)
        }
        TaskKind::Jump => {
            note(spec.jump.max_steps(sim.dt));
            task::jump_with_progress(&creature, sim, &spec.jump, record, &mut tell)
        }
        TaskKind::Catapult | TaskKind::Aim => {
            note(spec.catapult.max_steps(sim.dt));
            task::catapult_with_progress(&creature, sim, &spec.catapult, record, &mut tell)
        }
    };
    progress.finish();
    if let Some(&gap) = evaluation.terms.get("joint_gap")
        && gap > ontogeny::sim::JOINT_GAP_WARNING
    {
        eprintln!(
            "warning: the solver let a joint come {:.1} cm apart: this step setting is too coarse \
             for this creature, and its fitness may not hold at a finer one (try --substeps 16 \
             --solver-iterations 8; README, \"Speed and fidelity\")",
            gap * 100.0
        );
    }
    if let Some(dir) = &args.record {
        write_recording(dir, &creature, &evaluation)?;
    }
    if args.json {
        let mut shown = evaluation.clone();
        shown.recording.clear();
        say!("{}", serde_json::to_string_pretty(&shown)?);
        return Ok(());
    }
    let status = serde_json::to_value(evaluation.status)?;
    say!(
        "{}: {} fitness {:.6} ({})",
        input_name(&args.file),
        evaluation.task,
        evaluation.fitness,
        status.as_str().unwrap_or("?")
    );
    for (name, value) in &evaluation.terms {
        say!("  {name} = {value:.6}");
    }
    if let Some(message) = &evaluation.message {
        say!("  {message}");
    }
    if let Some(dir) = &args.record {
        say!(
            "wrote {0}/recording.json and {0}/behaviour.gif",
            dir.display()
        );
    }
    Ok(())
}

fn write_recording(dir: &Path, creature: &Creature, evaluation: &Evaluation) -> anyhow::Result<()> {
    write_recording_at(dir, creature, evaluation, 10.0)
}

/// Writes `DIR/recording.json` and `DIR/behaviour.gif` (`fps` pictures per simulated second).
pub fn write_recording_at(
    dir: &Path,
    creature: &Creature,
    evaluation: &Evaluation,
    fps: f64,
) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let path = dir.join("recording.json");
    // In the terms of every aim evaluation that got as far as placing the projectile, failed
    // or not.
    let target: Option<Vec<f64>> = ["target_x", "target_y", "target_z"]
        .iter()
        .map(|k| evaluation.terms.get(*k).copied())
        .collect();
    // Written straight from the frames (not through a `serde_json::Value`, which would widen
    // their f32 poses back to f64 digits).
    #[derive(serde::Serialize)]
    struct RecordingFile<'a> {
        creature: &'a Creature,
        task: &'a str,
        status: task::Status,
        message: Option<&'a str>,
        target: Option<Vec<f64>>,
        frames: &'a [ontogeny::task::RecordedFrame],
    }
    let file = RecordingFile {
        creature,
        task: &evaluation.task,
        status: evaluation.status,
        message: evaluation.message.as_deref(),
        target: target.clone(),
        frames: &evaluation.recording,
    };
    ontogeny::output::write(&path, serde_json::to_string(&file)?)?;
    let status = serde_json::to_value(evaluation.status)?;
    let why = format!(
        "{}: {}",
        status.as_str().unwrap_or("?"),
        evaluation
            .message
            .as_deref()
            .unwrap_or("the evaluation was refused before simulating")
    );
    draw_recording(
        creature,
        &evaluation.recording,
        target.map(|t| nalgebra::Vector3::new(t[0], t[1], t[2])),
        &dir.join("behaviour.gif"),
        fps,
        &why,
    )?;
    Ok(())
}

/// The largest `--fps` an animation takes: GIF delays are whole centiseconds, and browsers
/// slow frames shorter than 2 cs down to 10.
pub const MAX_FPS: f64 = 50.0;

/// The most frames a GIF holds (behaviour.gif and growth.gif; 10–11 MB at 480 × 300):
/// longer evaluations are drawn at a lower frame rate, longer growth with frames left out.
pub const MAX_GIF_FRAMES: usize = 600;

/// Which of frames at `times` (in time order) a GIF of at most `max` frames shows: the frame
/// nearest each of `max` times evenly spaced from the first to the last, each frame once, the
/// first and last always. All of them when there are no more than `max`.
pub fn evenly_in_time(times: &[f64], max: usize) -> Vec<usize> {
    let n = times.len();
    if n <= max || n == 0 {
        return (0..n).collect();
    }
    if max < 2 {
        return vec![n - 1];
    }
    let (first, last) = (times[0], times[n - 1]);
    let mut chosen: Vec<usize> = Vec::with_capacity(max);
    let mut next = 0;
    for k in 0..max {
        let t = first + (last - first) * k as f64 / (max - 1) as f64;
        while next + 1 < n && (times[next + 1] - t).abs() <= (times[next] - t).abs() {
            next += 1;
        }
        if chosen.last() != Some(&next) {
            chosen.push(next);
        }
    }
    chosen[0] = 0;
    if chosen.last() != Some(&(n - 1)) {
        chosen.push(n - 1);
    }
    chosen.dedup();
    chosen
}

/// Which recorded frames an animation at `fps` frames per second of simulated time shows
/// (the frame nearest each time k / fps), and each one's GIF delay in centiseconds, chosen
/// so that frame k starts at round(100 k / fps) cs: played back, the animation keeps the
/// simulation's time, whatever the ratio of `fps` to the recording's rate. Returns the frame
/// rate used too: lower than `fps` when the recording is too long for [`MAX_GIF_FRAMES`].
pub fn animation_frames(
    frames: &[ontogeny::task::RecordedFrame],
    fps: f64,
) -> (Vec<usize>, Vec<u16>, f64) {
    let (Some(first), Some(last)) = (frames.first(), frames.last()) else {
        return (Vec::new(), Vec::new(), fps);
    };
    let span = (last.t - first.t).max(0.0);
    // A long evaluation is shown at a lower rate, so the GIF stays under MAX_GIF_FRAMES.
    let fps = if span * fps + 1.0 > MAX_GIF_FRAMES as f64 {
        (MAX_GIF_FRAMES - 1) as f64 / span
    } else {
        fps
    };
    let count = (span * fps + 1e-9).floor() as usize + 1;
    let mut chosen = Vec::with_capacity(count);
    let mut next = 0;
    for k in 0..count {
        let t = first.t + k as f64 / fps;
        // The recorded frame nearest t (frames are in time order).
        while next + 1 < frames.len()
            && (frames[next + 1].t - t).abs() <= (frames[next].t - t).abs()
        {
            next += 1;
        }
        chosen.push(next);
    }
    let start = |k: usize| (100.0 * k as f64 / fps).round() as u64;
    let delays = (0..count)
        .map(|k| (start(k + 1) - start(k)).clamp(2, u16::MAX as u64) as u16)
        .collect();
    (chosen, delays, fps)
}

/// Simulated seconds for a note: to the millisecond, without trailing zeros (`601.483`).
fn seconds_text(seconds: f64) -> String {
    ontogeny::lsystem::format_number((seconds * 1000.0).round() / 1000.0)
}

/// The most points of a projectile's trail drawn in one frame.
const MAX_TRAIL_POINTS: usize = 400;

/// Renders recorded frames as an animation, `fps` pictures per second of simulated time:
/// each frame labelled with its simulated time and the protocol's phase, the projectile's
/// trail so far drawn, and `target` (the aim task's, in world coordinates) when there is one.
///
/// A recording without frames (an evaluation refused before simulating) is drawn as one
/// picture of the creature as built, checked, saying that nothing was recorded.
pub fn render_recording(
    creature: &Creature,
    frames: &[ontogeny::task::RecordedFrame],
    target: Option<nalgebra::Vector3<f64>>,
    path: &Path,
    fps: f64,
) -> anyhow::Result<()> {
    draw_recording(
        creature,
        frames,
        target,
        path,
        fps,
        "the evaluation was refused before simulating",
    )
}

/// The most characters of a line of a refused recording's picture (its 3D view's width in
/// the 8-pixel font, less a margin).
const STILL_LINE: usize = 40;

/// `text` broken at spaces into lines of at most `width` characters (a longer word alone on
/// its line).
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(line) if line.chars().count() + 1 + word.chars().count() <= width => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// [`render_recording`], with `why` (the status and message of the evaluation) written on the
/// picture of a recording without frames.
fn draw_recording(
    creature: &Creature,
    frames: &[ontogeny::task::RecordedFrame],
    target: Option<nalgebra::Vector3<f64>>,
    path: &Path,
    fps: f64,
    why: &str,
) -> anyhow::Result<()> {
    if frames.is_empty() {
        let label: Vec<String> = std::iter::once("no frames recorded (starting pose)".to_string())
            .chain(wrap(why, STILL_LINE))
            .collect();
        ontogeny::render::write_still_gif(creature, &label, path, 480, 300)
            .map_err(super::render_error(path))?;
        return Ok(());
    }
    let (chosen, delays, shown_fps) = animation_frames(frames, fps);
    if shown_fps < fps {
        eprintln!(
            "note: {} s recorded: {} is drawn at {shown_fps:.3} frames/s instead of {fps}, to keep to {MAX_GIF_FRAMES} frames",
            seconds_text(frames.last().map_or(0.0, |f| f.t)),
            path.display()
        );
    }
    let posed: Vec<Creature> = chosen
        .iter()
        .map(|&i| &frames[i])
        .map(|frame| {
            let mut c = creature.clone();
            for (part, (position, orientation)) in c.parts.iter_mut().zip(&frame.parts) {
                part.position = *position;
                part.orientation = *orientation;
            }
            if let Some(p) = frame.projectile {
                // The projectile, drawn orange like a growing part.
                c.parts.push(ontogeny::creature::Part {
                    size: frame
                        .projectile_size
                        .unwrap_or(nalgebra::Vector3::repeat(0.2)),
                    position: p,
                    orientation: nalgebra::UnitQuaternion::identity(),
                    density: 1.0,
                    growing: true,
                });
            }
            // Joints move with their parent part.
            for joint in &mut c.joints {
                let (Some(before), Some(after)) =
                    (creature.parts.get(joint.parent), c.parts.get(joint.parent))
                else {
                    continue;
                };
                let turn = after.orientation * before.orientation.inverse();
                joint.anchor = after.position + turn * (joint.anchor - before.position);
                for axis in &mut joint.axes {
                    *axis = turn * *axis;
                }
            }
            c
        })
        .collect();
    let overlays: Vec<ontogeny::render::Overlay> = chosen
        .iter()
        .map(|&i| {
            let frame = &frames[i];
            let flown: Vec<_> = frames[..=i].iter().filter_map(|f| f.projectile).collect();
            let stride = flown.len().div_ceil(MAX_TRAIL_POINTS).max(1);
            let mut trail: Vec<_> = flown.iter().step_by(stride).copied().collect();
            if let Some(last) = flown.last()
                && trail.last() != Some(last)
            {
                trail.push(*last);
            }
            ontogeny::render::Overlay {
                // The time, and the protocol's phase below it.
                label: std::iter::once(format!("t = {:.2} s", frame.t))
                    .chain(frame.phase.map(|p| p.label().to_string()))
                    .collect(),
                target,
                trail,
            }
        })
        .collect();
    let framing = ontogeny::render::Framing::Following {
        parts: creature.parts.len(),
    };
    let name = path
        .file_name()
        .unwrap_or(path.as_os_str())
        .to_string_lossy();
    let mut progress = Progress::new(format!("drawing {name}"));
    ontogeny::render::write_gif_with_progress(
        posed.iter(),
        &overlays,
        path,
        480,
        300,
        &delays,
        framing,
        &mut |f| progress.set(f),
    )
    .map_err(super::render_error(path))?;
    progress.finish();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use ontogeny::task::{CatapultOptions, WalkerOptions};

    fn recording(seconds: f64) -> Vec<ontogeny::task::RecordedFrame> {
        (0..=(seconds * 60.0).round() as usize)
            .map(|k| ontogeny::task::RecordedFrame {
                t: k as f64 / 60.0,
                phase: None,
                parts: Vec::new(),
                projectile: None,
                projectile_size: None,
            })
            .collect()
    }

    fn thrower() -> Creature {
        let lsys = LSystem::from_path(Path::new("examples/thrower.lsys")).unwrap();
        let options = ontogeny::lsystem::DeriveOptions::default();
        let frames =
            ontogeny::develop::grow(&lsys, &options, None, &BuildOptions::default()).unwrap();
        frames.into_iter().last().unwrap().creature
    }

    /// The frames of the GIF at `path` as straight RGBA.
    fn gif_frames(path: &Path) -> Vec<Vec<u8>> {
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = options
            .read_info(std::fs::File::open(path).unwrap())
            .unwrap();
        let mut frames = Vec::new();
        while let Some(frame) = decoder.read_next_frame().unwrap() {
            frames.push(frame.buffer.to_vec());
        }
        frames
    }

    /// The aim task's target colour in the pictures (render's `TARGET`).
    const TARGET: [u8; 3] = [225, 0, 200];

    #[test]
    fn an_aim_recording_shows_its_target_and_a_catapult_one_does_not() {
        let creature = thrower();
        let dir = std::env::temp_dir().join(format!("ontogeny-aim-gif-{}", std::process::id()));
        let sim = SimOptions::default();
        let mut gifs = Vec::new();
        for (name, target) in [("catapult", None), ("aim", Some([5.0, 0.0, 0.0]))] {
            let options = CatapultOptions {
                target: target.map(|[x, y, z]| nalgebra::Vector3::new(x, y, z)),
                ..CatapultOptions::default()
            };
            let evaluation = task::catapult(&creature, &sim, &options, true);
            assert_eq!(
                evaluation.status,
                task::Status::Ok,
                "{:?}",
                evaluation.message
            );
            write_recording_at(&dir.join(name), &creature, &evaluation, 10.0).unwrap();
            gifs.push(std::fs::read(dir.join(name).join("behaviour.gif")).unwrap());
        }
        assert_ne!(gifs[0], gifs[1], "an aim GIF differs from a catapult one");
        let has_target = |name: &str| {
            gif_frames(&dir.join(name).join("behaviour.gif"))
                .iter()
                .map(|f| f.chunks_exact(4).filter(|p| p[..3] == TARGET).count())
                .collect::<Vec<_>>()
        };
        assert!(has_target("catapult").iter().all(|&n| n == 0));
        assert!(
            has_target("aim").iter().all(|&n| n > 20),
            "{:?}",
            has_target("aim")
        );
        // The projectile's trail grows: the last frame holds more of its colour than the first.
        let trail = |f: &Vec<u8>| f.chunks_exact(4).filter(|p| p[..3] == [190, 90, 0]).count();
        let frames = gif_frames(&dir.join("catapult").join("behaviour.gif"));
        assert!(trail(frames.last().unwrap()) > trail(&frames[0]) + 50);

        // A failed aim evaluation still records its target, and its GIF still shows it.
        let cut = CatapultOptions {
            target: Some(nalgebra::Vector3::new(5.0, 0.0, 0.0)),
            max_seconds: 1.0,
            ..CatapultOptions::default()
        };
        let failed = task::catapult(&creature, &sim, &cut, true);
        assert_eq!(failed.status, task::Status::Unstable);
        let out = dir.join("failed");
        write_recording_at(&out, &creature, &failed, 10.0).unwrap();
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("recording.json")).unwrap())
                .unwrap();
        assert!(json["target"].is_array(), "{}", json["target"]);
        assert!(has_target("failed").iter().all(|&n| n > 20));
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn long_growth_keeps_600_frames_evenly_spaced_in_time() {
        // `grow --dt 0.002` of a 4-unit development: 2001 frames.
        let times: Vec<f64> = (0..=2000).map(|k| k as f64 * 0.002).collect();
        let chosen = evenly_in_time(&times, MAX_GIF_FRAMES);
        assert_eq!(chosen.len(), MAX_GIF_FRAMES);
        assert_eq!(chosen[0], 0);
        assert_eq!(*chosen.last().unwrap(), 2000);
        // Frame k is the one nearest 4 k / 599: within half a frame (0.001) of it.
        for (k, &i) in chosen.iter().enumerate() {
            let ideal = 4.0 * k as f64 / 599.0;
            assert!(
                (times[i] - ideal).abs() <= 0.001 + 1e-12,
                "{k}: {}",
                times[i]
            );
        }
        assert!(chosen.windows(2).all(|w| w[0] < w[1]));
        // Few frames: all of them.
        assert_eq!(evenly_in_time(&[0.0, 1.0, 2.0], 600), [0, 1, 2]);
        assert!(evenly_in_time(&[], 600).is_empty());
    }

    #[test]
    fn uneven_growth_frames_are_each_shown_once() {
        // Nine frames crowded at the start, then one at t = 10: three evenly spaced times
        // (0, 5, 10) pick frame 0, then the one nearest 5 (t = 0.8), then the last.
        let mut times: Vec<f64> = (0..9).map(|k| k as f64 * 0.1).collect();
        times.push(10.0);
        assert_eq!(evenly_in_time(&times, 3), [0, 8, 9]);
        // Four times (0, 3.33, 6.67, 10) would pick frame 8 twice: it is shown once.
        assert_eq!(evenly_in_time(&times, 4), [0, 8, 9]);
    }

    #[test]
    fn a_refused_evaluation_writes_one_picture_saying_why() {
        let creature = ontogeny::develop::creature_from_commands(
            "forward(1) left(1) forward(1) left(1) forward(1) left(1) forward(2)",
        )
        .unwrap();
        let evaluation = task::walker(
            &creature,
            &SimOptions::default(),
            &WalkerOptions::default(),
            true,
        );
        assert_eq!(evaluation.status, task::Status::SelfIntersecting);
        assert!(evaluation.recording.is_empty());
        let dir = std::env::temp_dir().join(format!("ontogeny-refused-{}", std::process::id()));
        write_recording_at(&dir, &creature, &evaluation, 10.0).unwrap();
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("recording.json")).unwrap())
                .unwrap();
        assert_eq!(json["status"], "self-intersecting");
        assert_eq!(json["message"], "parts 0 and 3 interpenetrate");
        let frames = gif_frames(&dir.join("behaviour.gif"));
        assert_eq!(frames.len(), 1, "one picture, not an empty GIF");
        // The picture is checked: the interpenetrating parts are outlined and the text is
        // written in the marking red (render's `MARK`), thousands of pixels of it with the
        // frame round an invalid creature.
        let red = frames[0]
            .chunks_exact(4)
            .filter(|p| p[..3] == [255, 0, 0])
            .count();
        assert!(red > 2000, "{red}");
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn refusals_are_wrapped_at_spaces() {
        assert_eq!(
            wrap("self-intersecting: parts 0 and 3 interpenetrate", 20),
            ["self-intersecting:", "parts 0 and 3", "interpenetrate"]
        );
        assert_eq!(
            wrap("averyveryverylongword x", 5),
            ["averyveryverylongword", "x"]
        );
        assert!(wrap("", 5).is_empty());
    }

    #[test]
    fn recorded_seconds_are_shown_to_the_millisecond() {
        assert_eq!(seconds_text(601.483333333115), "601.483");
        assert_eq!(seconds_text(3603.266666684936), "3603.267");
        assert_eq!(seconds_text(600.0000000001), "600");
        assert_eq!(seconds_text(0.5), "0.5");
    }

    #[test]
    fn a_short_recording_is_drawn_at_the_asked_rate() {
        let (chosen, delays, fps) = animation_frames(&recording(2.0), 10.0);
        assert_eq!(fps, 10.0);
        assert_eq!(chosen.len(), 21);
        // Frame k shows the recording at k / 10 s: recorded frame 6k at 60 frames/s.
        assert!(chosen.iter().enumerate().all(|(k, &i)| i == 6 * k));
        assert!(delays.iter().all(|&d| d == 10));
    }

    #[test]
    fn a_long_recording_stays_under_the_frame_cap() {
        // An hour at 10 frames/s would be 36,001 frames.
        let (chosen, delays, fps) = animation_frames(&recording(3600.0), 10.0);
        assert!(chosen.len() <= MAX_GIF_FRAMES, "{}", chosen.len());
        assert_eq!(chosen.len(), MAX_GIF_FRAMES);
        assert!((fps - 599.0 / 3600.0).abs() < 1e-12);
        // It still plays back in real time: the delays add up to the hour (in cs).
        let total: u64 = delays[..delays.len() - 1].iter().map(|&d| d as u64).sum();
        assert!((total as f64 - 360_000.0).abs() <= 1.0, "{total}");
    }
}
