//! A run's configuration: the encoding, the seed, the genetic algorithm's settings, the task
//! and the encoding's limits, read from a `config.toml` (unknown keys and out-of-range values
//! are errors that name the file, line and key) and written back in full at the start of a
//! run.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::{Deserialize, Serialize, de::DeserializeOwned};

use super::config_errors::{key_span, setting_diagnostic, toml_diagnostic};
use crate::encoding::{CheckedLimits, ENCODINGS, encoding_named};
use crate::evolve::ga::{Algorithm, GaSettings, Preset, WwdCrossover};
use crate::lang::suggest::did_you_mean;
use crate::lang::{Diagnostic, DiagnosticKind, FileKind, Source, read_as};
use crate::sim::SettingError;
use crate::task::{TaskSpec, TaskTables};

/// Every setting of a run, resolved: what `config.toml` holds in a run directory.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunConfig<L> {
    /// The encoding's name (`lsystem`, `lsystem-continuous`, ...).
    pub encoding: String,
    /// The run's seed: any 64-bit unsigned number, written as a TOML integer up to
    /// 2^63 − 1 and as a string of digits above (TOML's integers are signed), see [`seed`].
    #[serde(with = "seed")]
    pub seed: u64,
    /// A grammar whose mutants seed the first generation, relative to the run directory.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub init: Option<PathBuf>,
    /// Whether each generation's best individual is walked again at the fine reference
    /// setting ([`crate::sim::SimOptions::fine_reference`]) and the result stored with the
    /// generation. Absent from the `config.toml` of a run started before it existed: on.
    #[serde(default = "verify_best_default")]
    pub verify_best: bool,
    /// Whether an individual whose creature is identical, bit for bit, to one evaluated
    /// earlier in the run reuses that evaluation instead of simulating it again
    /// ([`crate::evolve::cache`]); results are the same either way. Absent from the `config.toml` of
    /// a run started before it existed: on.
    #[serde(default = "cache_default")]
    pub cache: bool,
    /// The genetic algorithm's settings.
    pub ga: GaSettings,
    /// The task.
    pub task: TaskSpec,
    /// The encoding's limits.
    pub limits: L,
}

/// A seed in TOML, whose integers are signed 64-bit: a seed up to 2^63 − 1 is written as an
/// integer, a larger one as a string of decimal digits (`seed = "18446744073709551615"`), so
/// every seed the command line accepts reads back. Either form is read, in a run's
/// `config.toml` and in a configuration file.
pub mod seed {
    use serde::{Deserializer, Serializer, de};

    /// Writes `seed` as an integer when TOML holds it, else as a string of digits.
    pub fn serialize<S: Serializer>(seed: &u64, serializer: S) -> Result<S::Ok, S::Error> {
        match i64::try_from(*seed) {
            Ok(small) => serializer.serialize_i64(small),
            Err(_) => serializer.serialize_str(&seed.to_string()),
        }
    }

    /// Reads a seed written as a whole number from 0 to 2^64 − 1, or as a string of its
    /// decimal digits.
    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<u64, D::Error> {
        deserializer.deserialize_any(SeedVisitor)
    }

    /// [`deserialize`] for an optional key.
    pub fn deserialize_option<'de, D: Deserializer<'de>>(
        deserializer: D,
    ) -> Result<Option<u64>, D::Error> {
        deserialize(deserializer).map(Some)
    }

    /// The message of a seed that is neither.
    const EXPECTED: &str = "a whole number from 0 to 18446744073709551615 (in quotes above 9223372036854775807, e.g. seed = \"9223372036854775808\")";

    struct SeedVisitor;

