//! Ontogeny from Python: the compiled module `ontogeny._ontogeny`, which the package
//! `ontogeny` (python/ontogeny/__init__.py) re-exports.
//!
//! The binding is thin: every function calls the library functions the command line calls
//! (`grow`, `derive`, `eval`, `evolve`, `runs`), so that its results are the command line's,
//! bit for bit. Bad input raises a Python exception (`ValueError` with the command line's
//! message, which names the file, line and column of a grammar; `FileNotFoundError` or
//! `OSError` for a file that cannot be read); nothing crashes the interpreter. The long calls
//! (`grow`, `derive`, `evaluate`, `evaluate_many`, `evolve`, `resume`) stop on Ctrl-C and
//! raise `KeyboardInterrupt` ([`interrupt`]).

mod interrupt;
mod resume;

use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use interrupt::{interrupted_error, interruptible};
use numpy::IntoPyArray;
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{PyArray1, PyArray2, PyArray3};
use ontogeny::cancel::Cancel;
use ontogeny::creature::Creature;
use ontogeny::encoding::{Genome, LoadError, LoadOptions, grow_grammar, load_creature};
use ontogeny::evolve::config::read_config_source;
use ontogeny::evolve::run::{Run, RunError};
use ontogeny::evolve::settings::{self, RunFlags};
use ontogeny::evolve::store::RunStore;
use ontogeny::lang::{Diagnostic, Source};
use ontogeny::lsystem::{DefineOverride, DeriveOptions, LSystem, print};
use ontogeny::sim::{SimOptions, StepSetting};
use ontogeny::task::flags::TaskFlags;
use ontogeny::task::{Evaluation as Outcome, TaskKind, TaskSpec, WalkerFitness, Watch};
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;

/// The most worker threads `threads=` may ask for, as `--threads` on the command line.
const MAX_THREADS: usize = 1024;

/// A bad-input error: `ValueError` with the command line's message.
fn value_error(message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// A library's diagnostic (a grammar's names its file, line and column) as `ValueError`.
fn diagnostic_error(d: Diagnostic) -> PyErr {
    value_error(d)
}

/// A failure to load a creature as Python sees it.
fn load_error(e: LoadError) -> PyErr {
    match e {
        LoadError::Read { path, source } => {
            let message = format!("cannot read {}: {source}", path.display());
            match source.kind() {
                std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
                _ => PyOSError::new_err(message),
            }
        }
        LoadError::Bad(d) => diagnostic_error(d),
    }
}

/// A run's failure as Python sees it: a file that cannot be read or written is an `OSError`,
/// an interrupted run `KeyboardInterrupt`, anything else (a bad configuration, a run already
/// there, a locked run) a `ValueError`.
fn run_error(e: RunError) -> PyErr {
    match e {
        RunError::Io { path, source } => {
            PyOSError::new_err(format!("{}: {source}", path.display()))
        }
        RunError::Interrupted(e) => interrupted_error(e),
        other => value_error(other),
    }
}

/// Refuses a path that does not exist with `FileNotFoundError`, as Python's `open` does.
fn require_exists(path: &Path) -> PyResult<()> {
    if path.exists() {
        Ok(())
    } else {
        Err(PyFileNotFoundError::new_err(format!(
            "{}: no such file or directory",
            path.display()
        )))
    }
}

/// Issues each of `messages` as a Python `UserWarning`.
fn warn_all(py: Python<'_>, messages: &[String]) -> PyResult<()> {
    let category = py.get_type::<PyUserWarning>();
    for message in messages {
        let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, category.as_any(), &text, 1)?;
    }
    Ok(())
}

/// A local pool of `threads` worker threads (default: one per core), 1 to 1024.
fn thread_pool(threads: Option<usize>) -> PyResult<rayon::ThreadPool> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if !(1..=MAX_THREADS).contains(&n) {
            return Err(value_error(format!(
                "threads must be 1 to {MAX_THREADS}, not {n}"
            )));
        }
        builder = builder.num_threads(n);
    }
    builder
        .build()
        .map_err(|e| PyOSError::new_err(format!("cannot start the worker threads: {e}")))
}

