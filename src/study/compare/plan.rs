//! A comparison's plan and directory: what it is (`compare.toml`: encodings, replicates,
//! budget, seed), the settings its replicates share (`evolve.toml`), the budget in
//! generations, each replicate's seed, directory and settings, and the lock that keeps the
//! directory one process's.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{CompareError, io};
use crate::encoding::Genome;
use crate::evolve::ga::GaSettings;
use crate::lang::Source;
use crate::run::config::{RunConfig, check_settings};
use crate::run::lock::{DirectoryLock, LockError};
use crate::task::TaskSpec;

/// What a comparison is (`compare.toml`): the encodings compared under shared settings, or
/// the conditions compared, each under its own; never both.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// The encodings compared, in the order given (none when conditions are compared).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub encodings: Vec<String>,
    /// The conditions compared, in the order given (none when encodings are compared): each
    /// a whole run config, in `<condition>/evolve.toml`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub conditions: Vec<String>,
    /// Replicates per encoding or condition.
    pub replicates: usize,
    /// The budget asked for, in walks simulated (evaluations times
    /// [`walks_per_individual`]).
    pub evaluations: u64,
    /// The seed every replicate's seed derives from.
    pub seed: u64,
    /// The primary pair, two of the names compared (none: every pair is secondary): tested
    /// alone at the full level, the others Holm-corrected among themselves. Kept here so that
    /// `--resume` and `--merge` report it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub primary: Vec<String>,
}

/// The most replicates per encoding a comparison may have.
pub const MAX_REPLICATES: usize = 10_000;

/// The longest condition name.
pub const MAX_CONDITION_NAME: usize = 64;

/// Checks a condition's name: 1 to [`MAX_CONDITION_NAME`] ASCII letters, digits, `-` and `_`,
/// starting with a letter or digit. It names a directory of the comparison, so it holds no
/// path character, no dot (which the comparison's own files have) and no space.
pub fn check_condition_name(name: &str) -> Result<(), String> {
    if name.is_empty() {
        return Err("a condition needs a name before the =".into());
    }
    if name.len() > MAX_CONDITION_NAME {
        return Err(format!(
            "the condition name {name} is longer than {MAX_CONDITION_NAME} characters"
        ));
    }
    if let Some(c) = name
        .chars()
        .find(|&c| !(c.is_ascii_alphanumeric() || c == '-' || c == '_'))
    {
        return Err(format!(
            "the condition name {name} holds {c:?}: a name is ASCII letters, digits, - and _"
        ));
    }
    if !name.starts_with(|c: char| c.is_ascii_alphanumeric()) {
        return Err(format!(
            "the condition name {name} must start with a letter or a digit"
        ));
    }
    Ok(())
}

impl Manifest {
    /// The names compared: the conditions when there are any, else the encodings. A
    /// replicate of each lives in `<name>/rep-<k>`.
    pub fn names(&self) -> &[String] {
        if self.conditions.is_empty() {
            &self.encodings
        } else {
            &self.conditions
        }
    }

    /// What the names are: "condition" or "encoding".
    pub fn kind(&self) -> &'static str {
        if self.conditions.is_empty() {
            "encoding"
        } else {
            "condition"
        }
    }

    /// Checks what a comparison's manifest may get wrong: no encoding and no condition, or
    /// both, one named twice (conditions: in any case, as their directories would clash on
    /// some systems), a condition's name ([`check_condition_name`]), replicates out of 1 to
    /// [`MAX_REPLICATES`]; the message names the key. (An encoding name the program does not
    /// know is refused where it is run.)
    pub fn check(&self) -> Result<(), String> {
        match (self.encodings.is_empty(), self.conditions.is_empty()) {
            (true, true) => return Err("encodings names no encoding".into()),
            (false, false) => {
                return Err("encodings and conditions: a comparison has one or the other".into());
            }
            _ => {}
        }
        for (i, e) in self.encodings.iter().enumerate() {
            if self.encodings[..i].contains(e) {
                return Err(format!("encodings names {e} twice"));
            }
        }
        for (i, c) in self.conditions.iter().enumerate() {
            check_condition_name(c).map_err(|e| format!("conditions: {e}"))?;
            if let Some(first) = self.conditions[..i]
                .iter()
                .find(|x| x.eq_ignore_ascii_case(c))
            {
                return Err(duplicate_condition(first, c));
            }
        }
        if !self.primary.is_empty() {
            if self.primary.len() != 2 || self.primary[0] == self.primary[1] {
                return Err(format!(
                    "primary names a pair: two different {}s, not {}",
                    self.kind(),
                    self.primary.join(",")
                ));
            }
            if let Some(x) = self.primary.iter().find(|x| !self.names().contains(x)) {
                return Err(format!(
                    "primary names {x}, which is not one of the {}s compared ({})",
                    self.kind(),
                    self.names().join(", ")
                ));
            }
        }
        if !(1..=MAX_REPLICATES).contains(&self.replicates) {
            return Err(format!(
                "replicates must be 1 to {MAX_REPLICATES}, not {}",
                self.replicates
            ));
        }
        Ok(())
    }
}

