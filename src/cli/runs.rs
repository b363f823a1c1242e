//! `ontogeny runs`: inspecting run directories.

use std::path::PathBuf;

use anyhow::Context;
use clap::{Args, Subcommand};
use ontogeny::encoding::Genome;
use ontogeny::evolve::settings::MAX_IN_FLIGHT;
use ontogeny::front::text;
use ontogeny::run::pick::PickError;
use ontogeny::run::profile::read_profile;
use ontogeny::run::{Run, encoding_of_run, unknown_encoding_of_run};
use ontogeny::study::canalization::{self, Settings};
use ontogeny::study::lifetime;
use ontogeny::study::listing;
use ontogeny::study::plasticity::{self, FoundRun, PlasticityError};
use ontogeny::study::schedule::{self, Machine, Schedule};
use ontogeny::study::steady_schedule;
use ontogeny::study::sustained::{self, SustainedSettings};

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
    Plasticity(MeasuredRunsArgs),
    /// Measure development during the walk (Kriegman's measure) for runs whose creatures grow
    /// while they walk: per generation, what the best individual and the generation on average
    /// grew during their walks, body (parts, length) against brain (neurons, links). A table
    /// per condition, a row per generation (medians over the runs).
    Growth(MeasuredRunsArgs),
    /// Check sustained motion (Chaumont et al. 3.5): walk each run's champion (a
    /// comparison's, the runs under a directory, or one run's; plain walker runs) for longer
    /// than it was evolved for, and say whether it stopped: whether its root moved less than
    /// --still metres in the last --window seconds. A row per champion, and how many stopped.
    Sustained(SustainedArgs),
    /// Predict from a run's profile (`evolve --profile FILE`) the evaluations per second it
    /// would reach on other numbers of threads (or MPI ranks × threads), under its own
    /// generational schedule (each generation's walks in their recorded order, each to the
    /// first thread free, a barrier at the generation's end, its time outside evaluation as
    /// recorded) or a steady-state one (--steady-state). --population and --driver-us project
    /// to populations and costs no run recorded. A row per machine.
    Schedule(ScheduleArgs),
}

/// The flags of `ontogeny runs schedule`.
#[derive(Args)]
pub struct ScheduleArgs {
    /// The profile, written by `ontogeny evolve --profile FILE`.
    profile: PathBuf,
    /// Threads per rank to predict for, comma-separated, each 1 to 1024 [default:
    /// 1,2,4,...,1024].
    #[arg(long, value_name = "N,N,...", value_delimiter = ',')]
    threads: Vec<u32>,
    /// MPI ranks, each with the threads of --threads, 1 to 1024.
    #[arg(long, value_name = "R", default_value_t = 1)]
    ranks: u32,
    /// Model each generation's walks handed out longest-first, by their creatures' parts
    /// (`evolve --walk-order longest-first`, the default), on a profile recorded in the
    /// individuals' order.
    #[arg(long)]
    longest_first: bool,
    /// Model the fine re-walk of each generation's best walked beside the next generation's
    /// walks, first in its batch, on a profile recorded while it was walked alone before the
    /// generation was stored (by Ontogeny before it walked it beside, as `evolve` does now).
    #[arg(long)]
    fine_beside: bool,
    /// Replay the profile as a steady-state run with W births in flight (no generation
    /// barrier; births integrated in order; 1 to 100000, as `evolve --in-flight`) instead of
    /// generationally.
    #[arg(long, value_name = "W", conflicts_with_all = ["longest_first", "fine_beside"])]
    steady_state: Option<usize>,
    /// Replay generations of N evaluations of one walk each, drawn at random (seed 1, with
    /// replacement) from the profile's walks, in place of the recorded generations (1 to
    /// 1000000): a projection to a population no run recorded.
    #[arg(long, value_name = "N")]
    population: Option<usize>,
    /// With --population: how many generations to draw [default: the profile's].
    #[arg(long, value_name = "G", requires = "population")]
    generations: Option<usize>,
    /// Charge each evaluation this many microseconds of serial work on the driver (rank 0's
    /// breeding, developing and keying) in place of the recorded time outside evaluation (the
    /// fine re-walks kept): a projection to a cheaper or dearer rank 0. 0 to 1000000.
    #[arg(long, value_name = "US")]
    driver_us: Option<f64>,
    /// Print one JSON object: what the profile recorded and a prediction per machine.
    #[arg(long)]
    json: bool,
}

