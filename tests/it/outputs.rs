//! What the command line gives a newcomer to read: `genome show` of every encoding's file,
//! a run's records as CSV and JSON, the runs and comparisons under a directory, a comparison
//! too small for statistics saying so, and messages (the files written, the size of a run)
//! on standard error with results alone on standard output.

use std::path::{Path, PathBuf};

use ontogeny::run::store::RunStore;

use crate::util::{ontogeny, ontogeny_ok, refused, scratch_dir, stderr, stdout, tiny_run};

/// A fresh, empty scratch directory of this module's, named after `name`.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("outputs-{name}"))
}

/// A path as an argument.
fn arg(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// A tiny comparison of lsystem and direct into `out` with one replicate each.
fn one_replicate_comparison(out: &Path) -> std::process::Output {
    ontogeny(&[
        "compare",
        "--encodings",
        "lsystem,direct",
        "--task",
        "walker",
        "--replicates",
        "1",
        "--evaluations",
        "12",
        "--pop",
        "6",
        "--seconds",
        "1",
        "--out",
        arg(out),
    ])
}

#[test]
fn genome_show_recognises_every_encodings_file() {
    for (file, encoding, summary) in [
        ("docs/evolve/walker-best.lsys", "lsystem", "rules: "),
        (
            "docs/evolve/continuous-best.lsys",
            "lsystem-continuous",
            "continuous time: ",
        ),
        ("docs/evolve/direct-best.lsys", "direct", "\naxiom: "),
        (
            "docs/evolve/graph-walker-best.json",
            "graph",
            "graph genome: ",
        ),
    ] {
        let out = stdout(&ontogeny_ok(&["genome", "show", file]));
        assert!(
            out.starts_with(&format!("{file}: {encoding} genome (")),
            "{file}: {out}"
        );
        assert!(out.contains(summary), "{file}: {out}");
        assert!(out.contains("\ndevelops into "), "{file}: {out}");
    }
}

#[test]
fn genome_show_refuses_a_file_that_is_no_genome_naming_it_and_what_it_expected() {
    let dir = scratch("not-a-genome");
    let expected = "expected the text of a genome, .lsys (lsystem, lsystem-continuous, direct) or .json (graph)";
    refused(
        &ontogeny(&["genome", "show", "Cargo.toml"]),
        &format!("Cargo.toml: not a genome file: {expected}"),
    );
    // A grammar no encoding reads back: each encoding says why.
    let grammar = dir.join("open.lsys");
    std::fs::write(&grammar, "environment: 1 2\naxiom: A\nA --> forward(1) A\n").unwrap();
    let said = refused(
        &ontogeny(&["genome", "show", arg(&grammar)]),
        &format!("{}: not a genome file: {expected}", grammar.display()),
    );
    assert!(
        said.contains("as direct: a direct genome's file is an axiom alone"),
        "{said}"
    );
    // A grammar that does not compile: its located error.
    std::fs::write(&grammar, "axiom: F(\n").unwrap();
    refused(
        &ontogeny(&["genome", "show", arg(&grammar)]),
        &format!("{}:1:10", grammar.display()),
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn runs_show_gives_every_generation_as_csv_and_json() {
    let dir = scratch("records");
    let run = dir.join("run");
    tiny_run("lsystem", &run, &[]);
    let store = RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    let generations = store.generations().unwrap();
    assert_eq!(generations.len(), 2);

    let csv = stdout(&ontogeny_ok(&["runs", "show", arg(&run), "--csv"]));
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(
        rows[0],
        [
            "generation",
            "best",
            "best_fine",
            "best_fine_status",
            "mean",
            "median",
            "sd",
            "valid_fraction",
            "evaluations",
            "reused",
            "wall_seconds",
            "evaluations_per_second"
        ]
    );
    assert_eq!(rows.len(), 3);
    for (row, g) in rows[1..].iter().zip(&generations) {
        assert_eq!(row.len(), 12);
        assert_eq!(row[0], g.index.to_string());
        // Every number in full: it reads back to the stored value.
        assert_eq!(row[1].parse::<f64>().unwrap(), g.best);
        let fine = g.best_fine.as_ref().expect("the best is re-walked");
        assert_eq!(row[2].parse::<f64>().unwrap(), fine.fitness);
        assert_eq!(row[3], fine.status);
        assert_eq!(row[8], g.evaluations.to_string());
    }

    let json = stdout(&ontogeny_ok(&["runs", "show", arg(&run), "--json"]));
    let value: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(value["encoding"], "lsystem");
    assert_eq!(value["task"], "walker");
    assert_eq!(value["planned_generations"], 2);
    assert_eq!(value["settings"]["ga"]["population"], 6);
    let shown = value["generations"].as_array().unwrap();
    assert_eq!(shown.len(), 2);
    assert_eq!(shown[1]["generation"], 1);
    assert_eq!(shown[1]["best"].as_f64().unwrap(), generations[1].best);
    assert_eq!(shown[1]["evaluations"], generations[1].evaluations);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn runs_list_lists_runs_and_comparisons_and_a_damaged_one_with_its_error() {
    let dir = scratch("list");
    tiny_run("lsystem", &dir.join("runs").join("walker"), &[]);
    assert!(one_replicate_comparison(&dir.join("cmp")).status.success());
    std::fs::create_dir_all(dir.join("runs").join("broken")).unwrap();
    std::fs::write(dir.join("runs").join("broken").join("run.sqlite"), "junk").unwrap();
    let o = ontogeny_ok(&["runs", "list", arg(&dir)]);
    let lines: Vec<String> = stdout(&o).lines().map(str::to_string).collect();
    let at = |p: &str| format!("{}  ", dir.join(p).display());
    assert_eq!(lines.len(), 5, "{lines:?}");
    assert!(lines[0].starts_with(&format!("{}comparison  lsystem,direct  walker, normalised (Chaumont eq. 1)  2/2 replicates finished  best ", at("cmp"))), "{lines:?}");
    assert!(
        lines[1].starts_with(&format!("{}run  direct  walker", at("cmp/direct/rep-1"))),
        "{lines:?}"
    );
    assert!(
        lines[2].starts_with(&format!("{}run  lsystem  walker", at("cmp/lsystem/rep-1"))),
        "{lines:?}"
    );
    assert!(
        lines[3].starts_with(&format!("{}run  error: ", at("runs/broken"))),
        "{lines:?}"
    );
    assert!(
        lines[4].starts_with(&format!(
            "{}run  lsystem  walker, normalised (Chaumont eq. 1)  2/2 generations  best ",
            at("runs/walker")
        )),
        "{lines:?}"
    );
    refused(
        &ontogeny(&["runs", "list", arg(&dir.join("nothing"))]),
        "cannot read",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_comparison_of_one_replicate_says_it_has_no_statistics() {
    let dir = scratch("one-replicate");
    let out = dir.join("cmp");
    let o = one_replicate_comparison(&out);
    let said = stdout(&o);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        said.contains("2 replicates of 11 evaluations each (1 per encoding)"),
        "{said}"
    );
    assert!(
        said.contains("no statistics for lsystem, direct: fewer than 2 finished replicates"),
        "{said}"
    );
    assert!(said.contains("(no spread;"), "{said}");
    // No pair is tested (the power line names A12 = 0.71, the effect it is stated for).
    assert!(!said.contains("NaN") && !said.contains(": U "), "{said}");
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        report.contains("1 replicate per encoding, seed 1;"),
        "{report}"
    );
    assert!(
        report.contains("**No statistics** for lsystem, direct"),
        "{report}"
    );
    assert!(!report.contains("| a | b | U |"), "{report}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_run_says_its_size_first_and_its_files_on_standard_error() {
    let dir = scratch("evolve-says");
    let run = dir.join("run");
    let o = tiny_run("lsystem", &run, &[]);
    let (out, err) = (stdout(&o), stderr(&o));
    assert!(err.starts_with("evolving lsystem on walker, normalised (Chaumont eq. 1): population 6 × 2 generations = 11 evaluations"), "{err}");
    assert!(err.contains("\ngeneration 0 took "), "{err}");
    assert!(
        err.contains(&format!("wrote {}/run.sqlite", run.display())),
        "{err}"
    );
    // Standard output holds the result alone.
    assert_eq!(out.lines().count(), 1, "{out}");
    assert!(
        out.starts_with(&format!("{}: walker", run.display())),
        "{out}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn export_to_a_file_says_what_it_wrote() {
    let dir = scratch("export");
    let model = dir.join("quadruped.xml");
    let o = ontogeny_ok(&["export", "examples/quadruped.lsys", "--out", arg(&model)]);
    assert_eq!(stdout(&o), "");
    assert_eq!(stderr(&o), format!("wrote {}\n", model.display()));
    assert!(model.is_file());
    let _ = std::fs::remove_dir_all(&dir);
}
