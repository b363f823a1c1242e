//! `ontogeny compare`: encodings, or conditions (whole run configs), compared on equal budgets
//! of walks over replicated runs.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;
use clap::Args;
use ontogeny::encoding::Genome;
use ontogeny::front::settings::{self, RunFlags};
use ontogeny::front::text::{self, ComparisonProgress};
use ontogeny::run::config::{ConfigFile, read_config};
use ontogeny::run::{GenerationReport, Run};
use ontogeny::sim::StepSetting;
use ontogeny::study::compare::{
    self, Arm, CompareError, Manifest, ReplicateState, read_replicate, replicate_config,
    replicate_dir,
};

use super::evolve::{EncodingArg, bad, encoding_names, encoding_parser, run_error, set_threads};
use super::physics::{RunTaskArgs, setting_parser};

/// The flags that go with `--resume`; it refuses every other ([`super::conflicts_with_all_but`]).
pub const WITH_RESUME: &[&str] = &["threads", "no_cache", "json"];

/// The flags that go with `--merge`; it refuses every other.
pub const WITH_MERGE: &[&str] = &["json"];

/// Compare encodings, or conditions (`--condition`), on equal terms: replicated runs of
/// each with the same budget, and a report of statistics (Mann–Whitney U, Holm, A12) over
/// their champions that states its power.
#[derive(Args)]
pub struct CompareArgs {
    /// The encodings to compare, comma-separated (e.g. lsystem,direct), under the shared
    /// settings of --config and the flags.
    #[arg(long, value_parser = encoding_parser(), value_delimiter = ',', required_unless_present_any = ["resume", "merge", "condition", "power_for"])]
    encodings: Vec<EncodingArg>,
    /// A condition to compare, NAME=CONFIG.toml: a whole run config (encoding, [ga] without
    /// generations, [task], [limits]); repeat it for each condition. NAME (letters, digits, -
    /// and _) names its directory and its rows in the report. The flags --task, --fitness,
    /// --preset, --pop, --seconds and --setting apply over every condition's config. Instead
    /// of --encodings and --config.
    #[arg(long, value_name = "NAME=CONFIG.toml", value_parser = parse_condition, conflicts_with_all = ["encodings", "config"])]
    condition: Vec<(String, PathBuf)>,
    #[command(flatten)]
    run_task: RunTaskArgs,
    /// Runs per encoding (default 10).
    #[arg(long)]
    replicates: Option<usize>,
    /// The budget of every replicate, in walks: every individual evaluated counts one walk per
    /// habitat and trial, simulated or reused from the evaluation cache (an elite carried over
    /// counts none; with fresh trials it is walked again and counts). The generations are as
    /// many as fit in it.
    #[arg(long, required_unless_present_any = ["resume", "merge", "power_for"])]
    evaluations: Option<u64>,
    /// The comparison's seed; replicate k's seed derives from it (default: the config's,
    /// else 1).
    #[arg(long)]
    seed: Option<u64>,
    /// The comparison directory to create.
    #[arg(long, value_name = "DIR", required_unless_present_any = ["resume", "merge", "power_for"])]
    out: Option<PathBuf>,
    /// The primary pair, A,B (two of the encodings or conditions): tested alone at α = 0.05,
    /// the other pairs secondary, Holm-corrected among themselves. Kept in the comparison's
    /// compare.toml for --resume and --merge.
    #[arg(long, value_name = "A,B", value_delimiter = ',', conflicts_with_all = ["resume", "merge"])]
    primary: Vec<String>,
    /// Print the replicates per side that a two-sided Mann–Whitney test needs to detect this
    /// A12 (e.g. 0.71, a large effect) with power 0.8, for one pair at α = 0.05 and for 3 and
    /// 6 pairs under Holm, and run nothing.
    #[arg(long, value_name = "A12", conflicts_with_all = ["resume", "merge", "plan", "condition", "encodings", "json"])]
    power_for: Option<f64>,
    /// The genetic algorithm's schedule (default: the config's, else chaumont).
    #[arg(long, value_parser = super::evolve::preset_parser())]
    preset: Option<ontogeny::evolve::ga::Preset>,
    /// Individuals per generation (default: the preset's, 300).
    #[arg(long)]
    pop: Option<usize>,
    /// Seconds of the task's measurement (walker: walking, default 20), in (0, 3600].
    #[arg(long)]
    seconds: Option<f64>,
    /// The named step setting (default: the config's `[task.sim]`, else default); it replaces
    /// the config's five stepping values.
    #[arg(long, value_name = "NAME", value_parser = setting_parser())]
    setting: Option<StepSetting>,
    /// A TOML file of the settings the encodings share ([ga] without generations, [task],
    /// seed).
    #[arg(long, value_name = "FILE.toml")]
    config: Option<PathBuf>,
    /// Worker threads (default: every core). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Create the comparison directory and print one `ontogeny evolve` command per
    /// replicate instead of running them (then `compare --merge DIR`).
    #[arg(long, conflicts_with_all = ["resume", "merge"])]
    plan: bool,
    /// Simulate every individual of the replicates this command starts, even one identical
    /// to a creature evaluated earlier in its run (their `cache = false`); results are the
    /// same either way.
    #[arg(long, conflicts_with = "merge")]
    no_cache: bool,
    /// Run the replicates of the comparison in DIR that are missing or unfinished, then
    /// write the report.
    #[arg(long, value_name = "DIR")]
    resume: Option<PathBuf>,
    /// Write the report of the comparison in DIR from its finished replicates (runs nothing).
    #[arg(long, value_name = "DIR")]
    merge: Option<PathBuf>,
    /// Print the report's summary as one JSON object (each encoding's figures, the pairwise
    /// tests, the files written) instead of text.
    #[arg(long, conflicts_with = "plan")]
    json: bool,
}

