//! Evaluations from Python: `evaluate`, `evaluate_many` and the `Evaluation` class.

use crate::common::{
    diagnostic_error, load_error, require_exists, setting_named, task_named, thread_pool,
    value_error, warn_all,
};
use crate::creature::PyCreature;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::interrupt::{interrupted_error, interruptible};
use numpy::IntoPyArray;
use numpy::ndarray::{Array1, Array3};
use numpy::{PyArray1, PyArray3};
use ontogeny::cancel::Cancel;
use ontogeny::creature::Creature;
use ontogeny::develop::{BuildOptions, Seedling};
use ontogeny::encoding::{LoadError, LoadOptions, Loaded, load_creature};
use ontogeny::evolve::evaluator::Evaluator;
use ontogeny::evolve::habitats::{
    Growth, evaluate_grown_in_habitats, grammar_in_habitats, recorded_walk,
};
use ontogeny::front::flags::{TaskFlags, option_of};
use ontogeny::lang::suggest::did_you_mean;
use ontogeny::lsystem::{DeriveOptions, LSystem};
use ontogeny::run::champion::ChampionRecord;
use ontogeny::run::config::read_task_config;
use ontogeny::sim::knobs::{Knob, Value, knob};
use ontogeny::sim::{ActuatorModel, JointModel, KNOBS, SimOptions, StrengthFrom};
use ontogeny::task::{
    Evaluation as Outcome, GrowError, TaskSpec, Watch, check_continuous, keyword_refusal,
};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyInt};
use rayon::prelude::*;

/// The outcome of an evaluation: its fitness, status, the terms behind the fitness and, when
/// it was recorded, the parts' trajectory.
#[pyclass(name = "Evaluation", module = "ontogeny", frozen)]
pub(crate) struct PyEvaluation {
    outcome: Outcome,
}

#[pymethods]
impl PyEvaluation {
    /// The task's name.
    #[getter]
    fn task(&self) -> String {
        self.outcome.task.clone()
    }

    /// The fitness; -999999 unless the status is `ok` (0 for a walker that never came to rest).
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

