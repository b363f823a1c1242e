//! `ontogeny evolve` and `ontogeny runs`.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::{Args, Subcommand};
use ontogeny::encoding::{ENCODINGS, EncodingInfo, Genome, LSystemGenome, encoding_named};
use ontogeny::evolve::config::{ConfigFile, RunConfig, check_settings, encoding_of, read_config};
use ontogeny::evolve::ga::Preset;
use ontogeny::evolve::run::{GenerationReport, Run, RunError, encoding_of_run, exploits_stepping};
use ontogeny::evolve::store::RunStore;
use ontogeny::lang::{Diagnostic, DiagnosticKind, Source};
use ontogeny::sim::StepSetting;
use ontogeny::task::{TaskKind, TaskSpec, WalkerFitness};

use super::physics::{flag_error, setting_parser, task_parser};

/// An encoding `--encoding` accepts: one of the library's registry ([`ENCODINGS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EncodingArg(&'static EncodingInfo);

impl EncodingArg {
    /// The encoding's name, as the run store spells it.
    pub fn name(self) -> &'static str {
        self.0.name
    }
}

/// Parses an encoding's name, every name listed in the help with its description.
pub fn encoding_parser() -> impl clap::builder::TypedValueParser<Value = EncodingArg> {
    use clap::builder::TypedValueParser;
    let names = ENCODINGS
        .iter()
        .map(|e| clap::builder::PossibleValue::new(e.name).help(e.description));
    clap::builder::PossibleValuesParser::new(names).try_map(|name: String| {
        encoding_named(&name)
            .map(EncodingArg)
            .ok_or_else(|| format!("unknown encoding '{name}'"))
    })
}

