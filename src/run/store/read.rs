//! The run store's reads. In a store of schema version 4 or later each verifies the checksum
//! of every row it reads ([`super::checksum`]) before using any of its values, and the reads
//! of a generation check that it holds exactly the individuals its record counts: a damaged
//! record is [`StoreError::Damaged`], never data. A store of an older schema (read-only: one
//! opened for writing was migrated) has no checksums, and is read as it is.

use rusqlite::Row;

use super::checksum::verify_row;
use super::error::{StoreError, classify};
use super::records::{get_real, individual_from_row};
use super::schema::{
    GENERATION_COLUMNS, INDIVIDUAL_COLUMNS, INDIVIDUAL_COLUMNS_ALL, INDIVIDUAL_COLUMNS_V4,
    RUN_COLUMNS,
};
use super::{FineEvaluation, GenerationRecord, IndividualRecord, RunRecord, RunStore, StoredKey};
use crate::evolve::evaluator_version::EVALUATOR_VERSION;

/// A generation's row: its record, the evaluator version that made it (1 before versions
/// were recorded) and the count of individuals it records (`None` before schema version 4).
struct GenerationRow {
    record: GenerationRecord,
    evaluator: u32,
    individuals: Option<u64>,
}

impl RunStore {
    /// Whether the open file's rows carry checksums (schema version 4 and later).
    fn checksummed(&self) -> bool {
        self.version >= 4
    }

    /// The run's record.
    pub fn run(&self) -> Result<RunRecord, StoreError> {
        let checksum = if self.checksummed() {
            "checksum"
        } else {
            "NULL"
        };
        let read = |r: &Row<'_>| -> Result<(String, String, String, String, String), StoreError> {
            if self.checksummed() {
                let columns = (RUN_COLUMNS.len(), RUN_COLUMNS.len());
                verify_row(&self.path, "run", r, columns, || "the run".into())?;
            }
            let get = || Ok((r.get(1)?, r.get(2)?, r.get(3)?, r.get(4)?, r.get(5)?));
            get().map_err(|e| classify(&self.path, "cannot read the run row", e))
        };
        let mut rows = self.read_rows(
            &format!(
                "SELECT {}, {checksum} FROM run WHERE id = 1",
                RUN_COLUMNS.join(", ")
            ),
            [],
            "cannot read the run row",
            read,
        )?;
        let Some((config, seed, encoding, task, version)) = rows.pop() else {
            return Err(StoreError::Corrupt {
                path: self.path.clone(),
                detail: "the run table has no row".into(),
            });
        };
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

    /// The index of the last complete generation, if any. Every stored generation is complete,
    /// since each is written in one transaction.
    pub fn last_generation(&self) -> Result<Option<u32>, StoreError> {
        self.conn
            .query_row("SELECT max(generation) FROM generation", [], |r| r.get(0))
            .map_err(|e| classify(&self.path, "cannot read the last generation", e))
    }

    /// Every stored generation, in index order.
    pub fn generations(&self) -> Result<Vec<GenerationRecord>, StoreError> {
        Ok(self
            .generation_rows(None)?
            .into_iter()
            .map(|g| g.record)
            .collect())
    }

    /// The evaluator version that made each stored generation, by generation index, in
    /// index order ([`crate::evolve::evaluator_version`]; 1 for a generation stored before
    /// the version was recorded): where a run went on under another evaluator, the version
    /// changes.
    pub fn evaluators(&self) -> Result<Vec<(u32, u32)>, StoreError> {
        Ok(self
            .generation_rows(None)?
            .into_iter()
            .map(|g| (g.record.index, g.evaluator))
            .collect())
    }

    /// The rows of every generation, or of generation `only`, verified.
    fn generation_rows(&self, only: Option<u32>) -> Result<Vec<GenerationRow>, StoreError> {
        // Version 1 has no fine reference columns (none was verified); versions before 4 no
        // evaluator (version 1), count or checksum.
        let columns = match self.version {
            1 => format!(
                "{}, NULL, NULL, 1, NULL, NULL",
                GENERATION_COLUMNS[..9].join(", ")
            ),
            2 | 3 => format!("{}, 1, NULL, NULL", GENERATION_COLUMNS[..11].join(", ")),
            _ => format!("{}, checksum", GENERATION_COLUMNS.join(", ")),
        };
        // Before version 3 no evaluation was reused.
        let reused = if self.version >= 3 {
            "(SELECT count(*) FROM individual WHERE individual.generation = generation.generation \
             AND reused = 1)"
        } else {
            "0"
        };
        let filter = match only {
            Some(_) => "WHERE generation = ?1",
            None => "WHERE ?1 IS NULL",
        };
        self.read_rows(
            &format!("SELECT {columns}, {reused} FROM generation {filter} ORDER BY generation"),
            [only],
            "cannot read the generations",
            |r| {
                if self.checksummed() {
                    verify_row(
                        &self.path,
                        "generation",
                        r,
                        (GENERATION_COLUMNS.len(), GENERATION_COLUMNS.len()),
                        || match r.get::<_, i64>(0) {
                            Ok(g) => format!("generation {g}"),
                            Err(_) => "a generation".into(),
                        },
                    )?;
                }
                generation_row(r)
                    .map_err(|e| classify(&self.path, "cannot read the generations", e))
            },
        )
    }

