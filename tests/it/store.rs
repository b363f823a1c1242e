//! The run store (`run.sqlite`) and the fitness plot: round trips, one transaction per
//! generation, refusals that leave files untouched, a version-1 file read as it is and
//! migrated when opened for writing, the run store reference's example queries.

mod integrity;
mod migration;
mod run_config;

use std::fs;
use std::path::{Path, PathBuf};

use ontogeny::run::plot::{FAILURE_FLOOR, FINE_LABEL, fitness_svg};
use ontogeny::run::store::{
    FineEvaluation, GenerationRecord, IndividualRecord, RunRecord, RunStore, SCHEMA_VERSION,
    StoreError,
};

use crate::util::scratch_dir;

/// A fresh, empty scratch directory of this module's, named after `name`.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("store-{name}"))
}

fn run_record() -> RunRecord {
    RunRecord {
        config: "[ga]\npopulation = 4\nseed = 18446744073709551615\n".into(),
        // The largest seed: above i64::MAX, which SQLite integers cannot hold.
        seed: u64::MAX,
        encoding: "lsystem".into(),
        task: "walker".into(),
        version: "0.1.0".into(),
    }
}

fn generation(index: u32) -> GenerationRecord {
    GenerationRecord {
        index,
        best: 12.5 + index as f64,
        mean: 3.25,
        median: 2.0,
        sd: 1.5,
        valid_fraction: 0.75,
        evaluations: 4,
        reused: 0,
        wall_seconds: 0.5,
        evaluations_per_second: 8.0,
        best_fine: None,
    }
}

fn fine(fitness: f64, status: &str) -> Option<FineEvaluation> {
    Some(FineEvaluation {
        fitness,
        status: status.into(),
    })
}

/// Four individuals: `fitness[i]` each; individual 3 failed.
fn individuals(generation: u32, fitness: [f64; 4]) -> Vec<IndividualRecord> {
    (0..4)
        .map(|i| IndividualRecord {
            generation,
            index: i,
            parents: match i {
                0 => vec![],
                1 => vec![3],
                _ => vec![1, 2],
            },
            operator: ["random", "mutation", "crossover", "crossover"][i as usize].into(),
            genome_text: format!("axiom: A({i})\nproductions:\n  A(x) -> [+F] A(x + 1) # \"é\"\n"),
            genome_json: format!("{{\"rules\":[{i}],\"text\":\"a\\\"b\"}}"),
            fitness: fitness[i as usize],
            status: if i == 3 { "failed: exploded" } else { "ok" }.into(),
            terms_json: format!("{{\"distance\":{}.5,\"energy\":-0.25}}", i),
            parts: 3 + i,
            joints: 2 + i,
            neurons: 10 * i,
            reused: false,
            evaluation_key: None,
            parents_generation: None,
        })
        .collect()
}

/// Equality that treats NaN as equal to NaN.
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn same_generation(a: &GenerationRecord, b: &GenerationRecord) -> bool {
    a.index == b.index
        && same(a.best, b.best)
        && same(a.mean, b.mean)
        && same(a.median, b.median)
        && same(a.sd, b.sd)
        && same(a.valid_fraction, b.valid_fraction)
        && a.evaluations == b.evaluations
        && same(a.wall_seconds, b.wall_seconds)
        && same(a.evaluations_per_second, b.evaluations_per_second)
        && match (&a.best_fine, &b.best_fine) {
            (None, None) => true,
            (Some(x), Some(y)) => same(x.fitness, y.fitness) && x.status == y.status,
            _ => false,
        }
}

/// A store with generations 0 and 1 written, closed again.
fn finished_store(dir: &Path) -> PathBuf {
    let path = dir.join("run.sqlite");
    let mut store = RunStore::create(&path, &run_record()).unwrap();
    store
        .write_generation(
            &generation(0),
            &individuals(0, [1.0, 2.0, 0.5, FAILURE_FLOOR]),
        )
        .unwrap();
    store
        .write_generation(
            &generation(1),
            &individuals(1, [4.0, 2.0, 3.0, FAILURE_FLOOR]),
        )
        .unwrap();
    path
}

