//! `ontogeny eval`: loads a creature (from an `.lsys`, a `creature.json` or a graph genome),
//! builds the task's specification from the flags, evaluates it and prints the result; with
//! `--record`, writes the recording and its animation.

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use ontogeny::creature::Creature;
use ontogeny::develop::BuildOptions;
use ontogeny::evolve::habitats::Growth;
use ontogeny::front::flags::{self, TaskFlags};
use ontogeny::output::FolderKind;
use ontogeny::render::Playback;
use ontogeny::run::champion::ChampionRecord;
use ontogeny::sim::WorldSpec;
use ontogeny::sim::{JointModel, SimOptions};
use ontogeny::task::{
    CatapultOptions, DevelopWhen, Evaluation, GrowError, Recording, TaskKind, TaskSpec,
    WalkerOptions,
};

use super::derive::DevelopmentArgs;
use super::input::load_creature_with;
use super::physics::{FitnessArgs, PhysicsArgs, flag_error, names_parser, task_parser};
use super::progress::Progress;

/// Evaluate a creature in physics on a task (see `--task`) and print its fitness, the
/// terms behind it and its status.
#[derive(Args)]
pub struct EvalArgs {
    /// An L-system file (`.lsys`, grown to its last frame), a `creature.json` or a graph
    /// genome (`.json`); `-` reads an L-system from standard input.
    file: PathBuf,
    /// The task [default: the one a run's champion file records, else walker].
    #[arg(long, value_parser = task_parser())]
    task: Option<TaskKind>,
    /// Seconds of evaluation, in (0, 3600] (walker: measured walking, default 20; jump and
    /// stand: default 10; swim: default 20; catapult and aim: the cap on waiting for the
    /// projectile to rest, default 60).
    #[arg(long)]
    seconds: Option<f64>,
    #[command(flatten)]
    development: DevelopmentArgs,
    /// Most parts: a creature grown from an L-system with more is invalid, a
    /// `creature.json` with more is refused.
    #[arg(long, default_value_t = BuildOptions::default().max_parts, value_parser = super::parse_part_count)]
    max_parts: usize,
    #[arg(long, help = super::physics::help("joints"), value_parser = names_parser(JointModel::ALL, JointModel::name, JointModel::summary), default_value = "impulse")]
    joints: JointModel,
    #[command(flatten)]
    physics: PhysicsArgs,
    #[command(flatten)]
    fitness: FitnessArgs,
    /// Seconds of the walker's first activation of the controller, between its two waits
    /// for rest, in [0, 3600] (walker only) [default: 1, Chaumont et al.'s final protocol;
    /// 0.15 is their first attempt, 9 steps of 1/60 s].
    #[arg(long, value_name = "SECONDS")]
    activation: Option<f64>,
    /// The aim task's target relative to the projectile's start, as X,Y,Z metres (aim only)
    /// [default: 5,0,0].
    #[arg(long, value_name = "X,Y,Z", value_parser = flags::parse_point, allow_hyphen_values = true)]
    target: Option<[f64; 3]>,
    /// The projectile: edge length of the cube in metres, positive (catapult and aim)
    /// [default: 0.2].
    #[arg(long)]
    projectile_size: Option<f64>,
    /// The projectile: density in kg/m³, positive (catapult and aim) [default: 1000].
    #[arg(long)]
    projectile_density: Option<f64>,
    #[command(flatten)]
    develop: Box<DevelopFlags>,
    /// Write recording.json (every part's pose per step; a long run keeps evenly spaced
    /// steps, at most 12,000 frames) and behaviour.gif into DIR; with habitats or trials, of
    /// the first walk (of `--habitat`'s habitat, when given).
    #[arg(long, value_name = "DIR")]
    record: Option<PathBuf>,
    /// Print the evaluation as JSON.
    #[arg(long)]
    json: bool,
    /// Take the task and its settings — habitats and trials included — from a run
    /// configuration's `[task]` table instead of the task's flags.
    #[arg(long, value_name = "CONFIG")]
    config: Option<PathBuf>,
    /// Evaluate only the habitat named NAME (every trial of it) of a task with
    /// `[[task.habitats]]`.
    #[arg(long, value_name = "NAME")]
    habitat: Option<String>,
}

