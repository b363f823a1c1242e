//! `ontogeny compare` end to end: equal budgets, `--plan` commands merged equal a direct
//! comparison, a comparison killed and resumed equals an uninterrupted one, and bad input
//! exits 2 without losing anything computed; conditions (`--condition`) run, resume, state
//! their power, and have their budgets and names checked.

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

/// The report's numbers without wall-clock figures, for encodings compared.
fn numbers(dir: &Path) -> String {
    numbers_of(dir, &["lsystem", "direct"])
}

/// The numbers of a comparison of the arms `arms` (encodings or conditions) without
/// wall-clock figures: `summary.csv` without its last column (wall seconds) and the arms'
/// rows of `report.md` without their evaluations-per-second column.
fn numbers_of(dir: &Path, arms: &[&str]) -> String {
    let csv = std::fs::read_to_string(dir.join("summary.csv")).unwrap();
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    let mut out = String::new();
    for line in csv.lines() {
        out += &line[..line.rfind(',').unwrap()];
        out.push('\n');
    }
    for line in md
        .lines()
        .filter(|l| arms.iter().any(|arm| l.starts_with(&format!("| {arm}"))))
    {
        let cells: Vec<&str> = line.split('|').collect();
        // A line of the arms' table has 15 cells; drop evaluations/s.
        let keep = if cells.len() == 17 {
            &cells[..15]
        } else {
            &cells[..]
        };
        out += &keep.join("|");
        out.push('\n');
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
    assert!(
        partial.contains(
            "not yet in the report: lsystem rep-2 (not started), lsystem-continuous rep-2 \
             (not started), direct rep-2 (not started)"
        ),
        "{partial}"
    );
    // The power paragraph is the plan's; the pairs' own are in their tables.
    assert!(
        partial.contains("(as planned; each pair's own"),
        "{partial}"
    );
    let report = std::fs::read_to_string(planned.join("report.md")).unwrap();
    assert!(report.contains("**Incomplete**"), "{report}");
    assert!(report.contains("That is the power as planned"), "{report}");
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
            "climb",
            "--evaluations",
            "6",
            "--out",
            o,
        ]),
        "climb",
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
    // A walker formula for another task is refused: it is no expression of its terms.
    let jump = ontogeny_command()
        .args(["compare", "--encodings", "direct", "--task", "jump"])
        .args(["--fitness", "distance", "--evaluations", "6", "--out"])
        .arg(dir.join("jump"))
        .output()
        .unwrap();
    refused(
        &jump,
        "--fitness \"distance\" is a formula of the walker task, not of the jump task, whose \
         fitness may be an expression of its terms: height, resting_lowest_point, joint_gap",
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
        assert_eq!(header[12..], ["simulated", "reused", "wall_seconds"]);
        csv.lines()
            .skip(1)
            .map(|line| {
                let cells: Vec<&str> = line.split(',').collect();
                (
                    cells[..12].join(","),
                    cells[12].parse().unwrap(),
                    cells[13].parse().unwrap(),
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

/// Two tiny conditions' configs in `dir`: `low.toml` and `high.toml`, the L-system genome on
/// 0.2 s walks with a population of 5 (20% elite: 1), mutation rates 0.05 and 0.3.
fn two_conditions(dir: &Path) -> (PathBuf, PathBuf) {
    let config = |rate: f64| {
        format!(
            "encoding = \"lsystem\"\n\n[ga]\npopulation = 5\nmutation_rate = {rate}\n\n\
             [task]\ntask = \"walker\"\n\n[task.walker]\nseconds = 0.2\n"
        )
    };
    let (low, high) = (dir.join("low.toml"), dir.join("high.toml"));
    std::fs::write(&low, config(0.05)).unwrap();
    std::fs::write(&high, config(0.3)).unwrap();
    (low, high)
}

/// `compare --condition low=... --condition high=...`, 3 replicates of 9 walks (5 + 4: two
/// generations), into `out`.
fn compare_conditions(low: &Path, high: &Path, out: &Path) -> Command {
    let mut c = ontogeny_command();
    c.arg("compare")
        .arg("--condition")
        .arg(format!("low={}", low.display()))
        .arg("--condition")
        .arg(format!("high={}", high.display()))
        .args([
            "--replicates",
            "3",
            "--evaluations",
            "9",
            "--seed",
            "3",
            "--out",
        ])
        .arg(out);
    c
}

#[test]
fn two_conditions_run_resume_and_report_both_names_and_their_power() {
    let dir = scratch("conditions");
    let (low, high) = two_conditions(&dir);
    let out = dir.join("cmp");
    let stdout = succeeded(&compare_conditions(&low, &high, &out).output().unwrap());
    assert!(
        stdout.contains("6 replicates of 9 walks each (3 per condition); walker, normalised"),
        "{stdout}"
    );
    assert!(
        stdout.contains("\n  low                  n   3  best "),
        "{stdout}"
    );
    assert!(
        stdout.contains("\n  high                 n   3  best "),
        "{stdout}"
    );
    // Three replicates a side cannot reach p ≤ 0.05 (the most extreme order has p = 0.1):
    // nothing is detected, and the summary says that nothing could be.
    let pair = stdout
        .lines()
        .find(|l| l.starts_with("  low vs high: U "))
        .unwrap_or_else(|| panic!("no pair in {stdout}"));
    assert!(
        pair.ends_with(": not detected at this power (none is detectable with 3 and 3 replicates)"),
        "{pair}"
    );
    assert!(
        stdout.contains(
            "power: 3 replicates per condition, 1 pair, each tested at 0.0500: detects nothing: \
             with 3 and 3 replicates no result reaches p ≤ 0.0500"
        ),
        "{stdout}"
    );
    assert!(!stdout.contains("no difference"), "{stdout}");
    // Each condition's settings, its replicates with the same seeds, each an ordinary run of
    // exactly 9 evaluations that has the condition's mutation rate.
    for (name, rate) in [("low", "0.05"), ("high", "0.3")] {
        let settings = std::fs::read_to_string(out.join(name).join("evolve.toml")).unwrap();
        assert!(
            settings.contains(&format!("mutation_rate = {rate}\n")),
            "{settings}"
        );
        assert!(settings.contains("generations = 2\n"), "{settings}");
        for k in 1..=3 {
            let run = out.join(name).join(format!("rep-{k}"));
            assert_eq!(evaluations_in(&run), 9, "{}", run.display());
        }
    }
    let csv = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows[0][..3], ["condition", "replicate", "seed"]);
    assert_eq!(rows.len(), 7);
    assert_eq!((rows[1][0], rows[4][0]), ("low", "high"));
    assert_eq!(
        rows[1][2], rows[4][2],
        "replicate 1 of each condition has one seed"
    );
    assert_ne!(rows[1][2], rows[2][2]);
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    for text in [
        "# Comparison of the conditions low, high\n",
        "a budget of 9 walks per replicate",
        "| low | lsystem | walker, normalised (Chaumont eq. 1) | 5 | 2 | 1 | chaumont | 1 | 9 |",
        "| condition | n | mean best |",
        "| a | b | U | p | method | Holm p | A12 | effect | detectable | verdict |",
        "| none | not detected at this power (none is detectable with 3 and 3 replicates) |",
        "Power: with 3 replicates per condition and 1 pair, each pair is tested at 0.05 / 1 = 0.0500",
        "The comparison detects nothing: with 3 and 3 replicates no result reaches p ≤ 0.0500, \
         and has power 0.00 for A12 = 0.71.",
        "tests of the champions' fitness at the fine reference",
        "| condition | n | mean best | at the fine reference | sd | 95% CI | parts | joints | \
         neurons | repeated | mirrored | bytes/part |",
    ] {
        assert!(md.contains(text), "{text:?} not in:\n{md}");
    }
    // The same as JSON.
    let json: serde_json::Value = serde_json::from_str(&succeeded(
        &ontogeny_command()
            .args(["compare", "--json", "--merge"])
            .arg(&out)
            .output()
            .unwrap(),
    ))
    .unwrap();
    let conditions = json["conditions"].as_array().unwrap();
    assert_eq!(conditions.len(), 2);
    assert_eq!(conditions[1]["condition"], "high");
    assert_eq!(conditions[1]["encoding"], "lsystem");
    assert_eq!(conditions[1]["walks"], 9);
    assert!(json.get("encodings").is_none());
    assert_eq!(json["evaluations"], 9);
    assert_eq!(json["pairs"][0]["detected"], false);
    assert_eq!(json["pairs"][0]["detectable_a12"], serde_json::Value::Null);
    assert_eq!(
        json["power"],
        serde_json::json!({"replicates": 3, "pairs": 1, "level": 0.05, "power": 0.8,
            "detectable_a12": null, "method": "simulated", "power_at_large": 0.0,
            "primary": null, "needed_for_large": 29})
    );
    assert_eq!(json["primary"], serde_json::Value::Null);
    assert_eq!(json["fine_pairs"][0]["a"], "low");
    // A replicate lost and the comparison resumed: the same report.
    let before = numbers_of(&out, &["low", "high"]);
    std::fs::remove_dir_all(out.join("high/rep-2")).unwrap();
    let resumed = ontogeny_command()
        .args(["compare", "--resume"])
        .arg(&out)
        .output()
        .unwrap();
    succeeded(&resumed);
    assert!(
        stderr(&resumed).contains("[high 2/3]"),
        "{}",
        stderr(&resumed)
    );
    assert!(!stderr(&resumed).contains("[low "), "{}", stderr(&resumed));
    assert_eq!(numbers_of(&out, &["low", "high"]), before);
    // Planned: one `evolve` command per replicate reading its condition's settings; run and
    // merged, the same report.
    let planned = dir.join("planned");
    let plan = succeeded(
        &compare_conditions(&low, &high, &planned)
            .arg("--plan")
            .output()
            .unwrap(),
    );
    let lines: Vec<&str> = plan.lines().collect();
    assert_eq!(lines.len(), 6, "{plan}");
    assert_eq!(
        lines[1],
        format!(
            "ontogeny evolve --config {} --seed {} --out {}",
            planned.join("high/evolve.toml").display(),
            rows[1][2],
            planned.join("high/rep-1").display()
        )
    );
    for line in &lines {
        run_planned(line);
    }
    succeeded(
        &ontogeny_command()
            .args(["compare", "--merge"])
            .arg(&planned)
            .output()
            .unwrap(),
    );
    assert_eq!(numbers_of(&planned, &["low", "high"]), before);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn conditions_whose_budgets_end_far_apart_are_refused_and_a_little_apart_noted() {
    let dir = scratch("condition-budgets");
    let config = |name: &str, population: usize| {
        let path = dir.join(name);
        std::fs::write(&path, format!("[ga]\npopulation = {population}\n")).unwrap();
        format!("{}={}", &name[..1], path.display())
    };
    let (a, b) = (config("a.toml", 20), config("b.toml", 21));
    let out = dir.join("cmp");
    let plan = |budget: &str| {
        ontogeny_command()
            .args(["compare", "--plan", "--condition", &a, "--condition", &b])
            .args(["--evaluations", budget, "--out"])
            .arg(&out)
            .output()
            .unwrap()
    };
    // Population 20 (elite 4) makes 20 + 16k walks, 21 (elite 4) 21 + 17k: of 100, 100 and
    // 89, more than 10% apart.
    refused(
        &plan("100"),
        "--condition: the budgets of a replicate differ by more than 10%: \
         a: 100 walks (population 20, 6 generations, 1 walk per individual), \
         b: 89 walks (population 21, 5 generations, 1 walk per individual); \
         choose populations that divide the budget more evenly, or a larger --evaluations",
    );
    assert!(!out.exists());
    // Of 200: 196 and 191, within 10%: planned, with a note that names them.
    let o = plan("200");
    succeeded(&o);
    assert!(
        stderr(&o).contains(
            "note: the budgets of a replicate differ (generations are whole): \
             a: 196 walks (population 20, 12 generations, 1 walk per individual), \
             b: 191 walks (population 21, 11 generations, 1 walk per individual)"
        ),
        "{}",
        stderr(&o)
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bad_conditions_exit_2_with_a_clear_message_and_write_nothing() {
    let dir = scratch("bad-conditions");
    let (low, high) = two_conditions(&dir);
    let seeded = dir.join("seeded.toml");
    std::fs::write(&seeded, "seed = 4\n").unwrap();
    let out = dir.join("cmp");
    let with = |conditions: &[String], extra: &[&str]| {
        let mut c = ontogeny_command();
        c.arg("compare");
        for condition in conditions {
            c.args(["--condition", condition]);
        }
        c.args(["--evaluations", "9", "--out"])
            .arg(&out)
            .args(extra);
        c.output().unwrap()
    };
    let named = |name: &str, path: &Path| format!("{name}={}", path.display());
    refused(
        &with(&[low.display().to_string()], &[]),
        &format!(
            "expected NAME=CONFIG.toml (e.g. pop30=examples/compare-condition-pop30.toml), not {}",
            low.display()
        ),
    );
    refused(
        &with(&[named("a", &dir.join("missing.toml"))], &[]),
        &format!("cannot read {}", dir.join("missing.toml").display()),
    );
    refused(
        &with(&[named("a", &low), named("a", &high)], &[]),
        "--condition: the condition a is named twice",
    );
    refused(
        &with(&[named("Low", &low), named("low", &high)], &[]),
        "--condition: the conditions Low and low differ only in case",
    );
    refused(
        &with(&[named("../a", &low)], &[]),
        "the condition name ../a holds '.': a name is ASCII letters, digits, - and _",
    );
    refused(
        &with(&[format!("a b={}", low.display())], &[]),
        "the condition name a b holds ' '",
    );
    refused(
        &with(&[named("a", &seeded)], &[]),
        "seed has no place in a comparison's config: --seed sets every replicate's seed",
    );
    refused(
        &with(&[named("a", &low)], &["--encodings", "lsystem"]),
        "'--condition <NAME=CONFIG.toml>' cannot be used with '--encodings <ENCODINGS>'",
    );
    refused(
        &with(
            &[named("a", &low)],
            &["--config", &low.display().to_string()],
        ),
        "'--condition <NAME=CONFIG.toml>' cannot be used with '--config <FILE.toml>'",
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_primary_pair_is_tested_alone_kept_for_merge_and_refused_when_not_compared() {
    let dir = scratch("primary");
    let out = dir.join("cmp");
    let stdout = succeeded(
        &tiny(&out)
            .args(["--primary", "direct,lsystem"])
            .output()
            .unwrap(),
    );
    // The primary pair in the order named, tested alone; the two others secondary.
    assert!(
        stdout.contains("\n  direct vs lsystem (primary): U "),
        "{stdout}"
    );
    assert!(stdout.contains("(alone "), "{stdout}");
    assert!(
        stdout.contains("primary direct vs lsystem tested at 0.0500: detects nothing"),
        "{stdout}"
    );
    assert!(
        stdout.contains("2 secondary pairs, each tested at 0.0250"),
        "{stdout}"
    );
    let manifest = std::fs::read_to_string(out.join("compare.toml")).unwrap();
    assert!(
        manifest.contains("primary = [\"direct\", \"lsystem\"]"),
        "{manifest}"
    );
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    for text in [
        "| direct | lsystem | primary |",
        "The primary pair, direct against lsystem, is tested alone at 0.05",
        "tests of the champions' fitness at the fine reference",
        "needs 29 replicates a side to detect A12 = 0.71",
    ] {
        assert!(md.contains(text), "{text:?} not in:\n{md}");
    }
    // A merge reads the primary pair from the plan.
    let json: serde_json::Value = serde_json::from_str(&succeeded(
        &ontogeny_command()
            .args(["compare", "--json", "--merge"])
            .arg(&out)
            .output()
            .unwrap(),
    ))
    .unwrap();
    assert_eq!(json["primary"], serde_json::json!(["direct", "lsystem"]));
    assert_eq!(json["pairs"][0]["primary"], false);
    let primary: Vec<&serde_json::Value> = json["pairs"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["primary"] == true)
        .collect();
    assert_eq!(primary.len(), 1);
    assert_eq!(
        (&primary[0]["a"], &primary[0]["b"]),
        (&"direct".into(), &"lsystem".into())
    );
    // A pair that is not two of the encodings compared is refused before anything is made.
    let bad = dir.join("bad");
    let o = tiny(&bad)
        .args(["--primary", "direct,graph"])
        .output()
        .unwrap();
    refused(
        &o,
        "--primary: names graph, which is not one of the encodings compared",
    );
    assert!(!bad.join("compare.toml").exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn power_for_an_effect_prints_the_replicates_needed_and_refuses_no_effect() {
    let o = ontogeny_command()
        .args(["compare", "--power-for", "0.71"])
        .output()
        .unwrap();
    let stdout = succeeded(&o);
    // The same figure the library's test bounds (Noether's formula asks 30).
    assert!(
        stdout.contains("1 pair (a primary pair)  level 0.0500: 29\n"),
        "{stdout}"
    );
    assert!(stdout.contains("3 pairs (Holm)"), "{stdout}");
    for bad in ["0.5", "1.2", "nan"] {
        let o = ontogeny_command()
            .args(["compare", "--power-for", bad])
            .output()
            .unwrap();
        refused(&o, "--power-for");
    }
}

#[test]
fn hornby_and_pollacks_conditions_give_every_encoding_the_same_limits() {
    let dir = scratch("hp-equal");
    let out = dir.join("cmp");
    let mut c = ontogeny_command();
    c.args(["compare", "--plan"]);
    for e in ["lsystem", "direct", "lsystem-continuous", "graph"] {
        c.arg("--condition")
            .arg(format!("{e}=examples/compare-hornby-pollack-{e}.toml"));
    }
    c.args([
        "--primary",
        "lsystem,direct",
        "--replicates",
        "2",
        "--evaluations",
        "3940",
        "--out",
    ])
    .arg(&out);
    succeeded(&c.output().unwrap());
    for e in ["lsystem", "direct", "lsystem-continuous", "graph"] {
        let settings = std::fs::read_to_string(out.join(e).join("evolve.toml")).unwrap();
        assert!(
            settings.contains(&format!("encoding = \"{e}\"")),
            "{settings}"
        );
        assert!(settings.contains("max_parts = 20\n"), "{settings}");
        assert!(settings.contains("generations = 49\n"), "{settings}");
    }
    let manifest = std::fs::read_to_string(out.join("compare.toml")).unwrap();
    assert!(
        manifest.contains("primary = [\"lsystem\", \"direct\"]"),
        "{manifest}"
    );
    let _ = std::fs::remove_dir_all(dir);
}