fn compare_error(e: CompareError) -> anyhow::Error {
    match e {
        CompareError::Input(m) => bad(m),
        CompareError::Io { path, source } => {
            anyhow::Error::new(source).context(path.display().to_string())
        }
        CompareError::Output(e) => anyhow::Error::new(e),
        CompareError::Other(m) => anyhow::anyhow!(m),
    }
}

/// Parses `--condition NAME=CONFIG.toml` (the name checked; the file is read later).
fn parse_condition(text: &str) -> Result<(String, PathBuf), String> {
    let Some((name, path)) = text.split_once('=') else {
        return Err(format!(
            "expected NAME=CONFIG.toml (e.g. pop30=examples/compare-condition-pop30.toml), not {text}"
        ));
    };
    compare::check_condition_name(name)?;
    if path.is_empty() {
        return Err(format!(
            "the condition {name} names no config file after the ="
        ));
    }
    Ok((name.to_string(), PathBuf::from(path)))
}

/// Runs `ontogeny compare`.
pub fn run(args: &CompareArgs) -> anyhow::Result<()> {
    set_threads(args.threads)?;
    let Some(_cluster) = ontogeny::evolve::evaluator::join_cluster()? else {
        return Ok(()); // a worker rank of an MPI job: it evaluated what rank 0 sent
    };
    if let Some(a12) = args.power_for {
        return power_for(a12);
    }
    if let Some(root) = &args.merge {
        let _lock = compare::lock(root).map_err(compare_error)?;
        let (manifest, arms) = compare::open(root).map_err(compare_error)?;
        return report(root, &manifest, &arms, true, args.json);
    }
    if let Some(root) = &args.resume {
        let _lock = compare::lock(root).map_err(compare_error)?;
        let (manifest, arms) = compare::open(root).map_err(compare_error)?;
        run_all(root, &manifest, &arms, !args.no_cache)?;
        return report(root, &manifest, &arms, false, args.json);
    }
    let root = args
        .out
        .as_ref()
        .expect("clap requires --out without --resume or --merge");
    let (manifest, arms) = if args.condition.is_empty() {
        plan(args)?
    } else {
        plan_conditions(args)?
    };
    let mut manifest = manifest;
    manifest.primary = args.primary.clone();
    manifest
        .check()
        .map_err(|e| bad(format!("--primary: {}", e.trim_start_matches("primary "))))?;
    let _lock = compare::create(root, &manifest, &arms).map_err(compare_error)?;
    // Read back what was written, so that a direct run and `--plan` commands start from the
    // same settings.
    let (manifest, arms) = compare::open(root).map_err(compare_error)?;
    if args.plan {
        let mut files = vec![root.join("compare.toml")];
        if manifest.conditions.is_empty() {
            files.push(root.join("evolve.toml"));
        } else {
            files.extend(
                manifest
                    .conditions
                    .iter()
                    .map(|c| compare::condition_file(root, c)),
            );
        }
        tell!("{}", ontogeny::output::wrote(&files));
        for command in text::plan_commands(root, &manifest, args.no_cache) {
            say!("{command}");
        }
        tell!(
            "{} commands, one per replicate; when they are done: ontogeny compare --merge {}",
            manifest.replicates * manifest.names().len(),
            text::shell_word(root)
        );
        return Ok(());
    }
    run_all(root, &manifest, &arms, !args.no_cache)?;
    report(root, &manifest, &arms, false, args.json)
}

