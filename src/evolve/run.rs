//! A run directory: `config.toml` (every setting, written at the start), `run.sqlite` (the
//! record of truth, one transaction per generation), `fitness.svg`, `best.lsys` (`best.json`, ... after the encoding's text form) and `log.txt`,
//! rewritten after every generation. A run killed at any moment resumes from its last complete
//! generation and ends exactly as an uninterrupted run would.

use std::path::{Path, PathBuf};
use std::time::Instant;

use super::config::{RunConfig, read_run_config};
use super::ga::{Evolution, Fallbacks, GenerationStats, Individual, Operator, ranking};
use super::plot::fitness_svg;
use super::store::{
    FineEvaluation, GenerationRecord, IndividualRecord, RunRecord, RunStore, StoreError,
};
use crate::encoding::{Genome, Purpose};
use crate::lang::{Diagnostic, Source};
use crate::task::{Evaluation, TaskKind, TaskSpec};

/// Why a run could not start, resume or go on.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// `--out` names a run that exists.
    #[error(
        "{0} already holds a run: resume it with `ontogeny evolve --resume {0}`, or choose another --out"
    )]
    Exists(PathBuf),
    /// A directory that is not a run.
    #[error("{0} is not a run directory (no config.toml)")]
    NotARun(PathBuf),
    /// A bad configuration.
    #[error("{0}")]
    Config(Diagnostic),
    /// The database refused.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// A stored individual does not read back (a database written by another encoding or
    /// version).
    #[error("{0}")]
    Corrupt(String),
    /// The plot could not be drawn.
    #[error("{0}")]
    Plot(String),
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> RunError + '_ {
    move |source| RunError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Writes `text` to `path` through a temporary file and a rename, so a crash leaves either
/// the old file or the new one.
fn write_atomically(path: &Path, text: &[u8]) -> Result<(), RunError> {
    let temporary = path.with_extension("tmp");
    std::fs::write(&temporary, text).map_err(io(&temporary))?;
    std::fs::rename(&temporary, path).map_err(io(path))
}

/// What happened in one generation, for progress displays.
#[derive(Clone, Debug)]
pub struct GenerationReport {
    /// The generation's index.
    pub generation: u32,
    /// Its figures.
    pub stats: GenerationStats,
    /// Wall-clock seconds it took (development, evaluation and bookkeeping).
    pub wall_seconds: f64,
    /// Of which evaluating (development and physics).
    pub evaluation_seconds: f64,
    /// Children made by mutation so far because the encoding lacks an operator.
    pub fallbacks: Fallbacks,
    /// The best individual re-walked at the fine reference setting (`None` when the run's
    /// `verify_best` is off).
    pub best_fine: Option<FineEvaluation>,
}

/// A run: its directory, settings, genetic algorithm and store.
pub struct Run<G: Genome> {
    dir: PathBuf,
    config: RunConfig<G::Limits>,
    evolution: Evolution<G>,
    store: RunStore,
}

impl<G: Genome> Run<G> {
    /// Starts a new run in `dir` (refused if it holds a run): writes `config.toml` (and
    /// `init.lsys`, the grammar of `init_text`) and creates the database.
    pub fn start(
        dir: &Path,
        mut config: RunConfig<G::Limits>,
        init_text: Option<&str>,
    ) -> Result<Run<G>, RunError> {
        if dir.join("config.toml").exists() || dir.join("run.sqlite").exists() {
            return Err(RunError::Exists(dir.to_path_buf()));
        }
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let init = match init_text {
            Some(text) => {
                let genome =
                    G::from_lsys(text, &config.limits).map_err(|e| RunError::Corrupt(e.0))?;
                let path = dir.join("init.lsys");
                std::fs::write(&path, text).map_err(io(&path))?;
                config.init = Some(PathBuf::from("init.lsys"));
                Some(genome)
            }
            None => {
                config.init = None;
                None
            }
        };
        let text = config.to_toml().map_err(RunError::Corrupt)?;
        let path = dir.join("config.toml");
        write_atomically(&path, text.as_bytes())?;
        let store = RunStore::create(
            &dir.join("run.sqlite"),
            &RunRecord {
                config: text,
                seed: config.seed,
                encoding: config.encoding.clone(),
                task: config.task.task.name().to_string(),
                version: env!("CARGO_PKG_VERSION").to_string(),
            },
        )?;
        Ok(Run::assemble(dir, config, store, init))
    }

    /// Opens the run in `dir` to go on with it.
    pub fn resume(dir: &Path) -> Result<Run<G>, RunError> {
        let path = dir.join("config.toml");
        if !path.exists() {
            return Err(RunError::NotARun(dir.to_path_buf()));
        }
        let source = Source::read(&path).map_err(io(&path))?;
        let config: RunConfig<G::Limits> = read_run_config(&source).map_err(RunError::Config)?;
        let store = RunStore::open(&dir.join("run.sqlite"))?;
        let init = match &config.init {
            Some(file) => {
                let path = dir.join(file);
                let text = std::fs::read_to_string(&path).map_err(io(&path))?;
                Some(G::from_lsys(&text, &config.limits).map_err(|e| RunError::Corrupt(e.0))?)
            }
            None => None,
        };
        Ok(Run::assemble(dir, config, store, init))
    }