/// The message for two conditions of one name (`first` given before `second`; the same but
/// for case counts as the same).
pub fn duplicate_condition(first: &str, second: &str) -> String {
    if first == second {
        format!("the condition {first} is named twice")
    } else {
        format!(
            "the conditions {first} and {second} differ only in case: their directories would be one on some systems"
        )
    }
}

/// The settings every replicate shares (`evolve.toml`, readable by `ontogeny evolve
/// --config`): the genetic algorithm, its generations set by the budget, and the task.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shared {
    /// The genetic algorithm's settings.
    pub ga: GaSettings,
    /// The task.
    pub task: TaskSpec,
}

/// A condition's settings (`<condition>/evolve.toml`, readable by `ontogeny evolve
/// --config`): a whole run config but its seed.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConditionFile {
    /// The encoding.
    pub encoding: String,
    /// The genetic algorithm's settings, its generations set by the budget.
    pub ga: GaSettings,
    /// The task.
    pub task: TaskSpec,
    /// The encoding's limits, every key written (none: the encoding's defaults).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limits: Option<toml::Table>,
}

/// One side of a comparison: an encoding under the shared settings, or a condition under its
/// own.
#[derive(Clone, Debug)]
pub struct Arm {
    /// Its name: the encoding's, or the condition's.
    pub name: String,
    /// Its encoding.
    pub encoding: String,
    /// Its genetic algorithm and task.
    pub settings: Shared,
    /// Its encoding's limits (none: the encoding's defaults).
    pub limits: Option<toml::Table>,
}

impl Arm {
    /// The walks one of its replicates simulates: its evaluations
    /// ([`evaluations_of`]) times [`walks_per_individual`].
    pub fn walks(&self) -> u64 {
        let task = &self.settings.task;
        evaluations_of(&self.settings.ga, task.trials.fresh) * walks_per_individual(task)
    }
}

/// What the arms' fitness is, for people: their task's fitness label, or each arm's
/// (`name: label`, joined by "; ") when they differ.
pub fn fitness_labels(arms: &[Arm]) -> String {
    let labels: Vec<String> = arms
        .iter()
        .map(|a| a.settings.task.fitness_label())
        .collect();
    if labels.windows(2).all(|w| w[0] == w[1]) {
        return labels.into_iter().next().unwrap_or_default();
    }
    arms.iter()
        .zip(labels)
        .map(|(a, l)| format!("{}: {l}", a.name))
        .collect::<Vec<_>>()
        .join("; ")
}

/// The walks simulated to evaluate one individual under `task`: its trials × habitats
/// ([`TaskSpec::walks_per_evaluation`]; 1 without either). A budget counts walks, so that a
/// task that walks each individual several times is compared with one that walks it once on
/// equal terms.
pub fn walks_per_individual(task: &TaskSpec) -> u64 {
    task.walks_per_evaluation() as u64
}

/// The arms of a comparison of encodings under `shared`.
pub fn encoding_arms(manifest: &Manifest, shared: &Shared) -> Vec<Arm> {
    manifest
        .encodings
        .iter()
        .map(|e| Arm {
            name: e.clone(),
            encoding: e.clone(),
            settings: shared.clone(),
            limits: None,
        })
        .collect()
}

