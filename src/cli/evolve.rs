//! `ontogeny evolve` and `ontogeny runs`.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::Args;
use ontogeny::encoding::{ENCODINGS, EncodingInfo, Genome, encoding_named};
use ontogeny::evolve::ga::{Algorithm, Preset, WalkOrder};
use ontogeny::front::settings::{self, RunFlags};
use ontogeny::front::start::{NewRun, StartError, start_run};
use ontogeny::front::text::{self, RunTally};
use ontogeny::lang::Source;
use ontogeny::run::config::read_config_source;
use ontogeny::run::{GenerationReport, Run, RunError, encoding_of_run, unknown_encoding_of_run};
use ontogeny::sim::StepSetting;

pub use super::bad;
use super::physics::{RunTaskArgs, setting_parser};

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

/// Parses `--preset`: one of the library's presets by its name ([`Preset::name`]), every
/// name listed in the help with its summary.
pub fn preset_parser() -> impl clap::builder::TypedValueParser<Value = Preset> {
    use clap::builder::TypedValueParser;
    let names = Preset::ALL.map(|p| clap::builder::PossibleValue::new(p.name()).help(p.summary()));
    clap::builder::PossibleValuesParser::new(names).try_map(|name: String| {
        Preset::named(&name).ok_or_else(|| format!("unknown preset '{name}'"))
    })
}

/// Parses `--algorithm`: one of the library's algorithms by its name, every name listed in
/// the help with its summary.
fn algorithm_parser() -> impl clap::builder::TypedValueParser<Value = Algorithm> {
    use clap::builder::TypedValueParser;
    let names =
        Algorithm::ALL.map(|a| clap::builder::PossibleValue::new(a.name()).help(a.summary()));
    clap::builder::PossibleValuesParser::new(names).try_map(|name: String| {
        Algorithm::named(&name).ok_or_else(|| format!("unknown algorithm '{name}'"))
    })
}

/// Parses `--walk-order`: one of the library's walk orders by its name, every name listed in
/// the help with its summary.
fn walk_order_parser() -> impl clap::builder::TypedValueParser<Value = WalkOrder> {
    use clap::builder::TypedValueParser;
    let names =
        WalkOrder::ALL.map(|o| clap::builder::PossibleValue::new(o.name()).help(o.summary()));
    clap::builder::PossibleValuesParser::new(names).try_map(|name: String| {
        WalkOrder::named(&name).ok_or_else(|| format!("unknown walk order '{name}'"))
    })
}

/// The flags that go with `--resume`; it refuses every other ([`super::conflicts_with_all_but`]).
pub const WITH_RESUME: &[&str] = &[
    "gens",
    "threads",
    "allow_evaluator_change",
    "json",
    "profile",
    "walk_order",
];