/// A name of one of the library's vocabularies, or `ValueError` listing the names.
fn parse_name<T: std::str::FromStr>(
    what: &str,
    name: &str,
    all: impl IntoIterator<Item = T>,
    spell: fn(T) -> &'static str,
) -> PyResult<T> {
    name.parse::<T>().map_err(|_| {
        let names: Vec<&str> = all.into_iter().map(spell).collect();
        value_error(format!(
            "unknown {what} '{name}' (one of: {})",
            names.join(", ")
        ))
    })
}

fn task_named(name: &str) -> PyResult<TaskKind> {
    parse_name("task", name, TaskKind::ALL, TaskKind::name)
}

fn fitness_named(name: &str) -> PyResult<WalkerFitness> {
    parse_name("fitness", name, WalkerFitness::ALL, WalkerFitness::name)
}

fn setting_named(name: &str) -> PyResult<StepSetting> {
    parse_name("setting", name, StepSetting::ALL, StepSetting::name)
}

/// The derivation options of the keyword arguments shared by `grow` and `derive`, as the
/// command line's development flags give them.
fn derive_options(
    seed: Option<u64>,
    time: Option<f64>,
    dt: Option<f64>,
    env: Option<Vec<(usize, f64)>>,
) -> DeriveOptions {
    DeriveOptions {
        seed,
        time,
        dt,
        env: env.unwrap_or_default(),
        ..DeriveOptions::default()
    }
}

/// How to grow a creature from a grammar: `steps` discrete steps, or the derivation options.
fn load_options(
    steps: Option<u64>,
    seed: Option<u64>,
    time: Option<f64>,
    dt: Option<f64>,
    env: Option<Vec<(usize, f64)>>,
) -> LoadOptions {
    LoadOptions {
        derive: derive_options(seed, time, dt, env),
        steps,
        ..LoadOptions::default()
    }
}

/// The `defines={NAME: VALUE}` keyword as overrides of a grammar's defines (in name order;
/// a value that is not a finite number is a `ValueError`).
fn define_overrides(
    defines: Option<std::collections::BTreeMap<String, f64>>,
) -> PyResult<Vec<DefineOverride>> {
    defines
        .unwrap_or_default()
        .into_iter()
        .map(|(name, value)| {
            if !value.is_finite() {
                return Err(value_error(format!(
                    "defines: the value of {name}, {value}, is not a finite number"
                )));
            }
            Ok(DefineOverride { name, value })
        })
        .collect()
}

/// Compiles grammar `text` with `defines` in place of the values of its defines.
fn grammar_text(text: &str, defines: &[DefineOverride]) -> PyResult<LSystem> {
    LSystem::parse_with(Source::new(TEXT_NAME, text), defines).map_err(diagnostic_error)
}

/// The name a grammar given as text goes by in messages.
const TEXT_NAME: &str = "<string>";

/// A creature: its body (box parts joined by joints) and brain, grown from a grammar, read
/// from a file or developed from a genome.
#[pyclass(name = "Creature", module = "ontogeny", frozen)]
struct PyCreature {
    creature: Arc<Creature>,
    notes: Vec<String>,
}

impl PyCreature {
    fn new(creature: Creature, notes: Vec<String>) -> Self {
        PyCreature {
            creature: Arc::new(creature),
            notes,
        }
    }
}

#[pymethods]
impl PyCreature {
    /// The number of parts (boxes).
    #[getter]
    fn parts(&self) -> usize {
        self.creature.parts.len()
    }

    /// The number of joints.
    #[getter]
    fn joints(&self) -> usize {
        self.creature.joints.len()
    }

    /// The number of neurons of the brain.
    #[getter]
    fn neurons(&self) -> usize {
        self.creature.brain.neurons.len()
    }

