//! The `--json` outputs of `evolve` (its final line), `compare`, `genome show` and `bench`:
//! one JSON object on standard output, parsed here, with the figures the text gives.

use std::path::{Path, PathBuf};

use ontogeny::run::store::RunStore;
use serde_json::Value;

use crate::util::{ontogeny, ontogeny_command, scratch_dir, stderr, stdout};

/// A fresh, empty scratch directory of this module's, named after `name`.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("json-{name}"))
}

/// Standard output of a command that succeeded, parsed as one JSON object.
fn object(o: &std::process::Output) -> Value {
    assert!(o.status.success(), "{}", stderr(o));
    let value: Value = serde_json::from_str(&stdout(o))
        .unwrap_or_else(|e| panic!("not one JSON object ({e}): {}", stdout(o)));
    assert!(value.is_object(), "{value}");
    value
}

#[test]
fn evolve_json_prints_the_final_line_as_one_object_and_genome_show_json_its_champion() {
    let dir = scratch("evolve");
    let run = dir.join("run");
    let o = ontogeny_command()
        .args([
            "evolve",
            "--encoding",
            "direct",
            "--task",
            "walker",
            "--pop",
            "4",
            "--gens",
            "2",
            "--seconds",
            "0.5",
            "--seed",
            "3",
            "--json",
            "--out",
        ])
        .arg(&run)
        .output()
        .unwrap();
    let json = object(&o);
    let store = RunStore::open(&run.join("run.sqlite")).unwrap();
    let generations = store.generations().unwrap();
    let last = generations.last().unwrap();
    assert_eq!(json["dir"], run.display().to_string());
    assert_eq!(json["encoding"], "direct");
    assert_eq!(json["fitness"], "walker, normalised (Chaumont eq. 1)");
    assert_eq!(json["generation"], 1);
    assert_eq!(json["best"].as_f64(), Some(last.best));
    let fine = last.best_fine.as_ref().unwrap();
    assert_eq!(json["best_fine"]["fitness"].as_f64(), Some(fine.fitness));
    assert_eq!(json["best_fine"]["status"], fine.status);
    let evaluations: u64 = generations.iter().map(|g| g.evaluations).sum();
    let reused: u64 = generations.iter().map(|g| g.reused).sum();
    assert_eq!(json["evaluations"], evaluations);
    assert_eq!(json["simulated"], evaluations - reused);
    assert!(json["seconds"].as_f64().unwrap() > 0.0);
    let files: Vec<&str> = json["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    assert_eq!(files.len(), 4);
    assert!(
        files.iter().all(|f| std::path::Path::new(f).is_file()),
        "{files:?}"
    );
    // The progress lines stay on standard error.
    assert!(stderr(&o).contains("generation 0: "), "{}", stderr(&o));
    // Resuming the finished run prints the same object, with nothing evaluated this time.
    let again = object(
        &ontogeny_command()
            .args(["evolve", "--json", "--resume"])
            .arg(&run)
            .output()
            .unwrap(),
    );
    for key in [
        "dir",
        "encoding",
        "fitness",
        "generation",
        "best",
        "best_fine",
        "files",
    ] {
        assert_eq!(again[key], json[key], "{key}");
    }
    assert_eq!(again["evaluations"], 0);
    assert_eq!(again["simulated"], 0);
    assert_eq!(again["seconds"], 0.0);

    // The champion's genome, shown as JSON: what the text says, as numbers.
    let best = run.join("best.lsys");
    let text = ontogeny(&["genome", "show", best.to_str().unwrap()]);
    let json = object(&ontogeny(&[
        "genome",
        "show",
        best.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(json["encoding"], "direct");
    assert_eq!(json["develops"], true);
    assert!(json["error"].is_null());
    let parts = json["creature"]["parts"].as_u64().unwrap();
    assert!(
        stdout(&text).contains(&format!("develops into {parts} part")),
        "{}",
        stdout(&text)
    );
    assert!(
        stdout(&text).contains(json["genome"].as_str().unwrap()),
        "{}",
        stdout(&text)
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn compare_json_prints_each_encodings_figures_and_the_pairwise_test() {
    let dir = scratch("compare");
    let out = dir.join("cmp");
    let o = ontogeny_command()
        .args([
            "compare",
            "--encodings",
            "direct,lsystem",
            "--task",
            "walker",
            "--replicates",
            "2",
            "--evaluations",
            "9",
            "--pop",
            "4",
            "--seconds",
            "0.5",
            "--seed",
            "4",
            "--json",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let json = object(&o);
    assert_eq!(json["dir"], out.display().to_string());
    assert_eq!(json["replicates"], 4);
    assert_eq!(json["unfinished"], serde_json::json!([]));
    let encodings = json["encodings"].as_array().unwrap();
    let names: Vec<&str> = encodings
        .iter()
        .map(|e| e["encoding"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["direct", "lsystem"]);
    for e in encodings {
        assert_eq!(e["replicates"], 2);
        assert!(e["best"]["mean"].is_f64(), "{e}");
    }
    let pairs = json["pairs"].as_array().unwrap();
    assert_eq!(pairs.len(), 1);
    assert_eq!(pairs[0]["a"], "direct");
    assert_eq!(pairs[0]["b"], "lsystem");
    let p = pairs[0]["p"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&p), "{p}");
    // The mean of the replicates' best, as summary.csv lists them.
    let csv = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let bests: Vec<f64> = csv
        .lines()
        .filter(|l| l.starts_with("direct,"))
        .map(|l| l.split(',').nth(4).unwrap().parse().unwrap())
        .collect();
    assert_eq!(bests.len(), 2);
    let mean = encodings[0]["best"]["mean"].as_f64().unwrap();
    assert!(
        (mean - (bests[0] + bests[1]) / 2.0).abs() <= 1e-12 * mean.abs().max(1e-300),
        "{mean}: {csv}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bench_json_prints_one_creatures_speed_and_is_refused_with_fidelity() {
    let json = object(&ontogeny(&[
        "bench",
        "--creature",
        "examples/quadruped.lsys",
        "--evaluations",
        "1",
        "--seconds",
        "0.2",
        "--json",
    ]));
    assert_eq!(json["creature"], "examples/quadruped.lsys");
    assert_eq!(json["evaluations"], 1);
    assert_eq!(json["seconds"], 0.2);
    assert!(json["evaluations_per_second"].as_f64().unwrap() > 0.0);
    assert!(json["us_per_step"].as_f64().unwrap() > 0.0);
    let o = ontogeny(&["bench", "--fidelity", "2", "--json"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o),
        "error: --json is for the speed figures: give it without --fidelity\n"
    );
    assert!(stdout(&o).is_empty());
}

/// `ontogeny evolve ARGS --out MINE`, MINE a folder of the user's in `dir` (it holds
/// `notes.txt`): refused (exit code 2) once the settings are resolved, after any note.
/// Returns the folder and the standard error.
fn evolve_into_a_folder_of_the_users(dir: &Path, args: &[&str]) -> (PathBuf, String) {
    let mine = dir.join("mine");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "mine").unwrap();
    let o = ontogeny_command()
        .arg("evolve")
        .args(args)
        .arg("--out")
        .arg(&mine)
        .output()
        .unwrap();
    let said = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {said}");
    (mine, said)
}

#[test]
fn the_walker_examples_note_gives_the_walks_that_seconds_sets() {
    let dir = scratch("default-seconds");
    let (_, said) = evolve_into_a_folder_of_the_users(&dir, &["--seconds", "2.5"]);
    assert!(
        said.contains(
            "100 creatures × 40 generations of 2.5-second walks (--seconds), fitness distance"
        ),
        "{said}"
    );
}

#[test]
fn evolve_with_nothing_about_the_runs_size_starts_the_walker_example_and_says_so() {
    let dir = scratch("default");
    let (mine, said) = evolve_into_a_folder_of_the_users(&dir, &[]);
    assert!(
        said.starts_with(
            "note: no --config, --preset, --pop or --gens: starting the walker example (examples/evolve-walker.toml, built in"
        ),
        "{said}"
    );
    assert_eq!(
        std::fs::read_to_string(mine.join("notes.txt")).unwrap(),
        "mine"
    );
    // With a size, no note; settings out of range are refused before any note.
    for args in [&["--pop", "4"][..], &["--seconds", "5000"][..]] {
        let (_, said) = evolve_into_a_folder_of_the_users(&dir, args);
        assert!(!said.contains("note: no --config"), "{args:?}: {said}");
    }
    let _ = std::fs::remove_dir_all(dir);
}
