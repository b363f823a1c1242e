//! The checksum stored with every row of a run store (schema version 4): a truncated SHA-256
//! of the row's values, written in the same transaction as the row and verified whenever the
//! row is read back, so a record damaged on disk (a flipped bit SQLite's own checks do not
//! see, since they cover the file's structure and not what a record says) is refused, never
//! used.
//!
//! The digest covers the table's name and each column's value in order, with its SQL type:
//! NULL, an INTEGER (8 bytes), a REAL (its 8 bytes, with −0 read as 0, as SQLite stores it), a
//! TEXT or BLOB (its length, then its bytes). The first 8 bytes of it, as 16 hexadecimal
//! digits, are stored in the row's `checksum` column.
//!
//! A column added to a table after schema version 4 (`individual.parents_generation`) is
//! covered only where it holds a value: the values after a table's version-4 columns are
//! covered up to the last of them that is not NULL. So a row stored before the column was
//! added (NULL in it) keeps its checksum, and a migration rewrites no row.

use std::path::Path;

use rusqlite::Row;
use rusqlite::types::{Value, ValueRef};
use sha2::{Digest, Sha256};

use super::error::StoreError;

/// The length of a stored checksum, in hexadecimal digits.
pub(super) const CHECKSUM_DIGITS: usize = 16;

/// The checksum of a row of `table` holding `values`, in column order.
pub(super) fn checksum<'a>(table: &str, values: impl IntoIterator<Item = ValueRef<'a>>) -> String {
    let mut hasher = Sha256::new();
    hasher.update(table.as_bytes());
    hasher.update([0]);
    for value in values {
        match value {
            ValueRef::Null => hasher.update([0]),
            ValueRef::Integer(i) => {
                hasher.update([1]);
                hasher.update(i.to_be_bytes());
            }
            ValueRef::Real(x) => {
                hasher.update([2]);
                // SQLite keeps no negative zero in a REAL column: it reads back as 0.
                let x = if x == 0.0 { 0.0 } else { x };
                hasher.update(x.to_bits().to_be_bytes());
            }
            ValueRef::Text(bytes) | ValueRef::Blob(bytes) => {
                hasher.update([if matches!(value, ValueRef::Text(_)) {
                    3
                } else {
                    4
                }]);
                hasher.update((bytes.len() as u64).to_be_bytes());
                hasher.update(bytes);
            }
        }
    }
    let digest = hasher.finalize();
    digest[..CHECKSUM_DIGITS / 2]
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The values of a row whose first `always` values (its table's columns of schema version
/// 4) a checksum always covers: those, then the later ones up to the last that is not NULL.
pub(super) fn covered<T>(
    mut values: Vec<T>,
    always: usize,
    is_null: impl Fn(&T) -> bool,
) -> Vec<T> {
    while values.len() > always && values.last().is_some_and(&is_null) {
        values.pop();
    }
    values
}

/// The checksum of a row about to be written, from the values bound to its columns, the
/// first `always` of them always covered ([`covered`]).
pub(super) fn checksum_of(table: &str, values: &[Value], always: usize) -> String {
    let values = covered(values.iter().map(ValueRef::from).collect(), always, |v| {
        matches!(v, ValueRef::Null)
    });
    checksum(table, values)
}

/// Checks that the first `columns` values of `row` (a row of `table`, the first `always` of
/// them always covered: [`covered`]) match the checksum read after them; else the store at
/// `path` is damaged in `what` ("individual 3 of generation 1").
pub(super) fn verify_row(
    path: &Path,
    table: &str,
    row: &Row<'_>,
    (always, columns): (usize, usize),
    what: impl FnOnce() -> String,
) -> Result<(), StoreError> {
    let read = || -> rusqlite::Result<(String, Option<String>)> {
        let values = (0..columns)
            .map(|i| row.get_ref(i))
            .collect::<rusqlite::Result<Vec<_>>>()?;
        let values = covered(values, always, |v| matches!(v, ValueRef::Null));
        let stored = match row.get_ref(columns)? {
            ValueRef::Text(t) => Some(String::from_utf8_lossy(t).into_owned()),
            _ => None,
        };
        Ok((checksum(table, values), stored))
    };
    match read() {
        Ok((computed, Some(stored))) if computed == stored => Ok(()),
        Ok(_) => Err(StoreError::Damaged {
            path: path.into(),
            what: what(),
            detail: "it does not match the checksum stored with it".into(),
        }),
        Err(e) => Err(StoreError::Damaged {
            path: path.into(),
            what: what(),
            detail: format!("it does not read back ({e})"),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_trailing_nulls_after_the_columns_always_covered_are_left_out() {
        let null = |v: &i32| *v == 0;
        // Always covered: the first two, NULL or not.
        assert_eq!(covered(vec![1, 0], 2, null), [1, 0]);
        // After them, up to the last value that is not NULL.
        assert_eq!(covered(vec![1, 0, 0, 0], 2, null), [1, 0]);
        assert_eq!(covered(vec![1, 2, 0, 3], 2, null), [1, 2, 0, 3]);
        assert_eq!(covered(vec![1, 2, 3, 0], 2, null), [1, 2, 3]);
    }

    #[test]
    fn a_null_left_out_gives_the_checksum_of_the_row_without_the_column() {
        let v4 = [Value::Integer(1), Value::Null, Value::Text("a".into())];
        let with_null = [v4.to_vec(), vec![Value::Null]].concat();
        let with_value = [v4.to_vec(), vec![Value::Integer(0)]].concat();
        assert_eq!(
            checksum_of("individual", &with_null, 3),
            checksum_of("individual", &v4, 3)
        );
        assert_ne!(
            checksum_of("individual", &with_value, 3),
            checksum_of("individual", &v4, 3)
        );
        // Where every column is always covered, a NULL last counts.
        assert_ne!(
            checksum_of("individual", &with_null, 4),
            checksum_of("individual", &v4, 3)
        );
    }
}
