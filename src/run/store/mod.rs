//! The run store: one SQLite database per run (`runs/NAME/run.sqlite`) holding the run's
//! settings, one row per generation and one row per individual. This is the only code in the
//! crate that knows SQL.
//!
//! Durability: the database is in WAL mode with `synchronous=FULL`, and each generation is
//! written in one transaction. A crash (`kill -9`, a panic, a power cut) at any moment leaves
//! every generation whose [`RunStore::write_generation`] returned, and nothing of the one being
//! written. `FULL` (rather than `NORMAL`, which is enough for a killed process but may lose the
//! last commits on a power cut) costs one `fsync` per generation, which is nothing beside the
//! seconds a generation's evaluations take.
//!
//! Integrity: every row carries a checksum written with it (`checksum`), verified whenever
//! the row is read back; a damaged record is an error naming it ([`StoreError::Damaged`]),
//! never data. Each generation records the evaluator version that made it
//! ([`crate::evolve::evaluator_version`]).
//!
//! The schema and its migrations are in `schema`, its version in `version`, the row records in `records`, the
//! checksums in `checksum`, the errors in `error`; the reads (each verifying what it reads)
//! in `read`; this file holds the store itself and its writes.

mod checksum;
mod error;
mod read;
mod records;
mod schema;
mod version;

pub use crate::evolve::record::{FineEvaluation, GenerationRecord};
pub use error::StoreError;
pub use records::{IndividualRecord, RunRecord, StoredKey};
pub use version::{APPLICATION_ID, OLDEST_SCHEMA_VERSION, SCHEMA_VERSION};

use std::fs::{self, OpenOptions};
use std::path::{Path, PathBuf};
use std::time::Duration;

use rusqlite::types::Value;
use rusqlite::{Connection, OpenFlags, TransactionBehavior, params_from_iter};

use crate::evolve::evaluator_version::EVALUATOR_VERSION;
use checksum::checksum_of;
use error::{classify, io_error, sqlite, write_error};
use records::real;
use schema::{
    GENERATION_COLUMNS, INDIVIDUAL_COLUMNS_ALL, INDIVIDUAL_COLUMNS_V4, MIGRATE_1_TO_2,
    MIGRATE_2_TO_3, MIGRATE_3_TO_4, MIGRATE_4_TO_5, RUN_COLUMNS, SCHEMA, check_header, check_store,
    checksum_rows,
};

/// An open run store.
#[derive(Debug)]
pub struct RunStore {
    conn: Connection,
    path: PathBuf,
    /// The schema version of the open file: [`SCHEMA_VERSION`], except for an older file
    /// opened with [`RunStore::open_read_only`].
    version: i64,
    /// The evaluator version recorded with each generation written
    /// ([`RunStore::set_evaluator_version`]).
    evaluator: u32,
}