    impl de::Visitor<'_> for SeedVisitor {
        type Value = u64;

        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str(EXPECTED)
        }

        fn visit_i64<E: de::Error>(self, v: i64) -> Result<u64, E> {
            u64::try_from(v).map_err(|_| E::custom(format!("seed must be {EXPECTED}, not {v}")))
        }

        fn visit_u64<E: de::Error>(self, v: u64) -> Result<u64, E> {
            Ok(v)
        }

        fn visit_str<E: de::Error>(self, v: &str) -> Result<u64, E> {
            match v.parse::<u64>() {
                Ok(seed) if v.bytes().all(|b| b.is_ascii_digit()) => Ok(seed),
                _ => Err(E::custom(format!("seed must be {EXPECTED}, not \"{v}\""))),
            }
        }
    }
}

/// The default of [`RunConfig::verify_best`]: on.
pub fn verify_best_default() -> bool {
    true
}

/// The default of [`RunConfig::cache`]: on.
pub fn cache_default() -> bool {
    true
}

/// The `[ga]` table as a person writes it: a preset, and any of its values overridden.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GaOverrides {
    /// The schedule (default `chaumont`).
    pub preset: Option<Preset>,
    /// See [`GaSettings`].
    pub population: Option<usize>,
    /// See [`GaSettings`].
    pub generations: Option<usize>,
    /// See [`GaSettings`].
    pub elite: Option<f64>,
    /// See [`GaSettings`].
    pub breeders: Option<f64>,
    /// See [`GaSettings`].
    pub asexual: Option<f64>,
    /// See [`GaSettings`].
    pub crossover: Option<f64>,
    /// See [`GaSettings`].
    pub mutation_rate: Option<f64>,
    /// See [`GaSettings`].
    pub mutation_chance_after_mating: Option<f64>,
    /// See [`GaSettings`].
    pub mutation_rate_after_mating: Option<f64>,
    /// See [`GaSettings`].
    pub environment_reads: Option<f64>,
    /// See [`GaSettings`].
    pub regenerate: Option<usize>,
    /// See [`GaSettings`].
    pub wwd_crossover: Option<WwdCrossover>,
    /// See [`GaSettings`].
    pub algorithm: Option<Algorithm>,
    /// See [`GaSettings`].
    pub in_flight: Option<usize>,
}

impl GaOverrides {
    /// The preset's settings with these values over them.
    pub fn resolve(&self) -> GaSettings {
        let mut s = GaSettings::preset(self.preset.unwrap_or(Preset::Chaumont));
        macro_rules! over {
            ($($f:ident),*) => {$(if let Some(v) = self.$f { s.$f = v; })*};
        }
        over!(
            population,
            generations,
            elite,
            breeders,
            asexual,
            crossover,
            mutation_rate,
            mutation_chance_after_mating,
            mutation_rate_after_mating,
            environment_reads,
            regenerate,
            wwd_crossover,
            algorithm
        );
        s.in_flight = self.in_flight;
        if s.algorithm == Algorithm::SteadyState {
            // Stored with the run, so that a later default cannot change it.
            s.in_flight = Some(s.in_flight());
        }
        s
    }
}

/// A configuration file as a person writes it: everything optional.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound(deserialize = "L: DeserializeOwned"))]
pub struct ConfigFile<L> {
    /// The encoding's name.
    pub encoding: Option<String>,
    /// The run's seed (an integer, or a string of digits for a seed of 2^63 or more).
    #[serde(default, deserialize_with = "seed::deserialize_option")]
    pub seed: Option<u64>,
    /// A grammar whose mutants seed the first generation (relative to the config file).
    pub init: Option<PathBuf>,
    /// See [`RunConfig::verify_best`] (default: on).
    pub verify_best: Option<bool>,
    /// See [`RunConfig::cache`] (default: on).
    pub cache: Option<bool>,
    /// The genetic algorithm.
    #[serde(default)]
    pub ga: GaOverrides,
    /// The task and its settings: any number of tasks' tables, until the task is known.
    pub task: Option<TaskTables>,
    /// The encoding's limits.
    pub limits: Option<L>,
}

/// No file: nothing set, everything from the command line and the preset.
impl<L> Default for ConfigFile<L> {
    fn default() -> Self {
        ConfigFile {
            encoding: None,
            seed: None,
            init: None,
            verify_best: None,
            cache: None,
            ga: GaOverrides::default(),
            task: None,
            limits: None,
        }
    }
}

