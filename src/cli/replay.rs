//! `ontogeny replay`: a recording drawn again, or a run's individual re-evaluated with one.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use ontogeny::encoding::Genome;
use ontogeny::evolve::habitats::Growth;
use ontogeny::render::MAX_FPS;
use ontogeny::run::pick::{PickError, individual_by_rank};
use ontogeny::run::{Run, encoding_of_run, unknown_encoding_of_run};
use ontogeny::task::{Recording, TaskSpec};

use super::physics::{FitnessArgs, SteppingArgs};

/// Re-render a recording written by `eval --record DIR` into DIR/behaviour.gif; or, given
/// a run directory, re-evaluate one of its individuals with a recording.
#[derive(Args)]
pub struct ReplayArgs {
    /// A directory written by `ontogeny eval --record DIR`, or a run directory written by
    /// `ontogeny evolve`.
    dir: PathBuf,
    /// Frames per second of the animation, in (0, 50]; image k shows the recording at
    /// k / fps seconds, and plays back in real time.
    #[arg(long, default_value_t = 10.0)]
    fps: f64,
    /// For a run: the generation (default: the last complete one).
    #[arg(long = "gen", value_name = "G")]
    generation: Option<u32>,
    /// For a run: the individual's rank in its generation, 1 for the best.
    #[arg(long, default_value_t = 1)]
    rank: usize,
    /// For a run: re-evaluate at this step setting, as `eval` does [default: the run's
    /// `[task.sim]`].
    #[command(flatten)]
    stepping: SteppingArgs,
    /// For a run: re-evaluate with this fitness formula.
    #[command(flatten)]
    fitness: FitnessArgs,
    /// For a run with `[[task.habitats]]`: the habitat named NAME alone (its creature, its
    /// trials' aggregate, its first trial recorded), written to `replay/gen-G-rank-K-NAME/`
    /// [default: every habitat, the first habitat's first trial recorded].
    #[arg(long, value_name = "NAME")]
    habitat: Option<String>,
}

/// Re-renders `DIR/recording.json` into `DIR/behaviour.gif`.
pub fn run(args: &ReplayArgs) -> anyhow::Result<()> {
    if !(args.fps > 0.0 && args.fps <= MAX_FPS) {
        anyhow::bail!(super::bad(format!(
            "--fps must be in (0, {}], not {} (GIF frames last whole centiseconds)",
            MAX_FPS, args.fps
        )));
    }
    if args.dir.join("config.toml").exists() {
        return replay_run(args);
    }
    if args.stepping.any_given() || args.fitness.fitness.is_some() {
        anyhow::bail!(super::bad(format!(
            "{}: the step setting and --fitness re-evaluate a run's individual; a recording is drawn as it was recorded",
            args.dir.display()
        )));
    }
    let path = args.dir.join("recording.json");
    let text = ontogeny::input::read_to_string(&path)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let recording: Recording = serde_json::from_str(&text)
        .map_err(|e| super::bad(format!("{}: not a recording: {e}", path.display())))?;
    recording.creature.check_consistency().map_err(|problem| {
        super::bad(format!(
            "{}: not a usable creature: {problem}",
            path.display()
        ))
    })?;
    recording.check_growth().map_err(|problem| {
        super::bad(format!(
            "{}: not a usable growth: {problem}",
            path.display()
        ))
    })?;
    let gif = args.dir.join("behaviour.gif");
    super::check_outputs([&gif])?;
    let playback = super::eval::draw_recording(
        &recording,
        &gif,
        args.fps,
        "the evaluation was refused before simulating",
    )?;
    tell!(
        "{} ({} frames at {} frames/s, of {} recorded)",
        ontogeny::output::wrote(&[&gif]),
        playback.shown.len(),
        ontogeny::number::format_number(playback.fps),
        recording.samples.len()
    );
    Ok(())
}

/// `ontogeny replay RUN [--gen G] [--rank K]`: re-evaluates individual K (1 = best) of
/// generation G (default: the last) with a recording, and writes its genome, `creature.png`,
/// `recording.json` and `behaviour.gif` to `RUN/replay/gen-G-rank-K/`.
pub fn replay_run(args: &ReplayArgs) -> anyhow::Result<()> {
    let dir = &args.dir;
    let encoding = encoding_of_run(dir).map_err(super::evolve::run_error)?;
    with_genome!(
        encoding.as_str(),
        G => replay_typed::<G>(args),
        |other| Err(super::bad(unknown_encoding_of_run(dir, other)))
    )
}

/// The run's task with the step setting and fitness flags over it (`None` when none is
/// given).
fn changed_task(args: &ReplayArgs, task: &TaskSpec) -> anyhow::Result<Option<TaskSpec>> {
    if !args.stepping.any_given() && args.fitness.fitness.is_none() {
        return Ok(None);
    }
    let mut task = task.clone();
    if args.stepping.any_given() {
        task.sim = args.stepping.apply(&task.sim)?;
    }
    if let Some(f) = &args.fitness.fitness {
        task.set_fitness(f);
        task.task
            .check_fitness()
            .map_err(|e| super::bad(e.for_flag("--fitness")))?;
    }
    Ok(Some(task))
}

