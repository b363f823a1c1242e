//! A run directory: `run.sqlite` (the record of truth: every setting, written when the run
//! starts, and one transaction per generation), `config.toml` (the settings as text, for
//! people), and the files derived from the store: `log.txt`, `fitness.svg` and `best.lsys`
//! (`best.json`, ... after the encoding's text form), written whole from the store whenever
//! the run starts or is resumed, and advanced by each generation ([`derived`]).
//!
//! A run killed at any moment resumes from its last complete generation and ends exactly as
//! an uninterrupted run would. The store is created whole and only then `config.toml`, so a
//! kill during the start leaves either no run (start it again) or a run `--resume` completes.
//! A process writing a run holds the directory's lock ([`super::lock`]); a resume whose
//! `config.toml` differs from the settings the store was created with is refused.

use std::path::{Path, PathBuf};

use super::config::{RunConfig, check_settings, read_run_config, with_generations};
use super::folder::{CONFIG_FILE, Claim, STORE_FILE, claim_folder};
use super::lock::DirectoryLock;
use super::profile::ProfileWriter;
use super::store::{GenerationRecord, RunRecord, RunStore};
use crate::cancel::Cancel;
use crate::encoding::{CheckedLimits, Genome, Purpose};
use crate::evolve::cache::EvaluationCache;
use crate::evolve::evaluator_version::EVALUATOR_VERSION;
use crate::evolve::ga::{Algorithm, Evolution, Fallbacks, Individual, Operator, WalkOrder};
use crate::evolve::key::{EvaluationKey, KeyVersion};
use crate::lang::{Diagnostic, DiagnosticKind, Source};
use crate::output;
use crate::task::{Evaluation, TaskTables};

mod beside;
mod births;
mod conclude;
pub mod derived;
mod error;
mod generational;
mod pool;
mod progress;
mod steady;

pub use error::RunError;
use error::io;

/// The settings a resume may change (by `--gens`, or in `config.toml`): the number of
/// generations, as no choice of the genetic algorithm depends on it.
pub const RESUMABLE_KEYS: [&str; 1] = ["ga.generations"];

/// What happened in one generation, for progress displays.
#[derive(Clone, Debug)]
pub struct GenerationReport {
    /// The generation's index.
    pub generation: u32,
    /// Its figures, as stored, but for `reused` in a steady-state run: every birth of the
    /// block that reused an evaluation, kept or not (the store counts the members kept).
    pub stats: GenerationRecord,
    /// Wall-clock seconds it took (development, evaluation and bookkeeping).
    pub wall_seconds: f64,
    /// Of which evaluating (development and physics).
    pub evaluation_seconds: f64,
    /// Children made by mutation so far because the encoding lacks an operator.
    pub fallbacks: Fallbacks,
}

/// A run: its directory, settings, genetic algorithm and store.
pub struct Run<G: Genome> {
    dir: PathBuf,
    config: RunConfig<G::Limits>,
    evolution: Evolution<G>,
    store: RunStore,
    /// The evaluations made so far, by key (rebuilt from the store when the run goes on).
    cache: EvaluationCache,
    /// The directory's lock, held while the run may write (`None` when opened read-only).
    _lock: Option<DirectoryLock>,
    /// Stops [`Run::run`] between evaluations once set.
    cancel: Cancel,
    /// What the derived files hold, once written from the store ([`derived`]).
    written: Option<derived::Written>,
    /// Where each generation's timings go ([`Run::set_profile`]), if anywhere.
    profile: Option<ProfileWriter>,
}

/// What is said of the run in `dir` when its encoding, `name`, is none of the registry's:
/// `RUN: unknown encoding 'NAME'`.
pub fn unknown_encoding_of_run(dir: &Path, name: &str) -> String {
    format!("{}: unknown encoding '{name}'", dir.display())
}

/// The encoding of the run in `dir`, as its store records it (or, for a start interrupted
/// before its store was made, as its `config.toml` says), read without changing anything.
pub fn encoding_of_run(dir: &Path) -> Result<String, RunError> {
    let store = dir.join(STORE_FILE);
    if RunStore::is_vacant(&store) {
        let path = dir.join(CONFIG_FILE);
        if !path.is_file() {
            return Err(RunError::NotARun(dir.to_path_buf()));
        }
        let source = Source::read(&path).map_err(io(&path))?;
        return Ok(super::config::encoding_of(&source)
            .map_err(RunError::Config)?
            .unwrap_or_else(|| "lsystem".to_string()));
    }
    Ok(RunStore::open_read_only(&store)?.run()?.encoding)
}

