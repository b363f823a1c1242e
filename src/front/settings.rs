//! A run's and a comparison's settings from the command line: the flags of `ontogeny evolve`
//! and `ontogeny compare` over a config file over the preset, resolved and checked. Errors are
//! messages for people, naming the flag or the file at fault.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::encoding::{Genome, LSystemGenome};
use crate::lang::{Diagnostic, DiagnosticKind, Source, read_grammar};
use crate::sim::StepSetting;
use crate::task::{CatapultOptions, TaskKind, TaskSpec, TaskTables, keyword_refusal};

use crate::evolve::ga::{Algorithm, GaSettings, Preset};
use crate::run::config::{ConfigFile, RunConfig, check_settings};
use crate::run::config_errors::setting_diagnostic;
use crate::study::compare::{self, Arm, Manifest, Shared, generations_for};

/// The flags that set a run's genetic algorithm and task, shared by `evolve` and `compare`
/// (each `None` when not given).
#[derive(Clone, Debug, Default)]
pub struct RunFlags {
    /// `--preset`.
    pub preset: Option<Preset>,
    /// `--pop`.
    pub population: Option<usize>,
    /// `--gens`.
    pub generations: Option<usize>,
    /// `--walks`: a budget of walks simulated, which sets the generations to as many as fit
    /// (an individual walks once in each habitat-trial).
    pub walks: Option<u64>,
    /// `--task`.
    pub task: Option<TaskKind>,
    /// `--fitness`: one of the task's formulas by name, or an expression of its terms.
    pub fitness: Option<String>,
    /// `--seconds`.
    pub seconds: Option<f64>,
    /// `--setting`.
    pub setting: Option<StepSetting>,
    /// `--target` (the aim task's, metres from the projectile's start).
    pub target: Option<[f64; 3]>,
    /// `--algorithm`.
    pub algorithm: Option<Algorithm>,
    /// `--in-flight`.
    pub in_flight: Option<usize>,
}

/// A message about the command line's or a config file's settings as a diagnostic (exit code
/// 2 on the command line).
fn plain(message: String) -> Diagnostic {
    Diagnostic::without_location(DiagnosticKind::Semantic, message)
}

/// The task of a config file's `[task]` tables: the one `--task` or else `task =` names
/// (default: the walker), with its table (its defaults when the file has none), and
/// `--fitness`, `--seconds`, `--setting` and `--target` over it (a named setting replaces the file's five stepping
/// values, and nothing else). A flag of a setting the task does not read
/// ([`crate::task::Task::KEYWORDS`]: `--fitness` but for the walker, `--target` but for aim)
/// is refused.
pub fn resolve_task(file: Option<&TaskTables>, flags: &RunFlags) -> Result<TaskSpec, String> {
    let tables = file.cloned().unwrap_or_default();
    let task = flags.task.unwrap_or(tables.kind());
    let mut spec = tables.spec(task);
    if let Some(setting) = flags.setting {
        spec.sim = setting.apply(&spec.sim);
    }
    if let Some(s) = flags.seconds {
        *spec.seconds_mut() = s;
    }
    let refuse =
        |keyword: &str| match keyword_refusal(keyword, &format!("--{keyword}"), task.info()) {
            Some(refusal) => Err(refusal),
            None => Ok(()),
        };
    if let Some(fitness) = &flags.fitness {
        refuse("fitness")?;
        spec.set_fitness(fitness);
    }
    if let Some([x, y, z]) = flags.target {
        refuse("target")?;
        if let Some(catapult) = spec.task.get_mut::<CatapultOptions>() {
            catapult.target = Some(nalgebra::Vector3::new(x, y, z));
        }
    }
    Ok(spec)
}

