//! Older run stores: version 1, 2, 3 and 4 files read as they are and migrated when opened
//! for writing (their records checksummed as they are; a version-4 file's checksums kept),
//! a migration that fails part-way leaving the file as it was, a schema older than version 1
//! refused, and the cache's and the lineage's columns read back.

use super::*;

/// The schema of version 1, as ontogeny 0.1 created it: the `generation` table without the
/// fine reference columns.
const SCHEMA_V1: &str = "
CREATE TABLE run (
    id       INTEGER PRIMARY KEY CHECK (id = 1),
    config   TEXT NOT NULL,
    seed     TEXT NOT NULL CHECK (seed GLOB '[0-9]*' AND seed NOT GLOB '*[^0-9]*'),
    encoding TEXT NOT NULL,
    task     TEXT NOT NULL,
    version  TEXT NOT NULL
) STRICT;
CREATE TABLE generation (
    generation             INTEGER PRIMARY KEY CHECK (generation >= 0),
    best                   REAL,
    mean                   REAL,
    median                 REAL,
    sd                     REAL,
    valid_fraction         REAL,
    evaluations            INTEGER NOT NULL CHECK (evaluations >= 0),
    wall_seconds           REAL,
    evaluations_per_second REAL
) STRICT;
CREATE TABLE individual (
    generation  INTEGER NOT NULL REFERENCES generation (generation),
    individual  INTEGER NOT NULL CHECK (individual >= 0),
    parents     TEXT NOT NULL CHECK (json_valid(parents) AND json_type(parents) = 'array'),
    operator    TEXT NOT NULL,
    genome_text TEXT NOT NULL,
    genome_json TEXT NOT NULL CHECK (json_valid(genome_json)),
    fitness     REAL,
    status      TEXT NOT NULL,
    terms_json  TEXT NOT NULL CHECK (json_valid(terms_json)),
    parts       INTEGER NOT NULL CHECK (parts >= 0),
    joints      INTEGER NOT NULL CHECK (joints >= 0),
    neurons     INTEGER NOT NULL CHECK (neurons >= 0),
    PRIMARY KEY (generation, individual)
) STRICT;
";

/// A version-1 store at `path` holding the run record and generations 0 and 1 of
/// [`finished_store`], written with SQL as ontogeny 0.1 did (a rollback journal: no WAL).
fn version_1_store(path: &Path) {
    let conn = rusqlite::Connection::open(path).unwrap();
    conn.pragma_update(None, "application_id", 0x4F6E_746F_i64)
        .unwrap();
    conn.pragma_update(None, "user_version", 1).unwrap();
    conn.execute_batch(SCHEMA_V1).unwrap();
    let run = run_record();
    conn.execute(
        "INSERT INTO run VALUES (1, ?1, ?2, ?3, ?4, ?5)",
        rusqlite::params![
            run.config,
            run.seed.to_string(),
            run.encoding,
            run.task,
            run.version
        ],
    )
    .unwrap();
    for (g, fitness) in [
        (0, [1.0, 2.0, 0.5, FAILURE_FLOOR]),
        (1, [4.0, 2.0, 3.0, 1.0]),
    ] {
        let r = generation(g);
        conn.execute(
            "INSERT INTO generation VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)",
            rusqlite::params![
                r.index,
                r.best,
                r.mean,
                r.median,
                r.sd,
                r.valid_fraction,
                r.evaluations as i64,
                r.wall_seconds,
                r.evaluations_per_second
            ],
        )
        .unwrap();
        for i in individuals(g, fitness) {
            conn.execute(
                "INSERT INTO individual VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)",
                rusqlite::params![
                    i.generation,
                    i.index,
                    serde_json::to_string(&i.parents).unwrap(),
                    i.operator,
                    i.genome_text,
                    i.genome_json,
                    i.fitness,
                    i.status,
                    i.terms_json,
                    i.parts,
                    i.joints,
                    i.neurons
                ],
            )
            .unwrap();
        }
    }
}

