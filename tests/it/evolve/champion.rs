//! A champion's file records every input of its evaluation, and `eval` on it repeats that
//! evaluation; `evolve --init` seeds a run from any shipped grammar that builds a creature,
//! its individual 0 scoring what `eval` gives the file; `replay` re-evaluates with
//! `--setting` and `--fitness`; `evolve --target` sets the aim task's target.

use std::path::Path;

use ontogeny::run::store::RunStore;

use super::scratch;
use crate::util::{ontogeny_command, ontogeny_ok, refused, stderr, succeeded};

/// The fitness `eval ARGS --json` prints, and its standard error.
fn eval_fitness(args: &[&str]) -> (f64, String) {
    let mut all = vec!["eval"];
    all.extend_from_slice(args);
    all.push("--json");
    let o = ontogeny_ok(&all);
    let value: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    (value["fitness"].as_f64().unwrap(), stderr(&o))
}

/// The fitness a champion file's record gives it.
fn recorded_fitness(path: &Path) -> f64 {
    let text = std::fs::read_to_string(path).unwrap();
    let record = ontogeny::run::champion::ChampionRecord::of_text(&text)
        .unwrap()
        .unwrap_or_else(|| panic!("{} has no record", path.display()));
    record.fitness
}

#[test]
fn eval_on_every_shipped_champion_prints_the_fitness_its_header_records() {
    let mut champions: Vec<_> = std::fs::read_dir("docs/evolve")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().unwrap().to_string_lossy().contains("-best."))
        .collect();
    champions.sort();
    assert_eq!(champions.len(), 14);
    for path in champions {
        let file = path.to_str().unwrap();
        let (fitness, notes) = eval_fitness(&[file]);
        assert_eq!(fitness, recorded_fitness(&path), "{file}");
        assert!(notes.contains("records its evaluation"), "{file}: {notes}");
        // The header's human line says the same number.
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(&format!("fitness {fitness} (ok)")), "{file}");
    }
}