    /// A generation's individuals, in index order (empty if the generation is not stored).
    /// In a store of schema version 4 or later they must be exactly the individuals its
    /// record counts, indexed from 0: a row missing, moved or repeated is
    /// [`StoreError::Damaged`].
    pub fn individuals(&self, generation: u32) -> Result<Vec<IndividualRecord>, StoreError> {
        let individuals = self.individual_rows(
            "WHERE generation = ?1 ORDER BY individual",
            [generation],
            &format!("cannot read generation {generation}'s individuals"),
        )?;
        if !self.checksummed() {
            return Ok(individuals);
        }
        let counted = self.generation_rows(Some(generation))?.pop();
        let damaged = |detail: String| StoreError::Damaged {
            path: self.path.clone(),
            what: format!("generation {generation}"),
            detail,
        };
        let expected = match counted {
            Some(row) => row.individuals.unwrap_or(0),
            None if individuals.is_empty() => return Ok(individuals),
            None => {
                return Err(damaged(
                    "its individuals are stored, its record is not".into(),
                ));
            }
        };
        if individuals.len() as u64 != expected {
            return Err(damaged(format!(
                "it holds {} individuals where its record says {expected}",
                individuals.len()
            )));
        }
        if let Some((at, i)) = individuals
            .iter()
            .enumerate()
            .find(|(at, i)| i.index as usize != *at || i.generation != generation)
        {
            return Err(damaged(format!(
                "its individual at place {at} says it is individual {} of generation {}",
                i.index, i.generation
            )));
        }
        Ok(individuals)
    }

    /// Verifies every record of the store (schema version 4 or later; an older store has no
    /// checksums): the run, every generation, every individual, and that each generation
    /// holds exactly the individuals its record counts. Reads only.
    pub fn verify(&self) -> Result<(), StoreError> {
        if !self.checksummed() {
            return Ok(());
        }
        self.run()?;
        let generations = self.generation_rows(None)?;
        let mut counted = 0u64;
        for g in &generations {
            counted += self.individuals(g.record.index)?.len() as u64;
        }
        // Individuals of a generation that has no record are found by no generation's read.
        let all = self.individual_rows("", [], "cannot read the individuals")?;
        if all.len() as u64 != counted {
            let stray = all
                .iter()
                .find(|i| !generations.iter().any(|g| g.record.index == i.generation));
            return Err(StoreError::Damaged {
                path: self.path.clone(),
                what: match stray {
                    Some(i) => format!("individual {} of generation {}", i.index, i.generation),
                    None => "the individuals".into(),
                },
                detail: "it belongs to no stored generation".into(),
            });
        }
        Ok(())
    }

    /// The (generation, index) of every stored individual that `operator` made (its name as
    /// the store spells it, e.g. `mutation`), in generation and index order.
    pub fn individuals_made_by(&self, operator: &str) -> Result<Vec<(u32, u32)>, StoreError> {
        // Every row is read and verified: a damaged operator must not drop a row unseen.
        Ok(self
            .individual_rows(
                "ORDER BY generation, individual",
                [],
                "cannot read the individuals' operators",
            )?
            .into_iter()
            .filter(|i| i.operator == operator)
            .map(|i| (i.generation, i.index))
            .collect())
    }

    /// The fittest individual of the whole run (ties go to the earliest generation, then the
    /// lowest index); `None` before the first generation. NaN fitness never wins. Every
    /// individual is verified, so a damaged fitness cannot make another the best.
    pub fn best_individual(&self) -> Result<Option<IndividualRecord>, StoreError> {
        let all = self.individual_rows(
            "ORDER BY generation, individual",
            [],
            "cannot read the best individual",
        )?;
        let mut best: Option<IndividualRecord> = None;
        for i in all {
            if !i.fitness.is_nan() && best.as_ref().is_none_or(|b| i.fitness > b.fitness) {
                best = Some(i);
            }
        }
        Ok(best)
    }

    /// Every stored individual's key, fitness and reuse, in generation and index order.
    pub fn keys(&self) -> Result<Vec<StoredKey>, StoreError> {
        Ok(self
            .individual_rows(
                "ORDER BY generation, individual",
                [],
                "cannot read the evaluation keys",
            )?
            .into_iter()
            .map(|i| StoredKey {
                generation: i.generation,
                index: i.index,
                fitness: i.fitness,
                reused: i.reused,
                evaluation_key: i.evaluation_key,
            })
            .collect())
    }

