//! `ontogeny compare` end to end: equal budgets, `--plan` commands merged equal a direct
//! comparison, a comparison killed and resumed equals an uninterrupted one, and bad input
//! exits 2 without losing anything computed.

use std::path::{Path, PathBuf};
use std::process::Command;

use ontogeny::run::store::RunStore;

use crate::util::{ontogeny_command, refused, scratch_dir, stderr, succeeded};

/// A fresh, empty scratch directory of this module's, named after `name`.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("compare-{name}"))
}

/// Every encoding the tests compare.
const ENCODINGS: &str = "lsystem,lsystem-continuous,direct";

/// The tiny comparison's flags: 2 replicates, population 6, 16 evaluations (3 generations:
/// 6 + 5 + 5, the elite of 1 not re-evaluated), 1 s walks.
fn tiny(out: &Path) -> Command {
    let mut c = ontogeny_command();
    c.args([
        "compare",
        "--encodings",
        ENCODINGS,
        "--task",
        "walker",
        "--replicates",
        "2",
        "--evaluations",
        "17",
        "--pop",
        "6",
        "--seconds",
        "1",
        "--seed",
        "4",
        "--out",
    ])
    .arg(out);
    c
}

/// The report's numbers without wall-clock figures: `summary.csv` without its last column
/// (wall seconds) and `report.md` without its evaluations-per-second column.
fn numbers(dir: &Path) -> String {
    let csv = std::fs::read_to_string(dir.join("summary.csv")).unwrap();
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    let mut out = String::new();
    for line in csv.lines() {
        out += &line[..line.rfind(',').unwrap()];
        out.push('\n');
    }
    for line in md.lines() {
        if line.starts_with("| lsystem") || line.starts_with("| direct") {
            let cells: Vec<&str> = line.split('|').collect();
            // A line of the encodings' table has 13 cells; drop evaluations/s.
            let keep = if cells.len() == 15 {
                &cells[..13]
            } else {
                &cells[..]
            };
            out += &keep.join("|");
            out.push('\n');
        }
    }
    out
}

fn evaluations_in(run: &Path) -> u64 {
    let store = RunStore::open(&run.join("run.sqlite")).unwrap();
    store
        .generations()
        .unwrap()
        .iter()
        .map(|g| g.evaluations)
        .sum()
}

#[test]
fn every_replicate_gets_exactly_the_same_evaluations() {
    let dir = scratch("budget");
    let out = dir.join("cmp");
    let stdout = succeeded(&tiny(&out).output().unwrap());
    assert!(
        stdout.contains("6 replicates of 16 evaluations"),
        "{stdout}"
    );
    for encoding in ENCODINGS.split(',') {
        for k in 1..=2 {
            let run = out.join(encoding).join(format!("rep-{k}"));
            // A budget of 17 buys 3 generations: 6 + 5 + 5 = 16 (a fourth would need 21).
            assert_eq!(evaluations_in(&run), 16, "{}", run.display());
            // Each replicate is an ordinary run directory.
            let shown = succeeded(
                &ontogeny_command()
                    .args(["runs", "show"])
                    .arg(&run)
                    .output()
                    .unwrap(),
            );
            assert!(shown.contains(&format!("{encoding} encoding")), "{shown}");
            let resumed = ontogeny_command()
                .args(["evolve", "--resume"])
                .arg(&run)
                .output()
                .unwrap();
            succeeded(&resumed);
            let said = stderr(&resumed);
            assert!(said.contains("nothing to resume"), "{said}");
        }
    }
    // The same seed for replicate k of every encoding, different seeds for k = 1, 2.
    let csv = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let seeds: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap())
        .collect();
    assert_eq!(seeds.len(), 6);
    assert_eq!(seeds[0], seeds[2]);
    assert_ne!(seeds[0], seeds[1]);
    // Each replicate's final champion re-walked at the fine reference: its last generation's
    // stored value, and the report's mean of them.
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(header[4..6], ["best_fitness", "best_fine"]);
    let mut fine_of = std::collections::BTreeMap::<&str, Vec<f64>>::new();
    for line in csv.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let run = out.join(cells[0]).join(format!("rep-{}", cells[1]));
        let store = RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
        let last = store.generations().unwrap().pop().unwrap();
        let stored = last.best_fine.expect("compare verifies the best").fitness;
        assert_eq!(cells[5].parse::<f64>().unwrap(), stored, "{line}");
        fine_of.entry(cells[0]).or_default().push(stored);
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    for (encoding, values) in fine_of {
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let row = md
            .lines()
            .find(|l| l.starts_with(&format!("| {encoding} | 2 |")))
            .unwrap();
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        assert_eq!(cells[4], format!("{mean:.4}"), "{row}");
    }
    for file in ["report.md", "fitness.svg", "parts.svg"] {
        assert!(out.join(file).is_file(), "{file}");
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("every replicate made exactly 16 evaluations (budget 17"));
    assert!(md.contains("| lsystem | direct |"), "{md}");
    // Resuming a complete comparison runs nothing and writes the same report.
    let before = numbers(&out);
    succeeded(
        &ontogeny_command()
            .args(["compare", "--resume"])
            .arg(&out)
            .output()
            .unwrap(),
    );
    assert_eq!(numbers(&out), before);
    let _ = std::fs::remove_dir_all(dir);
}