/// When the creature develops (boxed in [`EvalArgs`], which stays small).
#[derive(Args)]
struct DevelopFlags {
    /// When the creature develops: `before` the evaluation (the last frame of its growth is
    /// evaluated; the default) or `during` it (an `.lsys` in continuous time: the creature at
    /// `--develop-t0` is dropped, and development goes on during the walker's activation and
    /// walk; with habitats or trials, it starts from each habitat's array and anew in each
    /// trial). Over the config's `develop`.
    #[arg(long, value_parser = ["before", "during"])]
    develop: Option<String>,
    /// With `--develop during`: developmental time per second of physics, above 0
    /// [default: 1].
    #[arg(long, value_name = "RATE")]
    develop_rate: Option<f64>,
    /// With `--develop during`: the developmental time of the creature dropped, 0 or more
    /// [default: the grammar's first frame that builds a valid creature].
    #[arg(long, value_name = "T")]
    develop_t0: Option<f64>,
}

/// How the input is named in reports: its path, or `<stdin>` for `-` (as in diagnostics).
fn input_name(file: &Path) -> String {
    if file.as_os_str() == "-" {
        "<stdin>".to_string()
    } else {
        file.display().to_string()
    }
}

/// The task and its settings the flags ask for, checked; an error names the flag at fault.
fn task_spec(args: &EvalArgs) -> anyhow::Result<TaskSpec> {
    let physics = args.physics.sim_options()?;
    let sim = SimOptions {
        joints: args.joints,
        ..physics
    };
    task_flags(args).spec(sim).map_err(flag_error)
}

fn task_flags(args: &EvalArgs) -> TaskFlags {
    TaskFlags {
        task: args.task.unwrap_or_default(),
        seconds: args.seconds,
        fitness: args.fitness.fitness.clone(),
        activation: args.activation,
        target: args.target,
        projectile_size: args.projectile_size,
        projectile_density: args.projectile_density,
    }
}

/// The flags given on the command line (by clap's id), set once by `main`: a champion file's
/// record gives every other setting.
static GIVEN: std::sync::OnceLock<Vec<String>> = std::sync::OnceLock::new();

/// Records which of `eval`'s flags the command line gave (`matches`, its subcommand's).
pub fn set_given(matches: &clap::ArgMatches) {
    let given = matches
        .ids()
        .filter(|id| {
            matches.value_source(id.as_str()) == Some(clap::parser::ValueSource::CommandLine)
        })
        .map(|id| id.to_string())
        .collect();
    let _ = GIVEN.set(given);
}

fn given(id: &str) -> bool {
    GIVEN.get().is_some_and(|g| g.iter().any(|i| i == id))
}

/// Whether a flag that sets the simulator (`--setting`, `--joints`, `--strength`, ...) was
/// given.
fn physics_given() -> bool {
    use clap::Args as _;
    let physics = PhysicsArgs::augment_args(clap::Command::new("physics"));
    given("joints") || physics.get_arguments().any(|a| given(a.get_id().as_str()))
}

/// What the evaluation uses: the task, the grammar's seed, the most parts and modules.
struct Inputs {
    spec: TaskSpec,
    seed: Option<u64>,
    max_parts: usize,
    max_modules: usize,
}

