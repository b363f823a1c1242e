//! Going on with a run from Python: `resume`, as `ontogeny evolve --resume` does, and the
//! loop over a run's remaining generations that `evolve` and `resume` share, which Ctrl-C
//! stops between evaluations (the run keeps its stored generations).

use std::path::{Path, PathBuf};

use ontogeny::cancel::Cancel;
use ontogeny::encoding::Genome;
use ontogeny::front::text;
use ontogeny::run::{GenerationReport, Run, encoding_of_run};
use pyo3::prelude::*;

use super::common::{require_exists, run_error, thread_pool, value_error};
use super::interrupt::interruptible;

/// Goes on with the run in the directory `path` (one that `evolve` started, interrupted or
/// finished), as `ontogeny evolve --resume PATH [--gens GENS]` does: from its last stored
/// generation to its last generation, or to `gens` generations in all (extending a finished
/// run); returns the run's directory. A resumed run ends as an uninterrupted one would.
#[pyfunction]
#[pyo3(signature = (path, *, gens=None, threads=None, progress=false))]
pub fn resume(
    py: Python<'_>,
    path: PathBuf,
    gens: Option<usize>,
    threads: Option<usize>,
    progress: bool,
) -> PyResult<PathBuf> {
    require_exists(&path)?;
    let pool = thread_pool(threads)?;
    let name = encoding_of_run(&path).map_err(run_error)?;
    interruptible(py, |cancel| {
        pool.install(|| {
            ontogeny::with_genome!(
                name.as_str(),
                G => resume_run::<G>(&path, gens, progress, cancel),
                |other: &str| Err(value_error(format!(
                    "{}: unknown encoding '{other}'",
                    path.display()
                )))
            )
        })
    })??;
    Ok(path)
}

/// Resumes the run in `dir`, extended to `generations` if given, and runs it to its end;
/// a finished run gets its derived files written again, as the command line does.
fn resume_run<G: Genome>(
    dir: &Path,
    generations: Option<usize>,
    progress: bool,
    cancel: &Cancel,
) -> PyResult<()> {
    let mut run = Run::<G>::resume(dir).map_err(run_error)?;
    if let Some(generations) = generations {
        run.extend(generations).map_err(run_error)?;
    }
    let done = run.last_generation().map_err(run_error)?;
    if done.is_some_and(|g| g as usize + 1 >= run.config().ga.generations) {
        return run.write_derived_files().map_err(run_error);
    }
    run_to_end(&mut run, progress, cancel)
}

/// Runs `run`'s remaining generations, a line per generation on standard error with
/// `progress`, until `cancel` stops it.
pub fn run_to_end<G: Genome>(run: &mut Run<G>, progress: bool, cancel: &Cancel) -> PyResult<()> {
    let fitness = run.config().task.fitness_label();
    let mut observer = |r: &GenerationReport| {
        if progress {
            eprintln!(
                "generation {}: {}",
                r.generation,
                text::generation_line(&fitness, r)
            );
        }
    };
    run.set_cancel(cancel.clone());
    run.run(&mut observer).map_err(run_error)
}