/// Runs one line of `compare --plan` with this build's binary.
fn run_planned(line: &str) {
    let words: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(words[0], "ontogeny", "{line}");
    succeeded(&ontogeny_command().args(&words[1..]).output().unwrap());
}

#[test]
fn planned_replicates_merged_equal_a_direct_comparison() {
    let dir = scratch("plan");
    let direct = dir.join("direct");
    succeeded(&tiny(&direct).output().unwrap());
    let planned = dir.join("planned");
    let plan = succeeded(&tiny(&planned).arg("--plan").output().unwrap());
    let lines: Vec<&str> = plan.lines().collect();
    assert_eq!(lines.len(), 6, "{plan}");
    // Nothing runs at --plan, and nothing is finished to merge yet.
    assert!(!planned.join("direct").exists());
    refused(
        &ontogeny_command()
            .args(["compare", "--merge"])
            .arg(&planned)
            .output()
            .unwrap(),
        "no replicate is finished",
    );
    // Half the commands, then a merge of what is finished.
    for line in &lines[..3] {
        run_planned(line);
    }
    let partial = succeeded(
        &ontogeny_command()
            .args(["compare", "--merge"])
            .arg(&planned)
            .output()
            .unwrap(),
    );
    assert!(partial.contains("not yet in the report"), "{partial}");
    assert!(
        std::fs::read_to_string(planned.join("report.md"))
            .unwrap()
            .contains("**Incomplete**")
    );
    for line in &lines[3..] {
        run_planned(line);
    }
    succeeded(
        &ontogeny_command()
            .args(["compare", "--merge"])
            .arg(&planned)
            .output()
            .unwrap(),
    );
    assert_eq!(numbers(&planned), numbers(&direct));
    // Replicate by replicate, the databases hold the same individuals.
    for encoding in ENCODINGS.split(',') {
        let a = RunStore::open(&direct.join(encoding).join("rep-2/run.sqlite")).unwrap();
        let b = RunStore::open(&planned.join(encoding).join("rep-2/run.sqlite")).unwrap();
        assert_eq!(a.best_individual().unwrap(), b.best_individual().unwrap());
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_killed_comparison_resumes_to_the_same_report() {
    let dir = scratch("kill");
    let whole = dir.join("whole");
    succeeded(&tiny(&whole).output().unwrap());
    let killed = dir.join("killed");
    let mut child = tiny(&killed)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Kill it once the second replicate (lsystem-continuous rep-1) has a generation.
    let log = killed.join("lsystem-continuous/rep-1/log.txt");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    while !log.exists() && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(1));
    }
    child.kill().unwrap();
    let _ = child.wait();
    assert!(
        !killed.join("report.md").exists(),
        "the comparison finished before it was killed"
    );
    succeeded(
        &ontogeny_command()
            .args(["compare", "--resume"])
            .arg(&killed)
            .output()
            .unwrap(),
    );
    assert_eq!(numbers(&killed), numbers(&whole));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bad_input_exits_2_and_keeps_what_was_computed() {
    let dir = scratch("bad");
    let out = dir.join("cmp");
    let with = |extra: &[&str]| {
        let mut c = ontogeny_command();
        c.args([
            "compare",
            "--replicates",
            "1",
            "--pop",
            "6",
            "--seconds",
            "1",
        ])
        .args(extra);
        c.output().unwrap()
    };
    let o = out.to_str().unwrap();
    refused(
        &with(&[
            "--encodings",
            "lsystem,nonsense",
            "--evaluations",
            "6",
            "--out",
            o,
        ]),
        "nonsense",
    );
    refused(
        &with(&[
            "--encodings",
            "lsystem",
            "--task",
            "swim",
            "--evaluations",
            "6",
            "--out",
            o,
        ]),
        "swim",
    );
    refused(
        &with(&["--encodings", "lsystem", "--evaluations", "5", "--out", o]),
        "a budget of 5 evaluations is smaller than one generation (6 individuals)",
    );
    refused(
        &with(&[
            "--encodings",
            "lsystem,lsystem",
            "--evaluations",
            "6",
            "--out",
            o,
        ]),
        "names lsystem twice",
    );
    let config = dir.join("limits.toml");
    std::fs::write(&config, "[limits]\nmax_rules = 3\n").unwrap();
    refused(
        &with(&[
            "--encodings",
            "lsystem",
            "--evaluations",
            "6",
            "--config",
            config.to_str().unwrap(),
            "--out",
            o,
        ]),
        "every encoding runs with its default limits",
    );
    assert!(!out.exists(), "refused input wrote {}", out.display());
    refused(
        &ontogeny_command()
            .args(["compare", "--resume"])
            .arg(&dir)
            .output()
            .unwrap(),
        "not a comparison directory",
    );
    // A comparison of one finished replicate per encoding.
    succeeded(&with(&[
        "--encodings",
        "lsystem,direct",
        "--evaluations",
        "11",
        "--out",
        o,
    ]));
    let before = numbers(&out);
    refused(
        &with(&["--encodings", "direct", "--evaluations", "11", "--out", o]),
        "already holds a comparison",
    );
    // A replicate run with other settings (2 s walks) where rep-1 of direct belongs.
    let rep = out.join("direct/rep-1");
    let moved = dir.join("kept");
    std::fs::rename(&rep, &moved).unwrap();
    let plan = succeeded(
        &ontogeny_command()
            .args([
                "compare",
                "--plan",
                "--encodings",
                "lsystem,direct",
                "--replicates",
                "1",
            ])
            .args([
                "--pop",
                "6",
                "--seconds",
                "1",
                "--evaluations",
                "11",
                "--out",
            ])
            .arg(dir.join("other"))
            .output()
            .unwrap(),
    );
    let direct_line = plan
        .lines()
        .find(|l| l.contains("--encoding direct"))
        .unwrap();
    let seed = direct_line
        .split_whitespace()
        .skip_while(|w| *w != "--seed")
        .nth(1)
        .unwrap();
    succeeded(
        &ontogeny_command()
            .args([
                "evolve",
                "--encoding",
                "direct",
                "--pop",
                "6",
                "--gens",
                "2",
                "--seconds",
                "2",
            ])
            .args(["--seed", seed, "--out"])
            .arg(&rep)
            .output()
            .unwrap(),
    );
    refused(
        &ontogeny_command()
            .args(["compare", "--merge"])
            .arg(&out)
            .output()
            .unwrap(),
        "is not replicate 1 of this comparison: its task.walker.seconds differs",
    );
    refused(
        &ontogeny_command()
            .args(["compare", "--resume"])
            .arg(&out)
            .output()
            .unwrap(),
        "is not replicate 1 of this comparison",
    );
    // Nothing computed was lost: the odd replicate is still there, and with the original
    // back the report is as before.
    assert!(rep.join("run.sqlite").is_file());
    std::fs::remove_dir_all(&rep).unwrap();
    std::fs::rename(&moved, &rep).unwrap();
    succeeded(
        &ontogeny_command()
            .args(["compare", "--merge"])
            .arg(&out)
            .output()
            .unwrap(),
    );
    assert_eq!(numbers(&out), before);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_second_process_on_a_comparison_is_refused_at_once_naming_the_holder() {
    let dir = scratch("locked");
    let out = dir.join("cmp");
    let mut first = ontogeny_command()
        .args([
            "compare",
            "--encodings",
            "direct",
            "--replicates",
            "2",
            "--evaluations",
            "100000",
            "--pop",
            "6",
            "--seconds",
            "1",
            "--out",
        ])
        .arg(&out)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let holder = format!("pid {}:", first.id());
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    // The holder locks the directory, then writes compare.toml.
    while !(std::fs::read_to_string(out.join(".lock")).is_ok_and(|h| h.starts_with(&holder))
        && out.join("compare.toml").is_file())
    {
        assert!(std::time::Instant::now() < deadline, "no lock taken");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let resumed = ontogeny_command()
        .args(["compare", "--resume"])
        .arg(&out)
        .output()
        .unwrap();
    let merged = ontogeny_command()
        .args(["compare", "--merge"])
        .arg(&out)
        .output()
        .unwrap();
    first.kill().unwrap();
    let _ = first.wait();
    for output in [&resumed, &merged] {
        refused(output, "is in use by another ontogeny process");
        refused(output, &holder);
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_comparison_whose_files_were_edited_out_of_range_is_refused() {
    let dir = scratch("edited");
    let out = dir.join("c");
    succeeded(&tiny(&out).arg("--plan").output().unwrap());
    let edit = |name: &str, key: &str, value: &str| {
        let path = out.join(name);
        let text = std::fs::read_to_string(&path).unwrap();
        let edited: Vec<String> = text
            .lines()
            .map(|line| match line.split(" = ").next() {
                Some(k) if k == key => format!("{key} = {value}"),
                _ => line.to_string(),
            })
            .collect();
        std::fs::write(&path, edited.join("\n")).unwrap();
        text
    };
    // The input the config fuzz target found: `compare --resume` panicked computing the
    // budget of a population of 0.
    let original = edit("evolve.toml", "population", "0");
    for verb in ["--resume", "--merge"] {
        refused(
            &ontogeny_command()
                .args(["compare", verb])
                .arg(&out)
                .output()
                .unwrap(),
            "evolve.toml: [ga] population must be 2 to 100000, not 0",
        );
    }
    std::fs::write(out.join("evolve.toml"), original).unwrap();
    edit("compare.toml", "replicates", "20000");
    refused(
        &ontogeny_command()
            .args(["compare", "--merge"])
            .arg(&out)
            .output()
            .unwrap(),
        "compare.toml: replicates must be 1 to 10000, not 20000",
    );
    assert!(!out.join("lsystem").exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_comparison_optimises_the_fitness_its_flag_names_and_its_report_says_so() {
    let dir = scratch("fitness");
    let out = dir.join("c");
    let mut command = ontogeny_command();
    command
        .args(["compare", "--encodings", "direct", "--fitness", "distance"])
        .args(["--replicates", "1", "--evaluations", "6", "--pop", "6"])
        .args(["--seconds", "1", "--seed", "4", "--out"])
        .arg(&out);
    let stdout = succeeded(&command.output().unwrap());
    assert!(stdout.contains("; walker, distance (m)"), "{stdout}");
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        report.contains("Fitness: walker, distance (m)."),
        "{report}"
    );
    let shared = std::fs::read_to_string(out.join("evolve.toml")).unwrap();
    assert!(shared.contains("fitness = \"distance\""), "{shared}");
    // A walker formula for another task is refused.
    let jump = ontogeny_command()
        .args(["compare", "--encodings", "direct", "--task", "jump"])
        .args(["--fitness", "distance", "--evaluations", "6", "--out"])
        .arg(dir.join("jump"))
        .output()
        .unwrap();
    refused(
        &jump,
        "--fitness is for the walker task only, and the task is jump",
    );
    assert!(!dir.join("jump").exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_comparison_without_cache_reports_the_same_numbers_with_nothing_reused() {
    let dir = scratch("no-cache");
    let (on, off) = (dir.join("on"), dir.join("off"));
    succeeded(&tiny(&on).output().unwrap());
    succeeded(&tiny(&off).arg("--no-cache").output().unwrap());
    // summary.csv: simulated and reused are the two columns before wall_seconds.
    let split = |dir: &Path| -> Vec<(String, u64, u64)> {
        let csv = std::fs::read_to_string(dir.join("summary.csv")).unwrap();
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        assert_eq!(header[10..], ["simulated", "reused", "wall_seconds"]);
        csv.lines()
            .skip(1)
            .map(|line| {
                let cells: Vec<&str> = line.split(',').collect();
                (
                    cells[..10].join(","),
                    cells[10].parse().unwrap(),
                    cells[11].parse().unwrap(),
                )
            })
            .collect()
    };
    let (with, without) = (split(&on), split(&off));
    assert_eq!(with.len(), without.len());
    for (a, b) in with.iter().zip(&without) {
        assert_eq!(a.0, b.0, "the replicates' numbers differ");
        assert_eq!(a.1 + a.2, b.1, "evaluations differ");
        assert_eq!(b.2, 0, "a replicate without cache reused");
    }
    let md = std::fs::read_to_string(off.join("report.md")).unwrap();
    assert!(md.contains("| simulated | reused |"), "{md}");
    let _ = std::fs::remove_dir_all(dir);
}