/// Evolve creatures: a genetic algorithm over an encoding, on a task, into a run directory
/// (or `--resume` one).
#[derive(Args)]
pub struct EvolveArgs {
    /// The run directory to create (refused if it holds a run).
    #[arg(long, value_name = "DIR", required_unless_present = "resume")]
    out: Option<PathBuf>,
    /// Continue the run in DIR where it stopped (any other flag but --threads and --gens is
    /// refused).
    #[arg(long, value_name = "DIR")]
    resume: Option<PathBuf>,
    /// The genome encoding (default: the config's, else lsystem).
    #[arg(long, value_parser = encoding_parser())]
    encoding: Option<EncodingArg>,
    #[command(flatten)]
    run_task: RunTaskArgs,
    /// The genetic algorithm's schedule (default: the config's, else chaumont).
    #[arg(long, value_parser = preset_parser())]
    preset: Option<Preset>,
    /// How generations follow one another (default: the config's, else generational):
    /// steady-state breeds one creature at a time and replaces the population's worst, with no
    /// wait at a generation's end, so that every thread stays busy. Results never depend on
    /// the threads.
    #[arg(long, value_parser = algorithm_parser())]
    algorithm: Option<Algorithm>,
    /// Steady-state: the births in flight at the least, W (default: the config's, else 32);
    /// each creature is bred from the last generation that ended at least W births before it.
    /// Part of the algorithm: results depend on it (never on --threads); give several times
    /// the threads you run on (on 16 threads, 100 filled them best of 32, 50 and 100 measured).
    #[arg(long, value_name = "W")]
    in_flight: Option<usize>,
    /// Individuals per generation (default: the preset's, 300).
    #[arg(long)]
    pop: Option<usize>,
    /// Generations (default: the preset's, 100). With --resume: extend the run to this many
    /// generations in all (at least as many as it has).
    #[arg(long)]
    gens: Option<usize>,
    /// A budget of walks instead of --gens: as many generations as fit in N walks, counting
    /// the whole first generation, then every individual but the elite (the elite too with
    /// fresh trials), each one walk per habitat and trial, simulated or reused from the
    /// evaluation cache (so K = 4 trials gets a quarter of the evaluations of K = 1).
    #[arg(long, value_name = "N", conflicts_with = "gens")]
    walks: Option<u64>,
    /// The run's seed (default: the config's, else 1).
    #[arg(long)]
    seed: Option<u64>,
    /// Seconds of the task's measurement (walker: walking, default 20), in (0, 3600].
    #[arg(long)]
    seconds: Option<f64>,
    /// The aim task's target relative to the projectile's start, as X,Y,Z metres, as `eval
    /// --target` (aim only; default: the config's `[task.catapult] target`).
    #[arg(long, value_name = "X,Y,Z", value_parser = ontogeny::front::flags::parse_point, allow_hyphen_values = true)]
    target: Option<[f64; 3]>,
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
    /// With --resume: go on with a run whose last generation another evaluator version (an
    /// ontogeny whose physics or task protocol differ) made; the store records where the
    /// version changes.
    #[arg(long)]
    allow_evaluator_change: bool,
    /// Do not re-walk each generation's best at the fine reference setting (the config's
    /// `verify_best = false`).
    #[arg(long)]
    no_verify_best: bool,
    /// Simulate every individual, even one identical to a creature evaluated earlier in the
    /// run (the config's `cache = false`); results are the same either way.
    #[arg(long)]
    no_cache: bool,
    /// Write where each generation's time goes to FILE (JSON Lines, a line per generation
    /// this command runs): the seconds of breeding, developing, keying, evaluating, waiting
    /// for the fine re-walk and writing, and every walk's seconds and the thread that ran it. For `ontogeny
    /// runs schedule`; the run's results do not depend on it.
    #[arg(long, value_name = "FILE")]
    profile: Option<PathBuf>,
    /// The order in which each generation's walks are handed to the threads, each to the
    /// first thread free: the longest likely first keeps the threads busy until the
    /// generation's end (the generational algorithm, and a steady-state run's generation 0).
    /// The run's results do not depend on it; for benchmarks.
    #[arg(long, value_name = "ORDER", value_parser = walk_order_parser(), default_value = "longest-first")]
    walk_order: WalkOrder,
    /// Print the final line as one JSON object (the run's directory, encoding and fitness, the
    /// last generation's best and its fine reference, the counts and speed, the files
    /// written); progress and messages still go to standard error.
    #[arg(long)]
    json: bool,
}