/// The flags of `ontogeny runs sustained`.
#[derive(Args)]
pub struct SustainedArgs {
    /// A comparison directory, a directory with runs under it, or a run directory.
    dir: PathBuf,
    /// Seconds of measured walking, in (0, 3600] (the runs walked 20 in Chaumont's protocol).
    #[arg(long, default_value_t = 60.0)]
    seconds: f64,
    /// The last seconds of the walk whose movement says whether it stopped.
    #[arg(long, default_value_t = 10.0)]
    window: f64,
    /// A champion whose root moved less than this (m) over the window has stopped.
    #[arg(long, value_name = "M", default_value_t = 0.1)]
    still: f64,
    /// Print one JSON object: the settings and a walk per champion.
    #[arg(long)]
    json: bool,
}

/// The flags of `ontogeny runs plasticity` and `ontogeny runs growth`: the runs measured and
/// how the result is printed.
#[derive(Args)]
pub struct MeasuredRunsArgs {
    /// A comparison directory, a directory with runs under it, or a run directory.
    dir: PathBuf,
    /// Print a CSV: a header, then a row per champion and habitat (`plasticity`) or per run
    /// and generation (`growth`), every number in full (empty where there is none).
    #[arg(long, conflicts_with = "json")]
    csv: bool,
    /// Print one JSON object: each condition's champions and summary (`plasticity`), or the
    /// directory and each run's generations (`growth`).
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
/// growth DIR`), sustained motion (`runs sustained DIR`), the speed of a profiled run on other machines (`runs schedule PROFILE`).
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
                |other| Err(super::bad(unknown_encoding_of_run(&args.dir, other)))
            )?;
        }
        RunsVerb::Plasticity(args) => plasticity_of(args)?,
        RunsVerb::Growth(args) => growth_of(args)?,
        RunsVerb::Sustained(args) => sustained_of(args)?,
        RunsVerb::Schedule(args) => schedule_of(args)?,
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

/// The runs under `dir` (as `runs plasticity` finds them) measured by `measure`, with a
/// progress bar labelled `label` and the notes of both steps on standard error.
fn measure_found<T>(
    dir: &std::path::Path,
    label: &str,
    measure: impl FnOnce(
        &[FoundRun],
        &mut dyn FnMut(usize, usize),
    ) -> Result<(Vec<T>, Vec<String>), PlasticityError>,
) -> anyhow::Result<Vec<T>> {
    let (runs, notes) = plasticity::find_runs(dir).map_err(measurement_error)?;
    for note in notes {
        tell!("note: {note}");
    }
    let mut progress = super::progress::Progress::new(label);
    let (measured, notes) = measure(&runs, &mut |done, all| {
        progress.set(done as f64 / all as f64)
    })
    .map_err(measurement_error)?;
    progress.finish();
    for note in notes {
        tell!("note: {note}");
    }
    Ok(measured)
}

