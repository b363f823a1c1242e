//! `ontogeny evolve` end to end, for every encoding: the run directory and its database,
//! identical results on one and two threads, a run killed with SIGKILL mid-generation and
//! resumed equals the uninterrupted run, and bad input refused with exit code 2; and every
//! task and preset with the `direct` encoding. Each generation's best re-walked at the fine
//! reference setting: the stored value recomputed, the switch that turns it off, a version-1
//! database migrated on resume.

mod cache;
mod champion;
mod derived;
mod resume;
mod steady;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use ontogeny::encoding::{
    ContinuousGenome, DirectGenome, Genome, GraphGenome, LSystemGenome, Purpose,
};
use ontogeny::evolve::ga::ranking;
use ontogeny::run::plot::FINE_LABEL;
use ontogeny::run::store::RunStore;
use ontogeny::run::{Run, exploits_stepping};
use ontogeny::task::{Evaluation, TaskSpec};

use crate::util::{evolve_walkers, ontogeny_command, refused, scratch_dir, succeeded};

/// Every encoding the tests run for.
const ENCODINGS: [&str; 4] = ["lsystem", "lsystem-continuous", "direct", "graph"];

/// The extension of an encoding's text form: `.lsys` grammars, `.json` for graph genomes.
fn text_extension(encoding: &str) -> &'static str {
    if encoding == "graph" { "json" } else { "lsys" }
}

/// A fresh, empty scratch directory of this module's, named after `name`.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("evolve-{name}"))
}

/// A small, quick run of `encoding`: 12 individuals, `gens` generations, 1 s walks.
fn run_of(encoding: &str, out: &Path, gens: &str, extra: &[&str]) -> Output {
    evolve_command(encoding, out, gens, extra).output().unwrap()
}

/// The command of [`run_of`], to run or spawn.
fn evolve_command(encoding: &str, out: &Path, gens: &str, extra: &[&str]) -> Command {
    let mut c = evolve_walkers(encoding, "12");
    c.args(["--gens", gens, "--seconds", "1", "--seed", "5", "--out"])
        .arg(out)
        .args(extra);
    c
}

/// `log.txt` without its wall-clock figures (" in 1.2 s").
fn log_without_times(dir: &Path) -> String {
    std::fs::read_to_string(dir.join("log.txt"))
        .unwrap()
        .lines()
        .map(|line| match line.split_once(" simulated in ") {
            Some((head, tail)) => {
                let tail = tail.split_once(" s").map_or("", |(_, rest)| rest);
                format!("{head} simulated{tail}\n")
            }
            None => format!("{line}\n"),
        })
        .collect()
}

/// The small run of 4 generations.
fn small_run(encoding: &str, out: &Path, extra: &[&str]) -> Output {
    run_of(encoding, out, "4", extra)
}

/// Everything the store holds of a run but wall-clock times, as one comparable string.
pub(crate) fn contents(dir: &Path) -> String {
    contents_of(dir, true, CacheColumns::Both)
}

/// Which of the evaluation cache's columns [`contents_of`] shows.
#[derive(Clone, Copy, PartialEq)]
enum CacheColumns {
    /// `reused` and `evaluation_key`.
    Both,
    /// `evaluation_key` alone.
    Key,
    /// Neither, nor the generation of the individuals' parents: what a store migrated from
    /// schema version 1 or 2 lacks.
    Neither,
}

/// [`contents`], with or without the fine reference values and the cache's columns.
fn contents_of(dir: &Path, with_fine: bool, cache: CacheColumns) -> String {
    let store = RunStore::open_read_only(&dir.join("run.sqlite")).unwrap();
    let mut out = String::new();
    let last = store.last_generation().unwrap().unwrap();
    for g in store.generations().unwrap() {
        out += &format!(
            "{} {:?} {:?} {:?} {:?} {} {} {:?}\n",
            g.index,
            g.best,
            g.mean,
            g.median,
            g.sd,
            g.valid_fraction,
            g.evaluations,
            if with_fine { g.best_fine.clone() } else { None }
        );
    }
    for generation in 0..=last {
        for i in store.individuals(generation).unwrap() {
            out += &format!(
                "{} {} {:?} {} {:?} {} {} {} {} {} {}\n{}\n",
                i.generation,
                i.index,
                i.parents,
                i.operator,
                i.fitness,
                i.status,
                i.terms_json,
                i.parts,
                i.joints,
                i.neurons,
                i.genome_json,
                i.genome_text
            );
            if cache != CacheColumns::Neither {
                out += &format!(
                    "{:?} parents in {:?}\n",
                    i.evaluation_key, i.parents_generation
                );
            }
            if cache == CacheColumns::Both {
                out += &format!("reused {}\n", i.reused);
            }
        }
    }
    out
}

