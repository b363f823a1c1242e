//! Which run stores this program reads: the schema's version and its history, the oldest
//! version read, and the id that marks a file as a run store. The schema itself is in
//! `schema`, and the messages for a version this program cannot read in `error`.

/// The schema's version, kept in the database header (`PRAGMA user_version`). Raise it when
/// the tables change, and teach [`RunStore::open`](super::RunStore::open) to migrate the older versions.
///
/// - 1: the first schema.
/// - 2: `generation.best_fine` and `generation.best_fine_status`, the generation's best
///   re-walked at the fine reference setting (NULL when not verified). A version-1 file is
///   migrated when it is opened for writing; [`RunStore::open_read_only`](super::RunStore::open_read_only) reads it as it is.
/// - 3: `individual.reused` (1 when the individual's evaluation was taken from an identical
///   creature evaluated earlier in the run) and `individual.evaluation_key` (the key of its
///   creature and the task, [`crate::evolve::key::EvaluationKey`], NULL when it did not
///   develop). Versions 1 and 2 are migrated on writing: old rows get `reused` 0 and no key.
/// - 4: a `checksum` in every row of every table (a truncated SHA-256 of its values), verified whenever a
///   row is read; `generation.evaluator`, the evaluator's behaviour version that made the
///   generation ([`crate::evolve::evaluator_version`]), and `generation.individuals`, how
///   many individuals it has. Older versions are migrated on writing: their rows are
///   checksummed as they are, their generations taken as evaluator version 1.
/// - 5: `individual.parents_generation`, the generation an individual's `parents` index
///   (NULL for one without parents, and in rows stored before). Version 4 is migrated on
///   writing by adding the column: a NULL `parents_generation` is left out of a row's
///   checksum, so the rows stored before keep theirs and still verify.
pub const SCHEMA_VERSION: i64 = 5;

/// The oldest schema version this program reads (and migrates when it writes).
pub const OLDEST_SCHEMA_VERSION: i64 = 1;

/// Marks the file as an Ontogeny run store (`PRAGMA application_id`): the bytes "Onto".
pub const APPLICATION_ID: i64 = 0x4F6E_746F;
