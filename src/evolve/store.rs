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

use std::fs::{self, OpenOptions};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::time::Duration;

use rusqlite::{
    Connection, ErrorCode, OpenFlags, OptionalExtension, Row, TransactionBehavior, params,
};

/// The schema's version, kept in the database header (`PRAGMA user_version`). Raise it when
/// the tables change, and teach [`RunStore::open`] to migrate the older versions.
///
/// - 1: the first schema.
/// - 2: `generation.best_fine` and `generation.best_fine_status`, the generation's best
///   re-walked at the fine reference setting (NULL when not verified). A version-1 file is
///   migrated when it is opened for writing; [`RunStore::open_read_only`] reads it as it is.
/// - 3: `individual.reused` (1 when the individual's evaluation was taken from an identical
///   creature evaluated earlier in the run) and `individual.evaluation_key` (the key of its
///   creature and the task, [`crate::evolve::key::EvaluationKey`], NULL when it did not
///   develop). Versions 1 and 2 are migrated on writing: old rows get `reused` 0 and no key.
pub const SCHEMA_VERSION: i64 = 3;

/// The oldest schema version this program reads (and migrates when it writes).
pub const OLDEST_SCHEMA_VERSION: i64 = 1;

/// Marks the file as an Ontogeny run store (`PRAGMA application_id`): the bytes "Onto".
pub const APPLICATION_ID: i64 = 0x4F6E_746F;

/// The schema, created in one transaction by [`RunStore::create`]. A NaN in any REAL column
/// is stored as NULL (SQLite has no NaN) and read back as NaN.
const SCHEMA: &str = "
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
    evaluations_per_second REAL,
    best_fine              REAL,
    best_fine_status       TEXT
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
    reused      INTEGER NOT NULL CHECK (reused IN (0, 1)),
    evaluation_key TEXT CHECK (evaluation_key IS NULL OR length(evaluation_key) = 64),
    PRIMARY KEY (generation, individual)
) STRICT;
";

/// Version 1 to 2: the columns of the fine reference check, NULL in every generation stored
/// before (they were not verified).
const MIGRATE_1_TO_2: &str = "
ALTER TABLE generation ADD COLUMN best_fine REAL;
ALTER TABLE generation ADD COLUMN best_fine_status TEXT;
";

/// Version 2 to 3: whether an individual's evaluation was reused, and its evaluation key;
/// rows stored before were all evaluated (`reused` 0) and have no key.
const MIGRATE_2_TO_3: &str = "
ALTER TABLE individual ADD COLUMN reused INTEGER NOT NULL DEFAULT 0 CHECK (reused IN (0, 1));
ALTER TABLE individual ADD COLUMN evaluation_key TEXT
    CHECK (evaluation_key IS NULL OR length(evaluation_key) = 64);
";

/// The columns of the `generation` table (schema version 2 and later).
const GENERATION_COLUMNS: [&str; 11] = [
    "generation",
    "best",
    "mean",
    "median",
    "sd",
    "valid_fraction",
    "evaluations",
    "wall_seconds",
    "evaluations_per_second",
    "best_fine",
    "best_fine_status",
];

/// The columns of the `generation` table in schema version 1: all but the last two.
const GENERATION_COLUMNS_V1: &[&str] = GENERATION_COLUMNS.split_at(9).0;

/// The columns of the `individual` table (schema version 3).
const INDIVIDUAL_COLUMN_NAMES: [&str; 14] = [
    "generation",
    "individual",
    "parents",
    "operator",
    "genome_text",
    "genome_json",
    "fitness",
    "status",
    "terms_json",
    "parts",
    "joints",
    "neurons",
    "reused",
    "evaluation_key",
];

/// The columns of the `individual` table before schema version 3: all but the last two.
const INDIVIDUAL_COLUMNS_V2: &[&str] = INDIVIDUAL_COLUMN_NAMES.split_at(12).0;