    /// Each part's edge lengths (length, thickness, width) in metres: parts × 3.
    #[getter]
    fn sizes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows(self.creature.parts.iter().map(|p| p.size.into())).into_pyarray(py)
    }

    /// Each part's centre in world coordinates (metres; y is up): parts × 3.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows(self.creature.parts.iter().map(|p| p.position.into())).into_pyarray(py)
    }

    /// Each part's orientation as a unit quaternion (w, x, y, z): parts × 4.
    #[getter]
    fn orientations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let flat: Vec<f64> = self
            .creature
            .parts
            .iter()
            .flat_map(|p| {
                let q = p.orientation.quaternion();
                [q.w, q.i, q.j, q.k]
            })
            .collect();
        let n = self.creature.parts.len();
        Array2::from_shape_vec((n, 4), flat)
            .expect("4 numbers per part")
            .into_pyarray(py)
    }

    /// Whether the creature is valid: it has parts and its development reported no error.
    #[getter]
    fn valid(&self) -> bool {
        self.creature.is_valid()
    }

    /// The problems development reported (errors make the creature invalid), one line each.
    #[getter]
    fn problems(&self) -> Vec<String> {
        self.creature
            .problems
            .iter()
            .map(|p| p.to_string())
            .collect()
    }

    /// Notes and warnings from growing it (a grammar without a derivation length, the
    /// builder's warnings), one line each.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }

    /// The creature as JSON, the `creature.json` that `ontogeny grow --out` writes.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&*self.creature).map_err(value_error)
    }

    fn __repr__(&self) -> String {
        format!(
            "Creature(parts={}, joints={}, neurons={}, valid={})",
            self.parts(),
            self.joints(),
            self.neurons(),
            if self.valid() { "True" } else { "False" }
        )
    }
}

/// Rows of three numbers as an n × 3 array.
fn rows(points: impl Iterator<Item = [f64; 3]>) -> Array2<f64> {
    let flat: Vec<f64> = points.flatten().collect();
    let n = flat.len() / 3;
    Array2::from_shape_vec((n, 3), flat).expect("3 numbers per row")
}

/// Grows a creature from grammar text (an `.lsys` file's content), to its last frame, as
/// `ontogeny grow` does.
#[pyfunction]
#[pyo3(signature = (text, *, steps=None, time=None, dt=None, seed=None, env=None, defines=None))]
#[allow(clippy::too_many_arguments)]
fn grow(
    py: Python<'_>,
    text: &str,
    steps: Option<u64>,
    time: Option<f64>,
    dt: Option<f64>,
    seed: Option<u64>,
    env: Option<Vec<(usize, f64)>>,
    defines: Option<std::collections::BTreeMap<String, f64>>,
) -> PyResult<PyCreature> {
    let lsys = grammar_text(text, &define_overrides(defines)?)?;
    let options = load_options(steps, seed, time, dt, env);
    let loaded = interruptible(py, |cancel| {
        let options = LoadOptions {
            cancel: cancel.clone(),
            ..options
        };
        grow_grammar(&lsys, &options, &mut |_| {})
    })?
    .map_err(load_error)?;
    Ok(PyCreature::new(loaded.creature, loaded.notes))
}

/// Reads a creature from a file, as `ontogeny eval FILE` does: an `.lsys` grammar (or a
/// direct genome, grown to its last frame), a `creature.json`, or a graph genome's `.json`.
#[pyfunction]
#[pyo3(signature = (path, *, steps=None, time=None, dt=None, seed=None, env=None, defines=None))]
#[allow(clippy::too_many_arguments)]
fn load(
    py: Python<'_>,
    path: PathBuf,
    steps: Option<u64>,
    time: Option<f64>,
    dt: Option<f64>,
    seed: Option<u64>,
    env: Option<Vec<(usize, f64)>>,
    defines: Option<std::collections::BTreeMap<String, f64>>,
) -> PyResult<PyCreature> {
    require_exists(&path)?;
    let options = LoadOptions {
        defines: define_overrides(defines)?,
        ..load_options(steps, seed, time, dt, env)
    };
    let loaded = interruptible(py, |cancel| {
        let options = LoadOptions {
            cancel: cancel.clone(),
            ..options
        };
        load_creature(&path, &options, &mut |_| {})
    })?
    .map_err(load_error)?;
    Ok(PyCreature::new(loaded.creature, loaded.notes))
}

/// Develops a creature from a genome's text in one of the encodings (`direct`: an `.lsys`
/// file holding an axiom alone; `lsystem`, `continuous`: a run's `best.lsys`; `graph`: a
/// run's `best.json`), within the encoding's default limits, as evolution develops it.
#[pyfunction]
#[pyo3(signature = (text, encoding="direct", *, seed=0))]
fn genome(py: Python<'_>, text: &str, encoding: &str, seed: u64) -> PyResult<PyCreature> {
    let developed: Result<Creature, String> = ontogeny::with_genome!(
        encoding,
        G => {
            let limits = <G as Genome>::Limits::default();
            <G as Genome>::read_text(text, &limits)
                .and_then(|g| py.detach(|| g.develop(&limits, seed)))
                .map_err(|e| e.0)
        },
        |other: &str| Err(format!(
            "unknown encoding '{other}' (one of: {})",
            ontogeny::encoding::ENCODINGS.iter().map(|e| e.name).collect::<Vec<_>>().join(", ")
        ))
    );
    developed
        .map(|c| PyCreature::new(c, Vec::new()))
        .map_err(value_error)
}

