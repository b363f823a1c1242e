//! The steady-state algorithm (`--algorithm steady-state`): replace-worst and the arithmetic
//! of births checked by hand; a run the same on 1, 2 and 3 threads, changed by its
//! `in_flight`, its generation 0 the generational run's, each block of births one generation
//! row in which every slot only ever improves; killed and resumed, or extended, to the same
//! result; its lineage stored (each newborn's parents in the generation its birth was bred
//! from, each member kept through a block an elite of itself); its settings in `config.toml`
//! and bad values refused with exit code 2.

use std::path::Path;
use std::process::Command;

use ontogeny::cancel::Cancel;
use ontogeny::encoding::{DirectGenome, Genome};
use ontogeny::evolve::ga::{Evolution, Individual, Operator, individual_rng};
use ontogeny::evolve::steady::{Blocks, Snapshot, replace_worst};
use ontogeny::run::Run;
use ontogeny::run::profile::read_profile;
use ontogeny::run::store::RunStore;
use ontogeny::task::Evaluation;

use super::{contents, scratch};
use crate::util::{evolve_walkers, ontogeny_command, refused, succeeded};

/// An individual of fitness `fitness` (a random direct genome: only its fitness is read).
fn of_fitness(fitness: f64) -> Individual<DirectGenome> {
    let mut rng = individual_rng(1, 0, 0, 0);
    Individual {
        genome: DirectGenome::random(&Default::default(), &mut rng),
        develop_seed: 0,
        parents: Vec::new(),
        operator: Operator::Random,
        evaluation: Evaluation {
            fitness,
            ..Evaluation::invalid("walker", String::new())
        },
        size: (0, 0, 0),
        key: None,
        reused: false,
        parents_generation: None,
    }
}

#[test]
fn replace_worst_takes_the_worst_slot_only_when_strictly_better() {
    // Fitnesses 1, 3, 2: the worst is slot 0.
    let population: Vec<_> = [1.0, 3.0, 2.0].map(of_fitness).into();
    assert_eq!(replace_worst(&population, 1.5), Some(0));
    assert_eq!(replace_worst(&population, 10.0), Some(0));
    // A tie keeps the incumbent; worse is not kept.
    assert_eq!(replace_worst(&population, 1.0), None);
    assert_eq!(replace_worst(&population, 0.5), None);
    // Among equal worst, the highest index is the worst (the ranking puts it last).
    let tied: Vec<_> = [2.0, 1.0, 1.0].map(of_fitness).into();
    assert_eq!(replace_worst(&tied, 1.5), Some(2));
    // A fitness far below any walk (under the failure floor, -999999) loses to an ordinary one.
    let failing: Vec<_> = [0.2, -1e9, 0.1].map(of_fitness).into();
    assert_eq!(replace_worst(&failing, 0.0), Some(1));
}

#[test]
fn births_are_numbered_into_blocks_by_hand() {
    // Population 12, elite 20%: 2 survivors, so blocks of C = 10 births; W = 4.
    let blocks = Blocks {
        population: 12,
        children: 10,
        in_flight: 4,
    };
    assert_eq!(blocks.end_of(0), 12);
    assert_eq!(blocks.end_of(1), 22);
    assert_eq!(blocks.end_of(3), 42);
    // Birth 12 is child 0 of generation 1; birth 21 its last; birth 22 child 0 of gen 2.
    assert_eq!(blocks.place(12), (1, 0));
    assert_eq!(blocks.place(21), (1, 9));
    assert_eq!(blocks.place(22), (2, 0));
    // Birth b is bred from the last generation that ended at or before birth b + 1 - W:
    // generation 1 ends with 22 births, so birth 25 (25 + 1 - 4 = 22) is its first child,
    // birth 24 (21 births done) still generation 0's.
    assert_eq!(blocks.source(12), 0);
    assert_eq!(blocks.source(24), 0);
    assert_eq!(blocks.source(25), 1);
    assert_eq!(blocks.source(34), 1);
    assert_eq!(blocks.source(35), 2);
    // W = 1: every child of a generation is bred from the one before, as generationally.
    let one = Blocks {
        in_flight: 1,
        ..blocks
    };
    assert_eq!(one.source(21), 0);
    assert_eq!(one.source(22), 1);
    assert_eq!(one.source(31), 1);
}