/// Parses `text` as a TOML table. A top-level `seed` above 2^63 − 1 written as a bare integer
/// (as an ontogeny older than the string form of [`seed`] wrote it into a run's
/// `config.toml` and store) does not fit a [`toml::Value`]: such a text is read as if the
/// seed were in quotes. Any other error is the text's own, with its place in it.
pub fn parse_table(text: &str) -> Result<toml::Table, toml::de::Error> {
    toml::from_str(text).or_else(|error| {
        quoted_large_seed(text)
            .and_then(|quoted| toml::from_str(&quoted).ok())
            .ok_or(error)
    })
}

/// `text` with its top-level `seed = DIGITS` in quotes, when DIGITS is above 2^63 − 1.
fn quoted_large_seed(text: &str) -> Option<String> {
    let mut out = String::with_capacity(text.len() + 2);
    let mut done = false;
    let mut top_level = true;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim_start();
        top_level &= !trimmed.starts_with('[');
        if top_level
            && !done
            && let Some(rest) = trimmed.strip_prefix("seed")
            && let Some(value) = rest.trim_start().strip_prefix('=')
        {
            let digits = value.trim_start();
            let end = digits
                .find(|c: char| !c.is_ascii_digit())
                .unwrap_or(digits.len());
            if end > 0
                && digits[..end]
                    .parse::<u64>()
                    .is_ok_and(|s| s > i64::MAX as u64)
                && digits[end..]
                    .trim_start()
                    .chars()
                    .next()
                    .is_none_or(|c| c == '#')
            {
                let at = line.len() - digits.len();
                out.push_str(&line[..at]);
                out.push('"');
                out.push_str(&digits[..end]);
                out.push('"');
                out.push_str(&digits[end..]);
                done = true;
                continue;
            }
        }
        out.push_str(line);
    }
    done.then_some(out)
}

/// The `encoding` a configuration text names, if any (read before the rest, which depends on
/// it): one of the registry's ([`crate::encoding::ENCODINGS`]), else an error at the name,
/// with the names allowed and the closest of them.
pub fn encoding_of(source: &Source) -> Result<Option<String>, Diagnostic> {
    let table = parse_table(source.text()).map_err(|e| toml_diagnostic(source, &e))?;
    let names = ENCODINGS.iter().map(|e| e.name);
    let wrong = |message: String| match key_span(source, &["encoding"]) {
        Some(span) => Diagnostic::at(DiagnosticKind::Semantic, source, span, message),
        None => Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!("{}: {message}", source.name()),
        ),
    };
    let allowed = names.clone().collect::<Vec<_>>().join(", ");
    match table.get("encoding") {
        None => Ok(None),
        Some(toml::Value::String(s)) if encoding_named(s).is_some() => Ok(Some(s.clone())),
        Some(toml::Value::String(s)) => Err(wrong(format!(
            "encoding must be one of {allowed}, not \"{s}\"{}",
            did_you_mean(s, names)
        ))),
        Some(other) => Err(wrong(format!(
            "encoding must be one of {allowed}, in double quotes, not {other}"
        ))),
    }
}

/// Reads the configuration file at `path` (`-`: standard input), refusing, with what it is
/// and which command takes it, a file that is something else: a grammar (whose place is
/// `--init`), a MuJoCo model, a recording, ... ([`FileKind`]).
pub fn read_config_source(path: &Path) -> Result<Arc<Source>, Diagnostic> {
    let source = read_as(
        path,
        &[FileKind::Grammar, FileKind::Config],
        "a configuration",
    )?;
    // A text that is no TOML but is a grammar, or is named like one.
    let grammar = path.extension().is_some_and(|e| e == "lsys")
        || crate::lang::parse(&source).is_ok_and(|file| !file.rules.is_empty());
    if grammar && parse_table(source.text()).is_err() {
        return Err(FileKind::Grammar.refusal(path, "a configuration"));
    }
    Ok(source)
}