/// Derives grammar text as `ontogeny derive` does: a list of frames `(time, modules, env)`,
/// the axiom first: the frame's time (its step in discrete time), its module string as text,
/// and the environment's values.
#[pyfunction]
#[pyo3(signature = (text, *, steps=None, time=None, dt=None, seed=None, env=None, defines=None))]
#[allow(clippy::too_many_arguments)]
fn derive(
    py: Python<'_>,
    text: &str,
    steps: Option<u64>,
    time: Option<f64>,
    dt: Option<f64>,
    seed: Option<u64>,
    env: Option<Vec<(usize, f64)>>,
    defines: Option<std::collections::BTreeMap<String, f64>>,
) -> PyResult<Vec<(f64, String, Vec<f64>)>> {
    let lsys = grammar_text(text, &define_overrides(defines)?)?;
    let options = derive_options(seed, time, dt, env);
    let note = print::check_mode(&lsys, &options, steps, "printing").map_err(diagnostic_error)?;
    warn_all(py, &note.into_iter().collect::<Vec<_>>())?;
    let (frames, fixed) = interruptible(py, |cancel| {
        let mut frames = Vec::new();
        let mut fixed = None;
        lsys.for_each_frame_until(&options, steps, |frame| {
            cancel.check()?;
            if let Some(step) = frame.fixed_since {
                fixed = Some(format!(
                    "fixed point at step {step}: steps {} to {} give the same string, so they \
                     were not derived (the last frame is step {})",
                    step + 1,
                    frame.step,
                    frame.step
                ));
            }
            frames.push((
                frame.t,
                lsys.display(frame.string).to_string(),
                frame.env.values().to_vec(),
            ));
            Ok::<bool, Diagnostic>(true)
        })
        .map(|()| (frames, fixed))
    })?
    .map_err(diagnostic_error)?;
    warn_all(py, &fixed.into_iter().collect::<Vec<_>>())?;
    Ok(frames)
}

/// The outcome of an evaluation: its fitness, status, the terms behind the fitness and, when
/// it was recorded, the parts' trajectory.
#[pyclass(name = "Evaluation", module = "ontogeny", frozen)]
struct PyEvaluation {
    outcome: Outcome,
}

#[pymethods]
impl PyEvaluation {
    /// The task's name.
    #[getter]
    fn task(&self) -> String {
        self.outcome.task.clone()
    }

    /// The fitness; -999999 unless the status is `ok`.
    #[getter]
    fn fitness(&self) -> f64 {
        self.outcome.fitness
    }

    /// How it ended: `ok`, `unstable`, `exploded`, `self-intersecting`, `too-tall` or
    /// `invalid`.
    #[getter]
    fn status(&self) -> &'static str {
        self.outcome.status.name()
    }

    /// The terms behind the fitness, by name.
    #[getter]
    fn terms<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for (k, v) in &self.outcome.terms {
            dict.set_item(k, v)?;
        }
        Ok(dict)
    }

    /// What went wrong, when something did.
    #[getter]
    fn message(&self) -> Option<String> {
        self.outcome.message.clone()
    }

    /// Every part's centre at each recorded moment (frames × parts × 3, metres), or `None`
    /// when the evaluation was not recorded.
    #[getter]
    fn trajectory<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray3<f64>>> {
        let samples = &self.outcome.recording;
        let parts = samples.first()?.parts.len();
        let flat: Vec<f64> = samples
            .iter()
            .flat_map(|s| {
                (0..parts).flat_map(move |i| {
                    let p = s.parts.get(i).map_or([f64::NAN; 3], |(c, _)| (*c).into());
                    p.into_iter()
                })
            })
            .collect();
        Array3::from_shape_vec((samples.len(), parts, 3), flat)
            .ok()
            .map(|a| a.into_pyarray(py))
    }

    /// The simulated time of each recorded moment (seconds), or `None` when the evaluation
    /// was not recorded.
    #[getter]
    fn times<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        let samples = &self.outcome.recording;
        if samples.is_empty() {
            return None;
        }
        Some(Array1::from_iter(samples.iter().map(|s| s.t)).into_pyarray(py))
    }

    /// The evaluation as JSON, as `ontogeny eval --json` prints it (without the recording).
    fn to_json(&self) -> PyResult<String> {
        let mut shown = self.outcome.clone();
        shown.recording.clear();
        serde_json::to_string_pretty(&shown).map_err(value_error)
    }

    fn __repr__(&self) -> String {
        format!(
            "Evaluation(task='{}', fitness={}, status='{}')",
            self.outcome.task,
            self.outcome.fitness,
            self.outcome.status.name()
        )
    }
}

