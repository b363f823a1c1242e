//! A run's profile (`evolve --profile FILE`): every walk the evaluator simulated once, on a
//! thread of the run's, with a positive time, the steps of each generation within its whole;
//! a profiled run the same to the digit as one not profiled, on one thread or two and resumed;
//! and the schedule simulator (`runs schedule`) giving the makespans computed by hand.

use std::collections::BTreeSet;
use std::path::Path;
use std::process::Output;

use ontogeny::run::profile::{GenerationProfile, read_profile};
use ontogeny::run::store::RunStore;

use crate::util::{
    assert_bad_input, evolve_walkers, ontogeny, ontogeny_command, scratch_dir, stdout, succeeded,
};

/// Walkers: a population of 8, `gens` generations of 1 s walks, into `out` (and `extra`
/// flags).
fn walkers_for(gens: &str, out: &Path, extra: &[&str]) -> Output {
    let output = evolve_walkers("lsystem", "8")
        .args(["--gens", gens, "--seconds", "1"])
        .args(extra)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    succeeded(&output);
    output
}

/// [`walkers_for`] 3 generations.
fn walkers(out: &Path, extra: &[&str]) -> Output {
    walkers_for("3", out, extra)
}

/// The individuals of generation `g` of the run in `dir` that the evaluator walked: those
/// neither carried over (the elite) nor reused from the cache, that developed (have a key).
fn walked(dir: &Path, g: u32) -> BTreeSet<u32> {
    let store = RunStore::open_read_only(&dir.join("run.sqlite")).unwrap();
    store
        .individuals(g)
        .unwrap()
        .into_iter()
        .filter(|i| i.operator != "elite" && !i.reused && i.evaluation_key.is_some())
        .map(|i| i.index)
        .collect()
}