/// The genetic algorithm and the task of a config file (`source` its text, when there is one)
/// with the flags over them, checked together ([`check_settings`]). A value out of range is
/// named after its flag when a flag gave it (`--pop must be 2 to 100000, not 1`), else after
/// its key, at its place in the file.
pub fn resolve_ga_and_task<L>(
    file: &ConfigFile<L>,
    source: Option<&Source>,
    flags: &RunFlags,
    encodings: &[&str],
) -> Result<(GaSettings, TaskSpec), Diagnostic> {
    let mut overrides = file.ga.clone();
    if let Some(p) = flags.preset {
        overrides.preset = Some(p);
    }
    if flags.population.is_some() {
        overrides.population = flags.population;
    }
    if flags.generations.is_some() {
        overrides.generations = flags.generations;
    }
    if flags.algorithm.is_some() {
        overrides.algorithm = flags.algorithm;
    }
    if flags.in_flight.is_some() {
        overrides.in_flight = flags.in_flight;
    }
    let mut ga = overrides.resolve();
    if let Some(s) = flags.seconds {
        crate::task::check_duration("seconds", s).map_err(|e| plain(e.for_flag("--seconds")))?;
    }
    let task = resolve_task(file.task.as_ref(), flags).map_err(plain)?;
    if let Some(walks) = flags.walks {
        if flags.generations.is_some() {
            return Err(plain(
                "--walks sets the generations: give it or --gens, not both".into(),
            ));
        }
        let each = compare::walks_per_individual(&task);
        ga.generations = generations_for(&ga, task.trials.fresh, walks / each)
            .map_err(|e| plain(format!("--walks {walks} ({each} per individual): {e}")))?;
    }
    let other_tables = |tables: &TaskTables| tables.check_other_tables(task.task.table());
    check_settings(&ga, &task, encodings)
        .and_then(|()| file.task.as_ref().map_or(Ok(()), other_tables))
        .map_err(|e| {
            let run_table = format!("task.{}", task.task.table());
            let flag = match (e.table.as_str(), e.key) {
                ("ga", "population") if flags.population.is_some() => Some("--pop"),
                ("ga", "generations") if flags.generations.is_some() => Some("--gens"),
                ("ga", "in_flight") if flags.in_flight.is_some() => Some("--in-flight"),
                ("ga", "algorithm") if flags.algorithm.is_some() => Some("--algorithm"),
                (table, "fitness") if flags.fitness.is_some() && table == run_table => {
                    Some("--fitness")
                }
                _ => None,
            };
            match (flag, source) {
                (Some(flag), _) => plain(e.for_flag(flag)),
                (None, Some(source)) => setting_diagnostic(source, &e),
                (None, None) => plain(e.to_string()),
            }
        })?;
    Ok((ga, task))
}

/// The grammar that seeds a run's first generation: `--init` (relative to the working
/// directory), else the config file's `init` (relative to the file).
pub fn init_path(
    flag: Option<&Path>,
    file: Option<&Path>,
    source: Option<&Source>,
) -> Option<PathBuf> {
    match (flag, file, source) {
        (Some(p), _, _) => Some(p.to_path_buf()),
        (None, Some(p), Some(s)) => Some(
            Path::new(s.name())
                .parent()
                .unwrap_or(Path::new("."))
                .join(p),
        ),
        _ => None,
    }
}

/// The seed a grammar (`text`, read from `path`) gives the encoding `G` under `limits`
/// ([`Genome::seed_from_lsys`]: the limits widened to fit it, notes on what was rewritten),
/// or its refusal, which lists what cannot be represented.
pub fn check_init<G: Genome>(
    text: &str,
    limits: &G::Limits,
    path: &Path,
) -> Result<crate::encoding::Seed<G>, String> {
    G::seed_from_lsys(&path.display().to_string(), text, limits).map_err(|e| {
        format!(
            "{}: cannot seed the {} encoding: {}",
            path.display(),
            G::NAME,
            e.0
        )
    })
}

