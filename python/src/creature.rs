//! Creatures from Python: `grow`, `load`, `genome`, `genome_habitats` and `derive`, and the
//! `Creature` class.

use crate::common::{diagnostic_error, load_error, require_exists, value_error, warn_all};
use pyo3::exceptions::{PyDeprecationWarning, PyOSError, PyTypeError};
use std::ffi::CString;
use std::path::PathBuf;
use std::sync::Arc;

use crate::interrupt::interruptible;
use numpy::IntoPyArray;
use numpy::PyArray2;
use numpy::ndarray::Array2;
use ontogeny::creature::Creature;
use ontogeny::encoding::{Genome, LoadError, LoadOptions, Loaded, grow_grammar, load_creature};
use ontogeny::front::habitats::{GenomeHabitatsError, genome_in_habitats};
use ontogeny::lang::{Diagnostic, Source};
use ontogeny::lsystem::{DefineOverride, DeriveOptions, LSystem, Overrides, print};
use pyo3::prelude::*;

/// The derivation options of the keyword arguments shared by `grow` and `derive`, as the
/// command line's development flags give them.
pub(crate) fn derive_options(
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

/// The grammar's seed given as `grammar_seed=`, or under its old name `seed=` (still read,
/// with a `DeprecationWarning` saying what the command line's note on `--seed` says); both
/// at once are a `TypeError`.
pub(crate) fn given_grammar_seed(
    py: Python<'_>,
    grammar_seed: Option<u64>,
    seed: Option<u64>,
) -> PyResult<Option<u64>> {
    match (grammar_seed, seed) {
        (Some(_), Some(_)) => Err(PyTypeError::new_err(
            "grammar_seed= and seed= are one argument (seed= is its old name): give one",
        )),
        (None, Some(seed)) => {
            let category = py.get_type::<PyDeprecationWarning>();
            let message = CString::new(format!(
                "seed={seed} is read as grammar_seed={seed}, the seed of the grammar's \
                 stochastic rules (seed= is the genetic algorithm's seed, in evolve and compare)"
            ))
            .unwrap_or_default();
            PyErr::warn(py, category.as_any(), &message, 1)?;
            Ok(Some(seed))
        }
        (given, None) => Ok(given),
    }
}

/// How to grow a creature from a grammar: `steps` discrete steps, or the derivation options.
pub(crate) fn load_options(
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
pub(crate) fn define_overrides(
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

/// Compiles grammar `text` with `defines` in place of the values of its defines and `seed` in
/// place of its `seed:` (as `--define` and `--grammar-seed` do).
pub(crate) fn grammar_text(
    text: &str,
    defines: Vec<DefineOverride>,
    seed: Option<u64>,
) -> PyResult<LSystem> {
    LSystem::parse_with(Source::new(TEXT_NAME, text), &Overrides { defines, seed })
        .map_err(diagnostic_error)
}

/// The name a grammar given as text goes by in messages.
pub(crate) const TEXT_NAME: &str = "<string>";

/// A creature: its body (box parts joined by joints) and brain, grown from a grammar, read
/// from a file or developed from a genome.
#[pyclass(name = "Creature", module = "ontogeny", frozen)]
pub(crate) struct PyCreature {
    pub(crate) creature: Arc<Creature>,
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
pub(crate) fn rows(points: impl Iterator<Item = [f64; 3]>) -> Array2<f64> {
    let flat: Vec<f64> = points.flatten().collect();
    let n = flat.len() / 3;
    Array2::from_shape_vec((n, 3), flat).expect("3 numbers per row")
}

/// The keyword arguments of development that `grow`, `load` and `derive` share, as the
/// command line's development flags give them.
pub(crate) struct Growth {
    steps: Option<u64>,
    time: Option<f64>,
    dt: Option<f64>,
    grammar_seed: Option<u64>,
    env: Option<Vec<(usize, f64)>>,
    defines: Option<std::collections::BTreeMap<String, f64>>,
    seed: Option<u64>,
}

/// Declares the Python function `$name`, taking `$first` and the keyword arguments of
/// development ([`Growth`], `$growth` in its body): one signature for `grow`, `load` and
/// `derive`, as `help()` and the stubs show it.
macro_rules! growing_function {
    ($(#[$doc:meta])* fn $name:ident($py:ident, $first:ident: $ty:ty; $growth:ident) -> $ret:ty $body:block) => {
        $(#[$doc])*
        #[pyfunction]
        #[pyo3(signature = ($first, *, steps=None, time=None, dt=None, grammar_seed=None, env=None, defines=None, seed=None))]
        #[allow(clippy::too_many_arguments)]
        pub(crate) fn $name(
            $py: Python<'_>,
            $first: $ty,
            steps: Option<u64>,
            time: Option<f64>,
            dt: Option<f64>,
            grammar_seed: Option<u64>,
            env: Option<Vec<(usize, f64)>>,
            defines: Option<std::collections::BTreeMap<String, f64>>,
            seed: Option<u64>,
        ) -> $ret {
            let $growth = Growth { steps, time, dt, grammar_seed, env, defines, seed };
            $body
        }
    };
}

/// The creature `load` makes with `options`, which Ctrl-C stops.
fn loaded_with(
    py: Python<'_>,
    options: LoadOptions,
    load: impl FnOnce(&LoadOptions) -> Result<Loaded, LoadError> + Send,
) -> PyResult<PyCreature> {
    let loaded = interruptible(py, |cancel| {
        let options = LoadOptions {
            cancel: cancel.clone(),
            ..options
        };
        load(&options)
    })?
    .map_err(load_error)?;
    Ok(PyCreature::new(loaded.creature, loaded.notes))
}

growing_function! {
    /// Grows a creature from grammar text (an `.lsys` file's content), to its last frame, as
    /// `ontogeny grow` does.
    fn grow(py, text: &str; growth) -> PyResult<PyCreature> {
        let seed = given_grammar_seed(py, growth.grammar_seed, growth.seed)?;
        let lsys = grammar_text(text, define_overrides(growth.defines)?, seed)?;
        let options = load_options(growth.steps, seed, growth.time, growth.dt, growth.env);
        loaded_with(py, options, |options| grow_grammar(&lsys, options, &mut |_| {}))
    }
}

growing_function! {
    /// Reads a creature from a file, as `ontogeny eval FILE` does: an `.lsys` grammar (or a
    /// direct genome, grown to its last frame), a `creature.json`, or a graph genome's `.json`.
    fn load(py, path: PathBuf; growth) -> PyResult<PyCreature> {
        let seed = given_grammar_seed(py, growth.grammar_seed, growth.seed)?;
        require_exists(&path)?;
        let options = LoadOptions {
            defines: define_overrides(growth.defines)?,
            ..load_options(growth.steps, seed, growth.time, growth.dt, growth.env)
        };
        loaded_with(py, options, |options| load_creature(&path, options, &mut |_| {}))
    }
}

/// Develops a creature from a genome's text in one of the encodings (`direct`: an `.lsys`
/// file holding an axiom alone; `lsystem`, `continuous`: a run's `best.lsys`; `graph`: a
/// run's `best.json`), within the encoding's default limits, as evolution develops it.
#[pyfunction]
#[pyo3(signature = (text, encoding="direct", *, seed=0))]
pub(crate) fn genome(
    py: Python<'_>,
    text: &str,
    encoding: &str,
    seed: u64,
) -> PyResult<PyCreature> {
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

/// Develops a genome file in each habitat of a configuration, as `ontogeny genome show
/// --habitats CONFIG GENOME --json` does, and returns what it prints as a dict: `file`,
/// `encoding`, `habitats` (each `name`, `environment`, `develops`, `creature`, `error`),
/// `differences` (each pair's), `depends_on_habitat` and `verdict`.
#[pyfunction]
pub(crate) fn genome_habitats<'py>(
    py: Python<'py>,
    config: PathBuf,
    genome: PathBuf,
) -> PyResult<Bound<'py, PyAny>> {
    require_exists(&config)?;
    require_exists(&genome)?;
    let shown = py
        .detach(|| genome_in_habitats(&config, &genome))
        .map_err(|e| match e {
            GenomeHabitatsError::Diagnostic(d) => diagnostic_error(d),
            GenomeHabitatsError::Input(m) => value_error(m),
            GenomeHabitatsError::Read { path, source } => {
                PyOSError::new_err(format!("cannot read {}: {source}", path.display()))
            }
        })?;
    py.import("json")?
        .call_method1("loads", (shown.json().to_string(),))
}

growing_function! {
    /// Derives grammar text as `ontogeny derive` does: a list of frames `(time, modules, env)`,
    /// the axiom first: the frame's time (its step in discrete time), its module string as
    /// text, and the environment's values.
    fn derive(py, text: &str; growth) -> PyResult<Vec<(f64, String, Vec<f64>)>> {
        let seed = given_grammar_seed(py, growth.grammar_seed, growth.seed)?;
        let lsys = grammar_text(text, define_overrides(growth.defines)?, seed)?;
        let options = derive_options(seed, growth.time, growth.dt, growth.env);
        let note = print::check_mode(&lsys, &options, growth.steps, "printing").map_err(diagnostic_error)?;
        warn_all(py, &note.into_iter().collect::<Vec<_>>())?;
        let (frames, fixed) = interruptible(py, |cancel| {
            let mut frames = Vec::new();
            let mut fixed = None;
            lsys.for_each_frame_until(&options, growth.steps, |frame| {
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
}