/// Each table's columns, in order, as `open` expects to find them (schema version 3).
const TABLES: [(&str, &[&str]); 3] = [
    (
        "run",
        &["id", "config", "seed", "encoding", "task", "version"],
    ),
    ("generation", &GENERATION_COLUMNS),
    ("individual", &INDIVIDUAL_COLUMN_NAMES),
];

/// The columns every schema version's `individual` table has, as `SELECT` lists them.
const INDIVIDUAL_COLUMNS: &str = "generation, individual, parents, operator, genome_text, \
     genome_json, fitness, status, terms_json, parts, joints, neurons";

/// What a run is: written once, when the run starts.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRecord {
    /// The text of the run's `config.toml` (every setting).
    pub config: String,
    /// The run's master seed.
    pub seed: u64,
    /// The encoding's name, e.g. `lsystem`.
    pub encoding: String,
    /// The task's name, e.g. `walker`.
    pub task: String,
    /// The version of ontogeny that started the run (`CARGO_PKG_VERSION`).
    pub version: String,
}

impl RunRecord {
    /// The task its settings give (`[task]` of [`RunRecord::config`]); `None` when the text
    /// cannot be read as one.
    pub fn task_spec(&self) -> Option<crate::task::TaskSpec> {
        let config: toml::Table = toml::from_str(&self.config).ok()?;
        config.get("task")?.clone().try_into().ok()
    }
}

/// The evaluation of a generation's best individual at the fine reference setting
/// ([`crate::sim::SimOptions::fine_reference`]): a check that its fitness is not an artefact
/// of the evaluator's coarse stepping.
#[derive(Debug, Clone, PartialEq)]
pub struct FineEvaluation {
    /// Its fitness at the fine reference (NaN if the evaluation gave none).
    pub fitness: f64,
    /// The evaluation's status, e.g. `ok` or the reason it failed.
    pub status: String,
}

/// One generation's statistics. Statistics of an empty sample (no valid individual) are NaN.
#[derive(Debug, Clone, PartialEq)]
pub struct GenerationRecord {
    /// The generation's index, from 0.
    pub index: u32,
    /// The best fitness.
    pub best: f64,
    /// The mean fitness (the GA computes it over valid individuals).
    pub mean: f64,
    /// The median fitness (the GA computes it over valid individuals).
    pub median: f64,
    /// The standard deviation of fitness (over valid individuals).
    pub sd: f64,
    /// The fraction of individuals whose evaluation succeeded, in [0, 1].
    pub valid_fraction: f64,
    /// How many evaluations the generation ran.
    pub evaluations: u64,
    /// Wall-clock seconds the generation took.
    pub wall_seconds: f64,
    /// `evaluations / wall_seconds`.
    pub evaluations_per_second: f64,
    /// The best individual (rank 1) re-walked at the fine reference setting; `None` when it
    /// was not (the run's `verify_best` is off, or the generation predates schema version 2).
    pub best_fine: Option<FineEvaluation>,
}

/// One individual of one generation.
#[derive(Debug, Clone, PartialEq)]
pub struct IndividualRecord {
    /// The index of its generation.
    pub generation: u32,
    /// Its index within the generation, from 0.
    pub index: u32,
    /// Its parents' indices in the previous generation (empty for a random individual).
    pub parents: Vec<u32>,
    /// The operator that made it, e.g. `mutation`, `crossover`, `random`, `elite`.
    pub operator: String,
    /// The genome as text, for people (an L-system's `.lsys` text, say).
    pub genome_text: String,
    /// The genome as JSON (serde), to resume a run.
    pub genome_json: String,
    /// Its fitness; a failed evaluation scores the failure floor −999999, a normal value.
    pub fitness: f64,
    /// The evaluation's status, e.g. `ok` or the reason it failed.
    pub status: String,
    /// The fitness terms as a JSON object.
    pub terms_json: String,
    /// How many parts its body has.
    pub parts: u32,
    /// How many joints its body has.
    pub joints: u32,
    /// How many neurons its brain has.
    pub neurons: u32,
    /// Whether its evaluation was taken from an identical creature evaluated earlier in the
    /// run (always false for an elite, which is carried over, and in a run without cache).
    pub reused: bool,
    /// The key of its creature and the run's task, as 64 hex digits (`None` when it did not
    /// develop, or it was stored before schema version 3).
    pub evaluation_key: Option<String>,
}