/// The run's settings and limits in range ([`check_settings`], [`CheckedLimits`]); the error
/// names `name`, where they come from, and the key.
fn checked_settings<L: CheckedLimits>(config: &RunConfig<L>, name: &str) -> Result<(), RunError> {
    check_settings(&config.ga, &config.task, &[config.encoding.as_str()])
        .and_then(|()| config.limits.check_ranges())
        .map_err(|e| {
            RunError::Config(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!("{name}: {e}"),
            ))
        })
}

impl<G: Genome> Run<G> {
    /// Starts a new run in `dir` (refused if it holds a run, if another process holds its
    /// lock, or if a setting is out of range, before anything is written): writes `init.lsys`
    /// (the grammar of `init_text`), creates the database holding every setting, then writes
    /// `config.toml`, and rewrites the derived files.
    pub fn start(
        dir: &Path,
        mut config: RunConfig<G::Limits>,
        init_text: Option<&str>,
    ) -> Result<Run<G>, RunError> {
        checked_settings(&config, "the run's settings")?;
        if claim_folder(dir)? == Claim::HoldsARun {
            return Err(RunError::Exists(dir.to_path_buf()));
        }
        let lock = DirectoryLock::acquire(dir)?;
        let store_path = dir.join(STORE_FILE);
        if dir.join(CONFIG_FILE).exists() || !RunStore::is_vacant(&store_path) {
            return Err(RunError::Exists(dir.to_path_buf()));
        }
        // Neither config.toml nor a run: whatever a killed start left is ours to replace.
        RunStore::remove_vacant(&store_path)?;
        let init = match init_text {
            Some(text) => {
                let genome =
                    G::from_lsys(text, &config.limits).map_err(|e| RunError::Corrupt(e.0))?;
                output::write(&dir.join("init.lsys"), text.as_bytes())?;
                config.init = Some(PathBuf::from("init.lsys"));
                Some(genome)
            }
            None => {
                config.init = None;
                None
            }
        };
        let text = config.to_toml().map_err(RunError::Corrupt)?;
        let store = RunStore::create(
            &store_path,
            &RunRecord {
                config: text.clone(),
                seed: config.seed,
                encoding: config.encoding.clone(),
                task: config.task.task.name().to_string(),
                version: env!("CARGO_PKG_VERSION").to_string(),
            },
        )?;
        output::write(&dir.join(CONFIG_FILE), text.as_bytes())?;
        let mut run = Run::assemble(dir, config, store, init, Some(lock));
        run.write_derived_files()?;
        Ok(run)
    }

    /// Opens the run in `dir` to go on with it: takes the directory's lock, verifies every
    /// record of the store against its checksum, checks that `config.toml` holds the
    /// settings the store was created with (writing it from the store if a start was killed
    /// before it) and that this program's evaluator made the last generation, migrates an
    /// older store, and rewrites the derived files from the store. A refused resume writes
    /// nothing.
    pub fn resume(dir: &Path) -> Result<Run<G>, RunError> {
        Self::resume_with(dir, false)
    }