    /// Each habitat's and trial's walk, in the order the task lists them (habitat by habitat),
    /// a dict each: `name` (the habitat's), `trial` (from 0), `parts` and `joints` (of the
    /// creature walked there), `fitness`, `status`, `terms`, and `message` when something went
    /// wrong; empty for a task without habitats or trials.
    #[getter]
    fn habitats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let json = serde_json::to_string(self.outcome.units()).map_err(value_error)?;
        py.import("json")?.call_method1("loads", (json,))
    }

    /// Every part's centre at each recorded moment (frames × parts × 3, metres), or `None`
    /// when the evaluation was not recorded. `parts` counts every part the creature had at
    /// any moment, by id: a body that grows during the walk has rows of NaN for a part at
    /// the moments before it appeared.
    #[getter]
    fn trajectory<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray3<f64>>> {
        let samples = &self.outcome.recording;
        let parts = samples.iter().map(|s| s.parts.len()).max()?;
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

/// The task's keyword arguments that `evaluate` and `evaluate_many` share.
pub(crate) struct TaskArgs<'a, 'py> {
    task: &'a str,
    config: Option<PathBuf>,
    habitat: Option<&'a str>,
    seconds: Option<f64>,
    fitness: Option<&'a str>,
    setting: &'a str,
    sim: Option<&'a Bound<'py, PyDict>>,
    target: Option<[f64; 3]>,
}

impl TaskArgs<'_, '_> {
    /// The task's specification, built and checked as `ontogeny eval` builds it from the same
    /// flags ([`TaskFlags::spec`]). A keyword of a setting the task does not read (the
    /// registry's [`ontogeny::task::Task::KEYWORDS`]: `target=` but for aim) is a `ValueError`
    /// naming the task. `fitness=` is a formula's name or an expression of the task's terms,
    /// checked as `--fitness` is.
    pub(crate) fn spec(&self) -> PyResult<TaskSpec> {
        if let Some(config) = &self.config {
            let given = [
                ("task=", self.task != "walker"),
                ("seconds=", self.seconds.is_some()),
                ("fitness=", self.fitness.is_some()),
                ("setting=", self.setting != "default"),
                ("sim=", self.sim.is_some()),
                ("target=", self.target.is_some()),
            ];
            let clashing: Vec<&str> = given.iter().filter(|g| g.1).map(|g| g.0).collect();
            if !clashing.is_empty() {
                return Err(value_error(format!(
                    "config={} gives the task's settings; {} cannot be given with it (set it in \
                     the config's [task] table)",
                    config.display(),
                    clashing.join(", ")
                )));
            }
            return read_task_config(config).map_err(diagnostic_error);
        }
        if let Some(name) = self.habitat {
            return Err(value_error(format!(
                "habitat='{name}' names one of a config's [[task.habitats]]: give config= too"
            )));
        }
        let task = task_named(self.task)?;
        let given = [
            ("seconds", self.seconds.is_some()),
            ("fitness", self.fitness.is_some()),
            ("target", self.target.is_some()),
        ];
        for (keyword, _) in given.iter().filter(|(_, given)| *given) {
            if let Some(refusal) = keyword_refusal(keyword, &format!("{keyword}="), task.info()) {
                return Err(value_error(refusal));
            }
        }
        let flags = TaskFlags {
            task,
            seconds: self.seconds,
            fitness: self.fitness.map(str::to_string),
            activation: None,
            target: self.target,
            projectile_size: None,
            projectile_density: None,
        };
        let sim = sim_options(self.setting, self.sim)?;
        flags
            .spec(sim)
            .map_err(|e| value_error(e.for_flag(&option_of(e.key))))
    }
}

/// Declares the Python function `$name`, taking `$first`, the task's keyword arguments
/// ([`TaskArgs`], `$args` in its body), `$extra` keywords and `record`: one signature for
/// `evaluate` and `evaluate_many`, as `help()` and the stubs show it.
macro_rules! evaluating_function {
    ($(#[$doc:meta])* fn $name:ident($py:ident, $first:ident: $ty:ty $(, $extra:ident: $ety:ty = $default:tt)*; $args:ident, $record:ident) -> $ret:ty $body:block) => {
        $(#[$doc])*
        #[pyfunction]
        #[pyo3(signature = ($first, task="walker", *, $($extra=$default,)* seconds=None, fitness=None, setting="default", sim=None, target=None, config=None, habitat=None, record=false))]
        #[allow(clippy::too_many_arguments)]
        pub(crate) fn $name(
            $py: Python<'_>,
            $first: $ty,
            task: &str,
            $($extra: $ety,)*
            seconds: Option<f64>,
            fitness: Option<&str>,
            setting: &str,
            sim: Option<&Bound<'_, PyDict>>,
            target: Option<[f64; 3]>,
            config: Option<PathBuf>,
            habitat: Option<&str>,
            $record: bool,
        ) -> $ret {
            let $args = TaskArgs { task, config, habitat, seconds, fitness, setting, sim, target };
            $body
        }
    };
}

/// The simulator's options of `setting=` and `sim=`: the named step setting, each of `sim`'s
/// keys (a `[task.sim]` key of the table of knobs, [`KNOBS`], or its older name) over it,
/// then the range check of every knob. An error names the value as `sim['key']`.
fn sim_options(setting: &str, sim: Option<&Bound<'_, PyDict>>) -> PyResult<SimOptions> {
    let mut options = setting_named(setting)?.apply(&SimOptions::default());
    let mut given: Vec<&'static str> = Vec::new();
    for (key, value) in sim.into_iter().flat_map(|sim| sim.iter()) {
        let Ok(key) = key.extract::<String>() else {
            return Err(value_error(format!(
                "sim's keys must be strings, not {}",
                key.repr()?
            )));
        };
        let Some(knob) = knob(&key) else {
            let keys: Vec<&str> = KNOBS.iter().map(|k| k.key).collect();
            return Err(value_error(format!(
                "unknown key '{key}' in sim{}; its keys are {}",
                did_you_mean(&key, keys.iter().copied()),
                keys.join(", ")
            )));
        };
        if given.contains(&knob.key) {
            return Err(value_error(format!(
                "sim gives {} twice ({} is its older name)",
                knob.key,
                knob.older_key.unwrap_or_default()
            )));
        }
        given.push(knob.key);
        let value = knob_value(knob, (knob.get)(&options), &value)?;
        (knob.set)(&mut options, value);
    }
    options
        .check()
        .map_err(|e| value_error(e.for_flag(&format!("sim['{}']", e.key))))?;
    Ok(options)
}

/// `value` as a value of `knob`, of the kind of `like` (the knob's value now): a number for a
/// real, a whole number for a count (out of range: the knob's range error), `True` or `False`
/// for a switch, one of its names for a model.
fn knob_value(knob: &Knob, like: Value, value: &Bound<'_, PyAny>) -> PyResult<Value> {
    let wrong = |wanted: &str| -> PyResult<Value> {
        Err(value_error(format!(
            "sim['{}'] must be {wanted}, not {}",
            knob.key,
            value.repr()?
        )))
    };
    let is_bool = value.is_instance_of::<PyBool>();
    match like {
        Value::Real(_) if is_bool => wrong("a number"),
        Value::Real(_) => match value.extract::<f64>() {
            Ok(x) => Ok(Value::Real(x)),
            Err(_) => wrong("a number"),
        },
        Value::Count(_) if is_bool || !value.is_instance_of::<PyInt>() => wrong("a whole number"),
        Value::Count(_) => match value.extract::<usize>() {
            Ok(n) => Ok(Value::Count(n)),
            Err(_) => Err(value_error(format!(
                "sim['{}'] must be {}, not {}",
                knob.key,
                knob.range_words(),
                value.str()?
            ))),
        },
        Value::Switch(_) if is_bool => Ok(Value::Switch(value.extract()?)),
        Value::Switch(_) => wrong("True or False"),
        Value::Joints(_) => {
            named(knob, value, &JointModel::ALL, JointModel::name).map(Value::Joints)
        }
        Value::Actuator(_) => {
            named(knob, value, &ActuatorModel::ALL, ActuatorModel::name).map(Value::Actuator)
        }
        Value::StrengthFrom(_) => {
            named(knob, value, &StrengthFrom::ALL, StrengthFrom::name).map(Value::StrengthFrom)
        }
    }
}

/// The choice of `all` that `value` names, or an error listing the names and the closest.
fn named<T: Copy>(
    knob: &Knob,
    value: &Bound<'_, PyAny>,
    all: &[T],
    name: fn(T) -> &'static str,
) -> PyResult<T> {
    let names: Vec<&str> = all.iter().map(|v| name(*v)).collect();
    let text = value.extract::<String>().ok();
    if let Some(found) = all
        .iter()
        .copied()
        .find(|v| Some(name(*v)) == text.as_deref())
    {
        return Ok(found);
    }
    let hint = text.map_or(String::new(), |t| did_you_mean(&t, names.iter().copied()));
    Err(value_error(format!(
        "sim['{}'] must be one of {}, not {}{hint}",
        knob.key,
        names.join(", "),
        value.repr()?
    )))
}

evaluating_function! {
    /// Evaluates a creature on a task, as `ontogeny eval FILE --task TASK` does, with the same
    /// result bit for bit. Given a file's path in place of a creature, grows the file in each
    /// habitat of `config=` (with the habitat's chemical array), as `ontogeny eval FILE
    /// --config CONFIG` does.
    fn evaluate(py, creature: &Bound<'_, PyAny>; args, record) -> PyResult<PyEvaluation> {
        let spec = args.spec()?;
        if spec.develop.during() {
            return evaluate_growing(py, creature, &args, &spec, record);
        }
        let creatures = match creature.cast::<PyCreature>() {
            Ok(creature) => {
                args.only(&spec)?;
                let body = Arc::clone(&creature.get().creature);
                vec![(*body).clone(); spec.habitat_count()]
            }
            Err(_) => {
                let Ok(path) = creature.extract::<PathBuf>() else {
                    return Err(PyTypeError::new_err(format!(
                        "evaluate takes a Creature or a file's path, not {}",
                        creature.get_type().name()?
                    )));
                };
                require_exists(&path)?;
                grown_in_habitats(py, &path, &spec)?
            }
        };
        let only = args.habitat_index(&spec)?;
        let outcome = interruptible(py, |cancel| watched(&spec, &creatures, None, only, record, cancel))?
            .map_err(interrupted_error)?;
        Ok(PyEvaluation { outcome })
    }
}

/// `evaluate` of a grammar that develops during the walk (`develop = "during"` in
/// `config=`), as `ontogeny eval FILE --config CONFIG` does: the creature at t₀ walks and
/// grows. It takes the path of an `.lsys` file in continuous time, on the walker; with
/// habitats or trials, the grammar develops in each habitat's array and every unit walks it
/// (those of `habitat=` alone, when given).
fn evaluate_growing(
    py: Python<'_>,
    creature: &Bound<'_, PyAny>,
    args: &TaskArgs<'_, '_>,
    spec: &TaskSpec,
    record: bool,
) -> PyResult<PyEvaluation> {
    let refuse = |why: String| Err(value_error(format!("develop = \"during\": {why}")));
    let Ok(path) = creature.extract::<PathBuf>() else {
        return refuse(format!(
            "a grammar grows during the walk: give the path of its .lsys file, not a {}",
            creature.get_type().name()?
        ));
    };
    require_exists(&path)?;
    spec.check_growing().map_err(value_error)?;
    let only = args.habitat_index(spec)?;
    if path.extension().is_none_or(|e| e != "lsys") {
        return refuse(format!(
            "{} is not an L-system file (.lsys): only a grammar grows",
            path.display()
        ));
    }
    let seedling = Seedling {
        lsys: Arc::new(LSystem::from_path(&path).map_err(diagnostic_error)?),
        derive: DeriveOptions::default(),
        build: BuildOptions::default(),
    };
    check_continuous(&seedling, &path.display().to_string()).map_err(value_error)?;
    if !spec.is_plain() {
        let (creatures, seedlings) = grammar_in_habitats(spec, &seedling)
            .map_err(|e| value_error(format!("{}: {e}", path.display())))?;
        // The trials' draws are keyed by the grammar's text, as a run keys its genome's: a
        // champion file's text without the record above it.
        let text = ontogeny::input::read_to_string(&path)
            .map_err(|e| value_error(format!("cannot read {}: {e}", path.display())))?;
        let growth = Growth::of(&seedlings, ChampionRecord::genome_text(&text));
        let outcome = interruptible(py, |cancel| {
            watched(spec, &creatures, growth, only, record, cancel)
        })?
        .map_err(interrupted_error)?;
        return Ok(PyEvaluation { outcome });
    }
    let outcome = interruptible(py, |cancel| {
        let watch = Watch {
            record,
            progress: &mut |_| {},
            cancel: Some(cancel),
        };
        spec.evaluate_grown_job(&seedling, None, watch)
    })?;
    match outcome {
        Ok(outcome) => Ok(PyEvaluation { outcome }),
        Err(GrowError::Interrupted(i)) => Err(interrupted_error(i)),
        Err(e) => Err(value_error(e)),
    }
}

/// The creatures the file at `path` grows into, one per habitat of `spec` (one without
/// habitats), each grown from the habitat's chemical array
/// ([`LoadOptions::habitat_environment`]) as `ontogeny eval FILE --config` grows them; the
/// notes of growing are `UserWarning`s. Ctrl-C stops it.
fn grown_in_habitats(py: Python<'_>, path: &Path, spec: &TaskSpec) -> PyResult<Vec<Creature>> {
    let loaded = interruptible(py, |cancel| {
        (0..spec.habitat_count())
            .map(|h| {
                let options = LoadOptions {
                    habitat_environment: spec.habitat_environment(h).map(<[f64]>::to_vec),
                    cancel: cancel.clone(),
                    ..LoadOptions::default()
                };
                load_creature(path, &options, &mut |_| {})
            })
            .collect::<Result<Vec<Loaded>, LoadError>>()
    })?
    .map_err(load_error)?;
    let notes: Vec<String> = loaded.iter().flat_map(|l| l.notes.clone()).collect();
    warn_all(py, &notes)?;
    Ok(loaded.into_iter().map(|l| l.creature).collect())
}

impl TaskArgs<'_, '_> {
    /// The index of the habitat `habitat=` names in `spec` (a `ValueError` listing the
    /// habitats when it names none).
    fn habitat_index(&self, spec: &TaskSpec) -> PyResult<Option<usize>> {
        self.habitat
            .map(|name| spec.habitat_named(name).map_err(value_error))
            .transpose()
    }

    /// [`TaskArgs::habitat_index`], and that a creature already grown can walk in the
    /// habitats evaluated: none of them may set the chemical array its body would grow in.
    fn only(&self, spec: &TaskSpec) -> PyResult<Option<usize>> {
        let only = self.habitat_index(spec)?;
        for h in (0..spec.habitat_count()).filter(|h| only.is_none_or(|o| o == *h)) {
            if let Some(values) = spec.habitat_environment(h) {
                return Err(value_error(format!(
                    "habitat '{}' sets the chemical array a creature grows in ({values:?}); a \
                     creature already grown cannot grow again there: evaluate its file \
                     (evaluate(PATH, config=...) grows it in each habitat, as `ontogeny eval \
                     FILE --config` does), or grow it with env= and evaluate it in habitats \
                     that set none",
                    spec.habitat_name(h)
                )));
            }
        }
        Ok(only)
    }
}

/// `spec`'s evaluation of `creatures` (one per habitat of `spec`), stopped by `cancel`: with
/// habitats, each habitat's walks (or those of habitat `only` alone), combined, as `ontogeny
/// eval --config` does; recorded, the first walk evaluated is the recording.
pub(crate) fn watched(
    spec: &TaskSpec,
    creatures: &[Creature],
    growth: Option<Growth<'_>>,
    only: Option<usize>,
    record: bool,
    cancel: &Cancel,
) -> Result<Outcome, ontogeny::cancel::Interrupted> {
    if spec.is_plain() {
        let watch = Watch {
            record,
            progress: &mut |_| {},
            cancel: Some(cancel),
        };
        return spec.evaluate_watched(&creatures[0], watch);
    }
    let mut outcome =
        evaluate_grown_in_habitats(spec, creatures, growth, 0, only, Evaluator::Local, cancel)?;
    if record {
        outcome.recording = recorded_walk(spec, creatures, growth, only.unwrap_or(0))?
            .evaluation
            .recording;
    }
    Ok(outcome)
}

evaluating_function! {
    /// Evaluates many creatures on one task in parallel (on `threads` worker threads, default
    /// one per core), without holding the GIL; the results are in the creatures' order and
    /// equal to `evaluate`'s one by one.
    fn evaluate_many(
        py,
        creatures: Vec<PyRef<'_, PyCreature>>,
        threads: Option<usize> = None;
        args,
        record
    ) -> PyResult<Vec<PyEvaluation>> {
        let spec = args.spec()?;
        let only = args.only(&spec)?;
        let pool = thread_pool(threads)?;
        let bodies: Vec<Arc<Creature>> = creatures.iter().map(|c| Arc::clone(&c.creature)).collect();
        drop(creatures);
        let outcomes: Vec<Outcome> = interruptible(py, |cancel| {
            pool.install(|| {
                bodies
                    .par_iter()
                    .map(|c| watched(&spec, &vec![(**c).clone(); spec.habitat_count()], None, only, record, cancel))
                    .collect::<Result<_, _>>()
            })
        })?
        .map_err(interrupted_error)?;
        Ok(outcomes
            .into_iter()
            .map(|outcome| PyEvaluation { outcome })
            .collect())
    }
}