/// `compare --power-for A12`: the replicates a side needed to detect `a12` with power 0.8,
/// for one pair and for 3 and 6 pairs.
fn power_for(a12: f64) -> anyhow::Result<()> {
    use ontogeny::study::stats;
    if !(a12 > 0.0 && a12 < 1.0) || a12 == 0.5 {
        return Err(bad(format!(
            "--power-for takes an A12 between 0 and 1 other than 0.5 (no effect), not {a12}"
        )));
    }
    say!(
        "replicates per side for power {} at A12 {a12} (or {:.2}), two-sided Mann-Whitney:",
        stats::POWER,
        1.0 - a12
    );
    for pairs in [1, 3, 6] {
        let level = stats::ALPHA / pairs as f64;
        let n = stats::replicates_for(a12, pairs)
            .map_or_else(|| "more than 10000".to_string(), |n| n.to_string());
        let what = if pairs == 1 {
            "1 pair (a primary pair)".to_string()
        } else {
            format!("{pairs} pairs (Holm)")
        };
        say!("  {what:<24} level {level:.4}: {n}");
    }
    Ok(())
}

/// The flags that set every replicate's genetic algorithm and task.
fn run_flags(args: &CompareArgs) -> RunFlags {
    RunFlags {
        preset: args.preset,
        population: args.pop,
        generations: None,
        walks: None,
        task: args.run_task.task,
        fitness: args.run_task.fitness.clone(),
        seconds: args.seconds,
        setting: args.setting,
        target: None,
        algorithm: None,
        in_flight: None,
    }
}

/// The comparison of conditions the flags describe, checked; says so when the conditions'
/// budgets differ a little (more is refused).
fn plan_conditions(args: &CompareArgs) -> anyhow::Result<(Manifest, Vec<Arm>)> {
    let mut conditions = Vec::with_capacity(args.condition.len());
    for (name, path) in &args.condition {
        let source =
            super::evolve::read_source(Some(path))?.expect("a path was given, so a source is read");
        conditions.push(settings::ConditionSource {
            name: name.clone(),
            source,
        });
    }
    let budget = args.evaluations.expect("clap requires --evaluations");
    let (manifest, arms, note) = settings::plan_conditions(
        &conditions,
        &encoding_names(),
        args.replicates,
        budget,
        args.seed,
        &run_flags(args),
    )?;
    if let Some(note) = note {
        tell!("note: {note}");
    }
    Ok((manifest, arms))
}

/// The comparison of encodings the flags describe, checked.
fn plan(args: &CompareArgs) -> anyhow::Result<(Manifest, Vec<Arm>)> {
    let source = super::evolve::read_source(args.config.as_deref())?;
    let file: ConfigFile<toml::Value> = match &source {
        Some(s) => read_config(s)?,
        None => ConfigFile::default(),
    };
    let encodings: Vec<&str> = args.encodings.iter().map(|e| e.name()).collect();
    let flags = run_flags(args);
    let budget = args.evaluations.expect("clap requires --evaluations");
    let (manifest, shared) = settings::plan_comparison(
        &encodings,
        &encoding_names(),
        args.replicates,
        budget,
        args.seed,
        &file,
        source.as_deref(),
        &flags,
    )?;
    let arms = compare::encoding_arms(&manifest, &shared);
    Ok((manifest, arms))
}

