//! A run made by an earlier release (`tests/fixtures/old-release/run`, made as its README
//! says): it opens, the evaluation keys it stored are the keys a run computes today, so its
//! cache still finds them, and it resumes to the result that release gave.

use std::path::{Path, PathBuf};

use ontogeny::encoding::LSystemGenome;
use ontogeny::run::Run;

use crate::util::{ontogeny, ontogeny_ok, scratch_dir, stderr, stdout};

/// A scratch copy of the fixture run, named after `name`.
fn copy_of_the_old_run(name: &str) -> PathBuf {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/old-release/run");
    let dir = scratch_dir(&format!("old_release-{name}")).join("run");
    std::fs::create_dir_all(&dir).unwrap();
    for entry in std::fs::read_dir(&fixture).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), dir.join(entry.file_name())).unwrap();
    }
    dir
}

#[test]
fn every_key_an_old_run_stored_is_the_key_its_run_computes_today() {
    let dir = copy_of_the_old_run("keys");
    let run = Run::<LSystemGenome>::open_read_only(&dir).unwrap();
    assert_eq!(run.last_generation().unwrap(), Some(2));
    let mut keyed = 0;
    for generation in 0..=2 {
        for individual in run.population(generation).unwrap() {
            let today = run.evaluation_key(&individual.genome, individual.develop_seed);
            assert_eq!(today, individual.key, "generation {generation}");
            keyed += usize::from(individual.key.is_some());
        }
    }
    // Of the three generations of four, one individual (generation 0's last) did not develop,
    // and has no key.
    assert_eq!(keyed, 11);
}

/// The figures of each line of `log.txt`, up to its evaluation counts (the seconds after
/// them are timings).
fn figures(log: &str) -> Vec<&str> {
    log.lines()
        .filter(|l| l.starts_with("generation "))
        .map(|l| &l[..l.find(" simulated").unwrap()])
        .collect()
}

#[test]
fn an_old_run_resumes_to_the_result_its_release_gave() {
    let dir = copy_of_the_old_run("resume");
    // Its evaluator (version 1) scored a walker that never came to rest at the failure floor;
    // today's scores it 0 (Chaumont 3.3): the resume is refused unless asked for.
    let refused = ontogeny(&["evolve", "--resume", dir.to_str().unwrap(), "--gens", "6"]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(stderr(&refused).contains("--allow-evaluator-change"));
    let out = ontogeny_ok(&[
        "evolve",
        "--resume",
        dir.to_str().unwrap(),
        "--gens",
        "6",
        "--allow-evaluator-change",
    ]);
    let said = stdout(&out);
    let last = said.lines().rfind(|l| l.contains(": walker, ")).unwrap();
    assert!(
        last.contains(
            "walker, normalised (Chaumont eq. 1): generation 5 best 0.013635 (fine reference 0.013486); 9 evaluations, 8 simulated in"
        ),
        "{last}"
    );
    // What the earlier release wrote resuming a copy of the same run (none of these
    // creatures fails to come to rest, so the results are its own), but for one count: the
    // cache does not reuse the evaluations the other evaluator stored, so generation 3
    // simulates a creature that release found in its cache (3 simulated, not 2).
    let log = std::fs::read_to_string(dir.join("log.txt")).unwrap();
    assert_eq!(
        figures(&log),
        [
            "generation 0: walker, normalised (Chaumont eq. 1): best 0.004485 (fine reference 0.010060), mean 0.004485, median 0.004485, valid 25%, 4 evaluations, 4",
            "generation 1: walker, normalised (Chaumont eq. 1): best 0.008822 (fine reference 0.010735), mean 0.005931, median 0.004485, valid 75%, 3 evaluations, 2",
            "generation 2: walker, normalised (Chaumont eq. 1): best 0.008822 (fine reference 0.010735), mean 0.002945, median 0.000011, valid 75%, 3 evaluations, 3",
            "generation 3: walker, normalised (Chaumont eq. 1): best 0.008822 (fine reference 0.010735), mean 0.004412, median 0.004412, valid 100%, 3 evaluations, 3",
            "generation 4: walker, normalised (Chaumont eq. 1): best 0.008822 (fine reference 0.010735), mean 0.003007, median 0.000191, valid 75%, 3 evaluations, 3",
            "generation 5: walker, normalised (Chaumont eq. 1): best 0.013635 (fine reference 0.013486), mean 0.007821, median 0.008822, valid 100%, 3 evaluations, 2",
        ]
    );
}