    /// The key and `genome_json` of every stored individual that was evaluated (not reused)
    /// and has a key, in a generation this program's evaluator made
    /// ([`EVALUATOR_VERSION`]), in generation and index order: the evaluations a resumed
    /// run's cache holds. A run gone on under another evaluator reuses none of the old one's.
    pub fn evaluations_by_key(&self) -> Result<Vec<(String, String)>, StoreError> {
        let current: Vec<u32> = self
            .evaluators()?
            .into_iter()
            .filter(|&(_, evaluator)| evaluator == EVALUATOR_VERSION)
            .map(|(g, _)| g)
            .collect();
        Ok(self
            .individual_rows(
                "ORDER BY generation, individual",
                [],
                "cannot read the stored evaluations",
            )?
            .into_iter()
            .filter(|i| !i.reused && current.contains(&i.generation))
            .filter_map(|i| Some((i.evaluation_key?, i.genome_json)))
            .collect())
    }

    /// How many individuals of each stored generation reused an evaluation, by generation
    /// index (generations with none are absent).
    pub fn reused_by_generation(&self) -> Result<Vec<(u32, u64)>, StoreError> {
        let mut out: Vec<(u32, u64)> = Vec::new();
        for i in self.individual_rows(
            "ORDER BY generation, individual",
            [],
            "cannot read the reused evaluations",
        )? {
            match out.last_mut() {
                _ if !i.reused => {}
                Some((g, n)) if *g == i.generation => *n += 1,
                _ => out.push((i.generation, 1)),
            }
        }
        Ok(out)
    }

    /// The individuals `tail` (`WHERE ...`, `ORDER BY ...`) selects, each verified.
    fn individual_rows(
        &self,
        tail: &str,
        params: impl rusqlite::Params,
        action: &str,
    ) -> Result<Vec<IndividualRecord>, StoreError> {
        // A store older than version 3 (opened read-only) reads `reused` as 0 and no key,
        // one older than version 5 no parents' generation.
        let columns = match self.version {
            ..=2 => format!("{INDIVIDUAL_COLUMNS}, 0, NULL, NULL, NULL"),
            3 => format!("{}, NULL, NULL", INDIVIDUAL_COLUMNS_V4.join(", ")),
            4 => format!("{}, NULL, checksum", INDIVIDUAL_COLUMNS_V4.join(", ")),
            _ => format!("{}, checksum", INDIVIDUAL_COLUMNS_ALL.join(", ")),
        };
        self.read_rows(
            &format!("SELECT {columns} FROM individual {tail}"),
            params,
            action,
            |r| {
                if self.checksummed() {
                    verify_row(
                        &self.path,
                        "individual",
                        r,
                        (INDIVIDUAL_COLUMNS_V4.len(), INDIVIDUAL_COLUMNS_ALL.len()),
                        || match (r.get::<_, i64>(1), r.get::<_, i64>(0)) {
                            (Ok(i), Ok(g)) => format!("individual {i} of generation {g}"),
                            _ => "an individual".into(),
                        },
                    )?;
                }
                individual_from_row(r).map_err(|e| classify(&self.path, action, e))
            },
        )
    }

    /// The rows `row` makes of the query `sql` with `params`; a failure of SQLite's says the
    /// store `action` (e.g. "cannot read the generations").
    fn read_rows<T>(
        &self,
        sql: &str,
        params: impl rusqlite::Params,
        action: &str,
        mut row: impl FnMut(&Row<'_>) -> Result<T, StoreError>,
    ) -> Result<Vec<T>, StoreError> {
        let fail = |e| classify(&self.path, action, e);
        let mut stmt = self.conn.prepare(sql).map_err(fail)?;
        let mut rows = stmt.query(params).map_err(fail)?;
        let mut out = Vec::new();
        while let Some(r) = rows.next().map_err(fail)? {
            out.push(row(r)?);
        }
        Ok(out)
    }
}

/// A generation's row as [`RunStore::generation_rows`] selects it: the record's columns, the
/// evaluator, the count, the checksum, and the count of reused evaluations.
fn generation_row(r: &Row<'_>) -> rusqlite::Result<GenerationRow> {
    let whole = |i: usize| -> rusqlite::Result<u64> {
        u64::try_from(r.get::<_, i64>(i)?).map_err(|e| {
            rusqlite::Error::FromSqlConversionFailure(
                i,
                rusqlite::types::Type::Integer,
                Box::new(e),
            )
        })
    };
    Ok(GenerationRow {
        record: GenerationRecord {
            index: r.get(0)?,
            best: get_real(r, 1)?,
            mean: get_real(r, 2)?,
            median: get_real(r, 3)?,
            sd: get_real(r, 4)?,
            valid_fraction: get_real(r, 5)?,
            evaluations: whole(6)?,
            wall_seconds: get_real(r, 7)?,
            evaluations_per_second: get_real(r, 8)?,
            best_fine: match r.get::<_, Option<String>>(10)? {
                Some(status) => Some(FineEvaluation {
                    fitness: get_real(r, 9)?,
                    status,
                }),
                None => None,
            },
            reused: whole(14)?,
        },
        evaluator: r.get(11)?,
        individuals: match r.get::<_, Option<i64>>(12)? {
            Some(_) => Some(whole(12)?),
            None => None,
        },
    })
}
