//! `ontogeny runs`: inspecting run directories.

use std::path::PathBuf;

use anyhow::Context;
use clap::{Args, Subcommand};
use ontogeny::encoding::Genome;
use ontogeny::front::text;
use ontogeny::run::pick::PickError;
use ontogeny::run::{Run, encoding_of_run};
use ontogeny::study::canalization::{self, Settings};
use ontogeny::study::lifetime;
use ontogeny::study::listing;
use ontogeny::study::plasticity::{self, PlasticityError};

/// Subcommands of `ontogeny runs`.
#[derive(Subcommand)]
pub enum RunsVerb {
    /// Print a run's generation table (or, with --csv or --json, every generation's record).
    Show {
        /// The run directory.
        dir: PathBuf,
        /// Print the generations as CSV: a header, then a row per generation, every number in
        /// full (empty where there is none).
        #[arg(long, conflicts_with = "json")]
        csv: bool,
        /// Print the run as one JSON object: its settings and an array of its generations.
        #[arg(long)]
        json: bool,
    },
    /// List the runs and comparisons in a directory and under it, one line each: path, kind,
    /// encoding(s), task, progress and best (or why it cannot be read).
    List {
        /// The directory to search.
        dir: PathBuf,
    },
    /// Measure canalization: how much each generation's best individual's body varies under
    /// noise in the chemical values it develops in (each habitat's, or its own) and under
    /// mutation. A row per generation measured.
    Canalization(CanalizationArgs),
    /// Measure plasticity: for each run's champion (a comparison's, the runs under a
    /// directory, or one run's), its fitness in each habitat walked again, and its reaction
    /// norm: the body grown under each cue (each distinct chemical array of the habitats) and
    /// how those bodies differ. A table per condition, a row per champion, and a summary.
    Plasticity(PlasticityArgs),
    /// Measure development during the walk (Kriegman's measure) for runs whose creatures grow
    /// while they walk: per generation, what the best individual and the generation on average
    /// grew during their walks, body (parts, length) against brain (neurons, links). A table
    /// per condition, a row per generation (medians over the runs).
    Growth(GrowthArgs),
}

/// The flags of `ontogeny runs growth`.
#[derive(Args)]
pub struct GrowthArgs {
    /// A comparison directory, a directory with runs under it, or a run directory.
    dir: PathBuf,
    /// Print a CSV: a header, then a row per run and generation, every number in full (empty
    /// where there is none).
    #[arg(long, conflicts_with = "json")]
    csv: bool,
    /// Print one JSON object: the directory and a row per run and generation.
    #[arg(long)]
    json: bool,
}

/// The flags of `ontogeny runs plasticity`.
#[derive(Args)]
pub struct PlasticityArgs {
    /// A comparison directory, a directory with runs under it, or a run directory.
    dir: PathBuf,
    /// Print a CSV: a header, then a row per champion and habitat, every number in full
    /// (empty where there is none).
    #[arg(long, conflicts_with = "json")]
    csv: bool,
    /// Print one JSON object: each condition's champions and summary.
    #[arg(long)]
    json: bool,
}

/// The flags of `ontogeny runs canalization`.
#[derive(Args)]
pub struct CanalizationArgs {
    /// The run directory.
    dir: PathBuf,
    /// Noisy arrays, and mutants, per array the genome develops in.
    #[arg(long, default_value_t = canalization::DEFAULT_SAMPLES)]
    samples: usize,
    /// Each slot of a noisy array moves by a uniform draw in ±X.
    #[arg(long, value_name = "X", default_value_t = canalization::DEFAULT_NOISE)]
    noise: f64,
    /// The mutants' mutation rate, in [0, 1] [default: the run's `[ga] mutation_rate`].
    #[arg(long, value_name = "R")]
    rate: Option<f64>,
    /// Measure every K-th generation from 0, and the last [default: every generation].
    #[arg(long, value_name = "K", default_value_t = 1)]
    every: u32,
    /// The seed of every draw: the same seed gives the same figures on any number of threads.
    #[arg(long, value_name = "N", default_value_t = 0)]
    seed: u64,
    /// Print a CSV: a header, then a row per generation, every number in full (empty where
    /// there is none).
    #[arg(long, conflicts_with = "json")]
    csv: bool,
    /// Print one JSON object: the settings and an array of the generations measured.
    #[arg(long)]
    json: bool,
}

/// Inspect runs: a run's generations (`runs show DIR`), the runs and comparisons under a
/// directory (`runs list DIR`), the canalization of its champions (`runs canalization DIR`),
/// the plasticity of champions (`runs plasticity DIR`), development during the walk (`runs
/// growth DIR`).
#[derive(Args)]
pub struct RunsArgs {
    #[command(subcommand)]
    verb: RunsVerb,
}