/// Everything a store holds, fine reference columns aside, for before/after comparisons.
fn held(store: &RunStore) -> (RunRecord, Vec<GenerationRecord>, Vec<Vec<IndividualRecord>>) {
    let generations = store.generations().unwrap();
    let individuals = generations
        .iter()
        .map(|g| store.individuals(g.index).unwrap())
        .collect();
    (store.run().unwrap(), generations, individuals)
}

#[test]
fn a_version_1_store_is_read_as_it_is_and_migrated_when_opened_for_writing() {
    let dir = scratch("version-1");
    let path = dir.join("run.sqlite");
    version_1_store(&path);
    let before = fs::read(&path).unwrap();

    // Read-only: read whole, nothing verified, the file not touched.
    let store = RunStore::open_read_only(&path).unwrap();
    assert_eq!(store.schema_version(), 1);
    let (run, generations, individuals_v1) = held(&store);
    assert_eq!(run, run_record());
    assert_eq!(generations.len(), 2);
    for (g, r) in generations.iter().enumerate() {
        assert!(same_generation(r, &generation(g as u32)), "{r:?}");
        assert_eq!(r.best_fine, None);
    }
    assert_eq!(
        individuals_v1[1],
        individuals(1, [4.0, 2.0, 3.0, 1.0]),
        "individuals read back"
    );
    assert_eq!(store.best_individual().unwrap().unwrap().fitness, 4.0);
    drop(store);
    assert_eq!(
        fs::read(&path).unwrap(),
        before,
        "a read-only open changed it"
    );
    let mut store = RunStore::open_read_only(&path).unwrap();
    assert!(
        store
            .write_generation(&generation(2), &individuals(2, [1.0; 4]))
            .is_err(),
        "a read-only store took a write"
    );
    drop(store);
    assert_eq!(fs::read(&path).unwrap(), before);

    // For writing: migrated to the current version, everything kept, old generations NULL.
    let mut store = RunStore::open(&path).unwrap();
    assert_eq!(store.schema_version(), SCHEMA_VERSION);
    let (run, migrated, individuals_v2) = held(&store);
    assert_eq!(run, run_record());
    assert_eq!(individuals_v2, individuals_v1);
    assert_eq!(migrated.len(), 2);
    for (a, b) in migrated.iter().zip(&generations) {
        assert!(same_generation(a, b), "{a:?}");
    }
    // The next generation stores its fine reference value beside the old ones' NULLs.
    let g2 = GenerationRecord {
        best_fine: fine(1.25, "ok"),
        ..generation(2)
    };
    store
        .write_generation(&g2, &individuals(2, [1.0; 4]))
        .unwrap();
    drop(store);
    let conn = rusqlite::Connection::open(&path).unwrap();
    let version: i64 = conn
        .query_row("PRAGMA user_version", [], |r| r.get(0))
        .unwrap();
    assert_eq!(version, SCHEMA_VERSION);
    let fine_rows: Vec<(u32, Option<f64>, Option<String>)> = conn
        .prepare("SELECT generation, best_fine, best_fine_status FROM generation ORDER BY 1")
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(
        fine_rows,
        vec![
            (0, None, None),
            (1, None, None),
            (2, Some(1.25), Some("ok".into()))
        ]
    );
    drop(conn);
    // Opening the migrated file again changes nothing more; read-only sees version 2.
    let store = RunStore::open_read_only(&path).unwrap();
    assert_eq!(store.schema_version(), SCHEMA_VERSION);
    let gs = store.generations().unwrap();
    assert_eq!(gs[2].best_fine, fine(1.25, "ok"));
    assert_eq!(gs[0].best_fine, None);
}

#[test]
fn a_schema_older_than_version_1_is_refused() {
    let dir = scratch("version-0");
    let path = dir.join("run.sqlite");
    version_1_store(&path);
    {
        let conn = rusqlite::Connection::open(&path).unwrap();
        conn.pragma_update(None, "user_version", 0).unwrap();
    }
    let err = open_rejects(&path);
    assert!(
        matches!(err, StoreError::OlderSchema { found: 0, .. }),
        "{err:?}"
    );
    assert!(matches!(
        RunStore::open_read_only(&path),
        Err(StoreError::OlderSchema { .. })
    ));
}