impl RunStore {
    /// Creates `path` (error if it exists), the schema, and the run row, and opens it.
    ///
    /// The store is built whole under a temporary name beside `path` (`run.sqlite.partial`)
    /// and renamed into place once its run row is committed, so `path` never names a store
    /// that is empty or half made: a process killed (or a disk filled) while creating it
    /// leaves no file at `path`. A temporary file left by such a start is removed by the
    /// next; the caller holds the directory's lock ([`crate::run::lock`]).
    pub fn create(path: &Path, run: &RunRecord) -> Result<RunStore, StoreError> {
        if fs::symlink_metadata(path).is_ok() {
            return Err(StoreError::Exists { path: path.into() });
        }
        let partial = side_file(path, ".partial");
        remove_with_side_files(&partial);
        let result = Self::create_schema(&partial, run);
        if let Err(e) = result {
            // The file is ours and holds no committed run: leave no half-made store behind.
            remove_with_side_files(&partial);
            return Err(match e {
                StoreError::Sqlite { action, source, .. } => StoreError::Sqlite {
                    path: path.into(),
                    action,
                    source,
                },
                other => other,
            });
        }
        // A hard link never replaces a file that appeared meanwhile (a rename would); where
        // the file system has no hard links, a rename.
        let placed = match fs::hard_link(&partial, path) {
            Ok(()) => fs::remove_file(&partial),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                remove_with_side_files(&partial);
                return Err(StoreError::Exists { path: path.into() });
            }
            Err(_) => fs::rename(&partial, path),
        };
        if let Err(source) = placed.and_then(|()| sync_directory(path)) {
            remove_with_side_files(&partial);
            return Err(io_error(
                path,
                "cannot move the new store into place",
                source,
            ));
        }
        Self::open(path)
    }

    /// Whether `path` holds no run: there is no file, or an empty one, or an SQLite
    /// database with no table (a start interrupted before the schema was committed, by an
    /// earlier ontogeny that created the store in place). Such a file can be replaced
    /// without losing anything.
    pub fn is_vacant(path: &Path) -> bool {
        let Ok(metadata) = fs::metadata(path) else {
            return fs::symlink_metadata(path).is_err();
        };
        if !metadata.is_file() {
            return false;
        }
        if metadata.len() == 0 {
            // An empty file, unless a write-ahead log beside it holds committed pages.
            return fs::metadata(side_file(path, "-wal")).map_or(true, |m| m.len() == 0);
        }
        // Without a write-ahead log beside it, read as immutable: no side file is made.
        let opened = open_read_only(path, side_file(path, "-wal").exists());
        let Ok(conn) = opened else {
            return false;
        };
        conn.query_row("SELECT count(*) FROM sqlite_master", [], |r| {
            r.get::<_, i64>(0)
        })
        .is_ok_and(|tables| tables == 0)
    }

    /// Removes a vacant store ([`RunStore::is_vacant`]) and its side files; refuses (and
    /// removes nothing) when `path` holds a run.
    pub fn remove_vacant(path: &Path) -> Result<(), StoreError> {
        if !Self::is_vacant(path) {
            return Err(StoreError::Exists { path: path.into() });
        }
        remove_with_side_files(path);
        Ok(())
    }

    fn create_schema(path: &Path, run: &RunRecord) -> Result<(), StoreError> {
        // create_new makes the file atomically, so two starts can never share one.
        match OpenOptions::new().write(true).create_new(true).open(path) {
            Ok(_) => {}
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                return Err(StoreError::Exists { path: path.into() });
            }
            Err(source) => {
                return Err(io_error(path, "cannot create the file", source));
            }
        }
        // A rollback journal while building: once committed, everything is in the main file
        // (no write-ahead log to carry along when it is renamed). `open` turns on WAL mode.
        let mut conn = Connection::open_with_flags(
            path,
            OpenFlags::SQLITE_OPEN_READ_WRITE | OpenFlags::SQLITE_OPEN_NO_MUTEX,
        )
        .map_err(|e| classify(path, "cannot open it", e))?;
        conn.pragma_update(None, "journal_mode", "DELETE")
            .and_then(|()| conn.pragma_update(None, "synchronous", "FULL"))
            .map_err(|e| classify(path, "cannot set it up", e))?;
        let tx = conn
            .transaction()
            .map_err(|e| sqlite(path, "cannot start a transaction", e))?;
        tx.pragma_update(None, "application_id", APPLICATION_ID)
            .and_then(|()| tx.pragma_update(None, "user_version", SCHEMA_VERSION))
            .and_then(|()| tx.execute_batch(SCHEMA))
            .and_then(|()| {
                let values = run_values(run);
                tx.execute(
                    &format!(
                        "INSERT INTO run ({}, checksum) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)",
                        RUN_COLUMNS.join(", ")
                    ),
                    params_from_iter(with_checksum("run", values, RUN_COLUMNS.len())),
                )
            })
            .and_then(|_| tx.commit())
            .map_err(|e| sqlite(path, "cannot create the schema", e))?;
        conn.close()
            .map_err(|(_, e)| classify(path, "cannot close it", e))
    }

    /// Opens an existing store to read and write it, checking it is a run store of a schema
    /// this program reads and not corrupt (`PRAGMA quick_check`); never modifies a file it
    /// rejects. A store of an older schema is migrated to [`SCHEMA_VERSION`] in one
    /// transaction, keeping everything stored (columns added since are NULL in old rows).
    ///
    /// Every record is verified against its checksum first ([`RunStore::verify`]), on a
    /// read-only connection: a damaged store is refused before anything is written to it.
    pub fn open(path: &Path) -> Result<RunStore, StoreError> {
        let (ro, version) = Self::checked_read_only(path)?;
        let ro = RunStore {
            conn: ro,
            path: path.into(),
            version,
            evaluator: EVALUATOR_VERSION,
        };
        ro.verify()?;
        ro.conn
            .close()
            .map_err(|(_, e)| classify(path, "cannot close it", e))?;
        let mut store = Self::connect(path)?;
        if version < SCHEMA_VERSION {
            store.migrate()?;
        }
        Ok(store)
    }

    /// Opens an existing store to read it only, with the checks of [`RunStore::open`]. A store
    /// of an older schema is read as it is, never migrated: what it lacks reads as absent
    /// (e.g. [`GenerationRecord::best_fine`] is `None`). Writing through it fails.
    pub fn open_read_only(path: &Path) -> Result<RunStore, StoreError> {
        let (conn, version) = Self::checked_read_only(path)?;
        conn.busy_timeout(Duration::from_secs(10))
            .map_err(|e| classify(path, "cannot set it up", e))?;
        Ok(RunStore {
            conn,
            path: path.into(),
            version,
            evaluator: EVALUATOR_VERSION,
        })
    }

    /// Brings the open store to [`SCHEMA_VERSION`], in one transaction that first reads the
    /// version again (another process may have migrated it meanwhile).
    fn migrate(&mut self) -> Result<(), StoreError> {
        let path = self.path.clone();
        let tx = self
            .conn
            .transaction_with_behavior(TransactionBehavior::Immediate)
            .map_err(|e| classify(&path, "cannot start the schema migration", e))?;
        let version: i64 = tx
            .pragma_query_value(None, "user_version", |r| r.get(0))
            .map_err(|e| classify(&path, "cannot read user_version", e))?;
        if version < SCHEMA_VERSION {
            let migrate = || -> rusqlite::Result<()> {
                if version < 2 {
                    tx.execute_batch(MIGRATE_1_TO_2)?;
                }
                if version < 3 {
                    tx.execute_batch(MIGRATE_2_TO_3)?;
                }
                if version < 4 {
                    tx.execute_batch(MIGRATE_3_TO_4)?;
                    checksum_rows(&tx)?;
                }
                if version < 5 {
                    tx.execute_batch(MIGRATE_4_TO_5)?;
                }
                tx.pragma_update(None, "user_version", SCHEMA_VERSION)
            };
            migrate().map_err(|e| {
                classify(
                    &path,
                    &format!(
                        "cannot migrate the schema from version {version} to {SCHEMA_VERSION} (nothing was changed)"
                    ),
                    e,
                )
            })?;
        }
        // Dropping an uncommitted transaction (any `?` above) rolls it back.
        tx.commit().map_err(|e| {
            classify(
                &path,
                "cannot commit the schema migration (nothing was changed)",
                e,
            )
        })?;
        self.version = SCHEMA_VERSION;
        Ok(())
    }

    /// Checks `path` on a read-only connection (see [`RunStore::open`]) and returns that
    /// connection with the file's schema version.
    fn checked_read_only(path: &Path) -> Result<(Connection, i64), StoreError> {
        // A write-ahead log beside the file holds commits not yet copied into it (the last
        // run was killed, or is still running): then SQLite must read the log too.
        let wal = side_file(path, "-wal").exists();
        if !wal {
            check_header(path)?;
        }
        // Every check runs on a read-only connection, so a rejected file is left as it was.
        // Without a log, `immutable=1` also keeps SQLite from creating `-shm` and `-wal`
        // files beside it.
        let ro = open_read_only(path, wal).map_err(|e| classify(path, "cannot open it", e))?;
        let version = check_store(path, &ro)?;
        Ok((ro, version))
    }

    /// Opens a read-write connection with the store's settings.
    fn connect(path: &Path) -> Result<RunStore, StoreError> {
        let conn = Connection::open_with_flags(
            path,
            OpenFlags::SQLITE_OPEN_READ_WRITE | OpenFlags::SQLITE_OPEN_NO_MUTEX,
        )
        .map_err(|e| classify(path, "cannot open it", e))?;
        let setup = || -> rusqlite::Result<String> {
            // A reader (sqlite3 in another terminal) must not make a write fail at once.
            conn.busy_timeout(Duration::from_secs(10))?;
            let mode: String =
                conn.pragma_update_and_check(None, "journal_mode", "WAL", |r| r.get(0))?;
            conn.pragma_update(None, "synchronous", "FULL")?;
            conn.pragma_update(None, "foreign_keys", true)?;
            Ok(mode)
        };
        let mode = setup().map_err(|e| classify(path, "cannot set it up", e))?;
        if !mode.eq_ignore_ascii_case("wal") {
            return Err(StoreError::Sqlite {
                path: path.into(),
                action: format!("cannot switch to WAL mode (journal mode is {mode})"),
                source: rusqlite::Error::InvalidQuery,
            });
        }
        Ok(RunStore {
            conn,
            path: path.into(),
            version: SCHEMA_VERSION,
            evaluator: EVALUATOR_VERSION,
        })
    }

    /// The schema version of the open file: [`SCHEMA_VERSION`], or an older one when opened
    /// with [`RunStore::open_read_only`].
    pub fn schema_version(&self) -> i64 {
        self.version
    }

    /// The database's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Sets the evaluator version recorded with every generation this store writes from now
    /// on: [`EVALUATOR_VERSION`], this program's, unless set. (A tool that stores generations
    /// another evaluator made sets it, as the tests of a resume across evaluators do.)
    pub fn set_evaluator_version(&mut self, version: u32) {
        self.evaluator = version;
    }

    /// Replaces the text of the run's settings (`run.config`): a run extended to more
    /// generations records the count it now runs to. The run's record is verified first.
    pub fn set_config(&mut self, config: &str) -> Result<(), StoreError> {
        let run = RunRecord {
            config: config.to_string(),
            ..self.run()?
        };
        let checksum = checksum_of("run", &run_values(&run), RUN_COLUMNS.len());
        self.conn
            .execute(
                "UPDATE run SET config = ?1, checksum = ?2 WHERE id = 1",
                [config, &checksum],
            )
            .map(|_| ())
            .map_err(|e| classify(&self.path, "cannot record the run's settings", e))
    }

    /// Writes one generation row and all its individuals in ONE transaction: either all of it
    /// is stored or, on any error, none of it. A generation index already stored is refused.
    pub fn write_generation(
        &mut self,
        generation: &GenerationRecord,
        individuals: &[IndividualRecord],
    ) -> Result<(), StoreError> {
        let g = generation.index;
        let invalid = |reason: String| StoreError::InvalidRecord {
            path: self.path.clone(),
            generation: g,
            reason,
        };
        if let Some(i) = individuals.iter().find(|i| i.generation != g) {
            return Err(invalid(format!(
                "individual {} says it belongs to generation {}",
                i.index, i.generation
            )));
        }
        if let Some(last) = self.last_generation()?
            && g <= last
        {
            return Err(invalid(format!(
                "the store already holds generations up to {last}"
            )));
        }
        let evaluations = i64::try_from(generation.evaluations).map_err(|_| {
            invalid(format!(
                "{} evaluations is too many",
                generation.evaluations
            ))
        })?;
        let count = i64::try_from(individuals.len())
            .map_err(|_| invalid(format!("{} individuals is too many", individuals.len())))?;
        let path = self.path.clone();
        let tx = self
            .conn
            .transaction()
            .map_err(|e| classify(&path, "cannot start a transaction", e))?;
        let values = vec![
            Value::from(g),
            real_value(generation.best),
            real_value(generation.mean),
            real_value(generation.median),
            real_value(generation.sd),
            real_value(generation.valid_fraction),
            Value::from(evaluations),
            real_value(generation.wall_seconds),
            real_value(generation.evaluations_per_second),
            generation
                .best_fine
                .as_ref()
                .map_or(Value::Null, |f| real_value(f.fitness)),
            generation
                .best_fine
                .as_ref()
                .map_or(Value::Null, |f| Value::from(f.status.clone())),
            Value::from(self.evaluator),
            Value::from(count),
        ];
        tx.execute(
            &format!(
                "INSERT INTO generation ({}, checksum) VALUES ({})",
                GENERATION_COLUMNS.join(", "),
                placeholders(GENERATION_COLUMNS.len() + 1)
            ),
            params_from_iter(with_checksum(
                "generation",
                values,
                GENERATION_COLUMNS.len(),
            )),
        )
        .map_err(|e| write_error(&path, g, "the generation row".into(), e))?;
        {
            let mut insert = tx
                .prepare(&format!(
                    "INSERT INTO individual ({}, checksum) VALUES ({})",
                    INDIVIDUAL_COLUMNS_ALL.join(", "),
                    placeholders(INDIVIDUAL_COLUMNS_ALL.len() + 1)
                ))
                .map_err(|e| classify(&path, "cannot prepare the insert", e))?;
            for i in individuals {
                let parents = serde_json::to_string(&i.parents).expect("a Vec<u32> serialises");
                let values = vec![
                    Value::from(i.generation),
                    Value::from(i.index),
                    Value::from(parents),
                    Value::from(i.operator.clone()),
                    Value::from(i.genome_text.clone()),
                    Value::from(i.genome_json.clone()),
                    real_value(i.fitness),
                    Value::from(i.status.clone()),
                    Value::from(i.terms_json.clone()),
                    Value::from(i.parts),
                    Value::from(i.joints),
                    Value::from(i.neurons),
                    Value::from(i.reused),
                    i.evaluation_key.clone().map_or(Value::Null, Value::from),
                    i.parents_generation.map_or(Value::Null, Value::from),
                ];
                let values = with_checksum("individual", values, INDIVIDUAL_COLUMNS_V4.len());
                insert
                    .execute(params_from_iter(values))
                    .map_err(|e| write_error(&path, g, format!("individual {}", i.index), e))?;
            }
        }
        // Dropping an uncommitted transaction (any `?` above) rolls it back.
        tx.commit()
            .map_err(|e| write_error(&path, g, "the commit".into(), e))
    }
}