#[test]
fn every_field_round_trips() {
    let dir = scratch("round-trip");
    let path = dir.join("run.sqlite");
    let mut store = RunStore::create(&path, &run_record()).unwrap();
    assert_eq!(store.last_generation().unwrap(), None);
    assert_eq!(store.best_individual().unwrap(), None);
    assert!(store.generations().unwrap().is_empty());

    // Generation 0: no valid individual, so its statistics are NaN; every fitness is the floor.
    let g0 = GenerationRecord {
        index: 0,
        best: FAILURE_FLOOR,
        mean: f64::NAN,
        median: f64::NAN,
        sd: f64::NAN,
        valid_fraction: 0.0,
        evaluations: 4,
        reused: 0,
        wall_seconds: 0.0,
        evaluations_per_second: f64::INFINITY,
        // Verified, but the fine evaluation gave no number: NULL fitness, a status.
        best_fine: fine(f64::NAN, "invalid"),
    };
    let i0 = individuals(0, [FAILURE_FLOOR; 4]);
    store.write_generation(&g0, &i0).unwrap();
    let g1 = GenerationRecord {
        best_fine: fine(0.1 + 0.2, "ok"),
        ..generation(1)
    };
    let i1 = individuals(1, [0.1 + 0.2, -3.0e-300, 7.0, FAILURE_FLOOR]);
    store.write_generation(&g1, &i1).unwrap();
    drop(store);

    let store = RunStore::open(&path).unwrap();
    assert_eq!(store.run().unwrap(), run_record());
    assert_eq!(store.last_generation().unwrap(), Some(1));
    let gs = store.generations().unwrap();
    assert_eq!(gs.len(), 2);
    assert!(same_generation(&gs[0], &g0), "{:?}", gs[0]);
    assert!(same_generation(&gs[1], &g1), "{:?}", gs[1]);
    assert!(gs[0].best_fine.as_ref().unwrap().fitness.is_nan());
    assert_eq!(gs[1].best_fine.as_ref().unwrap().fitness, 0.1 + 0.2);
    assert_eq!(store.individuals(0).unwrap(), i0);
    // Every bit of the fitness survives (0.1 + 0.2 is not 0.3).
    assert_eq!(store.individuals(1).unwrap(), i1);
    assert!(store.individuals(2).unwrap().is_empty());
    // The fittest of the run: generation 1's individual 2 (7.0).
    let best = store.best_individual().unwrap().unwrap();
    assert_eq!((best.generation, best.index, best.fitness), (1, 2, 7.0));
}

#[test]
fn the_file_is_in_wal_mode_with_the_schema_version() {
    let dir = scratch("pragmas");
    let path = finished_store(&dir);
    let conn = rusqlite::Connection::open(&path).unwrap();
    let mode: String = conn
        .query_row("PRAGMA journal_mode", [], |r| r.get(0))
        .unwrap();
    assert_eq!(mode, "wal");
    let version: i64 = conn
        .query_row("PRAGMA user_version", [], |r| r.get(0))
        .unwrap();
    assert_eq!(version, SCHEMA_VERSION);
    // The failure floor is stored as a REAL like any fitness.
    let (kind, value): (String, f64) = conn
        .query_row(
            "SELECT typeof(fitness), fitness FROM individual WHERE generation = 0 AND individual = 3",
            [],
            |r| Ok((r.get(0)?, r.get(1)?)),
        )
        .unwrap();
    assert_eq!((kind.as_str(), value), ("real", -999_999.0));
}

