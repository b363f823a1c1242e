//! Stopping long work through a cancellation token: a growth between frames, an evaluation
//! between control steps, a run between evaluations; an unset token changes nothing, and an
//! interrupted run resumes to the uninterrupted run's result.

use std::path::Path;

use crate::util::{grown, lsystem, scratch_dir};

use ontogeny::cancel::{Cancel, Interrupted};
use ontogeny::develop::{BuildOptions, for_each_growth_frame, grow_last};
use ontogeny::encoding::DirectGenome;
use ontogeny::front::settings::{self, RunFlags};
use ontogeny::lang::DiagnosticKind;
use ontogeny::lsystem::DeriveOptions;
use ontogeny::run::store::{IndividualRecord, RunStore};
use ontogeny::run::{Run, RunError};
use ontogeny::task::{TaskKind, TaskSpec, Watch};

/// Ten steps of a growing string, eleven frames with the axiom.
const GROWING: &str = "axiom: A\nderivation length: 10\nA --> forward(0.1) A\n";

fn set_token() -> Cancel {
    let token = Cancel::new();
    token.cancel();
    token
}

#[test]
fn a_growth_whose_token_is_set_stops_before_its_first_frame() {
    let options = BuildOptions {
        cancel: set_token(),
        ..BuildOptions::default()
    };
    let mut told = Vec::new();
    let e = grow_last(
        &lsystem(GROWING),
        &DeriveOptions::default(),
        None,
        &options,
        &mut |f| told.push(f),
    )
    .unwrap_err();
    assert_eq!(e.kind, DiagnosticKind::Interrupted);
    assert_eq!(e.to_string(), "error: interrupted");
    assert!(told.is_empty(), "{told:?}");
}

#[test]
fn a_token_set_during_a_growth_stops_it_at_the_next_frame() {
    let options = BuildOptions::default();
    let mut seen = Vec::new();
    let e = for_each_growth_frame(
        &lsystem(GROWING),
        &DeriveOptions::default(),
        None,
        &options,
        |_, _| true,
        &mut |_| {},
        |frame| {
            seen.push(frame.step);
            if frame.step == 4 {
                options.cancel.cancel();
            }
            Ok::<(), ontogeny::lang::Diagnostic>(())
        },
    )
    .unwrap_err();
    assert_eq!(e.kind, DiagnosticKind::Interrupted);
    assert_eq!(seen, [0, 1, 2, 3, 4]);
}

/// The walker task with a two-second walk.
fn two_second_walk() -> TaskSpec {
    let mut spec = TaskSpec::new(TaskKind::Walker);
    *spec.seconds_mut() = 2.0;
    spec
}

/// A two-second walk of the ten-part chain, watched with `cancel`; the fractions told.
fn watched_walk(
    cancel: &Cancel,
    cancel_at: f64,
) -> (Result<ontogeny::task::Evaluation, Interrupted>, Vec<f64>) {
    let creature = grown("benches/chain10.lsys");
    let spec = two_second_walk();
    let mut told = Vec::new();
    let outcome = spec.evaluate_watched(
        &creature,
        Watch {
            record: false,
            progress: &mut |f| {
                told.push(f);
                if f >= cancel_at {
                    cancel.cancel();
                }
            },
            cancel: Some(cancel),
        },
    );
    (outcome, told)
}

#[test]
fn an_evaluation_whose_token_is_set_stops_before_its_first_step() {
    let (outcome, told) = watched_walk(&set_token(), 2.0);
    assert_eq!(outcome.unwrap_err(), Interrupted);
    assert!(told.is_empty(), "{told:?}");
}