#[test]
fn reused_flags_and_evaluation_keys_read_back_as_written() {
    let dir = scratch("keys");
    let path = dir.join("run.sqlite");
    let mut store = RunStore::create(&path, &run_record()).unwrap();
    let mut is = individuals(0, [1.0, 2.0, 2.0, FAILURE_FLOOR]);
    let key = "0123456789abcdef".repeat(4);
    is[1].evaluation_key = Some(key.clone());
    is[2].evaluation_key = Some(key.clone());
    is[2].reused = true;
    store.write_generation(&generation(0), &is).unwrap();
    assert_eq!(store.individuals(0).unwrap(), is);
    assert_eq!(
        store.evaluations_by_key().unwrap(),
        vec![(key.clone(), is[1].genome_json.clone())],
        "the reused individual is not an evaluation"
    );
    assert_eq!(store.reused_by_generation().unwrap(), vec![(0, 1)]);
    // A key that is not 64 characters breaks the schema: nothing of the generation is stored.
    let mut bad = individuals(1, [1.0; 4]);
    bad[0].evaluation_key = Some("abc".into());
    assert!(matches!(
        store.write_generation(&generation(1), &bad),
        Err(StoreError::InvalidRecord { .. })
    ));
    assert_eq!(store.last_generation().unwrap(), Some(0));
}

#[test]
fn a_version_2_store_is_read_as_it_is_and_migrated_to_the_current_version_when_opened_for_writing()
{
    let dir = scratch("version-2");
    let path = dir.join("run.sqlite");
    version_1_store(&path);
    // Version 2: version 1 with the fine reference columns.
    RunStore::open(&path).unwrap();
    {
        let conn = rusqlite::Connection::open(&path).unwrap();
        conn.execute_batch(&format!(
            "{}
             ALTER TABLE individual DROP COLUMN reused;
             ALTER TABLE individual DROP COLUMN evaluation_key;
             PRAGMA user_version = 2;
             PRAGMA wal_checkpoint(TRUNCATE);",
            crate::util::DROP_VERSION_4
        ))
        .unwrap();
    }
    let before = fs::read(&path).unwrap();
    let store = RunStore::open_read_only(&path).unwrap();
    assert_eq!(store.schema_version(), 2);
    let (_, _, old) = held(&store);
    assert_eq!(old[1], individuals(1, [4.0, 2.0, 3.0, 1.0]));
    assert_eq!(store.reused_by_generation().unwrap(), vec![]);
    assert_eq!(store.evaluations_by_key().unwrap(), vec![]);
    drop(store);
    assert_eq!(
        fs::read(&path).unwrap(),
        before,
        "a read-only open changed it"
    );
    // Migrated: old rows were all evaluated and have no key; new rows keep theirs.
    let mut store = RunStore::open(&path).unwrap();
    assert_eq!(store.schema_version(), SCHEMA_VERSION);
    let (_, _, migrated) = held(&store);
    assert_eq!(migrated, old);
    let mut new = individuals(2, [1.0; 4]);
    new[0].evaluation_key = Some("ab".repeat(32));
    new[1].evaluation_key = Some("ab".repeat(32));
    new[1].reused = true;
    store.write_generation(&generation(2), &new).unwrap();
    assert_eq!(store.individuals(2).unwrap(), new);
    assert_eq!(store.reused_by_generation().unwrap(), vec![(2, 1)]);
}

/// A store of generations 0 and 1 ([`finished_store`]) taken back to schema version 3.
fn version_3_store(dir: &Path) -> PathBuf {
    let path = finished_store(dir);
    let conn = rusqlite::Connection::open(&path).unwrap();
    conn.execute_batch(crate::util::DROP_VERSION_4).unwrap();
    conn.execute_batch("PRAGMA user_version = 3; PRAGMA wal_checkpoint(TRUNCATE);")
        .unwrap();
    path
}