/// Asserts generation 1 is absent, on the open store and on disk.
fn assert_only_generation_0(store: &RunStore, path: &Path) {
    assert_eq!(store.last_generation().unwrap(), Some(0));
    assert_eq!(store.generations().unwrap().len(), 1);
    assert!(store.individuals(1).unwrap().is_empty());
    let conn = rusqlite::Connection::open(path).unwrap();
    let rows: i64 = conn
        .query_row(
            "SELECT (SELECT count(*) FROM generation WHERE generation = 1) + \
                    (SELECT count(*) FROM individual WHERE generation = 1)",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert_eq!(rows, 0);
}

#[test]
fn a_generation_is_stored_whole_or_not_at_all() {
    let dir = scratch("transaction");
    let path = dir.join("run.sqlite");
    let mut store = RunStore::create(&path, &run_record()).unwrap();
    store
        .write_generation(&generation(0), &individuals(0, [1.0; 4]))
        .unwrap();

    // Individual 2's terms are not JSON: the generation row and individuals 0 and 1 were
    // already inserted when the database refuses it, and must be rolled back.
    let mut bad = individuals(1, [1.0; 4]);
    bad[2].terms_json = "{distance: 1".into();
    let err = store.write_generation(&generation(1), &bad).unwrap_err();
    let message = err.to_string();
    assert!(
        matches!(err, StoreError::InvalidRecord { generation: 1, .. }),
        "{err:?}"
    );
    assert!(message.contains("individual 2"), "{message}");
    assert!(message.contains("nothing of it was stored"), "{message}");
    assert!(message.contains("run.sqlite"), "{message}");
    assert_only_generation_0(&store, &path);

    // Two individuals with index 3: the primary key refuses the second, after three inserts.
    let mut twice = individuals(1, [1.0; 4]);
    twice[3].index = 1;
    let err = store.write_generation(&generation(1), &twice).unwrap_err();
    assert!(err.to_string().contains("individual 1"), "{err}");
    assert_only_generation_0(&store, &path);

    // The failed attempts left nothing in the way: the corrected generation goes in.
    store
        .write_generation(&generation(1), &individuals(1, [1.0; 4]))
        .unwrap();
    assert_eq!(store.last_generation().unwrap(), Some(1));
    assert_eq!(store.individuals(1).unwrap().len(), 4);
}

#[test]
fn write_generation_refuses_mismatched_or_repeated_generations() {
    let dir = scratch("refuse-write");
    let path = finished_store(&dir);
    let mut store = RunStore::open(&path).unwrap();
    // An individual labelled with another generation.
    let err = store
        .write_generation(&generation(2), &individuals(1, [1.0; 4]))
        .unwrap_err();
    assert!(
        err.to_string()
            .contains("individual 0 says it belongs to generation 1"),
        "{err}"
    );
    // A generation already stored.
    let err = store
        .write_generation(&generation(1), &individuals(1, [1.0; 4]))
        .unwrap_err();
    assert!(
        err.to_string()
            .contains("already holds generations up to 1"),
        "{err}"
    );
    assert_eq!(store.last_generation().unwrap(), Some(1));
    assert_eq!(store.individuals(1).unwrap()[0].fitness, 4.0);
}

#[test]
fn create_refuses_an_existing_path() {
    let dir = scratch("exists");
    let path = dir.join("run.sqlite");
    fs::write(&path, "precious").unwrap();
    let err = RunStore::create(&path, &run_record()).unwrap_err();
    assert!(matches!(err, StoreError::Exists { .. }), "{err:?}");
    assert!(err.to_string().contains("already exists"), "{err}");
    assert_eq!(fs::read(&path).unwrap(), b"precious");

    // Nor may a second run be created over a real store.
    let store_path = finished_store(&scratch("exists-store"));
    let before = fs::read(&store_path).unwrap();
    assert!(matches!(
        RunStore::create(&store_path, &run_record()),
        Err(StoreError::Exists { .. })
    ));
    assert_eq!(fs::read(&store_path).unwrap(), before);
    assert_eq!(
        RunStore::open(&store_path)
            .unwrap()
            .last_generation()
            .unwrap(),
        Some(1)
    );
}

/// Opens `path`, expecting an error, and checks the file is byte-identical afterwards and
/// no side file was left beside it.
fn open_rejects(path: &Path) -> StoreError {
    let before = fs::read(path).unwrap();
    let siblings = |p: &Path| {
        let mut names: Vec<_> = fs::read_dir(p.parent().unwrap())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        names.sort();
        names
    };
    let files = siblings(path);
    let err = RunStore::open(path).unwrap_err();
    assert_eq!(
        fs::read(path).unwrap(),
        before,
        "open modified a file it rejected"
    );
    assert_eq!(
        siblings(path),
        files,
        "open left files beside one it rejected"
    );
    let message = err.to_string();
    assert!(
        message.contains(&path.display().to_string()),
        "the message does not name the file: {message}"
    );
    err
}

#[test]
fn open_refuses_a_file_that_is_not_a_database() {
    let dir = scratch("not-db");
    let path = dir.join("run.sqlite");
    fs::write(&path, "[ga]\npopulation = 100\n".repeat(200)).unwrap();
    let err = open_rejects(&path);
    assert_eq!(
        err.to_string(),
        format!(
            "{} is not a run database (file is not a database)",
            path.display()
        )
    );

    fs::write(&path, "").unwrap();
    let err = open_rejects(&path);
    assert!(
        err.to_string()
            .ends_with("is not a run database (the file is empty)"),
        "{err}"
    );

    let missing = dir.join("nowhere.sqlite");
    let err = RunStore::open(&missing).unwrap_err();
    assert!(matches!(err, StoreError::Missing { .. }), "{err:?}");
    assert!(!missing.exists());
}

#[test]
fn open_refuses_a_truncated_store() {
    let dir = scratch("truncated");
    // Big genomes so the database spans many pages.
    let path = dir.join("run.sqlite");
    let mut store = RunStore::create(&path, &run_record()).unwrap();
    for g in 0..5 {
        let mut is = individuals(g, [1.0; 4]);
        for i in &mut is {
            i.genome_text = format!("{} {}", i.genome_text, "F ".repeat(3000));
        }
        store.write_generation(&generation(g), &is).unwrap();
    }
    drop(store); // checkpoints the WAL into the file
    let full = fs::read(&path).unwrap();
    assert!(full.len() >= 16 * 4096, "only {} bytes", full.len());

    for (name, keep) in [("half", full.len() / 2), ("header", 60)] {
        let cut = dir.join(format!("{name}.sqlite"));
        fs::write(&cut, &full[..keep]).unwrap();
        let err = open_rejects(&cut);
        assert!(matches!(err, StoreError::Corrupt { .. }), "{name}: {err:?}");
        assert!(err.to_string().contains(" is corrupt: "), "{err}");
        if name == "half" {
            assert!(
                err.to_string().contains(&format!(
                    "the file is truncated ({keep} bytes where its header says {})",
                    full.len()
                )),
                "{err}"
            );
        }
    }
}

#[test]
fn open_refuses_another_schema() {
    let dir = scratch("schema");
    // Somebody else's database.
    let other = dir.join("other.sqlite");
    {
        let conn = rusqlite::Connection::open(&other).unwrap();
        conn.execute_batch(
            "CREATE TABLE run (id INTEGER, name TEXT); INSERT INTO run VALUES (1, 'x');",
        )
        .unwrap();
    }
    let err = open_rejects(&other);
    assert!(matches!(err, StoreError::NotARunStore { .. }), "{err:?}");
    assert!(err.to_string().contains("not one ontogeny wrote"), "{err}");

    // A run store from a future version of ontogeny.
    let newer = finished_store(&dir);
    {
        let conn = rusqlite::Connection::open(&newer).unwrap();
        conn.pragma_update(None, "user_version", SCHEMA_VERSION + 1)
            .unwrap();
    }
    let err = open_rejects(&newer);
    assert!(matches!(err, StoreError::NewerSchema { .. }), "{err:?}");
    assert!(
        err.to_string().contains(&format!(
            "was written by a newer schema (version {})",
            SCHEMA_VERSION + 1
        )),
        "{err}"
    );

    // Our marks on a table of another shape.
    let reshaped = dir.join("reshaped.sqlite");
    {
        let newer_store = dir.join("run.sqlite");
        fs::copy(&newer_store, &reshaped).unwrap();
        let conn = rusqlite::Connection::open(&reshaped).unwrap();
        conn.pragma_update(None, "user_version", SCHEMA_VERSION)
            .unwrap();
        conn.execute_batch("ALTER TABLE individual DROP COLUMN neurons")
            .unwrap();
        conn.execute_batch("PRAGMA wal_checkpoint(TRUNCATE)")
            .unwrap();
    }
    let err = open_rejects(&reshaped);
    assert!(
        err.to_string()
            .ends_with("is not a run database (its individual table lacks the column neurons)"),
        "{err}"
    );
}

/// The run store reference's example queries, which must appear in it word for word.
const BEST_PER_GENERATION: &str = "SELECT generation, individual, max(fitness) AS fitness, parts
FROM individual GROUP BY generation ORDER BY generation;";
const VALID_PER_OPERATOR: &str = "SELECT operator, count(*) AS individuals,
       round(avg(status = 'ok'), 3) AS valid_fraction
FROM individual GROUP BY operator ORDER BY operator;";
const PARENTS_OF: &str =
    "SELECT parent.generation, parent.individual, parent.operator, parent.fitness
FROM individual AS child, json_each(child.parents) AS p
JOIN individual AS parent
  ON parent.generation = child.parents_generation AND parent.individual = p.value
WHERE child.generation = 3 AND child.individual = 0;";

#[test]
fn the_run_store_reference_s_queries_work() {
    let readme = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/docs/reference/run-store.md"
    ))
    .unwrap();
    assert!(readme.contains(BEST_PER_GENERATION));
    assert!(readme.contains(VALID_PER_OPERATOR));
    assert!(readme.contains(PARENTS_OF));
    let path = finished_store(&scratch("readme"));
    let conn = rusqlite::Connection::open(&path).unwrap();

    let best: Vec<(u32, u32, f64, u32)> = conn
        .prepare(BEST_PER_GENERATION)
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?)))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    // Generation 0's fitness is [1, 2, 0.5, floor]: individual 1 (4 parts); generation 1's is
    // [4, 2, 3, floor]: individual 0 (3 parts).
    assert_eq!(best, vec![(0, 1, 2.0, 4), (1, 0, 4.0, 3)]);

    let valid: Vec<(String, u32, f64)> = conn
        .prepare(VALID_PER_OPERATOR)
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    // Per generation: individuals 2 and 3 are crossovers, 3 failed; 0 random, 1 mutation.
    assert_eq!(
        valid,
        vec![
            ("crossover".into(), 4, 0.5),
            ("mutation".into(), 2, 1.0),
            ("random".into(), 2, 1.0)
        ]
    );

    // Individual 0 of generation 3, a crossover of individuals 1 and 2 of generation 1 (bred
    // two generations back, as a steady-state birth may be).
    drop(conn);
    let mut store = RunStore::open(&path).unwrap();
    store
        .write_generation(&generation(2), &individuals(2, [1.0; 4]))
        .unwrap();
    let mut is = individuals(3, [1.0; 4]);
    is[0].parents = vec![1, 2];
    is[0].operator = "crossover".into();
    is[0].parents_generation = Some(1);
    store.write_generation(&generation(3), &is).unwrap();
    drop(store);
    let conn = rusqlite::Connection::open(&path).unwrap();
    let parents: Vec<(u32, u32, String, f64)> = conn
        .prepare(PARENTS_OF)
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?)))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    // Generation 1's fitness is [4, 2, 3, floor], its operators random, mutation, crossover.
    assert_eq!(
        parents,
        vec![
            (1, 1, "mutation".into(), 2.0),
            (1, 2, "crossover".into(), 3.0)
        ]
    );
}