/// The file SQLite keeps beside `path` with `suffix` (`-wal`, `-shm`, `-journal`).
fn side_file(path: &Path, suffix: &str) -> PathBuf {
    let mut side = path.as_os_str().to_owned();
    side.push(suffix);
    PathBuf::from(side)
}

/// Removes `path` and the files SQLite keeps beside it, where they exist.
fn remove_with_side_files(path: &Path) {
    let _ = fs::remove_file(path);
    for suffix in ["-wal", "-shm", "-journal"] {
        let _ = fs::remove_file(side_file(path, suffix));
    }
}

/// Makes a rename into `path`'s directory durable (a power cut after it keeps it).
fn sync_directory(path: &Path) -> std::io::Result<()> {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => fs::File::open(dir)?.sync_all(),
        _ => fs::File::open(".")?.sync_all(),
    }
}

/// A read-only connection to `path`: through its write-ahead log when `wal` (a log beside it
/// holds commits), else as immutable, so that SQLite makes no side file beside it.
fn open_read_only(path: &Path, wal: bool) -> rusqlite::Result<Connection> {
    if wal {
        Connection::open_with_flags(
            path,
            OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX,
        )
    } else {
        Connection::open_with_flags(
            immutable_uri(path),
            OpenFlags::SQLITE_OPEN_READ_ONLY
                | OpenFlags::SQLITE_OPEN_NO_MUTEX
                | OpenFlags::SQLITE_OPEN_URI,
        )
    }
}

