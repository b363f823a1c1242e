//! A config's `[task]` tables: a config may hold several tasks' tables and run the one
//! `task =` or `--task` names; every table it holds is checked; the files a run writes
//! (`config.toml`, the store's copy, `best.*`) carry the run task's table alone, so that an
//! earlier release, which knows no newer task's table, still reads them.

use std::path::{Path, PathBuf};

use ontogeny::run::store::RunStore;

use crate::util::{ontogeny_command, refused, scratch_dir, stderr, succeeded};

/// A config holding the walker's, the jump's and the stand task's tables, naming `task`.
fn several_tables(task: &str) -> String {
    format!(
        "encoding = \"lsystem\"\n[ga]\npopulation = 4\ngenerations = 1\n[task]\ntask = \"{task}\"\n\
         [task.walker]\nseconds = 0.5\n[task.jump]\nseconds = 0.25\n[task.stand]\nseconds = 0.75\n"
    )
}

/// Runs `ontogeny evolve --config CONFIG --seed 3 EXTRA --out DIR/NAME` with `config` written
/// into `dir`; returns the run's directory.
fn evolve_with(dir: &Path, name: &str, config: &str, extra: &[&str]) -> PathBuf {
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, config).unwrap();
    let out = dir.join(name);
    let output = ontogeny_command()
        .args(["evolve", "--seed", "3", "--config"])
        .arg(&file)
        .args(extra)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    succeeded(&output);
    out
}

/// The `[task...]` table headers of a TOML text, in order.
fn task_tables(text: &str) -> Vec<&str> {
    text.lines().filter(|l| l.starts_with("[task")).collect()
}

#[test]
fn a_walker_runs_written_files_carry_only_the_walker_table() {
    let dir = scratch_dir("task_tables-walker");
    let run = evolve_with(&dir, "run", &several_tables("walker"), &[]);
    let written = std::fs::read_to_string(run.join("config.toml")).unwrap();
    assert_eq!(
        task_tables(&written),
        [
            "[task]",
            "[task.sim]",
            "[task.walker]",
            "[task.walker.rest]"
        ]
    );
    assert!(
        written.contains("[task.walker]\nseconds = 0.5\n"),
        "{written}"
    );
    let stored = RunStore::open_read_only(&run.join("run.sqlite"))
        .unwrap()
        .run()
        .unwrap()
        .config;
    assert_eq!(stored, written);
    let best = std::fs::read_to_string(run.join("best.lsys")).unwrap();
    assert!(best.contains("\"walker\":{"), "{best}");
    for other in ["\"jump\"", "\"stand\"", "\"catapult\""] {
        assert!(!best.contains(other), "{other} in {best}");
    }
}

#[test]
fn a_config_with_several_tables_runs_the_task_it_names_or_the_one_task_names() {
    let dir = scratch_dir("task_tables-choose");
    let run = evolve_with(&dir, "jump", &several_tables("jump"), &[]);
    let written = std::fs::read_to_string(run.join("config.toml")).unwrap();
    assert!(written.contains("task = \"jump\""), "{written}");
    assert!(
        written.contains("[task.jump]\nseconds = 0.25\n"),
        "{written}"
    );
    assert!(!written.contains("[task.walker]"), "{written}");
    let run = evolve_with(&dir, "stand", &several_tables("jump"), &["--task", "stand"]);
    let written = std::fs::read_to_string(run.join("config.toml")).unwrap();
    assert!(written.contains("task = \"stand\""), "{written}");
    assert!(
        written.contains("[task.stand]\nseconds = 0.75\n"),
        "{written}"
    );
    assert_eq!(
        task_tables(&written),
        ["[task]", "[task.sim]", "[task.stand]", "[task.stand.rest]"]
    );
}

#[test]
fn a_table_of_another_task_is_checked_though_it_is_not_run() {
    let dir = scratch_dir("task_tables-checked");
    let file = dir.join("other.toml");
    std::fs::write(
        &file,
        "[task]\ntask = \"walker\"\n[task.jump]\nseconds = -1.0\n",
    )
    .unwrap();
    let output = ontogeny_command()
        .args(["evolve", "--pop", "4", "--gens", "1", "--config"])
        .arg(&file)
        .arg("--out")
        .arg(dir.join("run"))
        .output()
        .unwrap();
    let said = refused(&output, "[task.jump] seconds must be in (0, 3600], not -1");
    assert!(said.contains("other.toml:4:11"), "{said}");
    assert!(!dir.join("run").exists(), "{}", stderr(&output));
}

#[test]
fn a_table_of_no_task_is_refused_with_the_tables_there_are() {
    let dir = scratch_dir("task_tables-unknown");
    let file = dir.join("climb.toml");
    std::fs::write(
        &file,
        "[task]\ntask = \"walker\"\n[task.climb]\nseconds = 1.0\n",
    )
    .unwrap();
    let output = ontogeny_command()
        .args(["evolve", "--config"])
        .arg(&file)
        .arg("--out")
        .arg(dir.join("run"))
        .output()
        .unwrap();
    let said = refused(&output, "unknown key climb in [task]");
    assert!(said.contains("climb.toml:3:"), "{said}");
    assert!(
        said.contains(
            "its keys are task, develop, develop_rate, develop_t0, sim, world, trials, habitats, walker, \
             jump, catapult, stand, swim"
        ),
        "{said}"
    );
}