#[test]
fn the_fitness_plot_names_its_series_and_axes() {
    let dir = scratch("plot");
    let path = dir.join("fitness.svg");
    let mut gs: Vec<GenerationRecord> = (0..30)
        .map(|g| {
            let x = g as f64;
            GenerationRecord {
                best: 10.0 + 3.0 * x.sqrt(),
                mean: 4.0 + 2.0 * x.sqrt(),
                median: 3.5 + 2.1 * x.sqrt(),
                ..generation(g)
            }
        })
        .collect();
    // A generation with no valid individual: must not crush the axis.
    gs[5].best = FAILURE_FLOOR;
    gs[5].mean = f64::NAN;
    gs[5].median = f64::NAN;
    fitness_svg(&path, &gs, "walker & lsystem", "fitness: distance (m)").unwrap();
    let svg = fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(80)]);
    // plotters writes each text on a line of its own.
    let texts: Vec<&str> = svg.lines().map(str::trim).collect();
    for text in [
        "best",
        "mean",
        "median",
        "generation",
        "fitness: distance (m)",
    ] {
        assert!(texts.contains(&text), "no text {text} in the SVG");
    }
    assert!(svg.contains("walker &amp; lsystem"));
    // The y axis is labelled from about 3 to 27, not down to -999999.
    assert!(!svg.contains("999999") && !svg.contains("-1000000"));
    assert!(!dir.join("fitness.svg.tmp").exists());

    // Nothing was re-walked at the fine reference: no dashed line, no legend for it.
    assert!(!svg.contains(FINE_LABEL));
    // Generations 10 to 29 re-walked: a dashed line and its legend entry; its values, down
    // to -20, stretch the y axis.
    for (k, g) in gs.iter_mut().enumerate().skip(10) {
        g.best_fine = fine(-(k as f64) + 9.0, "ok");
    }
    fitness_svg(&path, &gs, "fine", "fitness").unwrap();
    let with_fine = fs::read_to_string(&path).unwrap();
    let texts: Vec<&str> = with_fine.lines().map(str::trim).collect();
    assert!(
        texts.contains(&FINE_LABEL),
        "no text {FINE_LABEL} in the SVG"
    );
    assert!(
        texts.contains(&"-20.0"),
        "the y axis does not reach the fine values"
    );
    // Dashes: many more line pieces than the solid plot has.
    let paths = |s: &str| s.matches("<polyline").count();
    assert!(
        paths(&with_fine) > paths(&svg) + 20,
        "{} pieces against {}",
        paths(&with_fine),
        paths(&svg)
    );

    // No generation yet, or none with a valid individual: still a picture, not an error.
    fitness_svg(&path, &[], "empty", "fitness").unwrap();
    assert!(fs::read_to_string(&path).unwrap().contains("\nmedian\n"));
    let failed = GenerationRecord {
        best: FAILURE_FLOOR,
        mean: f64::NAN,
        median: f64::NAN,
        ..generation(0)
    };
    fitness_svg(&path, &[failed], "failed", "fitness").unwrap();

    // An unwritable place is an error naming the file.
    let err = fitness_svg(&dir.join("no/such/dir/fitness.svg"), &gs, "x", "y").unwrap_err();
    assert!(err.to_string().contains("fitness.svg"), "{err}");
}