/// An SQLite URI opening `path` as immutable: read without locks, logs or side files.
fn immutable_uri(path: &Path) -> String {
    let mut uri = String::from("file:");
    let bytes = path.as_os_str().as_encoded_bytes();
    if bytes.starts_with(b"/") {
        // An empty authority, so a path starting with "//" is not read as a host.
        uri.push_str("//");
    }
    for &b in bytes {
        if b.is_ascii_alphanumeric() || b"/-._~".contains(&b) {
            uri.push(b as char);
        } else {
            uri.push_str(&format!("%{b:02X}"));
        }
    }
    uri.push_str("?immutable=1");
    uri
}

/// A run record's values, in the order of the `run` table's columns ([`RUN_COLUMNS`]).
fn run_values(run: &RunRecord) -> Vec<Value> {
    vec![
        Value::Integer(1),
        Value::from(run.config.clone()),
        Value::from(run.seed.to_string()),
        Value::from(run.encoding.clone()),
        Value::from(run.task.clone()),
        Value::from(run.version.clone()),
    ]
}

/// `values` of a row of `table`, followed by their checksum (which always covers the first
/// `always`: [`checksum::covered`]).
fn with_checksum(table: &str, mut values: Vec<Value>, always: usize) -> Vec<Value> {
    let checksum = checksum_of(table, &values, always);
    values.push(Value::from(checksum));
    values
}

/// A REAL column's value: NaN as NULL ([`real`]).
fn real_value(x: f64) -> Value {
    real(x).map_or(Value::Null, Value::Real)
}

/// `?1, ?2, ..., ?n`.
fn placeholders(n: usize) -> String {
    (1..=n)
        .map(|i| format!("?{i}"))
        .collect::<Vec<_>>()
        .join(", ")
}