/// The evaluation key, fitness and reuse of one stored individual: what a resumed run needs
/// to rebuild its evaluation cache.
#[derive(Debug, Clone, PartialEq)]
pub struct StoredKey {
    /// The index of its generation.
    pub generation: u32,
    /// Its index within the generation.
    pub index: u32,
    /// Its fitness (NaN where the store holds NULL).
    pub fitness: f64,
    /// Whether its evaluation was reused.
    pub reused: bool,
    /// Its evaluation key as 64 hex digits, if it has one.
    pub evaluation_key: Option<String>,
}

/// Why a run store could not be created, opened, read or written. Every message names the file.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    /// `create` was given a path that exists.
    #[error("{} already exists; a new run needs a new file (nothing was changed)", path.display())]
    Exists {
        /// The database's path.
        path: PathBuf,
    },
    /// `open` was given a path that does not exist.
    #[error("{} does not exist", path.display())]
    Missing {
        /// The database's path.
        path: PathBuf,
    },
    /// The file is not an SQLite database, or a database but not a run store.
    #[error("{} is not a run database ({reason})", path.display())]
    NotARunStore {
        /// The database's path.
        path: PathBuf,
        /// What is wrong, in plain words.
        reason: String,
    },
    /// The file is a damaged database (truncated, overwritten).
    #[error("{} is corrupt: {detail}", path.display())]
    Corrupt {
        /// The database's path.
        path: PathBuf,
        /// What SQLite found.
        detail: String,
    },
    /// The run store was written by a newer schema than this program reads.
    #[error(
        "{} was written by a newer schema (version {found}); this ontogeny reads version {SCHEMA_VERSION}: update ontogeny",
        path.display()
    )]
    NewerSchema {
        /// The database's path.
        path: PathBuf,
        /// The schema version found in the file.
        found: i64,
    },
    /// The run store was written by an older schema that this program cannot read.
    #[error(
        "{} was written by an older schema (version {found}) that this ontogeny (schema versions {OLDEST_SCHEMA_VERSION} to {SCHEMA_VERSION}) cannot read",
        path.display()
    )]
    OlderSchema {
        /// The database's path.
        path: PathBuf,
        /// The schema version found in the file.
        found: i64,
    },
    /// A record given to `write_generation` does not fit the store; nothing was written.
    #[error("{}: cannot write generation {generation} (nothing of it was stored): {reason}", path.display())]
    InvalidRecord {
        /// The database's path.
        path: PathBuf,
        /// The generation being written.
        generation: u32,
        /// What is wrong.
        reason: String,
    },
    /// A file-system error outside SQLite.
    #[error("{}: {action}: {source}", path.display())]
    Io {
        /// The database's path.
        path: PathBuf,
        /// What was being done.
        action: &'static str,
        /// The error.
        #[source]
        source: std::io::Error,
    },
    /// Any other SQLite error.
    #[error("{}: {action}: {source}", path.display())]
    Sqlite {
        /// The database's path.
        path: PathBuf,
        /// What was being done.
        action: String,
        /// SQLite's error.
        #[source]
        source: rusqlite::Error,
    },
}

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
            return Err(StoreError::Io {
                path: path.into(),
                action: "cannot move the new store into place",
                source,
            });
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
                return Err(StoreError::Io {
                    path: path.into(),
                    action: "cannot create the file",
                    source,
                });
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
        let read = || -> rusqlite::Result<Vec<GenerationRecord>> {
            let mut stmt = self.conn.prepare(&format!(
                "SELECT generation, best, mean, median, sd, valid_fraction, evaluations, \
                 wall_seconds, evaluations_per_second, {fine} FROM generation \
                 ORDER BY generation"
            ))?;
            stmt.query_map([], |r| {
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
                })
            })?
            .collect()
        };
        read().map_err(|e| classify(&self.path, "cannot read the generations", e))
    }

    /// A generation's individuals, in index order (empty if the generation is not stored).
    pub fn individuals(&self, generation: u32) -> Result<Vec<IndividualRecord>, StoreError> {
        let read = || -> rusqlite::Result<Vec<IndividualRecord>> {
            let mut stmt = self.conn.prepare(&format!(
                "SELECT {} FROM individual WHERE generation = ?1 ORDER BY individual",
                self.individual_columns()
            ))?;
            stmt.query_map([generation], individual_from_row)?.collect()
        };
        read().map_err(|e| {
            classify(
                &self.path,
                &format!("cannot read generation {generation}'s individuals"),
                e,
            )
        })
    }

    /// The (generation, index) of every stored individual that `operator` made (its name as
    /// the store spells it, e.g. `mutation`), in generation and index order.
    pub fn individuals_made_by(&self, operator: &str) -> Result<Vec<(u32, u32)>, StoreError> {
        let read = || -> rusqlite::Result<Vec<(u32, u32)>> {
            let mut stmt = self.conn.prepare(
                "SELECT generation, individual FROM individual WHERE operator = ?1 \
                 ORDER BY generation, individual",
            )?;
            stmt.query_map([operator], |r| Ok((r.get(0)?, r.get(1)?)))?
                .collect()
        };
        read().map_err(|e| classify(&self.path, "cannot read the individuals' operators", e))
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
        let read = || -> rusqlite::Result<Vec<StoredKey>> {
            let mut stmt = self.conn.prepare(&format!(
                "SELECT generation, individual, fitness, {columns} FROM individual \
                 ORDER BY generation, individual"
            ))?;
            stmt.query_map([], |r| {
                Ok(StoredKey {
                    generation: r.get(0)?,
                    index: r.get(1)?,
                    fitness: get_real(r, 2)?,
                    reused: r.get(3)?,
                    evaluation_key: r.get(4)?,
                })
            })?
            .collect()
        };
        read().map_err(|e| classify(&self.path, "cannot read the evaluation keys", e))
    }

    /// The key and `genome_json` of every stored individual that was evaluated (not reused)
    /// and has a key, in generation and index order: the evaluations a resumed run's cache
    /// holds.
    pub fn evaluations_by_key(&self) -> Result<Vec<(String, String)>, StoreError> {
        if self.version < 3 {
            return Ok(Vec::new());
        }
        let read = || -> rusqlite::Result<Vec<(String, String)>> {
            let mut stmt = self.conn.prepare(
                "SELECT evaluation_key, genome_json FROM individual \
                 WHERE evaluation_key IS NOT NULL AND reused = 0 \
                 ORDER BY generation, individual",
            )?;
            stmt.query_map([], |r| Ok((r.get(0)?, r.get(1)?)))?
                .collect()
        };
        read().map_err(|e| classify(&self.path, "cannot read the stored evaluations", e))
    }

    /// How many individuals of each stored generation reused an evaluation, by generation
    /// index (generations with none are absent).
    pub fn reused_by_generation(&self) -> Result<Vec<(u32, u64)>, StoreError> {
        if self.version < 3 {
            return Ok(Vec::new());
        }
        let read = || -> rusqlite::Result<Vec<(u32, u64)>> {
            let mut stmt = self.conn.prepare(
                "SELECT generation, count(*) FROM individual WHERE reused = 1 \
                 GROUP BY generation ORDER BY generation",
            )?;
            stmt.query_map([], |r| Ok((r.get(0)?, r.get::<_, i64>(1)?.max(0) as u64)))?
                .collect()
        };
        read().map_err(|e| classify(&self.path, "cannot read the reused evaluations", e))
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

/// NaN becomes NULL: SQLite has no NaN (it would store NULL anyway, but say so).
fn real(x: f64) -> Option<f64> {
    (!x.is_nan()).then_some(x)
}

/// NULL becomes NaN.
fn get_real(r: &Row<'_>, i: usize) -> rusqlite::Result<f64> {
    Ok(r.get::<_, Option<f64>>(i)?.unwrap_or(f64::NAN))
}

fn individual_from_row(r: &Row<'_>) -> rusqlite::Result<IndividualRecord> {
    let parents: String = r.get(2)?;
    let parents = serde_json::from_str(&parents).map_err(|e| {
        rusqlite::Error::FromSqlConversionFailure(2, rusqlite::types::Type::Text, Box::new(e))
    })?;
    Ok(IndividualRecord {
        generation: r.get(0)?,
        index: r.get(1)?,
        parents,
        operator: r.get(3)?,
        genome_text: r.get(4)?,
        genome_json: r.get(5)?,
        fitness: get_real(r, 6)?,
        status: r.get(7)?,
        terms_json: r.get(8)?,
        parts: r.get(9)?,
        joints: r.get(10)?,
        neurons: r.get(11)?,
        reused: r.get(12)?,
        evaluation_key: r.get(13)?,
    })
}

fn sqlite(path: &Path, action: &str, source: rusqlite::Error) -> StoreError {
    StoreError::Sqlite {
        path: path.into(),
        action: action.into(),
        source,
    }
}

/// Turns SQLite's "not a database" and "malformed" codes into their plain errors.
fn classify(path: &Path, action: &str, e: rusqlite::Error) -> StoreError {
    match e.sqlite_error_code() {
        Some(ErrorCode::NotADatabase) => StoreError::NotARunStore {
            path: path.into(),
            reason: "file is not a database".into(),
        },
        Some(ErrorCode::DatabaseCorrupt) => StoreError::Corrupt {
            path: path.into(),
            detail: e.to_string(),
        },
        _ => sqlite(path, action, e),
    }
}

fn write_error(path: &Path, generation: u32, what: String, e: rusqlite::Error) -> StoreError {
    match e.sqlite_error_code() {
        Some(ErrorCode::ConstraintViolation) => StoreError::InvalidRecord {
            path: path.into(),
            generation,
            reason: format!("{what} breaks a rule of the schema ({e})"),
        },
        _ => match classify(path, "", e) {
            StoreError::Sqlite { source, .. } => StoreError::Sqlite {
                path: path.into(),
                action: format!(
                    "cannot write generation {generation} (nothing of it was stored): {what}"
                ),
                source,
            },
            other => other,
        },
    }
}

/// Checks the file exists and starts like an SQLite database, before SQLite sees it.
fn check_header(path: &Path) -> Result<(), StoreError> {
    let mut file = match fs::File::open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(StoreError::Missing { path: path.into() });
        }
        Err(source) => {
            return Err(StoreError::Io {
                path: path.into(),
                action: "cannot read it",
                source,
            });
        }
    };
    let mut header = Vec::with_capacity(100);
    (&mut file)
        .take(100)
        .read_to_end(&mut header)
        .map_err(|source| StoreError::Io {
            path: path.into(),
            action: "cannot read it",
            source,
        })?;
    let not = |reason: &str| StoreError::NotARunStore {
        path: path.into(),
        reason: reason.into(),
    };
    if header.is_empty() {
        return Err(not("the file is empty"));
    }
    if !header.starts_with(b"SQLite format 3\0") {
        return Err(not("file is not a database"));
    }
    if header.len() < 100 {
        return Err(StoreError::Corrupt {
            path: path.into(),
            detail: format!(
                "the file is {} bytes long, shorter than an SQLite header",
                header.len()
            ),
        });
    }
    // The header's page size and page count (valid when the change counter at 24 matches the
    // "version valid for" at 92) give the file's length: a shorter file was truncated.
    let be32 = |at: usize| u32::from_be_bytes(header[at..at + 4].try_into().expect("4 bytes"));
    let page_size = match u16::from_be_bytes([header[16], header[17]]) {
        1 => 65536,
        n => u64::from(n),
    };
    let pages = u64::from(be32(28));
    let length = file.metadata().map(|m| m.len()).unwrap_or(u64::MAX);
    if be32(24) == be32(92) && pages > 0 && page_size * pages > length {
        return Err(StoreError::Corrupt {
            path: path.into(),
            detail: format!(
                "the file is truncated ({length} bytes where its header says {})",
                page_size * pages
            ),
        });
    }
    Ok(())
}