/// Refuses arms whose budgets, in walks per replicate ([`Arm::walks`]), are too far apart:
/// generations are whole, so a budget is met to within a generation, but the smallest must be
/// at least [`BUDGET_TOLERANCE`] of the largest. Returns a note naming each arm's walks when
/// they are not all equal.
pub fn check_budgets(arms: &[Arm]) -> Result<Option<String>, String> {
    let walks: Vec<u64> = arms.iter().map(Arm::walks).collect();
    let (Some(&least), Some(&most)) = (walks.iter().min(), walks.iter().max()) else {
        return Ok(None);
    };
    if least == most {
        return Ok(None);
    }
    let each = arms
        .iter()
        .zip(&walks)
        .map(|(a, w)| {
            format!(
                "{}: {w} walks (population {}, {} generations, {} walk{} per individual)",
                a.name,
                a.settings.ga.population,
                a.settings.ga.generations,
                walks_per_individual(&a.settings.task),
                if walks_per_individual(&a.settings.task) == 1 {
                    ""
                } else {
                    "s"
                }
            )
        })
        .collect::<Vec<_>>()
        .join(", ");
    if (least as f64) < BUDGET_TOLERANCE * most as f64 {
        return Err(format!(
            "the budgets of a replicate differ by more than {:.0}%: {each}; choose populations that divide the budget more evenly, or a larger --evaluations",
            (1.0 - BUDGET_TOLERANCE) * 100.0
        ));
    }
    Ok(Some(format!(
        "the budgets of a replicate differ (generations are whole): {each}"
    )))
}

/// The least share of the largest budget every arm's budget must reach ([`check_budgets`]).
pub const BUDGET_TOLERANCE: f64 = 0.9;

/// The individuals a run of `ga` evaluates in each generation after the first: all but the
/// elite (carried over with its evaluation), or the whole population when the trials are
/// `fresh` (the elite is walked again on each generation's draws).
pub fn evaluated_per_generation(ga: &GaSettings, fresh: bool) -> u64 {
    let population = ga.population as u64;
    if fresh {
        population
    } else {
        population - ga.survivors() as u64
    }
}

/// The evaluations a run of `ga` makes: the whole first generation, then
/// [`evaluated_per_generation`] in each later one.
pub fn evaluations_of(ga: &GaSettings, fresh: bool) -> u64 {
    ga.population as u64
        + (ga.generations as u64).saturating_sub(1) * evaluated_per_generation(ga, fresh)
}

/// The most generations whose evaluations fit in `budget` (see [`evaluations_of`]): at least
/// the first generation must fit. Errors name the numbers.
pub fn generations_for(ga: &GaSettings, fresh: bool, budget: u64) -> Result<usize, String> {
    let population = ga.population as u64;
    if budget < population {
        return Err(format!(
            "a budget of {budget} evaluations is smaller than one generation ({population} individuals)"
        ));
    }
    let children = evaluated_per_generation(ga, fresh);
    if children == 0 {
        return Err(format!(
            "elite {} keeps the whole population of {population}: no generation after the first evaluates anything",
            ga.elite
        ));
    }
    let generations = 1 + (budget - population) / children;
    if generations > 100_000 {
        return Err(format!(
            "a budget of {budget} evaluations makes {generations} generations of {population}; at most 100000: raise the population"
        ));
    }
    Ok(generations as usize)
}

/// The seed of replicate `k` (1-based) of a comparison seeded with `seed`: both mixed by SplitMix64,
/// kept to 31 bits so that it reads easily in commands and tables.
pub fn replicate_seed(seed: u64, k: usize) -> u64 {
    let mut x = seed
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add(k as u64);
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    (x ^ (x >> 31)) >> 33
}