#[test]
fn a_run_writes_its_directory_and_database() {
    for encoding in ENCODINGS {
        writes_its_directory_and_database(encoding);
    }
}

fn writes_its_directory_and_database(encoding: &str) {
    let dir = scratch(&format!("layout-{encoding}"));
    let out = dir.join("run");
    let o = small_run(encoding, &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let best = format!("best.{}", text_extension(encoding));
    for file in [
        "config.toml",
        "run.sqlite",
        "fitness.svg",
        best.as_str(),
        "log.txt",
    ] {
        assert!(out.join(file).exists(), "{file}");
    }
    let store = RunStore::open(&out.join("run.sqlite")).unwrap();
    let run = store.run().unwrap();
    assert_eq!(
        (run.encoding.as_str(), run.task.as_str(), run.seed),
        (encoding, "walker", 5)
    );
    assert_eq!(
        run.config,
        std::fs::read_to_string(out.join("config.toml")).unwrap()
    );
    let generations = store.generations().unwrap();
    assert_eq!(generations.len(), 4);
    // Generation 0 evaluates everyone; later ones all but the elite (20% of 12: 2).
    assert_eq!(generations[0].evaluations, 12);
    assert!(generations[1..].iter().all(|g| g.evaluations == 10));
    for g in 0..4 {
        let individuals = store.individuals(g).unwrap();
        assert_eq!(individuals.len(), 12);
        // The best of each generation is the generation's best figure.
        let best = individuals
            .iter()
            .map(|i| i.fitness)
            .fold(f64::NEG_INFINITY, f64::max);
        assert_eq!(best, generations[g as usize].best);
        // Elitism: the best never gets worse.
        if g > 0 {
            assert!(generations[g as usize].best >= generations[g as usize - 1].best);
            assert_eq!(individuals[0].operator, "elite");
        }
    }
    // best.lsys (best.json) is a genome that grows and evaluates to the stored best fitness.
    let eval = ontogeny_command()
        .args(["eval", "--task", "walker", "--seconds", "1", "--json"])
        .arg(out.join(&best))
        .output()
        .unwrap();
    assert!(
        eval.status.success(),
        "{}",
        String::from_utf8_lossy(&eval.stderr)
    );
    let value: serde_json::Value = serde_json::from_slice(&eval.stdout).unwrap();
    assert_eq!(
        value["fitness"].as_f64().unwrap(),
        generations[3].best,
        "{encoding}"
    );
    // `runs show` prints a row per generation; `replay` re-evaluates the best.
    let show = ontogeny_command()
        .args(["runs", "show"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(show.status.success());
    assert_eq!(String::from_utf8_lossy(&show.stdout).lines().count(), 2 + 4);
    let replay = ontogeny_command()
        .arg("replay")
        .arg(&out)
        .args(["--gen", "3"])
        .output()
        .unwrap();
    assert!(
        replay.status.success(),
        "{}",
        String::from_utf8_lossy(&replay.stderr)
    );
    let shown = out.join("replay").join("gen-3-rank-1");
    let genome = format!("genome.{}", text_extension(encoding));
    for file in [
        genome.as_str(),
        "creature.png",
        "recording.json",
        "behaviour.gif",
    ] {
        assert!(shown.join(file).exists(), "{file}");
    }
    assert!(
        !String::from_utf8_lossy(&replay.stdout).contains("differs"),
        "{encoding}"
    );
    // Each generation's best was re-walked at the fine reference: the value stored is the
    // evaluation recomputed here, and the log, plot, `runs show` and end line say it.
    match encoding {
        "lsystem" => fine_values_are_recomputed::<LSystemGenome>(&out),
        "lsystem-continuous" => fine_values_are_recomputed::<ContinuousGenome>(&out),
        "direct" => fine_values_are_recomputed::<DirectGenome>(&out),
        "graph" => fine_values_are_recomputed::<GraphGenome>(&out),
        other => panic!("no genome type for {other}"),
    }
    let log = std::fs::read_to_string(out.join("log.txt")).unwrap();
    assert_eq!(log.matches(" (fine reference ").count(), 4, "{log}");
    let svg = std::fs::read_to_string(out.join("fitness.svg")).unwrap();
    assert!(
        svg.contains(FINE_LABEL),
        "{encoding}: no fine line in the plot"
    );
    let shown = String::from_utf8_lossy(&show.stdout).to_string();
    assert!(shown.contains("best fine"), "{shown}");
    let last = store.generations().unwrap()[3].best_fine.clone().unwrap();
    let end = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(
        end.contains(&format!(
            "generation 3 best {:.6} (fine reference {:.6}",
            generations[3].best, last.fitness
        )),
        "{end}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// Checks every generation's stored fine reference value of the run in `out` against the
/// rank-1 individual developed again and evaluated with the run's task at
/// `sim.fine_reference()`; and that the check differs from the stored best somewhere, so it
/// does run at another setting.
fn fine_values_are_recomputed<G: Genome>(out: &Path) {
    let run = Run::<G>::resume(out).unwrap();
    let config = run.config().clone();
    let mut limits = config.limits.clone();
    G::adapt_limits(&mut limits, Purpose::Locomotion);
    let fine = TaskSpec {
        sim: config.task.sim.fine_reference(),
        ..config.task.clone()
    };
    assert_eq!(
        (
            fine.sim.substeps,
            fine.sim.solver_iterations,
            fine.sim.pgs_iterations
        ),
        (4, 8, 1)
    );
    assert_eq!(
        (fine.sim.rest_substeps, fine.sim.rest_solver_iterations),
        (4, 8)
    );
    assert_eq!(fine.sim.control_step, config.task.sim.control_step);
    let store = RunStore::open_read_only(&out.join("run.sqlite")).unwrap();
    let mut differs = false;
    for g in store.generations().unwrap() {
        let population = run.population(g.index).unwrap();
        let best = &population[ranking(&population)[0]];
        assert_eq!(best.evaluation.fitness, g.best);
        let expected = match best.genome.develop(&limits, best.develop_seed) {
            Ok(creature) => fine.evaluate(&creature, false),
            Err(e) => Evaluation::invalid("walker", format!("development: {e}")),
        };
        let stored = g.best_fine.expect("verified");
        assert_eq!(
            stored.fitness.to_bits(),
            expected.fitness.to_bits(),
            "{} generation {}: {} stored, {} recomputed",
            G::NAME,
            g.index,
            stored.fitness,
            expected.fitness
        );
        assert_eq!(
            serde_json::to_value(expected.status).unwrap(),
            serde_json::Value::String(stored.status.clone())
        );
        differs |= stored.fitness != g.best;
    }
    assert!(
        differs,
        "{}: the fine reference gave the stored best",
        G::NAME
    );
}

#[test]
fn verify_best_off_stores_null_and_evaluates_nothing_more() {
    let dir = scratch("no-verify");
    // From the command line, and from the config file.
    let config = dir.join("off.toml");
    std::fs::write(&config, "verify_best = false\n").unwrap();
    let flag = dir.join("flag");
    let file = dir.join("file");
    let on = dir.join("on");
    for (out, extra) in [
        (&flag, vec!["--no-verify-best".to_string()]),
        (&file, vec!["--config".into(), config.display().to_string()]),
        (&on, vec![]),
    ] {
        let extra: Vec<&str> = extra.iter().map(String::as_str).collect();
        let o = run_of("lsystem", out, "2", &extra);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    for out in [&flag, &file] {
        let written = std::fs::read_to_string(out.join("config.toml")).unwrap();
        assert!(written.contains("verify_best = false"), "{written}");
        let store = RunStore::open(&out.join("run.sqlite")).unwrap();
        assert!(
            store
                .generations()
                .unwrap()
                .iter()
                .all(|g| g.best_fine.is_none())
        );
        let log = std::fs::read_to_string(out.join("log.txt")).unwrap();
        assert!(!log.contains("fine reference"), "{log}");
        let svg = std::fs::read_to_string(out.join("fitness.svg")).unwrap();
        assert!(!svg.contains(FINE_LABEL));
        // The GA itself is the same as with the check on.
        assert_ne!(contents(out), contents(&on));
        assert_eq!(contents(out), contents_of(&on, false, CacheColumns::Both));
    }
    assert!(
        std::fs::read_to_string(on.join("config.toml"))
            .unwrap()
            .contains("verify_best = true")
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_version_1_database_is_migrated_on_resume() {
    let dir = scratch("version-1");
    let whole = dir.join("whole");
    assert!(small_run("lsystem", &whole, &[]).status.success());
    // The same run stopped after generation 1 by a version that knew schema 1 only: its
    // database turned back into version 1 (the columns dropped), its config.toml without
    // the switch.
    let old = dir.join("old");
    assert!(small_run("lsystem", &old, &[]).status.success());
    let config = std::fs::read_to_string(old.join("config.toml")).unwrap();
    std::fs::write(
        old.join("config.toml"),
        config.replace("verify_best = true\n", ""),
    )
    .unwrap();
    {
        let conn = rusqlite::Connection::open(old.join("run.sqlite")).unwrap();
        conn.execute_batch(crate::util::DROP_VERSION_4).unwrap();
        conn.execute_batch(
            "DELETE FROM individual WHERE generation >= 2;
             DELETE FROM generation WHERE generation >= 2;
             ALTER TABLE generation DROP COLUMN best_fine;
             ALTER TABLE generation DROP COLUMN best_fine_status;
             ALTER TABLE individual DROP COLUMN reused;
             ALTER TABLE individual DROP COLUMN evaluation_key;
             PRAGMA user_version = 1;
             PRAGMA wal_checkpoint(TRUNCATE);",
        )
        .unwrap();
    }
    // `runs show` reads it without changing it.
    let before = std::fs::read(old.join("run.sqlite")).unwrap();
    let show = ontogeny_command()
        .args(["runs", "show"])
        .arg(&old)
        .output()
        .unwrap();
    assert!(
        show.status.success(),
        "{}",
        String::from_utf8_lossy(&show.stderr)
    );
    assert_eq!(String::from_utf8_lossy(&show.stdout).lines().count(), 2 + 2);
    assert_eq!(std::fs::read(old.join("run.sqlite")).unwrap(), before);
    // A store of schema 1 records no evaluator version: it was made by evaluator 1, and
    // today's resumes it when asked to.
    let resumed = ontogeny_command()
        .arg("evolve")
        .arg("--resume")
        .arg(&old)
        .arg("--allow-evaluator-change")
        .output()
        .unwrap();
    assert!(
        resumed.status.success(),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    let store = RunStore::open_read_only(&old.join("run.sqlite")).unwrap();
    assert_eq!(store.schema_version(), ontogeny::run::store::SCHEMA_VERSION);
    let generations = store.generations().unwrap();
    let fresh = RunStore::open_read_only(&whole.join("run.sqlite"))
        .unwrap()
        .generations()
        .unwrap();
    // The old generations read back as not verified; the new ones as the uninterrupted
    // run's.
    assert_eq!(generations[0].best_fine, None);
    assert_eq!(generations[1].best_fine, None);
    assert!(fresh[2].best_fine.is_some());
    assert_eq!(generations[2].best_fine, fresh[2].best_fine);
    assert_eq!(generations[3].best_fine, fresh[3].best_fine);
    // Nothing else differs.
    assert_eq!(
        contents_of(&old, false, CacheColumns::Neither),
        contents_of(&whole, false, CacheColumns::Neither)
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_warning_threshold_is_half_the_stored_best_s_size() {
    // Half of 26.23 is 13.115.
    assert!(exploits_stepping(26.23, 4.10));
    assert!(exploits_stepping(26.23, 13.11));
    assert!(!exploits_stepping(26.23, 13.12));
    assert!(!exploits_stepping(26.23, 30.0));
    // No number at the fine reference: suspicious too.
    assert!(exploits_stepping(26.23, f64::NAN));
    // A best of 0 has nothing to lose.
    assert!(!exploits_stepping(0.0, -5.0));
    // A negative best (the hornby-pollack fitness can be one) is suspicious when it falls
    // by more than half its size: -2 to below -3.
    assert!(!exploits_stepping(-2.0, -2.9));
    assert!(!exploits_stepping(-2.0, 1.0));
    assert!(exploits_stepping(-2.0, -3.1));
    assert!(exploits_stepping(-3.0, -999_999.0));
}

#[test]
fn one_and_two_threads_give_the_same_run() {
    for encoding in ENCODINGS {
        let dir = scratch(&format!("threads-{encoding}"));
        let (a, b) = (dir.join("one"), dir.join("two"));
        assert!(
            small_run(encoding, &a, &["--threads", "1"])
                .status
                .success()
        );
        assert!(
            small_run(encoding, &b, &["--threads", "2"])
                .status
                .success()
        );
        assert_eq!(contents(&a), contents(&b), "{encoding}");
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn a_run_killed_mid_generation_resumes_to_the_same_result() {
    for encoding in ENCODINGS {
        killed_mid_generation_resumes_to_the_same_result(encoding);
    }
}

fn killed_mid_generation_resumes_to_the_same_result(encoding: &str) {
    let dir = scratch(&format!("kill-{encoding}"));
    let whole = dir.join("whole");
    assert!(small_run(encoding, &whole, &[]).status.success());
    let killed = dir.join("killed");
    // Start the same run and SIGKILL it once generation 1 is committed, while generation 2
    // is being evaluated.
    let mut child = evolve_command(encoding, &killed, "4", &[])
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
        done.is_some_and(|g| g < 3),
        "{encoding}: killed before the end: {done:?}"
    );
    let resumed = ontogeny_command()
        .arg("evolve")
        .arg("--resume")
        .arg(&killed)
        .output()
        .unwrap();
    assert!(
        resumed.status.success(),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    assert_eq!(contents(&whole), contents(&killed), "{encoding}");
    // A complete run has nothing to resume; its derived files are written again, the same.
    let plot = killed.join("fitness.svg");
    let drawn = std::fs::read(&plot).unwrap();
    std::fs::remove_file(&plot).unwrap();
    let again = ontogeny_command()
        .arg("evolve")
        .arg("--resume")
        .arg(&killed)
        .output()
        .unwrap();
    assert!(again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("nothing to resume"));
    assert_eq!(std::fs::read(&plot).unwrap(), drawn, "{encoding}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bad_input_is_refused_with_exit_code_2() {
    for encoding in ENCODINGS {
        bad_input_is_refused(encoding);
    }
}

fn bad_input_is_refused(encoding: &str) {
    let dir = scratch(&format!("bad-{encoding}"));
    // An unknown key: file, line and key.
    let config = dir.join("bad.toml");
    std::fs::write(
        &config,
        format!("encoding = \"{encoding}\"\n\n[ga]\npopulation = 10\npopulaton = 12\n"),
    )
    .unwrap();
    let o = ontogeny_command()
        .args(["evolve", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(dir.join("x"))
        .output()
        .unwrap();
    let err = refused(&o, "bad.toml:5:1");
    assert!(err.contains("populaton"), "{err}");
    assert!(!dir.join("x").exists());
    // An out-of-range value.
    std::fs::write(
        &config,
        format!("encoding = \"{encoding}\"\n[ga]\nelite = 1.5\n"),
    )
    .unwrap();
    let o = ontogeny_command()
        .args(["evolve", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(dir.join("y"))
        .output()
        .unwrap();
    refused(&o, "elite must be between 0 and 1");
    // --out naming an existing run is refused, and the run is untouched.
    let run = dir.join("run");
    assert!(run_of(encoding, &run, "1", &[]).status.success());
    let before = std::fs::read(run.join("run.sqlite")).unwrap();
    let o = small_run(encoding, &run, &[]);
    refused(&o, "--resume");
    assert_eq!(before, std::fs::read(run.join("run.sqlite")).unwrap());
    // A truncated database: a clear message, nothing overwritten.
    let half = before[..before.len() / 2].to_vec();
    std::fs::write(run.join("run.sqlite"), &half).unwrap();
    let o = ontogeny_command()
        .arg("evolve")
        .arg("--resume")
        .arg(&run)
        .output()
        .unwrap();
    refused(&o, "run.sqlite");
    assert_eq!(half, std::fs::read(run.join("run.sqlite")).unwrap());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn init_seeds_the_first_generation_with_a_grammar_and_its_mutants() {
    // The file, and a shipped grammar the encoding cannot hold.
    for (encoding, refused) in [("lsystem", "dl-figure1"), ("direct", "dl-figure1")] {
        let dir = scratch(&format!("init-{encoding}"));
        let out = dir.join("run");
        let o = run_of(
            encoding,
            &out,
            "1",
            &["--init", "examples/hornby-walker.lsys"],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(
            std::fs::read_to_string(out.join("init.lsys")).unwrap(),
            std::fs::read_to_string("examples/hornby-walker.lsys").unwrap()
        );
        let store = RunStore::open(&out.join("run.sqlite")).unwrap();
        let first = store.individuals(0).unwrap();
        assert!(first.iter().all(|i| i.operator == "init"));
        if encoding == "direct" {
            // The grammar's derived string, as an axiom.
            assert!(
                first[0]
                    .genome_text
                    .contains("\naxiom: width(0.6) thickness(0.2) forward(0.8) [")
            );
        }
        // Individual 0 is the grammar itself: it scores what `eval` gives the file.
        let eval = ontogeny_command()
            .args(["eval", "--task", "walker", "--seconds", "1", "--json"])
            .arg("examples/hornby-walker.lsys")
            .output()
            .unwrap();
        let value: serde_json::Value = serde_json::from_slice(&eval.stdout).unwrap();
        assert_eq!(value["fitness"].as_f64().unwrap(), first[0].fitness);
        // A grammar the genome cannot hold is refused before anything is written.
        let o = run_of(
            encoding,
            &dir.join("bad"),
            "1",
            &["--init", &format!("examples/{refused}.lsys")],
        );
        crate::util::refused(&o, &format!("does not fit the {encoding} genome"));
        assert!(!dir.join("bad").exists());
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn every_task_and_preset_runs_with_the_direct_and_graph_encodings() {
    for encoding in ["direct", "graph"] {
        every_task_and_preset_runs_with(encoding);
    }
}

fn every_task_and_preset_runs_with(encoding: &str) {
    let dir = scratch(&format!("tasks-{encoding}"));
    // The aim task needs a target.
    let config = dir.join("aim.toml");
    std::fs::write(&config, "[task.catapult]\ntarget = [3.0, 0.0, 0.0]\n").unwrap();
    for task in ["walker", "catapult", "aim", "jump"] {
        for preset in ["chaumont", "wwd"] {
            let out = dir.join(format!("{task}-{preset}"));
            // Two generations of 6, so that the preset's operators make the second.
            let o = ontogeny_command()
                .args(["evolve", "--encoding", encoding, "--task", task])
                .args(["--preset", preset, "--pop", "6", "--gens", "2"])
                .args(["--seconds", "0.5", "--seed", "3", "--config"])
                .arg(&config)
                .arg("--out")
                .arg(&out)
                .output()
                .unwrap();
            assert!(
                o.status.success(),
                "{task} {preset}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            let store = RunStore::open(&out.join("run.sqlite")).unwrap();
            let run = store.run().unwrap();
            assert_eq!((run.encoding.as_str(), run.task.as_str()), (encoding, task));
            assert_eq!(store.generations().unwrap().len(), 2, "{task} {preset}");
            let second = store.individuals(1).unwrap();
            assert!(
                second.iter().any(|i| i.operator == "crossover"),
                "{task} {preset}: {:?}",
                second.iter().map(|i| &i.operator).collect::<Vec<_>>()
            );
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn an_elite_copy_of_the_best_is_not_walked_again() {
    let dir = scratch("elite-copy");
    let whole = dir.join("whole");
    // The small run of seed 12 (a seed whose generation 1 finds a new best that 2 and 3 keep).
    let seeded_run = |out: &Path| {
        let output = ontogeny_command()
            .args([
                "evolve",
                "--encoding",
                "lsystem",
                "--task",
                "walker",
                "--pop",
                "12",
                "--gens",
                "4",
                "--seconds",
                "1",
                "--seed",
                "12",
                "--out",
            ])
            .arg(out)
            .output()
            .unwrap();
        assert!(output.status.success());
    };
    seeded_run(&whole);
    let fine = |dir: &Path| -> Vec<f64> {
        RunStore::open_read_only(&dir.join("run.sqlite"))
            .unwrap()
            .generations()
            .unwrap()
            .iter()
            .map(|g| g.best_fine.as_ref().unwrap().fitness)
            .collect()
    };
    // Which generations' best is the previous best carried over unchanged.
    let rank_1 = |store: &RunStore, g: u32| {
        let is = store.individuals(g).unwrap();
        let best = is
            .iter()
            .map(|i| i.fitness)
            .fold(f64::NEG_INFINITY, f64::max);
        is.into_iter().find(|i| i.fitness == best).unwrap()
    };
    let store = RunStore::open_read_only(&whole.join("run.sqlite")).unwrap();
    let copied: Vec<bool> = (1..4)
        .map(|g| {
            let (now, before) = (rank_1(&store, g), rank_1(&store, g - 1));
            now.operator == "elite" && now.parents == [before.index]
        })
        .collect();
    assert_eq!(
        copied,
        [false, true, true],
        "the run's bests changed: pick another"
    );
    drop(store);
    // The run stopped after generation `after`, whose stored value is then replaced by a
    // marker; the fine reference values of the resumed run.
    let resumed_with_marker = |after: u32| -> Vec<f64> {
        let cut = dir.join(format!("cut-{after}"));
        seeded_run(&cut);
        {
            let conn = rusqlite::Connection::open(cut.join("run.sqlite")).unwrap();
            conn.execute_batch(&format!(
                "DELETE FROM individual WHERE generation > {after};
                 DELETE FROM generation WHERE generation > {after};
                 UPDATE generation SET best_fine = 123.0 WHERE generation = {after};"
            ))
            .unwrap();
            // Edited by hand: made a version-3 store, whose resume checksums it as it is.
            conn.execute_batch(crate::util::DROP_VERSION_4).unwrap();
            conn.pragma_update(None, "user_version", 3).unwrap();
        }
        // A version-3 store records no evaluator version: taken as evaluator 1's, resumed
        // by today's when asked to.
        let resumed = ontogeny_command()
            .args(["evolve", "--resume"])
            .arg(&cut)
            .arg("--allow-evaluator-change")
            .output()
            .unwrap();
        assert!(resumed.status.success());
        fine(&cut)
    };
    let whole = fine(&whole);
    assert!(!whole.contains(&123.0));
    // Generation 1's best is new: walked, whatever was stored before it; 2 and 3 copy it.
    assert_eq!(
        resumed_with_marker(0),
        [vec![123.0], whole[1..].to_vec()].concat()
    );
    // Generation 1's stored value, the marker, came from another evaluator (a store edited
    // by hand is migrated as one made by evaluator 1): generation 2's elite copy of that best
    // is walked again, not given the marker, and generation 3 copies generation 2's walk.
    assert_eq!(
        resumed_with_marker(1),
        [&whole[..1], &[123.0], &whole[2..]].concat()
    );
    assert_eq!(whole[2], whole[3]);
    let _ = std::fs::remove_dir_all(dir);
}

/// Runs `ontogeny evolve --resume DIR`.
fn resume(dir: &Path) -> Output {
    ontogeny_command()
        .args(["evolve", "--resume"])
        .arg(dir)
        .output()
        .unwrap()
}

/// `ontogeny evolve --resume DIR --allow-evaluator-change`: the resume of a store whose schema
/// predates the evaluator version (taken as evaluator 1's).
fn resume_older_store(dir: &Path) -> Output {
    ontogeny_command()
        .args(["evolve", "--resume"])
        .arg(dir)
        .arg("--allow-evaluator-change")
        .output()
        .unwrap()
}

/// The `config.toml` of the run in `dir`.
fn config_text(dir: &Path) -> String {
    std::fs::read_to_string(dir.join("config.toml")).unwrap()
}