/// The inputs the flags give, over the record of `file` when it is a run's champion (the
/// flags that differ from the record said on standard error).
fn inputs(args: &EvalArgs) -> anyhow::Result<Inputs> {
    let max_modules = ontogeny::lsystem::DEFAULT_MAX_MODULES;
    if let Some(config) = &args.config {
        let mut clashing: Vec<String> = [
            "task",
            "seconds",
            "fitness",
            "activation",
            "target",
            "projectile_size",
            "projectile_density",
        ]
        .into_iter()
        .filter(|id| given(id))
        .map(|id| format!("--{}", id.replace('_', "-")))
        .collect();
        if physics_given() {
            clashing.push("a physics flag".to_string());
        }
        if !clashing.is_empty() {
            return Err(super::bad(format!(
                "--config {} gives the task's settings; {} cannot be given with it (set it in the config's [task] table)",
                config.display(),
                clashing.join(", ")
            )));
        }
        let spec = ontogeny::run::config::read_task_config(config).map_err(anyhow::Error::new)?;
        return Ok(Inputs {
            spec,
            seed: args.development.seed.seed(),
            max_parts: args.max_parts,
            max_modules,
        });
    }
    let record = if args.file.as_os_str() == "-" {
        None
    } else {
        let text = ontogeny::input::read_to_string(&args.file)
            .with_context(|| format!("cannot read {}", args.file.display()))?;
        ChampionRecord::of_text(&text)
            .map_err(|e| super::bad(format!("{}: {e}", args.file.display())))?
    };
    let Some(record) = record else {
        return Ok(Inputs {
            spec: task_spec(args)?,
            seed: args.development.seed.seed(),
            max_parts: args.max_parts,
            max_modules,
        });
    };
    let name = input_name(&args.file);
    let mut notes = Vec::new();
    let mut differs = |flag: &str, what: String| {
        notes.push(format!(
            "note: {flag} differs from the evaluation {name} records ({what}); the flag's is used"
        ))
    };
    let recorded = &record.task;
    if args.task.is_some_and(|t| t != recorded.kind()) {
        differs("--task", recorded.task.name().to_string());
        for n in notes {
            tell!("{n}");
        }
        return Ok(Inputs {
            spec: task_spec(args)?,
            seed: args.development.seed.seed().or(Some(record.grammar_seed)),
            max_parts: args.max_parts,
            max_modules: record.max_modules.unwrap_or(max_modules),
        });
    }
    let flags = task_flags(args);
    let mut spec = recorded.clone();
    if physics_given() {
        let sim = SimOptions {
            joints: args.joints,
            ..args.physics.sim_options()?
        };
        if serde_json::to_value(&sim)? != serde_json::to_value(&spec.sim)? {
            differs("a physics flag", "its [task.sim] values".to_string());
        }
        spec.sim = sim;
    }
    if let Some(f) = &flags.fitness {
        let recorded = spec.fitness_measure();
        spec.set_fitness(f);
        if spec.fitness_measure() != recorded {
            differs("--fitness", recorded);
        }
    }
    if let Some(s) = flags.seconds {
        let field = spec.seconds_mut();
        if *field != s {
            differs("--seconds", format!("{} seconds", *field));
        }
        *field = s;
    }
    if let (Some(a), Some(walker)) = (flags.activation, spec.task.get_mut::<WalkerOptions>()) {
        if a != walker.activation {
            differs("--activation", format!("{} s", walker.activation));
        }
        walker.activation = a;
    }
    let aim = spec.kind() == TaskKind::Aim;
    if let Some(catapult) = spec.task.get_mut::<CatapultOptions>() {
        if let Some([x, y, z]) = flags.target.filter(|_| aim) {
            let target = nalgebra::Vector3::new(x, y, z);
            if catapult.target != Some(target) {
                let shown = catapult
                    .target
                    .map_or("none".to_string(), |t| format!("{},{},{}", t.x, t.y, t.z));
                differs("--target", shown);
            }
            catapult.target = Some(target);
        }
        if let Some(size) = flags.projectile_size {
            catapult.projectile_size = nalgebra::Vector3::repeat(size);
        }
        if let Some(density) = flags.projectile_density {
            catapult.projectile_density = density;
        }
    }
    spec.check().map_err(flag_error)?;
    let seed = match args.development.seed.seed() {
        Some(s) if s != record.grammar_seed => {
            differs(
                "--grammar-seed",
                format!("grammar seed {}", record.grammar_seed),
            );
            s
        }
        _ => record.grammar_seed,
    };
    let max_parts = match record.max_parts {
        Some(m) if !given("max_parts") => m,
        Some(m) if m != args.max_parts => {
            differs("--max-parts", m.to_string());
            args.max_parts
        }
        _ => args.max_parts,
    };
    let changed = !notes.is_empty();
    for n in notes {
        tell!("{n}");
    }
    tell!(
        "note: {name} records its evaluation ({}); {}",
        recorded.fitness_label(),
        if changed {
            "the flags above change it"
        } else {
            "repeating it"
        }
    );
    Ok(Inputs {
        spec,
        seed: Some(seed),
        max_parts,
        max_modules: record.max_modules.unwrap_or(max_modules),
    })
}