/// Runs `ontogeny runs`.
pub fn run(args: &RunsArgs) -> anyhow::Result<()> {
    match &args.verb {
        RunsVerb::Show { dir, csv, json } => {
            let shown = match (csv, json) {
                (true, _) => text::generation_csv(dir),
                (_, true) => text::generation_json(dir),
                _ => text::generation_table(dir),
            };
            say!("{}", shown.map_err(|e| super::bad(e.to_string()))?);
        }
        RunsVerb::List { dir } => {
            let found =
                listing::list(dir).with_context(|| format!("cannot read {}", dir.display()))?;
            if found.is_empty() {
                tell!("{}: no run or comparison here", dir.display());
            }
            for listed in found {
                say!("{}", listed.line());
            }
        }
        RunsVerb::Canalization(args) => {
            if args.every == 0 {
                anyhow::bail!(super::bad("--every must be at least 1, not 0"));
            }
            let encoding = encoding_of_run(&args.dir).map_err(super::evolve::run_error)?;
            with_genome!(
                encoding.as_str(),
                G => canalization_of::<G>(args),
                |other| Err(super::bad(format!(
                    "{}: unknown encoding '{other}'",
                    args.dir.display()
                )))
            )?;
        }
        RunsVerb::Plasticity(args) => plasticity_of(args)?,
        RunsVerb::Growth(args) => growth_of(args)?,
    }
    Ok(())
}

/// A measurement's error as the command line reports it: bad input exits 2.
fn measurement_error(e: PlasticityError) -> anyhow::Error {
    match e {
        PlasticityError::Run(e) => super::evolve::run_error(e),
        PlasticityError::Input(message) => super::bad(message),
        PlasticityError::Other(message) => anyhow::anyhow!(message),
    }
}

/// `ontogeny runs growth`.
fn growth_of(args: &GrowthArgs) -> anyhow::Result<()> {
    let (runs, notes) = plasticity::find_runs(&args.dir).map_err(measurement_error)?;
    for note in notes {
        tell!("note: {note}");
    }
    let mut progress = super::progress::Progress::new("reading the runs");
    let (rows, notes) = lifetime::measure_runs(&runs, &mut |done, all| {
        progress.set(done as f64 / all as f64)
    })
    .map_err(measurement_error)?;
    progress.finish();
    for note in notes {
        tell!("note: {note}");
    }
    if args.json {
        say!("{}", lifetime::json(&args.dir, &rows));
    } else if args.csv {
        say!("{}", lifetime::csv(&rows));
    } else {
        say!("{}", lifetime::text(&rows));
    }
    Ok(())
}

/// `ontogeny runs plasticity`.
fn plasticity_of(args: &PlasticityArgs) -> anyhow::Result<()> {
    let dir = &args.dir;
    let error = measurement_error;
    let (runs, notes) = plasticity::find_runs(dir).map_err(error)?;
    for note in notes {
        tell!("note: {note}");
    }
    let mut progress = super::progress::Progress::new("measuring plasticity");
    let (champions, notes) = plasticity::measure_runs(&runs, &mut |done, all| {
        progress.set(done as f64 / all as f64)
    })
    .map_err(error)?;
    progress.finish();
    for note in notes {
        tell!("note: {note}");
    }
    if args.json {
        say!("{}", plasticity::json(dir, &champions));
    } else if args.csv {
        say!("{}", plasticity::csv(&champions));
    } else {
        say!("{}", plasticity::text(dir, &champions));
    }
    Ok(())
}

/// `ontogeny runs canalization` on a run of genome `G`.
fn canalization_of<G: Genome>(args: &CanalizationArgs) -> anyhow::Result<()> {
    let dir = &args.dir;
    // Read-only: measuring never changes the run's store.
    let run = Run::<G>::open_read_only(dir).map_err(super::evolve::run_error)?;
    let settings = Settings {
        samples: args.samples,
        noise: args.noise,
        mutation_rate: args.rate.unwrap_or(run.config().ga.mutation_rate),
        seed: args.seed,
    };
    settings.check().map_err(super::bad)?;
    let last = run
        .last_generation()
        .map_err(super::evolve::run_error)?
        .ok_or_else(|| super::bad(format!("{}: no complete generation yet", dir.display())))?;
    let generations = canalization::generations_measured(last, args.every);
    let mut progress = super::progress::Progress::new("measuring canalization");
    let rows = canalization::measure_run(&run, dir, &generations, &settings, &mut |done, all| {
        progress.set(done as f64 / all as f64)
    })
    .map_err(|e| match e {
        PickError::Run(e) => super::evolve::run_error(e),
        PickError::Input(message) => super::bad(message),
    })?;
    progress.finish();
    if args.json {
        say!("{}", canalization::json(dir, &settings, &rows));
    } else if args.csv {
        say!("{}", canalization::csv(&rows));
    } else {
        let arrays = run.config().task.habitat_count();
        say!(
            "{}: canalization of each generation's best; {}",
            dir.display(),
            canalization::settings_line(&settings, arrays)
        );
        say!("{}", canalization::table(&rows));
    }
    Ok(())
}