/// The folder under `RUN/replay/` of generation `generation`'s rank `rank`: `gen-G-rank-K`,
/// and with a habitat alone, `gen-G-rank-K-NAME` (`gen-G-rank-K-habitat-H`, H counted from 1,
/// when the name is not a plain file name of letters, digits, `-`, `_` and `.`), so that the
/// replays of each habitat stand side by side.
fn replay_folder_name(
    generation: u32,
    rank: usize,
    only: Option<usize>,
    task: &TaskSpec,
) -> String {
    let plain = format!("gen-{generation}-rank-{rank}");
    let Some(habitat) = only else {
        return plain;
    };
    let name = task.habitat_name(habitat);
    let simple = !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'));
    if simple && !name.is_empty() {
        format!("{plain}-{name}")
    } else {
        format!("{plain}-habitat-{}", habitat + 1)
    }
}

fn replay_typed<G: Genome>(args: &ReplayArgs) -> anyhow::Result<()> {
    let (dir, generation, rank, fps) = (&args.dir, args.generation, args.rank, args.fps);
    // Read-only: replaying never changes the run's store.
    let run = Run::<G>::open_read_only(dir).map_err(super::evolve::run_error)?;
    let changed = changed_task(args, &run.config().task)?;
    let (generation, individual) =
        individual_by_rank(&run, dir, generation, rank).map_err(|e| match e {
            PickError::Run(e) => super::evolve::run_error(e),
            PickError::Input(message) => super::bad(message),
        })?;
    let limits = &run.config().limits;
    let task = changed.as_ref().unwrap_or(&run.config().task);
    let only = match &args.habitat {
        Some(name) => Some(task.habitat_named(name).map_err(super::bad)?),
        None => None,
    };
    let out = dir
        .join("replay")
        .join(replay_folder_name(generation, rank, only, task));
    ontogeny::output::prepare_folder(&out, ontogeny::output::FolderKind::Replay)?;
    let genome_name = format!("genome.{}", G::TEXT_EXTENSION);
    let genome_path = out.join(&genome_name);
    let png = out.join("creature.png");
    super::check_outputs([
        &genome_path,
        &png,
        &out.join("recording.json"),
        &out.join("behaviour.gif"),
    ])?;
    ontogeny::output::write(&genome_path, individual.genome.to_text())?;
    let (creatures, seedlings) = ontogeny::evolve::habitats::develop_with_seedlings(
        &individual.genome,
        limits,
        individual.develop_seed,
        task,
    )
    .map_err(|e| super::bad(format!("the genome does not develop: {e}")))?;
    let text = individual.genome.to_text();
    let growth = Growth::of(&seedlings, &text);
    let habitat = only.unwrap_or(0);
    let creature = &creatures[habitat];
    let title = format!("generation {generation}, rank {rank}");
    ontogeny::render::write_png(creature, &title, &png, 960, 600)
        .map_err(super::render_error(&png))?;
    let walk = ontogeny::evolve::habitats::recorded_walk(task, &creatures, growth, habitat)?;
    super::eval::write_recording_at(&out, &walk.creature, &walk.evaluation, &walk.world, fps)?;
    let evaluation = if task.is_plain() {
        walk.evaluation
    } else {
        // Every unit walked for the aggregate; the habitat's first trial recorded.
        let evaluation = ontogeny::evolve::habitats::evaluate_here(task, &creatures, growth, only)?;
        say!(
            "{}",
            ontogeny::front::flags::habitats_text(task, &evaluation)
        );
        evaluation
    };
    let stored = individual.evaluation.fitness;
    say!(
        "generation {generation}, rank {rank}: {} fitness {:.6} ({}; stored {stored:.6})",
        evaluation.task,
        evaluation.fitness,
        serde_json::to_value(evaluation.status)?
            .as_str()
            .unwrap_or("?")
    );
    if changed.is_some() {
        tell!(
            "note: re-evaluated as the flags ask ({}), not as the run evaluated it ({}); the stored fitness is the run's",
            task.fitness_label(),
            run.config().task.fitness_label()
        );
    } else if only.is_some() {
        tell!(
            "note: habitat {} alone; the stored fitness is the aggregate of every habitat",
            args.habitat.as_deref().unwrap_or("")
        );
    } else if evaluation.fitness != stored {
        tell!("warning: the re-evaluation differs from the stored fitness");
    }
    let files = [
        genome_name.as_str(),
        "creature.png",
        "recording.json",
        "behaviour.gif",
    ];
    tell!("{}", ontogeny::output::wrote(&files.map(|f| out.join(f))));
    Ok(())
}