/// `inputs`' specification with `--develop`, `--develop-rate` and `--develop-t0` over it,
/// checked.
fn with_develop_flags(args: &EvalArgs, inputs: &mut Inputs) -> anyhow::Result<()> {
    let (flags, develop) = (&args.develop, &mut inputs.spec.develop);
    if let Some(when) = &flags.develop {
        develop.when = if when == "during" {
            DevelopWhen::During
        } else {
            DevelopWhen::Before
        };
    }
    if let Some(rate) = flags.develop_rate {
        develop.rate = rate;
    }
    if flags.develop_t0.is_some() {
        develop.t0 = flags.develop_t0;
    }
    develop
        .check()
        .map_err(|e| super::bad(e.for_flag(&format!("--{}", e.key.replace('_', "-")))))
}

/// Evaluates the creature and prints the result.
pub fn run(args: &EvalArgs) -> anyhow::Result<()> {
    let mut inputs = inputs(args)?;
    with_develop_flags(args, &mut inputs)?;
    let only = match &args.habitat {
        Some(name) => Some(inputs.spec.habitat_named(name).map_err(super::bad)?),
        None => None,
    };
    if inputs.spec.develop.during() {
        return run_growing(args, &inputs, only);
    }
    if !inputs.spec.is_plain() {
        return run_in_habitats(args, &inputs, only);
    }
    let creature = load_creature_with(
        &args.file,
        &args.development,
        inputs.seed,
        inputs.max_parts,
        inputs.max_modules,
        None,
    )?;
    let spec = inputs.spec;
    // A place to record into, checked before the evaluation runs.
    if let Some(dir) = &args.record {
        // Missing, empty, or a recording's: never a folder of the user's files.
        ontogeny::output::check_folder(dir, FolderKind::Recording)?;
        super::check_outputs(["recording.json", "behaviour.gif"].map(|f| dir.join(f)))?;
    }
    for flag in task_flags(args).inapplicable() {
        tell!("warning: {flag}; ignored");
    }
    let mut progress = Progress::new(flags::progress_label(&spec));
    if let Some(note) = flags::recording_note(&spec).filter(|_| args.record.is_some()) {
        tell!("{note}");
    }
    let evaluation =
        spec.evaluate_with_progress(&creature, args.record.is_some(), &mut |f| progress.set(f));
    progress.finish();
    if let Some(warning) = flags::joint_gap_warning(&evaluation) {
        tell!("{warning}");
    }
    if let Some(dir) = &args.record {
        ontogeny::output::prepare_folder(dir, FolderKind::Recording)?;
        write_recording(dir, &creature, &evaluation, &spec.world)?;
        let files = ["recording.json", "behaviour.gif"].map(|f| dir.join(f));
        tell!("{}", ontogeny::output::wrote(&files));
    }
    show_evaluation(args, &evaluation)
}

/// Prints an evaluation of `args.file`: as JSON with `--json` (without its recording, which
/// `--record` writes), else as text.
fn show_evaluation(args: &EvalArgs, evaluation: &Evaluation) -> anyhow::Result<()> {
    if args.json {
        let mut shown = evaluation.clone();
        shown.recording.clear();
        say!("{}", serde_json::to_string_pretty(&shown)?);
        return Ok(());
    }
    say!(
        "{}",
        flags::evaluation_text(&input_name(&args.file), evaluation)
    );
    Ok(())
}