/// The settings of replicate `k` (1-based) of `arm`, whose encoding is `G`: the arm's
/// `[ga]`, `[task]` and limits (an encoding's defaults when it has none), the replicate's
/// seed, the best re-walked at the fine reference, and the evaluation cache on or off
/// (`cache` changes no result). Errors: limits that are not `G`'s.
pub fn replicate_config<G: Genome>(
    manifest: &Manifest,
    arm: &Arm,
    k: usize,
    cache: bool,
) -> Result<RunConfig<G::Limits>, CompareError> {
    let limits = match &arm.limits {
        None => G::Limits::default(),
        Some(table) => toml::Value::Table(table.clone()).try_into().map_err(|e| {
            CompareError::Input(format!(
                "{}: [limits] are not the {} encoding's: {e}",
                arm.name,
                G::NAME
            ))
        })?,
    };
    Ok(RunConfig {
        encoding: G::NAME.to_string(),
        seed: replicate_seed(manifest.seed, k),
        init: None,
        verify_best: true,
        cache,
        ga: arm.settings.ga.clone(),
        task: arm.settings.task.clone(),
        limits,
    })
}

/// Replicate `k`'s run directory, of the encoding or condition `name`.
pub fn replicate_dir(root: &Path, name: &str, k: usize) -> PathBuf {
    root.join(name).join(format!("rep-{k}"))
}

/// A condition's settings file: `<condition>/evolve.toml`.
pub fn condition_file(root: &Path, name: &str) -> PathBuf {
    root.join(name).join("evolve.toml")
}

/// Takes the lock of the comparison in `root` ([`crate::run::lock`]), held while the
/// returned value lives: one process at a time runs replicates or writes the report.
pub fn lock(root: &Path) -> Result<DirectoryLock, CompareError> {
    if !root.join("compare.toml").is_file() {
        // No comparison: say so, and leave the directory untouched (no lock file).
        return Err(not_a_comparison(root));
    }
    acquire(root)
}

/// Locks `root`, a directory that exists.
fn acquire(root: &Path) -> Result<DirectoryLock, CompareError> {
    DirectoryLock::acquire(root).map_err(|e| match e {
        LockError::Held { .. } => CompareError::Input(e.to_string()),
        LockError::Io { path, source } => CompareError::Io { path, source },
    })
}

/// Writes `compare.toml` and the settings of `arms` into `root` (created): `evolve.toml`, the
/// settings every encoding shares, or each condition's `<condition>/evolve.toml`. Refuses a
/// directory that already holds a comparison; returns the comparison's lock, taken before
/// anything is written.
pub fn create(
    root: &Path,
    manifest: &Manifest,
    arms: &[Arm],
) -> Result<DirectoryLock, CompareError> {
    let path = root.join("compare.toml");
    let exists = || {
        CompareError::Input(format!(
            "{} already holds a comparison: complete it with `ontogeny compare --resume {0}`, or choose another --out",
            root.display()
        ))
    };
    // A comparison an older version made carries no mark: refused as a comparison. One this
    // version made is refused as one below, once its lock is free.
    let kind = crate::output::FolderKind::Comparison;
    if !crate::output::folder::is_marked(root, kind) && path.exists() {
        return Err(exists());
    }
    // Missing, empty or a comparison's: never a folder of the user's files.
    crate::output::prepare_folder(root, kind)?;
    let lock = acquire(root)?;
    if path.exists() {
        return Err(exists());
    }
    if manifest.conditions.is_empty() {
        let shared = &arms
            .first()
            .ok_or_else(|| CompareError::Input("no encoding to compare".into()))?
            .settings;
        crate::output::write(&root.join("evolve.toml"), toml_text(shared)?)?;
    } else {
        for arm in arms {
            let dir = root.join(&arm.name);
            std::fs::create_dir_all(&dir).map_err(io(&dir))?;
            let file = ConditionFile {
                encoding: arm.encoding.clone(),
                ga: arm.settings.ga.clone(),
                task: arm.settings.task.clone(),
                limits: arm.limits.clone(),
            };
            crate::output::write(&condition_file(root, &arm.name), toml_text(&file)?)?;
        }
    }
    // The manifest last: a comparison exists once it is written.
    crate::output::write(&path, toml_text(manifest)?)?;
    Ok(lock)
}

/// `value` as TOML text.
fn toml_text<T: Serialize>(value: &T) -> Result<String, CompareError> {
    toml::to_string(value).map_err(|e| CompareError::Other(e.to_string()))
}

/// The error for a directory that holds no comparison.
fn not_a_comparison(root: &Path) -> CompareError {
    CompareError::Input(format!(
        "{} is not a comparison directory (no readable compare.toml)",
        root.display()
    ))
}