    /// [`Run::resume`]; with `allow_evaluator_change`, a run whose last generation another
    /// evaluator version made goes on with this program's ([`EVALUATOR_VERSION`]): its
    /// generations from then on record the new version, and the evaluations of the old one
    /// are not reused (an elite keeps the evaluation it was carried over with).
    pub fn resume_with(dir: &Path, allow_evaluator_change: bool) -> Result<Run<G>, RunError> {
        let config_path = dir.join(CONFIG_FILE);
        let store_path = dir.join(STORE_FILE);
        // A directory with neither is no run: leave it untouched (no lock file either).
        if !config_path.is_file() && !store_path.is_file() {
            return Err(RunError::NotARun(dir.to_path_buf()));
        }
        let lock = DirectoryLock::acquire(dir)?;
        let file_config = if config_path.exists() {
            let source = Source::read(&config_path).map_err(io(&config_path))?;
            Some((
                read_run_config::<G::Limits>(&source).map_err(RunError::Config)?,
                source,
            ))
        } else {
            None
        };
        if RunStore::is_vacant(&store_path) {
            // A start killed by an older ontogeny after config.toml, before its store held
            // the run: nothing was computed; make the store from config.toml.
            let Some((config, source)) = file_config else {
                return Err(RunError::NotARun(dir.to_path_buf()));
            };
            checked_settings(&config, source.name())?;
            RunStore::remove_vacant(&store_path)?;
            let store = RunStore::create(
                &store_path,
                &RunRecord {
                    config: source.text().to_string(),
                    seed: config.seed,
                    encoding: config.encoding.clone(),
                    task: config.task.task.name().to_string(),
                    version: env!("CARGO_PKG_VERSION").to_string(),
                },
            )?;
            let init = Self::read_init(dir, &config)?;
            let mut run = Run::assemble(dir, config, store, init, Some(lock));
            run.write_derived_files()?;
            return Ok(run);
        }
        // Read-only until the records and settings are checked: a refused resume changes
        // nothing.
        let checked = RunStore::open_read_only(&store_path)?;
        checked.verify()?;
        let stored = checked.run()?;
        if let Some(&(generation, version)) = checked.evaluators()?.last()
            && version != EVALUATOR_VERSION
            && !allow_evaluator_change
        {
            return Err(RunError::EvaluatorChanged {
                dir: dir.to_path_buf(),
                generation,
                stored: version,
                current: EVALUATOR_VERSION,
            });
        }
        drop(checked);
        let source = Source::new(
            format!(
                "{} (the settings the run started with)",
                store_path.display()
            ),
            stored.config.clone(),
        );
        let config: RunConfig<G::Limits> = read_run_config(&source).map_err(RunError::Config)?;
        checked_settings(&config, source.name())?;
        let mut extend_to = None;
        match &file_config {
            Some((edited, _)) => {
                let keys = config.differences(edited).map_err(RunError::Corrupt)?;
                let refused: Vec<String> = keys
                    .iter()
                    .filter(|k| !RESUMABLE_KEYS.contains(&k.as_str()))
                    .cloned()
                    .collect();
                if !refused.is_empty() {
                    return Err(RunError::ConfigChanged {
                        path: config_path,
                        keys: refused,
                    });
                }
                if keys.iter().any(|k| k == "ga.generations") {
                    extend_to = Some(edited.ga.generations);
                }
            }
            None => output::write(&config_path, stored.config.as_bytes())?,
        }
        let store = RunStore::open(&store_path)?;
        let init = Self::read_init(dir, &config)?;
        let mut run = Run::assemble(dir, config, store, init, Some(lock));
        run.adopt_stored_keys()?;
        if let Some(generations) = extend_to {
            run.extend(generations)?;
        }
        run.write_derived_files()?;
        Ok(run)
    }

    /// Makes the run go on to `generations` generations in all (at least as many as it has
    /// stored): the count is recorded in the store and in `config.toml`, and the run then
    /// equals one started with that count, as no choice of the genetic algorithm depends on
    /// it.
    pub fn extend(&mut self, generations: usize) -> Result<(), RunError> {
        if self._lock.is_none() {
            return Err(RunError::Corrupt(format!(
                "{}: opened read-only, so it cannot be extended",
                self.dir.display()
            )));
        }
        let stored = self.store.last_generation()?.map_or(0, |g| g as usize + 1);
        let mut ga = self.config.ga.clone();
        ga.generations = generations;
        ga.check().map_err(|e| {
            RunError::Extend(match e.key {
                "generations" => e.for_flag("--gens"),
                _ => format!("--gens: {e}"),
            })
        })?;
        if generations < stored {
            return Err(RunError::Extend(format!(
                "{} has {stored} generations stored; it can go on to more, not stop at {generations}",
                self.dir.display()
            )));
        }
        if generations == self.config.ga.generations {
            return Ok(());
        }
        // Only the count changes, in the store's copy and in config.toml: the comments and
        // layout a person gave the file stay.
        let config_path = self.dir.join(CONFIG_FILE);
        let file = std::fs::read_to_string(&config_path).map_err(io(&config_path))?;
        let edit = |text: &str, name: &Path| {
            with_generations(text, generations).map_err(|e| {
                RunError::Extend(format!(
                    "{}: cannot set [ga] generations to {generations}: {e}",
                    name.display()
                ))
            })
        };
        let file = edit(&file, &config_path)?;
        let stored = edit(&self.store.run()?.config, &self.dir.join(STORE_FILE))?;
        self.store.set_config(&stored)?;
        output::write(&config_path, file.as_bytes())?;
        self.config.ga.generations = generations;
        self.evolution.settings.generations = generations;
        Ok(())
    }