/// [`run`] for a creature that develops during the evaluation: an `.lsys` in continuous
/// time, on the walker; `--record` records the parts as they appear and grow. With habitats
/// or trials, the grammar develops in each habitat's array and every unit (those of habitat
/// `only`, when given) walks it, as evolution walks its genomes ([`walk_in_habitats`]).
fn run_growing(args: &EvalArgs, inputs: &Inputs, only: Option<usize>) -> anyhow::Result<()> {
    let spec = &inputs.spec;
    let refuse = |why: &str| Err(super::bad(format!("develop = \"during\": {why}")));
    spec.check_growing()
        .map_err(|e| super::bad(e.to_string()))?;
    if args.file.extension().is_none_or(|e| e != "lsys") {
        return refuse(&format!(
            "{} is not an L-system file (.lsys): only a grammar grows",
            args.file.display()
        ));
    }
    let overrides = ontogeny::lsystem::Overrides {
        defines: args.development.defines.defines.clone(),
        seed: inputs.seed,
    };
    let seedling = ontogeny::develop::Seedling {
        lsys: std::sync::Arc::new(
            ontogeny::lsystem::LSystem::from_path_with(&args.file, &overrides)
                .map_err(anyhow::Error::new)?,
        ),
        derive: ontogeny::lsystem::DeriveOptions {
            seed: inputs.seed,
            ..super::derive::derive_options(&args.development, inputs.max_modules)
        },
        build: BuildOptions {
            max_parts: inputs.max_parts,
            ..BuildOptions::default()
        },
    };
    ontogeny::task::check_continuous(&seedling, &args.file.display().to_string())
        .map_err(|e| super::bad(e.to_string()))?;
    if !spec.is_plain() {
        let (creatures, seedlings) =
            ontogeny::evolve::habitats::grammar_in_habitats(spec, &seedling)
                .map_err(|e| super::bad(format!("{}: {e}", args.file.display())))?;
        // The trials' draws are keyed by the grammar's text, as a run keys its genome's: a
        // champion file's text without the record above it.
        let text = ontogeny::input::read_to_string(&args.file)
            .with_context(|| format!("cannot read {}", args.file.display()))?;
        let growth = Growth::of(&seedlings, ChampionRecord::genome_text(&text));
        return walk_in_habitats(args, spec, &creatures, growth, only);
    }
    let grow_error = |e: GrowError| match e {
        GrowError::Development(d) => anyhow::Error::new(d),
        GrowError::Interrupted(i) => anyhow::Error::new(i),
        e => super::bad(e.to_string()),
    };
    // The creature as dropped, which a recording starts from; its samples hold its growth.
    let creature = match &args.record {
        Some(dir) => {
            ontogeny::output::check_folder(dir, FolderKind::Recording)?;
            super::check_outputs(["recording.json", "behaviour.gif"].map(|f| dir.join(f)))?;
            let growing = ontogeny::task::Growing::from_seedling(&seedling, &spec.develop)
                .map_err(anyhow::Error::new)?;
            Some(growing.creature().clone())
        }
        None => None,
    };
    let mut progress = Progress::new(flags::progress_label(spec));
    let mut tell = |f| progress.set(f);
    let watch = ontogeny::task::Watch::uncancelled(args.record.is_some(), &mut tell);
    let evaluation = spec
        .evaluate_grown_job(&seedling, None, watch)
        .map_err(grow_error)?;
    progress.finish();
    if let (Some(dir), Some(creature)) = (&args.record, &creature) {
        ontogeny::output::prepare_folder(dir, FolderKind::Recording)?;
        write_recording(dir, creature, &evaluation, &spec.world)?;
        let files = ["recording.json", "behaviour.gif"].map(|f| dir.join(f));
        tell!("{}", ontogeny::output::wrote(&files));
    }
    show_evaluation(args, &evaluation)
}

/// [`run`] for a task with habitats or trials: the creature grown in each habitat (with its
/// array), every unit walked (those of habitat `only`, when given), a line per unit and the
/// aggregate; `--record` records the first unit's walk.
fn run_in_habitats(args: &EvalArgs, inputs: &Inputs, only: Option<usize>) -> anyhow::Result<()> {
    let spec = &inputs.spec;
    if args.file.as_os_str() == "-" && spec.habitat_count() > 1 {
        return Err(super::bad(
            "a task with several habitats grows the creature once in each; give a file, not -",
        ));
    }
    let creatures = (0..spec.habitat_count())
        .map(|h| {
            load_creature_with(
                &args.file,
                &args.development,
                inputs.seed,
                inputs.max_parts,
                inputs.max_modules,
                spec.habitat_environment(h),
            )
        })
        .collect::<anyhow::Result<Vec<Creature>>>()?;
    walk_in_habitats(args, spec, &creatures, None, only)
}