    /// A run of `config`, its store and its `init` genome.
    fn assemble(
        dir: &Path,
        config: RunConfig<G::Limits>,
        store: RunStore,
        init: Option<G>,
    ) -> Run<G> {
        let purpose = match config.task.task {
            TaskKind::Walker | TaskKind::Jump => Purpose::Locomotion,
            TaskKind::Catapult | TaskKind::Aim => Purpose::Throwing,
        };
        let mut limits = config.limits.clone();
        G::adapt_limits(&mut limits, purpose);
        Run {
            dir: dir.to_path_buf(),
            evolution: Evolution {
                settings: config.ga.clone(),
                limits,
                task: config.task.clone(),
                seed: config.seed,
                init,
            },
            config,
            store,
        }
    }

    /// The run's settings.
    pub fn config(&self) -> &RunConfig<G::Limits> {
        &self.config
    }

    /// The index of the last complete generation, if any.
    pub fn last_generation(&self) -> Result<Option<u32>, RunError> {
        Ok(self.store.last_generation()?)
    }

    /// Reads generation `generation` back from the store.
    pub fn population(&self, generation: u32) -> Result<Vec<Individual<G>>, RunError> {
        self.store
            .individuals(generation)?
            .iter()
            .map(|r| {
                serde_json::from_str(&r.genome_json).map_err(|e| {
                    RunError::Corrupt(format!(
                        "{}: individual {} of generation {generation} does not read back as a {} genome: {e}",
                        self.dir.join("run.sqlite").display(),
                        r.index,
                        G::NAME
                    ))
                })
            })
            .collect()
    }

    /// Runs the remaining generations, calling `observer` after each.
    pub fn run(&mut self, observer: &mut dyn FnMut(&GenerationReport)) -> Result<(), RunError> {
        let generations = self.config.ga.generations as u32;
        let (mut population, first) = match self.store.last_generation()? {
            None => (Vec::new(), 0),
            Some(g) => (self.population(g)?, g + 1),
        };
        // The previous generation's best (its index) and its fine reference evaluation: an
        // elite copy of it needs no second walk, as the evaluation is a pure function of the
        // genome, its development seed and the task.
        let mut previous_best: Option<(u32, FineEvaluation)> = None;
        if first > 0
            && let Some(&best) = ranking(&population).first()
            && let Some(stored) = self.store.generations()?.pop().and_then(|g| g.best_fine)
        {
            previous_best = Some((best as u32, stored));
        }
        let mut fallbacks = Fallbacks::default();
        let log = self.dir.join("log.txt");
        for generation in first..generations {
            let started = Instant::now();
            let (next, evaluations) = if generation == 0 {
                let p = self.evolution.first_generation();
                let n = p.len() as u64;
                (p, n)
            } else {
                self.evolution
                    .next_generation(&population, generation, &mut fallbacks)
            };
            population = next;
            let best = ranking(&population).first().copied();
            let best_fine = match best {
                Some(best) if self.config.verify_best => {
                    let b = &population[best];
                    Some(match &previous_best {
                        Some((p, fine)) if b.operator == Operator::Elite && b.parents == [*p] => {
                            fine.clone()
                        }
                        _ => self.fine_evaluation(b),
                    })
                }
                _ => None,
            };
            previous_best = best.zip(best_fine.clone()).map(|(b, f)| (b as u32, f));
            let evaluation_seconds = started.elapsed().as_secs_f64();
            let stats = GenerationStats::of(&population, evaluations);
            self.record(generation, &population, &stats, best_fine.clone(), started)?;
            let wall_seconds = started.elapsed().as_secs_f64();
            let line = format!(
                "generation {generation}: best {:.6}{}, mean {:.6}, median {:.6}, valid {:.0}%, {} evaluations in {:.1} s{}\n",
                stats.best,
                fine_note(best_fine.as_ref()),
                stats.mean,
                stats.median,
                stats.valid_fraction * 100.0,
                evaluations,
                wall_seconds,
                fallback_note(&fallbacks, G::NAME),
            );
            append(&log, &line)?;
            observer(&GenerationReport {
                generation,
                stats,
                wall_seconds,
                evaluation_seconds,
                fallbacks: fallbacks.clone(),
                best_fine,
            });
        }
        Ok(())
    }

    /// The task specification of the fine reference check: the run's, with the simulator at
    /// its fine reference setting.
    pub fn fine_task(&self) -> TaskSpec {
        TaskSpec {
            sim: self.config.task.sim.fine_reference(),
            ..self.config.task.clone()
        }
    }

