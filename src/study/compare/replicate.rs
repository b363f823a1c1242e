//! A finished replicate as the report uses it: its curve, its counts and its champion (body,
//! brain and regularity), read from its run store after checking that its settings are this
//! comparison's.

use std::collections::BTreeSet;
use std::path::Path;

use super::CompareError;
use super::plan::{Arm, Manifest, replicate_config, replicate_dir};
use crate::creature::Creature;
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
    /// Distinct part shapes per part (see [`distinct_shapes_per_part`]); NaN when it has no
    /// parts.
    pub shapes_per_part: f64,
}

/// The regularity measure: the number of distinct part shapes divided by the number of
/// parts. A shape is a part's three edge lengths, sorted (a turned box is the same box) and
/// rounded to the millimetre. 1 means every part differs; 1/parts, that one shape is used
/// throughout. Lower is more regular. NaN without parts.
pub fn distinct_shapes_per_part(creature: &Creature) -> f64 {
    if creature.parts.is_empty() {
        return f64::NAN;
    }
    let shapes: BTreeSet<[i64; 3]> = creature
        .parts
        .iter()
        .map(|p| {
            let mut s = [p.size.x, p.size.y, p.size.z].map(|v| (v * 1000.0).round() as i64);
            s.sort_unstable();
            s
        })
        .collect();
    shapes.len() as f64 / creature.parts.len() as f64
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
    let shapes_per_part = individual
        .genome
        .develop(&config.limits, individual.develop_seed)
        .map_or(f64::NAN, |c| distinct_shapes_per_part(&c));
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
            shapes_per_part,
        },
    })))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regularity_counts_distinct_shapes() {
        use crate::creature::Part;
        use nalgebra::{UnitQuaternion, Vector3};
        let part = |x: f64, y: f64, z: f64| Part {
            size: Vector3::new(x, y, z),
            position: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
            density: 1.0,
            growing: false,
        };
        let mut c = Creature::default();
        assert!(distinct_shapes_per_part(&c).is_nan());
        // Four parts: two equal boxes, the same box turned, and another: 2 shapes / 4 parts.
        c.parts = vec![
            part(1.0, 0.2, 0.1),
            part(1.0, 0.2, 0.1),
            part(0.1, 1.0, 0.2),
            part(0.5, 0.2, 0.1),
        ];
        assert_eq!(distinct_shapes_per_part(&c), 0.5);
        // Below a millimetre apart is the same shape.
        c.parts[1].size.x = 1.0004;
        assert_eq!(distinct_shapes_per_part(&c), 0.5);
        c.parts[1].size.x = 1.002;
        assert_eq!(distinct_shapes_per_part(&c), 0.75);
    }
}