    /// Opens the run in `dir` to read it: the store read-only (never migrated, never
    /// written), the settings from the store, no lock. [`Run::run`] fails on such a run.
    pub fn open_read_only(dir: &Path) -> Result<Run<G>, RunError> {
        let store_path = dir.join(STORE_FILE);
        if RunStore::is_vacant(&store_path) {
            return Err(RunError::NotARun(dir.to_path_buf()));
        }
        let store = RunStore::open_read_only(&store_path)?;
        let stored = store.run()?;
        let source = Source::new(
            format!(
                "{} (the settings the run started with)",
                store_path.display()
            ),
            stored.config,
        );
        let config: RunConfig<G::Limits> = read_run_config(&source).map_err(RunError::Config)?;
        let init = Self::read_init(dir, &config).ok().flatten();
        let mut run = Run::assemble(dir, config, store, init, None);
        run.adopt_stored_keys()?;
        Ok(run)
    }

    /// The genome of the run's `init.lsys`, if it has one.
    fn read_init(dir: &Path, config: &RunConfig<G::Limits>) -> Result<Option<G>, RunError> {
        match &config.init {
            Some(file) => {
                let path = dir.join(file);
                let text = crate::input::read_to_string(&path).map_err(io(&path))?;
                Ok(Some(
                    G::from_lsys(&text, &config.limits).map_err(|e| RunError::Corrupt(e.0))?,
                ))
            }
            None => Ok(None),
        }
    }

    /// A run of `config`, its store and its `init` genome.
    fn assemble(
        dir: &Path,
        config: RunConfig<G::Limits>,
        store: RunStore,
        init: Option<G>,
        lock: Option<DirectoryLock>,
    ) -> Run<G> {
        let purpose = if config.task.task.throws() {
            Purpose::Throwing
        } else {
            Purpose::Locomotion
        };
        let mut limits = config.limits.clone();
        G::adapt_limits(&mut limits, purpose);
        if let Some(catapult) = config.task.task.get::<crate::task::CatapultOptions>()
            && catapult.evolve_projectile
        {
            let [x, y, z] = catapult.projectile_size.into();
            G::evolve_projectile(&mut limits, [x, y, z]);
        }
        G::allow_environment_reads(&mut limits, config.ga.environment_reads);
        Run {
            cache: EvaluationCache::new(config.cache),
            dir: dir.to_path_buf(),
            evolution: Evolution {
                settings: config.ga.clone(),
                limits,
                task: config.task.clone(),
                seed: config.seed,
                init,
                key_version: KeyVersion::default(),
                key_tables: None,
                walk_order: WalkOrder::default(),
            },
            config,
            store,
            _lock: lock,
            cancel: Cancel::default(),
            written: None,
            profile: None,
        }
    }

    /// Lets `cancel` stop [`Run::run`]: once it is set, the evaluations under way stop at
    /// their next control step, the generations not yet stored are dropped (the one under
    /// way, and in a generational run the one before it when its best's fine re-walk was still
    /// walking), and `run` returns [`RunError::Interrupted`]. The run then resumes from its
    /// last stored generation ([`Run::resume`]) and ends as an uninterrupted run would.
    pub fn set_cancel(&mut self, cancel: Cancel) {
        self.cancel = cancel;
    }

    /// Profiles the generations [`Run::run`] makes from now on: writes the file at `path` anew,
    /// empty, and adds each generation's line ([`super::profile`]) once it is stored. The run's
    /// results do not change.
    pub fn set_profile(&mut self, path: &Path) -> Result<(), RunError> {
        self.profile = Some(ProfileWriter::create(path)?);
        Ok(())
    }

    /// Hands each generation's walks to the evaluator in `order` from now on. The run's
    /// results do not change: only when each walk starts.
    pub fn set_walk_order(&mut self, order: WalkOrder) {
        self.evolution.walk_order = order;
    }

    /// The run's settings.
    pub fn config(&self) -> &RunConfig<G::Limits> {
        &self.config
    }

    /// The limits its genomes develop within: the config's, adapted to the task's purpose
    /// and to its `[ga] environment_reads`, as the genetic algorithm uses them.
    pub fn limits(&self) -> &G::Limits {
        &self.evolution.limits
    }

    /// The evaluation key this run gives the creature `genome` develops into with
    /// `develop_seed` (`None` when it does not develop): the key its cache finds it by.
    pub fn evaluation_key(&self, genome: &G, develop_seed: u64) -> Option<EvaluationKey> {
        self.evolution.key(genome, develop_seed)
    }

