//! A finished replicate as the report uses it: its curve, its counts and its champion (body,
//! brain and regularity), read from its run store after checking that its settings are this
//! comparison's.

use std::path::Path;

use super::CompareError;
use super::plan::{Arm, Manifest, replicate_config, replicate_dir};
use crate::creature::{Regularity, regularity};
use crate::encoding::Genome;
use crate::evolve::ga::Individual;
use crate::lang::Source;
use crate::run::config::{RunConfig, read_run_config};
use crate::run::store::RunStore;

/// The champion's body and brain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Champion {
    /// Its fitness: the replicate's best.
    pub fitness: f64,
    /// The last generation's best (the champion, which elitism carries to the end, unless
    /// another individual ties with it) re-walked at the fine reference setting; NaN when the
    /// run did not verify it (a run of schema version 1).
    pub fine_fitness: f64,
    /// Parts of its body.
    pub parts: u32,
    /// Joints.
    pub joints: u32,
    /// Neurons.
    pub neurons: u32,
    /// The regularity of its body ([`Regularity`]); NaN on each measure when it has no
    /// parts or does not develop.
    pub regularity: Regularity,
}

/// One finished replicate, as the report uses it.
#[derive(Clone, Debug, PartialEq)]
pub struct Replicate {
    /// Its encoding's or condition's name ([`Arm::name`]).
    pub name: String,
    /// Its number (1-based).
    pub k: usize,
    /// Its seed.
    pub seed: u64,
    /// Cumulative evaluations and the best fitness so far, after each generation.
    pub curve: Vec<(u64, f64)>,
    /// Evaluations made (the last point of the curve).
    pub evaluations: u64,
    /// Of which reused from an identical creature evaluated earlier in the run (the others
    /// were simulated).
    pub reused: u64,
    /// Wall-clock seconds its generations took.
    pub wall_seconds: f64,
    /// Its best individual.
    pub champion: Champion,
}

/// A replicate's state on disk.
#[derive(Clone, Debug, PartialEq)]
pub enum ReplicateState {
    /// No run yet.
    Missing,
    /// A run stopped after this many complete generations.
    Partial(usize),
    /// Complete.
    Done(Box<Replicate>),
}

/// Checks that the run in `dir` is replicate `k` of `arm` (whose encoding is `G`) in this
/// comparison (the arm's settings and limits, the expected seed) and reads it.
pub fn read_replicate<G: Genome>(
    root: &Path,
    manifest: &Manifest,
    arm: &Arm,
    k: usize,
) -> Result<ReplicateState, CompareError> {
    let dir = replicate_dir(root, &arm.name, k);
    let database = dir.join("run.sqlite");
    if RunStore::is_vacant(&database) {
        return Ok(ReplicateState::Missing);
    }
    // Read-only: reading a comparison does not migrate its replicates' files. The settings
    // are the store's, the run's record of truth (a resume checks config.toml against them).
    let store =
        RunStore::open_read_only(&database).map_err(|e| CompareError::Other(e.to_string()))?;
    let stored = store
        .run()
        .map_err(|e| CompareError::Other(e.to_string()))?;
    let source = Source::new(database.display().to_string(), stored.config);
    let config: RunConfig<G::Limits> = read_run_config(&source)
        .map_err(|d| CompareError::Input(format!("{}: {d}", database.display())))?;
    // The cache changes no result: a replicate may have run with or without it.
    let expected = replicate_config::<G>(manifest, arm, k, config.cache)?;
    let differences = config.differences(&expected).map_err(CompareError::Other)?;
    if !differences.is_empty() {
        return Err(CompareError::Input(format!(
            "{} is not replicate {k} of this comparison: its {} differ{} from {}",
            dir.display(),
            differences.join(", "),
            if differences.len() == 1 { "s" } else { "" },
            if manifest.conditions.is_empty() {
                root.join("evolve.toml")
            } else {
                super::plan::condition_file(root, &arm.name)
            }
            .display()
        )));
    }
    let generations = store
        .generations()
        .map_err(|e| CompareError::Other(e.to_string()))?;
    if generations.len() < arm.settings.ga.generations {
        return Ok(ReplicateState::Partial(generations.len()));
    }
    let mut curve = Vec::with_capacity(generations.len());
    let (mut evaluations, mut best, mut wall) = (0u64, f64::NEG_INFINITY, 0.0);
    for g in &generations {
        evaluations += g.evaluations;
        best = best.max(g.best);
        wall += g.wall_seconds;
        curve.push((evaluations, best));
    }
    let reused = generations.iter().map(|g| g.reused).sum();
    let record = store
        .best_individual()
        .map_err(|e| CompareError::Other(e.to_string()))?
        .ok_or_else(|| CompareError::Other(format!("{}: no individual", database.display())))?;
    let individual: Individual<G> = serde_json::from_str(&record.genome_json).map_err(|e| {
        CompareError::Other(format!(
            "{}: the champion does not read back as a {} genome: {e}",
            database.display(),
            G::NAME
        ))
    })?;
    // Developed again from the stored genome: a run of any age has its champion's body.
    let regularity = individual
        .genome
        .develop(&config.limits, individual.develop_seed)
        .map_or(
            Regularity {
                repeated: f64::NAN,
                symmetry: f64::NAN,
                description_bytes: f64::NAN,
            },
            |c| regularity(&c),
        );
    Ok(ReplicateState::Done(Box::new(Replicate {
        name: arm.name.clone(),
        k,
        seed: config.seed,
        curve,
        evaluations,
        reused,
        wall_seconds: wall,
        champion: Champion {
            fitness: record.fitness,
            fine_fitness: generations
                .last()
                .and_then(|g| g.best_fine.as_ref())
                .map_or(f64::NAN, |f| f.fitness),
            parts: record.parts,
            joints: record.joints,
            neurons: record.neurons,
            regularity,
        },
    })))
}