/// Runs every replicate that is missing or unfinished: replicate 1 of every encoding or
/// condition, then replicate 2, ..., one at a time, each on all worker threads.
/// A replicate started here caches evaluations when `cache` is on.
fn run_all(root: &Path, manifest: &Manifest, arms: &[Arm], cache: bool) -> anyhow::Result<()> {
    let survey = compare::survey(root, manifest, arms).map_err(compare_error)?;
    if survey.todo.is_empty() {
        tell!("{}: every replicate is complete", root.display());
        return Ok(());
    }
    let mut progress = ComparisonProgress {
        total: survey.total,
        done: survey.done,
        at_start: survey.done,
        started: Instant::now(),
    };
    for (i, k) in survey.todo {
        let arm = &arms[i];
        with_genome!(
            arm.encoding.as_str(),
            G => run_replicate::<G>(root, manifest, arm, k, cache, &mut progress),
            |other| Err(bad(format!("unknown encoding '{other}'")))
        )?;
    }
    Ok(())
}

fn run_replicate<G: Genome>(
    root: &Path,
    manifest: &Manifest,
    arm: &Arm,
    k: usize,
    cache: bool,
    progress: &mut ComparisonProgress,
) -> anyhow::Result<()> {
    let dir = replicate_dir(root, &arm.name, k);
    let mut run = match read_replicate::<G>(root, manifest, arm, k).map_err(compare_error)? {
        ReplicateState::Done(_) => return Ok(()),
        ReplicateState::Partial(_) => Run::<G>::resume(&dir).map_err(run_error)?,
        ReplicateState::Missing => {
            // A start killed before its store held the run left nothing computed (at most
            // a config.toml written by an older ontogeny, or an empty store): start again.
            let config = dir.join("config.toml");
            if config.exists() {
                std::fs::remove_file(&config)
                    .with_context(|| format!("cannot remove {}", config.display()))?;
            }
            let config = replicate_config::<G>(manifest, arm, k, cache).map_err(compare_error)?;
            Run::<G>::start(&dir, config, None).map_err(run_error)?
        }
    };
    let label = format!(
        "[{} {k}/{}] {}:",
        arm.name,
        manifest.replicates,
        arm.settings.task.fitness_label()
    );
    let generations = arm.settings.ga.generations;
    let walks = compare::walks_per_individual(&arm.settings.task);
    let mut observer = |r: &GenerationReport| {
        tell!("{}", progress.line(&label, r, generations, walks));
    };
    run.run(&mut observer).map_err(run_error)
}

/// Gathers the finished replicates and writes the report. `merging`: say what is missing
/// rather than treat it as an error.
fn report(
    root: &Path,
    manifest: &Manifest,
    arms: &[Arm],
    merging: bool,
    json: bool,
) -> anyhow::Result<()> {
    let (finished, unfinished) = compare::gather(root, manifest, arms).map_err(compare_error)?;
    if finished.is_empty() {
        return Err(bad(format!(
            "{}: no replicate is finished yet (run the `compare --plan` commands, or `compare --resume {0}`)",
            root.display()
        )));
    }
    if !merging && !unfinished.is_empty() {
        anyhow::bail!("replicates still unfinished: {}", unfinished.join(", "));
    }
    let r = compare::write_report(root, manifest, arms, &finished, &unfinished)
        .map_err(compare_error)?;
    if json {
        let files = ["report.md", "summary.csv", "fitness.svg", "parts.svg"].map(|f| root.join(f));
        tell!("{}", ontogeny::output::wrote(&files));
        let object =
            ontogeny::front::json::comparison_json(root, arms, &r, finished.len(), &unfinished);
        say!("{}", serde_json::to_string_pretty(&object)?);
        return Ok(());
    }
    super::print(text::comparison_summary(
        root,
        arms,
        &r,
        finished.len(),
        &unfinished,
    ))
}