    /// `individual` developed again (same limits and development seed as in the run) and
    /// evaluated with [`Run::fine_task`]: a pure function of the genome and the task.
    pub fn fine_evaluation(&self, individual: &Individual<G>) -> FineEvaluation {
        let task = self.fine_task();
        let evaluation = match individual
            .genome
            .develop(&self.evolution.limits, individual.develop_seed)
        {
            Ok(creature) => task.evaluate(&creature, false),
            Err(e) => Evaluation::invalid(task.task.name(), format!("development: {e}")),
        };
        FineEvaluation {
            fitness: evaluation.fitness,
            status: status_text(&evaluation),
        }
    }

    /// Stores a generation (one transaction), then rewrites `best.lsys` (or the encoding's
    /// extension) and `fitness.svg`.
    fn record(
        &mut self,
        generation: u32,
        population: &[Individual<G>],
        stats: &GenerationStats,
        best_fine: Option<FineEvaluation>,
        started: Instant,
    ) -> Result<(), RunError> {
        let individuals = population
            .iter()
            .enumerate()
            .map(|(index, i)| {
                Ok(IndividualRecord {
                    generation,
                    index: index as u32,
                    parents: i.parents.clone(),
                    operator: i.operator.name().to_string(),
                    genome_text: i.genome.to_text(),
                    genome_json: serde_json::to_string(i)
                        .map_err(|e| RunError::Corrupt(e.to_string()))?,
                    fitness: i.evaluation.fitness,
                    status: status_name(i),
                    terms_json: serde_json::to_string(&i.evaluation.terms)
                        .map_err(|e| RunError::Corrupt(e.to_string()))?,
                    parts: i.size.0,
                    joints: i.size.1,
                    neurons: i.size.2,
                })
            })
            .collect::<Result<Vec<_>, RunError>>()?;
        let wall_seconds = started.elapsed().as_secs_f64();
        self.store.write_generation(
            &GenerationRecord {
                index: generation,
                best: stats.best,
                mean: stats.mean,
                median: stats.median,
                sd: stats.sd,
                valid_fraction: stats.valid_fraction,
                evaluations: stats.evaluations,
                wall_seconds,
                evaluations_per_second: stats.evaluations as f64 / wall_seconds.max(1e-9),
                best_fine: best_fine.clone(),
            },
            &individuals,
        )?;
        if let Some(&best) = ranking(population).first() {
            let b = &population[best];
            let fine = match &best_fine {
                Some(f) => format!(
                    "; re-walked at the fine reference setting: {} ({})",
                    f.fitness, f.status
                ),
                None => String::new(),
            };
            let note = format!(
                "The best individual of {} after generation {generation}: {} fitness {} ({}){fine}.\nGrow it with `ontogeny grow`, evaluate it with `ontogeny eval`.",
                self.dir.display(),
                self.config.task.task.name(),
                b.evaluation.fitness,
                status_name(b),
            );
            let text = b.genome.annotated_text(&note);
            let name = format!("best.{}", G::TEXT_EXTENSION);
            write_atomically(&self.dir.join(name), text.as_bytes())?;
        }
        let generations = self.store.generations()?;
        let title = format!(
            "{}: {} on the {} task",
            self.dir.display(),
            G::NAME,
            self.config.task.task.name()
        );
        fitness_svg(&self.dir.join("fitness.svg"), &generations, &title)
            .map_err(|e| RunError::Plot(e.to_string()))?;
        Ok(())
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

/// Whether a champion's fitness at the fine reference setting, `fine`, is below half its
/// stored fitness `best` (a positive one), or is no number: then its score may owe more to
/// the evaluator's coarse stepping than to its behaviour, and `ontogeny evolve` warns.
pub fn exploits_stepping(best: f64, fine: f64) -> bool {
    best > 0.0 && (fine.is_nan() || fine < best / 2.0)
}

/// " (fine reference 4.100000)" for a log line, or nothing when the best was not verified.
fn fine_note(fine: Option<&FineEvaluation>) -> String {
    match fine {
        Some(f) if f.status == "ok" => format!(" (fine reference {:.6})", f.fitness),
        Some(f) => format!(" (fine reference {:.6}, {})", f.fitness, f.status),
        None => String::new(),
    }
}

fn fallback_note(f: &Fallbacks, encoding: &str) -> String {
    if f.crossover == 0 && f.graft == 0 {
        return String::new();
    }
    format!(
        " (the {encoding} encoding has no {}: {} children so far made by mutation instead)",
        match (f.crossover > 0, f.graft > 0) {
            (true, true) => "crossover or grafting",
            (true, false) => "crossover",
            _ => "grafting",
        },
        f.crossover + f.graft
    )
}

fn append(path: &Path, line: &str) -> Result<(), RunError> {
    use std::io::Write;
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
        .map_err(io(path))?;
    file.write_all(line.as_bytes()).map_err(io(path))
}
