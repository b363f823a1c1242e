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
//! The schema and its migrations are in `schema`, the row records in `records`, the errors
//! in `error`; this file holds the store itself.

mod error;
mod records;
mod schema;

pub use error::StoreError;
pub use records::{FineEvaluation, GenerationRecord, IndividualRecord, RunRecord, StoredKey};
pub use schema::{APPLICATION_ID, OLDEST_SCHEMA_VERSION, SCHEMA_VERSION};

use std::fs::{self, OpenOptions};
use std::path::{Path, PathBuf};
use std::time::Duration;

use rusqlite::{Connection, OpenFlags, OptionalExtension, TransactionBehavior, params};

use error::{classify, io_error, sqlite, write_error};
use records::{get_real, individual_from_row, real};
use schema::{
    INDIVIDUAL_COLUMNS, MIGRATE_1_TO_2, MIGRATE_2_TO_3, SCHEMA, check_header, check_store,
};

/// An open run store.
#[derive(Debug)]
pub struct RunStore {
    conn: Connection,
    path: PathBuf,
    /// The schema version of the open file: [`SCHEMA_VERSION`], except for an older file
    /// opened with [`RunStore::open_read_only`].
    version: i64,
}

impl RunStore {
    /// Creates `path` (error if it exists), the schema, and the run row, and opens it.
    ///
    /// The store is built whole under a temporary name beside `path` (`run.sqlite.partial`)
    /// and renamed into place once its run row is committed, so `path` never names a store
    /// that is empty or half made: a process killed (or a disk filled) while creating it
    /// leaves no file at `path`. A temporary file left by such a start is removed by the
    /// next; the caller holds the directory's lock ([`crate::evolve::lock`]).
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
        let Ok(conn) = Connection::open_with_flags(
            path,
            OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX,
        ) else {
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
                tx.execute(
                    "INSERT INTO run (id, config, seed, encoding, task, version) \
                     VALUES (1, ?1, ?2, ?3, ?4, ?5)",
                    params![
                        run.config,
                        run.seed.to_string(),
                        run.encoding,
                        run.task,
                        run.version
                    ],
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
    pub fn open(path: &Path) -> Result<RunStore, StoreError> {
        let (ro, version) = Self::checked_read_only(path)?;
        ro.close()
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
        let ro = if wal {
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
        .map_err(|e| classify(path, "cannot open it", e))?;
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

    /// The run's record.
    pub fn run(&self) -> Result<RunRecord, StoreError> {
        let (config, seed, encoding, task, version): (String, String, String, String, String) =
            self.conn
                .query_row(
                    "SELECT config, seed, encoding, task, version FROM run WHERE id = 1",
                    [],
                    |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?, r.get(4)?)),
                )
                .map_err(|e| classify(&self.path, "cannot read the run row", e))?;
        let seed = seed.parse().map_err(|_| StoreError::Corrupt {
            path: self.path.clone(),
            detail: format!("the run's seed {seed:?} is not a whole number below 2^64"),
        })?;
        Ok(RunRecord {
            config,
            seed,
            encoding,
            task,
            version,
        })
    }

    /// Replaces the text of the run's settings (`run.config`): a run extended to more
    /// generations records the count it now runs to.
    pub fn set_config(&mut self, config: &str) -> Result<(), StoreError> {
        self.conn
            .execute("UPDATE run SET config = ?1 WHERE id = 1", [config])
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
        let path = self.path.clone();
        let tx = self
            .conn
            .transaction()
            .map_err(|e| classify(&path, "cannot start a transaction", e))?;
        tx.execute(
            "INSERT INTO generation (generation, best, mean, median, sd, valid_fraction, \
             evaluations, wall_seconds, evaluations_per_second, best_fine, best_fine_status) \
             VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)",
            params![
                g,
                real(generation.best),
                real(generation.mean),
                real(generation.median),
                real(generation.sd),
                real(generation.valid_fraction),
                evaluations,
                real(generation.wall_seconds),
                real(generation.evaluations_per_second),
                generation.best_fine.as_ref().and_then(|f| real(f.fitness)),
                generation.best_fine.as_ref().map(|f| f.status.as_str()),
            ],
        )
        .map_err(|e| write_error(&path, g, "the generation row".into(), e))?;
        {
            let mut insert = tx
                .prepare(&format!(
                    "INSERT INTO individual ({INDIVIDUAL_COLUMNS}, reused, evaluation_key) \
                     VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14)"
                ))
                .map_err(|e| classify(&path, "cannot prepare the insert", e))?;
            for i in individuals {
                let parents = serde_json::to_string(&i.parents).expect("a Vec<u32> serialises");
                insert
                    .execute(params![
                        i.generation,
                        i.index,
                        parents,
                        i.operator,
                        i.genome_text,
                        i.genome_json,
                        real(i.fitness),
                        i.status,
                        i.terms_json,
                        i.parts,
                        i.joints,
                        i.neurons,
                        i.reused,
                        i.evaluation_key,
                    ])
                    .map_err(|e| write_error(&path, g, format!("individual {}", i.index), e))?;
            }
        }
        // Dropping an uncommitted transaction (any `?` above) rolls it back.
        tx.commit()
            .map_err(|e| write_error(&path, g, "the commit".into(), e))
    }

    /// The index of the last complete generation, if any. Every stored generation is complete,
    /// since each is written in one transaction.
    pub fn last_generation(&self) -> Result<Option<u32>, StoreError> {
        self.conn
            .query_row("SELECT max(generation) FROM generation", [], |r| r.get(0))
            .map_err(|e| classify(&self.path, "cannot read the last generation", e))
    }

    /// Every stored generation, in index order.
    pub fn generations(&self) -> Result<Vec<GenerationRecord>, StoreError> {
        // A version-1 file (read-only) has no fine reference columns: none was verified.
        let fine = if self.version >= 2 {
            "best_fine, best_fine_status"
        } else {
            "NULL, NULL"
        };
        // Before version 3 no evaluation was reused.
        let reused = if self.version >= 3 {
            "(SELECT count(*) FROM individual WHERE individual.generation = generation.generation \
             AND reused = 1)"
        } else {
            "0"
        };
        self.rows(
            &format!(
                "SELECT generation, best, mean, median, sd, valid_fraction, evaluations, \
                 wall_seconds, evaluations_per_second, {fine}, {reused} FROM generation \
                 ORDER BY generation"
            ),
            [],
            "cannot read the generations",
            |r| {
                Ok(GenerationRecord {
                    index: r.get(0)?,
                    best: get_real(r, 1)?,
                    mean: get_real(r, 2)?,
                    median: get_real(r, 3)?,
                    sd: get_real(r, 4)?,
                    valid_fraction: get_real(r, 5)?,
                    evaluations: u64::try_from(r.get::<_, i64>(6)?).map_err(|e| {
                        rusqlite::Error::FromSqlConversionFailure(
                            6,
                            rusqlite::types::Type::Integer,
                            Box::new(e),
                        )
                    })?,
                    wall_seconds: get_real(r, 7)?,
                    evaluations_per_second: get_real(r, 8)?,
                    best_fine: match r.get::<_, Option<String>>(10)? {
                        Some(status) => Some(FineEvaluation {
                            fitness: get_real(r, 9)?,
                            status,
                        }),
                        None => None,
                    },
                    reused: r.get::<_, i64>(11)?.max(0) as u64,
                })
            },
        )
    }

    /// A generation's individuals, in index order (empty if the generation is not stored).
    pub fn individuals(&self, generation: u32) -> Result<Vec<IndividualRecord>, StoreError> {
        self.rows(
            &format!(
                "SELECT {} FROM individual WHERE generation = ?1 ORDER BY individual",
                self.individual_columns()
            ),
            [generation],
            &format!("cannot read generation {generation}'s individuals"),
            individual_from_row,
        )
    }

    /// The (generation, index) of every stored individual that `operator` made (its name as
    /// the store spells it, e.g. `mutation`), in generation and index order.
    pub fn individuals_made_by(&self, operator: &str) -> Result<Vec<(u32, u32)>, StoreError> {
        self.rows(
            "SELECT generation, individual FROM individual WHERE operator = ?1 \
                 ORDER BY generation, individual",
            [operator],
            "cannot read the individuals' operators",
            |r| Ok((r.get(0)?, r.get(1)?)),
        )
    }

    /// The rows `row` makes of the query `sql` with `params`; a failure says the store
    /// `action` (e.g. "cannot read the generations").
    fn rows<T>(
        &self,
        sql: &str,
        params: impl rusqlite::Params,
        action: &str,
        row: impl FnMut(&rusqlite::Row<'_>) -> rusqlite::Result<T>,
    ) -> Result<Vec<T>, StoreError> {
        let read = || -> rusqlite::Result<Vec<T>> {
            let mut stmt = self.conn.prepare(sql)?;
            stmt.query_map(params, row)?.collect()
        };
        read().map_err(|e| classify(&self.path, action, e))
    }

    /// The fittest individual of the whole run (ties go to the earliest generation, then the
    /// lowest index); `None` before the first generation. NaN fitness never wins.
    pub fn best_individual(&self) -> Result<Option<IndividualRecord>, StoreError> {
        self.conn
            .query_row(
                &format!(
                    "SELECT {} FROM individual WHERE fitness IS NOT NULL \
                     ORDER BY fitness DESC, generation, individual LIMIT 1",
                    self.individual_columns()
                ),
                [],
                individual_from_row,
            )
            .optional()
            .map_err(|e| classify(&self.path, "cannot read the best individual", e))
    }

    /// The columns an [`IndividualRecord`] is read from: a store older than version 3
    /// (opened read-only) reads `reused` as 0 and no key.
    fn individual_columns(&self) -> String {
        if self.version >= 3 {
            format!("{INDIVIDUAL_COLUMNS}, reused, evaluation_key")
        } else {
            format!("{INDIVIDUAL_COLUMNS}, 0, NULL")
        }
    }

    /// Every stored individual's key, fitness and reuse, in generation and index order.
    pub fn keys(&self) -> Result<Vec<StoredKey>, StoreError> {
        let columns = if self.version >= 3 {
            "reused, evaluation_key"
        } else {
            "0, NULL"
        };
        self.rows(
            &format!(
                "SELECT generation, individual, fitness, {columns} FROM individual \
                 ORDER BY generation, individual"
            ),
            [],
            "cannot read the evaluation keys",
            |r| {
                Ok(StoredKey {
                    generation: r.get(0)?,
                    index: r.get(1)?,
                    fitness: get_real(r, 2)?,
                    reused: r.get(3)?,
                    evaluation_key: r.get(4)?,
                })
            },
        )
    }

    /// The key and `genome_json` of every stored individual that was evaluated (not reused)
    /// and has a key, in generation and index order: the evaluations a resumed run's cache
    /// holds.
    pub fn evaluations_by_key(&self) -> Result<Vec<(String, String)>, StoreError> {
        if self.version < 3 {
            return Ok(Vec::new());
        }
        self.rows(
            "SELECT evaluation_key, genome_json FROM individual \
                 WHERE evaluation_key IS NOT NULL AND reused = 0 \
                 ORDER BY generation, individual",
            [],
            "cannot read the stored evaluations",
            |r| Ok((r.get(0)?, r.get(1)?)),
        )
    }

    /// How many individuals of each stored generation reused an evaluation, by generation
    /// index (generations with none are absent).
    pub fn reused_by_generation(&self) -> Result<Vec<(u32, u64)>, StoreError> {
        if self.version < 3 {
            return Ok(Vec::new());
        }
        self.rows(
            "SELECT generation, count(*) FROM individual WHERE reused = 1 \
                 GROUP BY generation ORDER BY generation",
            [],
            "cannot read the reused evaluations",
            |r| Ok((r.get(0)?, r.get::<_, i64>(1)?.max(0) as u64)),
        )
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
