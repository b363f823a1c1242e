//! The flags that turn a grammar's knobs without editing its file, shared by every verb that
//! reads one: `--define NAME=VALUE` ([`DefineArgs`]) and `--grammar-seed` ([`SeedArgs`], with
//! the old spelling `--seed` still read, and a note).

use std::path::Path;
use std::sync::Once;

use clap::Args;
use ontogeny::lsystem::{DefineOverride, LSystem, Overrides};

/// `--define NAME=VALUE`, repeatable: a value in place of the grammar's `define NAME`.
#[derive(Args, Clone, Debug, Default)]
pub struct DefineArgs {
    /// Set the grammar's `define NAME` to VALUE without editing the file (repeatable; the
    /// defines after it that use it follow it). A NAME the grammar does not define is an
    /// error that lists the ones it does.
    #[arg(long = "define", value_name = "NAME=VALUE", value_parser = parse_define)]
    pub defines: Vec<DefineOverride>,
}

impl DefineArgs {
    /// Reads, parses and compiles the grammar at `path` with the defines given and `seed`
    /// ([`SeedArgs::seed`]) in place of its `seed:`.
    pub fn load(&self, path: &Path, seed: Option<u64>) -> anyhow::Result<LSystem> {
        Ok(LSystem::from_path_with(path, &self.overrides(seed))?)
    }

    /// The defines given, and `seed`, as what is set in place of the file's.
    pub fn overrides(&self, seed: Option<u64>) -> Overrides {
        Overrides {
            defines: self.defines.clone(),
            seed,
        }
    }
}

/// `--define`'s value parser.
fn parse_define(text: &str) -> Result<DefineOverride, String> {
    text.parse()
}

/// The seed of a grammar's stochastic rules and random functions: the file's `seed:` line
/// edited, the draws of its defines included.
#[derive(Args, Clone, Debug, Default)]
pub struct SeedArgs {
    /// Seed for the grammar's stochastic rules and random functions, its defines' included:
    /// as the file's `seed:` line edited to N (default: the file's `seed:`, else 0).
    #[arg(long, value_name = "N")]
    grammar_seed: Option<u64>,
    /// The old spelling of --grammar-seed, still read (with a note).
    #[arg(
        long = "seed",
        value_name = "N",
        hide = true,
        conflicts_with = "grammar_seed"
    )]
    old_seed: Option<u64>,
}

impl SeedArgs {
    /// The seed given, by either spelling; the old one (`--seed`) is told once that it now
    /// reads `--grammar-seed`.
    pub fn seed(&self) -> Option<u64> {
        if let Some(seed) = self.old_seed {
            static NOTE: Once = Once::new();
            NOTE.call_once(|| {
                tell!(
                    "note: --seed {seed} is read as --grammar-seed {seed}, the seed of the \
                     grammar's stochastic rules (--seed is the genetic algorithm's seed, in \
                     evolve and compare)"
                );
            });
        }
        self.grammar_seed.or(self.old_seed)
    }

    /// The flag given, by the name it was given under (for a warning when the input is not
    /// grown from a grammar).
    pub fn given(&self) -> Option<&'static str> {
        if self.grammar_seed.is_some() {
            Some("--grammar-seed")
        } else if self.old_seed.is_some() {
            Some("--seed")
        } else {
            None
        }
    }
}