/// Checks, on a read-only connection, that the database is an undamaged run store of a
/// schema this program reads; returns its version.
fn check_store(path: &Path, conn: &Connection) -> Result<i64, StoreError> {
    let not = |reason: String| StoreError::NotARunStore {
        path: path.into(),
        reason,
    };
    let pragma = |name: &str| -> Result<i64, StoreError> {
        conn.pragma_query_value(None, name, |r| r.get(0))
            .map_err(|e| classify(path, &format!("cannot read {name}"), e))
    };
    let application_id = pragma("application_id")?;
    if application_id != APPLICATION_ID {
        return Err(not(if application_id == 0 {
            "it is an SQLite database, but not one ontogeny wrote".into()
        } else {
            format!(
                "it is an SQLite database of another program (application_id {application_id:#x})"
            )
        }));
    }
    let version = pragma("user_version")?;
    if version > SCHEMA_VERSION {
        return Err(StoreError::NewerSchema {
            path: path.into(),
            found: version,
        });
    }
    if version < OLDEST_SCHEMA_VERSION {
        return Err(StoreError::OlderSchema {
            path: path.into(),
            found: version,
        });
    }
    let mut problems = Vec::new();
    conn.pragma_query(None, "quick_check", |r| {
        problems.push(r.get::<_, String>(0)?);
        Ok(())
    })
    .map_err(|e| classify(path, "cannot check it", e))?;
    if problems != ["ok"] {
        let shown = problems.len().min(3);
        let mut detail = problems[..shown].join("; ");
        if problems.len() > shown {
            detail.push_str(&format!(" (and {} more problems)", problems.len() - shown));
        }
        return Err(StoreError::Corrupt {
            path: path.into(),
            detail,
        });
    }
    for (table, expected) in TABLES {
        let expected = match table {
            "generation" if version < 2 => GENERATION_COLUMNS_V1,
            "individual" if version < 3 => INDIVIDUAL_COLUMNS_V2,
            _ => expected,
        };
        let mut columns: Vec<String> = Vec::new();
        conn.pragma(None, "table_info", table, |r| {
            columns.push(r.get(1)?);
            Ok(())
        })
        .map_err(|e| classify(path, "cannot read the schema", e))?;
        if columns.is_empty() {
            return Err(not(format!("it has no {table} table")));
        }
        if columns != expected {
            let missing: Vec<&str> = expected
                .iter()
                .filter(|c| !columns.iter().any(|have| have == *c))
                .copied()
                .collect();
            let extra: Vec<&str> = columns
                .iter()
                .filter(|c| !expected.contains(&c.as_str()))
                .map(String::as_str)
                .collect();
            return Err(not(match (missing.as_slice(), extra.as_slice()) {
                ([one], []) => format!("its {table} table lacks the column {one}"),
                ([], []) => format!("its {table} table's columns are in another order"),
                _ => format!(
                    "its {table} table lacks the columns ({}) and has others ({})",
                    missing.join(", "),
                    extra.join(", ")
                ),
            }));
        }
    }
    let runs: i64 = conn
        .query_row("SELECT count(*) FROM run", [], |r| r.get(0))
        .map_err(|e| classify(path, "cannot read the run table", e))?;
    if runs != 1 {
        return Err(StoreError::Corrupt {
            path: path.into(),
            detail: format!("the run table has {runs} rows, not 1"),
        });
    }
    Ok(version)
}
