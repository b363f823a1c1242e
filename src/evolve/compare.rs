//! Comparing encodings on equal terms (`ontogeny compare`): a comparison directory holds one
//! full run directory per replicate of every encoding, all with the same genetic algorithm,
//! task and evaluation budget, and a report of statistics over their champions.
//!
//! ```text
//! runs/NAME/compare.toml             the comparison: encodings, replicates, budget, seed
//! runs/NAME/evolve.toml              the shared settings ([ga] and [task]), an evolve config
//! runs/NAME/<encoding>/rep-<k>/      replicate k (1-based): an ordinary run directory
//! runs/NAME/report.md, summary.csv, fitness.svg, parts.svg
//! ```
//!
//! This module knows no encoding by name: everything that depends on one is generic over
//! [`Genome`].

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::config::{RunConfig, check_settings, read_run_config};
use super::ga::{GaSettings, Individual};
use super::lock::{DirectoryLock, LockError};
use super::plot::{self, Band};
use super::stats;
use super::store::RunStore;
use crate::creature::Creature;
use crate::encoding::Genome;
use crate::lang::Source;
use crate::task::TaskSpec;

/// Why a comparison could not be planned, run or reported.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// Bad input: a budget below one generation, a replicate whose settings differ, ...
    #[error("{0}")]
    Input(String),
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// An output file was refused or could not be written (see [`crate::output`]).
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// Anything else (a database or a plot that fails).
    #[error("{0}")]
    Other(String),
}

impl From<plot::PlotError> for CompareError {
    fn from(e: plot::PlotError) -> Self {
        match e {
            plot::PlotError::Output(e) => CompareError::Output(e),
            other => CompareError::Other(other.to_string()),
        }
    }
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> CompareError + '_ {
    move |source| CompareError::Io {
        path: path.to_path_buf(),
        source,
    }
}

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

/// Replicate `k`'s run directory.
pub fn replicate_dir(root: &Path, encoding: &str, k: usize) -> PathBuf {
    root.join(encoding).join(format!("rep-{k}"))
}