    /// Keys the run's individuals as its store does ([`Run::stored_key_version`]): a run
    /// whose keys are of version 1 hashes every task's table of its stored settings, as it
    /// did when it stored them.
    fn adopt_stored_keys(&mut self) -> Result<(), RunError> {
        let stored = self.store.run()?.config;
        let tables = crate::run::config::parse_table(&stored)
            .ok()
            .and_then(|config| config.get("task")?.clone().try_into::<TaskTables>().ok());
        self.evolution.key_tables = tables;
        self.evolution.key_version = self.stored_key_version()?;
        if self.evolution.key_version != KeyVersion::V1 {
            self.evolution.key_tables = None;
        }
        Ok(())
    }

    /// The version of the evaluation keys the store holds: the one that gives the first
    /// keyed individual of a generation its stored key. A store made before keys had versions
    /// holds version 1, and keeps it, so that its cache finds what it evaluated; a store with
    /// no key yet takes today's.
    fn stored_key_version(&self) -> Result<KeyVersion, RunError> {
        let Some(last) = self.store.last_generation()? else {
            return Ok(KeyVersion::default());
        };
        for generation in 0..=last {
            let population = self.population(generation)?;
            let Some(keyed) = population.iter().find(|i| i.key.is_some()) else {
                continue;
            };
            for version in [KeyVersion::V2, KeyVersion::V1] {
                let key = self
                    .evolution
                    .key_of_version(&keyed.genome, keyed.develop_seed, version);
                if key == keyed.key {
                    return Ok(version);
                }
            }
        }
        Ok(KeyVersion::default())
    }

    /// The index of the last complete generation, if any.
    pub fn last_generation(&self) -> Result<Option<u32>, RunError> {
        Ok(self.store.last_generation()?)
    }

    /// The last complete generation's report as the store holds it (its timings 0: nothing
    /// ran), if any.
    pub fn last_report(&self) -> Result<Option<GenerationReport>, RunError> {
        let Some(stats) = self.store.generations()?.pop() else {
            return Ok(None);
        };
        let fallbacks = self.fallbacks_by_generation()?.pop().unwrap_or_default();
        Ok(Some(GenerationReport {
            generation: stats.index,
            stats,
            wall_seconds: 0.0,
            evaluation_seconds: 0.0,
            fallbacks,
        }))
    }

    /// Reads generation `generation` back from the store.
    pub fn population(&self, generation: u32) -> Result<Vec<Individual<G>>, RunError> {
        self.store
            .individuals(generation)?
            .iter()
            .map(|r| {
                let mut individual: Individual<G> =
                    serde_json::from_str(&r.genome_json).map_err(|e| {
                        RunError::Corrupt(format!(
                            "{}: individual {} of generation {generation} does not read back as a {} genome: {e}",
                            self.dir.join(STORE_FILE).display(),
                            r.index,
                            G::NAME
                        ))
                    })?;
                individual.reused = r.reused;
                individual.parents_generation = r.parents_generation;
                individual.key = r
                    .evaluation_key
                    .as_deref()
                    .map(|hex| self.stored_key(hex, generation, r.index))
                    .transpose()?;
                Ok(individual)
            })
            .collect()
    }

    /// The evaluation key `hex` of individual `index` of generation `generation`.
    fn stored_key(
        &self,
        hex: &str,
        generation: u32,
        index: u32,
    ) -> Result<EvaluationKey, RunError> {
        EvaluationKey::from_hex(hex).ok_or_else(|| {
            RunError::Corrupt(format!(
                "{}: individual {index} of generation {generation} has the evaluation key {hex:?}, not 64 hexadecimal digits",
                self.dir.join(STORE_FILE).display()
            ))
        })
    }

