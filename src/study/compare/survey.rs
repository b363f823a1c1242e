//! Where a comparison stands: every replicate's state read by its encoding's name, the
//! evaluations made so far and the replicates left to run ([`survey`]), and the finished and
//! unfinished replicates a report is made of ([`gather`]).

use std::path::Path;

use super::CompareError;
use super::plan::{Manifest, Shared, evaluations_of};
use super::replicate::{Replicate, ReplicateState, read_replicate};

/// The state of replicate `k` of the encoding named `encoding`.
pub fn replicate_state(
    root: &Path,
    manifest: &Manifest,
    shared: &Shared,
    encoding: &str,
    k: usize,
) -> Result<ReplicateState, CompareError> {
    crate::with_genome!(
        encoding,
        G => read_replicate::<G>(root, manifest, shared, k),
        |other| Err(CompareError::Input(format!(
            "{}: unknown encoding '{other}'",
            root.join("compare.toml").display()
        )))
    )
}

/// Evaluations a replicate has made after `generations` complete generations.
fn made(shared: &Shared, generations: usize) -> u64 {
    if generations == 0 {
        return 0;
    }
    let mut ga = shared.ga.clone();
    ga.generations = generations;
    evaluations_of(&ga)
}

/// A comparison's progress before its missing and unfinished replicates run.
#[derive(Clone, Debug, Default)]
pub struct Survey {
    /// Evaluations of the whole comparison.
    pub total: u64,
    /// Evaluations made so far.
    pub done: u64,
    /// The replicates to run, `(encoding, k)`: replicate 1 of every encoding, then
    /// replicate 2, ...
    pub todo: Vec<(String, usize)>,
}

/// Reads every replicate's state: the evaluations made and the replicates left to run.
pub fn survey(root: &Path, manifest: &Manifest, shared: &Shared) -> Result<Survey, CompareError> {
    let per_replicate = evaluations_of(&shared.ga);
    let mut survey = Survey {
        total: per_replicate * (manifest.replicates * manifest.encodings.len()) as u64,
        ..Survey::default()
    };
    for k in 1..=manifest.replicates {
        for encoding in &manifest.encodings {
            match replicate_state(root, manifest, shared, encoding, k)? {
                ReplicateState::Done(_) => survey.done += per_replicate,
                ReplicateState::Partial(g) => {
                    survey.done += made(shared, g);
                    survey.todo.push((encoding.clone(), k));
                }
                ReplicateState::Missing => survey.todo.push((encoding.clone(), k)),
            }
        }
    }
    Ok(survey)
}

/// The finished replicates, and a description of each unfinished one (`lsystem rep-2 (3 of
/// 10 generations)`, `... (not started)`), encoding by encoding.
pub fn gather(
    root: &Path,
    manifest: &Manifest,
    shared: &Shared,
) -> Result<(Vec<Replicate>, Vec<String>), CompareError> {
    let mut finished: Vec<Replicate> = Vec::new();
    let mut unfinished = Vec::new();
    for encoding in &manifest.encodings {
        for k in 1..=manifest.replicates {
            match replicate_state(root, manifest, shared, encoding, k)? {
                ReplicateState::Done(r) => finished.push(*r),
                ReplicateState::Partial(g) => unfinished.push(format!(
                    "{encoding} rep-{k} ({g} of {} generations)",
                    shared.ga.generations
                )),
                ReplicateState::Missing => {
                    unfinished.push(format!("{encoding} rep-{k} (not started)"))
                }
            }
        }
    }
    Ok((finished, unfinished))
}