/// The task a configuration file at `path` gives (its `[task]` table; the walker's defaults
/// without one), checked as a run's is: for `ontogeny eval --config`. A key out of range is
/// named at its line and column.
pub fn read_task_config(path: &Path) -> Result<TaskSpec, Diagnostic> {
    let source = read_config_source(path)?;
    let config: ConfigFile<toml::Value> = read_config(&source)?;
    let tables = config.task.unwrap_or_default();
    let task = tables.spec(tables.kind());
    task.check()
        .and_then(|()| tables.check_other_tables(task.task.table()))
        .map_err(|e| setting_diagnostic(&source, &e))?;
    Ok(task)
}

/// Reads a configuration file whose limits are `L`.
pub fn read_config<L: DeserializeOwned>(source: &Source) -> Result<ConfigFile<L>, Diagnostic> {
    toml::from_str(source.text()).map_err(|e| toml_diagnostic(source, &e))
}

/// Reads a run directory's full `config.toml`. The file is written in full when a run starts,
/// so a key it lacks was added to the program later, and the run keeps what it ran with: its
/// encoding says what that was ([`crate::encoding::Genome::LIMITS_OF_OLDER_RUNS`]: a `graph`
/// run begun before `[limits] joint_kinds` existed drew all of Sims' joint kinds and resumes
/// with `joint_kinds = "sims"`). Its settings get the checks of [`check_settings`], and its
/// limits those of [`check_limits`], as a configuration file's do when a run starts: an
/// edited file may hold anything.
pub fn read_run_config<L: DeserializeOwned + CheckedLimits>(
    source: &Source,
) -> Result<RunConfig<L>, Diagnostic> {
    let config: RunConfig<L> = parse_run_config(source)?;
    check_settings(&config.ga, &config.task, &[config.encoding.as_str()])
        .map_err(|e| setting_diagnostic(source, &e))?;
    check_limits(&config.limits, Some(source))?;
    Ok(config)
}

/// Checks an encoding's limits against their ranges ([`CheckedLimits`]); the error names
/// the key in `[limits]`, at its line and column in `source` when the file sets it there.
pub fn check_limits<L: CheckedLimits>(
    limits: &L,
    source: Option<&Source>,
) -> Result<(), Diagnostic> {
    limits.check_ranges().map_err(|e| match source {
        Some(source) => setting_diagnostic(source, &e),
        None => Diagnostic::without_location(DiagnosticKind::Semantic, e.to_string()),
    })
}

/// [`read_run_config`] without the checks of the settings.
fn parse_run_config<L: DeserializeOwned>(source: &Source) -> Result<RunConfig<L>, Diagnostic> {
    let mut table = parse_table(source.text()).map_err(|e| toml_diagnostic(source, &e))?;
    let older_runs = table
        .get("encoding")
        .and_then(|e| e.as_str())
        .and_then(encoding_named)
        .map_or(&[][..], |e| e.limits_of_older_runs);
    let limits = table.get_mut("limits").and_then(|l| l.as_table_mut());
    match limits {
        Some(limits) if older_runs.iter().any(|(key, _)| !limits.contains_key(*key)) => {
            for (key, value) in older_runs {
                if !limits.contains_key(*key) {
                    limits.insert(key.to_string(), toml::Value::String(value.to_string()));
                }
            }
            toml::Value::Table(table)
                .try_into()
                .map_err(|e: toml::de::Error| {
                    Diagnostic::without_location(
                        DiagnosticKind::Semantic,
                        format!("{}: {}", source.name(), e.message()),
                    )
                })
        }
        _ => toml::from_str(source.text()).map_err(|e| toml_diagnostic(source, &e)),
    }
}

