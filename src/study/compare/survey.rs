//! Where a comparison stands: every replicate's state read by its arm's encoding, the
//! evaluations made so far and the replicates left to run ([`survey`]), and the finished and
//! unfinished replicates a report is made of ([`gather`]).

use std::path::Path;

use super::CompareError;
use super::plan::{Arm, Manifest, evaluations_of, walks_per_individual};
use super::replicate::{Replicate, ReplicateState, read_replicate};

/// The state of replicate `k` of `arm`.
pub fn replicate_state(
    root: &Path,
    manifest: &Manifest,
    arm: &Arm,
    k: usize,
) -> Result<ReplicateState, CompareError> {
    crate::with_genome!(
        arm.encoding.as_str(),
        G => read_replicate::<G>(root, manifest, arm, k),
        |other| Err(CompareError::Input(format!(
            "{}: unknown encoding '{other}'",
            if manifest.conditions.is_empty() {
                root.join("compare.toml")
            } else {
                super::plan::condition_file(root, &arm.name)
            }
            .display()
        )))
    )
}

/// Walks a replicate of `arm` has simulated after `generations` complete generations.
fn made(arm: &Arm, generations: usize) -> u64 {
    if generations == 0 {
        return 0;
    }
    let mut ga = arm.settings.ga.clone();
    ga.generations = generations;
    evaluations_of(&ga, arm.settings.task.trials.fresh) * walks_per_individual(&arm.settings.task)
}

/// A comparison's progress before its missing and unfinished replicates run.
#[derive(Clone, Debug, Default)]
pub struct Survey {
    /// Walks of the whole comparison.
    pub total: u64,
    /// Walks made so far.
    pub done: u64,
    /// The replicates to run, `(arm's index, k)`: replicate 1 of every arm, then
    /// replicate 2, ...
    pub todo: Vec<(usize, usize)>,
}

/// Reads every replicate's state: the walks made and the replicates left to run.
pub fn survey(root: &Path, manifest: &Manifest, arms: &[Arm]) -> Result<Survey, CompareError> {
    let mut survey = Survey {
        total: arms.iter().map(Arm::walks).sum::<u64>() * manifest.replicates as u64,
        ..Survey::default()
    };
    for k in 1..=manifest.replicates {
        for (i, arm) in arms.iter().enumerate() {
            match replicate_state(root, manifest, arm, k)? {
                ReplicateState::Done(_) => survey.done += arm.walks(),
                ReplicateState::Partial(g) => {
                    survey.done += made(arm, g);
                    survey.todo.push((i, k));
                }
                ReplicateState::Missing => survey.todo.push((i, k)),
            }
        }
    }
    Ok(survey)
}

/// The finished replicates, and a description of the unfinished ones arm by arm: each one
/// started (`lsystem rep-2 (3 of 10 generations)`) and each run of consecutive ones not
/// started (`lsystem rep-4 (not started)`, `lsystem rep-11 to rep-29 (not started)`).
pub fn gather(
    root: &Path,
    manifest: &Manifest,
    arms: &[Arm],
) -> Result<(Vec<Replicate>, Vec<String>), CompareError> {
    let mut finished: Vec<Replicate> = Vec::new();
    let mut unfinished = Vec::new();
    for arm in arms {
        let name = &arm.name;
        // The first of the current run of replicates not started.
        let mut missing_from: Option<usize> = None;
        for k in 1..=manifest.replicates {
            let state = replicate_state(root, manifest, arm, k)?;
            if !matches!(state, ReplicateState::Missing)
                && let Some(first) = missing_from.take()
            {
                unfinished.push(not_started(name, first, k - 1));
            }
            match state {
                ReplicateState::Done(r) => finished.push(*r),
                ReplicateState::Partial(g) => unfinished.push(format!(
                    "{name} rep-{k} ({g} of {} generations)",
                    arm.settings.ga.generations
                )),
                ReplicateState::Missing => {
                    missing_from.get_or_insert(k);
                }
            }
        }
        if let Some(first) = missing_from {
            unfinished.push(not_started(name, first, manifest.replicates));
        }
    }
    Ok((finished, unfinished))
}

/// Replicates `first..=last` of `name`, none started: `direct rep-3 (not started)` or
/// `direct rep-3 to rep-29 (not started)`.
fn not_started(name: &str, first: usize, last: usize) -> String {
    if first == last {
        format!("{name} rep-{first} (not started)")
    } else {
        format!("{name} rep-{first} to rep-{last} (not started)")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replicates_not_started_are_named_as_one_run() {
        assert_eq!(not_started("direct", 3, 3), "direct rep-3 (not started)");
        assert_eq!(
            not_started("graph", 11, 29),
            "graph rep-11 to rep-29 (not started)"
        );
    }
}