/// A steady-state run of 12 `encoding` walkers, `gens` generations of 1 s walks, seed 5.
fn steady_command(encoding: &str, out: &Path, gens: &str, extra: &[&str]) -> Command {
    let mut c = evolve_walkers(encoding, "12");
    c.args(["--gens", gens, "--seconds", "1", "--seed", "5"])
        .args(["--algorithm", "steady-state", "--out"])
        .arg(out)
        .args(extra);
    c
}

/// Every stored generation's individuals' fitness and genome (its JSON, lineage and all), by
/// slot.
fn slots(dir: &Path) -> Vec<Vec<(f64, String)>> {
    let store = RunStore::open_read_only(&dir.join("run.sqlite")).unwrap();
    let last = store.last_generation().unwrap().unwrap();
    (0..=last)
        .map(|g| {
            store
                .individuals(g)
                .unwrap()
                .into_iter()
                .map(|i| (i.fitness, i.genome_json))
                .collect()
        })
        .collect()
}

#[test]
fn a_steady_state_run_is_the_same_on_one_two_and_three_threads() {
    for encoding in ["lsystem", "direct"] {
        let dir = scratch(&format!("steady-threads-{encoding}"));
        let runs: Vec<_> = ["1", "2", "3"]
            .iter()
            .map(|threads| {
                let out = dir.join(threads);
                let run = steady_command(encoding, &out, "4", &["--in-flight", "4"])
                    .args(["--threads", threads])
                    .output()
                    .unwrap();
                succeeded(&run);
                contents(&out)
            })
            .collect();
        assert_eq!(runs[0], runs[1], "{encoding}: 1 and 2 threads");
        assert_eq!(runs[0], runs[2], "{encoding}: 1 and 3 threads");
        // Its generation 0 is the generational run's.
        let generational = dir.join("generational");
        succeeded(
            &super::evolve_command(encoding, &generational, "1", &[])
                .output()
                .unwrap(),
        );
        assert_eq!(
            slots(&generational)[0],
            slots(&dir.join("1"))[0],
            "{encoding}"
        );
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn each_block_of_births_is_a_generation_whose_slots_only_improve() {
    let dir = scratch("steady-blocks");
    let out = dir.join("run");
    succeeded(
        &steady_command("direct", &out, "5", &["--in-flight", "3"])
            .output()
            .unwrap(),
    );
    let store = RunStore::open_read_only(&out.join("run.sqlite")).unwrap();
    let generations = store.generations().unwrap();
    assert_eq!(generations.len(), 5);
    // Generation 0 evaluates its 12; each later block at most its C = 10 births.
    assert!(generations[0].evaluations <= 12);
    for g in &generations[1..] {
        assert!(g.evaluations <= 10, "{}: {}", g.index, g.evaluations);
    }
    let slots = slots(&out);
    for k in 1..slots.len() {
        assert_eq!(slots[k].len(), 12);
        let mut changed = 0;
        for (slot, (now, before)) in slots[k].iter().zip(&slots[k - 1]).enumerate() {
            // A newborn takes a slot only from a worse individual; a member not replaced is
            // stored as an elite of itself.
            if genome_alone(&now.1) != genome_alone(&before.1) {
                changed += 1;
                assert!(
                    now.0 > before.0,
                    "generation {k}, slot {slot}: {now:?} {before:?}"
                );
            } else {
                assert_eq!(now.0.to_bits(), before.0.to_bits());
                let lineage: serde_json::Value = serde_json::from_str(&now.1).unwrap();
                assert_eq!(lineage["operator"], "elite", "generation {k}, slot {slot}");
                assert_eq!(lineage["parents"], serde_json::json!([slot]));
            }
        }
        assert!(changed <= 10, "generation {k}: {changed} slots changed");
        assert!(generations[k].best >= generations[k - 1].best);
    }
    let config = std::fs::read_to_string(out.join("config.toml")).unwrap();
    assert!(config.contains("algorithm = \"steady-state\""), "{config}");
    assert!(config.contains("in_flight = 3"), "{config}");
    // `runs show` reads it as any run.
    let shown = ontogeny_command()
        .args(["runs", "show"])
        .arg(&out)
        .output()
        .unwrap();
    succeeded(&shown);
    let _ = std::fs::remove_dir_all(dir);
}

/// A stored individual's genome JSON without its lineage (`parents`, `operator`).
fn genome_alone(json: &str) -> serde_json::Value {
    let mut value: serde_json::Value = serde_json::from_str(json).unwrap();
    let object = value.as_object_mut().unwrap();
    object.remove("parents");
    object.remove("operator");
    value
}

#[test]
fn a_steady_runs_lineage_names_the_generation_each_newborn_was_bred_from() {
    // Population 12, 2 survivors: blocks of C = 10 births; W = 4. Birth b is bred from the
    // last generation g with 12 + 10 g <= b + 1 - 4 (generation 0 when none):
    // generation 1's births 12..=21 from generation 0; generation 2's 22..=24 from 0 and
    // 25..=31 from 1; generation 3's 32..=34 from 1 and 35..=41 from 2.
    let sources: Vec<(u64, u32)> = (12..=21)
        .map(|b| (b, 0))
        .chain((22..=24).map(|b| (b, 0)))
        .chain((25..=31).map(|b| (b, 1)))
        .chain((32..=34).map(|b| (b, 1)))
        .chain((35..=41).map(|b| (b, 2)))
        .collect();
    let dir = scratch("steady-lineage");
    let out = dir.join("run");
    succeeded(
        &steady_command("direct", &out, "4", &["--in-flight", "4"])
            .output()
            .unwrap(),
    );
    let run = Run::<DirectGenome>::open_read_only(&out).unwrap();
    let config = run.config();
    let blocks = Blocks::of(&config.ga);
    for &(birth, source) in &sources {
        assert_eq!(blocks.source(birth), source, "birth {birth}");
    }
    // Every birth bred again, as the run bred it, from the generation by hand above.
    let evolution = Evolution::<DirectGenome> {
        settings: config.ga.clone(),
        limits: run.limits().clone(),
        task: config.task.clone(),
        seed: config.seed,
        init: None,
        key_version: Default::default(),
        key_tables: None,
        walk_order: Default::default(),
    };
    let births: Vec<(u64, u32, Individual<DirectGenome>)> = sources
        .iter()
        .map(|&(birth, source)| {
            let snapshot = Snapshot::new(&evolution, run.population(source).unwrap());
            let born = evolution
                .birth(birth, &snapshot, None, &Cancel::default())
                .unwrap();
            (birth, source, born.individual)
        })
        .collect();
    let store = RunStore::open_read_only(&out.join("run.sqlite")).unwrap();
    let mut two_back = 0;
    let mut elites = 0;
    for g in 1..=3u32 {
        let before = store.individuals(g - 1).unwrap();
        for (slot, i) in store.individuals(g).unwrap().into_iter().enumerate() {
            let genome = genome_alone(&i.genome_json);
            if i.operator == "elite" {
                // Kept through block g: itself, in its slot, in generation g - 1.
                assert_eq!(i.parents, [slot as u32], "{g}/{slot}");
                assert_eq!(i.parents_generation, Some(g - 1), "{g}/{slot}");
                assert_eq!(genome, genome_alone(&before[slot].genome_json));
                assert_eq!(i.fitness.to_bits(), before[slot].fitness.to_bits());
                elites += 1;
                continue;
            }
            // A newborn of block g: one of its births, the same genome and parents.
            let (birth, source, born) = births
                .iter()
                .find(|(birth, _, born)| {
                    blocks.place(*birth).0 == g
                        && serde_json::to_value(born).unwrap()["genome"] == genome["genome"]
                        && genome["develop_seed"] == born.develop_seed
                })
                .unwrap_or_else(|| panic!("{g}/{slot} is none of block {g}'s births"));
            assert_eq!(
                i.parents_generation,
                Some(*source),
                "{g}/{slot}: birth {birth}"
            );
            assert_eq!(i.parents, born.parents, "{g}/{slot}: birth {birth}");
            assert_eq!(
                i.operator,
                born.operator.name(),
                "{g}/{slot}: birth {birth}"
            );
            assert!(!i.parents.is_empty());
            let parents = store.individuals(*source).unwrap();
            assert!(
                i.parents.iter().all(|&p| (p as usize) < parents.len()),
                "{g}/{slot}: {:?}",
                i.parents
            );
            if *source + 2 == g {
                two_back += 1;
            }
        }
    }
    assert!(elites > 0, "some members are kept through a block");
    assert!(
        two_back > 0,
        "some newborn kept was bred two generations back"
    );
    // Generation 0 was made at random: no parents, and no generation of them.
    for i in store.individuals(0).unwrap() {
        assert_eq!((i.parents.len(), i.parents_generation), (0, None));
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_steady_run_stored_by_schema_version_4_resumes_to_the_same_run_and_records_lineage_on() {
    let dir = scratch("steady-version-4");
    let whole = dir.join("whole");
    let flags = ["--in-flight", "4"];
    succeeded(
        &steady_command("direct", &whole, "4", &flags)
            .output()
            .unwrap(),
    );
    // The same run's first 2 generations as an ontogeny of schema version 4 stored them.
    let old = dir.join("old");
    succeeded(
        &steady_command("direct", &old, "2", &flags)
            .output()
            .unwrap(),
    );
    let path = old.join("run.sqlite");
    crate::util::make_steady_version_4(&path);
    let store = RunStore::open_read_only(&path).unwrap();
    assert_eq!(store.schema_version(), 4);
    store.verify().unwrap();
    let kept = store.individuals(1).unwrap();
    assert!(kept.iter().all(|i| i.operator != "elite"), "{kept:?}");
    drop(store);
    let resumed = ontogeny_command()
        .args(["evolve", "--gens", "4", "--resume"])
        .arg(&old)
        .output()
        .unwrap();
    succeeded(&resumed);
    let store = RunStore::open_read_only(&path).unwrap();
    assert_eq!(store.schema_version(), ontogeny::run::store::SCHEMA_VERSION);
    store.verify().unwrap();
    let fresh = RunStore::open_read_only(&whole.join("run.sqlite")).unwrap();
    for g in 0..4 {
        let (migrated, unbroken) = (store.individuals(g).unwrap(), fresh.individuals(g).unwrap());
        assert_eq!(migrated.len(), 12);
        for (m, u) in migrated.iter().zip(&unbroken) {
            if g >= 2 {
                // Stored after the migration: the unbroken run's rows, lineage and all.
                assert_eq!(m, u);
            } else {
                // Stored before: the same creatures, their lineage as version 4 kept it.
                assert_eq!(genome_alone(&m.genome_json), genome_alone(&u.genome_json));
                assert_eq!(m.fitness.to_bits(), u.fitness.to_bits());
                assert_eq!(m.parents_generation, None);
            }
        }
        let (a, b) = (
            &store.generations().unwrap()[g as usize],
            &fresh.generations().unwrap()[g as usize],
        );
        assert_eq!(
            (a.best, a.mean, a.evaluations),
            (b.best, b.mean, b.evaluations)
        );
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_steady_runs_profile_counts_each_blocks_time_once_and_its_words_say_steady_state() {
    let dir = scratch("steady-profile");
    let out = dir.join("run");
    let profile = dir.join("profile.jsonl");
    let started = std::time::Instant::now();
    let output = steady_command("direct", &out, "6", &["--in-flight", "3", "--profile"])
        .arg(&profile)
        .output()
        .unwrap();
    let wall = started.elapsed().as_secs_f64();
    succeeded(&output);
    // Each generation's time runs from the end of the one before (a block's clock starts
    // once the block before is handed over, the wait for the fine re-walk of the one before
    // that and its writing included): the times of one command's generations, one after
    // another, add up to no more than its wall time.
    let generations = read_profile(&profile).unwrap();
    assert_eq!(generations.len(), 6);
    let total: f64 = generations.iter().map(|g| g.total).sum();
    assert!(total <= wall, "{total} s profiled in {wall} s");
    for g in &generations {
        assert!(g.evaluating + g.fine + g.writing <= g.total + 1e-9, "{g:?}");
        // A steady-state run re-walks each block's best beside the next block's births:
        // `fine` is the wait for it, `fine_walk` the walk (0 when the figure was known).
        assert!(g.fine_walk.is_some(), "{g:?}");
    }
    // The opening line and the plot's title say the algorithm and its births in flight.
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("steady-state, 3 births in flight: population 12 × 6 generations"),
        "{stderr}"
    );
    let plot = std::fs::read_to_string(out.join("fitness.svg")).unwrap();
    assert!(plot.contains("steady-state (3 in flight)"), "{plot}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn in_flight_is_part_of_the_algorithm() {
    let dir = scratch("steady-in-flight");
    let (a, b) = (dir.join("a"), dir.join("b"));
    for (out, w) in [(&a, "1"), (&b, "12")] {
        succeeded(
            &steady_command("direct", out, "4", &["--in-flight", w])
                .output()
                .unwrap(),
        );
    }
    let (a, b) = (slots(&a), slots(&b));
    assert_eq!(a[0], b[0], "generation 0 does not depend on it");
    assert_ne!(a[1..], b[1..]);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_steady_state_run_killed_or_extended_resumes_to_the_same_result() {
    let dir = scratch("steady-kill");
    let whole = dir.join("whole");
    succeeded(
        &steady_command("lsystem", &whole, "5", &[])
            .output()
            .unwrap(),
    );
    let killed = dir.join("killed");
    let mut child = steady_command("lsystem", &killed, "5", &[])
        .stderr(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let log = killed.join("log.txt");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    loop {
        let lines = std::fs::read_to_string(&log).map_or(0, |t| t.lines().count());
        if lines >= 2 || std::time::Instant::now() > deadline {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    child.kill().unwrap();
    let _ = child.wait();
    let store = RunStore::open(&killed.join("run.sqlite")).unwrap();
    let done = store.last_generation().unwrap();
    drop(store);
    assert!(
        done.is_some_and(|g| g < 4),
        "killed before the end: {done:?}"
    );
    let resume = |dir: &Path, extra: &[&str]| {
        let output = ontogeny_command()
            .arg("evolve")
            .arg("--resume")
            .arg(dir)
            .args(extra)
            .output()
            .unwrap();
        succeeded(&output);
    };
    resume(&killed, &["--threads", "2"]);
    assert_eq!(contents(&whole), contents(&killed));
    // A run of 3 generations extended to 5 is the run of 5.
    let extended = dir.join("extended");
    succeeded(
        &steady_command("lsystem", &extended, "3", &[])
            .output()
            .unwrap(),
    );
    resume(&extended, &["--gens", "5", "--threads", "1"]);
    assert_eq!(contents(&whole), contents(&extended));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bad_steady_state_settings_are_refused_with_exit_code_2() {
    let dir = scratch("steady-bad");
    let out = dir.join("run");
    let run = |extra: &[&str]| steady_command("direct", &out, "2", extra).output().unwrap();
    refused(
        &run(&["--in-flight", "0"]),
        "--in-flight must be 1 to 100000, not 0",
    );
    let mut generational = evolve_walkers("direct", "12");
    generational
        .args(["--gens", "2", "--in-flight", "4", "--out"])
        .arg(&out);
    refused(
        &generational.output().unwrap(),
        "--in-flight is read by algorithm = \"steady-state\" only",
    );
    let bogus = evolve_walkers("direct", "12")
        .args(["--algorithm", "bogus", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(bogus.status.code(), Some(2));
    // In a config file: the file, line and column of the key.
    let config = dir.join("steady.toml");
    std::fs::write(
        &config,
        "[ga]\nalgorithm = \"steady-state\"\nin_flight = 0\n",
    )
    .unwrap();
    let said = refused(
        &evolve_walkers("direct", "12")
            .arg("--config")
            .arg(&config)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap(),
        "in_flight",
    );
    assert!(said.contains("steady.toml:3:"), "{said}");
    // Fresh trials draw anew each generation: only the generational algorithm has them.
    std::fs::write(
        &config,
        "[ga]\nalgorithm = \"steady-state\"\n\n[task.trials]\ncount = 2\nheading = 30\nfresh = true\n",
    )
    .unwrap();
    refused(
        &evolve_walkers("direct", "12")
            .arg("--config")
            .arg(&config)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap(),
        "fresh trials",
    );
    assert!(!out.exists(), "nothing is written for refused settings");
    let _ = std::fs::remove_dir_all(dir);
}