/// Every encoding's name, comma-separated (for messages).
pub fn encoding_names() -> String {
    ENCODINGS
        .iter()
        .map(|e| e.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// `--seconds` checked against the evaluator's limit, (0, [`ontogeny::task::MAX_SECONDS`]].
pub fn check_seconds(seconds: Option<f64>) -> anyhow::Result<()> {
    match seconds {
        Some(s) => ontogeny::task::check_duration("seconds", s).map_err(flag_error),
        None => Ok(()),
    }
}

/// A settings error, prefixed with the config file's name when there is one.
pub fn config_error(source: Option<&Source>, error: String) -> String {
    match source {
        Some(s) => format!("{}: {error}", s.name()),
        None => error,
    }
}

/// The task of a config file (default: the walker), with `--task`, `--fitness`, `--seconds`
/// and `--setting` over it (a named setting replaces the file's five stepping values, and
/// nothing else). `--fitness` for a task other than the walker is refused.
pub fn resolve_task(
    file: Option<TaskSpec>,
    task: Option<TaskKind>,
    fitness: Option<WalkerFitness>,
    seconds: Option<f64>,
    setting: Option<StepSetting>,
) -> anyhow::Result<TaskSpec> {
    let mut spec = file.unwrap_or_else(|| TaskSpec::new(TaskKind::Walker));
    if let Some(setting) = setting {
        spec.sim = setting.apply(&spec.sim);
    }
    if let Some(t) = task {
        spec.task = t;
    }
    if let Some(s) = seconds {
        match spec.task {
            TaskKind::Walker => spec.walker.seconds = s,
            TaskKind::Jump => spec.jump.seconds = s,
            TaskKind::Catapult | TaskKind::Aim => spec.catapult.max_seconds = s,
        }
    }
    if let Some(fitness) = fitness {
        if spec.task != TaskKind::Walker {
            return Err(bad(format!(
                "--fitness is for the walker task only, and the task is {}",
                spec.task.name()
            )));
        }
        spec.walker.fitness = fitness;
    }
    Ok(spec)
}

/// Parses `--preset`: one of the library's presets by its name ([`Preset::name`]), every
/// name listed in the help with its summary.
pub fn preset_parser() -> impl clap::builder::TypedValueParser<Value = Preset> {
    use clap::builder::TypedValueParser;
    let names = Preset::ALL.map(|p| clap::builder::PossibleValue::new(p.name()).help(p.summary()));
    clap::builder::PossibleValuesParser::new(names).try_map(|name: String| {
        Preset::named(&name).ok_or_else(|| format!("unknown preset '{name}'"))
    })
}

/// Flags of `ontogeny evolve`.
#[derive(Args)]
pub struct EvolveArgs {
    /// The run directory to create (refused if it holds a run).
    #[arg(long, value_name = "DIR", required_unless_present = "resume")]
    out: Option<PathBuf>,
    /// Continue the run in DIR where it stopped (any other flag but --threads and --gens is
    /// refused).
    #[arg(long, value_name = "DIR", conflicts_with_all = ["out", "encoding", "task", "fitness", "preset", "pop", "seed", "config", "init", "seconds", "setting", "no_verify_best", "no_cache"])]
    resume: Option<PathBuf>,
    /// The genome encoding (default: the config's, else lsystem).
    #[arg(long, value_parser = encoding_parser())]
    encoding: Option<EncodingArg>,
    /// The task (default: the config's, else walker).
    #[arg(long, value_parser = task_parser())]
    task: Option<TaskKind>,
    /// The walker's fitness formula, as `eval --fitness` (walker only; default: the config's
    /// `[task.walker] fitness`, else normalised).
    #[arg(long, value_parser = super::walker_fitness_parser())]
    fitness: Option<WalkerFitness>,
    /// The genetic algorithm's schedule (default: the config's, else chaumont).
    #[arg(long, value_parser = preset_parser())]
    preset: Option<Preset>,
    /// Individuals per generation (default: the preset's, 300).
    #[arg(long)]
    pop: Option<usize>,
    /// Generations (default: the preset's, 100). With --resume: extend the run to this many
    /// generations in all (at least as many as it has).
    #[arg(long)]
    gens: Option<usize>,
    /// The run's seed (default: the config's, else 1).
    #[arg(long)]
    seed: Option<u64>,
    /// Seconds of the task's measurement (walker: walking, default 20), in (0, 3600].
    #[arg(long)]
    seconds: Option<f64>,
    /// The named step setting (default: the config's `[task.sim]`, else default); it replaces
    /// the config's five stepping values.
    #[arg(long, value_name = "NAME", value_parser = setting_parser())]
    setting: Option<StepSetting>,
    /// Worker threads (default: every core). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// A TOML file of settings; command-line values override it.
    #[arg(long, value_name = "FILE.toml")]
    config: Option<PathBuf>,
    /// Seed the first generation with mutants of this hand-written grammar.
    #[arg(long, value_name = "FILE.lsys")]
    init: Option<PathBuf>,
    /// Do not re-walk each generation's best at the fine reference setting (the config's
    /// `verify_best = false`).
    #[arg(long)]
    no_verify_best: bool,
    /// Simulate every individual, even one identical to a creature evaluated earlier in the
    /// run (the config's `cache = false`); results are the same either way.
    #[arg(long)]
    no_cache: bool,
}

/// A bad-input error (exit code 2) with `message`.
pub fn bad(message: impl Into<String>) -> anyhow::Error {
    anyhow::Error::new(Diagnostic::without_location(
        DiagnosticKind::Semantic,
        message.into(),
    ))
}

/// The command line's error for a run's.
pub fn run_error(e: RunError) -> anyhow::Error {
    match e {
        RunError::Config(d) => anyhow::Error::new(d),
        RunError::Io { path, source } => {
            anyhow::Error::new(source).context(format!("{}", path.display()))
        }
        other => bad(other.to_string()),
    }
}

/// Sets the number of worker threads (`--threads`), 1 to 1024.
pub fn set_threads(threads: Option<usize>) -> anyhow::Result<()> {
    if let Some(threads) = threads {
        if !(1..=1024).contains(&threads) {
            return Err(bad(format!("--threads must be 1 to 1024, not {threads}")));
        }
        // The global pool may already exist in tests; a second build is harmless to refuse.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global();
    }
    Ok(())
}

/// Runs `ontogeny evolve`.
pub fn run(args: &EvolveArgs) -> anyhow::Result<()> {
    set_threads(args.threads)?;
    if let Some(dir) = &args.resume {
        let encoding = encoding_of_run(dir).map_err(run_error)?;
        return with_genome!(encoding.as_str(), G => resume::<G>(dir, args.gens), |other| Err(bad(
            format!("{}: unknown encoding '{other}'", dir.display())
        )));
    }
    let source = match &args.config {
        Some(path) => {
            Some(Source::read(path).with_context(|| format!("cannot read {}", path.display()))?)
        }
        None => None,
    };
    let encoding = match (args.encoding, &source) {
        (Some(e), _) => e.name().to_string(),
        (None, Some(s)) => encoding_of(s)?.unwrap_or_else(|| LSystemGenome::NAME.to_string()),
        (None, None) => LSystemGenome::NAME.to_string(),
    };
    with_genome!(
        encoding.as_str(),
        G => start::<G>(args, source.as_deref()),
        |other| Err(bad(format!(
            "unknown encoding '{other}' ({})",
            encoding_names()
        )))
    )
}

/// Resolves the settings (command line over config file over preset) and starts the run.
fn start<G: Genome>(args: &EvolveArgs, source: Option<&Source>) -> anyhow::Result<()> {
    let out = args
        .out
        .as_ref()
        .expect("clap requires --out without --resume");
    let file: ConfigFile<G::Limits> = match source {
        Some(s) => read_config(s)?,
        None => ConfigFile::default(),
    };
    let mut overrides = file.ga.clone();
    if let Some(p) = args.preset {
        overrides.preset = Some(p);
    }
    if args.pop.is_some() {
        overrides.population = args.pop;
    }
    if args.gens.is_some() {
        overrides.generations = args.gens;
    }
    let ga = overrides.resolve();
    check_seconds(args.seconds)?;
    let task = resolve_task(
        file.task.clone(),
        args.task,
        args.fitness,
        args.seconds,
        args.setting,
    )?;
    check_settings(&ga, &task).map_err(|e| bad(config_error(source, e)))?;
    // --init on the command line is relative to the working directory; in the config file,
    // to the file.
    let init_path = match (&args.init, &file.init, source) {
        (Some(p), _, _) => Some(p.clone()),
        (None, Some(p), Some(s)) => Some(
            Path::new(s.name())
                .parent()
                .unwrap_or(Path::new("."))
                .join(p),
        ),
        _ => None,
    };
    let init_text = match &init_path {
        Some(p) => Some(
            std::fs::read_to_string(p).with_context(|| format!("cannot read {}", p.display()))?,
        ),
        None => None,
    };
    if let Some(text) = &init_text {
        let limits = file.limits.clone().unwrap_or_default();
        G::from_lsys(text, &limits).map_err(|e| {
            bad(format!(
                "{}: cannot seed the {} encoding: {}",
                init_path
                    .as_ref()
                    .map_or(String::new(), |p| p.display().to_string()),
                G::NAME,
                e.0
            ))
        })?;
    }
    let config = RunConfig {
        encoding: G::NAME.to_string(),
        seed: args.seed.or(file.seed).unwrap_or(1),
        init: None,
        verify_best: !args.no_verify_best && file.verify_best.unwrap_or(true),
        cache: !args.no_cache && file.cache.unwrap_or(true),
        ga,
        task,
        limits: file.limits.unwrap_or_default(),
    };
    let mut run = Run::<G>::start(out, config, init_text.as_deref()).map_err(run_error)?;
    go(&mut run, out)
}

fn resume<G: Genome>(dir: &Path, generations: Option<usize>) -> anyhow::Result<()> {
    let mut run = Run::<G>::resume(dir).map_err(run_error)?;
    if let Some(generations) = generations {
        run.extend(generations).map_err(run_error)?;
    }
    let done = run.last_generation().map_err(run_error)?;
    let total = run.config().ga.generations as u32;
    match done {
        Some(g) if g + 1 >= total => {
            say!(
                "{}: complete ({total} generations); nothing to resume",
                dir.display()
            );
            return Ok(());
        }
        Some(g) => say!("{}: resuming after generation {g}", dir.display()),
        None => say!("{}: resuming from the first generation", dir.display()),
    }
    go(&mut run, dir)
}

/// Runs the remaining generations with a progress bar on a terminal, log lines otherwise.
fn go<G: Genome>(run: &mut Run<G>, dir: &Path) -> anyhow::Result<()> {
    let total = run.config().ga.generations as u64;
    let first = run
        .last_generation()
        .map_err(run_error)?
        .map_or(0, |g| g + 1) as u64;
    let terminal = std::io::stderr().is_terminal();
    let bar = if terminal {
        let bar = indicatif::ProgressBar::new(total);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{bar:30} gen {pos}/{len}  {msg}  [{elapsed_precise}, {eta} left]",
            )
            .expect("a valid template"),
        );
        bar.set_position(first);
        Some(bar)
    } else {
        None
    };
    let started = std::time::Instant::now();
    let mut evaluations = 0u64;
    let mut reused = 0u64;
    let mut evaluating = 0.0;
    let mut last: Option<GenerationReport> = None;
    let fitness = run.config().task.fitness_label();
    let mut observer = |r: &GenerationReport| {
        evaluations += r.stats.evaluations;
        reused += r.stats.reused;
        evaluating += r.evaluation_seconds;
        let fine = match &r.best_fine {
            Some(f) => format!(" (fine reference {:.4})", f.fitness),
            None => String::new(),
        };
        let line = format!(
            "{fitness}: best {:.4}{fine}  mean {:.4}  valid {:.0}%  {:.1} evaluations/s",
            r.stats.best,
            r.stats.mean,
            r.stats.valid_fraction * 100.0,
            r.stats.evaluations as f64 / r.wall_seconds.max(1e-9)
        );
        match &bar {
            Some(bar) => {
                bar.set_message(line);
                bar.inc(1);
            }
            None => eprintln!("generation {}: {line}", r.generation),
        }
        last = Some(r.clone());
    };
    run.run(&mut observer).map_err(run_error)?;
    if let Some(bar) = &bar {
        bar.finish();
    }
    let wall = started.elapsed().as_secs_f64();
    if let Some(r) = last {
        if r.fallbacks.crossover + r.fallbacks.graft > 0 {
            say!(
                "note: the {} encoding lacks an operator of the schedule; {} children of this run were made by mutation instead (see log.txt)",
                G::NAME,
                r.fallbacks.crossover + r.fallbacks.graft
            );
        }
        let fine = match &r.best_fine {
            Some(f) if f.status == "ok" => format!(" (fine reference {:.6})", f.fitness),
            Some(f) => format!(" (fine reference {:.6}, {})", f.fitness, f.status),
            None => String::new(),
        };
        say!(
            "{}: {fitness}: generation {} best {:.6}{fine}; {evaluations} evaluations, {} simulated in {wall:.1} s ({:.1} evaluations/s), {:.1}% of the time outside evaluation",
            dir.display(),
            r.generation,
            r.stats.best,
            evaluations - reused,
            evaluations as f64 / wall.max(1e-9),
            (wall - evaluating).max(0.0) / wall.max(1e-9) * 100.0
        );
        if let Some(f) = &r.best_fine
            && exploits_stepping(r.stats.best, f.fitness)
        {
            say!(
                "warning: the champion scores {:.6} at the fine reference setting, down more than half of its {:.6}: it may exploit the simulator's step setting (see the README's \"Evolve\", \"Re-walking the best at the fine reference\")",
                f.fitness,
                r.stats.best
            );
        }
        say!(
            "wrote {0}/run.sqlite, {0}/fitness.svg, {0}/best.{1} and {0}/log.txt",
            dir.display(),
            G::TEXT_EXTENSION
        );
    }
    Ok(())
}