/// The environment variable that turns [`kill_9_keeps_every_committed_generation`], run
/// again in a child process, into the writer it kills: the store's path.
const CHILD_STORE: &str = "ONTOGENY_STORE_CHILD";

/// The child of [`kill_9_keeps_every_committed_generation`]: resumes the store at `path` (or
/// creates it) and writes generations of 50 individuals for ever, printing `committed N`
/// after each.
fn write_generations_for_ever(path: &Path) -> ! {
    use std::io::Write;
    let mut store = if path.exists() {
        RunStore::open(path).unwrap()
    } else {
        RunStore::create(path, &run_record()).unwrap()
    };
    let mut g = store.last_generation().unwrap().map_or(0, |last| last + 1);
    loop {
        let is: Vec<IndividualRecord> = (0..50)
            .map(|i| IndividualRecord {
                index: i,
                genome_text: "F ".repeat(500),
                fitness: f64::from(g) + f64::from(i) / 100.0,
                ..individuals(g, [0.0; 4])[0].clone()
            })
            .collect();
        store.write_generation(&generation(g), &is).unwrap();
        println!("committed {g}");
        std::io::stdout().flush().unwrap();
        g += 1;
    }
}

#[test]
fn kill_9_keeps_every_committed_generation() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    // Run again as the child (below), this test is the writer that is killed.
    if let Some(path) = std::env::var_os(CHILD_STORE) {
        write_generations_for_ever(Path::new(&path));
    }
    let path = scratch("kill").join("run.sqlite");
    let mut seen = 0;
    // Three lives: each child resumes the store its killed predecessor left.
    for life in 0..3 {
        let mut child = Command::new(std::env::current_exe().unwrap())
            .args([
                "--exact",
                "store::kill_9_keeps_every_committed_generation",
                "--nocapture",
                "--test-threads=1",
            ])
            .env(CHILD_STORE, &path)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
        let mut committed_this_life = 0;
        while committed_this_life < 10 {
            let line = lines
                .next()
                .expect("the child stopped before committing 10 generations")
                .unwrap();
            if let Some(n) = line.strip_prefix("committed ") {
                seen = n.parse().unwrap();
                committed_this_life += 1;
            }
        }
        // SIGKILL, while the child is most likely inside its next transaction.
        child.kill().unwrap();
        child.wait().unwrap();

        let store = RunStore::open(&path).unwrap();
        let last = store.last_generation().unwrap().unwrap();
        assert!(
            last >= seen,
            "life {life}: generation {seen} was committed, last is {last}"
        );
        assert!(last >= 10 * life + 9);
        let gs = store.generations().unwrap();
        assert_eq!(gs.len() as u32, last + 1, "a generation is missing");
        for g in 0..=last {
            let is = store.individuals(g).unwrap();
            assert_eq!(is.len(), 50, "generation {g} is incomplete");
            assert_eq!(is[49].fitness, f64::from(g) + 0.49);
        }
    }
}