/// The task's specification from `evaluate`'s keyword arguments, built and checked as
/// `ontogeny eval` builds it from the same flags ([`TaskFlags::spec`]); the arguments the task
/// does not use are warned about, as `eval` does.
fn task_spec(
    py: Python<'_>,
    task: &str,
    seconds: Option<f64>,
    fitness: Option<&str>,
    setting: &str,
    target: Option<[f64; 3]>,
) -> PyResult<TaskSpec> {
    let flags = TaskFlags {
        task: task_named(task)?,
        seconds,
        fitness: fitness.map(fitness_named).transpose()?,
        activation: None,
        target,
        projectile_size: None,
        projectile_density: None,
    };
    let sim = setting_named(setting)?.apply(&SimOptions::default());
    sim.check()
        .map_err(|e| value_error(e.for_flag("setting")))?;
    let spec = flags.spec(sim).map_err(|e| {
        let name = match e.key {
            "seconds" | "max_seconds" => "seconds",
            key => key,
        };
        value_error(e.for_flag(name))
    })?;
    let ignored: Vec<String> = flags
        .inapplicable()
        .into_iter()
        .map(|m| format!("{}; ignored", m.replace("--", "")))
        .collect();
    warn_all(py, &ignored)?;
    Ok(spec)
}

/// Evaluates a creature on a task, as `ontogeny eval FILE --task TASK` does, with the same
/// result bit for bit.
#[pyfunction]
#[pyo3(signature = (creature, task="walker", *, seconds=None, fitness=None, setting="default", target=None, record=false))]
#[allow(clippy::too_many_arguments)]
fn evaluate(
    py: Python<'_>,
    creature: &PyCreature,
    task: &str,
    seconds: Option<f64>,
    fitness: Option<&str>,
    setting: &str,
    target: Option<[f64; 3]>,
    record: bool,
) -> PyResult<PyEvaluation> {
    let spec = task_spec(py, task, seconds, fitness, setting, target)?;
    let body = Arc::clone(&creature.creature);
    let outcome = interruptible(py, |cancel| watched(&spec, &body, record, cancel))?
        .map_err(interrupted_error)?;
    Ok(PyEvaluation { outcome })
}

/// `spec`'s evaluation of `creature`, stopped by `cancel`.
fn watched(
    spec: &TaskSpec,
    creature: &Creature,
    record: bool,
    cancel: &Cancel,
) -> Result<Outcome, ontogeny::cancel::Interrupted> {
    let watch = Watch {
        record,
        progress: &mut |_| {},
        cancel: Some(cancel),
    };
    spec.evaluate_watched(creature, watch)
}

/// Evaluates many creatures on one task in parallel (on `threads` worker threads, default one
/// per core), without holding the GIL; the results are in the creatures' order and equal to
/// `evaluate`'s one by one.
#[pyfunction]
#[pyo3(signature = (creatures, task="walker", *, threads=None, seconds=None, fitness=None, setting="default", target=None, record=false))]
#[allow(clippy::too_many_arguments)]
fn evaluate_many(
    py: Python<'_>,
    creatures: Vec<PyRef<'_, PyCreature>>,
    task: &str,
    threads: Option<usize>,
    seconds: Option<f64>,
    fitness: Option<&str>,
    setting: &str,
    target: Option<[f64; 3]>,
    record: bool,
) -> PyResult<Vec<PyEvaluation>> {
    let spec = task_spec(py, task, seconds, fitness, setting, target)?;
    let pool = thread_pool(threads)?;
    let bodies: Vec<Arc<Creature>> = creatures.iter().map(|c| Arc::clone(&c.creature)).collect();
    drop(creatures);
    let outcomes: Vec<Outcome> = interruptible(py, |cancel| {
        pool.install(|| {
            bodies
                .par_iter()
                .map(|c| watched(&spec, c, record, cancel))
                .collect::<Result<_, _>>()
        })
    })?
    .map_err(interrupted_error)?;
    Ok(outcomes
        .into_iter()
        .map(|outcome| PyEvaluation { outcome })
        .collect())
}

