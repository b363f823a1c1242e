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

mod common;
mod creature;
mod evaluation;
mod evolution;
mod interrupt;
mod resume;

use pyo3::prelude::*;

use creature::{PyCreature, derive, genome, genome_habitats, grow, load};
use evaluation::{PyEvaluation, evaluate, evaluate_many};
use evolution::{PyRun, evolve};

/// The compiled part of the `ontogeny` package.
#[pymodule]
fn _ontogeny(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    // The tasks of the library's registry, by name, with their summaries.
    let tasks = pyo3::types::PyDict::new(m.py());
    for task in ontogeny::task::TASKS {
        tasks.set_item(task.name, task.summary)?;
    }
    m.add("TASKS", tasks)?;
    m.add_class::<PyCreature>()?;
    m.add_class::<PyEvaluation>()?;
    m.add_class::<PyRun>()?;
    m.add_function(wrap_pyfunction!(grow, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(genome, m)?)?;
    m.add_function(wrap_pyfunction!(genome_habitats, m)?)?;
    m.add_function(wrap_pyfunction!(derive, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_many, m)?)?;
    m.add_function(wrap_pyfunction!(evolve, m)?)?;
    m.add_function(wrap_pyfunction!(resume::resume, m)?)?;
    Ok(())
}
