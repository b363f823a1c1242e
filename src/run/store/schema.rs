//! The run store's schema: the tables as SQL, the migrations from older versions, the
//! columns each version has, and the checks that a file is an undamaged run store of a
//! version this program reads (its header, its application id, its version and its tables).

use std::fs;
use std::io::Read;
use std::path::Path;

use rusqlite::Connection;

use super::checksum::checksum;
use super::error::{StoreError, classify, io_error};
use super::version::{APPLICATION_ID, OLDEST_SCHEMA_VERSION, SCHEMA_VERSION};

/// The schema, created in one transaction by [`RunStore::create`](super::RunStore::create). A NaN in any REAL column
/// is stored as NULL (SQLite has no NaN) and read back as NaN.
pub(super) const SCHEMA: &str = "
CREATE TABLE run (
    id       INTEGER PRIMARY KEY CHECK (id = 1),
    config   TEXT NOT NULL,
    seed     TEXT NOT NULL CHECK (seed GLOB '[0-9]*' AND seed NOT GLOB '*[^0-9]*'),
    encoding TEXT NOT NULL,
    task     TEXT NOT NULL,
    version  TEXT NOT NULL,
    checksum TEXT NOT NULL CHECK (length(checksum) = 16)
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
    best_fine_status       TEXT,
    evaluator              INTEGER NOT NULL CHECK (evaluator >= 1),
    individuals            INTEGER NOT NULL CHECK (individuals >= 0),
    checksum               TEXT NOT NULL CHECK (length(checksum) = 16)
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
    checksum    TEXT NOT NULL CHECK (length(checksum) = 16),
    parents_generation INTEGER
        CHECK (parents_generation IS NULL OR parents_generation BETWEEN 0 AND generation - 1),
    PRIMARY KEY (generation, individual)
) STRICT;
";

/// Version 1 to 2: the columns of the fine reference check, NULL in every generation stored
/// before (they were not verified).
pub(super) const MIGRATE_1_TO_2: &str = "
ALTER TABLE generation ADD COLUMN best_fine REAL;
ALTER TABLE generation ADD COLUMN best_fine_status TEXT;
";

/// Version 2 to 3: whether an individual's evaluation was reused, and its evaluation key;
/// rows stored before were all evaluated (`reused` 0) and have no key.
pub(super) const MIGRATE_2_TO_3: &str = "
ALTER TABLE individual ADD COLUMN reused INTEGER NOT NULL DEFAULT 0 CHECK (reused IN (0, 1));
ALTER TABLE individual ADD COLUMN evaluation_key TEXT
    CHECK (evaluation_key IS NULL OR length(evaluation_key) = 64);
";

/// Version 3 to 4: a checksum in every row (computed, as the rows are, by
/// [`checksum_rows`] in the same transaction), the evaluator's version of each generation
/// (1 for every generation stored before it was recorded) and its count of individuals.
pub(super) const MIGRATE_3_TO_4: &str = "
ALTER TABLE run ADD COLUMN checksum TEXT CHECK (checksum IS NULL OR length(checksum) = 16);
ALTER TABLE generation ADD COLUMN evaluator INTEGER NOT NULL DEFAULT 1 CHECK (evaluator >= 1);
ALTER TABLE generation ADD COLUMN individuals INTEGER NOT NULL DEFAULT 0
    CHECK (individuals >= 0);
ALTER TABLE generation ADD COLUMN checksum TEXT
    CHECK (checksum IS NULL OR length(checksum) = 16);
ALTER TABLE individual ADD COLUMN checksum TEXT
    CHECK (checksum IS NULL OR length(checksum) = 16);
UPDATE generation SET individuals =
    (SELECT count(*) FROM individual WHERE individual.generation = generation.generation);
";

/// Version 4 to 5: the generation an individual's parents index, NULL in every row stored
/// before (whose checksums do not cover a NULL there: [`super::checksum::covered`]), so no
/// row is rewritten.
pub(super) const MIGRATE_4_TO_5: &str = "
ALTER TABLE individual ADD COLUMN parents_generation INTEGER
    CHECK (parents_generation IS NULL OR parents_generation BETWEEN 0 AND generation - 1);
";