/// Runs an evolution into the directory `out`, as `ontogeny evolve --out OUT` does with the
/// same settings (a config file, and the keyword arguments over it as the command line's
/// flags); returns the run's directory.
#[pyfunction]
#[pyo3(signature = (config=None, *, out, encoding=None, task=None, fitness=None, preset=None, pop=None, gens=None, seed=None, seconds=None, setting=None, threads=None, init=None, verify_best=true, cache=true, progress=false))]
#[allow(clippy::too_many_arguments)]
fn evolve(
    py: Python<'_>,
    config: Option<PathBuf>,
    out: PathBuf,
    encoding: Option<&str>,
    task: Option<&str>,
    fitness: Option<&str>,
    preset: Option<&str>,
    pop: Option<usize>,
    gens: Option<usize>,
    seed: Option<u64>,
    seconds: Option<f64>,
    setting: Option<&str>,
    threads: Option<usize>,
    init: Option<PathBuf>,
    verify_best: bool,
    cache: bool,
    progress: bool,
) -> PyResult<PathBuf> {
    if let Some(path) = &config {
        require_exists(path)?;
    }
    if let Some(path) = &init {
        require_exists(path)?;
    }
    let encoding = match encoding {
        Some(name) => Some(
            ontogeny::encoding::encoding_named(name)
                .ok_or_else(|| {
                    value_error(format!(
                        "unknown encoding '{name}' (one of: {})",
                        ontogeny::encoding::ENCODINGS
                            .iter()
                            .map(|e| e.name)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ))
                })?
                .name,
        ),
        None => None,
    };
    let preset = preset
        .map(|name| {
            ontogeny::evolve::ga::Preset::named(name)
                .ok_or_else(|| value_error(format!("unknown preset '{name}'")))
        })
        .transpose()?;
    let flags = RunFlags {
        preset,
        population: pop,
        generations: gens,
        task: task.map(task_named).transpose()?,
        fitness: fitness.map(fitness_named).transpose()?,
        seconds,
        setting: setting.map(setting_named).transpose()?,
        target: None,
    };
    let pool = thread_pool(threads)?;
    let source = config
        .as_deref()
        .map(read_config_source)
        .transpose()
        .map_err(diagnostic_error)?;
    let name = settings::new_run_encoding(encoding, source.as_deref()).map_err(diagnostic_error)?;
    let start = NewRun {
        out: &out,
        source: source.as_deref(),
        flags: &flags,
        init: init.as_deref(),
        seed,
        verify_best,
        cache,
        progress,
    };
    interruptible(py, |cancel| {
        pool.install(|| {
            ontogeny::with_genome!(
                name.as_str(),
                G => start.run::<G>(cancel),
                |other: &str| Err(value_error(format!("unknown encoding '{other}'")))
            )
        })
    })??;
    Ok(out)
}

/// What `evolve` starts a run with.
struct NewRun<'a> {
    out: &'a Path,
    source: Option<&'a ontogeny::lang::Source>,
    flags: &'a RunFlags,
    init: Option<&'a Path>,
    seed: Option<u64>,
    verify_best: bool,
    cache: bool,
    progress: bool,
}

impl NewRun<'_> {
    /// Starts the run and runs it to its last generation, a line per generation on standard
    /// error with `progress`, until `cancel` stops it.
    fn run<G: Genome>(&self, cancel: &Cancel) -> PyResult<()> {
        let (config, init) = settings::new_run::<G>(
            self.source,
            self.flags,
            self.init,
            self.seed,
            self.verify_best,
            self.cache,
        )
        .map_err(diagnostic_error)?;
        let mut run = Run::<G>::start(self.out, config, init.as_ref().map(|s| s.text()))
            .map_err(run_error)?;
        resume::run_to_end(&mut run, self.progress, cancel)
    }
}