/// The settings of a new run: a config file with the flags over it (`seed`, and whether to
/// re-walk the best and to cache, as `--no-verify-best` and `--no-cache` leave them).
pub fn run_config<G: Genome>(
    file: ConfigFile<G::Limits>,
    source: Option<&Source>,
    flags: &RunFlags,
    seed: Option<u64>,
    verify_best: bool,
    cache: bool,
) -> Result<RunConfig<G::Limits>, Diagnostic> {
    let (ga, task) = resolve_ga_and_task(&file, source, flags, &[G::NAME])?;
    Ok(RunConfig {
        encoding: G::NAME.to_string(),
        seed: seed.or(file.seed).unwrap_or(1),
        init: None,
        verify_best: verify_best && file.verify_best.unwrap_or(true),
        cache: cache && file.cache.unwrap_or(true),
        ga,
        task,
        limits: file.limits.unwrap_or_default(),
    })
}

/// The encoding of a new run: `flag` (`--encoding`), else the config file's (`source`), else
/// the L-system genome's.
pub fn new_run_encoding(flag: Option<&str>, source: Option<&Source>) -> Result<String, Diagnostic> {
    Ok(match (flag, source) {
        (Some(e), _) => e.to_string(),
        (None, Some(s)) => {
            crate::run::config::encoding_of(s)?.unwrap_or_else(|| LSystemGenome::NAME.to_string())
        }
        (None, None) => LSystemGenome::NAME.to_string(),
    })
}

/// A new run: its settings, the grammar that seeds its first generation (if any), and the
/// notes on that seed (what of the grammar was rewritten for the genome, and which limits were
/// widened to fit it; the run's config records the widened limits).
#[derive(Debug)]
pub struct ResolvedRun<L> {
    /// The run's settings.
    pub config: RunConfig<L>,
    /// The grammar that seeds its first generation.
    pub init: Option<Arc<Source>>,
    /// The notes on the seed, one line each.
    pub notes: Vec<String>,
}

/// A new run's settings ([`run_config`]) from its config file (`source`, if any) and the
/// flags over it, with the grammar that seeds its first generation (`init`, `--init`, else
/// the file's `init`), read and checked ([`check_init`]), and the notes on it.
pub fn new_run<G: Genome>(
    source: Option<&Source>,
    flags: &RunFlags,
    init: Option<&Path>,
    seed: Option<u64>,
    verify_best: bool,
    cache: bool,
) -> Result<ResolvedRun<G::Limits>, Diagnostic> {
    let file: ConfigFile<G::Limits> = match source {
        Some(s) => crate::run::config::read_config(s)?,
        None => ConfigFile::default(),
    };
    let init_path = init_path(init, file.init.as_deref(), source);
    let mut config = run_config::<G>(file, source, flags, seed, verify_best, cache)?;
    crate::run::config::check_limits(&config.limits, source)?;
    let init = init_path.as_deref().map(read_grammar).transpose()?;
    let mut notes = Vec::new();
    if let (Some(init), Some(path)) = (&init, &init_path) {
        let seed = check_init::<G>(init.text(), &config.limits, path).map_err(plain)?;
        config.limits = seed.limits;
        notes = seed
            .notes
            .into_iter()
            .map(|n| format!("note: {}: {n}", path.display()))
            .collect();
    }
    Ok(ResolvedRun {
        config,
        init,
        notes,
    })
}