/// The command line's error for a run's: bad input (exit code 2), or, for a store or a plot
/// that could not be written, ontogeny's own failure (exit code 1).
pub fn run_error(e: RunError) -> anyhow::Error {
    match e {
        RunError::Config(d) => anyhow::Error::new(d),
        RunError::Io { path, source } => {
            anyhow::Error::new(source).context(format!("{}", path.display()))
        }
        RunError::Store(e) if !e.is_bad_input() => anyhow::anyhow!("{e}"),
        e @ (RunError::Plot(_) | RunError::Panicked(_)) => anyhow::anyhow!("{e}"),
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
    if let Some(path) = &args.profile {
        // Refused before the run starts, rather than after its directory is made.
        ontogeny::output::check_target(path).map_err(|e| bad(e.to_string()))?;
    }
    let Some(_cluster) = ontogeny::evolve::evaluator::join_cluster()? else {
        return Ok(()); // a worker rank of an MPI job: it evaluated what rank 0 sent
    };
    if let Some(dir) = &args.resume {
        let encoding = encoding_of_run(dir).map_err(run_error)?;
        return with_genome!(encoding.as_str(), G => resume::<G>(dir, args), |other| Err(bad(unknown_encoding_of_run(dir, other))));
    }
    if args.allow_evaluator_change {
        return Err(bad(
            "--allow-evaluator-change goes with --resume: a new run has one evaluator",
        ));
    }
    let mut source = read_source(args.config.as_deref())?;
    let example = source.is_none()
        && args.preset.is_none()
        && args.pop.is_none()
        && args.gens.is_none()
        && args.walks.is_none();
    if example {
        // Chaumont's full schedule is 300 × 100 walks (hours): with nothing said about the
        // run's size, the README's walker example starts instead, and says so.
        source = Some(ontogeny::lang::Source::new(
            DEFAULT_CONFIG_NAME,
            DEFAULT_CONFIG,
        ));
    }
    let encoding =
        settings::new_run_encoding(args.encoding.map(EncodingArg::name), source.as_deref())?;
    with_genome!(
        encoding.as_str(),
        G => start::<G>(args, source.as_deref(), example),
        |other| Err(bad(format!(
            "unknown encoding '{other}' ({})",
            encoding_names()
        )))
    )
}

/// The configuration a new run starts from when no `--config`, `--preset`, `--pop` or
/// `--gens` is given: the README's walker example (100 × 40 walks of 20 s, distance).
const DEFAULT_CONFIG: &str = include_str!("../../examples/evolve-walker.toml");

/// The name [`DEFAULT_CONFIG`] goes by in messages.
const DEFAULT_CONFIG_NAME: &str = "examples/evolve-walker.toml (built in)";

/// What a new run started from [`DEFAULT_CONFIG`] says on standard error.
pub fn default_run_note(seconds: Option<f64>) -> String {
    let walks = match seconds {
        Some(s) => format!(
            "{}-second walks (--seconds)",
            ontogeny::number::format_number(s)
        ),
        None => "20-second walks".to_string(),
    };
    format!(
        "note: no --config, --preset, --pop or --gens: starting the walker example (examples/evolve-walker.toml, built in: the lsystem genome, Chaumont's schedule, 100 creatures × 40 generations of {walks}, fitness distance; about a minute on two cores); other flags apply over it; --preset chaumont runs Chaumont's full 300 × 100"
    )
}

/// The run's flags that set its genetic algorithm and task.
fn run_flags(args: &EvolveArgs) -> RunFlags {
    RunFlags {
        preset: args.preset,
        population: args.pop,
        generations: args.gens,
        walks: args.walks,
        task: args.run_task.task,
        fitness: args.run_task.fitness.clone(),
        seconds: args.seconds,
        setting: args.setting,
        target: args.target,
        algorithm: args.algorithm,
        in_flight: args.in_flight,
    }
}

/// The config file at `path`, if one is given.
pub fn read_source(path: Option<&Path>) -> anyhow::Result<Option<std::sync::Arc<Source>>> {
    Ok(path.map(read_config_source).transpose()?)
}

/// Resolves the settings (command line over config file over preset) and starts the run;
/// `example` says that `source` is the built-in walker example, noted once the settings hold.
fn start<G: Genome>(
    args: &EvolveArgs,
    source: Option<&Source>,
    example: bool,
) -> anyhow::Result<()> {
    let out = args
        .out
        .as_ref()
        .expect("clap requires --out without --resume");
    let flags = run_flags(args);
    let new = NewRun {
        out,
        source,
        flags: &flags,
        init: args.init.as_deref(),
        seed: args.seed,
        verify_best: !args.no_verify_best,
        cache: !args.no_cache,
    };
    let mut run = start_run::<G>(&new, |notes| {
        if example {
            tell!("{}", default_run_note(args.seconds));
        }
        for note in notes {
            tell!("{note}");
        }
    })
    .map_err(|e| match e {
        StartError::Settings(d) => anyhow::Error::new(d),
        StartError::Run(e) => run_error(e),
    })?;
    go(
        &mut run,
        out,
        args.json,
        args.profile.as_deref(),
        args.walk_order,
    )
}

fn resume<G: Genome>(dir: &Path, args: &EvolveArgs) -> anyhow::Result<()> {
    let json = args.json;
    let mut run = Run::<G>::resume_with(dir, args.allow_evaluator_change).map_err(run_error)?;
    if let Some(generations) = args.gens {
        run.extend(generations).map_err(run_error)?;
    }
    let done = run.last_generation().map_err(run_error)?;
    let total = run.config().ga.generations as u32;
    match done {
        Some(g) if g + 1 >= total => {
            // Its log, plot and best genome are drawn again from the store, as this
            // version draws them.
            run.write_derived_files().map_err(run_error)?;
            tell!(
                "{}: complete ({total} generations); nothing to resume; its log.txt, fitness.svg and best genome written again",
                dir.display()
            );
            if json && let Some(last) = run.last_report().map_err(run_error)? {
                // The final line of the run as it stands: nothing evaluated by this command.
                let fitness = run.config().task.fitness_label();
                let end = ontogeny::front::text::RunEnd {
                    dir,
                    fitness: &fitness,
                    encoding: G::NAME,
                    extension: G::TEXT_EXTENSION,
                    last: &last,
                    wall: 0.0,
                };
                let object = ontogeny::front::json::run_json(&RunTally::default(), &end);
                say!("{}", serde_json::to_string_pretty(&object)?);
            }
            return Ok(());
        }
        Some(g) => tell!("{}: resuming after generation {g}", dir.display()),
        None => tell!("{}: resuming from the first generation", dir.display()),
    }
    go(
        &mut run,
        dir,
        json,
        args.profile.as_deref(),
        args.walk_order,
    )
}

/// Runs the remaining generations with a progress bar on a terminal, log lines otherwise;
/// the final line as JSON when `json` is set; each generation's timings to `profile`, if
/// given; the walks handed out in `walk_order`.
fn go<G: Genome>(
    run: &mut Run<G>,
    dir: &Path,
    json: bool,
    profile: Option<&Path>,
    walk_order: WalkOrder,
) -> anyhow::Result<()> {
    run.set_walk_order(walk_order);
    if let Some(path) = profile {
        run.set_profile(path).map_err(run_error)?;
    }
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
    let mut tally = RunTally::default();
    let mut last: Option<GenerationReport> = None;
    let fitness = run.config().task.fitness_label();
    let ga = run.config().ga.clone();
    let fresh = run.config().task.trials.fresh;
    let threads = rayon::current_num_threads();
    let start = text::start_line(G::NAME, &fitness, &ga, fresh, first as usize, threads);
    tell!("{start}");
    let mut observer = |r: &GenerationReport| {
        tally.add(r);
        let line = text::generation_line(&fitness, r);
        let left = text::evaluations_from(&ga, fresh, r.generation as usize + 1);
        let estimate = (last.is_none() && left > 0).then(|| text::estimate_line(r, left));
        match &bar {
            Some(bar) => {
                if let Some(e) = estimate {
                    bar.println(e);
                }
                bar.set_message(line);
                bar.inc(1);
            }
            None => {
                tell!("generation {}: {line}", r.generation);
                if let Some(e) = estimate {
                    tell!("{e}");
                }
            }
        }
        last = Some(r.clone());
    };
    run.run(&mut observer).map_err(run_error)?;
    if let Some(bar) = &bar {
        bar.finish();
    }
    let wall = started.elapsed().as_secs_f64();
    if let Some(r) = last {
        let end = ontogeny::front::text::RunEnd {
            dir,
            fitness: &fitness,
            encoding: G::NAME,
            extension: G::TEXT_EXTENSION,
            last: &r,
            wall,
        };
        let lines = tally.closing_lines(&end);
        if json {
            // The messages as ever; the final line as JSON.
            for line in lines {
                if let ontogeny::front::text::Line::Message(m) = line {
                    tell!("{m}");
                }
            }
            let object = ontogeny::front::json::run_json(&tally, &end);
            say!("{}", serde_json::to_string_pretty(&object)?);
        } else {
            super::print(lines)?;
        }
    }
    Ok(())
}