#[test]
fn a_token_set_during_an_evaluation_stops_it_at_the_next_control_step() {
    let (whole, all_told) = watched_walk(&Cancel::new(), 2.0);
    let whole = whole.unwrap();
    assert_eq!(all_told.last(), Some(&1.0));
    let (outcome, told) = watched_walk(&Cancel::new(), 0.25);
    assert_eq!(outcome.unwrap_err(), Interrupted);
    // It told what the whole walk told, up to the quarter, and nothing after.
    let quarter = all_told.iter().position(|f| *f >= 0.25).unwrap();
    assert_eq!(told[..], all_told[..=quarter]);
    // An unset token changes nothing.
    let plain = two_second_walk().evaluate(&grown("benches/chain10.lsys"), false);
    assert_eq!(whole.fitness.to_bits(), plain.fitness.to_bits());
    assert_eq!(whole.terms, plain.terms);
}

/// A run of direct-genome walkers in `out` (population 6, 3 generations of 1 s walks, seed 7).
fn start_run(out: &Path) -> Run<DirectGenome> {
    let flags = RunFlags {
        population: Some(6),
        generations: Some(3),
        seconds: Some(1.0),
        ..RunFlags::default()
    };
    let config = settings::new_run::<DirectGenome>(None, &flags, None, Some(7), true, true)
        .unwrap()
        .config;
    Run::<DirectGenome>::start(out, config, None).unwrap()
}

/// Every individual of every generation of the run in `out`.
fn stored(out: &Path) -> Vec<IndividualRecord> {
    let store = RunStore::open_read_only(&out.join("run.sqlite")).unwrap();
    let last = store.last_generation().unwrap().unwrap();
    (0..=last)
        .flat_map(|g| store.individuals(g).unwrap())
        .collect()
}

/// The run in `dir` resumed. The lock the dropped run held may linger for a moment: a test
/// beside this one that starts a process forks this one, and the child holds a copy of every
/// open file until it executes its program.
fn resume_when_free(dir: &Path) -> Run<DirectGenome> {
    for _ in 0..100 {
        match Run::<DirectGenome>::resume(dir) {
            Err(RunError::Locked(_)) => std::thread::sleep(std::time::Duration::from_millis(20)),
            resumed => return resumed.unwrap(),
        }
    }
    panic!("{} stayed locked for 2 s", dir.display())
}

#[test]
fn an_interrupted_run_keeps_its_stored_generations_and_resumes_to_the_uninterrupted_result() {
    let dir = scratch_dir("cancel-run");
    let (whole, cut) = (dir.join("whole"), dir.join("cut"));
    start_run(&whole).run(&mut |_| {}).unwrap();

    let token = Cancel::new();
    let mut run = start_run(&cut);
    run.set_cancel(token.clone());
    let e = run
        .run(&mut |report| {
            if report.generation == 0 {
                token.cancel();
            }
        })
        .unwrap_err();
    assert!(matches!(e, RunError::Interrupted(Interrupted)), "{e:?}");
    assert_eq!(e.to_string(), "interrupted");
    drop(run);
    let store = RunStore::open_read_only(&cut.join("run.sqlite")).unwrap();
    assert_eq!(store.last_generation().unwrap(), Some(0));
    drop(store);

    resume_when_free(&cut).run(&mut |_| {}).unwrap();
    let (a, b) = (stored(&whole), stored(&cut));
    assert_eq!(a.len(), 18);
    assert_eq!(a, b);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn each_generation_is_stored_with_its_fine_figure_when_it_is_reported() {
    // The fine re-walk of a generation's best walks beside the next generation; the
    // generation is stored, with its figure, before it is reported.
    let dir = scratch_dir("reported-stored");
    let out = dir.join("run");
    let mut reported = Vec::new();
    start_run(&out)
        .run(&mut |report| {
            let store = RunStore::open_read_only(&out.join("run.sqlite")).unwrap();
            let generations = store.generations().unwrap();
            let last = generations.last().unwrap();
            assert_eq!(last.index, report.generation);
            assert!(last.best_fine.is_some());
            assert_eq!(last.best_fine, report.stats.best_fine);
            reported.push(report.generation);
        })
        .unwrap();
    assert_eq!(reported, [0, 1, 2]);
    let _ = std::fs::remove_dir_all(dir);
}