/// Reads a comparison's `compare.toml` and the settings of its arms: `evolve.toml`, or each
/// condition's `<condition>/evolve.toml`, checked as a new comparison's.
pub fn open(root: &Path) -> Result<(Manifest, Vec<Arm>), CompareError> {
    let path = root.join("compare.toml");
    let source = Source::read(&path).map_err(|_| not_a_comparison(root))?;
    let manifest: Manifest = toml::from_str(source.text())
        .map_err(|e| CompareError::Input(format!("{}: {e}", path.display())))?;
    // The files may have been edited: their values get the checks of a new comparison's.
    manifest
        .check()
        .map_err(|e| CompareError::Input(format!("{}: {e}", path.display())))?;
    let read = |path: &Path| -> Result<String, CompareError> {
        crate::input::read_to_string(path).map_err(io(path))
    };
    let bad = |path: &Path, e: &dyn std::fmt::Display| {
        CompareError::Input(format!("{}: {e}", path.display()))
    };
    if manifest.conditions.is_empty() {
        let path = root.join("evolve.toml");
        let shared: Shared = toml::from_str(&read(&path)?).map_err(|e| bad(&path, &e))?;
        let encodings: Vec<&str> = manifest.encodings.iter().map(String::as_str).collect();
        check_settings(&shared.ga, &shared.task, &encodings).map_err(|e| bad(&path, &e))?;
        let arms = encoding_arms(&manifest, &shared);
        return Ok((manifest, arms));
    }
    let mut arms = Vec::with_capacity(manifest.conditions.len());
    for name in &manifest.conditions {
        let path = condition_file(root, name);
        let file: ConditionFile = toml::from_str(&read(&path)?).map_err(|e| bad(&path, &e))?;
        check_settings(&file.ga, &file.task, &[file.encoding.as_str()])
            .map_err(|e| bad(&path, &e))?;
        arms.push(Arm {
            name: name.clone(),
            encoding: file.encoding,
            settings: Shared {
                ga: file.ga,
                task: file.task,
            },
            limits: file.limits,
        });
    }
    Ok((manifest, arms))
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::*;
    use crate::study::compare::chaumont_ga as ga;
    use crate::task::TaskSpec;

    #[test]
    fn the_budget_counts_what_the_ga_evaluates() {
        // Population 10, elite 20% = 2: generation 0 costs 10, each later one 8.
        let g = ga(10, 1);
        assert_eq!(generations_for(&g, false, 10), Ok(1));
        assert_eq!(generations_for(&g, false, 17), Ok(1));
        assert_eq!(generations_for(&g, false, 18), Ok(2));
        assert_eq!(generations_for(&g, false, 100), Ok(12)); // 10 + 11·8 = 98
        assert_eq!(evaluations_of(&ga(10, 12), false), 98);
        assert_eq!(evaluations_of(&ga(10, 1), false), 10);
        assert!(
            generations_for(&g, false, 9)
                .unwrap_err()
                .contains("smaller than one generation (10 individuals)")
        );
        // Population 6: elite round(1.2) = 1, so 5 per later generation.
        assert_eq!(generations_for(&ga(6, 1), false, 16), Ok(3));
        assert_eq!(evaluations_of(&ga(6, 3), false), 16);
        let everyone = GaSettings {
            elite: 1.0,
            ..ga(6, 1)
        };
        assert!(generations_for(&everyone, false, 60).is_err());
        // Fresh trials walk the elite again: every generation evaluates all 10.
        assert_eq!(evaluated_per_generation(&g, true), 10);
        assert_eq!(evaluations_of(&ga(10, 10), true), 100);
        assert_eq!(generations_for(&g, true, 100), Ok(10));
        assert_eq!(generations_for(&g, true, 99), Ok(9));
        assert_eq!(generations_for(&everyone, true, 60), Ok(10));
    }

    #[test]
    fn replicate_seeds_differ_and_repeat() {
        let seeds: BTreeSet<u64> = (1..=100).map(|k| replicate_seed(7, k)).collect();
        assert_eq!(seeds.len(), 100);
        assert_eq!(replicate_seed(7, 3), replicate_seed(7, 3));
        assert_ne!(replicate_seed(7, 3), replicate_seed(8, 3));
        assert!(seeds.iter().all(|&s| s < 1 << 31));
    }
    #[test]
    fn condition_names_are_plain_words() {
        for good in ["pop30", "K4_rough", "a", "4-trials"] {
            assert_eq!(check_condition_name(good), Ok(()), "{good}");
        }
        assert_eq!(
            check_condition_name("../a"),
            Err(
                "the condition name ../a holds '.': a name is ASCII letters, digits, - and _"
                    .into()
            )
        );
        assert!(
            check_condition_name("a/b")
                .unwrap_err()
                .contains("holds '/'")
        );
        assert!(
            check_condition_name("report.md")
                .unwrap_err()
                .contains("holds '.'")
        );
        assert!(
            check_condition_name("-a")
                .unwrap_err()
                .contains("must start with a letter")
        );
        assert!(check_condition_name("").is_err());
        assert!(check_condition_name(&"x".repeat(65)).is_err());
        assert!(check_condition_name(&"x".repeat(64)).is_ok());
    }

    #[test]
    fn a_manifest_compares_encodings_or_conditions_never_both() {
        let m = Manifest {
            encodings: vec![],
            conditions: vec!["a".into(), "b".into()],
            replicates: 2,
            evaluations: 10,
            seed: 1,
            primary: vec![],
        };
        assert_eq!(m.check(), Ok(()));
        // A primary pair is two different names of the comparison.
        let primary = |p: &[&str]| Manifest {
            primary: p.iter().map(|s| s.to_string()).collect(),
            ..m.clone()
        };
        assert_eq!(primary(&["b", "a"]).check(), Ok(()));
        assert!(
            primary(&["a"])
                .check()
                .unwrap_err()
                .contains("names a pair")
        );
        assert!(
            primary(&["a", "a"])
                .check()
                .unwrap_err()
                .contains("names a pair")
        );
        assert!(
            primary(&["a", "c"])
                .check()
                .unwrap_err()
                .contains("primary names c, which is not one of the conditions compared (a, b)")
        );
        assert_eq!((m.names(), m.kind()), (&m.conditions[..], "condition"));
        let both = Manifest {
            encodings: vec!["lsystem".into()],
            ..m.clone()
        };
        assert!(both.check().unwrap_err().contains("one or the other"));
        let twice = Manifest {
            conditions: vec!["a".into(), "A".into()],
            ..m.clone()
        };
        assert!(twice.check().unwrap_err().contains("differ only in case"));
        // A manifest of encodings reads and writes as before: no conditions key.
        let old =
            "encodings = [\"lsystem\", \"direct\"]\nreplicates = 2\nevaluations = 17\nseed = 4\n";
        let read: Manifest = toml::from_str(old).unwrap();
        assert_eq!(read.kind(), "encoding");
        assert_eq!(toml::to_string(&read).unwrap(), old);
    }

    #[test]
    fn budgets_a_little_apart_are_noted_and_far_apart_refused() {
        let arm = |name: &str, population: usize, generations: usize| Arm {
            name: name.into(),
            encoding: "lsystem".into(),
            settings: Shared {
                ga: ga(population, generations),
                task: TaskSpec::new(crate::task::TaskKind::Walker),
            },
            limits: None,
        };
        // Population 20, elite 4: 20 + 16·11 = 196; 21, elite 4: 21 + 17·10 = 191.
        assert_eq!(arm("a", 20, 12).walks(), 196);
        assert_eq!(arm("b", 21, 11).walks(), 191);
        assert_eq!(
            check_budgets(&[arm("a", 20, 12), arm("c", 20, 12)]),
            Ok(None)
        );
        let note = check_budgets(&[arm("a", 20, 12), arm("b", 21, 11)])
            .unwrap()
            .unwrap();
        assert!(
            note.contains(
                "a: 196 walks (population 20, 12 generations, 1 walk per individual), b: 191 walks"
            ),
            "{note}"
        );
        // 176 is below 90% of 196.
        assert!(
            check_budgets(&[arm("a", 20, 12), arm("b", 21, 10)])
                .unwrap_err()
                .contains("differ by more than 10%")
        );
    }
}