/// Subcommands of `ontogeny runs`.
#[derive(Subcommand)]
pub enum RunsVerb {
    /// Print a run's generation table.
    Show {
        /// The run directory.
        dir: PathBuf,
    },
}

/// Flags of `ontogeny runs`.
#[derive(Args)]
pub struct RunsArgs {
    #[command(subcommand)]
    verb: RunsVerb,
}

/// Runs `ontogeny runs`.
pub fn runs(args: &RunsArgs) -> anyhow::Result<()> {
    match &args.verb {
        RunsVerb::Show { dir } => {
            // Read-only: an old run's file is shown as it is, not migrated.
            let store = RunStore::open_read_only(&dir.join("run.sqlite"))
                .map_err(|e| bad(e.to_string()))?;
            let run = store.run().map_err(|e| bad(e.to_string()))?;
            // The task and its fitness as the run's settings name them; a settings text this
            // version cannot read names the task alone.
            let task = run
                .task_spec()
                .map_or_else(|| format!("{} task", run.task), |spec| spec.fitness_label());
            say!(
                "{}: {} encoding, {task}, seed {}, ontogeny {}",
                dir.display(),
                run.encoding,
                run.seed,
                run.version
            );
            say!(
                "{:>5} {:>12} {:>12} {:>12} {:>12} {:>10} {:>7} {:>6} {:>8} {:>8}",
                "gen",
                "best",
                "best fine",
                "mean",
                "median",
                "sd",
                "valid",
                "evals",
                "seconds",
                "evals/s"
            );
            for g in store.generations().map_err(|e| bad(e.to_string()))? {
                // "–" where the best was not re-walked at the fine reference; a status other
                // than ok follows the value.
                let fine = match &g.best_fine {
                    None => "–".to_string(),
                    Some(f) if f.status == "ok" => format!("{:.6}", f.fitness),
                    Some(f) => format!("{:.6} {}", f.fitness, f.status),
                };
                say!(
                    "{:>5} {:>12.6} {fine:>12} {:>12.6} {:>12.6} {:>10.6} {:>6.0}% {:>6} {:>8.1} {:>8.1}",
                    g.index,
                    g.best,
                    g.mean,
                    g.median,
                    g.sd,
                    g.valid_fraction * 100.0,
                    g.evaluations,
                    g.wall_seconds,
                    g.evaluations_per_second
                );
            }
            Ok(())
        }
    }
}