#[test]
fn a_version_3_store_is_checksummed_as_it_is_when_migrated_and_its_damage_is_then_refused() {
    let dir = scratch("version-3");
    let path = version_3_store(&dir);
    let store = RunStore::open_read_only(&path).unwrap();
    assert_eq!(store.schema_version(), 3);
    let before = held(&store);
    assert_eq!(store.evaluators().unwrap(), [(0, 1), (1, 1)]);
    drop(store);
    let store = RunStore::open(&path).unwrap();
    assert_eq!(store.schema_version(), SCHEMA_VERSION);
    assert_eq!(held(&store), before);
    assert_eq!(store.evaluators().unwrap(), [(0, 1), (1, 1)]);
    store.verify().unwrap();
    drop(store);
    // Its records now carry checksums: a fitness changed behind the store's back is refused.
    rusqlite::Connection::open(&path)
        .unwrap()
        .execute_batch(
            "UPDATE individual SET fitness = 5.0 WHERE generation = 1 AND individual = 2",
        )
        .unwrap();
    let err = RunStore::open_read_only(&path)
        .unwrap()
        .individuals(1)
        .unwrap_err();
    assert!(
        err.to_string()
            .contains("the record of individual 2 of generation 1 is damaged"),
        "{err}"
    );
}

#[test]
fn a_migration_that_fails_part_way_leaves_the_store_as_it_was() {
    let dir = scratch("migration-fails");
    let path = version_3_store(&dir);
    // The last step, checksumming the individuals, fails after the columns were added and
    // the generations checksummed.
    rusqlite::Connection::open(&path)
        .unwrap()
        .execute_batch(
            "CREATE TRIGGER refuse BEFORE UPDATE OF checksum ON individual
             BEGIN SELECT RAISE(ABORT, 'the disk is gone'); END;",
        )
        .unwrap();
    let before = fs::read(&path).unwrap();
    let err = RunStore::open(&path).unwrap_err();
    let message = err.to_string();
    assert!(
        message.contains(
            "cannot migrate the schema from version 3 to 5 (nothing was changed): the disk is gone"
        ),
        "{message}"
    );
    // Ontogeny's own failure, not the input's: the command line exits with 1.
    assert!(!err.is_bad_input());
    assert_eq!(fs::read(&path).unwrap(), before);
    let store = RunStore::open_read_only(&path).unwrap();
    assert_eq!(store.schema_version(), 3);
    drop(store);
    // Without the obstacle, the same file migrates.
    rusqlite::Connection::open(&path)
        .unwrap()
        .execute_batch("DROP TRIGGER refuse; PRAGMA wal_checkpoint(TRUNCATE);")
        .unwrap();
    assert_eq!(
        RunStore::open(&path).unwrap().schema_version(),
        SCHEMA_VERSION
    );
}

/// Every individual row's `checksum`, in generation and index order.
fn stored_checksums(path: &Path) -> Vec<String> {
    let conn = rusqlite::Connection::open(path).unwrap();
    let mut stmt = conn
        .prepare("SELECT checksum FROM individual ORDER BY generation, individual")
        .unwrap();
    stmt.query_map([], |r| r.get(0))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap()
}

/// The values of individual `index` of generation `generation` in `columns`, for
/// [`crate::util::documented_checksum`], and its stored checksum.
fn row_values(
    path: &Path,
    columns: &str,
    generation: u32,
    index: u32,
) -> (Vec<rusqlite::types::Value>, String) {
    let conn = rusqlite::Connection::open(path).unwrap();
    let n = columns.split(',').count();
    conn.query_row(
        &format!(
            "SELECT {columns}, checksum FROM individual WHERE generation = ?1 AND individual = ?2"
        ),
        [generation, index],
        |r| {
            let values = (0..n).map(|i| r.get(i)).collect::<Result<_, _>>()?;
            Ok((values, r.get(n)?))
        },
    )
    .unwrap()
}

