//! The evaluation cache and the fitness a run optimises: the cache changes nothing stored but
//! `reused`, identical creatures reuse their evaluation bit for bit, every report names the
//! fitness, and a version-2 database is migrated on resume.

use super::*;

/// Every stored individual of the run in `dir`, in generation and index order.
fn stored_individuals(dir: &Path) -> Vec<ontogeny::run::store::IndividualRecord> {
    let store = RunStore::open_read_only(&dir.join("run.sqlite")).unwrap();
    let last = store.last_generation().unwrap().unwrap();
    (0..=last)
        .flat_map(|g| store.individuals(g).unwrap())
        .collect()
}

#[test]
fn the_cache_changes_nothing_in_the_database_but_reused_for_every_encoding() {
    for encoding in ENCODINGS {
        let dir = scratch(&format!("cache-{encoding}"));
        let (on, off) = (dir.join("on"), dir.join("off"));
        succeeded(&small_run(encoding, &on, &[]));
        succeeded(&small_run(encoding, &off, &["--no-cache"]));
        assert_eq!(
            contents_of(&on, true, CacheColumns::Key),
            contents_of(&off, true, CacheColumns::Key),
            "{encoding}"
        );
        assert!(config_text(&off).contains("cache = false"), "{encoding}");
        let off = stored_individuals(&off);
        assert!(off.iter().all(|i| !i.reused), "{encoding}");
        // Every developed creature has a key; one that did not develop has none.
        for i in &off {
            let undeveloped = i.genome_json.contains(r#""message":"development: "#);
            assert_eq!(i.evaluation_key.is_none(), undeveloped, "{encoding} {i:?}");
        }
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn an_lsystem_run_reuses_the_evaluation_of_an_identical_creature_bit_for_bit() {
    let dir = scratch("cache-reuse");
    let run = dir.join("run");
    succeeded(&small_run("lsystem", &run, &[]));
    let all = stored_individuals(&run);
    let reused: Vec<_> = all.iter().filter(|i| i.reused).collect();
    assert!(!reused.is_empty(), "no individual was reused");
    for r in &reused {
        assert_ne!(r.operator, "elite");
        let first = all
            .iter()
            .find(|i| i.evaluation_key == r.evaluation_key && !i.reused)
            .expect("a reused individual's key was evaluated before");
        assert!((first.generation, first.index) < (r.generation, r.index));
        assert_eq!(first.fitness.to_bits(), r.fitness.to_bits());
        assert_eq!(
            (
                &first.status,
                &first.terms_json,
                first.parts,
                first.joints,
                first.neurons
            ),
            (&r.status, &r.terms_json, r.parts, r.joints, r.neurons)
        );
    }
    // The log counts them per generation: evaluations, of which simulated.
    let log = std::fs::read_to_string(run.join("log.txt")).unwrap();
    let store = RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    for (line, g) in log.lines().zip(store.generations().unwrap()) {
        let reused_here = reused.iter().filter(|i| i.generation == g.index).count() as u64;
        let counts = format!(
            "{} evaluations, {} simulated in",
            g.evaluations,
            g.evaluations - reused_here
        );
        assert!(line.contains(&counts), "{line} lacks {counts}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn evolve_optimises_the_fitness_its_flag_names_and_every_report_names_it() {
    let dir = scratch("fitness");
    let out = dir.join("run");
    let o = run_of("direct", &out, "2", &["--fitness", "hornby-pollack"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let label = "walker, hornby-pollack (m)";
    let end = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(
        end.contains(&format!("{label}: generation 1 best ")),
        "{end}"
    );
    let progress = String::from_utf8_lossy(&o.stderr).to_string();
    assert!(
        progress.contains(&format!("generation 1: {label}: best ")),
        "{progress}"
    );
    let config = std::fs::read_to_string(out.join("config.toml")).unwrap();
    assert!(config.contains("fitness = \"hornby-pollack\""), "{config}");
    let log = std::fs::read_to_string(out.join("log.txt")).unwrap();
    let generations: Vec<&str> = log
        .lines()
        .filter(|l| l.starts_with("generation "))
        .collect();
    assert_eq!(generations.len(), 2, "{log}");
    assert!(
        generations
            .iter()
            .all(|line| line.contains(&format!(": {label}: best "))),
        "{log}"
    );
    let show = ontogeny_command()
        .args(["runs", "show"])
        .arg(&out)
        .output()
        .unwrap();
    let shown = String::from_utf8_lossy(&show.stdout).to_string();
    assert!(
        shown.contains(&format!("direct encoding, {label}, seed 5")),
        "{shown}"
    );
    // Without the flag, the task's default formula, named as such.
    let default = dir.join("default");
    let o = run_of("direct", &default, "1", &[]);
    let end = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(
        end.contains("walker, normalised (Chaumont eq. 1): generation 0"),
        "{end}"
    );
    // A walker formula for another task is refused, and nothing is written.
    let jump = ontogeny_command()
        .args(["evolve", "--task", "jump", "--fitness", "distance", "--out"])
        .arg(dir.join("jump"))
        .output()
        .unwrap();
    refused(
        &jump,
        "--fitness \"distance\" is a formula of the walker task, not of the jump task",
    );
    assert!(!dir.join("jump").exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_version_2_database_is_migrated_to_the_current_version_on_resume() {
    let dir = scratch("version-2");
    let whole = dir.join("whole");
    succeeded(&small_run("lsystem", &whole, &[]));
    // The same run stopped after generation 1 by a version that knew schema 2: no reused
    // or evaluation_key columns, no cache setting in config.toml.
    let old = dir.join("old");
    succeeded(&small_run("lsystem", &old, &[]));
    let config = config_text(&old);
    std::fs::write(
        old.join("config.toml"),
        config.replace("cache = true\n", ""),
    )
    .unwrap();
    {
        let conn = rusqlite::Connection::open(old.join("run.sqlite")).unwrap();
        conn.execute_batch(crate::util::DROP_VERSION_4).unwrap();
        conn.execute_batch(
            "DELETE FROM individual WHERE generation >= 2;
             DELETE FROM generation WHERE generation >= 2;
             ALTER TABLE individual DROP COLUMN reused;
             ALTER TABLE individual DROP COLUMN evaluation_key;
             PRAGMA user_version = 2;
             PRAGMA wal_checkpoint(TRUNCATE);",
        )
        .unwrap();
    }
    succeeded(&resume_older_store(&old));
    let store = RunStore::open_read_only(&old.join("run.sqlite")).unwrap();
    assert_eq!(store.schema_version(), ontogeny::run::store::SCHEMA_VERSION);
    drop(store);
    // The old rows: evaluated, no key; the new ones keyed as in the uninterrupted run.
    let (migrated, fresh) = (stored_individuals(&old), stored_individuals(&whole));
    for (m, f) in migrated.iter().zip(&fresh) {
        if m.generation < 2 {
            assert!(!m.reused && m.evaluation_key.is_none(), "{m:?}");
        } else {
            assert_eq!(m.evaluation_key, f.evaluation_key);
        }
    }
    assert_eq!(
        contents_of(&old, true, CacheColumns::Neither),
        contents_of(&whole, true, CacheColumns::Neither)
    );
    let _ = std::fs::remove_dir_all(dir);
}