    /// Fills the evaluation cache (when the run's `cache` is on) from the store: every
    /// individual evaluated (not reused) with a key, its evaluation read back from its JSON
    /// form, and each verified generation's fine reference re-walk under its best
    /// individual's key. A resumed run thus reuses what an uninterrupted one would.
    fn rebuild_cache(&mut self) -> Result<(), RunError> {
        /// The evaluation within an individual's JSON form (the genome is skipped).
        #[derive(serde::Deserialize)]
        struct StoredEvaluation {
            evaluation: Evaluation,
        }
        let mut cache = EvaluationCache::new(self.config.cache);
        if cache.enabled() {
            for (hex, json) in self.store.evaluations_by_key()? {
                let stored: StoredEvaluation = serde_json::from_str(&json).map_err(|e| {
                    RunError::Corrupt(format!(
                        "{}: an individual with the evaluation key {hex} does not read back: {e}",
                        self.dir.join(STORE_FILE).display()
                    ))
                })?;
                let key = EvaluationKey::from_hex(&hex).ok_or_else(|| {
                    RunError::Corrupt(format!(
                        "{}: the evaluation key {hex:?} is not 64 hexadecimal digits",
                        self.dir.join(STORE_FILE).display()
                    ))
                })?;
                cache.insert(key, &stored.evaluation);
            }
            let keys = self.store.keys()?;
            let evaluators = self.store.evaluators()?;
            for generation in self.store.generations()? {
                let Some(fine) = &generation.best_fine else {
                    continue;
                };
                // Only this program's evaluator's values (a run gone on under another).
                if !evaluators.contains(&(generation.index, EVALUATOR_VERSION)) {
                    continue;
                }
                let members = keys.iter().filter(|k| k.generation == generation.index);
                // The best as [`ranking`] orders them: highest fitness, then lowest index. A
                // NaN fitness (stored as NULL, its sign lost) could rank otherwise: skip.
                let mut best: Option<&super::store::StoredKey> = None;
                let mut unsure = false;
                for k in members {
                    unsure |= k.fitness.is_nan();
                    if best.is_none_or(|b| k.fitness.total_cmp(&b.fitness).is_gt()) {
                        best = Some(k);
                    }
                }
                if let (Some(hex), false) = (best.and_then(|b| b.evaluation_key.as_deref()), unsure)
                {
                    let key =
                        self.stored_key(hex, generation.index, best.map_or(0, |b| b.index))?;
                    cache.insert_fine(key, fine);
                }
            }
        }
        self.cache = cache;
        Ok(())
    }

    /// Runs the remaining generations, calling `observer` after each; stops with
    /// [`RunError::Interrupted`] once the token of [`Run::set_cancel`] is set. Outside
    /// evaluation a generation costs the same whatever came before it: one transaction of the
    /// store and the derived files advanced by it ([`derived`]).
    pub fn run(&mut self, observer: &mut dyn FnMut(&GenerationReport)) -> Result<(), RunError> {
        let mut progress = self.progress()?;
        let outcome = match self.config.ga.algorithm {
            Algorithm::Generational => self.run_generational(&mut progress, observer),
            Algorithm::SteadyState => self.run_steady(&mut progress, observer),
        };
        if outcome.is_err() {
            // Stopped early: the plot shows every stored generation, as a resume draws it.
            // Should that fail too, the first error is the one to tell.
            let _ = self.catch_up_plot();
        }
        outcome
    }

    /// How many children each stored generation had made by mutation instead of the
    /// scheduled operator, counted from the first generation through that one (index 0 is
    /// the first generation's, always none).
    /// A steady-state run counts none (a stored slot does not say what its birth was
    /// scheduled to be).
    fn fallbacks_by_generation(&self) -> Result<Vec<Fallbacks>, RunError> {
        let generations = self.store.generations()?;
        let mut fallen = vec![Fallbacks::default(); generations.len()];
        if self.config.ga.algorithm == Algorithm::SteadyState {
            return Ok(fallen);
        }
        for (generation, index) in self.store.individuals_made_by(Operator::Mutation.name())? {
            if let Some(f) = fallen.get_mut(generation as usize) {
                f.count_stored(&self.config.ga, index as usize, Operator::Mutation);
            }
        }
        let mut total = Fallbacks::default();
        for f in &mut fallen {
            total.crossover += f.crossover;
            total.graft += f.graft;
            *f = total.clone();
        }
        Ok(fallen)
    }
}

fn status_name<G>(i: &Individual<G>) -> String {
    status_text(&i.evaluation)
}

/// An evaluation's status as the store spells it (`ok`, `unstable`, ...).
fn status_text(e: &Evaluation) -> String {
    serde_json::to_value(e.status)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

/// Whether a champion's fitness at the fine reference setting, `fine`, falls below its
/// stored fitness `best` by more than half of `best`'s size (below half a positive `best`;
/// below 1.5 × a negative one), or is no number: then its score may owe more to the
/// evaluator's coarse stepping than to its behaviour, and `ontogeny evolve` warns. A `best`
/// of 0 has nothing to lose.
pub fn exploits_stepping(best: f64, fine: f64) -> bool {
    best != 0.0 && best.is_finite() && (fine.is_nan() || fine < best - best.abs() / 2.0)
}