/// A run directory's records, read from its store (`run.sqlite`) read-only, as `ontogeny
/// runs show` reads them.
#[pyclass(name = "Run", module = "ontogeny", subclass, frozen)]
struct PyRun {
    dir: PathBuf,
}

impl PyRun {
    fn store(&self) -> PyResult<RunStore> {
        RunStore::open_read_only(&self.dir.join("run.sqlite")).map_err(value_error)
    }
}

#[pymethods]
impl PyRun {
    /// Opens the run in the directory `path` (refused if it holds no run).
    #[new]
    fn new(path: PathBuf) -> PyResult<Self> {
        require_exists(&path)?;
        let run = PyRun { dir: path };
        run.store()?;
        Ok(run)
    }

    /// The run's directory.
    #[getter]
    fn path(&self) -> PathBuf {
        self.dir.clone()
    }

    /// The run's settings: `encoding`, `task`, `seed`, `version` and `config` (the text of
    /// its `config.toml`).
    fn settings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let run = self.store()?.run().map_err(value_error)?;
        let dict = PyDict::new(py);
        dict.set_item("encoding", run.encoding)?;
        dict.set_item("task", run.task)?;
        dict.set_item("seed", run.seed)?;
        dict.set_item("version", run.version)?;
        dict.set_item("config", run.config)?;
        Ok(dict)
    }

    /// Every generation's record, a dict each (`index`, `best`, `mean`, `median`, `sd`,
    /// `valid_fraction`, `evaluations`, ...), as `ontogeny runs show --json` prints them; a
    /// number that is not one (the mean of a generation without valid individuals) is
    /// `None`.
    fn generations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let records = self.store()?.generations().map_err(value_error)?;
        let json = serde_json::to_string(&records).map_err(value_error)?;
        py.import("json")?.call_method1("loads", (json,))
    }

    /// The individuals of one generation (default: every generation's), a dict each with the
    /// run store's columns: `generation`, `individual`, `parents`, `operator`, `genome_text`,
    /// `fitness`, `status`, `terms`, `parts`, `joints`, `neurons`, `reused`.
    #[pyo3(signature = (generation=None))]
    fn individuals<'py>(
        &self,
        py: Python<'py>,
        generation: Option<u32>,
    ) -> PyResult<Bound<'py, PyList>> {
        let store = self.store()?;
        let generations: Vec<u32> = match generation {
            Some(g) => vec![g],
            None => match store.last_generation().map_err(value_error)? {
                Some(last) => (0..=last).collect(),
                None => Vec::new(),
            },
        };
        let json = py.import("json")?;
        let list = PyList::empty(py);
        for g in generations {
            for i in store.individuals(g).map_err(value_error)? {
                let dict = PyDict::new(py);
                dict.set_item("generation", i.generation)?;
                dict.set_item("individual", i.index)?;
                dict.set_item("parents", i.parents)?;
                dict.set_item("operator", i.operator)?;
                dict.set_item("genome_text", i.genome_text)?;
                dict.set_item("fitness", i.fitness)?;
                dict.set_item("status", i.status)?;
                dict.set_item("terms", json.call_method1("loads", (i.terms_json,))?)?;
                dict.set_item("parts", i.parts)?;
                dict.set_item("joints", i.joints)?;
                dict.set_item("neurons", i.neurons)?;
                dict.set_item("reused", i.reused)?;
                list.append(dict)?;
            }
        }
        Ok(list)
    }

    fn __repr__(&self) -> String {
        format!("Run('{}')", self.dir.display())
    }
}

/// The compiled part of the `ontogeny` package.
#[pymodule]
fn _ontogeny(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<PyCreature>()?;
    m.add_class::<PyEvaluation>()?;
    m.add_class::<PyRun>()?;
    m.add_function(wrap_pyfunction!(grow, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(genome, m)?)?;
    m.add_function(wrap_pyfunction!(derive, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_many, m)?)?;
    m.add_function(wrap_pyfunction!(evolve, m)?)?;
    m.add_function(wrap_pyfunction!(resume::resume, m)?)?;
    Ok(())
}