/// Walks `creatures` (one per habitat of `spec`, growing as `growth` says when they grow
/// during their walks) in every unit (those of habitat `only`, when given), records the
/// first unit's walk with `--record`, and prints a line per unit and the aggregate.
fn walk_in_habitats(
    args: &EvalArgs,
    spec: &TaskSpec,
    creatures: &[Creature],
    growth: Option<Growth<'_>>,
    only: Option<usize>,
) -> anyhow::Result<()> {
    if let Some(dir) = &args.record {
        ontogeny::output::check_folder(dir, FolderKind::Recording)?;
        super::check_outputs(["recording.json", "behaviour.gif"].map(|f| dir.join(f)))?;
    }
    let mut progress = Progress::new(format!(
        "{} walks",
        spec.trials.count as usize * only.map_or(spec.habitat_count(), |_| 1)
    ));
    let evaluation = ontogeny::evolve::habitats::evaluate_here(spec, creatures, growth, only)?;
    progress.finish();
    if let Some(dir) = &args.record {
        let habitat = only.unwrap_or(0);
        let walk = ontogeny::evolve::habitats::recorded_walk(spec, creatures, growth, habitat)?;
        tell!(
            "note: recording {}trial 1",
            match spec.habitat_name(habitat) {
                "" => String::new(),
                name => format!("habitat {name}, "),
            }
        );
        ontogeny::output::prepare_folder(dir, FolderKind::Recording)?;
        write_recording(dir, &walk.creature, &walk.evaluation, &walk.world)?;
        let files = ["recording.json", "behaviour.gif"].map(|f| dir.join(f));
        tell!("{}", ontogeny::output::wrote(&files));
    }
    if args.json {
        say!("{}", serde_json::to_string_pretty(&evaluation)?);
        return Ok(());
    }
    say!(
        "{}",
        flags::evaluation_text(&input_name(&args.file), &evaluation)
    );
    say!("{}", flags::habitats_text(spec, &evaluation));
    Ok(())
}

fn write_recording(
    dir: &Path,
    creature: &Creature,
    evaluation: &Evaluation,
    world: &WorldSpec,
) -> anyhow::Result<()> {
    write_recording_at(dir, creature, evaluation, world, 10.0)
}

/// Writes `DIR/recording.json` ([`Recording`], in `world`) and `DIR/behaviour.gif` (`fps`
/// images per simulated second, the world drawn) into `dir`, a folder made ready for them
/// ([`ontogeny::output::prepare_folder`]).
pub fn write_recording_at(
    dir: &Path,
    creature: &Creature,
    evaluation: &Evaluation,
    world: &WorldSpec,
    fps: f64,
) -> anyhow::Result<()> {
    let recording = Recording::of(creature, evaluation).in_world(world);
    ontogeny::output::write(
        &dir.join("recording.json"),
        serde_json::to_string(&recording)?,
    )?;
    let why = format!(
        "{}: {}",
        evaluation.status.name(),
        evaluation
            .message
            .as_deref()
            .unwrap_or("the evaluation was refused before simulating")
    );
    draw_recording(&recording, &dir.join("behaviour.gif"), fps, &why)?;
    Ok(())
}

/// Simulated seconds for a note: to the millisecond, without trailing zeros (`601.483`).
fn seconds_text(seconds: f64) -> String {
    ontogeny::number::format_number((seconds * 1000.0).round() / 1000.0)
}

/// Draws `recording` as `path` at `fps` images per simulated second
/// ([`ontogeny::render::write_behaviour_gif`]), with a note when it is too long for that
/// rate and a progress bar on a terminal; `why` is written on the picture of a recording
/// without samples. Returns how it was played.
pub fn draw_recording(
    recording: &Recording,
    path: &Path,
    fps: f64,
    why: &str,
) -> anyhow::Result<Playback> {
    let samples = &recording.samples;
    let playback = ontogeny::render::playback(samples, fps);
    let size = (480, 300);
    if !samples.is_empty() && playback.fps < fps {
        tell!(
            "note: {} s recorded: {} is drawn at {:.3} frames/s instead of {fps}, to keep to {} frames",
            seconds_text(samples.last().map_or(0.0, |s| s.t)),
            path.display(),
            playback.fps,
            ontogeny::render::MAX_GIF_IMAGES
        );
    }
    let name = path
        .file_name()
        .unwrap_or(path.as_os_str())
        .to_string_lossy();
    let mut progress = Progress::new(format!("drawing {name}"));
    ontogeny::render::write_behaviour_gif(recording, &playback, why, path, size, &mut |f| {
        progress.set(f)
    })
    .map_err(super::render_error(path))?;
    progress.finish();
    Ok(playback)
}

#[cfg(test)]
mod tests {
    use super::seconds_text;

    #[test]
    fn recorded_seconds_are_shown_to_the_millisecond() {
        assert_eq!(seconds_text(601.483333333115), "601.483");
        assert_eq!(seconds_text(3603.266666684936), "3603.267");
        assert_eq!(seconds_text(600.0000000001), "600");
        assert_eq!(seconds_text(0.5), "0.5");
    }
}
