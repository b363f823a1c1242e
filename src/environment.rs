//! The chemical environment: an array of concentrations that development reads and writes
//! through `?E` modules (open L-systems), and that a creature's controller shares: it reads and
//! writes the array the creature grew in (`Creature::environment`).

use serde::{Deserialize, Serialize};

/// The chemical array. Its length is fixed when it is made.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Environment {
    values: Vec<f64>,
}

/// An index past the end of the array.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("environment index {index} is outside the array of {len} slot(s)")]
pub struct OutOfRange {
    /// The index asked for.
    pub index: usize,
    /// The array's length.
    pub len: usize,
}

impl Environment {
    /// An environment with these initial concentrations.
    pub fn new(values: Vec<f64>) -> Self {
        Environment { values }
    }

    /// Number of slots.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Whether there are no slots.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// The concentration in slot `index`.
    pub fn get(&self, index: usize) -> Result<f64, OutOfRange> {
        self.values.get(index).copied().ok_or(OutOfRange {
            index,
            len: self.len(),
        })
    }

    /// Sets slot `index`.
    pub fn set(&mut self, index: usize, value: f64) -> Result<(), OutOfRange> {
        let len = self.len();
        let slot = self
            .values
            .get_mut(index)
            .ok_or(OutOfRange { index, len })?;
        *slot = value;
        Ok(())
    }

    /// All concentrations in slot order.
    pub fn values(&self) -> &[f64] {
        &self.values
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_writes_and_refuses_indices_outside() {
        let mut env = Environment::new(vec![0.0, 0.5]);
        env.set(1, 0.8).unwrap();
        assert_eq!(env.get(1), Ok(0.8));
        assert_eq!(env.get(2), Err(OutOfRange { index: 2, len: 2 }));
        assert!(env.set(5, 1.0).is_err());
        assert_eq!(env.values(), &[0.0, 0.8]);
    }
}