/// `ontogeny replay RUN [--gen G] [--rank K]`: re-evaluates individual K (1 = best) of
/// generation G (default: the last) with a recording, and writes its genome, `creature.png`,
/// `recording.json` and `behaviour.gif` to `RUN/replay/gen-G-rank-K/`.
pub fn replay_run(
    dir: &Path,
    generation: Option<u32>,
    rank: usize,
    fps: f64,
) -> anyhow::Result<()> {
    let encoding = encoding_of_run(dir).map_err(run_error)?;
    with_genome!(
        encoding.as_str(),
        G => replay_typed::<G>(dir, generation, rank, fps),
        |other| Err(bad(format!("{}: unknown encoding '{other}'", dir.display())))
    )
}

fn replay_typed<G: Genome>(
    dir: &Path,
    generation: Option<u32>,
    rank: usize,
    fps: f64,
) -> anyhow::Result<()> {
    // Read-only: replaying never changes the run's store.
    let run = Run::<G>::open_read_only(dir).map_err(run_error)?;
    let last = run
        .last_generation()
        .map_err(run_error)?
        .ok_or_else(|| bad(format!("{}: no complete generation yet", dir.display())))?;
    let generation = generation.unwrap_or(last);
    if generation > last {
        return Err(bad(format!(
            "--gen {generation}: {} has generations 0 to {last}",
            dir.display()
        )));
    }
    let population = run.population(generation).map_err(run_error)?;
    if rank == 0 || rank > population.len() {
        return Err(bad(format!(
            "--rank must be 1 to {}, not {rank}",
            population.len()
        )));
    }
    let order = ontogeny::evolve::ga::ranking(&population);
    let individual = &population[order[rank - 1]];
    let out = dir
        .join("replay")
        .join(format!("gen-{generation}-rank-{rank}"));
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
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
    let limits = &run.config().limits;
    let creature = individual
        .genome
        .develop(limits, individual.develop_seed)
        .map_err(|e| bad(format!("the genome does not develop: {e}")))?;
    let title = format!("generation {generation}, rank {rank}");
    ontogeny::render::write_png(&creature, &title, &png, 960, 600)
        .map_err(super::render_error(&png))?;
    let evaluation = run.config().task.evaluate(&creature, true);
    super::eval::write_recording_at(&out, &creature, &evaluation, fps)?;
    let stored = individual.evaluation.fitness;
    say!(
        "generation {generation}, rank {rank}: {} fitness {:.6} ({}; stored {stored:.6})",
        evaluation.task,
        evaluation.fitness,
        serde_json::to_value(evaluation.status)?
            .as_str()
            .unwrap_or("?")
    );
    if evaluation.fitness != stored {
        say!("warning: the re-evaluation differs from the stored fitness");
    }
    say!(
        "wrote {0}/{genome_name}, {0}/creature.png, {0}/recording.json and {0}/behaviour.gif",
        out.display()
    );
    Ok(())
}
