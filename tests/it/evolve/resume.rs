//! Resuming a run: an edited config refused, a second process refused, every state a killed
//! start leaves completed, the log and plot rewritten, a finished run extended with `--gens`,
//! a version-1 store replayed without migrating it.

use super::*;

#[test]
fn a_resume_whose_config_was_edited_is_refused_naming_the_keys_and_changes_nothing() {
    let dir = scratch("edited");
    let run = dir.join("run");
    succeeded(&run_of("direct", &run, "2", &[]));
    let config = std::fs::read_to_string(run.join("config.toml")).unwrap();
    let edited = config
        .replace("seed = 5\n", "seed = 6\n")
        .replace("population = 12\n", "population = 13\n");
    assert_ne!(edited, config);
    std::fs::write(run.join("config.toml"), &edited).unwrap();
    let before = contents(&run);
    let database = std::fs::read(run.join("run.sqlite")).unwrap();
    refused(
        &resume(&run),
        "ga.population, seed differ from the settings",
    );
    assert_eq!(contents(&run), before);
    assert_eq!(std::fs::read(run.join("run.sqlite")).unwrap(), database);
    // A change that does not change a setting (a comment, the layout) is no change.
    std::fs::write(run.join("config.toml"), format!("# my notes\n\n{config}")).unwrap();
    succeeded(&resume(&run));
    let _ = std::fs::remove_dir_all(dir);
}