#[test]
fn a_version_4_store_is_migrated_by_adding_the_parents_generation_and_its_rows_still_verify() {
    use crate::util::{INDIVIDUAL_COLUMNS_V4, documented_checksum};
    let dir = scratch("version-4");
    let path = finished_store(&dir);
    {
        // Version 4: no parents_generation column.
        let conn = rusqlite::Connection::open(&path).unwrap();
        conn.execute_batch(
            "ALTER TABLE individual DROP COLUMN parents_generation;
             PRAGMA user_version = 4;
             PRAGMA wal_checkpoint(TRUNCATE);",
        )
        .unwrap();
    }
    // Its rows hold the checksums version 4 documents: over its fourteen columns.
    let (values, stored) = row_values(&path, INDIVIDUAL_COLUMNS_V4, 1, 2);
    assert_eq!(documented_checksum("individual", &values), stored);
    let checksums = stored_checksums(&path);
    let before = fs::read(&path).unwrap();
    let store = RunStore::open_read_only(&path).unwrap();
    assert_eq!(store.schema_version(), 4);
    store.verify().unwrap();
    let old = held(&store);
    assert!(
        old.2
            .iter()
            .flatten()
            .all(|i| i.parents_generation.is_none()),
        "no parents' generation in a version-4 store"
    );
    drop(store);
    assert_eq!(
        fs::read(&path).unwrap(),
        before,
        "a read-only open changed it"
    );

    // Migrated: the column added, every row as it was, its checksum untouched and verified.
    let mut store = RunStore::open(&path).unwrap();
    assert_eq!(store.schema_version(), SCHEMA_VERSION);
    store.verify().unwrap();
    assert_eq!(held(&store), old);
    assert_eq!(stored_checksums(&path), checksums, "no row was rewritten");
    // A new generation records where its parents are, and its checksum covers it.
    let mut new = individuals(2, [1.0; 4]);
    for i in &mut new[1..] {
        i.parents_generation = Some(1);
    }
    store.write_generation(&generation(2), &new).unwrap();
    assert_eq!(store.individuals(2).unwrap(), new);
    let columns = format!("{INDIVIDUAL_COLUMNS_V4}, parents_generation");
    let (values, stored) = row_values(&path, &columns, 2, 1);
    assert_eq!(values[14], rusqlite::types::Value::Integer(1));
    assert_eq!(documented_checksum("individual", &values), stored);
    // Individual 0 has no parents: its NULL is left out, as in a version-4 row.
    let (values, stored) = row_values(&path, INDIVIDUAL_COLUMNS_V4, 2, 0);
    assert_eq!(documented_checksum("individual", &values), stored);
    // A parents' generation that is not an earlier generation breaks the schema.
    let mut bad = individuals(3, [1.0; 4]);
    bad[1].parents_generation = Some(3);
    assert!(matches!(
        store.write_generation(&generation(3), &bad),
        Err(StoreError::InvalidRecord { .. })
    ));
    drop(store);
    rusqlite::Connection::open(&path)
        .unwrap()
        .execute_batch("PRAGMA wal_checkpoint(TRUNCATE);")
        .unwrap();
    // A parents' generation changed behind the store's back, or given to a row stored
    // before, is refused naming the record.
    for (edit, record) in [
        (
            "UPDATE individual SET parents_generation = 0 WHERE generation = 2 AND individual = 1",
            "individual 1 of generation 2",
        ),
        (
            "UPDATE individual SET parents_generation = NULL WHERE generation = 2 AND individual = 3",
            "individual 3 of generation 2",
        ),
        (
            "UPDATE individual SET parents_generation = 0 WHERE generation = 1 AND individual = 2",
            "individual 2 of generation 1",
        ),
    ] {
        let copy = dir.join("edited.sqlite");
        fs::copy(&path, &copy).unwrap();
        rusqlite::Connection::open(&copy)
            .unwrap()
            .execute_batch(edit)
            .unwrap();
        let err = RunStore::open_read_only(&copy)
            .unwrap()
            .verify()
            .unwrap_err();
        assert!(
            err.to_string()
                .contains(&format!("the record of {record} is damaged")),
            "{edit}: {err}"
        );
        fs::remove_file(&copy).unwrap();
    }
}