/// `text` (a run's `config.toml`) with `[ga] generations` set to `generations`, and nothing
/// else changed: comments, layout, the order of keys and the way the other values are
/// written stay as they are ([`toml_edit`]), and so do the comment and spacing around the
/// value itself. A bare seed above 2^63 − 1 (see [`parse_table`]) is put in quotes, as TOML
/// holds no such integer. An error says why the text has no such key to change.
pub fn with_generations(text: &str, generations: usize) -> Result<String, String> {
    let mut document: toml_edit::DocumentMut = text.parse().or_else(|e| {
        quoted_large_seed(text)
            .and_then(|quoted| quoted.parse().ok())
            .ok_or_else(|| format!("{e}"))
    })?;
    let count = i64::try_from(generations)
        .map_err(|_| format!("{generations} generations is more than TOML holds"))?;
    let value = document
        .get_mut("ga")
        .and_then(|ga| ga.get_mut("generations"))
        .and_then(toml_edit::Item::as_value_mut)
        .ok_or("it has no [ga] generations to change")?;
    let decor = value.decor().clone();
    *value = toml_edit::Value::from(count);
    *value.decor_mut() = decor;
    Ok(document.to_string())
}

impl<L: Serialize> RunConfig<L> {
    /// The configuration as TOML text.
    pub fn to_toml(&self) -> Result<String, String> {
        toml::to_string(self).map_err(|e| e.to_string())
    }

    /// The settings in which `self` and `other` differ, as dotted TOML keys
    /// (`seed`, `ga.population`, `task.sim.substeps`), in key order.
    pub fn differences(&self, other: &RunConfig<L>) -> Result<Vec<String>, String> {
        let table = |c: &RunConfig<L>| toml::Table::try_from(c).map_err(|e| e.to_string());
        let mut out = Vec::new();
        differing_keys("", &table(self)?, &table(other)?, &mut out);
        Ok(out)
    }
}

/// Pushes onto `out` the keys, under `prefix`, whose values differ between `a` and `b`,
/// descending into tables both hold.
fn differing_keys(prefix: &str, a: &toml::Table, b: &toml::Table, out: &mut Vec<String>) {
    let keys: BTreeSet<&String> = a.keys().chain(b.keys()).collect();
    for key in keys {
        let name = format!("{prefix}{key}");
        match (a.get(key), b.get(key)) {
            (Some(toml::Value::Table(x)), Some(toml::Value::Table(y))) => {
                differing_keys(&format!("{name}."), x, y, out)
            }
            (x, y) if x != y => out.push(name),
            _ => {}
        }
    }
}

/// Checks the values a configuration may get wrong ([`GaSettings::check`] and
/// [`TaskSpec::check`]) for a run of each of `encodings`: `develop = "during"` only on the
/// walker with the `lsystem-continuous` genome, the one whose creatures grow during their
/// evaluation. The error names the setting in its table (`[task.sim] substeps ...`).
pub fn check_settings(
    ga: &GaSettings,
    task: &TaskSpec,
    encodings: &[&str],
) -> Result<(), SettingError> {
    ga.check().map_err(|e| e.within("ga"))?;
    if ga.algorithm == Algorithm::SteadyState && task.trials.fresh {
        return Err(SettingError {
            table: "ga".into(),
            key: "algorithm",
            problem: "\"steady-state\" keeps each evaluation for life, and fresh trials draw \
                      anew each generation: use \"generational\" with fresh trials"
                .into(),
        });
    }
    if task.develop.during() {
        let refuse = |why: String| {
            Err(SettingError::out_of_range("develop", &why, "\"during\"").within("task"))
        };
        if task.check_growing().is_err() {
            return refuse(format!(
                "\"before\" on the {} task (only the walker grows its creature during its \
                 evaluation)",
                task.kind().name()
            ));
        }
        let grows = <crate::encoding::ContinuousGenome as crate::encoding::Genome>::NAME;
        if let Some(other) = encodings.iter().find(|&&e| e != grows) {
            return refuse(format!(
                "\"before\" with the {other} genome (only {grows} grows during its evaluation)"
            ));
        }
    }
    task.check()
}