/// Waits until the process `pid` holds the lock of `dir` (it wrote itself into `.lock`) and
/// has made its run's store.
fn wait_for_lock(dir: &Path, pid: u32) {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while !(std::fs::read_to_string(dir.join(".lock"))
        .is_ok_and(|holder| holder.starts_with(&format!("pid {pid}:")))
        && dir.join("config.toml").is_file())
    {
        assert!(std::time::Instant::now() < deadline, "no lock taken");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
}

#[test]
fn a_second_process_on_a_run_directory_is_refused_at_once_naming_the_holder() {
    let dir = scratch("locked");
    let run = dir.join("run");
    let mut first = evolve_command("direct", &run, "1000", &[])
        .stderr(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    wait_for_lock(&run, first.id());
    let holder = format!("pid {}", first.id());
    // Another start on the same directory, and a resume while it runs.
    let again = run_of("direct", &run, "1000", &[]);
    let resumed = resume(&run);
    first.kill().unwrap();
    let _ = first.wait();
    for output in [&again, &resumed] {
        refused(output, "is in use by another ontogeny process");
        refused(output, &holder);
    }
    // The lock dies with its holder, however it died.
    ontogeny::run::lock::DirectoryLock::acquire(&run).unwrap();
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn every_state_a_killed_start_leaves_is_one_resume_completes() {
    let dir = scratch("start-states");
    let whole = dir.join("whole");
    succeeded(&run_of("lsystem", &whole, "2", &[]));
    let config = config_text(&whole);
    // An older ontogeny wrote config.toml first, then created the store in place: killed
    // in between, it left config.toml alone, or beside an empty file, or beside an SQLite
    // file in WAL mode with no table yet.
    let alone = dir.join("config-alone");
    let empty = dir.join("empty-store");
    let tableless = dir.join("tableless-store");
    for d in [&alone, &empty, &tableless] {
        std::fs::create_dir_all(d).unwrap();
        std::fs::write(d.join("config.toml"), &config).unwrap();
    }
    std::fs::write(empty.join("run.sqlite"), b"").unwrap();
    {
        let conn = rusqlite::Connection::open(tableless.join("run.sqlite")).unwrap();
        conn.pragma_update(None, "journal_mode", "WAL").unwrap();
    }
    // This ontogeny creates the store whole, then config.toml: killed in between, the store
    // alone (with no generation yet).
    let store_alone = dir.join("store-alone");
    {
        let source = ontogeny::lang::Source::new("config.toml", config.clone());
        let run_config = ontogeny::run::config::read_run_config(&source).unwrap();
        Run::<LSystemGenome>::start(&store_alone, run_config, None).unwrap();
    }
    std::fs::remove_file(store_alone.join("config.toml")).unwrap();
    for d in [&alone, &empty, &tableless, &store_alone] {
        // `--out` refuses it as a run, and `--resume` completes it.
        refused(&run_of("lsystem", d, "2", &[]), "already holds a run");
        succeeded(&resume(d));
        assert_eq!(contents(d), contents(&whole), "{}", d.display());
        assert_eq!(config_text(d), config, "{}", d.display());
    }
    // Killed while building the store under its temporary name: no run; `--out` starts it.
    let partial = dir.join("partial");
    std::fs::create_dir_all(&partial).unwrap();
    std::fs::write(partial.join("run.sqlite.partial"), b"SQLite format 3\0half").unwrap();
    refused(&resume(&partial), "holds no run");
    succeeded(&run_of("lsystem", &partial, "2", &[]));
    assert_eq!(contents(&partial), contents(&whole));
    assert!(!partial.join("run.sqlite.partial").exists());
    let _ = std::fs::remove_dir_all(dir);
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

#[test]
fn log_and_plot_are_rewritten_from_the_store_on_every_resume() {
    // The direct encoding has no crossover: the log counts the children made by mutation
    // instead, and a resume counts on from the store, not from zero.
    let dir = scratch("derived");
    let whole = dir.join("whole");
    succeeded(&run_of("direct", &whole, "4", &[]));
    let log = log_without_times(&whole);
    // A line per generation, then the note, said once.
    assert_eq!(log.lines().count(), 4 + 1, "{log}");
    assert!(
        log.lines()
            .last()
            .unwrap()
            .contains("children of generations 1 to 3 were made by mutation instead"),
        "{log}"
    );
    assert_eq!(log.matches("made by mutation instead").count(), 1, "{log}");
    // A kill inside a commit lost the last log line and left the plot a point short; another
    // process damaged the best file. A resume of the finished run rewrites all three.
    let damaged = dir.join("damaged");
    std::fs::create_dir_all(&damaged).unwrap();
    for file in ["config.toml", "run.sqlite"] {
        std::fs::copy(whole.join(file), damaged.join(file)).unwrap();
    }
    let first_line: String = log.lines().next().unwrap().to_string();
    std::fs::write(damaged.join("log.txt"), first_line).unwrap();
    std::fs::write(damaged.join("best.lsys"), "").unwrap();
    succeeded(&resume(&damaged));
    assert_eq!(log_without_times(&damaged), log);
    assert_eq!(
        std::fs::read_to_string(damaged.join("best.lsys")).unwrap(),
        std::fs::read_to_string(whole.join("best.lsys"))
            .unwrap()
            .replace(&whole.display().to_string(), &damaged.display().to_string())
    );
    assert!(damaged.join("fitness.svg").is_file());
    // Killed after generation 1 and resumed: the same log as the uninterrupted run.
    let killed = dir.join("killed");
    succeeded(&run_of("direct", &killed, "4", &[]));
    {
        let conn = rusqlite::Connection::open(killed.join("run.sqlite")).unwrap();
        conn.execute_batch(
            "DELETE FROM individual WHERE generation >= 2;
             DELETE FROM generation WHERE generation >= 2;",
        )
        .unwrap();
    }
    succeeded(&resume(&killed));
    assert_eq!(contents(&killed), contents(&whole));
    assert_eq!(log_without_times(&killed), log);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn replay_reads_a_version_1_store_without_migrating_it() {
    let dir = scratch("read-only");
    let run = dir.join("run");
    succeeded(&small_run("lsystem", &run, &[]));
    crate::util::make_version_1(&run.join("run.sqlite"));
    let before = std::fs::read(run.join("run.sqlite")).unwrap();
    succeeded(
        &ontogeny_command()
            .args(["replay"])
            .arg(&run)
            .args(["--gen", "0", "--rank", "2"])
            .output()
            .unwrap(),
    );
    assert_eq!(std::fs::read(run.join("run.sqlite")).unwrap(), before);
    let store = RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    assert_eq!(store.schema_version(), 1);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_finished_run_extended_with_gens_equals_a_run_started_with_that_many() {
    let dir = scratch("extend");
    let whole = dir.join("whole");
    succeeded(&small_run("direct", &whole, &[]));
    let extended = dir.join("extended");
    succeeded(&run_of("direct", &extended, "2", &[]));
    // Fewer generations than it has stored: refused, nothing changed.
    let before = contents(&extended);
    let shorter = ontogeny_command()
        .args(["evolve", "--gens", "1", "--resume"])
        .arg(&extended)
        .output()
        .unwrap();
    refused(&shorter, "has 2 generations stored");
    assert_eq!(contents(&extended), before);
    let longer = ontogeny_command()
        .args(["evolve", "--gens", "4", "--resume"])
        .arg(&extended)
        .output()
        .unwrap();
    succeeded(&longer);
    assert_eq!(contents(&extended), contents(&whole));
    let settings = |d: &Path| {
        RunStore::open_read_only(&d.join("run.sqlite"))
            .unwrap()
            .run()
            .unwrap()
            .config
    };
    assert_eq!(settings(&extended), settings(&whole));
    assert_eq!(config_text(&extended), config_text(&whole));
    // Editing the count in config.toml extends it too: the one setting a resume may change.
    let config = config_text(&extended);
    std::fs::write(
        extended.join("config.toml"),
        config.replace("generations = 4\n", "generations = 5\n"),
    )
    .unwrap();
    succeeded(&resume(&extended));
    assert_eq!(
        RunStore::open_read_only(&extended.join("run.sqlite"))
            .unwrap()
            .last_generation()
            .unwrap(),
        Some(4)
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_run_whose_config_was_edited_to_a_population_of_zero_is_refused_on_resume() {
    let dir = scratch("resume-population-0");
    let run = dir.join("run");
    assert!(run_of("direct", &run, "1", &[]).status.success());
    // The input the config fuzz target found: the GA panicked (`clamp` with min > max).
    let config = run.join("config.toml");
    let edited: Vec<String> = std::fs::read_to_string(&config)
        .unwrap()
        .lines()
        .map(|line| match line.split(" = ").next() {
            Some("population") => "population = 0".to_string(),
            Some("generations") => "generations = 3".to_string(),
            _ => line.to_string(),
        })
        .collect();
    std::fs::write(&config, edited.join("\n")).unwrap();
    let before = std::fs::read(run.join("run.sqlite")).unwrap();
    let o = ontogeny_command()
        .args(["evolve", "--resume"])
        .arg(&run)
        .output()
        .unwrap();
    let said = refused(&o, "[ga] population must be 2 to 100000, not 0\n");
    assert!(said.contains("config.toml:"), "the file at fault: {said}");
    assert_eq!(before, std::fs::read(run.join("run.sqlite")).unwrap());
    // `replay` reads the run's settings from its store, not the edited file.
    let o = ontogeny_command().arg("replay").arg(&run).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(before, std::fs::read(run.join("run.sqlite")).unwrap());
    let _ = std::fs::remove_dir_all(dir);
}