/// `ontogeny runs schedule`.
fn schedule_of(args: &ScheduleArgs) -> anyhow::Result<()> {
    let threads = if args.threads.is_empty() {
        schedule::default_threads()
    } else {
        args.threads.clone()
    };
    let machines: Vec<Machine> = threads
        .iter()
        .map(|&threads| Machine {
            ranks: args.ranks,
            threads,
        })
        .collect();
    for machine in &machines {
        machine.check().map_err(super::bad)?;
    }
    let recorded = read_profile(&args.profile).map_err(|e| super::bad(e.to_string()))?;
    // A generational run walks its fine re-walks beside the next generation: replayed as
    // walked alone, with that lever on, as the run scheduled them.
    let beside = recorded.iter().any(|g| g.fine_walk.is_some());
    let mut profile: Vec<_> = recorded.iter().map(|g| g.walked_alone()).collect();
    let levers = schedule::Levers {
        longest_first: args.longest_first,
        fine_beside: args.fine_beside || (beside && args.steady_state.is_none()),
    };
    if levers.longest_first && !schedule::records_parts(&profile) {
        return Err(super::bad(format!(
            "{}: the profile records no creature sizes (it was written by an older ontogeny): --longest-first needs them; profile the run again",
            args.profile.display()
        )));
    }
    let limit = 1_000_000;
    for (flag, value, most) in [
        ("--steady-state", args.steady_state, MAX_IN_FLIGHT),
        ("--population", args.population, limit),
        ("--generations", args.generations, limit),
    ] {
        if let Some(n) = value
            && !(1..=most).contains(&n)
        {
            return Err(super::bad(format!("{flag} must be 1 to {most}, not {n}")));
        }
    }
    if let Some(population) = args.population {
        let generations = args.generations.unwrap_or(profile.len());
        if population.saturating_mul(generations) > 10 * limit {
            return Err(super::bad(format!(
                "--population {population} × --generations {generations} is over {} walks; draw fewer",
                10 * limit
            )));
        }
        profile = steady_schedule::resampled(&profile, population, generations, 1);
        if profile.is_empty() {
            return Err(super::bad(format!(
                "{}: the profile holds no walk times to draw from (a run over MPI ranks does not record them)",
                args.profile.display()
            )));
        }
    }
    if let Some(us) = args.driver_us {
        if !(0.0..=1e6).contains(&us) {
            return Err(super::bad(format!(
                "--driver-us must be 0 to 1000000, not {us}"
            )));
        }
        profile = steady_schedule::with_driver(&profile, us * 1e-6);
    }
    let plan = match args.steady_state {
        Some(in_flight) => Schedule::SteadyState { in_flight },
        None => Schedule::Generational(levers),
    };
    let recorded = schedule::recorded(&profile);
    let rows: Vec<_> = machines
        .iter()
        .map(|&m| plan.predict(&profile, m))
        .collect();
    let mut name = args.profile.display().to_string();
    if let Some(population) = args.population {
        name.push_str(&format!(
            " (its walks drawn into {} generation{} of {population}: what follows is of the drawn profile, not measured)",
            profile.len(),
            if profile.len() == 1 { "" } else { "s" }
        ));
    }
    if let Some(us) = args.driver_us {
        name.push_str(&format!(" (driver {us} µs an evaluation)"));
    }
    let ceiling = schedule::ceiling_per_thread(&profile);
    if args.json {
        say!("{}", schedule::json(&name, &recorded, ceiling, &rows, plan));
    } else {
        let one = plan.predict(
            &profile,
            Machine {
                ranks: 1,
                threads: 1,
            },
        );
        say!(
            "{}",
            schedule::table(&name, &recorded, (&one, ceiling), &rows, plan)
        );
    }
    Ok(())
}

/// `ontogeny runs growth`.
fn growth_of(args: &MeasuredRunsArgs) -> anyhow::Result<()> {
    let rows = measure_found(&args.dir, "reading the runs", lifetime::measure_runs)?;
    say!(
        "{}",
        if args.json {
            lifetime::json(&args.dir, &rows)
        } else if args.csv {
            lifetime::csv(&rows)
        } else {
            lifetime::text(&rows)
        }
    );
    Ok(())
}

/// `ontogeny runs sustained`.
fn sustained_of(args: &SustainedArgs) -> anyhow::Result<()> {
    let settings = SustainedSettings {
        seconds: args.seconds,
        window: args.window,
        still: args.still,
    };
    settings.check().map_err(super::bad)?;
    let walks = measure_found(&args.dir, "walking the champions", |runs, progress| {
        sustained::walk_champions(runs, &settings, progress)
    })?;
    say!(
        "{}",
        if args.json {
            serde_json::json!({ "settings": settings, "walks": walks }).to_string()
        } else {
            sustained::text(&settings, &walks)
        }
    );
    Ok(())
}

/// `ontogeny runs plasticity`.
fn plasticity_of(args: &MeasuredRunsArgs) -> anyhow::Result<()> {
    let dir = &args.dir;
    let champions = measure_found(dir, "measuring plasticity", plasticity::measure_runs)?;
    say!(
        "{}",
        if args.json {
            plasticity::json(dir, &champions)
        } else if args.csv {
            plasticity::csv(&champions)
        } else {
            plasticity::text(dir, &champions)
        }
    );
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