#[test]
fn a_profile_holds_every_walk_once_with_its_time_and_thread() {
    let dir = scratch_dir("profile-contents");
    let run = dir.join("run");
    let profile = dir.join("profile.jsonl");
    walkers(
        &run,
        &["--threads", "2", "--profile", profile.to_str().unwrap()],
    );
    let generations: Vec<GenerationProfile> = read_profile(&profile).unwrap();
    let stored = RunStore::open_read_only(&run.join("run.sqlite"))
        .unwrap()
        .generations()
        .unwrap();
    assert_eq!(generations.len(), 3);
    let mut walks = 0;
    for (g, s) in generations.iter().zip(&stored) {
        assert_eq!(g.generation, s.index);
        assert_eq!((g.threads, g.ranks), (2, 1));
        assert_eq!(g.evaluations, s.evaluations);
        // Every walked individual once, and no other.
        let individuals: Vec<u32> = g.walks.iter().map(|w| w.individual).collect();
        let once: BTreeSet<u32> = individuals.iter().copied().collect();
        assert_eq!(once.len(), individuals.len(), "generation {}", g.generation);
        assert_eq!(
            once,
            walked(&run, g.generation),
            "generation {}",
            g.generation
        );
        for w in &g.walks {
            assert!(w.seconds > 0.0 && w.thread < 2 && w.rank == 0, "{w:?}");
            // A walk lies within its batch, ...
            assert!(w.seconds <= g.evaluating, "{w:?} in {}", g.evaluating);
        }
        // ... and two threads walk at most twice the batch's time.
        let walking: f64 = g.walks.iter().map(|w| w.seconds).sum();
        assert!(walking <= 2.0 * g.evaluating);
        // The steps add up to the whole.
        let steps = g.breeding + g.developing + g.keying + g.evaluating + g.fine + g.writing;
        assert!(g.breeding > 0.0 && g.developing > 0.0 && g.writing > 0.0);
        assert!((steps + g.other - g.total).abs() < 1e-9, "{g:?}");
        walks += g.walks.len();
    }
    // The first generation's best is re-walked at the fine reference, beside the next
    // generation: the walk's own seconds are recorded, and the wait for it is no longer.
    assert!(generations[0].fine_walk.is_some_and(|walk| walk > 0.0));
    assert!(generations[0].fine <= generations[0].fine_walk.unwrap());
    assert!(generations.iter().all(|g| g.fine_walk.is_some()));
    // Replayed as walked alone: the walk in place of the wait, the whole still the sum.
    let alone = generations[0].walked_alone();
    assert_eq!(alone.fine, generations[0].fine_walk.unwrap());
    assert_eq!(alone.fine_walk, None);
    let steps = alone.breeding + alone.developing + alone.keying + alone.evaluating;
    assert!((steps + alone.fine + alone.writing + alone.other - alone.total).abs() < 1e-9);
    assert!(walks > 0);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_profiled_run_is_the_same_as_one_not_profiled_on_one_or_two_threads_and_resumed() {
    let dir = scratch_dir("profile-same");
    walkers(&dir.join("plain"), &["--threads", "1"]);
    let plain = crate::evolve::contents(&dir.join("plain"));
    for threads in ["1", "2"] {
        let run = dir.join(format!("profiled-{threads}"));
        let profile = dir.join(format!("profile-{threads}.jsonl"));
        walkers(
            &run,
            &["--threads", threads, "--profile", profile.to_str().unwrap()],
        );
        assert_eq!(crate::evolve::contents(&run), plain, "{threads} threads");
    }
    // Stopped after two generations, then resumed with a profile of its own: the profile
    // holds the generation the resume made, and the run is the same.
    let stopped = dir.join("stopped");
    walkers_for("2", &stopped, &[]);
    let profile = dir.join("resumed.jsonl");
    let resumed = ontogeny_command()
        .args(["evolve", "--gens", "3", "--profile"])
        .arg(&profile)
        .arg("--resume")
        .arg(&stopped)
        .output()
        .unwrap();
    succeeded(&resumed);
    assert_eq!(crate::evolve::contents(&stopped), plain);
    let generations: Vec<u32> = read_profile(&profile)
        .unwrap()
        .iter()
        .map(|g| g.generation)
        .collect();
    assert_eq!(generations, [2]);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_walk_order_changes_no_result_on_one_two_or_three_threads() {
    let dir = scratch_dir("profile-walk-order");
    walkers(
        &dir.join("index"),
        &["--threads", "1", "--walk-order", "index"],
    );
    let plain = crate::evolve::contents(&dir.join("index"));
    for threads in ["1", "2", "3"] {
        let run = dir.join(format!("longest-{threads}"));
        let profile = dir.join(format!("longest-{threads}.jsonl"));
        walkers(
            &run,
            &["--threads", threads, "--profile", profile.to_str().unwrap()],
        );
        assert_eq!(crate::evolve::contents(&run), plain, "{threads} threads");
        // The walks were handed out by their creatures' parts, most first, ties in the
        // individuals' order.
        for g in read_profile(&profile).unwrap() {
            let handed: Vec<(u32, u32)> = g.walks.iter().map(|w| (w.parts, w.individual)).collect();
            let mut sorted = handed.clone();
            sorted.sort_by_key(|&(parts, individual)| (std::cmp::Reverse(parts), individual));
            assert_eq!(handed, sorted, "generation {}", g.generation);
            // The creatures' sizes are recorded (a creature with no part walks too, briefly).
            assert!(handed.iter().any(|&(parts, _)| parts > 0), "{handed:?}");
        }
    }
    // In the individuals' order, on two threads: the same run, its walks in their order.
    let profile = dir.join("index-2.jsonl");
    walkers(
        &dir.join("index-2"),
        &[
            "--threads",
            "2",
            "--walk-order",
            "index",
            "--profile",
            profile.to_str().unwrap(),
        ],
    );
    assert_eq!(crate::evolve::contents(&dir.join("index-2")), plain);
    for g in read_profile(&profile).unwrap() {
        let individuals: Vec<u32> = g.walks.iter().map(|w| w.individual).collect();
        assert!(individuals.is_sorted(), "{individuals:?}");
    }
    assert_bad_input(
        &["evolve", "--walk-order", "shortest"],
        "invalid value 'shortest' for '--walk-order <ORDER>'",
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// A profile's line: one generation of `walks` (seconds, each on thread 0), `outside` seconds
/// of breeding, and `evaluations` individuals evaluated.
fn line(generation: u32, walks: &[f64], outside: f64, evaluations: u64) -> String {
    let evaluating: f64 = walks.iter().sum();
    let walks: Vec<String> = walks
        .iter()
        .enumerate()
        .map(|(i, s)| format!(r#"{{"individual":{i},"seconds":{s},"thread":0,"rank":0}}"#))
        .collect();
    format!(
        r#"{{"generation":{generation},"threads":1,"ranks":1,"evaluations":{evaluations},"breeding":{outside},"developing":0,"keying":0,"evaluating":{evaluating},"fine":0,"writing":0,"other":0,"total":{},"walks":[{}]}}"#,
        outside + evaluating,
        walks.join(",")
    )
}

#[test]
fn the_schedule_simulator_gives_the_hand_computed_makespans() {
    let dir = scratch_dir("profile-schedule");
    let profile = dir.join("hand.jsonl");
    // One generation: walks of 3, 1, 1, 1 and 2 s, and 0.5 s outside evaluation.
    std::fs::write(&profile, line(0, &[3.0, 1.0, 1.0, 1.0, 2.0], 0.5, 5) + "\n").unwrap();
    let path = profile.to_str().unwrap();
    let out = ontogeny(&["runs", "schedule", path, "--threads", "1,2,3,8", "--json"]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&succeeded_output(out))).unwrap();
    let seconds: Vec<f64> = json["predictions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["seconds"].as_f64().unwrap())
        .collect();
    // 1 thread: 8 s of walks. 2: the 3 on one, the three 1s on the other, the 2 after the 3
    // on whichever is free first (both at 3 s): 5 s (greedy; the best packing is 4). 3: 3 s.
    // 8: the longest, 3 s. Each + 0.5 s.
    assert_eq!(seconds, [8.5, 5.5, 3.5, 3.5]);
    assert_eq!(
        json["predictions"][1]["evaluations_per_second"].as_f64(),
        Some(5.0 / 5.5)
    );
    assert_eq!(
        json["recorded"]["evaluations_per_second"].as_f64(),
        Some(5.0 / 8.5)
    );
    // The table names one generation in the singular.
    let text = stdout(&succeeded_output(ontogeny(&["runs", "schedule", path])));
    assert!(
        text.contains(": 1 generation, 5 evaluations, 5 walks"),
        "{text}"
    );
    // With 2 ranks of 1 thread: 2 threads.
    let out = ontogeny(&[
        "runs",
        "schedule",
        path,
        "--threads",
        "1",
        "--ranks",
        "2",
        "--json",
    ]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&succeeded_output(out))).unwrap();
    assert_eq!(json["predictions"][0]["seconds"].as_f64(), Some(5.5));
    // Two generations (the second's 3 evaluations with 2 walks, one reused): each waits for
    // its last walk: 3 | 2 + 1, then 1 and 1 (4 s), then 2 | 1 (2 s) on 2 threads.
    std::fs::write(
        &profile,
        line(0, &[3.0, 2.0, 1.0, 1.0, 1.0], 0.0, 5) + "\n" + &line(1, &[2.0, 1.0], 0.0, 3),
    )
    .unwrap();
    let text = stdout(&succeeded_output(ontogeny(&[
        "runs",
        "schedule",
        path,
        "--threads",
        "2",
    ])));
    // 8 evaluations in 6 s on 2 threads: 1.33 a second, 1.83× one thread's 11 s, 0.917 of
    // two one-thread runs; the threads walk 11 of their 12 s.
    assert!(
        text.contains("2 generations, 8 evaluations, 7 walks"),
        "{text}"
    );
    assert!(
        text.lines()
            .any(|l| l.split_whitespace().collect::<Vec<_>>()
                == ["1", "2", "1.33", "1.83×", "0.917", "0.917"]),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_simulator_models_the_levers_on_a_profile_recorded_without_them() {
    let dir = scratch_dir("profile-levers");
    let profile = dir.join("levers.jsonl");
    // Generation 0: walks of 1, 1, 1 and 3 s by creatures of 2, 2, 3 and 9 parts, 0.5 s
    // outside evaluation of which 0.4 s re-walking its best at the fine reference;
    // generation 1: walks of 2 and 2 s by 4-part creatures, the same 0.5 s outside.
    let with = |line: String, parts: &[u32]| {
        let mut value: serde_json::Value = serde_json::from_str(&line).unwrap();
        for (w, &p) in value["walks"].as_array_mut().unwrap().iter_mut().zip(parts) {
            w["parts"] = p.into();
        }
        value["fine"] = 0.4.into();
        value["breeding"] = 0.1.into();
        value.to_string()
    };
    std::fs::write(
        &profile,
        with(line(0, &[1.0, 1.0, 1.0, 3.0], 0.5, 4), &[2, 2, 3, 9])
            + "\n"
            + &with(line(1, &[2.0, 2.0], 0.5, 2), &[4, 4]),
    )
    .unwrap();
    let path = profile.to_str().unwrap();
    let seconds = |levers: &[&str]| {
        let out = ontogeny(
            &[
                &["runs", "schedule", path, "--threads", "2", "--json"],
                levers,
            ]
            .concat(),
        );
        let json: serde_json::Value =
            serde_json::from_str(&stdout(&succeeded_output(out))).unwrap();
        json["predictions"][0]["seconds"].as_f64().unwrap()
    };
    // As recorded, on 2 threads: 1 | 1, the third 1 to the first thread (1-2), the 3 to the
    // second (1-4): 4 s; then 2 | 2: 2 s; + 1 s outside: 7 s.
    assert_eq!(seconds(&[]), 7.0);
    // Longest first: the 3 (9 parts) | 1, 1, 1: 3 s; then 2 s; + 1: 6 s.
    assert_eq!(seconds(&["--longest-first"]), 6.0);
    // The fine re-walk beside: generation 0 keeps 0.1 s outside, generation 1 walks 0.4 | 2,
    // then 2 (0.4-2.4): 4 + 2.4 + 0.1 + 0.5 = 7 s.
    assert!((seconds(&["--fine-beside"]) - 7.0).abs() < 1e-9);
    // Both: 3 + 2.4 + 0.6 = 6 s.
    assert!((seconds(&["--longest-first", "--fine-beside"]) - 6.0).abs() < 1e-9);
    // A profile without the creatures' sizes cannot be ordered by them.
    std::fs::write(&profile, line(0, &[1.0, 2.0], 0.0, 2)).unwrap();
    assert_bad_input(
        &["runs", "schedule", path, "--longest-first"],
        "records no creature sizes",
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_simulator_replays_a_profile_as_a_steady_state_run_and_projects_it() {
    let dir = scratch_dir("profile-steady");
    let profile = dir.join("steady.jsonl");
    // A population of 2 (walks of 3 and 1 s), then three generations of one birth (1 s
    // each); nothing outside.
    std::fs::write(
        &profile,
        [
            line(0, &[3.0, 1.0], 0.0, 2),
            line(1, &[1.0], 0.0, 1),
            line(2, &[1.0], 0.0, 1),
            line(3, &[1.0], 0.0, 1),
        ]
        .join("\n"),
    )
    .unwrap();
    let path = profile.to_str().unwrap();
    let json = |flags: &[&str]| -> serde_json::Value {
        let out = ontogeny(&[&["runs", "schedule", path, "--json"], flags].concat());
        serde_json::from_str(&stdout(&succeeded_output(out))).unwrap()
    };
    let seconds = |flags: &[&str]| json(flags)["predictions"][0]["seconds"].as_f64().unwrap();
    // Generational on 2 threads: 3 | 1, then 1, 1, 1: 6 s.
    assert_eq!(seconds(&["--threads", "2"]), 6.0);
    // Steady-state, 1 in flight: births 0 and 1 at once (0-3, 0-1), integrated at 3; birth 2
    // is bred from generation 0 (3-4), birth 3 from generation 1 once birth 2 is in (4-5),
    // birth 4 from generation 2 (5-6): 6 s.
    let one = json(&["--threads", "2", "--steady-state", "1"]);
    assert_eq!(one["algorithm"], "steady-state");
    assert_eq!(one["in_flight"], 1);
    assert_eq!(one["predictions"][0]["seconds"].as_f64(), Some(6.0));
    // 2 in flight: births 2 and 3 from generation 0 (3-4 each), birth 4 from generation 1
    // (4-5): 5 s.
    assert_eq!(seconds(&["--threads", "2", "--steady-state", "2"]), 5.0);
    // A driver of 0.5 s an evaluation before each birth: births handed at 0.5 and 1 (0.5-3.5,
    // 1-2), integrated at 3.5; birth 2 at 4 (4-5), birth 3 at 4.5 (4.5-5.5), birth 4 once
    // birth 2 is in (5), at 5.5: 5.5-6.5.
    assert!(
        (seconds(&[
            "--threads",
            "2",
            "--steady-state",
            "2",
            "--driver-us",
            "500000"
        ]) - 6.5)
            .abs()
            < 1e-9
    );
    // The same driver generationally: 1 + 3, then 0.5 + 1 three times: 8.5 s.
    assert!((seconds(&["--threads", "2", "--driver-us", "500000"]) - 8.5).abs() < 1e-9);
    // Drawn generations: 3 of 50 walks, each one of the five recorded, the same every time.
    let drawn = json(&["--population", "50", "--generations", "3", "--threads", "4"]);
    assert_eq!(drawn["recorded"]["evaluations"], 150);
    assert_eq!(drawn["recorded"]["walks"], 150);
    assert_eq!(
        drawn,
        json(&["--population", "50", "--generations", "3", "--threads", "4"])
    );
    let table = stdout(&succeeded_output(ontogeny(&[
        "runs",
        "schedule",
        path,
        "--population",
        "50",
        "--threads",
        "4",
    ])));
    assert!(
        table.contains("drawn into 4 generations of 50") && table.contains("not measured"),
        "{table}"
    );
    // Bad values are refused, by flag.
    assert_bad_input(
        &["runs", "schedule", path, "--steady-state", "0"],
        "--steady-state must be 1 to 100000, not 0",
    );
    // The most births in flight `evolve --in-flight` takes, and not one more.
    assert_bad_input(
        &["runs", "schedule", path, "--steady-state", "100001"],
        "--steady-state must be 1 to 100000, not 100001",
    );
    assert_bad_input(
        &["runs", "schedule", path, "--driver-us", "NaN"],
        "--driver-us must be 0 to 1000000, not NaN",
    );
    assert_bad_input(
        &[
            "runs",
            "schedule",
            path,
            "--population",
            "1000000",
            "--generations",
            "1000",
        ],
        "draw fewer",
    );
    assert_bad_input(
        &[
            "runs",
            "schedule",
            path,
            "--steady-state",
            "4",
            "--longest-first",
        ],
        "cannot be used with",
    );
    let _ = std::fs::remove_dir_all(dir);
}

fn succeeded_output(output: Output) -> Output {
    succeeded(&output);
    output
}

#[test]
fn a_bad_profile_or_machine_is_refused_with_exit_code_2() {
    let dir = scratch_dir("profile-bad");
    let profile = dir.join("bad.jsonl");
    std::fs::write(
        &profile,
        line(0, &[1.0], 0.0, 1) + "\n{\"generation\": 1}\n",
    )
    .unwrap();
    let path = profile.to_str().unwrap();
    assert_bad_input(&["runs", "schedule", path], "bad.jsonl:2: not a generation");
    std::fs::write(&profile, line(0, &[-1.0, 2.0], 0.0, 1)).unwrap();
    assert_bad_input(&["runs", "schedule", path], "walk 0 took -1 s");
    std::fs::write(&profile, "\n").unwrap();
    assert_bad_input(&["runs", "schedule", path], "no generation in the profile");
    std::fs::write(&profile, line(0, &[1.0], 0.0, 1)).unwrap();
    assert_bad_input(
        &["runs", "schedule", path, "--threads", "0"],
        "--threads must be 1 to 1024, not 0",
    );
    assert_bad_input(
        &["runs", "schedule", path, "--ranks", "2000"],
        "--ranks must be 1 to 1024, not 2000",
    );
    let missing = dir.join("missing.jsonl");
    assert_bad_input(
        &["runs", "schedule", missing.to_str().unwrap()],
        "missing.jsonl",
    );
    // A profile that is a directory is refused before the run starts.
    let out = dir.join("run");
    assert_bad_input(
        &[
            "evolve",
            "--task",
            "walker",
            "--pop",
            "4",
            "--gens",
            "1",
            "--seconds",
            "1",
            "--profile",
            dir.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        "not a regular file",
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_scaling_benchmark_runs_the_readme_s_evolution() {
    // benches/scaling.sh carries its own copy of examples/evolve-walker.toml (it runs from
    // the binary alone): the two hold the same settings.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let script = std::fs::read_to_string(root.join("benches/scaling.sh")).unwrap();
    let start = script
        .find("<<'TOML'\n")
        .expect("the script's configuration")
        + 9;
    let length = script[start..].find("\nTOML\n").expect("its end");
    let copy: toml::Table = toml::from_str(&script[start..start + length]).unwrap();
    let example = std::fs::read_to_string(root.join("examples/evolve-walker.toml")).unwrap();
    let example: toml::Table = toml::from_str(&example).unwrap();
    assert_eq!(copy, example);
}