/// Takes the lock of the comparison in `root` ([`crate::evolve::lock`]), held while the
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
    std::fs::create_dir_all(root).map_err(io(root))?;
    let lock = acquire(root)?;
    let path = root.join("compare.toml");
    if path.exists() {
        return Err(CompareError::Input(format!(
            "{} already holds a comparison: complete it with `ontogeny compare --resume {0}`, or choose another --out",
            root.display()
        )));
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
    let text = std::fs::read_to_string(&path).map_err(io(&path))?;
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
    /// Its encoding.
    pub encoding: String,
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

/// Checks that the run in `dir` is replicate `k` of encoding `G` in this comparison (same
/// settings, the expected seed and the encoding's default limits) and reads it.
pub fn read_replicate<G: Genome>(
    root: &Path,
    manifest: &Manifest,
    shared: &Shared,
    k: usize,
) -> Result<ReplicateState, CompareError> {
    let dir = replicate_dir(root, G::NAME, k);
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
    let expected = RunConfig {
        encoding: G::NAME.to_string(),
        seed: replicate_seed(manifest.seed, k),
        init: None,
        verify_best: true,
        // The cache changes no result: a replicate may have run with or without it.
        cache: config.cache,
        ga: shared.ga.clone(),
        task: shared.task.clone(),
        limits: G::Limits::default(),
    };
    let differences = config.differences(&expected).map_err(CompareError::Other)?;
    if !differences.is_empty() {
        return Err(CompareError::Input(format!(
            "{} is not replicate {k} of this comparison: its {} differ{} from {}",
            dir.display(),
            differences.join(", "),
            if differences.len() == 1 { "s" } else { "" },
            root.join("evolve.toml").display()
        )));
    }
    let generations = store
        .generations()
        .map_err(|e| CompareError::Other(e.to_string()))?;
    if generations.len() < shared.ga.generations {
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
    let reused = store
        .reused_by_generation()
        .map_err(|e| CompareError::Other(e.to_string()))?
        .iter()
        .map(|&(_, n)| n)
        .sum();
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
        encoding: G::NAME.to_string(),
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

/// One encoding's figures.
#[derive(Clone, Debug, PartialEq)]
pub struct EncodingSummary {
    /// The encoding.
    pub encoding: String,
    /// Finished replicates.
    pub replicates: usize,
    /// The replicates' best fitness.
    pub best: stats::Summary,
    /// The mean of the replicates' final champions re-walked at the fine reference setting
    /// ([`Champion::fine_fitness`]), over those that were and whose re-walk did not fail (NaN
    /// if none): a failed re-walk scores the failure floor, which would swamp the mean.
    pub mean_fine: f64,
    /// How many replicates' champions were re-walked at the fine reference.
    pub fine_replicates: usize,
    /// How many of those re-walks failed (scored the failure floor: unstable, exploded, ...).
    pub fine_failed: usize,
    /// The champions' median parts, joints and neurons.
    pub median_parts: f64,
    /// See `median_parts`.
    pub median_joints: f64,
    /// See `median_parts`.
    pub median_neurons: f64,
    /// The champions' median distinct part shapes per part.
    pub median_shapes_per_part: f64,
    /// Evaluations per second over all its replicates.
    pub evaluations_per_second: f64,
    /// Evaluations its replicates simulated, in all.
    pub simulated: u64,
    /// Evaluations its replicates reused from an identical creature evaluated earlier in the
    /// same run, in all.
    pub reused: u64,
}

/// One pairwise test.
#[derive(Clone, Debug, PartialEq)]
pub struct Pair {
    /// The first encoding.
    pub a: String,
    /// The second.
    pub b: String,
    /// The test of a's best fitness against b's.
    pub test: stats::MannWhitney,
    /// Holm-corrected p over all pairs.
    pub holm_p: f64,
    /// Vargha–Delaney A12 of a over b.
    pub a12: f64,
}

/// The report's numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// Per encoding, in the manifest's order.
    pub encodings: Vec<EncodingSummary>,
    /// Every pair, in the manifest's order.
    pub pairs: Vec<Pair>,
    /// The evaluations every replicate made.
    pub evaluations: u64,
}

/// The statistics of `replicates` (finished ones, any order) of the comparison.
pub fn report(manifest: &Manifest, shared: &Shared, replicates: &[Replicate]) -> Report {
    let of = |e: &str| -> Vec<&Replicate> {
        let mut v: Vec<&Replicate> = replicates.iter().filter(|r| r.encoding == e).collect();
        v.sort_by_key(|r| r.k);
        v
    };
    let encodings = manifest
        .encodings
        .iter()
        .map(|e| {
            let rs = of(e);
            let pick = |f: fn(&Champion) -> f64| {
                stats::median(&rs.iter().map(|r| f(&r.champion)).collect::<Vec<_>>())
            };
            let evaluations: u64 = rs.iter().map(|r| r.evaluations).sum();
            let reused: u64 = rs.iter().map(|r| r.reused).sum();
            let wall: f64 = rs.iter().map(|r| r.wall_seconds).sum();
            let walked: Vec<f64> = rs
                .iter()
                .map(|r| r.champion.fine_fitness)
                .filter(|f| !f.is_nan())
                .collect();
            let fine: Vec<f64> = walked
                .iter()
                .copied()
                .filter(|&f| f > crate::task::FAILURE_FITNESS)
                .collect();
            EncodingSummary {
                encoding: e.clone(),
                replicates: rs.len(),
                best: stats::summary(&rs.iter().map(|r| r.champion.fitness).collect::<Vec<_>>()),
                mean_fine: if fine.is_empty() {
                    f64::NAN
                } else {
                    fine.iter().sum::<f64>() / fine.len() as f64
                },
                fine_replicates: walked.len(),
                fine_failed: walked.len() - fine.len(),
                median_parts: pick(|c| c.parts as f64),
                median_joints: pick(|c| c.joints as f64),
                median_neurons: pick(|c| c.neurons as f64),
                median_shapes_per_part: pick(|c| c.shapes_per_part),
                evaluations_per_second: if wall > 0.0 {
                    evaluations as f64 / wall
                } else {
                    f64::NAN
                },
                simulated: evaluations.saturating_sub(reused),
                reused,
            }
        })
        .collect();
    let mut pairs = Vec::new();
    for (i, a) in manifest.encodings.iter().enumerate() {
        for b in &manifest.encodings[i + 1..] {
            let best = |e: &str| -> Vec<f64> { of(e).iter().map(|r| r.champion.fitness).collect() };
            let (x, y) = (best(a), best(b));
            pairs.push(Pair {
                a: a.clone(),
                b: b.clone(),
                test: stats::mann_whitney(&x, &y),
                holm_p: f64::NAN,
                a12: stats::a12(&x, &y),
            });
        }
    }
    let corrected = stats::holm(&pairs.iter().map(|p| p.test.p).collect::<Vec<_>>());
    for (p, h) in pairs.iter_mut().zip(corrected) {
        p.holm_p = h;
    }
    Report {
        encodings,
        pairs,
        evaluations: evaluations_of(&shared.ga),
    }
}

/// Writes `text` to `path` whole or not at all ([`crate::output::write`]): a reader never sees
/// half a report.
fn write_file(path: &Path, text: &str) -> Result<(), CompareError> {
    Ok(crate::output::write(path, text)?)
}

/// A number for a table: NaN as "–".
fn num(v: f64, decimals: usize) -> String {
    if v.is_finite() {
        format!("{v:.decimals$}")
    } else {
        "–".to_string()
    }
}

/// Writes `report.md`, `summary.csv`, `fitness.svg` and `parts.svg` into `root`.
/// `unfinished` lists the replicates not (yet) in the report.
pub fn write_report(
    root: &Path,
    manifest: &Manifest,
    shared: &Shared,
    replicates: &[Replicate],
    unfinished: &[String],
) -> Result<Report, CompareError> {
    let r = report(manifest, shared, replicates);
    let mut md = String::new();
    let task = shared.task.task.name();
    let _ = writeln!(
        md,
        "# Comparison of {} on the {task} task\n\nFitness: {}.\n",
        manifest.encodings.join(", "),
        shared.task.fitness_label()
    );
    let _ = writeln!(
        md,
        "{} replicates per encoding, seed {}; every replicate made exactly {} evaluations \
         (budget {}: population {}, {} generations, elite {} not re-evaluated; preset {}).\n",
        manifest.replicates,
        manifest.seed,
        r.evaluations,
        manifest.evaluations,
        shared.ga.population,
        shared.ga.generations,
        shared.ga.survivors(),
        serde_json::to_value(shared.ga.preset)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default()
    );
    if !unfinished.is_empty() {
        let _ = writeln!(
            md,
            "**Incomplete**: not in this report: {}.\n",
            unfinished.join(", ")
        );
    }
    let _ = writeln!(
        md,
        "Best fitness of each replicate: mean, sample standard deviation and the 95% confidence \
         interval of the mean (Student's t). Champions (each replicate's best individual): \
         median parts, joints and neurons, and median distinct part shapes per part (lower is \
         more regular). \"At the fine reference\": the mean of the replicates' final \
         champions walked again with 4 physics substeps of 8 solver iterations (the stored \
         best comes from the run's own stepping, 4 substeps of 4 iterations by default; a \
         much lower value means the champions exploit it, or were lucky), over the replicates that recorded it when fewer. \
         Simulated and reused: the evaluations of all its replicates, split into those \
         simulated and those that reused the evaluation of an identical creature earlier in \
         the same run.\n"
    );
    let _ = writeln!(
        md,
        "| encoding | n | mean best | at the fine reference | sd | 95% CI | parts | joints | neurons | shapes/part | simulated | reused | evaluations/s |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for e in &r.encodings {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} to {} | {} | {} | {} | {} | {} | {} | {} |",
            e.encoding,
            e.replicates,
            num(e.best.mean, 4),
            match (
                e.fine_replicates == e.replicates || e.fine_replicates == 0,
                e.fine_failed
            ) {
                (true, 0) => num(e.mean_fine, 4),
                (false, 0) => format!(
                    "{} ({} of {})",
                    num(e.mean_fine, 4),
                    e.fine_replicates,
                    e.replicates
                ),
                (_, failed) => format!(
                    "{} ({} of {}; {failed} failed)",
                    num(e.mean_fine, 4),
                    e.fine_replicates - failed,
                    e.replicates
                ),
            },
            num(e.best.sd, 4),
            num(e.best.mean - e.best.ci95, 4),
            num(e.best.mean + e.best.ci95, 4),
            num(e.median_parts, 1),
            num(e.median_joints, 1),
            num(e.median_neurons, 1),
            num(e.median_shapes_per_part, 3),
            e.simulated,
            e.reused,
            num(e.evaluations_per_second, 1),
        );
    }
    let _ = writeln!(
        md,
        "\nPairwise two-sided Mann–Whitney U tests of the best fitness (exact distribution \
         without ties and up to {} replicates, else the normal approximation with tie and \
         continuity corrections), Holm-corrected over the {} pairs; A12 is Vargha and \
         Delaney's probability that a replicate of the first encoding beats one of the second \
         (0.5: no effect).\n",
        stats::EXACT_MAX,
        r.pairs.len()
    );
    let _ = writeln!(md, "| a | b | U | p | method | Holm p | A12 | effect |");
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|");
    for p in &r.pairs {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            p.a,
            p.b,
            num(p.test.u, 1),
            num(p.test.p, 4),
            p.test.method.name(),
            num(p.holm_p, 4),
            num(p.a12, 3),
            stats::a12_magnitude(p.a12)
        );
    }
    let _ = writeln!(
        md,
        "\n![mean best fitness against evaluations](fitness.svg)\n\n![champions' parts](parts.svg)"
    );
    write_file(&root.join("report.md"), &md)?;

    let mut csv = String::from(
        "encoding,replicate,seed,evaluations,best_fitness,best_fine,parts,joints,neurons,shapes_per_part,simulated,reused,wall_seconds\n",
    );
    let mut sorted: Vec<&Replicate> = replicates.iter().collect();
    let position = |e: &str| manifest.encodings.iter().position(|x| x == e);
    sorted.sort_by_key(|r| (position(&r.encoding), r.k));
    for rep in sorted {
        let c = &rep.champion;
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{},{},{:.3}",
            rep.encoding,
            rep.k,
            rep.seed,
            rep.evaluations,
            c.fitness,
            c.fine_fitness,
            c.parts,
            c.joints,
            c.neurons,
            c.shapes_per_part,
            rep.evaluations - rep.reused,
            rep.reused,
            rep.wall_seconds
        );
    }
    write_file(&root.join("summary.csv"), &csv)?;

    let bands: Vec<Band> = manifest
        .encodings
        .iter()
        .map(|e| band(e, replicates))
        .collect();
    let title = format!("{task}: mean best fitness with 95% confidence bands");
    plot::bands_svg(&root.join("fitness.svg"), &bands, &title)?;
    let parts: Vec<(String, Vec<f64>)> = manifest
        .encodings
        .iter()
        .map(|e| {
            let mut v: Vec<(usize, f64)> = replicates
                .iter()
                .filter(|r| &r.encoding == e)
                .map(|r| (r.k, r.champion.parts as f64))
                .collect();
            v.sort_by_key(|x| x.0);
            (e.clone(), v.into_iter().map(|x| x.1).collect())
        })
        .collect();
    plot::strip_svg(
        &root.join("parts.svg"),
        &parts,
        "parts",
        &format!("{task}: the champions' parts (bar: median)"),
    )?;
    Ok(r)
}