/// The comparison `compare`'s flags describe over its config file (`source` its text), checked:
/// `encodings` each named once, 1 to [`compare::MAX_REPLICATES`] replicates (default 10), a
/// config without the settings a comparison sets itself, and generations as many as fit in
/// the `budget` of evaluations.
#[allow(clippy::too_many_arguments)]
pub fn plan_comparison(
    encodings: &[&str],
    all_encodings: &str,
    replicates: Option<usize>,
    budget: u64,
    seed: Option<u64>,
    file: &ConfigFile<toml::Value>,
    source: Option<&Source>,
    flags: &RunFlags,
) -> Result<(Manifest, Shared), Diagnostic> {
    let mut names: Vec<String> = Vec::new();
    for e in encodings {
        if names.iter().any(|x| x == e) {
            return Err(plain(format!("--encodings names {e} twice")));
        }
        names.push(e.to_string());
    }
    if names.is_empty() {
        return Err(plain(format!(
            "--encodings needs at least one of {all_encodings}"
        )));
    }
    let replicates = checked_replicates(replicates)?;
    let refuse = |path: &[&str], what: &str, why: &str| Err(refusal(source, path, what, why));
    if file.encoding.is_some() {
        return refuse(&["encoding"], "encoding", "--encodings names them");
    }
    if file.limits.is_some() {
        return refuse(
            &["limits"],
            "[limits]",
            "every encoding runs with its default limits",
        );
    }
    refuse_replicated_keys(file.init.is_some(), file.ga.generations.is_some(), source)?;
    let one_generation = RunFlags {
        generations: Some(1),
        ..flags.clone()
    };
    let encodings: Vec<&str> = names.iter().map(String::as_str).collect();
    let (mut ga, task) = resolve_ga_and_task(file, source, &one_generation, &encodings)?;
    // The budget counts walks: an individual of K trials in H habitats walks K·H times.
    let walks = compare::walks_per_individual(&task);
    ga.generations = generations_for(&ga, task.trials.fresh, budget / walks)
        .map_err(|e| plain(format!("--evaluations: {e}")))?;
    Ok((
        Manifest {
            encodings: names,
            conditions: Vec::new(),
            replicates,
            evaluations: budget,
            seed: seed.or(file.seed).unwrap_or(1),
            primary: Vec::new(),
        },
        Shared { ga, task },
    ))
}

/// `--replicates`, 1 to [`compare::MAX_REPLICATES`] (default 10).
fn checked_replicates(replicates: Option<usize>) -> Result<usize, Diagnostic> {
    let replicates = replicates.unwrap_or(10);
    if !(1..=compare::MAX_REPLICATES).contains(&replicates) {
        return Err(plain(format!(
            "--replicates must be 1 to {}, not {replicates}",
            compare::MAX_REPLICATES
        )));
    }
    Ok(replicates)
}

/// The refusal of a key (`path`, said as `what`) that a comparison's config file (`source`)
/// sets but the comparison sets itself (`why`): at its place in the file.
/// Refuses, in a comparison's config, the keys every replicate sets for itself: `init` (every
/// replicate starts from random genomes) and `[ga] generations` (`--evaluations` sets them).
fn refuse_replicated_keys(
    init: bool,
    generations: bool,
    source: Option<&Source>,
) -> Result<(), Diagnostic> {
    if init {
        return Err(refusal(
            source,
            &["init"],
            "init",
            "every replicate starts from random genomes",
        ));
    }
    if generations {
        return Err(refusal(
            source,
            &["ga", "generations"],
            "[ga] generations",
            "--evaluations sets the generations",
        ));
    }
    Ok(())
}

fn refusal(source: Option<&Source>, path: &[&str], what: &str, why: &str) -> Diagnostic {
    let message = format!("{what} has no place in a comparison's config: {why}");
    let at = source.and_then(|s| Some((s, crate::run::config_errors::key_span(s, path)?)));
    match (at, source) {
        (Some((s, span)), _) => Diagnostic::at(DiagnosticKind::Semantic, s, span, message),
        (None, Some(s)) => plain(format!("{}: {message}", s.name())),
        (None, None) => plain(message),
    }
}

/// One `--condition NAME=CONFIG.toml`: the condition's name and its config.
#[derive(Clone, Debug)]
pub struct ConditionSource {
    /// The condition's name.
    pub name: String,
    /// Its config file, read.
    pub source: Arc<Source>,
}