#[test]
fn a_fresh_champion_is_evaluated_as_its_run_evaluated_it_and_flags_override_with_a_note() {
    let dir = scratch("champion-fresh");
    for (encoding, extension) in [("lsystem", "lsys"), ("graph", "json")] {
        let out = dir.join(encoding);
        let o = ontogeny_command()
            .args([
                "evolve",
                "--encoding",
                encoding,
                "--pop",
                "4",
                "--gens",
                "1",
            ])
            .args([
                "--seconds",
                "1.5",
                "--fitness",
                "distance",
                "--setting",
                "fast",
            ])
            .args(["--seed", "3", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        succeeded(&o);
        let best = out.join(format!("best.{extension}"));
        let file = best.to_str().unwrap();
        let (fitness, notes) = eval_fitness(&[file]);
        assert_eq!(fitness, recorded_fitness(&best), "{encoding}");
        assert!(
            notes.contains(&format!(
                "note: {file} records its evaluation (walker, distance (m)); repeating it"
            )),
            "{notes}"
        );
        // A flag that differs from the record is used, and said.
        let (_, notes) = eval_fitness(&[file, "--seconds", "1"]);
        assert!(
            notes.contains(&format!(
                "note: --seconds differs from the evaluation {file} records (1.5 seconds); the flag's is used"
            )),
            "{notes}"
        );
        assert!(notes.contains("the flags above change it"), "{notes}");
        // The same evaluation spelt out in flags gives the same number.
        let (spelt, _) = eval_fitness(&[
            file,
            "--task",
            "walker",
            "--fitness",
            "distance",
            "--seconds",
            "1.5",
            "--setting",
            "fast",
        ]);
        assert_eq!(spelt, fitness, "{encoding}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn eval_without_a_task_evaluates_a_walker() {
    let (default, _) = eval_fitness(&["examples/hornby-walker.lsys", "--seconds", "1"]);
    let (walker, _) = eval_fitness(&[
        "examples/hornby-walker.lsys",
        "--seconds",
        "1",
        "--task",
        "walker",
    ]);
    assert_eq!(default, walker);
}

#[test]
fn init_on_every_shipped_grammar_that_builds_a_creature_seeds_a_run_whose_individual_0_scores_as_eval()
 {
    let dir = scratch("champion-init");
    for name in [
        "quadruped",
        "snake",
        "thrower",
        "hornby-walker",
        "continuous-walker",
        "syntax-tour",
        "plastic",
        "algae",
    ] {
        let file = format!("examples/{name}.lsys");
        let out = dir.join(name);
        let o = ontogeny_command()
            .args(["evolve", "--init", &file, "--pop", "2", "--gens", "1"])
            .args([
                "--seconds",
                "1",
                "--fitness",
                "distance",
                "--no-verify-best",
            ])
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        succeeded(&o);
        let store = RunStore::open(&out.join("run.sqlite")).unwrap();
        let first = store.individuals(0).unwrap();
        let (fitness, _) = eval_fitness(&[&file, "--seconds", "1", "--fitness", "distance"]);
        assert_eq!(first[0].fitness, fitness, "{name}");
    }
    // A grammar whose rules and derived string both escape the genome: every reason at once.
    let o = ontogeny_command()
        .args(["evolve", "--init", "examples/parametric.lsys", "--pop", "2"])
        .arg("--out")
        .arg(dir.join("bad"))
        .output()
        .unwrap();
    let message = refused(
        &o,
        "examples/parametric.lsys: cannot seed the lsystem encoding",
    );
    assert!(
        message.contains("line 6, column 31: the argument 'x + y'"),
        "{message}"
    );
    assert!(
        message.contains("line 7, column 29: the argument 'x / y'"),
        "{message}"
    );
    assert!(
        message.contains("its derived string has no building command"),
        "{message}"
    );
    assert!(!dir.join("bad").exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn replay_re_evaluates_with_another_setting_and_fitness_and_evolve_takes_an_aim_target() {
    let dir = scratch("champion-replay");
    let out = dir.join("aim");
    let o = ontogeny_command()
        .args([
            "evolve",
            "--encoding",
            "graph",
            "--task",
            "aim",
            "--target",
            "3,0,1",
        ])
        .args(["--pop", "4", "--gens", "1", "--seconds", "5", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    succeeded(&o);
    let config = std::fs::read_to_string(out.join("config.toml")).unwrap();
    assert!(config.contains("target = [3.0, 0.0, 1.0]"), "{config}");
    // A walker formula is no expression of the aim task's terms.
    let o = ontogeny_command()
        .args(["replay", "--fitness", "distance"])
        .arg(&out)
        .output()
        .unwrap();
    refused(
        &o,
        "--fitness \"distance\" is a formula of the walker task, not of the aim task",
    );
    let walker = dir.join("walker");
    let o = ontogeny_command()
        .args([
            "evolve",
            "--pop",
            "4",
            "--gens",
            "1",
            "--seconds",
            "1",
            "--fitness",
            "distance",
            "--out",
        ])
        .arg(&walker)
        .output()
        .unwrap();
    succeeded(&o);
    let o = ontogeny_command()
        .args(["replay", "--setting", "fine", "--fitness", "normalised"])
        .arg(&walker)
        .output()
        .unwrap();
    let notes = succeeded(&o);
    assert!(
        stderr(&o).contains("note: re-evaluated as the flags ask (walker, normalised (Chaumont eq. 1)), not as the run evaluated it (walker, distance (m))"),
        "{notes}"
    );
    // --target is the aim task's.
    let o = ontogeny_command()
        .args(["evolve", "--target", "3,0,1", "--pop", "4", "--out"])
        .arg(dir.join("no"))
        .output()
        .unwrap();
    refused(
        &o,
        "--target is for the aim task only, and the task is walker",
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// Individual 0's fitness in a run `evolve --init FILE` seeds (walker, distance, 1 s), and
/// the run's standard error.
fn seeded_fitness(file: &Path, out: &Path, extra: &[&str]) -> (f64, String) {
    let o = ontogeny_command()
        .args(["evolve", "--init"])
        .arg(file)
        .args(["--pop", "2", "--gens", "1", "--seconds", "1"])
        .args(["--fitness", "distance", "--no-verify-best"])
        .args(extra)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    succeeded(&o);
    let store = RunStore::open(&out.join("run.sqlite")).unwrap();
    (store.individuals(0).unwrap()[0].fitness, stderr(&o))
}

#[test]
fn init_rewrites_the_textbook_symbols_into_the_genomes_commands_and_grows_the_same_creature() {
    let dir = scratch("champion-init-textbook");
    // Through the rules (a production with a textbook successor) and through the derived
    // string (a rule the genome cannot write: a stochastic one).
    let rules = "angle: 90\nstep: 0.5\nderivation length: 1\nmodule Leg\n\
                 axiom: !(0.2) F [ + Leg ] [ + | Leg ] F(0.3)\n\
                 Leg --> revolute1 F(0.4) output(1)\n";
    let derived = "angle: 180\nderivation length: 1\nmodule Leg\n\
                   axiom: !(0.3) F(0.5) [ +(90) Leg ] [ -(-270) Leg ] F(0.3)\n\
                   Leg --> revolute1 F(0.4) output(1) : 1\n";
    for (name, text) in [("rules", rules), ("derived", derived)] {
        let file = dir.join(format!("{name}.lsys"));
        std::fs::write(&file, text).unwrap();
        let (first, said) = seeded_fitness(&file, &dir.join(name), &[]);
        let path = file.to_str().unwrap();
        let (fitness, _) = eval_fitness(&[path, "--seconds", "1", "--fitness", "distance"]);
        assert_eq!(first, fitness, "{name}: {said}");
        assert!(fitness > 0.0, "{name}: a valid walker");
        assert_eq!(
            said.contains("its rules cannot be the genome's"),
            name == "derived"
        );
    }
    // The first best's file writes the genome's commands, never the textbook's.
    let best = std::fs::read_to_string(dir.join("rules/best.lsys")).unwrap();
    assert!(
        best.contains("width(0.2) thickness(0.2) forward(0.5) [ left(1)"),
        "{best}"
    );
    assert!(best.contains("[ left(1) left(2) P1"), "{best}");
    // What has no equivalent is refused, every reason at once, each where it is written.
    let bad = dir.join("bad.lsys");
    std::fs::write(&bad, "angle: 25.7\nheading: up\naxiom: ! F f(0.2) + F\n").unwrap();
    let o = ontogeny_command()
        .args(["evolve", "--init"])
        .arg(&bad)
        .arg("--out")
        .arg(dir.join("bad"))
        .output()
        .unwrap();
    let message = refused(&o, "cannot seed the lsystem encoding");
    for reason in [
        "line 2, column 1: its turtle starts heading up ('heading: up'); the genome's starts on the ground",
        "line 3, column 8: a bare '!' scales the width by 0.7; the genome sets widths, it does not scale them",
        "line 3, column 12: 'f' moves without building and leaves a gap; the genome builds one body",
        "line 3, column 19: '+' turns by 25.7°, not a multiple of 90°; the genome turns by quarter turns",
    ] {
        assert!(message.contains(reason), "{reason} in {message}");
    }
    assert!(!dir.join("bad").exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn init_widens_the_parts_and_modules_limits_to_the_seed_and_refuses_a_seed_beyond_any_run_once() {
    let dir = scratch("champion-init-limits");
    // 60 hinged parts from a string of over 1,000 modules (1,024 control symbols C).
    let big = dir.join("big.lsys");
    std::fs::write(
        &big,
        "derivation length: 60\nmodule A, C\naxiom: A(0) C(0)\n\
         A(n) : n < 60 --> revolute1 forward(0.3) A(n + 1)\n\
         C(n) : n < 10 --> C(n + 1) C(n + 1)\n",
    )
    .unwrap();
    let (_, said) = seeded_fitness(&big, &dir.join("big"), &[]);
    assert!(
        said.contains(
            "the run's limits are widened to fit the seed (derivation_length 6 → 61, \
             max_modules 1000 → 1145, max_parts 50 → 60); its mutants keep within them"
        ),
        "{said}"
    );
    let store = RunStore::open(&dir.join("big/run.sqlite")).unwrap();
    let first = store.individuals(0).unwrap();
    assert_eq!(first[0].status, "ok", "{}", first[0].genome_text);
    // A derivation length beyond the limit's range (0 to 64): refused once, without a note.
    let long = dir.join("long.lsys");
    std::fs::write(
        &long,
        "derivation length: 120\nmodule A\naxiom: A(0)\nA(n) : n < 3 --> revolute1 forward(0.3) A(n + 1)\n",
    )
    .unwrap();
    let o = ontogeny_command()
        .args(["evolve", "--init"])
        .arg(&long)
        .arg("--out")
        .arg(dir.join("long"))
        .output()
        .unwrap();
    let said = refused(&o, "");
    assert_eq!(
        said.trim_end(),
        format!(
            "error: {}: cannot seed the lsystem encoding: this file does not fit the lsystem \
             genome: its seed needs more than any run may hold: derivation_length must be 0 to \
             64, not 120",
            long.display()
        )
    );
    assert!(!dir.join("long").exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn init_messages_name_the_real_file_and_no_flag_that_evolve_lacks() {
    let dir = scratch("champion-init-names");
    let bad = dir.join("arity.lsys");
    std::fs::write(&bad, "axiom: forward(1, 2) revolute1\n").unwrap();
    let o = ontogeny_command()
        .args(["evolve", "--init"])
        .arg(&bad)
        .arg("--out")
        .arg(dir.join("arity"))
        .output()
        .unwrap();
    let said = refused(&o, &format!(" --> {}:1:8", bad.display()));
    assert!(!said.contains("file.lsys"), "{said}");
    // A runaway grammar: refused with the most any run may hold, without grow's flag.
    let runaway = dir.join("runaway.lsys");
    std::fs::write(
        &runaway,
        "derivation length: 30\naxiom: A\nA --> A A forward\n",
    )
    .unwrap();
    let o = ontogeny_command()
        .args(["evolve", "--init"])
        .arg(&runaway)
        .arg("--out")
        .arg(dir.join("runaway"))
        .output()
        .unwrap();
    let said = refused(
        &o,
        "this file does not fit the lsystem genome: it does not grow within the most any run \
         may hold (100000 modules, 1000 parts): the string grew past 100000 modules while \
         deriving step 16",
    );
    assert!(!said.contains("--max-modules"), "{said}");
    assert!(!dir.join("runaway").exists());
    let _ = std::fs::remove_dir_all(dir);
}