/// The mean best-so-far fitness of `encoding`'s replicates after each generation, with its
/// 95% confidence band (the band is the mean where fewer than 2 replicates exist).
fn band(encoding: &str, replicates: &[Replicate]) -> Band {
    let rs: Vec<&Replicate> = replicates
        .iter()
        .filter(|r| r.encoding == encoding)
        .collect();
    let points = rs.first().map_or(0, |r| r.curve.len());
    let mut out = Vec::with_capacity(points);
    for g in 0..points {
        let values: Vec<f64> = rs
            .iter()
            .filter_map(|r| r.curve.get(g))
            .map(|p| p.1)
            .collect();
        let s = stats::summary(&values);
        let half = if s.ci95.is_finite() { s.ci95 } else { 0.0 };
        out.push((
            rs[0].curve[g].0 as f64,
            s.mean,
            s.mean - half,
            s.mean + half,
        ));
    }
    Band {
        name: encoding.to_string(),
        points: out,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::evolve::ga::Preset;

    fn ga(population: usize, generations: usize) -> GaSettings {
        GaSettings {
            population,
            generations,
            ..GaSettings::preset(Preset::Chaumont)
        }
    }

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

    fn replicate(encoding: &str, k: usize, best: f64, parts: u32) -> Replicate {
        Replicate {
            encoding: encoding.into(),
            k,
            seed: k as u64,
            curve: vec![(6, best / 2.0), (11, best)],
            evaluations: 11,
            reused: 1,
            wall_seconds: 2.0,
            champion: Champion {
                fitness: best,
                fine_fitness: best / 4.0,
                parts,
                joints: parts.saturating_sub(1),
                neurons: 2 * parts,
                shapes_per_part: 1.0,
            },
        }
    }

    #[test]
    fn the_report_by_hand() {
        let manifest = Manifest {
            encodings: vec!["a".into(), "b".into(), "c".into()],
            replicates: 3,
            evaluations: 11,
            seed: 1,
        };
        let shared = Shared {
            ga: ga(6, 2),
            task: TaskSpec::new(crate::task::TaskKind::Walker),
        };
        // Replicate 1 of c was not re-walked at the fine reference (an old run).
        let mut unverified = replicate("c", 1, 1.5, 1);
        unverified.champion.fine_fitness = f64::NAN;
        // b's third champion did not come to rest at the fine reference: the failure floor.
        let mut failed = replicate("b", 3, 6.0, 2);
        failed.champion.fine_fitness = crate::task::FAILURE_FITNESS;
        let reps = vec![
            replicate("a", 1, 1.0, 3),
            replicate("a", 2, 2.0, 5),
            replicate("a", 3, 3.0, 9),
            replicate("b", 1, 4.0, 1),
            replicate("b", 2, 5.0, 1),
            failed,
            unverified,
            replicate("c", 2, 2.5, 1),
            replicate("c", 3, 3.5, 2),
        ];
        let r = report(&manifest, &shared, &reps);
        assert_eq!(r.evaluations, 11);
        let a = &r.encodings[0];
        assert_eq!(a.replicates, 3);
        assert_eq!(a.best.mean, 2.0);
        assert_eq!(a.best.sd, 1.0);
        // The fine reference values 1/4, 2/4, 3/4: mean 0.5.
        assert_eq!((a.mean_fine, a.fine_replicates), (0.5, 3));
        // c's over its two verified replicates: (2.5 + 3.5) / 4 / 2.
        let c = &r.encodings[2];
        assert_eq!((c.mean_fine, c.fine_replicates), (0.75, 2));
        // b's over the two re-walks that did not fail: (4 + 5) / 4 / 2; one failed.
        let b = &r.encodings[1];
        assert_eq!(
            (b.mean_fine, b.fine_replicates, b.fine_failed),
            (1.125, 3, 1)
        );
        assert_eq!((a.fine_failed, c.fine_failed), (0, 0));
        assert_eq!(a.median_parts, 5.0);
        assert_eq!(a.median_joints, 4.0);
        assert_eq!(a.median_neurons, 10.0);
        // 33 evaluations in 6 s.
        assert_eq!(a.evaluations_per_second, 5.5);
        // Of which one per replicate reused.
        assert_eq!((a.simulated, a.reused), (30, 3));
        // a against b: every b beats every a: U = 0, exact p = 2/C(6, 3) = 0.1, A12 = 0.
        let ab = &r.pairs[0];
        assert_eq!((ab.a.as_str(), ab.b.as_str()), ("a", "b"));
        assert_eq!(ab.test.u, 0.0);
        assert!((ab.test.p - 0.1).abs() < 1e-12);
        assert_eq!(ab.a12, 0.0);
        // a against c: a's 1, 2, 3 against 1.5, 2.5, 3.5: U = 0 + 1 + 2 = 3, A12 = 3/9.
        let ac = &r.pairs[1];
        assert_eq!(ac.test.u, 3.0);
        assert!((ac.a12 - 1.0 / 3.0).abs() < 1e-12);
        // b against c: U = 9, p = 0.1. Holm over p = (0.1, p_ac, 0.1): p_ac = 0.7 (U = 3 of
        // 9: P(U ≤ 3) = 7/20 = 0.35, twice 0.7); sorted 0.1·3, 0.1·2 → 0.3, 0.3; 0.7.
        assert!((ac.test.p - 0.7).abs() < 1e-12, "{}", ac.test.p);
        assert!((r.pairs[0].holm_p - 0.3).abs() < 1e-12);
        assert!((r.pairs[2].holm_p - 0.3).abs() < 1e-12);
        assert!((r.pairs[1].holm_p - 0.7).abs() < 1e-12);
        // The band: the mean of the best so far, 1, 2, 3 → 2 ± t(2)·1/√3.
        let b = band("a", &reps);
        assert_eq!(b.points.len(), 2);
        assert_eq!(b.points[1].0, 11.0);
        assert_eq!(b.points[1].1, 2.0);
        let half = stats::t_quantile_975(2) / 3f64.sqrt();
        assert!((b.points[1].3 - 2.0 - half).abs() < 1e-12);
    }
}
