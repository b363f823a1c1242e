//! A seedling: a grammar with the options that derive and build it — what a creature that
//! goes on developing during its evaluation grows from (`develop = "during"`).

use std::sync::Arc;

use super::BuildOptions;
use crate::lsystem::{DeriveOptions, LSystem};

/// A grammar with the options that derive its strings and build its creatures.
#[derive(Clone, Debug)]
pub struct Seedling {
    /// The grammar.
    pub lsys: Arc<LSystem>,
    /// Its derivation's settings (seed, initial environment values, time, limits).
    pub derive: DeriveOptions,
    /// The builder's settings.
    pub build: BuildOptions,
}

impl Seedling {
    /// Whether it develops in continuous time (a `time:` line, or a time in its derivation's
    /// settings): only such a development goes on during an evaluation.
    pub fn is_continuous(&self) -> bool {
        self.lsys.is_continuous() || self.derive.time.is_some()
    }
}