/// The comparison of `conditions` that `compare --condition`'s flags describe, checked: each
/// condition named once (letters, digits, `-` and `_`; names that differ only in case are one
/// name), 1 to [`compare::MAX_REPLICATES`] replicates (default 10), each config a whole run
/// config (`encoding`, default `all_encodings`' first, `[ga]`, `[task]`, `[limits]`) without
/// the settings a comparison sets itself (`seed`, `init`, `[ga] generations`), the flags over
/// every condition's config, and each condition's generations as many as fit in the `budget`
/// of walks ([`compare::walks_per_individual`]). Budgets that end too far apart are refused
/// ([`compare::check_budgets`]); budgets a little apart return a note that names them.
pub fn plan_conditions(
    conditions: &[ConditionSource],
    all_encodings: &str,
    replicates: Option<usize>,
    budget: u64,
    seed: Option<u64>,
    flags: &RunFlags,
) -> Result<(Manifest, Vec<Arm>, Option<String>), Diagnostic> {
    let mut names: Vec<String> = Vec::new();
    for c in conditions {
        compare::check_condition_name(&c.name).map_err(|e| plain(format!("--condition: {e}")))?;
        if let Some(first) = names.iter().find(|x| x.eq_ignore_ascii_case(&c.name)) {
            return Err(plain(format!(
                "--condition: {}",
                compare::duplicate_condition(first, &c.name)
            )));
        }
        names.push(c.name.clone());
    }
    if names.is_empty() {
        return Err(plain(
            "--condition needs at least one NAME=CONFIG.toml".into(),
        ));
    }
    let replicates = checked_replicates(replicates)?;
    let mut arms = Vec::with_capacity(conditions.len());
    for c in conditions {
        let source = c.source.as_ref();
        let encoding = new_run_encoding(None, Some(source))?;
        let arm = crate::with_genome!(
            encoding.as_str(),
            G => condition_arm::<G>(&c.name, source, flags, budget),
            |other| Err(plain(format!(
                "{}: unknown encoding '{other}' (one of {all_encodings})",
                source.name()
            )))
        )?;
        arms.push(arm);
    }
    let note = compare::check_budgets(&arms).map_err(|e| plain(format!("--condition: {e}")))?;
    Ok((
        Manifest {
            encodings: Vec::new(),
            conditions: names,
            replicates,
            evaluations: budget,
            seed: seed.unwrap_or(1),
            primary: Vec::new(),
        },
        arms,
        note,
    ))
}

/// The condition `name` of config `source`, whose encoding is `G`, with `flags` over it and
/// its generations as many as fit in `budget` walks.
fn condition_arm<G: Genome>(
    name: &str,
    source: &Source,
    flags: &RunFlags,
    budget: u64,
) -> Result<Arm, Diagnostic> {
    let file: ConfigFile<G::Limits> = crate::run::config::read_config(source)?;
    let refuse = |path: &[&str], what: &str, why: &str| Err(refusal(Some(source), path, what, why));
    if file.seed.is_some() {
        return refuse(&["seed"], "seed", "--seed sets every replicate's seed");
    }
    refuse_replicated_keys(
        file.init.is_some(),
        file.ga.generations.is_some(),
        Some(source),
    )?;
    let one_generation = RunFlags {
        generations: Some(1),
        ..flags.clone()
    };
    let (mut ga, task) = resolve_ga_and_task(&file, Some(source), &one_generation, &[G::NAME])?;
    let limits = file.limits.unwrap_or_default();
    crate::run::config::check_limits(&limits, Some(source))?;
    let walks = compare::walks_per_individual(&task);
    ga.generations = generations_for(&ga, task.trials.fresh, budget / walks).map_err(|e| {
        plain(format!(
            "condition {name} ({}): --evaluations: {e}",
            source.name()
        ))
    })?;
    let limits = match toml::Value::try_from(&limits) {
        Ok(toml::Value::Table(t)) => t,
        Ok(_) => toml::Table::new(),
        Err(e) => return Err(plain(format!("{}: [limits]: {e}", source.name()))),
    };
    Ok(Arm {
        name: name.to_string(),
        encoding: G::NAME.to_string(),
        settings: Shared { ga, task },
        limits: Some(limits),
    })
}