/// Fills the `checksum` column of every row of every table (the last step of
/// [`MIGRATE_3_TO_4`]), on the migration's transaction.
pub(super) fn checksum_rows(conn: &Connection) -> rusqlite::Result<()> {
    for (table, columns) in [
        ("run", RUN_COLUMNS),
        ("generation", GENERATION_COLUMNS),
        ("individual", INDIVIDUAL_COLUMNS_V4),
    ] {
        let mut update = conn.prepare(&format!(
            "UPDATE {table} SET checksum = ?1 WHERE rowid = ?2"
        ))?;
        let mut select = conn.prepare(&format!(
            "SELECT rowid, {} FROM {table}",
            columns.join(", ")
        ))?;
        let mut rows = select.query([])?;
        while let Some(row) = rows.next()? {
            let values = (1..=columns.len())
                .map(|i| row.get_ref(i))
                .collect::<rusqlite::Result<Vec<_>>>()?;
            let rowid: i64 = row.get(0)?;
            update.execute(rusqlite::params![checksum(table, values), rowid])?;
        }
    }
    Ok(())
}

/// The columns of the `run` table a checksum covers (all but `checksum`).
pub(super) const RUN_COLUMNS: &[&str] = &["id", "config", "seed", "encoding", "task", "version"];

/// The columns of the `generation` table (schema version 4), `checksum` last.
const GENERATION_COLUMN_NAMES: [&str; 14] = [
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
    "evaluator",
    "individuals",
    "checksum",
];

/// The columns of the `generation` table a checksum covers (all but `checksum`).
pub(super) const GENERATION_COLUMNS: &[&str] = GENERATION_COLUMN_NAMES.split_at(13).0;

/// The columns of the `generation` table in schema version 1: the first nine.
const GENERATION_COLUMNS_V1: &[&str] = GENERATION_COLUMN_NAMES.split_at(9).0;

/// The columns of the `generation` table in schema versions 2 and 3: the first eleven.
const GENERATION_COLUMNS_V2: &[&str] = GENERATION_COLUMN_NAMES.split_at(11).0;

/// The columns of the `individual` table a checksum covers, in the order reads select them:
/// those of schema version 4 ([`INDIVIDUAL_COLUMNS_V4`]), always covered, then
/// `parents_generation` (schema version 5), covered where it is not NULL
/// ([`super::checksum::covered`]).
pub(super) const INDIVIDUAL_COLUMNS_ALL: &[&str] = &[
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
    "parents_generation",
];

/// The columns of the `individual` table a checksum always covers: those of schema
/// version 4 but `checksum`, the first fourteen.
pub(super) const INDIVIDUAL_COLUMNS_V4: &[&str] = INDIVIDUAL_COLUMNS_ALL.split_at(14).0;

/// The columns of the `individual` table before schema version 3: the first twelve.
const INDIVIDUAL_COLUMNS_V2: &[&str] = INDIVIDUAL_COLUMNS_ALL.split_at(12).0;

/// The columns of the `individual` table (schema version 5) in the table's order: those of
/// version 4, `checksum`, then the column version 5 added (`ALTER TABLE` adds it last).
const INDIVIDUAL_COLUMN_NAMES: [&str; 16] = [
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
    "checksum",
    "parents_generation",
];

/// Each table's columns, in order, as `open` expects to find them (schema version 5).
const TABLES: [(&str, &[&str]); 3] = [
    (
        "run",
        &[
            "id", "config", "seed", "encoding", "task", "version", "checksum",
        ],
    ),
    ("generation", &GENERATION_COLUMN_NAMES),
    ("individual", &INDIVIDUAL_COLUMN_NAMES),
];

/// The columns every schema version's `individual` table has, as `SELECT` lists them.
pub(super) const INDIVIDUAL_COLUMNS: &str = "generation, individual, parents, operator, genome_text, \
     genome_json, fitness, status, terms_json, parts, joints, neurons";
/// Checks the file exists and starts like an SQLite database, before SQLite sees it.
pub(super) fn check_header(path: &Path) -> Result<(), StoreError> {
    let mut file = match fs::File::open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(StoreError::Missing { path: path.into() });
        }
        Err(source) => {
            return Err(io_error(path, "cannot read it", source));
        }
    };
    let mut header = Vec::with_capacity(100);
    (&mut file)
        .take(100)
        .read_to_end(&mut header)
        .map_err(|source| io_error(path, "cannot read it", source))?;
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
pub(super) fn check_store(path: &Path, conn: &Connection) -> Result<i64, StoreError> {
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
            "individual" if version == 4 => &INDIVIDUAL_COLUMN_NAMES[..15],
            _ if version >= 4 => expected,
            "run" => RUN_COLUMNS,
            "generation" if version < 2 => GENERATION_COLUMNS_V1,
            "generation" => GENERATION_COLUMNS_V2,
            "individual" if version < 3 => INDIVIDUAL_COLUMNS_V2,
            _ => INDIVIDUAL_COLUMNS_V4,
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
