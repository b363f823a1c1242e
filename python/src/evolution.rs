//! Evolution from Python: `evolve`, and the `Run` class that reads a run directory.

use crate::common::{
    diagnostic_error, require_exists, run_error, setting_named, task_named, thread_pool,
    value_error,
};
use std::path::PathBuf;

use crate::interrupt::interruptible;
use ontogeny::cancel::Cancel;
use ontogeny::encoding::Genome;
use ontogeny::front::settings::{self, RunFlags};
use ontogeny::front::start::{NewRun, StartError, start_run};
use ontogeny::run::config::read_config_source;
use ontogeny::run::pick::{PickError, individual_by_rank};
use ontogeny::run::store::RunStore;
use ontogeny::run::{Run, encoding_of_run};
use ontogeny::task::HabitatResult;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// Runs an evolution into the directory `out`, as `ontogeny evolve --out OUT` does with the
/// same settings (a config file, and the keyword arguments over it as the command line's
/// flags, `target` the aim task's `--target`; a keyword the task does not read is refused as
/// the command line refuses its flag); returns the run's directory.
#[pyfunction]
#[pyo3(signature = (config=None, *, out, encoding=None, task=None, fitness=None, preset=None, pop=None, gens=None, walks=None, seed=None, seconds=None, target=None, setting=None, threads=None, init=None, verify_best=true, cache=true, progress=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn evolve(
    py: Python<'_>,
    config: Option<PathBuf>,
    out: PathBuf,
    encoding: Option<&str>,
    task: Option<&str>,
    fitness: Option<&str>,
    preset: Option<&str>,
    pop: Option<usize>,
    gens: Option<usize>,
    walks: Option<u64>,
    seed: Option<u64>,
    seconds: Option<f64>,
    target: Option<[f64; 3]>,
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
        walks,
        task: task.map(task_named).transpose()?,
        fitness: fitness.map(str::to_string),
        seconds,
        setting: setting.map(setting_named).transpose()?,
        target,
        algorithm: None,
        in_flight: None,
    };
    let pool = thread_pool(threads)?;
    let source = config
        .as_deref()
        .map(read_config_source)
        .transpose()
        .map_err(diagnostic_error)?;
    let name = settings::new_run_encoding(encoding, source.as_deref()).map_err(diagnostic_error)?;
    let new = NewRun {
        out: &out,
        source: source.as_deref(),
        flags: &flags,
        init: init.as_deref(),
        seed,
        verify_best,
        cache,
    };
    interruptible(py, |cancel| {
        pool.install(|| {
            ontogeny::with_genome!(
                name.as_str(),
                G => run::<G>(&new, progress, cancel),
                |other: &str| Err(value_error(format!("unknown encoding '{other}'")))
            )
        })
    })??;
    Ok(out)
}

/// Starts the run `new` describes and runs it to its last generation, a line per generation
/// on standard error with `progress`, until `cancel` stops it.
fn run<G: Genome>(new: &NewRun<'_>, progress: bool, cancel: &Cancel) -> PyResult<()> {
    let mut run = start_run::<G>(new, |_| {}).map_err(|e| match e {
        StartError::Settings(d) => diagnostic_error(d),
        StartError::Run(e) => run_error(e),
    })?;
    crate::resume::run_to_end(&mut run, progress, cancel)
}

/// A run directory's records, read from its store (`run.sqlite`) read-only, as `ontogeny
/// runs show` reads them.
#[pyclass(name = "Run", module = "ontogeny", subclass, frozen)]
pub(crate) struct PyRun {
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
    /// run store's columns: `generation`, `individual`, `parents`, `parents_generation` (the
    /// generation `parents` index; `None` in generation 0 and in rows stored before it was
    /// recorded, where it is the previous generation), `operator`, `genome_text`, `fitness`,
    /// `status`, `terms`, `parts`, `joints`, `neurons`, `reused`; in a run with
    /// habitats or trials also `habitats`, each habitat's and trial's walk (a list of dicts
    /// as `Evaluation.habitats` gives them).
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
                dict.set_item("parents_generation", i.parents_generation)?;
                dict.set_item("operator", i.operator)?;
                dict.set_item("genome_text", i.genome_text)?;
                dict.set_item("fitness", i.fitness)?;
                dict.set_item("status", i.status)?;
                dict.set_item("terms", json.call_method1("loads", (i.terms_json,))?)?;
                dict.set_item("parts", i.parts)?;
                dict.set_item("joints", i.joints)?;
                dict.set_item("neurons", i.neurons)?;
                dict.set_item("reused", i.reused)?;
                // Each habitat's and trial's walk, kept in the individual's evaluation.
                let stored: serde_json::Value =
                    serde_json::from_str(&i.genome_json).map_err(value_error)?;
                let walks = &stored["evaluation"]["habitats"];
                if walks.is_array() {
                    let walks = json.call_method1("loads", (walks.to_string(),))?;
                    dict.set_item("habitats", walks)?;
                }
                list.append(dict)?;
            }
        }
        Ok(list)
    }

    /// The walks of the individual of rank `rank` (1 = the best) in generation `generation`
    /// (default: the last complete one), as `ontogeny replay RUN --gen G --rank K` picks it:
    /// each habitat's and trial's walk from its stored evaluation, a list of dicts as
    /// `Evaluation.habitats` gives them (`name`, `trial`, `parts`, `joints`, `fitness`,
    /// `status`, `terms`, and `message` when something went wrong); empty in a run without
    /// habitats or trials.
    #[pyo3(signature = (generation=None, rank=1))]
    fn habitats<'py>(
        &self,
        py: Python<'py>,
        generation: Option<u32>,
        rank: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let name = encoding_of_run(&self.dir).map_err(run_error)?;
        let units: Vec<HabitatResult> = ontogeny::with_genome!(
            name.as_str(),
            G => {
                let run = Run::<G>::open_read_only(&self.dir).map_err(run_error)?;
                let (_, picked) = individual_by_rank(&run, &self.dir, generation, rank)
                    .map_err(|e| match e {
                        PickError::Run(e) => run_error(e),
                        // Said with the keywords, not the command line's flags.
                        PickError::Input(m) => value_error(
                            m.replacen("--gen ", "generation=", 1).replacen("--rank", "rank", 1),
                        ),
                    })?;
                Ok::<_, PyErr>(picked.evaluation.units().to_vec())
            },
            |other: &str| Err(value_error(format!(
                "{}: unknown encoding '{other}'",
                self.dir.display()
            )))
        )?;
        let json = serde_json::to_string(&units).map_err(value_error)?;
        py.import("json")?.call_method1("loads", (json,))
    }

    fn __repr__(&self) -> String {
        format!("Run('{}')", self.dir.display())
    }
}
