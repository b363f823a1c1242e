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

/// What a comparison is (`compare.toml`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// The encodings compared, in the order given.
    pub encodings: Vec<String>,
    /// Replicates per encoding.
    pub replicates: usize,
    /// The evaluation budget asked for.
    pub evaluations: u64,
    /// The seed every replicate's seed derives from.
    pub seed: u64,
}

/// The most replicates per encoding a comparison may have.
pub const MAX_REPLICATES: usize = 10_000;

impl Manifest {
    /// Checks what a comparison's manifest may get wrong: no encoding or one named twice,
    /// replicates out of 1 to [`MAX_REPLICATES`]; the message names the key. (An encoding
    /// name the program does not know is refused where it is run.)
    pub fn check(&self) -> Result<(), String> {
        if self.encodings.is_empty() {
            return Err("encodings names no encoding".into());
        }
        for (i, e) in self.encodings.iter().enumerate() {
            if self.encodings[..i].contains(e) {
                return Err(format!("encodings names {e} twice"));
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

/// The evaluations a run of `ga` makes: the whole first generation, then every individual but
/// the elite (carried over with its evaluation) in each later one.
pub fn evaluations_of(ga: &GaSettings) -> u64 {
    let population = ga.population as u64;
    let children = population - ga.survivors() as u64;
    population + (ga.generations as u64).saturating_sub(1) * children
}

/// The most generations whose evaluations fit in `budget` (see [`evaluations_of`]): at least
/// the first generation must fit. Errors name the numbers.
pub fn generations_for(ga: &GaSettings, budget: u64) -> Result<usize, String> {
    let population = ga.population as u64;
    if budget < population {
        return Err(format!(
            "a budget of {budget} evaluations is smaller than one generation ({population} individuals)"
        ));
    }
    let children = population - ga.survivors() as u64;
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

/// The settings of replicate `k` (1-based) of encoding `G`: the shared `[ga]` and `[task]`,
/// the replicate's seed, the encoding's default limits, the best re-walked at the fine
/// reference, and the evaluation cache on or off (`cache` changes no result).
pub fn replicate_config<G: Genome>(
    manifest: &Manifest,
    shared: &Shared,
    k: usize,
    cache: bool,
) -> RunConfig<G::Limits> {
    RunConfig {
        encoding: G::NAME.to_string(),
        seed: replicate_seed(manifest.seed, k),
        init: None,
        verify_best: true,
        cache,
        ga: shared.ga.clone(),
        task: shared.task.clone(),
        limits: G::Limits::default(),
    }
}

/// Replicate `k`'s run directory.
pub fn replicate_dir(root: &Path, encoding: &str, k: usize) -> PathBuf {
    root.join(encoding).join(format!("rep-{k}"))
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

/// Writes `compare.toml` and `evolve.toml` into `root` (created), refusing a directory that
/// already holds a comparison; returns the comparison's lock, taken before anything is
/// written.
pub fn create(
    root: &Path,
    manifest: &Manifest,
    shared: &Shared,
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
    let settings = root.join("evolve.toml");
    let text = toml::to_string(shared).map_err(|e| CompareError::Other(e.to_string()))?;
    crate::output::write(&settings, text)?;
    let text = toml::to_string(manifest).map_err(|e| CompareError::Other(e.to_string()))?;
    // The manifest last: a comparison exists once both are written.
    crate::output::write(&path, text)?;
    Ok(lock)
}

/// The error for a directory that holds no comparison.
fn not_a_comparison(root: &Path) -> CompareError {
    CompareError::Input(format!(
        "{} is not a comparison directory (no readable compare.toml)",
        root.display()
    ))
}

/// Reads a comparison's `compare.toml` and `evolve.toml`.
pub fn open(root: &Path) -> Result<(Manifest, Shared), CompareError> {
    let path = root.join("compare.toml");
    let source = Source::read(&path).map_err(|_| not_a_comparison(root))?;
    let manifest: Manifest = toml::from_str(source.text())
        .map_err(|e| CompareError::Input(format!("{}: {e}", path.display())))?;
    let path = root.join("evolve.toml");
    let text = crate::input::read_to_string(&path).map_err(io(&path))?;
    let shared: Shared = toml::from_str(&text)
        .map_err(|e| CompareError::Input(format!("{}: {e}", path.display())))?;
    // Both files may have been edited: their values get the checks of a new comparison's.
    manifest.check().map_err(|e| {
        CompareError::Input(format!("{}: {e}", root.join("compare.toml").display()))
    })?;
    check_settings(&shared.ga, &shared.task)
        .map_err(|e| CompareError::Input(format!("{}: {e}", path.display())))?;
    Ok((manifest, shared))
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::*;
    use crate::study::compare::chaumont_ga as ga;

    #[test]
    fn the_budget_counts_what_the_ga_evaluates() {
        // Population 10, elite 20% = 2: generation 0 costs 10, each later one 8.
        let g = ga(10, 1);
        assert_eq!(generations_for(&g, 10), Ok(1));
        assert_eq!(generations_for(&g, 17), Ok(1));
        assert_eq!(generations_for(&g, 18), Ok(2));
        assert_eq!(generations_for(&g, 100), Ok(12)); // 10 + 11·8 = 98
        assert_eq!(evaluations_of(&ga(10, 12)), 98);
        assert_eq!(evaluations_of(&ga(10, 1)), 10);
        assert!(
            generations_for(&g, 9)
                .unwrap_err()
                .contains("smaller than one generation (10 individuals)")
        );
        // Population 6: elite round(1.2) = 1, so 5 per later generation.
        assert_eq!(generations_for(&ga(6, 1), 16), Ok(3));
        assert_eq!(evaluations_of(&ga(6, 3)), 16);
        let everyone = GaSettings {
            elite: 1.0,
            ..ga(6, 1)
        };
        assert!(generations_for(&everyone, 60).is_err());
    }

    #[test]
    fn replicate_seeds_differ_and_repeat() {
        let seeds: BTreeSet<u64> = (1..=100).map(|k| replicate_seed(7, k)).collect();
        assert_eq!(seeds.len(), 100);
        assert_eq!(replicate_seed(7, 3), replicate_seed(7, 3));
        assert_ne!(replicate_seed(7, 3), replicate_seed(8, 3));
        assert!(seeds.iter().all(|&s| s < 1 << 31));
    }
}
